//! `scenes[].duty_cycle` (issue 31): the bins of torque, speed and time share a scene runs in
//! place of its own torque and speed. Every rule is checked at its key before anything runs:
//! a bin's torque finite, its speed finite and ≥ 0 (0 a standstill), its share in [0, 1],
//! the shares summing to 1 within 1e-9, some bin turning the crank, no cycle together with the
//! scene's own `output_torque_nm`, `input_speed_rpm` or `torque_sweep` (a value the cycle
//! would otherwise ignore), and a scene that computes the crank-bearing force (what the cycle
//! rates).

use super::raw::{RawDutyBin, RawScene};
use super::values::finite;
use crate::error::{Error, Result};
use crate::model::{DutyBin, Effect, Plan};
use crate::{numeric, units};

/// How far from 1 the time shares of a cycle may sum: their round-off as decimals (ten
/// shares of 0.1 sum to 0.9999999999999999), far below any share a person writes.
pub const SHARE_SUM_TOLERANCE: f64 = 1e-9;

/// The duty cycle of the raw scene at `key` (`scenes[i]`) asking for `effects`, validated;
/// `None` without one.
pub(super) fn duty_cycle(
    key: &str,
    raw: &RawScene,
    effects: &[Effect],
) -> Result<Option<Vec<DutyBin>>> {
    let Some(bins) = &raw.duty_cycle else {
        return Ok(None);
    };
    let at = format!("{key}.duty_cycle");
    for (own, given) in [
        ("output_torque_nm", raw.output_torque_nm.is_some()),
        ("input_speed_rpm", raw.input_speed_rpm.is_some()),
        ("torque_sweep", raw.torque_sweep.is_some()),
    ] {
        if given {
            return Err(Error::invalid(
                format!("{key}.{own}"),
                format!(
                    "a scene with `duty_cycle` runs each bin at the bin's own torque and \
                     speed, in place of the scene's: give either `duty_cycle` or `{own}`, not \
                     both"
                ),
            ));
        }
    }
    let bearing = Plan::of(&raw.name, effects).has(Effect::Bearing);
    if bins.is_empty() {
        return Err(empty(&at));
    }
    if !bearing {
        return Err(Error::invalid(
            format!("{key}.effects"),
            "a duty cycle rates the crank bearing under its bins' loads: the scene must \
             compute the bearing force (add the effect `bearing`)"
                .into(),
        ));
    }
    bins_at(&at, bins).map(Some)
}

fn empty(at: &str) -> Error {
    Error::invalid(
        at,
        "a duty cycle needs at least one bin `{output_torque_nm, input_speed_rpm, \
         time_share}`"
            .into(),
    )
}

/// The bins of a duty cycle at `at` (`scenes[i].duty_cycle`, or a requirements file's
/// `duty_cycle`), validated by the rules of the module's doc: at least one bin, each torque
/// finite, each speed finite and ≥ 0, each share in [0, 1], the shares summing to 1 within
/// [`SHARE_SUM_TOLERANCE`], some bin turning.
pub(crate) fn bins_at(at: &str, bins: &[RawDutyBin]) -> Result<Vec<DutyBin>> {
    if bins.is_empty() {
        return Err(empty(at));
    }
    let mut cycle = Vec::with_capacity(bins.len());
    for (j, b) in bins.iter().enumerate() {
        let bin = format!("{at}[{j}]");
        let torque = finite(&format!("{bin}.output_torque_nm"), b.output_torque_nm)?;
        let speed = b.input_speed_rpm;
        if !(speed.is_finite() && speed >= 0.0) {
            return Err(Error::invalid(
                format!("{bin}.input_speed_rpm"),
                format!(
                    "must be a finite speed of at least 0 rpm (0: a standstill), got {}",
                    numeric::input(speed)
                ),
            ));
        }
        let speed = super::values::speed_rpm(&format!("{bin}.input_speed_rpm"), speed)?;
        let share = b.time_share;
        if !(share.is_finite() && (0.0..=1.0).contains(&share)) {
            return Err(Error::invalid(
                format!("{bin}.time_share"),
                format!(
                    "must be a share of the time in [0, 1], got {}",
                    numeric::input(share)
                ),
            ));
        }
        cycle.push(DutyBin {
            output_torque_nmm: units::nmm(torque),
            input_speed_rpm: speed,
            time_share: share,
        });
    }
    let sum: f64 = cycle.iter().map(|b| b.time_share).sum();
    if (sum - 1.0).abs() > SHARE_SUM_TOLERANCE {
        return Err(Error::invalid(
            at,
            format!(
                "the time shares sum to {}, not 1 (within {SHARE_SUM_TOLERANCE:e})",
                numeric::input(sum)
            ),
        ));
    }
    if cycle.iter().all(|b| b.revolution_weight_rpm() == 0.0) {
        return Err(Error::invalid(
            at,
            "no bin turns the crank (every bin with a share has speed 0): a cycle at a \
             standstill has no revolutions to rate a life or weight a torque by"
                .into(),
        ));
    }
    Ok(cycle)
}
