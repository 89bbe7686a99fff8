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

/// How far beyond `limit` in the direction `bound` `value` lies, in its unit: positive
/// outside, negative inside.
pub fn beyond(value: f64, limit: f64, bound: Bound) -> f64 {
    match bound {
        Bound::Max => value - limit,
        Bound::Min => limit - value,
    }
}

/// How far beyond `limit` in the direction `bound` a value lies, relative to |limit| (to 1
/// when the limit is 0): positive outside, negative inside; a NaN is infinitely outside.
pub fn excess(value: f64, limit: f64, bound: Bound) -> f64 {
    let beyond = beyond(value, limit, bound);
    if beyond.is_nan() {
        f64::INFINITY
    } else {
        relative(beyond, limit, Scale::Limit)
    }
}

/// What a distance from a limit is measured in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// |limit| (1 of its unit when the limit is 0): a check's excess, read against the limit it
    /// breaks (10 % over a 0.01 mm limit is 0.001 mm).
    Limit,
    /// max(|limit|, 1 of its unit): an optimisation's margins, which rank constraints of
    /// different units against each other, so a small bound must not magnify its margin.
    LimitOrUnit,
}

/// `distance` relative to `limit` on `scale` (the relative excess of a check, the relative
/// margin of a constraint).
pub fn relative(distance: f64, limit: f64, scale: Scale) -> f64 {
    let unit = match scale {
        Scale::Limit if limit != 0.0 => limit.abs(),
        Scale::Limit => 1.0,
        Scale::LimitOrUnit => limit.abs().max(1.0),
    };
    distance / unit
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two scales agree on a limit of 1 unit or more, and part below it: a check's excess
    /// over a 0.1 limit is read against 0.1, a margin against 1; a zero limit is 1 unit on both.
    /// Exact in f64: every value is a quotient by 1, 2 or a power of two.
    #[test]
    fn a_distance_is_relative_to_the_limit_or_to_one_unit() {
        assert_eq!(relative(1.0, 2.0, Scale::Limit), 0.5);
        assert_eq!(relative(1.0, -2.0, Scale::LimitOrUnit), 0.5);
        assert_eq!(relative(0.25, 0.125, Scale::Limit), 2.0);
        assert_eq!(relative(0.25, 0.125, Scale::LimitOrUnit), 0.25);
        assert_eq!(relative(0.25, 0.0, Scale::Limit), 0.25);
        assert_eq!(relative(0.25, 0.0, Scale::LimitOrUnit), 0.25);
        assert_eq!(excess(1.25, 0.125, Bound::Max), 9.0);
    }
}
