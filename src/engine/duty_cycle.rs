//! A duty cycle (issue 31): a scene's bins of output torque Tᵢ, input speed nᵢ and time share
//! sᵢ (Σ sᵢ = 1), each run as the scene loaded at its torque and speed over the scene's crank
//! range (`engine::scene` runs them), combined here.
//!
//! - Crank-bearing life (ISO 281 with the Palmgren–Miner rule; MODEL.md "Several discs,
//!   torsion, bearing life"): bin i wears the bearing of disc k with its own equivalent load
//!   P_ik = (mean of Fb^p over its loaded period)^(1/p) at its revolutions, which are in
//!   proportion to sᵢ·nᵢ. Miner's sum of damage fractions gives the constant load that wears
//!   alike, P_k = (Σ sᵢ·nᵢ·P_ik^p / Σ sᵢ·nᵢ)^(1/p), and L10 = (C/P_k)^p·10⁶ revolutions of the
//!   crank relative to the disc, turned at Σ sᵢ·nᵢ·(1 + 1/nc) on the time mean:
//!   L10h = L10 / (60·Σ sᵢ·nᵢ·(1 + 1/nc)) hours. A bin at a standstill (nᵢ = 0) turns no
//!   revolution and adds no damage, whatever its load. Each disc has its own bearing; the
//!   reducer's life is the shortest disc's (as `bearing_life_h` with several discs).
//! - Equivalent output torque: T_eq = (Σ sᵢ·nᵢ·|Tᵢ|³ / Σ sᵢ·nᵢ)^(1/3), the root-mean-cube
//!   weighted by the revolutions each bin turns: the "average load torque" of the makers'
//!   selection procedures (Harmonic Drive's catalogues, cube law; Nabtesco's RV catalogue
//!   writes the same mean with the exponent 10/3 of its bearings).
//! - Mean speed n_m = Σ sᵢ·nᵢ, rpm (the time mean of the input speed).
//! - Mean efficiency weighted by energy, with `efficiency`: η = Σ sᵢ·Dᵢ / Σ sᵢ·Eᵢ, each bin's
//!   energy delivered Dᵢ and entering Eᵢ from its power flow at its mean loss
//!   (`model::power_flow`, Pᵢ = |Tᵢ|·ωᵢ/nc, lossᵢ its losses per unit speed × ωᵢ, ωᵢ ∝ nᵢ):
//!   the input driving, Eᵢ = Pᵢ + lossᵢ and Dᵢ = Pᵢ; the output driving (Tᵢ < 0), Eᵢ = Pᵢ and
//!   Dᵢ = Pᵢ − lossᵢ; self-locked, Eᵢ = lossᵢ and Dᵢ = 0. The energy delivered over the energy
//!   entering in one cycle. A bin at a standstill moves no power: it has no efficiency (its run
//!   keeps none, `combine`) and adds nothing. With no energy moved at all it is 1.

use crate::engine::bearing_life::{self, weighted_power_mean};
use crate::model::results::{DutyBinResult, DutyCycle, SceneResult};
use crate::model::Design;

/// Each bin's revolution weight sᵢ·nᵢ (rpm), in the bins' order.
fn revolution_weights(bins: &[DutyBinResult]) -> Vec<f64> {
    bins.iter().map(|b| b.bin.revolution_weight_rpm()).collect()
}

/// The crank-bearing equivalent load of each disc in one bin's run, N (one entry per disc);
/// `None` when the bin's run did not rate it (no `crank_bearing`, or not whole loaded periods).
pub fn bin_equivalent_loads(r: &SceneResult) -> Option<Vec<f64>> {
    r.discs
        .iter()
        .map(|d| d.bearing_life.map(|b| b.equivalent_load_n))
        .collect()
}

/// The cycle's results from its bins' runs: the lives of `design`'s discs, the equivalent
/// torque, the mean speed and the energy-weighted efficiency (see the module's formulas).
pub fn combine(design: &Design, bins: Vec<DutyBinResult>) -> DutyCycle {
    let bins: Vec<DutyBinResult> = bins
        .into_iter()
        .map(standstill_without_efficiency)
        .collect();
    let weights = revolution_weights(&bins);
    let mean_speed_rpm: f64 = weights.iter().sum();
    let torques = (weights.iter().zip(&bins)).map(|(&w, b)| (w, b.bin.output_torque_nmm));
    let equivalent_torque_nmm = weighted_power_mean(torques, 3.0);
    let loads: Option<Vec<Vec<f64>>> = bins
        .iter()
        .map(|b| bin_equivalent_loads(&b.result))
        .collect();
    let life = match (design.crank_bearing, loads) {
        (Some(rating), Some(loads)) => (0..design.discs)
            .map(|k| {
                let pairs = weights.iter().zip(&loads).map(|(&w, l)| (w, l[k]));
                let load = weighted_power_mean(pairs, rating.life_exponent);
                bearing_life::life(load, rating, Some(mean_speed_rpm), design.teeth)
            })
            .collect(),
        _ => Vec::new(),
    };
    DutyCycle {
        contact_fatigue: crate::engine::duty_fatigue::lives(design, &bins),
        mean_efficiency: energy_efficiency(&bins),
        bins,
        equivalent_torque_nmm,
        mean_speed_rpm,
        life,
    }
}

/// Each bin's share of each disc's crank-bearing damage under the cycle, `[disc][bin]`, each
/// disc's summing to 1: by Miner's rule bin i uses up the bearing of disc k in proportion to
/// its revolutions and its load's damage per revolution, sᵢ·nᵢ·P_ik^p (p the bearing's life
/// exponent; a standstill none). `None` when the bearing is not rated or no bin wears it.
pub fn damage_shares(design: &Design, bins: &[DutyBinResult]) -> Option<Vec<Vec<f64>>> {
    let p = design.crank_bearing?.life_exponent;
    let loads: Vec<Vec<f64>> = bins
        .iter()
        .map(|b| bin_equivalent_loads(&b.result))
        .collect::<Option<_>>()?;
    let weights = revolution_weights(bins);
    (0..design.discs)
        .map(|k| {
            // Loads scaled by the largest so that P^p cannot overflow.
            let largest = loads.iter().fold(0.0f64, |m, l| m.max(l[k]));
            let damage: Vec<f64> = (weights.iter().zip(&loads))
                .map(|(&w, l)| w * (l[k] / largest).powf(p))
                .collect();
            let total: f64 = damage.iter().sum();
            (total > 0.0).then(|| damage.iter().map(|d| d / total).collect())
        })
        .collect()
}

/// A bin at a standstill moves no power, so it has no efficiency: its run's efficiency (computed
/// as a scene without a speed would be, where η does not depend on the speed) is dropped, with
/// each disc's.
fn standstill_without_efficiency(mut b: DutyBinResult) -> DutyBinResult {
    if b.bin.input_speed_rpm == 0.0 {
        b.result.reducer.efficiency = None;
        for d in &mut b.result.discs {
            d.efficiency = None;
        }
    }
    b
}

/// Σ sᵢ·nᵢ·Dᵢ / Σ sᵢ·nᵢ·Eᵢ, each bin's energy delivered and entering per unit speed from its
/// power flow at its mean loss (`model::power_flow`, `EfficiencyCurves::mean_loss_nmm`) times
/// nᵢ (∝ ωᵢ); `None` unless every turning bin computed the efficiency; 1 when no energy moves.
fn energy_efficiency(bins: &[DutyBinResult]) -> Option<f64> {
    let (mut delivered, mut entering) = (0.0, 0.0);
    for b in bins.iter().filter(|b| b.bin.input_speed_rpm > 0.0) {
        let e = b.result.reducer.efficiency.as_ref()?;
        let energy = e.reducer.as_ref()?.flow.energy(e.mean_loss_nmm.total());
        let w = b.bin.revolution_weight_rpm();
        delivered += w * energy.delivered_nmm;
        entering += w * energy.entering_nmm;
    }
    Some(if entering > 0.0 {
        delivered / entering
    } else {
        1.0
    })
}
