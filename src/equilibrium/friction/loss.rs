//! The power lost to friction at one crank angle, path by path, from a solved equilibrium's
//! contact forces (MODEL.md "Friction, efficiency and heat"): each loss is a Coulomb force μ·F
//! times the speed at which its surfaces slide (`sliding`). The loss model takes the forces of
//! the frictionless balance; the coupled model calls the same functions on its own solution,
//! so both measure losses one way.
//!
//! Every loss here is per unit input speed: N·mm per rad of crank (the power at ω = 1 rad/s,
//! N·mm/s). Multiply by ω in rad/s for N·mm/s, and by 1e-3 for W.

use super::sliding::{pin_sliding, relative_crank_speed_ratio, roller_sliding};
use crate::equilibrium::angle_solution::AngleSolution;
use crate::equilibrium::pins::PinState;
use crate::equilibrium::rollers::RollerState;
pub use crate::model::friction::PathLosses;
use crate::model::{
    BearingFriction, Design, Friction, PinFriction, PinMode, RollerFriction, RollerMode,
};

/// The speed at which a ring roller's friction slides, per unit input speed, mm/rad, at a
/// roller in contact at `state` (its point C and normal n) on a disc at crank angle
/// `crank_rad` (its phase included): fixed, the disc over the roller, |v_disc(C)·t| with
/// t = ẑ×n, which for the unmodified profile is (|P_i − I| − Rrp)/nc; rotating, the roller
/// rolls on the disc and its bore slides on its pin at that speed × r_b/Rrp (MODEL.md).
pub fn roller_slip_speed(
    mode: RollerMode,
    design: &Design,
    crank_rad: f64,
    state: &RollerState,
) -> f64 {
    let v = roller_sliding(
        crank_rad,
        design.built_eccentricity_mm(),
        design.teeth,
        state.point,
        state.normal,
    )
    .abs();
    mode.slip_scaled(v, design.roller_radius_mm)
}

/// The speed at which an output pin's friction slides, per unit input speed, mm/rad: fixed,
/// the hole over the pin at e·Ω/ω; a free sleeve rolls in the hole and slides on its pin at
/// e·Ω/ω·r_bore/r_pin (r_pin = `output_pins.pin_radius_mm`, the sleeve's outer radius).
pub fn pin_slip_speed(mode: PinMode, design: &Design) -> f64 {
    let v = pin_sliding(design.built_eccentricity_mm(), design.teeth);
    mode.slip_scaled(v, design.pins.pin_radius_mm)
}

/// Σ μ·F_i·slip_i over the rollers of one disc, N·mm/rad.
fn roller_losses(
    f: &RollerFriction,
    design: &Design,
    crank_rad: f64,
    rollers: &[RollerState],
) -> f64 {
    rollers
        .iter()
        .filter(|s| s.force_n > 0.0)
        .map(|s| f.mu * s.force_n * roller_slip_speed(f.mode, design, crank_rad, s))
        .sum()
}

/// Σ μ·F_j·slip over the output pins of one disc, N·mm/rad.
fn pin_losses(f: &PinFriction, design: &Design, pins: &[PinState]) -> f64 {
    let force: f64 = pins.iter().map(|p| p.force_n.max(0.0)).sum();
    f.mu * force * pin_slip_speed(f.mode, design)
}

/// μ·|Fb|·(d/2)·Ω/ω, N·mm/rad: the crank bearing's friction torque at the crank's speed
/// relative to the disc.
pub fn bearing_loss(f: &BearingFriction, design: &Design, bearing_force_n: f64) -> f64 {
    f.mu * bearing_force_n * 0.5 * f.bore_diameter_mm * relative_crank_speed_ratio(design.teeth)
}

/// The losses of one disc's contacts at crank angle `crank_rad` (the disc's own: its phase
/// 2πk/N included) from its solved equilibrium `solution`, per unit input speed, N·mm/rad,
/// without the input's drag (`no_load` 0: that is the reducer's, once, `reducer_losses`).
/// A path without friction, or not in the solution (no rollers, pins or bearing modelled),
/// loses nothing.
pub fn disc_losses(
    friction: &Friction,
    design: &Design,
    crank_rad: f64,
    solution: &AngleSolution,
) -> PathLosses {
    PathLosses {
        rollers: friction.rollers.map_or(0.0, |f| {
            roller_losses(&f, design, crank_rad, &solution.rollers)
        }),
        output_pins: friction
            .output_pins
            .map_or(0.0, |f| pin_losses(&f, design, &solution.pins)),
        crank_bearing: match (friction.crank_bearing, solution.bearing_force_n) {
            (Some(f), Some(fb)) => bearing_loss(&f, design, fb.norm()),
            _ => 0.0,
        },
        no_load: 0.0,
    }
}

/// The losses of a reducer at one crank angle, per unit input speed, N·mm/rad, from its discs'
/// contact losses (`disc_losses`, each at its own crank angle φ + 2πk/N): their sum and the
/// input's drag T0 at the input speed `input_rpm` (`no_load_torque_nmm`, times ω/ω = 1) once.
pub fn reducer_losses<'a>(
    friction: &Friction,
    input_rpm: Option<f64>,
    discs: impl IntoIterator<Item = &'a PathLosses>,
) -> PathLosses {
    let contacts = discs
        .into_iter()
        .fold(PathLosses::default(), |a, b| a.plus(b));
    PathLosses {
        no_load: friction.no_load_torque_nmm.at_rpm(input_rpm),
        ..contacts
    }
}

#[cfg(test)]
mod tests {
    //! The sliding speeds against their closed forms (MODEL.md), on roller states from the
    //! exact geometry of unmodified profiles: Rollers::evaluate at the ideal pose.
    use super::*;
    use crate::equilibrium::rollers::Rollers;
    use crate::geometry::clearance::Pose;
    use crate::geometry::{unit, Vec2};
    use crate::model::{
        ContactLaw, FrictionModel, GeometryMode, Material, Modification, OutputPins,
    };

    const STEEL: Material = Material {
        youngs_modulus_mpa: 2.06e5,
        poisson_ratio: 0.3,
    };

    fn design(rollers: usize, e: f64, rp: f64, rrp: f64) -> Design {
        Design {
            teeth: rollers - 1,
            rollers,
            discs: 1,
            eccentricity_mm: e,
            roller_circle_radius_mm: rp,
            roller_radius_mm: rrp,
            face_width_mm: 8.0,
            pins: OutputPins {
                count: 6,
                circle_radius_mm: 0.5 * rp,
                pin_radius_mm: 0.05 * rp,
                hole_clearance_mm: 0.0,
                support: None,
            },
            disc_material: STEEL,
            roller_material: STEEL,
            strength: Default::default(),
            crank_bearing: None,
            deviations: Default::default(),
            friction: None,
            thermal: None,
            structure_compliance_rad_per_nmm: 0.0,
            density_kg_per_mm3: 7.85e-6,
            output_inertia_kgmm2: 0.0,
            roller_inertia_kgmm2: 0.0,
        }
    }

    /// Every roller's state at the ideal pose of crank angle `phi` (exact geometry, no
    /// modification), each given a force of 1 N.
    fn states(d: &Design, phi: f64) -> Vec<RollerState> {
        let m = Modification {
            shift_mm: 0.0,
            equidistant_mm: 0.0,
            rotation_rad: 0.0,
        };
        let rollers = Rollers::new(d, &m, ContactLaw::PaperLinear, GeometryMode::Exact);
        let mut s = Vec::new();
        rollers.evaluate(&Pose::ideal(phi), &mut s).unwrap();
        s.iter_mut().for_each(|s| s.force_n = 1.0);
        s
    }

    /// (|P_i − I| − Rrp)/nc with P_i = Rp(cos 2πi/np, sin 2πi/np), I = e·np(cos φ, sin φ).
    fn closed_roller(d: &Design, i: usize, phi: f64) -> f64 {
        let a = std::f64::consts::TAU * i as f64 / d.rollers as f64;
        let p = unit(a) * d.roller_circle_radius_mm;
        let pitch = unit(phi) * (d.eccentricity_mm * d.rollers as f64);
        ((p - pitch).norm() - d.roller_radius_mm) / d.teeth as f64
    }

    /// Fixed rollers slide at the closed form, rotating ones at it × r_b/Rrp; over several
    /// designs and angles. Tolerance 1e-9 relative to Rp/nc: the foot of each roller on the
    /// exact profile is found to ~1e-12 mm (`geometry::clearance`), the closed form is exact.
    #[test]
    fn rollers_slide_at_the_closed_form() {
        for (np, e, rp, rrp) in [
            (10, 2.0, 30.0, 3.0),
            (16, 1.0, 40.0, 2.5),
            (31, 0.8, 50.0, 2.0),
        ] {
            let d = design(np, e, rp, rrp);
            let tol = 1e-9 * rp / (np - 1) as f64;
            for phi in [0.0, 0.3, 1.7, 4.0] {
                for (i, s) in states(&d, phi).iter().enumerate() {
                    let closed = closed_roller(&d, i, phi);
                    let fixed = roller_slip_speed(RollerMode::Fixed, &d, phi, s);
                    assert!(
                        (fixed - closed).abs() <= tol,
                        "np {np} φ {phi} i {i}: {fixed} vs {closed}"
                    );
                    let rotating = RollerMode::Rotating {
                        bore_radius_mm: 0.4 * rrp,
                    };
                    let r = roller_slip_speed(rotating, &d, phi, s);
                    assert!(
                        (r - 0.4 * closed).abs() <= tol,
                        "rotating: {r} vs {}",
                        0.4 * closed
                    );
                }
            }
        }
    }

    /// One angle's losses, path by path, against the hand sums of MODEL.md: rollers Σ μ·F·slip
    /// (F = 1 N each), pins μ·ΣF·e·(1 + 1/nc) (× r_bore/r_pin for sleeves), bearing
    /// μ·|Fb|·d/2·(1 + 1/nc), no-load T0. Round-off only (1e-12 relative).
    #[test]
    fn losses_are_the_hand_sums() {
        let d = design(10, 2.0, 30.0, 3.0);
        let phi = 0.9;
        let rollers = states(&d, phi);
        let pin = PinState {
            gap_mm: 0.0,
            force_n: 25.0,
            stiffness_n_per_mm: 0.0,
            arm_mm: 0.0,
            direction: Vec2::new(1.0, 0.0),
            point: Vec2::zeros(),
            gap_slope_mm: 0.0,
        };
        let solution = AngleSolution {
            rollers,
            pins: vec![
                pin,
                PinState {
                    force_n: 15.0,
                    ..pin
                },
            ],
            bearing_force_n: Some(Vec2::new(30.0, 40.0)),
            ..AngleSolution::default()
        };
        let omega_rel = 1.0 + 1.0 / 9.0;
        let rotating_rollers: f64 = (0..10)
            .map(|i| 0.05 * closed_roller(&d, i, phi) * 1.5 / 3.0)
            .sum();
        for (pins, pin_factor) in [
            (PinMode::Fixed, 1.0),
            (
                PinMode::Sleeve {
                    bore_radius_mm: 0.9,
                },
                0.9 / 1.5,
            ),
        ] {
            let f = Friction {
                model: FrictionModel::Loss,
                rollers: Some(RollerFriction {
                    mode: RollerMode::Rotating {
                        bore_radius_mm: 1.5,
                    },
                    mu: 0.05,
                }),
                output_pins: Some(PinFriction {
                    mode: pins,
                    mu: 0.1,
                }),
                crank_bearing: Some(BearingFriction {
                    mu: 0.002,
                    bore_diameter_mm: 12.0,
                }),
                no_load_torque_nmm: crate::model::NoLoadTorque::constant(7.0),
            };
            let disc = disc_losses(&f, &d, phi, &solution);
            let l = reducer_losses(&f, None, [&disc]);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1.0);
            assert!(
                close(l.rollers, rotating_rollers),
                "{} vs {rotating_rollers}",
                l.rollers
            );
            let pins_hand = 0.1 * 40.0 * 2.0 * omega_rel * pin_factor;
            assert!(
                close(l.output_pins, pins_hand),
                "{} vs {pins_hand}",
                l.output_pins
            );
            let bearing_hand = 0.002 * 50.0 * 6.0 * omega_rel;
            assert!(
                close(l.crank_bearing, bearing_hand),
                "{} vs {bearing_hand}",
                l.crank_bearing
            );
            assert_eq!(l.no_load, 7.0);
            assert!(close(
                l.total(),
                rotating_rollers + pins_hand + bearing_hand + 7.0
            ));
            // Two discs: the contacts' losses twice, the drag once.
            let two = reducer_losses(&f, None, [&disc, &disc]);
            assert!(close(two.rollers, 2.0 * rotating_rollers));
            assert_eq!(two.no_load, 7.0);
        }
    }
}
