//! Rating life of the crank bearing (ISO 281, MODEL.md "Several discs, torsion, bearing life").
//!
//! A bearing under a load that varies over the load cycle is rated for the constant load P
//! that wears it alike: P = (mean of F^p over the cycle)^(1/p), p the life exponent (10/3 for
//! roller bearings, 3 for ball bearings). Its basic rating life is L10 = (C/P)^p millions of
//! revolutions, C the basic dynamic load rating. The crank bearing turns with the crank
//! relative to the disc, which itself turns backwards at n/nc: the relative speed is
//! n·(1 + 1/nc), so L10h = (C/P)^p · 10⁶ / (60 · n · (1 + 1/nc)) hours.

use crate::equilibrium::friction::sliding::relative_crank_speed_ratio;
use crate::model::design::CrankBearing;
use crate::model::results::{bounded, BearingLife, UNBOUNDED_LIFE_H};

/// P = (mean of F^p)^(1/p), N, over bearing forces `force_n` (N) sampled evenly over whole
/// load cycles (the rectangle rule is then the mean of the periodic load). 0 without samples.
pub fn equivalent_load(force_n: &[f64], exponent: f64) -> f64 {
    weighted_power_mean(force_n.iter().map(|&f| (1.0, f)), exponent)
}

/// The weighted power mean (Σ wᵢ·xᵢ^p / Σ wᵢ)^(1/p) of magnitudes `x` (≥ 0) with weights
/// `w` (≥ 0, not all 0), scaled by the largest x so that x^p cannot overflow; 0 when every
/// weighted x is 0. The pairs (w, x) are read three times and never stored: the bearing's
/// equivalent load is this mean over every crank angle of a scene.
pub fn weighted_power_mean(pairs: impl Iterator<Item = (f64, f64)> + Clone, p: f64) -> f64 {
    let weight: f64 = pairs.clone().map(|(w, _)| w).sum();
    // A zero weight leaves its value out (its x may exceed the largest weighted one).
    let weighted = pairs.filter(|&(w, _)| w > 0.0);
    let largest = (weighted.clone()).fold(0.0f64, |m, (_, x)| m.max(x.abs()));
    if largest == 0.0 || weight <= 0.0 {
        return 0.0;
    }
    let sum: f64 = weighted.map(|(w, x)| w * (x.abs() / largest).powf(p)).sum();
    largest * (sum / weight).powf(1.0 / p)
}

/// The relative speed of the crank and the disc, rpm: n·(1 + 1/nc) for an input speed n
/// (`sliding::relative_crank_speed_ratio`).
pub fn relative_speed_rpm(input_rpm: f64, teeth: usize) -> f64 {
    input_rpm * relative_crank_speed_ratio(teeth)
}

/// L10h, hours, of a bearing of rating `rating_n` (C, N) and life exponent `exponent` (p)
/// under the equivalent load `load_n` (P, N) at the input speed `input_rpm` of a disc with
/// `teeth`: (C/P)^p·10⁶/(60·n·(1 + 1/nc)). An unloaded bearing (P = 0) never wears, and a
/// life beyond the largest double (P below C·1e-92 with p = 10/3: a load of round-off) has no
/// number: both are `UNBOUNDED_LIFE_H`, never ∞.
pub fn life_h(load_n: f64, rating_n: f64, exponent: f64, input_rpm: f64, teeth: usize) -> f64 {
    if load_n <= 0.0 {
        return UNBOUNDED_LIFE_H;
    }
    let revolutions = (rating_n / load_n).powf(exponent) * 1e6;
    bounded(revolutions / (60.0 * relative_speed_rpm(input_rpm, teeth)))
}

/// The rating life of the bearing `rating` under the equivalent load `load_n` (P, N): in hours
/// (`life_h`) at the input speed `input_rpm` of a disc with `teeth`, when it has one.
pub fn life(
    load_n: f64,
    rating: CrankBearing,
    input_rpm: Option<f64>,
    teeth: usize,
) -> BearingLife {
    let (c, p) = (rating.dynamic_load_rating_n, rating.life_exponent);
    BearingLife {
        equivalent_load_n: load_n,
        life_h: input_rpm.map(|n| life_h(load_n, c, p, n, teeth)),
    }
}

#[cfg(test)]
mod tests {
    use super::weighted_power_mean;

    /// Equal values give that value whatever the weights; zero weights leave a value out; the
    /// cube mean of (1, 2) with equal weights is (9/2)^(1/3); huge values do not overflow.
    #[test]
    fn the_weighted_power_mean_is_a_mean() {
        assert_eq!(
            weighted_power_mean([(0.3, 5.0), (0.7, 5.0)].into_iter(), 10.0 / 3.0),
            5.0
        );
        assert_eq!(
            weighted_power_mean([(0.0, 9.0), (2.0, 4.0)].into_iter(), 3.0),
            4.0
        );
        let m = weighted_power_mean([(1.0, 1.0), (1.0, 2.0)].into_iter(), 3.0);
        assert!((m - 4.5f64.cbrt()).abs() < 1e-15, "{m}");
        let big = weighted_power_mean([(1.0, 1e300), (1.0, 1e300)].into_iter(), 10.0);
        assert!((big / 1e300 - 1.0).abs() < 1e-15, "{big}");
        assert_eq!(weighted_power_mean([(1.0, 0.0)].into_iter(), 3.0), 0.0);
    }
}
