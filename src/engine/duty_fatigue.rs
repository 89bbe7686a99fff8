//! Contact fatigue under a duty cycle (issue 41, `docs/effects/strength.md`): Palmgren–Miner
//! over the bins. Bin i turns sᵢ·nᵢ·60 crank revolutions per hour of the cycle; a point of a
//! part's running surface is loaded c times per revolution (`contact::fatigue`: np/nc on the
//! disc, 1 on a roller) at the bin's largest Hertz pressure pᵢ, so the bin uses up
//! dᵢ = sᵢ·nᵢ·60·c / N(pᵢ) of the part's life per hour. A positive torque loads the drive flank
//! of each lobe and one side of each roller, a negative one the coast flank and the other side:
//! the two flanks wear apart, D_drive = Σ_{Tᵢ ≥ 0} dᵢ, D_coast = Σ_{Tᵢ < 0} dᵢ, and the part
//! lasts 1/max(D_drive, D_coast) hours. A standstill (nᵢ = 0) turns no revolution and adds none.

use crate::contact::fatigue;
use crate::model::results::{bounded, DiscResult, DutyBinResult, SceneResult};
use crate::model::strength::{ContactFatigue, DutyFatigue};
use crate::model::Design;

/// Each disc's fatigue under the cycle of `bins` (one entry per disc), when some S–N law is
/// given and every bin's run has its largest pressure over whole periods; else empty.
pub fn lives(design: &Design, bins: &[DutyBinResult]) -> Vec<DutyFatigue> {
    let s = &design.strength;
    if s.disc.contact_fatigue.is_none() && s.rollers.contact_fatigue.is_none() {
        return Vec::new();
    }
    // A standstill turns no revolution: its pressure wears nothing (its run has no speed, so
    // no fatigue figures of its own).
    let pressures: Option<Vec<Vec<f64>>> = bins
        .iter()
        .map(|b| match b.bin.input_speed_rpm > 0.0 {
            true => bin_pressures(&b.result),
            false => Some(vec![0.0; design.discs]),
        })
        .collect();
    let Some(pressures) = pressures else {
        return Vec::new();
    };
    let part = |law: Option<ContactFatigue>, passes: f64, k: usize| {
        law.map(|law| {
            let rates: Vec<(f64, bool)> = bins
                .iter()
                .zip(&pressures)
                .map(|(b, p)| {
                    let turns_per_h = b.bin.revolution_weight_rpm() * 60.0;
                    // A bin that turns nothing wears nothing, whatever N (0·c/N, which is NaN
                    // where N underflows to 0).
                    let rate = match turns_per_h > 0.0 {
                        true => turns_per_h * passes / fatigue::cycles_to_failure(&law, p[k]),
                        false => 0.0,
                    };
                    (rate, b.bin.output_torque_nmm < 0.0)
                })
                .collect();
            miner(&rates)
        })
    };
    (0..design.discs)
        .map(|k| {
            let disc_passes = fatigue::disc_passes_per_crank_turn(design.teeth);
            let disc = part(s.disc.contact_fatigue, disc_passes, k);
            let roller_passes = fatigue::ROLLER_PASSES_PER_CRANK_TURN;
            let rollers = part(s.rollers.contact_fatigue, roller_passes, k);
            DutyFatigue {
                disc_h: disc.as_ref().map(|d| d.0),
                rollers_h: rollers.as_ref().map(|r| r.0),
                disc_shares: disc.map(|d| d.1).unwrap_or_default(),
                rollers_shares: rollers.map(|r| r.1).unwrap_or_default(),
            }
        })
        .collect()
}

/// The largest Hertz pressure of each disc in one bin's run, MPa, as its strength found it
/// (over whole periods); `None` when the run has none.
fn bin_pressures(r: &SceneResult) -> Option<Vec<f64>> {
    let of = |d: &DiscResult| Some(d.loaded.strength?.fatigue?.pressure_mpa);
    r.discs.iter().map(of).collect()
}

/// Miner's sum of the damage rates `(per hour, on the coast flank)`: the life 1/max(D_drive,
/// D_coast), h (`UNBOUNDED_LIFE_H` without damage), and each bin's share of its flank's damage.
/// A rate is infinite where N(p) underflows to 0: the life is then 0 h and the flank's damage
/// is shared equally by its infinite rates (never inf/inf).
pub fn miner(rates: &[(f64, bool)]) -> (f64, Vec<f64>) {
    let flank = |coast: bool| -> f64 { rates.iter().filter(|r| r.1 == coast).map(|r| r.0).sum() };
    let infinite = |coast: bool| {
        let on = rates.iter().filter(|r| r.1 == coast && r.0.is_infinite());
        on.count() as f64
    };
    let (drive, coast) = (flank(false), flank(true));
    let life = bounded(1.0 / drive.max(coast));
    let shares = rates
        .iter()
        .map(|&(d, c)| {
            let total = if c { coast } else { drive };
            if total.is_infinite() {
                if d.is_infinite() {
                    1.0 / infinite(c)
                } else {
                    0.0
                }
            } else if total > 0.0 {
                d / total
            } else {
                0.0
            }
        })
        .collect();
    (life, shares)
}
