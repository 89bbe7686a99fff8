//! Rating life of the crank bearing (ISO 281, MODEL.md "Several discs, torsion, bearing life").
//!
//! A bearing under a load that varies over the load cycle is rated for the constant load P
//! that wears it alike: P = (mean of F^p over the cycle)^(1/p), p the life exponent (10/3 for
//! roller bearings, 3 for ball bearings). Its basic rating life is L10 = (C/P)^p millions of
//! revolutions, C the basic dynamic load rating. The crank bearing turns with the crank
//! relative to the disc, which itself turns backwards at n/nc: the relative speed is
//! n·(1 + 1/nc), so L10h = (C/P)^p · 10⁶ / (60 · n · (1 + 1/nc)) hours.

use crate::model::results::UNBOUNDED_LIFE_H;

/// P = (mean of F^p)^(1/p), N, over bearing forces `force_n` (N) sampled evenly over whole
/// load cycles (the rectangle rule is then the mean of the periodic load). 0 without samples.
pub fn equivalent_load(force_n: &[f64], exponent: f64) -> f64 {
    // Scaled by the largest force so that F^p cannot overflow for any p (no samples: 0).
    let largest = force_n.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    if largest == 0.0 {
        return 0.0;
    }
    let mean = force_n
        .iter()
        .map(|f| (f.abs() / largest).powf(exponent))
        .sum::<f64>()
        / force_n.len() as f64;
    largest * mean.powf(1.0 / exponent)
}

/// The relative speed of the crank and the disc, rpm: n·(1 + 1/nc) for an input speed n.
pub fn relative_speed_rpm(input_rpm: f64, teeth: usize) -> f64 {
    input_rpm * (1.0 + 1.0 / teeth as f64)
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
    let hours = revolutions / (60.0 * relative_speed_rpm(input_rpm, teeth));
    if hours.is_finite() {
        hours
    } else {
        UNBOUNDED_LIFE_H
    }
}
