//! An optimisation study (paper §4): objective, variables, start, constraints.

use super::modification::Modification;
use super::quantity::ObjectiveDef;
use crate::units;

/// An optimisation objective: a scalar quantity of the registry (`quantity::OBJECTIVES`).
pub type Objective = &'static ObjectiveDef;

/// Most points of a study's global stage: the length of its Sobol sequence (2^16).
pub const MAX_GLOBAL_SAMPLES: usize = 1 << 16;
/// Most points of a study's verification grid (steps^variables), as many as the global stage.
pub const MAX_VERIFY_POINTS: usize = MAX_GLOBAL_SAMPLES;
/// Most evaluations of one local run.
pub const MAX_LOCAL_EVALUATIONS: usize = 10_000;

/// Default interior points of the global stage for `dims` variables: 64, 512 and 2048 for 1, 2
/// and 3 variables (a spacing of 1/64, 1/23 and 1/13 of each range).
pub fn default_global_samples(dims: usize) -> usize {
    match dims {
        0 | 1 => 64,
        2 => 512,
        _ => 2048,
    }
}

/// Default points of the global stage on each face of the feasible region: 64 on a line (two
/// variables; a spacing of 1/64 of the face), 256 on a plane (three variables, 1/16); a single
/// variable's faces are points.
pub fn default_boundary_samples(dims: usize) -> usize {
    match dims {
        0 | 1 => 1,
        2 => 64,
        _ => 256,
    }
}

/// Default points per variable of the verification grid: 401 for one variable (a step of
/// 1/400 of the range), 41 × 41 for two (1/40), 17³ = 4913 for three (1/16).
pub fn default_verify_grid(dims: usize) -> usize {
    match dims {
        0 | 1 => 401,
        2 => 41,
        _ => 17,
    }
}

/// A design variable of a study, bounds in engine units (mm, or rad for the rotation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VariableKind {
    /// ΔRp, the shift modification, mm.
    Shift,
    /// ΔRrp, the equidistant modification, mm.
    Equidistant,
    /// Δδ, the rotation modification, rad (degrees in the spec).
    Rotation,
}

impl VariableKind {
    /// Its key in a study (`variables.<key>`, `start.<key>`), with the spec's unit.
    pub fn key(self) -> &'static str {
        match self {
            VariableKind::Shift => "shift_mm",
            VariableKind::Equidistant => "equidistant_mm",
            VariableKind::Rotation => "rotation_deg",
        }
    }

    /// The value of this variable in a modification, engine units.
    pub fn get(self, m: &Modification) -> f64 {
        match self {
            VariableKind::Shift => m.shift_mm,
            VariableKind::Equidistant => m.equidistant_mm,
            VariableKind::Rotation => m.rotation_rad,
        }
    }

    /// Set this variable of a modification to `value`, engine units.
    pub fn set(self, m: &mut Modification, value: f64) {
        match self {
            VariableKind::Shift => m.shift_mm = value,
            VariableKind::Equidistant => m.equidistant_mm = value,
            VariableKind::Rotation => m.rotation_rad = value,
        }
    }

    /// Engine value to the spec's unit (mm stay mm, rad become degrees).
    pub fn to_spec_unit(self, value: f64) -> f64 {
        match self {
            VariableKind::Rotation => units::deg(value),
            _ => value,
        }
    }
}

/// A variable of a study and its bounds, engine units (mm, or rad for the rotation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variable {
    /// Which modification it is.
    pub kind: VariableKind,
    /// Its lower bound.
    pub lower: f64,
    /// Its upper bound.
    pub upper: f64,
}

/// One optimisation study (paper §4): minimise a (weighted) objective of one scene over the
/// modification variables, subject to the tip clearance band (paper Eqs. 8, 21) and the
/// whole-mesh minimum clearance, checked on the exact geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// The study's name (`name`; `study-n` by default, n from 1), unique in the spec.
    pub name: String,
    /// Index into `Spec::scenes`.
    pub scene: usize,
    /// Weighted terms; a single objective has weight 1.
    pub objective: Vec<(Objective, f64)>,
    /// The variables optimised, those given in the order shift, equidistant, rotation.
    pub variables: Vec<Variable>,
    /// The starting modification (variables not optimised keep the spec's values).
    pub start: Modification,
    /// ΔRrp − ΔRp ∈ [lower, upper], mm.
    pub tip_clearance_mm: Option<(f64, f64)>,
    /// Whole-mesh minimum clearance ≥ this, mm.
    pub min_clearance_mm: Option<f64>,
    /// Largest unloaded lost motion over the scene's crank angles ≤ this, arcsec.
    pub max_lost_motion_arcsec: Option<f64>,
    /// Labelled modifications evaluated and reported beside the optimum (`references`).
    pub references: Vec<(String, Modification)>,
    /// Upper limit on this study's optimum objective; `None`: the spec's
    /// `limits.optimum_max_objective`, if set.
    pub optimum_max_objective: Option<f64>,
    /// Interior points of the global (space-filling) stage.
    pub global_samples: usize,
    /// Points of the global stage on each face of the feasible region (box faces, tip band).
    pub boundary_samples: usize,
    /// Evaluations allowed to each local run.
    pub local_evaluations: usize,
    /// Points per variable of the verification grid (0: no verification).
    pub verify_grid: usize,
}
