//! A requirement a design does not meet, with its value and limit.

use crate::engine::limit::excess;
use crate::model::quantity::Bound;

/// A requirement a design does not meet.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// The requirement's key (`envelope.max_outer_diameter_mm`, `limits.max_contact_pressure_mpa`,
    /// `rules`: a rule of the spec, `torque`: the contact model cannot hold the torque).
    pub requirement: String,
    /// The design's value and the limit, when the requirement is a bound.
    pub bound: Option<(f64, f64, Bound)>,
    pub unit: &'static str,
    /// What the engine said, for a rule of the spec or a torque the contacts cannot hold.
    pub message: Option<String>,
}

impl Failure {
    /// A bound broken: `value` beyond `limit` (`upper`: an upper limit).
    pub fn bound(key: &str, value: f64, limit: f64, unit: &'static str, upper: bool) -> Failure {
        let b = if upper { Bound::Max } else { Bound::Min };
        Failure {
            requirement: key.to_string(),
            bound: Some((value, limit, b)),
            unit,
            message: None,
        }
    }

    /// How far beyond its limit, relative (`engine::limit::excess`); a failure without a
    /// number ranks beyond every bound.
    pub fn excess(&self) -> f64 {
        self.bound.map_or(f64::MAX, |(v, l, b)| excess(v, l, b))
    }
}
