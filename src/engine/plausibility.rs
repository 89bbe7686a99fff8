//! Plausibility bands of the headline results: a value physically beyond what the parts can
//! bear or the torque can need is marked when no limit judges it (a limit makes it a check
//! instead). A mark is information for the reader, never a failed check: the exit code is the
//! checks' alone.
//!
//! - **Hertz pressure** against the material. Steel is recognised by its Young's modulus, E of
//!   both the disc and the rollers in 190–230 GPa (carbon, alloy and bearing steels lie at
//!   200–215 GPa; nothing else common in gears and bearings does): assumed hardened bearing
//!   steel, whose static limit is ISO 76:2006's 4,000 MPa at the centre of the most loaded
//!   roller (line) contact (the stress of a permanent deformation of 1/10,000 of the roller
//!   diameter; 4,200 MPa for ball bearings' point contacts). Any other E is not a material the
//!   tool knows: the band is then ISO 6336-5's contact endurance limit of case-hardened steel,
//!   1,500 MPa, the highest of that standard's gear materials, so a band that flags more rather
//!   than less (a softer material's own limit is lower still).
//! - **Forces** against the torque's scale. Every roller's contact normal passes through the
//!   pitch point, e·nc from the disc centre (MODEL.md), so a roller force's arm about the disc
//!   centre is at most e·nc and the rollers need at least T/(e·nc) in all to carry T; the pins'
//!   arms are at most rw, so they need at least T/rw. A clearance profile loads the rollers in
//!   proportion to their arms (the deflection is the lag times the arm), so a roller carrying
//!   many times the scale would sit on an arm many times shorter than e·nc, where it is loaded
//!   least: forces that large are balanced by forces against the torque, i.e. a preload or an
//!   interference, not by the torque. `FORCE_FACTOR` = 5: the shipped designs' largest roller,
//!   pin and crank-bearing forces are at most 1.8 times their scale, so 5 leaves room for an
//!   ordinary design and still catches a preload (the paper's negative start: 31.7 times for
//!   its largest roller, 9.8 times for its crank bearing). The scale takes the scene's whole
//!   torque T, also with several discs (each carries a share Tk ≤ T), which flags less, never
//!   more. A scene without torque has no scale and no force mark.

use crate::model::quantity::{
    Quantity, MAX_BEARING_FORCE, MAX_CONTACT_PRESSURE, MAX_PIN_FORCE, MAX_ROLLER_FORCE,
};
use crate::model::{Design, Limits};

/// ISO 76:2006: the static limit of hardened bearing steel in line contact, MPa.
pub const STEEL_LINE_CONTACT_MPA: f64 = 4000.0;
/// ISO 6336-5: contact endurance limit of case-hardened steel, the highest of its gear
/// materials, MPa: the band for a material not recognised as steel.
pub const UNKNOWN_MATERIAL_MPA: f64 = 1500.0;
/// Young's modulus of steel, MPa: 190–230 GPa.
pub const STEEL_E_MPA: (f64, f64) = (190e3, 230e3);
/// How many times the torque's scale a force may be before it is marked.
pub const FORCE_FACTOR: f64 = 5.0;

/// What a band rests on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Basis {
    /// Disc and rollers recognised as steel (E of each, MPa): ISO 76's static limit.
    Steel { disc_e_mpa: f64, roller_e_mpa: f64 },
    /// A material not recognised as steel (E of disc and rollers, MPa): the conservative band.
    UnknownMaterial { disc_e_mpa: f64, roller_e_mpa: f64 },
    /// `FORCE_FACTOR` times the force the torque needs at the largest arm.
    TorqueScale {
        /// The scene's torque, N·mm.
        torque_nmm: f64,
        /// The largest arm, mm: e·nc for rollers and the crank bearing, rw for the pins.
        arm_mm: f64,
        /// Whether the arm is the pin circle rw (else the pitch radius e·nc).
        pin_circle: bool,
    },
}

/// A headline value beyond its plausible band.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beyond {
    /// The band's upper end, in the quantity's unit.
    pub band: f64,
    pub basis: Basis,
}

/// The band of `q`'s headline in a scene of torque `torque_nmm` (N·mm, its magnitude taken),
/// or `None` when the quantity has none, a limit judges it, or the scene has no torque.
pub fn band(design: &Design, limits: &Limits, q: &Quantity, torque_nmm: f64) -> Option<Beyond> {
    if limits.get(q.key).is_some() {
        return None;
    }
    let t = torque_nmm.abs();
    let scale = |arm_mm: f64, pin_circle: bool| {
        (t > 0.0 && arm_mm > 0.0).then(|| {
            let basis = Basis::TorqueScale {
                torque_nmm: t,
                arm_mm,
                pin_circle,
            };
            Beyond {
                band: FORCE_FACTOR * t / arm_mm,
                basis,
            }
        })
    };
    let pitch_mm = design.eccentricity_mm * design.teeth as f64;
    match q.key {
        k if k == MAX_CONTACT_PRESSURE.key => {
            let disc_e_mpa = design.disc_material.youngs_modulus_mpa;
            let roller_e_mpa = design.roller_material.youngs_modulus_mpa;
            let steel = |e: f64| (STEEL_E_MPA.0..=STEEL_E_MPA.1).contains(&e);
            Some(if steel(disc_e_mpa) && steel(roller_e_mpa) {
                Beyond {
                    band: STEEL_LINE_CONTACT_MPA,
                    basis: Basis::Steel {
                        disc_e_mpa,
                        roller_e_mpa,
                    },
                }
            } else {
                Beyond {
                    band: UNKNOWN_MATERIAL_MPA,
                    basis: Basis::UnknownMaterial {
                        disc_e_mpa,
                        roller_e_mpa,
                    },
                }
            })
        }
        k if k == MAX_ROLLER_FORCE.key || k == MAX_BEARING_FORCE.key => scale(pitch_mm, false),
        k if k == MAX_PIN_FORCE.key => scale(design.pins.circle_radius_mm, true),
        _ => None,
    }
}

/// `value`'s mark: its band when `value` lies beyond it.
pub fn beyond(
    design: &Design,
    limits: &Limits,
    q: &Quantity,
    torque_nmm: f64,
    value: f64,
) -> Option<Beyond> {
    band(design, limits, q, torque_nmm).filter(|b| value > b.band)
}
