//! Rolling-contact fatigue of the disc and the rollers (issue 41, `docs/effects/strength.md`).
//!
//! A point of a running surface takes one stress cycle each time a loaded contact rolls over
//! it. Its S–N law is N(p) = N_ref·(p_ref/p)^k cycles to failure at the Hertz peak pressure p
//! (Basquin's form; for line contacts Lundberg–Palmgren give the life ∝ Q^(−4) in the load,
//! and p ∝ Q^½, so k = 8 in the pressure; ISO 6336-2's pitting curves use k = 13.2 for
//! through-hardened and case-hardened steels to 5·10⁷ cycles). Below an endurance pressure, when
//! given, a pass does no damage.
//!
//! Passes per crank turn. The load acts on the disc around the crank's eccentric direction,
//! which turns once per crank turn in the housing. The disc turns at −1/nc of the crank in the
//! housing, so the load turns 1 + 1/nc = np/nc times per crank turn relative to the disc:
//! each lobe of the disc is loaded np/nc times per crank turn. The rollers are fixed in the
//! housing (they spin on their axes, not round it): the load passes each once per crank turn,
//! on each disc's track.

use crate::model::results::bounded;
use crate::model::strength::ContactFatigue;

/// Passes of the load over each lobe of a disc of `teeth` (nc) per crank turn: np/nc.
pub fn disc_passes_per_crank_turn(teeth: usize) -> f64 {
    (teeth + 1) as f64 / teeth as f64
}

/// Passes of the load over each roller, on each disc's track, per crank turn.
pub const ROLLER_PASSES_PER_CRANK_TURN: f64 = 1.0;

/// N(p) = cycles·(pressure_mpa/p)^exponent, the cycles to failure under the Hertz pressure
/// `pressure_mpa` (p, MPa); infinite at p = 0 or at or below the endurance pressure.
pub fn cycles_to_failure(law: &ContactFatigue, pressure_mpa: f64) -> f64 {
    let endured = law
        .endurance_pressure_mpa
        .is_some_and(|e| pressure_mpa <= e);
    if pressure_mpa <= 0.0 || endured {
        return f64::INFINITY;
    }
    law.cycles * (law.pressure_mpa / pressure_mpa).powf(law.exponent)
}

/// The life in hours of a surface whose points are loaded `passes_per_turn` times per crank
/// turn at `pressure_mpa`, at the input speed `input_rpm`: N(p)/(passes·n·60).
/// `UNBOUNDED_LIFE_H` when it takes no damage or its life is beyond the largest double.
pub fn life_h(
    law: &ContactFatigue,
    pressure_mpa: f64,
    passes_per_turn: f64,
    input_rpm: f64,
) -> f64 {
    bounded(cycles_to_failure(law, pressure_mpa) / (passes_per_turn * input_rpm * 60.0))
}
