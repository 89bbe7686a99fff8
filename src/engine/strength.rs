//! The `strength` effect over a scene (issue 41, `docs/effects/strength.md`): the output pins'
//! stresses from every disc's pin forces (`equilibrium::pin_stress`), each disc's and the
//! rollers' rolling-contact fatigue lives at the scene's largest Hertz pressure
//! (`contact::fatigue`), and the crank bearing's static safety s0 = C0/max |Fb| (ISO 76).

use crate::contact::fatigue;
use crate::equilibrium::pin_beam::PinBeam;
use crate::equilibrium::pin_stress;
use crate::geometry::{rotate, unit, z_cross, Vec2};
use crate::model::results::{bounded, LoadedSweep, PinCurves};
use crate::model::strength::{DiscStrength, FatigueLives, PinStress, StaticSafety};
use crate::model::{Design, Effect, Plan, Scene};

/// The pins' stresses over the scene's crank angles `crank_rad` from each disc's sweep
/// (`discs[k]`, disc k at its crank phase), when the pins bend (`support`) and carry forces.
///
/// Disc k's hole pushes pin j with the force F_kj (its magnitude from the sweep) along the
/// direction the sweep recorded (`PinCurves::direction_rad`: the angle δ_kj from disc k's
/// eccentric direction e_φk = (cos(φ + 2πk/N), sin(φ + 2πk/N))), each disc's force at its own
/// mid-plane; the vectors are summed along the pin (`pin_stress::largest`).
///
/// `pin_friction` is c_p of the coupled friction model when the sweep balanced with it
/// (`loaded::Model::coupled`, a running crank sweep), else 0: the hole slides over its pin
/// along τ = ẑ × e_φk, so its friction on the disc is −c_p·F·τ (`Coupling::pin_friction`) and
/// on the pin +c_p·F·τ, at the same mid-plane as the normal force; the pin bends under both.
pub fn pin_stress(
    design: &Design,
    crank_rad: &[f64],
    discs: &[&LoadedSweep],
    pin_friction: f64,
) -> Option<PinStress> {
    let support = design.pins.support?;
    let pins: Vec<&PinCurves> = discs
        .iter()
        .map(|d| d.pins.as_ref())
        .collect::<Option<_>>()?;
    let diameter = 2.0 * PinBeam::of(design)?.bending_radius_mm;
    let count = design.pins.count;
    let mut bending = vec![vec![0.0; crank_rad.len()]; count];
    let mut shear = bending.clone();
    for (a, &phi) in crank_rad.iter().enumerate() {
        for j in 0..count {
            let loads: Vec<(f64, Vec2)> = (0..discs.len())
                .map(|k| {
                    let (sd, cd) = pins[k].direction_rad[j][a].sin_cos();
                    let e_phi = unit(phi + design.disc_phase_rad(k));
                    let along = rotate(e_phi, cd, sd) + z_cross(e_phi) * pin_friction;
                    (support.disc_positions_mm[k], pins[k].force_n[j][a] * along)
                })
                .collect();
            let (m, v) = pin_stress::largest(&support, &loads);
            bending[j][a] = pin_stress::bending_stress_mpa(m, diameter);
            shear[j][a] = pin_stress::shear_stress_mpa(v, diameter);
        }
    }
    Some(PinStress {
        bending_stress_mpa: bending,
        shear_stress_mpa: shear,
        yield_strength_mpa: design.strength.rollers.yield_strength_mpa,
    })
}

/// One disc's contact fatigue and crank bearing's static safety over the scene, from its sweep
/// `loaded`. The lives need an S–N law, the scene's speed and whole periods of the reducer as
/// run (`Scene::run_period_rad`: the largest pressure of part of a period is not the
/// reducer's); the safety needs C0.
pub fn disc_strength(
    design: &Design,
    (scene, plan): (&Scene, &Plan),
    loaded: &LoadedSweep,
) -> Option<DiscStrength> {
    if !plan.computes(Effect::Strength) {
        return None;
    }
    let whole = scene.spans_loaded_periods(design, plan);
    let fatigue = loaded
        .rollers
        .as_ref()
        .zip(scene.input_speed_rpm)
        .filter(|_| whole)
        .map(|(r, rpm)| lives(design, largest(&r.pressure_mpa), rpm))
        .filter(|f| f.disc_h.is_some() || f.rollers_h.is_some());
    let static_safety = design
        .crank_bearing
        .and_then(|b| b.static_load_rating_n)
        .zip(loaded.bearing.as_ref())
        .map(|(c0, b)| static_safety(c0, largest(std::slice::from_ref(&b.force_n))));
    Some(DiscStrength {
        fatigue,
        static_safety,
    })
}

/// The largest entry of `rows`, 0 when empty.
fn largest(rows: &[Vec<f64>]) -> f64 {
    rows.iter().flatten().fold(0.0, |m: f64, &x| m.max(x))
}

/// The disc's and the rollers' lives at the largest pressure `pressure_mpa` and the input speed
/// `rpm`: the disc's lobes loaded np/nc times per crank turn, each roller once.
pub fn lives(design: &Design, pressure_mpa: f64, rpm: f64) -> FatigueLives {
    let s = &design.strength;
    let disc_passes = fatigue::disc_passes_per_crank_turn(design.teeth);
    let roller_passes = fatigue::ROLLER_PASSES_PER_CRANK_TURN;
    FatigueLives {
        pressure_mpa,
        disc_h: (s.disc.contact_fatigue)
            .map(|law| fatigue::life_h(&law, pressure_mpa, disc_passes, rpm)),
        rollers_h: (s.rollers.contact_fatigue)
            .map(|law| fatigue::life_h(&law, pressure_mpa, roller_passes, rpm)),
    }
}

/// s0 = C0/F (ISO 76) of a bearing of static rating `c0_n` (N) under its largest force
/// `largest_force_n` (N); the largest double when it carries nothing.
pub fn static_safety(c0_n: f64, largest_force_n: f64) -> StaticSafety {
    let s0 = c0_n / largest_force_n;
    StaticSafety {
        largest_force_n,
        safety: bounded(s0),
    }
}
