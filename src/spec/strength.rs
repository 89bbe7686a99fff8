//! The `strength` effect's inputs and the rules of its limits (issue 41,
//! `docs/effects/strength.md`): the materials' yield strength and S–N law of rolling-contact
//! fatigue, and what each limit needs — a pin support for the pins' stresses, a yield strength
//! for their safety, an S–N law and a speed for a fatigue life, C0 for a static safety.

use super::raw::{RawContactFatigue, RawMaterial};
use super::values::positive;
use crate::error::{Error, Result};
use crate::model::strength::{ContactFatigue, PartStrength, Strength};
use crate::model::{CrankBearing, Design, Effect, Limits, Plan, Scene};
use crate::numeric;

/// The largest pressure exponent of an S–N law: published rolling-contact laws lie between
/// 3 (ball bearings' load exponent) and ~20 (ISO 6336-2's 13.2 for pitting of hardened steels);
/// beyond 30 a 1 % error in the pressure is a 35 % error in the life.
pub(crate) const MAX_EXPONENT: f64 = 30.0;

/// The disc's (`material`) and the rollers' (`roller_material`, the disc's when not given)
/// strength, their keys under `prefix` (`reducer.` in a spec, none in a requirements file).
pub(crate) fn materials_at(
    prefix: &str,
    disc: &RawMaterial,
    rollers: Option<&RawMaterial>,
) -> Result<Strength> {
    let disc_strength = part(&format!("{prefix}material"), disc)?;
    let rollers = match rollers {
        Some(r) => part(&format!("{prefix}roller_material"), r)?,
        None => disc_strength,
    };
    Ok(Strength {
        disc: disc_strength,
        rollers,
    })
}

/// One material's yield strength (positive) and S–N law.
fn part(key: &str, raw: &RawMaterial) -> Result<PartStrength> {
    Ok(PartStrength {
        yield_strength_mpa: raw
            .yield_strength_mpa
            .map(|y| positive(&format!("{key}.yield_strength_mpa"), y))
            .transpose()?,
        contact_fatigue: raw
            .contact_fatigue
            .map(|f| contact_fatigue(&format!("{key}.contact_fatigue"), &f))
            .transpose()?,
    })
}

/// An S–N law: a positive reference pressure, cycles and endurance pressure, an exponent in
/// (0, `MAX_EXPONENT`].
fn contact_fatigue(key: &str, raw: &RawContactFatigue) -> Result<ContactFatigue> {
    let exponent = raw.exponent;
    if !(exponent.is_finite() && exponent > 0.0 && exponent <= MAX_EXPONENT) {
        return Err(Error::invalid(
            format!("{key}.exponent"),
            format!(
                "must be in (0, {MAX_EXPONENT}], got {}: N(p) = cycles·(pressure_mpa/p)^exponent \
                 falls as the pressure rises only for a positive exponent, and published \
                 rolling-contact laws stay below {MAX_EXPONENT} (8 for line contact by \
                 Lundberg–Palmgren, 13.2 in ISO 6336-2)",
                numeric::input(exponent)
            ),
        ));
    }
    Ok(ContactFatigue {
        pressure_mpa: positive(&format!("{key}.pressure_mpa"), raw.pressure_mpa)?,
        cycles: positive(&format!("{key}.cycles"), raw.cycles)?,
        exponent,
        endurance_pressure_mpa: raw
            .endurance_pressure_mpa
            .map(|p| positive(&format!("{key}.endurance_pressure_mpa"), p))
            .transpose()?,
    })
}

/// What the strength limits may need, as given: a pin support, the pins' yield strength, an
/// S–N law of the disc or the rollers, C0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Inputs {
    pub support: bool,
    pub pins_yield: bool,
    pub fatigue_law: bool,
    pub static_rating: bool,
}

impl Inputs {
    /// What the materials' `strength`, a pin `support` (given or not) and the crank `bearing`
    /// give: a spec's design or a requirements file's blocks.
    pub(crate) fn new(
        strength: &Strength,
        support: bool,
        bearing: Option<&CrankBearing>,
    ) -> Inputs {
        Inputs {
            support,
            pins_yield: strength.rollers.yield_strength_mpa.is_some(),
            fatigue_law: strength.disc.contact_fatigue.is_some()
                || strength.rollers.contact_fatigue.is_some(),
            static_rating: bearing.and_then(|b| b.static_load_rating_n).is_some(),
        }
    }
}

/// Why the limit `key` cannot be judged with `inputs`, the keys named under `prefix`
/// (`reducer.` in a spec, none in a requirements file); none when it can (or is no strength
/// limit).
pub(crate) fn missing_input(key: &str, inputs: &Inputs, prefix: &str) -> Option<String> {
    let why = match key {
        "max_pin_bending_stress_mpa" | "min_pin_bending_safety" if !inputs.support => format!(
            "the pins' bending needs how they are held: give \
             `{prefix}output_pins.support: {{kind, length_mm, disc_positions_mm}}` (without it \
             the pins are rigid and no bending moment is computed)"
        ),
        "min_pin_bending_safety" if !inputs.pins_yield => format!(
            "the pins' safety is their yield strength over their bending stress: give \
             `yield_strength_mpa` to `{prefix}roller_material` (the pins' material; the disc's \
             `{prefix}material` without it)"
        ),
        "min_contact_fatigue_life_h" if !inputs.fatigue_law => format!(
            "a contact fatigue life needs an S–N law: give `contact_fatigue: {{pressure_mpa, \
             cycles, exponent}}` to `{prefix}material` (the disc) or `{prefix}roller_material` \
             (the rollers)"
        ),
        "min_static_safety" if !inputs.static_rating => format!(
            "a static safety needs the bearing's basic static load rating C0 (ISO 76): give \
             `{prefix}crank_bearing.static_load_rating_n`"
        ),
        _ => return None,
    };
    Some(why)
}

/// What each strength limit needs of the design and of the scenes that compute it.
pub(crate) fn check(limits: &Limits, design: &Design, scenes: &[Scene]) -> Result<()> {
    let bearing = design.crank_bearing.as_ref();
    let inputs = Inputs::new(&design.strength, design.pins.support.is_some(), bearing);
    for limit in &limits.entries {
        let key = limit.def.key;
        if let Some(why) = missing_input(key, &inputs, "reducer.") {
            return Err(Error::invalid(format!("limits.{key}"), why));
        }
        if key == "min_contact_fatigue_life_h" {
            speeds(scenes, key)?;
        }
    }
    Ok(())
}

/// A fatigue life in hours is at a speed: every scene that computes it needs one (a duty
/// cycle's bins have theirs).
fn speeds(scenes: &[Scene], key: &str) -> Result<()> {
    for (i, s) in scenes.iter().enumerate() {
        let computes = Plan::for_scene(s).computes(Effect::Strength);
        if computes && !s.has_speed() {
            return Err(Error::invalid(
                format!("scenes[{i}]"),
                format!(
                    "limits.{key} applies to scene `{}`, which computes `strength`: it needs \
                     `input_speed_rpm` (a life in hours is the cycles to failure over the \
                     cycles per hour)",
                    s.name
                ),
            ));
        }
    }
    Ok(())
}
