//! The accuracy ladder's settings (`accuracy:` of a spec, or the command line): the rungs'
//! resolutions and the tolerances a rung must meet (see `engine::accuracy`).

use super::design::Design;
use super::effect::Effect;
use super::scene::{Plan, Scene, MAX_ROLLER_ANGLES};
use crate::units;

/// Steps per mesh period of the coarsest rung.
pub const COARSEST: usize = 12;
/// Steps per mesh period of the reference unless asked otherwise.
pub const DEFAULT_FINEST: usize = 3072;
/// Largest finest rung accepted: 12·2^12.
pub const MAX_FINEST: usize = COARSEST << 12;
/// Slice counts of the face-slices rungs of a crowned or tilted face, coarse to fine; the last
/// is their reference.
pub const FACE_SLICES: [usize; 6] = [2, 5, 10, 20, 40, 80];
/// What a rung must reach against the reference to count as accurate enough.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LadderTolerances {
    /// TE curve and TE fluctuation, arcsec.
    pub te_arcsec: f64,
    /// Max roller and bearing force, N.
    pub force_n: f64,
    /// Ratio fluctuation κmax − κmin.
    pub ratio: f64,
    /// Min clearance, µm.
    pub clearance_um: f64,
    /// Max face load factor (peak line load over its roller's mean), only for a crowned or
    /// tilted face.
    pub face_load_factor: f64,
    /// Max line load along the face, N/mm, only for a crowned or tilted face.
    pub line_load_n_per_mm: f64,
}

impl Default for LadderTolerances {
    fn default() -> Self {
        LadderTolerances {
            te_arcsec: 0.1,
            force_n: 0.5,
            ratio: 1e-4,
            clearance_um: 0.1,
            // A face load factor is quoted to two decimals (ISO 6336's KHβ); 1 N/mm is under
            // 1 % of the line loads of a loaded reducer's rollers (55 N/mm mean, 171 N/mm peak
            // on the paper's design at 10 N·m tilted by 0.3 mrad, README).
            face_load_factor: 0.01,
            line_load_n_per_mm: 1.0,
        }
    }
}

/// How to build the ladder.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Steps per mesh period of the reference (12·2^k, k ≥ 1).
    pub finest: usize,
    /// Steps per mesh period of the settings rungs; `None`: the cheapest steps rung that meets
    /// the tolerances (the finest when none does).
    pub settings_steps: Option<usize>,
    /// What a rung must reach against the reference.
    pub tolerances: LadderTolerances,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            finest: DEFAULT_FINEST,
            settings_steps: None,
            tolerances: LadderTolerances::default(),
        }
    }
}

/// A steps-per-period value of the ladder: 12·2^k with 24 ≤ n ≤ `MAX_FINEST` (`min` 12 for the
/// settings resolution). The message says what is accepted.
pub fn ladder_steps(n: i64, min: usize) -> std::result::Result<usize, String> {
    let rungs: Vec<usize> = std::iter::successors(Some(COARSEST), |r| Some(2 * r))
        .take_while(|&r| r <= MAX_FINEST)
        .filter(|&r| r >= min)
        .collect();
    match rungs.iter().find(|&&r| r as i64 == n) {
        Some(&r) => Ok(r),
        None => Err(format!(
            "steps per mesh period must be 12·2^k, one of {}, got {n}",
            rungs
                .iter()
                .map(|r| r.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// A tolerance: a positive finite number.
pub fn tolerance(value: f64) -> std::result::Result<f64, String> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(format!(
            "a tolerance must be a positive number, got {}",
            crate::numeric::input(value)
        ))
    }
}

/// The setting a problem of `check` is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Setting {
    /// The scene the ladder runs (spec: `accuracy.scene`).
    Scene,
    /// The reference's steps per mesh period (`accuracy.finest_steps_per_period`).
    Finest,
    /// The settings rungs' steps per mesh period (`accuracy.settings_steps_per_period`).
    SettingsSteps,
}

/// Can this scene be run on this ladder? The error names the setting and says why not.
pub fn check(
    design: &Design,
    scene: &Scene,
    options: &Options,
) -> std::result::Result<(), (Setting, String)> {
    if let Some(s) = options.settings_steps {
        if s > options.finest {
            return Err((
                Setting::SettingsSteps,
                format!(
                    "the settings rungs' {s} steps per mesh period exceed the finest rung's {}",
                    options.finest
                ),
            ));
        }
    }
    if let Some(m) = scene.torsion_refusal("the ladder") {
        return Err((Setting::Scene, m));
    }
    if scene.duty_cycle.is_some() {
        return Err((
            Setting::Scene,
            format!(
                "scene `{}` runs a duty cycle (one run per bin): the ladder needs one run of a \
                 scene; name a scene with its own `output_torque_nm`",
                scene.name
            ),
        ));
    }
    let plan = Plan::for_scene(scene);
    let compared = [Effect::Clearance, Effect::RollerContact, Effect::Bearing];
    if !compared.iter().any(|&e| plan.has(e)) {
        return Err((
            Setting::Scene,
            format!(
            "scene `{}` computes none of the ladder's outputs (it needs clearance, roller_contact \
             or bearing)",
            scene.name
        ),
        ));
    }
    let periods = units::rad(scene.crank_to_deg - scene.crank_from_deg) / design.mesh_period_rad();
    let base = base_angles(periods);
    let finest = base as f64 * (options.finest / COARSEST) as f64;
    let max = (MAX_ROLLER_ANGLES as usize / design.rollers) as f64;
    if finest > max {
        return Err((
            Setting::Finest,
            format!(
            "the finest rung would solve {finest} crank angles over {:.4} mesh periods; at most \
             {max} fit in memory with {} rollers: choose a smaller finest rung or a shorter crank \
             range",
            periods, design.rollers
        ),
        ));
    }
    let finest_slices = FACE_SLICES[FACE_SLICES.len() - 1];
    let cells = design.rollers.max(design.pins.count) * scene.crank_rad.len() * finest_slices;
    if plan.has(Effect::RollerContact)
        && !design.deviations.face(&scene.face).is_uniform()
        && cells as i64 > MAX_ROLLER_ANGLES
    {
        return Err((
            Setting::Scene,
            format!(
                "scene `{}` loads a crowned or tilted face: its face-slices rungs would hold \
                 {finest_slices} slices × {} contacts × {} crank angles, {cells} line loads, more \
                 than the {MAX_ROLLER_ANGLES} a scene may hold; give the scene fewer crank steps",
                scene.name,
                design.rollers.max(design.pins.count),
                scene.crank_rad.len()
            ),
        ));
    }
    Ok(())
}

/// Crank angles of the coarsest rung: 12 per mesh period, at least one.
pub fn base_angles(periods: f64) -> usize {
    ((COARSEST as f64 * periods).round() as usize).max(1)
}
