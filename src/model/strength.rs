//! What a part can bear (issue 41, `docs/effects/strength.md`): the yield strength that judges
//! the output pins' bending, the S–N law of rolling-contact fatigue that gives the disc's and the
//! rollers' lives, and what the `strength` effect computes from a scene's loads. Engine units:
//! MPa, N, hours.

/// Rolling-contact fatigue of one part's running surface: N(p) = cycles·(pressure/p)^exponent
/// stress cycles to failure under the Hertz peak pressure p (spec:
/// `reducer.material.contact_fatigue`, `reducer.roller_material.contact_fatigue`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFatigue {
    /// The reference pressure of the S–N law, MPa (spec: `pressure_mpa`).
    pub pressure_mpa: f64,
    /// The cycles to failure at the reference pressure (spec: `cycles`).
    pub cycles: f64,
    /// The pressure exponent (spec: `exponent`), in (0, 30].
    pub exponent: f64,
    /// A pressure at or below which a pass does no damage, MPa (spec:
    /// `endurance_pressure_mpa`); none: every pass does some.
    pub endurance_pressure_mpa: Option<f64>,
}

/// What one body's material can bear, beside its elasticity (`Material`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PartStrength {
    /// The yield strength, MPa (spec: `yield_strength_mpa`).
    pub yield_strength_mpa: Option<f64>,
    /// Its running surface's rolling-contact fatigue (spec: `contact_fatigue`).
    pub contact_fatigue: Option<ContactFatigue>,
}

/// The strength of the disc's and the rollers' materials (`reducer.material`,
/// `reducer.roller_material`; the rollers take the disc's when theirs is not given). The output
/// pins take the rollers', as for their modulus.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Strength {
    /// The disc's.
    pub disc: PartStrength,
    /// The rollers' and the output pins'.
    pub rollers: PartStrength,
}

/// The output pins' stresses over a scene's sweep (`equilibrium::pin_stress`): the reducer's,
/// every disc's pin force on the same pin summed as vectors.
#[derive(Debug, Clone, PartialEq)]
pub struct PinStress {
    /// σ_b = 32·M/(π·d³) at the pin's most loaded section, MPa, `[pin][angle]`.
    pub bending_stress_mpa: Vec<Vec<f64>>,
    /// τ = 4·V/(3·A), the peak transverse shear stress of the round section at the largest
    /// shear force along the pin, MPa, `[pin][angle]`.
    pub shear_stress_mpa: Vec<Vec<f64>>,
    /// The pins' yield strength, MPa, when given: the safety is yield/σ_b.
    pub yield_strength_mpa: Option<f64>,
}

/// The rolling-contact fatigue lives of one disc and the rollers' track on it over a scene
/// (`contact::fatigue`), each at the largest Hertz pressure of the scene, hours at its speed;
/// `results::UNBOUNDED_LIFE_H` when a part takes no damage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FatigueLives {
    /// The largest Hertz pressure of the scene's whole periods, MPa.
    pub pressure_mpa: f64,
    /// The disc's life, h, when its S–N law is given.
    pub disc_h: Option<f64>,
    /// The rollers' life on this disc's track, h, when their S–N law is given.
    pub rollers_h: Option<f64>,
}

impl FatigueLives {
    /// The shorter of the two lives, h, and the part it is ("disc", "rollers").
    pub fn shorter(&self) -> Option<(f64, &'static str)> {
        let parts = [(self.disc_h, "disc"), (self.rollers_h, "rollers")];
        parts
            .into_iter()
            .filter_map(|(h, part)| Some((h?, part)))
            .reduce(|a, b| if b.0 < a.0 { b } else { a })
    }
}

/// The static safety of a disc's crank bearing (ISO 76): s0 = C0 / the largest bearing force.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticSafety {
    /// The largest bearing force of the scene, N.
    pub largest_force_n: f64,
    /// s0; `results::UNBOUNDED_LIFE_H` (the largest double) when the bearing carries nothing.
    pub safety: f64,
}

/// What the `strength` effect computes on one disc: its contact fatigue and its crank
/// bearing's static safety (the pins' stress is the reducer's, `PinStress`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DiscStrength {
    /// With a speed, an S–N law and whole periods.
    pub fatigue: Option<FatigueLives>,
    /// With `crank_bearing.static_load_rating_n`.
    pub static_safety: Option<StaticSafety>,
}

/// One disc's and its rollers' contact fatigue under a duty cycle (`engine::duty_fatigue`,
/// Palmgren–Miner over the bins, the drive and the coast flanks apart).
#[derive(Debug, Clone, PartialEq)]
pub struct DutyFatigue {
    /// The disc's life under the cycle, h, when its S–N law is given.
    pub disc_h: Option<f64>,
    /// The rollers' life on this disc's track under the cycle, h, with their law.
    pub rollers_h: Option<f64>,
    /// Each bin's share of the disc's damage on the flank it loads, `[bin]` (each flank's
    /// shares sum to 1, a flank without damage's are 0); empty without the disc's law.
    pub disc_shares: Vec<f64>,
    /// The same for the rollers.
    pub rollers_shares: Vec<f64>,
}
