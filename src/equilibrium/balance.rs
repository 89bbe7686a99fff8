//! The moment balance of a set of contacts about the disc centre, shared by the rollers (lag
//! β) and the output pins (output lag βo): the moment, its slope and scale, and the mix of two
//! neighbouring states that a balance stepping over its target by round-off settles on.

use super::solve::{piecewise_linear_root_near, settle_straddle, SolveFailure, Weights};

/// One contact of the disc in a moment balance about the disc centre, as a function of its lag
/// x (β for a roller, βo for a pin).
pub trait Contact {
    fn force_n(&self) -> f64;
    /// dF/d(approach), N/mm.
    fn stiffness_n_per_mm(&self) -> f64;
    /// Moment arm about the disc centre, mm: the contact's moment is F·arm.
    fn arm_mm(&self) -> f64;
    /// Gap, mm (negative: the contact is pressed).
    fn gap_mm(&self) -> f64;
    /// ∂gap/∂x, mm/rad (−arm for a roller: ∂gap/∂β = −l).
    fn gap_slope_mm(&self) -> f64;
    /// Force, stiffness and gap become w.x·self + w.y·other.
    fn mix(&mut self, other: &Self, w: Weights);
    /// No force and no stiffness: the contact just touches, or is open.
    fn unload(&mut self);
}

/// `Contact` for a contact state with the fields `force_n`, `stiffness_n_per_mm`, `arm_mm` and
/// `gap_mm`, given ∂gap/∂x as an expression of the state.
macro_rules! impl_contact {
    ($state:ty, |$s:ident| $gap_slope:expr) => {
        impl $crate::equilibrium::balance::Contact for $state {
            fn force_n(&self) -> f64 {
                self.force_n
            }
            fn stiffness_n_per_mm(&self) -> f64 {
                self.stiffness_n_per_mm
            }
            fn arm_mm(&self) -> f64 {
                self.arm_mm
            }
            fn gap_mm(&self) -> f64 {
                self.gap_mm
            }
            fn gap_slope_mm(&self) -> f64 {
                let $s = self;
                $gap_slope
            }
            fn mix(&mut self, other: &Self, w: $crate::equilibrium::solve::Weights) {
                use $crate::equilibrium::balance::mix;
                self.force_n = mix(self.force_n, other.force_n, w);
                self.stiffness_n_per_mm = mix(self.stiffness_n_per_mm, other.stiffness_n_per_mm, w);
                self.gap_mm = mix(self.gap_mm, other.gap_mm, w);
            }
            fn unload(&mut self) {
                (self.force_n, self.stiffness_n_per_mm) = (0.0, 0.0);
            }
        }
    };
}
pub(crate) use impl_contact;

/// Σ F·a (N·mm), its slope ∂/∂x = Σ k·a·(−∂gap/∂x) (geometry held fixed), and its scale Σ |F·a|
/// (for relative residuals).
pub fn moment<C: Contact>(states: &[C]) -> (f64, f64, f64) {
    moment_by(states, C::arm_mm)
}

/// `moment` with each contact's arm given by `arm` (a friction model's corrected arm).
pub fn moment_by<C: Contact>(states: &[C], arm: impl Fn(&C) -> f64) -> (f64, f64, f64) {
    states.iter().fold((0.0, 0.0, 0.0), |(m, dm, scale), s| {
        let (f, a) = (s.force_n(), arm(s));
        (
            m + f * a,
            dm - s.stiffness_n_per_mm() * a * s.gap_slope_mm(),
            scale + (f * a).abs(),
        )
    })
}

/// Whether the contacts' moments are round-off: their scale Σ |F·a| within `resolution` (N·mm,
/// the balance's `moment_resolution`).
pub fn round_off<C: Contact>(states: &[C], resolution: f64) -> bool {
    moment(states).2 <= resolution
}

/// Forces whose moments are round-off are zero at zero torque, the limit T → 0⁺ of no load:
/// every contact unloaded when `round_off`. (An unmodified profile touches every roller at
/// zero torque with gaps of ±1e-17 mm; pins without clearance touch their holes; a disc
/// floating in its backlash keeps forces of 1e-24 N, whose unbalanced moment made its residual
/// 1.)
pub fn unload_round_off<C: Contact>(states: &mut [C], resolution: f64) {
    if round_off(states, resolution) {
        states.iter_mut().for_each(C::unload);
    }
}

/// Mix two evaluations of the contacts at neighbouring lags, `states` ← w.x·`states` +
/// w.y·`other` in force, stiffness and gap (`solve::settle_straddle`); the geometry stays that
/// of `states` (one ulp of lag apart, it is the same to round-off).
pub fn blend<C: Contact>(states: &mut [C], other: &[C], w: Weights) {
    for (s, o) in states.iter_mut().zip(other) {
        s.mix(o, w);
    }
}

/// The balance Σ F·a = `torque` of linear contacts in closed form (first-order geometry,
/// linear law), shared by the rollers (β) and the pins (βo): the exact root of the
/// piecewise-linear balance of `terms` (gap, arm) with stiffness `k`, the states evaluated
/// there by `evaluate(lag, states)`, and, when the gaps' round-off at that double leaves the balance off by
/// more than `rel_tol`, the states of two neighbouring lags mixed so that it holds
/// (`settle_straddle`). Returns the lag and the moment scale Σ |F·a| of the states.
pub fn closed_form<C: Contact + Clone>(
    (k, terms, torque, rel_tol): (f64, &[(f64, f64)], f64, f64),
    guess: f64,
    events: &mut Vec<(f64, f64, f64)>,
    states: &mut Vec<C>,
    mut evaluate: impl FnMut(f64, &mut Vec<C>),
) -> Result<(f64, f64), SolveFailure> {
    let lag = piecewise_linear_root_near(k, terms, torque, guess, events).ok_or(
        SolveFailure::NoBracket {
            lo: f64::NEG_INFINITY,
            hi: f64::INFINITY,
            nearest: None,
        },
    )?;
    evaluate(lag, states);
    let (m, _, scale) = moment(states);
    if torque == 0.0 || (m - torque).abs() <= rel_tol * torque.abs().max(scale) {
        return Ok((lag, scale));
    }
    let settled = settle(lag, lag, torque, states, |y, other| {
        evaluate(y, other);
        Ok(())
    })?;
    Ok((settled, scale))
}

/// Settle a root the iterative solve straddles (`Root::straddle`): `states` hold the contacts
/// at `lag`; `evaluate(y, states)` evaluates them at y. Mixes them with those of the
/// neighbouring lag so that Σ F·a = `torque`; returns the lag nearer the mix.
pub fn settle<C: Contact + Clone>(
    lag: f64,
    towards: f64,
    torque: f64,
    states: &mut [C],
    mut evaluate: impl FnMut(f64, &mut Vec<C>) -> Result<(), SolveFailure>,
) -> Result<f64, SolveFailure> {
    let mut other = states.to_vec();
    let (at, weight) = settle_straddle(lag, towards, moment(states).0, torque, |y| {
        evaluate(y, &mut other)?;
        Ok(moment(&other).0)
    })?;
    blend(states, &other, weight);
    Ok(if weight.y > 0.5 { at } else { lag })
}

/// w.x·a + w.y·b, with both weights given (not one as 1 − the other): at 1e-100 N·m a
/// straddle's weight is ~1e-88, and a + w·(b − a), or b + (1 − w)·(a − b) with 1 − w = 1
/// exactly, would lose the whole load.
#[inline]
pub fn mix(a: f64, b: f64, w: Weights) -> f64 {
    w.x * a + w.y * b
}

#[cfg(test)]
mod tests {
    use super::mix;
    use crate::equilibrium::solve::settle_straddle;

    /// A straddle between an unloaded state (moment 0) and one ulp of contact (6.65e-10 N·mm)
    /// at a target of 1e-97 N·mm: whichever side the solver stopped on, the mix carries the
    /// target's load, 1e-97/6.65e-10 of the contact state's, not zero.
    #[test]
    fn a_tiny_weight_survives_the_mix() {
        let (loaded, target) = (6.65e-10, 1e-97);
        // The bracket of the touching lag, one ulp wide.
        let (lo, hi) = (3.6498611814574328e-3_f64, 3.6498611814574336e-3_f64);
        let from_loaded = settle_straddle(hi, lo, loaded, target, |_| Ok(0.0))
            .unwrap()
            .1;
        let from_unloaded = settle_straddle(lo, hi, 0.0, target, |_| Ok(loaded))
            .unwrap()
            .1;
        let expected = target / loaded;
        let mixed = mix(loaded, 0.0, from_loaded);
        assert!((mixed - target).abs() <= 1e-15 * target, "{mixed:e}");
        assert!((from_loaded.x - expected).abs() <= 1e-15 * expected);
        assert!((mix(0.0, loaded, from_unloaded) - target).abs() <= 1e-15 * target);
    }
}
