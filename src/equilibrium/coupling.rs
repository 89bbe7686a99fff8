//! The coupled friction model's coefficients (`Coupling`): `Friction` reduced to what the
//! disc's balance needs, per unit normal force. Plain data that the loaded model carries
//! (`loaded::Model::coupling`); the friction forces, arms and energy built on it are
//! `friction::coupled` (MODEL.md "Friction, efficiency and heat").

use crate::model::{Design, Friction, PinMode, RollerMode};

/// The friction of the coupled balance, per unit normal force (`Friction` reduced to what the
/// balance needs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coupling {
    /// c_r: the rollers' tangential force per unit normal force at the disc: μ (fixed), μ·r_b/Rrp
    /// (rotating).
    pub roller: f64,
    /// c_p: the pins' tangential force per unit normal force at the hole: μ (fixed pins),
    /// μ·r_bore/r_pin (free sleeves).
    pub pin: f64,
    /// c_b = μ_b·d/2: the crank bearing's friction moment per unit bearing force, mm.
    pub bearing_arm_mm: f64,
    /// The crank's eccentricity as built, e + de, mm (the kinematics' orbit).
    pub eccentricity_mm: f64,
    /// nc, the disc's teeth.
    pub teeth: usize,
    /// How the contacts slide: the running reducer's kinematics, or a torsion loop's turn.
    pub sliding: Sliding,
}

/// How the contacts slide, which sets every friction force's direction (MODEL.md "Friction,
/// efficiency and heat").
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sliding {
    /// The input turns at the nominal ratio: the rigid-body kinematics (`friction::sliding`).
    Running,
    /// Torsion under a locked input: the disc turns about its own centre O_d by dβ of the sign
    /// `sigma` (+1 on the loading branch, −1 unloading), the flange about the axis by
    /// dβ + dβo with dβo = `pin_ratio`·dβ (the pins' deflection per unit turn of the disc,
    /// ≥ 0; it sets the pins' sliding directions).
    Torsion { sigma: f64, pin_ratio: f64 },
}

impl Coupling {
    /// The coupling of `friction` on `design`; a path not given has no friction.
    pub fn new(friction: &Friction, design: &Design) -> Self {
        let roller = friction.rollers.map_or(0.0, |f| match f.mode {
            RollerMode::Fixed => f.mu,
            RollerMode::Rotating { bore_radius_mm } => {
                f.mu * bore_radius_mm / design.roller_radius_mm
            }
        });
        let pin = friction.output_pins.map_or(0.0, |f| match f.mode {
            PinMode::Fixed => f.mu,
            PinMode::Sleeve { bore_radius_mm } => f.mu * bore_radius_mm / design.pins.pin_radius_mm,
        });
        Coupling {
            roller,
            pin,
            bearing_arm_mm: friction
                .crank_bearing
                .map_or(0.0, |b| b.mu * 0.5 * b.bore_diameter_mm),
            eccentricity_mm: design.eccentricity_mm + design.deviations.eccentricity_mm,
            teeth: design.teeth,
            sliding: Sliding::Running,
        }
    }

    /// This coupling in a torsion loop's branch `sigma` (+1 loading, −1 unloading), the pins'
    /// ratio starting at 0 (`Sliding::Torsion`).
    pub fn in_torsion(self, sigma: f64) -> Self {
        Coupling {
            sliding: Sliding::Torsion {
                sigma,
                pin_ratio: 0.0,
            },
            ..self
        }
    }

    /// Whether this is a torsion loop's friction (`Sliding::Torsion`).
    pub fn is_torsion(&self) -> bool {
        matches!(self.sliding, Sliding::Torsion { .. })
    }

    /// Whether any contact has friction (with none, the balance is the frictionless one).
    pub fn active(&self) -> bool {
        self.roller > 0.0 || self.pin > 0.0 || self.bearing_arm_mm > 0.0
    }
}
