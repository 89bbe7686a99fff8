//! An optimisation study (paper §4): objective, variables, start, constraints.

use super::face::Crowning;
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

/// A point of a study: the tooth-profile modification and the disc's crowning along the face
/// width (`modification.crowning`; a circular crown's radius and start can be variables). The
/// crowning is the one every scene of the spec carries (`Face::crowning`) unless the study
/// varies it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Point {
    /// The tooth-profile modification.
    pub modification: Modification,
    /// The disc's crowning along the face width.
    pub crowning: Crowning,
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
    /// Rc, the radius of the disc's circular crown, mm (`modification.crowning.radius_mm`).
    /// Searched in log(Rc) (`Variable::at_unit`): a useful range spans decades.
    CrownRadius,
    /// z0, the half-length of the circular crown's flat middle, mm
    /// (`modification.crowning.start_mm`), in [0, B/2).
    CrownStart,
}

impl VariableKind {
    /// Its key in a study (`variables.<key>`, `start.<key>`), with the spec's unit.
    pub fn key(self) -> &'static str {
        match self {
            VariableKind::Shift => "shift_mm",
            VariableKind::Equidistant => "equidistant_mm",
            VariableKind::Rotation => "rotation_deg",
            VariableKind::CrownRadius => "crown_radius_mm",
            VariableKind::CrownStart => "crown_start_mm",
        }
    }

    /// Whether it is a variable of the crowning (which needs a circular crowning).
    pub fn of_crown(self) -> bool {
        matches!(self, VariableKind::CrownRadius | VariableKind::CrownStart)
    }

    /// The value of this variable at a point, engine units (NaN for a crown variable of a
    /// point without a circular crown, which validation refuses).
    pub fn get(self, p: &Point) -> f64 {
        let m = &p.modification;
        match (self, p.crowning) {
            (VariableKind::Shift, _) => m.shift_mm,
            (VariableKind::Equidistant, _) => m.equidistant_mm,
            (VariableKind::Rotation, _) => m.rotation_rad,
            (VariableKind::CrownRadius, Crowning::Circular { radius_mm, .. }) => radius_mm,
            (VariableKind::CrownStart, Crowning::Circular { start_mm, .. }) => start_mm,
            _ => f64::NAN,
        }
    }

    /// Set this variable of a point to `value`, engine units (a crown variable only changes a
    /// circular crown).
    pub fn set(self, p: &mut Point, value: f64) {
        let m = &mut p.modification;
        match (self, &mut p.crowning) {
            (VariableKind::Shift, _) => m.shift_mm = value,
            (VariableKind::Equidistant, _) => m.equidistant_mm = value,
            (VariableKind::Rotation, _) => m.rotation_rad = value,
            (VariableKind::CrownRadius, Crowning::Circular { radius_mm, .. }) => *radius_mm = value,
            (VariableKind::CrownStart, Crowning::Circular { start_mm, .. }) => *start_mm = value,
            _ => {}
        }
    }

    /// Engine value to the spec's unit (mm stay mm, rad become degrees).
    pub fn to_spec_unit(self, value: f64) -> f64 {
        match self {
            VariableKind::Rotation => units::deg(value),
            _ => value,
        }
    }

    /// The value of this variable at a point, in the spec's unit (`get`, `to_spec_unit`).
    pub fn spec_value(self, p: &Point) -> f64 {
        self.to_spec_unit(self.get(p))
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

impl Variable {
    /// Whether the search runs in log(x): the crown radius, whose bounds are positive and
    /// whose useful range spans decades (a flat and a round crown differ by 100×); on a linear
    /// scale the global sample would leave the lowest decade almost empty.
    pub fn logarithmic(&self) -> bool {
        self.kind == VariableKind::CrownRadius
    }

    /// The value at z ∈ [0, 1] of the search's unit interval: lower + z·(upper − lower), or
    /// lower·(upper/lower)^z for a logarithmic variable (whose z = 0 and 1 give the bounds
    /// exactly, not to the round-off of exp and ln).
    pub fn at_unit(&self, z: f64) -> f64 {
        if !self.logarithmic() {
            self.lower + z * (self.upper - self.lower)
        } else if z == 0.0 {
            self.lower
        } else if z == 1.0 {
            self.upper
        } else {
            (self.lower.ln() + z * (self.upper / self.lower).ln()).exp()
        }
    }

    /// The place of the value x in the search's unit interval (the inverse of `at_unit`).
    pub fn unit_of(&self, x: f64) -> f64 {
        if self.logarithmic() {
            (x / self.lower).ln() / (self.upper / self.lower).ln()
        } else {
            (x - self.lower) / (self.upper - self.lower)
        }
    }
}

/// One optimisation study (paper §4): minimise a (weighted) objective of one scene over the
/// modification variables (and the circular crown's radius and start), subject to the tip
/// clearance band (paper Eqs. 8, 21), the whole-mesh minimum clearance, checked on the exact
/// geometry, and upper bounds on other objectives of the scene.
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
    /// The starting crowning: the spec's, with the study's `start` crown values.
    pub crowning: Crowning,
    /// ΔRrp − ΔRp ∈ [lower, upper], mm.
    pub tip_clearance_mm: Option<(f64, f64)>,
    /// Whole-mesh minimum clearance ≥ this, mm.
    pub min_clearance_mm: Option<f64>,
    /// Largest unloaded lost motion over the scene's crank angles ≤ this, arcsec.
    pub max_lost_motion_arcsec: Option<f64>,
    /// Objectives bounded above on the study's scene (`constraints.objectives`), each ≤ its
    /// bound in the objective's unit: e.g. the TE fluctuation of a crown study.
    pub objective_limits: Vec<(Objective, f64)>,
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

impl Study {
    /// The study's start as a point: its modification and crowning.
    pub fn start_point(&self) -> Point {
        Point {
            modification: self.start,
            crowning: self.crowning,
        }
    }
}
