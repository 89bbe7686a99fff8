//! A value against a limit: the comparison tolerance, whether it passes, and by how much it
//! lies beyond. What the checks of limits (`check`), the constraints of an optimisation
//! (`optimise::problem::Margin`) and the tolerance study's worst samples share.

use crate::model::quantity::Bound;

/// Comparison tolerance of limits and constraints: 1e-12 of max(1, |limit|). It absorbs the
/// binary representation of decimal inputs (0.150 − 0.135 is 0.01499999999999999 in f64) and
/// the ~1e-14 mm round-off of the exact gap, and is a picometre on a millimetre limit.
pub fn tolerance(limit: f64) -> f64 {
    1e-12 * limit.abs().max(1.0)
}

/// Does `value` satisfy `limit` in the direction `bound` (within `tolerance`)?
pub fn passes(value: f64, limit: f64, bound: Bound) -> bool {
    match bound {
        Bound::Max => value <= limit + tolerance(limit),
        Bound::Min => value >= limit - tolerance(limit),
    }
}

/// How far beyond `limit` in the direction `bound` a value lies, relative to |limit| (to 1
/// when the limit is 0): positive outside, negative inside; a NaN is infinitely outside.
pub fn excess(value: f64, limit: f64, bound: Bound) -> f64 {
    let scale = if limit != 0.0 { limit.abs() } else { 1.0 };
    let beyond = match bound {
        Bound::Max => value - limit,
        Bound::Min => limit - value,
    };
    if beyond.is_nan() {
        f64::INFINITY
    } else {
        beyond / scale
    }
}
