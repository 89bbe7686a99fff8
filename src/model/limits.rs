//! Acceptance limits of a spec: bounds on scalar quantities of the registry
//! (`quantity::LIMITS`), each applied to every scene that computes its quantity.

use super::quantity::LimitDef;

/// One limit set by a spec.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limit {
    /// What it bounds: its key, quantity and side (an entry of `quantity::LIMITS`).
    pub def: &'static LimitDef,
    /// The bound, in the quantity's unit.
    pub value: f64,
}

/// Acceptance limits; each applies to every scene that computes its quantity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Limits {
    /// In the registry's order (`quantity::LIMITS`).
    pub entries: Vec<Limit>,
    /// Upper limit on the optimum objective of every optimisation study that sets none of its
    /// own (`Study::optimum_max_objective`).
    pub optimum_max_objective: Option<f64>,
    /// `accuracy_resolved: true`: the accuracy scene's crank resolution must meet the accuracy
    /// ladder's tolerances (`engine::resolution`), a failing check otherwise.
    pub accuracy_resolved: bool,
}

impl Limits {
    /// The value of the limit with this key, when the spec sets it.
    pub fn get(&self, key: &str) -> Option<f64> {
        self.entries
            .iter()
            .find(|l| l.def.key == key)
            .map(|l| l.value)
    }
}
