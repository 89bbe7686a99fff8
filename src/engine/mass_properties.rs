//! The reducer's mass properties: each disc's mass and inertia from its exact modified profile
//! (the disc as built when the spec was measured), and the inertia at the input.

use crate::geometry::mass_properties::{disc_mass, DiscMass};
use crate::geometry::placement::disc_body;
use crate::geometry::roller_spin::mean_square_spin_ratio;
use crate::geometry::{unit, Vec2};
use crate::model::{Effect, Plan};
use crate::spec::Spec;
use crate::units;

/// The discs' mass properties and the reducer's inertia at the input.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// One disc (the discs are identical).
    pub disc: DiscMass,
    /// J_in, kg·mm²: Σ over the discs of m·e² + J_c/nc² (e the crank's as built, e + de: the
    /// orbit of every disc centre), plus the output's J_out/nc² (the
    /// output turns at ω/nc), plus the rollers' spin when they turn and their inertia is given;
    /// the pins, crank shaft and its bearings are not in it.
    pub input_inertia_kgmm2: f64,
    /// The output's share of J_in, J_out/nc², kg·mm².
    pub output_kgmm2: f64,
    /// The rollers' spin's share of J_in, J_r·⟨Σ(Ωᵢ/ω)²⟩ (`geometry::roller_spin`), kg·mm²: 0
    /// unless they turn and `reducer.roller_inertia_kgm2` is given.
    pub rollers_kgmm2: f64,
}

/// The mass properties of `spec`'s discs under its modification, with the disc's form error
/// when it has one: the face inside the profile (`geometry::mass_properties::profile_moments`),
/// less the output-pin holes and the bore of `disc_solid`, over the face width at the density; and
/// the inertia at the input, with the rollers' spin when the spec gives their inertia (only
/// for rollers that turn).
pub fn mass_properties(spec: &Spec) -> MassProperties {
    let design = &spec.design;
    let disc = disc_mass(design, &spec.modification);
    let nc = design.teeth as f64;
    let discs = design.discs as f64
        * disc.input_inertia_kgmm2(design.built_eccentricity_mm(), design.teeth);
    let output = design.output_inertia_kgmm2 / (nc * nc);
    let rollers = design.roller_inertia_kgmm2 * mean_square_spin_ratio(design);
    MassProperties {
        disc,
        input_inertia_kgmm2: discs + output + rollers,
        output_kgmm2: output,
        rollers_kgmm2: rollers,
    }
}

/// What the discs' centripetal forces leave on the crank at speed in a scene that computes
/// `inertia` (`Effect::Inertia`): disc k is pulled in by F_c·(−e_φk) by its bearing, so the
/// crank carries F_c·e_φk at its mid-plane z_k; their sum and their couple about the mean
/// mid-plane z̄. Both turn with the crank and keep their size (the discs' phases are fixed
/// apart), so one crank angle gives them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unbalance {
    /// The scene's index in the spec.
    pub scene: usize,
    /// The speed it is at, rpm: the scene's, or a duty cycle's fastest bin's.
    pub input_speed_rpm: f64,
    /// F_c = m·(e + de)·ω², N: each disc's.
    pub disc_force_n: f64,
    /// |Σ F_c·e_φk|, N: zero for two or more discs evenly phased.
    pub force_n: f64,
    /// |Σ (z_k − z̄)·F_c·e_φk|, N·mm: two discs at 180° a face width B apart: F_c·B.
    pub moment_nmm: f64,
}

/// The unbalance of every scene of `spec` that computes `inertia`, from the disc's mass
/// (`disc`) and the discs' places along the axis (`geometry::placement::disc_body`, as the
/// solid export places them: `output_pins.support.disc_positions_mm`, or side by side).
pub fn unbalances(spec: &Spec, disc: &DiscMass) -> Vec<Unbalance> {
    let design = &spec.design;
    let bodies: Vec<(Vec2, f64)> = (0..design.discs)
        .map(|k| {
            let phase = design.disc_phase_rad(k);
            let z = disc_body(design, k).placement.z_mm + 0.5 * design.face_width_mm;
            (unit(phase), z)
        })
        .collect();
    let mean_z = bodies.iter().map(|b| b.1).sum::<f64>() / bodies.len() as f64;
    let force: Vec2 = bodies.iter().map(|b| b.0).sum();
    let couple: Vec2 = bodies.iter().map(|(u, z)| u * (z - mean_z)).sum();
    (spec.scenes.iter().enumerate())
        .filter(|(_, s)| Plan::for_scene(s).computes(Effect::Inertia))
        .filter_map(|(i, s)| {
            let bins = s.duty_cycle.iter().flatten().map(|b| b.input_speed_rpm);
            let speed = s.input_speed_rpm.into_iter().chain(bins).reduce(f64::max)?;
            let f =
                disc.centripetal_force_n(design.built_eccentricity_mm(), units::rad_per_s(speed));
            Some(Unbalance {
                scene: i,
                input_speed_rpm: speed,
                disc_force_n: f,
                force_n: f * force.norm(),
                moment_nmm: f * couple.norm(),
            })
        })
        .collect()
}
