//! An optimisation study (paper §4): objective, variables, start, constraints.

use super::design::Modification;
use super::quantity::ObjectiveDef;
use crate::units;

/// An optimisation objective: a scalar quantity of the registry (`quantity::OBJECTIVES`).
pub type Objective = &'static ObjectiveDef;

/// A design variable of a study, bounds in engine units (mm, or rad for the rotation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VariableKind {
    Shift,
    Equidistant,
    Rotation,
}

impl VariableKind {
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

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variable {
    pub kind: VariableKind,
    pub lower: f64,
    pub upper: f64,
}

/// One optimisation study (paper §4): minimise a (weighted) objective of one scene over the
/// modification variables, subject to the tip clearance band (paper Eqs. 8, 21) and the
/// whole-mesh minimum clearance, checked on the exact geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    pub name: String,
    /// Index into `Spec::scenes`.
    pub scene: usize,
    /// Weighted terms; a single objective has weight 1.
    pub objective: Vec<(Objective, f64)>,
    pub variables: Vec<Variable>,
    /// The starting modification (variables not optimised keep the spec's values).
    pub start: Modification,
    /// ΔRrp − ΔRp ∈ [lower, upper], mm.
    pub tip_clearance_mm: Option<(f64, f64)>,
    /// Whole-mesh minimum clearance ≥ this, mm.
    pub min_clearance_mm: Option<f64>,
    pub references: Vec<(String, Modification)>,
    pub optimum_max_objective: Option<f64>,
    pub global_samples: usize,
    pub local_evaluations: usize,
}
