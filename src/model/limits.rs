//! Acceptance limits of a spec.

/// Acceptance limits; each applies to every scene that computes its quantity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Limits {
    pub min_clearance_mm: Option<f64>,
    pub max_roller_force_n: Option<f64>,
    pub max_pin_force_n: Option<f64>,
    pub max_bearing_force_n: Option<f64>,
    pub max_contact_pressure_mpa: Option<f64>,
    pub max_te_fluctuation_arcsec: Option<f64>,
    pub max_ratio_fluctuation: Option<f64>,
    pub min_rollers_in_contact: Option<usize>,
    pub optimum_max_objective: Option<f64>,
}
