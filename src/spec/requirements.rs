//! A requirements file (`cycloid design`): YAML → `requirements_raw` → the validated
//! [`Requirements`]. Errors are located as a spec's: `file:line:column: kind: key: message`.

use super::raw::{RawCrankBearing, RawMaterial, RawPinSupport};
use super::requirements_raw::*;
use super::validate::{limits, material};
use super::values::{finite, positive};
use crate::error::{Error, Result};
use crate::model::design::MAX_DISCS;
use crate::model::requirements::loaded_mesh_periods;
use crate::model::requirements::*;
use crate::model::strength::Strength;
use crate::model::{Misalignment, PinSupport};
use crate::numeric;

/// Most ratios, pin counts or disc counts a search tries (each multiplies the work).
pub const MAX_CHOICES: usize = 16;
/// Largest Sobol sample per discrete choice (the sequence's length in `sobol_burley` is 2^16).
pub const MAX_SAMPLES: usize = 1 << 16;
/// Largest ratio: a disc of 200 teeth.
pub const MAX_RATIO: i64 = 200;
pub use super::mass::STEEL_DENSITY_KG_PER_M3;

/// Read and validate a requirements file.
pub fn load(path: &str) -> Result<Requirements> {
    let text = crate::files::read_text(
        std::path::Path::new(path),
        "requirements",
        crate::files::MAX_INPUT_BYTES,
    )?;
    parse(path, &text)
}

/// Parse and validate requirements text; `path` is used in messages only.
pub fn parse(path: &str, text: &str) -> Result<Requirements> {
    let raw: RawRequirements = super::yaml::parse_document(path, text, "requirements file")?;
    build(raw).map_err(|e| super::locate::locate_error(e, path, text))
}

fn non_negative(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(
            key,
            format!("must be a number ≥ 0, got {}", numeric::input(value)),
        ))
    }
}

/// A `[lower, upper]` range of finite numbers, lower ≤ upper; `positive_only`: lower > 0.
fn range(key: &str, raw: &[f64], positive_only: bool) -> Result<Range> {
    let &[lower, upper] = raw else {
        return Err(Error::invalid(
            key,
            format!(
                "must be a range [lower, upper] (the same number twice fixes it), got {} numbers",
                raw.len()
            ),
        ));
    };
    finite(&format!("{key}[0]"), lower)?;
    finite(&format!("{key}[1]"), upper)?;
    if lower > upper {
        return Err(Error::invalid(
            key,
            format!(
                "lower {} exceeds upper {}",
                numeric::input(lower),
                numeric::input(upper)
            ),
        ));
    }
    if positive_only && lower <= 0.0 {
        return Err(Error::invalid(
            format!("{key}[0]"),
            format!("must be positive, got {}", numeric::input(lower)),
        ));
    }
    Ok(Range { lower, upper })
}

/// A non-empty list of distinct integers in [min, max].
fn choices(key: &str, raw: &[i64], min: i64, max: i64) -> Result<Vec<usize>> {
    if raw.is_empty() || raw.len() > MAX_CHOICES {
        return Err(Error::invalid(
            key,
            format!("must list 1 to {MAX_CHOICES} values, got {}", raw.len()),
        ));
    }
    let mut out = Vec::new();
    for (i, &v) in raw.iter().enumerate() {
        if !(min..=max).contains(&v) {
            return Err(Error::invalid(
                format!("{key}[{i}]"),
                format!("must be in [{min}, {max}], got {v}"),
            ));
        }
        if out.contains(&(v as usize)) {
            return Err(Error::invalid(
                format!("{key}[{i}]"),
                format!("{v} is listed twice"),
            ));
        }
        out.push(v as usize);
    }
    Ok(out)
}

/// `ratio`: one integer or a list of them.
fn ratios(raw: &serde_yaml::Value) -> Result<Vec<usize>> {
    let bad = |key: String, what: String| {
        Error::invalid(
            key,
            format!(
                "must be a whole ratio (the disc's teeth, 2 to {MAX_RATIO}) or a list of them, \
                 got {what}"
            ),
        )
    };
    let one = |key: String, v: &serde_yaml::Value| -> Result<i64> {
        v.as_i64().ok_or_else(|| {
            bad(
                key,
                serde_yaml::to_string(v).unwrap_or_default().trim().into(),
            )
        })
    };
    let list = match raw {
        serde_yaml::Value::Sequence(items) => items
            .iter()
            .enumerate()
            .map(|(i, v)| one(format!("ratio[{i}]"), v))
            .collect::<Result<Vec<_>>>()?,
        v => {
            // One ratio, not a list: its errors are at `ratio` itself, not at an item.
            let ratio = one("ratio".into(), v)?;
            return choices("ratio", &[ratio], 2, MAX_RATIO).map_err(|mut e| {
                e.key_path = Some("ratio".into());
                e
            });
        }
    };
    choices("ratio", &list, 2, MAX_RATIO)
}

/// `misalignment` (within ±`values::MAX_TILT_MRAD`, mrad → rad) and `face_slices` (1 to `MAX_FACE_SLICES`), with the
/// spec's rules: a tilted or crowned face needs 2 slices or more, so does a limit on the load
/// along the face, and the line loads of a scene (contacts × crank angles × slices) must fit in
/// memory for every ratio and pin count of the search (`ratios`, `pin_counts` and `steps` per
/// mesh period as validated).
fn face(
    raw: &RawRequirements,
    ratios: &[usize],
    pin_counts: &[usize],
    steps: usize,
) -> Result<(Misalignment, usize)> {
    let face = super::face::scene_face("", raw.misalignment, raw.face_slices)?;
    let (misalignment, slices) = (face.misalignment, face.slices);
    let shaped = [
        ("misalignment", "tilted", !misalignment.is_zero()),
        ("crowning", "crowned", raw.crowning.is_some()),
    ];
    if let Some((key, what, _)) = shaped.into_iter().find(|&(_, _, is)| is && slices < 2) {
        // At `face_slices` where it is given (too few), else at what needs them.
        let key = if raw.face_slices.is_some() {
            "face_slices"
        } else {
            key
        };
        return Err(Error::invalid(
            key,
            format!(
                "a {what} face needs `face_slices: 2` or more (20 is a good start), the slices \
                 the line load is reported at"
            ),
        ));
    }
    for key in ["max_face_load_factor", "max_line_load_n_per_mm"] {
        if raw.limits.contains_key(key) && slices < 2 {
            return Err(Error::invalid(
                format!("limits.{key}"),
                "needs the load along the face width resolved: give `face_slices: 2` or more \
                 (and `misalignment`, without which the face is loaded evenly)"
                    .to_string(),
            ));
        }
    }
    for &nc in ratios {
        for &m in pin_counts {
            let angles = steps * loaded_mesh_periods(nc, m, !misalignment.is_zero());
            let case = format!(" (ratio {nc}, {m} pins)");
            super::face::line_loads_fit("face_slices", slices, ((nc + 1).max(m), angles), &case)?;
        }
    }
    Ok((misalignment, slices))
}

/// The strength limits' inputs (`spec::strength::missing_input`, the spec's rules with the
/// requirements' keys), and a speed for a contact fatigue life in hours.
fn strength_limits(
    raw: &RawRequirements,
    strength: &Strength,
    bearing: Option<&crate::model::CrankBearing>,
) -> Result<()> {
    let inputs = super::strength::Inputs::new(strength, raw.output_pins.is_some(), bearing);
    for key in raw.limits.keys() {
        let at = format!("limits.{key}");
        if let Some(why) = super::strength::missing_input(key, &inputs, "") {
            return Err(Error::invalid(at, why));
        }
        let speed = raw.input_speed_rpm.is_some() || raw.duty_cycle.is_some();
        if key == "min_contact_fatigue_life_h" && !speed {
            return Err(Error::invalid(
                at,
                "needs `input_speed_rpm` or `duty_cycle`: a life in hours is the cycles to \
                 failure over the cycles per hour"
                    .to_string(),
            ));
        }
    }
    Ok(())
}

/// `output_pins.support`, as a spec's `reducer.output_pins.support` (`validate::pin_support`)
/// for every design of `search`: one mid-plane per disc for each number of discs searched, the
/// mid-planes a face width apart at the largest face width searched.
fn pin_support(raw: &RawPinSupport, search: &Search) -> Result<PinSupport> {
    let positions = raw.disc_positions_mm.len();
    if let Some(&discs) = search.discs.iter().find(|&&d| d != positions) {
        return Err(Error::invalid(
            "output_pins.support.disc_positions_mm",
            format!(
                "gives {positions} position(s), but the search tries {discs} disc(s) \
                 (`search.discs`): one mid-plane per disc, mm from the flange; with a pin \
                 support search one number of discs"
            ),
        ));
    }
    super::validate::pin_support(
        "output_pins.support",
        raw,
        positions,
        search.continuous.face_width_mm.upper,
    )
}

fn build(raw: RawRequirements) -> Result<Requirements> {
    let rated = positive("rated_torque_nm", raw.rated_torque_nm)?;
    let peak = match raw.peak_torque_nm {
        Some(p) => positive("peak_torque_nm", p)?,
        None => rated,
    };
    if peak < rated {
        return Err(Error::invalid(
            "peak_torque_nm",
            format!(
                "the peak torque {} N·m is below the rated {} N·m",
                numeric::input(peak),
                numeric::input(rated)
            ),
        ));
    }
    let input_speed_rpm = raw
        .input_speed_rpm
        .map(|n| super::values::speed_rpm("input_speed_rpm", positive("input_speed_rpm", n)?))
        .transpose()?;
    let e = &raw.envelope;
    let envelope = Envelope {
        max_outer_diameter_mm: positive("envelope.max_outer_diameter_mm", e.max_outer_diameter_mm)?,
        max_axial_length_mm: positive("envelope.max_axial_length_mm", e.max_axial_length_mm)?,
        housing_wall_mm: non_negative(
            "envelope.housing_wall_mm",
            e.housing_wall_mm.unwrap_or(5.0),
        )?,
        axial_allowance_mm: non_negative(
            "envelope.axial_allowance_mm",
            e.axial_allowance_mm.unwrap_or(10.0),
        )?,
    };
    let m = &raw.material;
    if let Some(d) = raw.roller_material.and_then(|r| r.density_kg_per_m3) {
        return Err(Error::invalid(
            "roller_material.density_kg_per_m3",
            format!(
                "the search weighs the rollers and pins at `material.density_kg_per_m3` (its \
                 mass objective), so {} kg/m³ would change nothing: remove it",
                numeric::input(d)
            ),
        ));
    }
    // The density is the search's (`density` below); the candidates' specs are written with
    // their own.
    let disc_material = RawMaterial {
        density_kg_per_m3: None,
        ..*m
    };
    let roller_material = raw
        .roller_material
        .map(|r| material("roller_material", r))
        .transpose()?;
    let material = material("material", disc_material)?;
    let strength = super::strength::materials_at("", &disc_material, raw.roller_material.as_ref())?;
    let density = super::mass::density("material.density_kg_per_m3", m.density_kg_per_m3)?;
    let crank_bearing = raw
        .crank_bearing
        .as_ref()
        .map(|b| {
            let b = RawCrankBearing {
                dynamic_load_rating_n: b.dynamic_load_rating_n,
                life_exponent: b.life_exponent,
                outer_diameter_mm: None,
                static_load_rating_n: b.static_load_rating_n,
            };
            super::validate::crank_bearing("crank_bearing", &b)
        })
        .transpose()?;
    let r = &raw.rules;
    let max_k1 = r.max_k1.unwrap_or(1.0);
    if !(max_k1 > 0.0 && max_k1 <= 1.0) {
        return Err(Error::invalid(
            "rules.max_k1",
            format!("must be in (0, 1], got {}", numeric::input(max_k1)),
        ));
    }
    let rules = DesignRules {
        max_k1,
        min_ligament_mm: non_negative("rules.min_ligament_mm", r.min_ligament_mm.unwrap_or(0.0))?,
        min_roller_gap_mm: non_negative(
            "rules.min_roller_gap_mm",
            r.min_roller_gap_mm.unwrap_or(0.0),
        )?,
    };
    let limits = limits(&raw.limits)?;
    for key in ["optimum_max_objective", "accuracy_resolved"] {
        if raw.limits.contains_key(key) {
            return Err(Error::invalid(
                format!("limits.{key}"),
                "is not a limit a design search can set (its designs have no optimisation \
                 study or accuracy scene)"
                    .to_string(),
            ));
        }
    }
    let s = &raw.search;
    let zero = [0.0, 0.0];
    // In the order of `Continuous::KEYS`: six sizes (positive), then the two modifications.
    let given: [(&[f64], bool); 8] = [
        (&s.eccentricity_mm, true),
        (&s.roller_circle_radius_mm, true),
        (&s.roller_radius_mm, true),
        (&s.face_width_mm, true),
        (&s.pin_circle_radius_mm, true),
        (&s.pin_radius_mm, true),
        (s.shift_mm.as_deref().unwrap_or(&zero), false),
        (s.equidistant_mm.as_deref().unwrap_or(&zero), false),
    ];
    let ranges = (Continuous::KEYS.iter().zip(given))
        .map(|(key, (raw, positive_only))| range(&format!("search.{key}"), raw, positive_only))
        .collect::<Result<Vec<_>>>()?;
    let continuous = Continuous::from_array(ranges.try_into().expect("one range per key"));
    let duty_cycle = raw
        .duty_cycle
        .as_deref()
        .map(|bins| super::duty_cycle::bins_at("duty_cycle", bins))
        .transpose()?;
    // The peak scene carries the largest torque the reducer sees; a bin beyond it (driving or
    // braking, |T|) would be judged on forces the peak does not bound.
    let bins = raw.duty_cycle.as_deref().unwrap_or_default().iter();
    if let Some((j, bin)) = bins
        .enumerate()
        .find(|(_, b)| b.output_torque_nm.abs() > peak)
    {
        let torque = bin.output_torque_nm;
        return Err(Error::invalid(
            format!("duty_cycle[{j}].output_torque_nm"),
            format!(
                "the bin's torque {} N·m is beyond the peak torque {} N·m (peak_torque_nm, or \
                 the rated torque when no peak is given): the peak bounds every torque the \
                 reducer carries, driving or braking",
                numeric::input(torque),
                numeric::input(peak)
            ),
        ));
    }
    if duty_cycle.is_some() && input_speed_rpm.is_some() {
        return Err(Error::invalid(
            "input_speed_rpm",
            "a duty cycle runs each bin at its own torque and speed: give either \
             `duty_cycle` or `input_speed_rpm`, not both"
                .to_string(),
        ));
    }
    // A bore must fit every design of the search: below the smallest roller and pin radius.
    let friction = raw
        .friction
        .as_ref()
        .map(|f| {
            super::friction::friction_at(
                "friction",
                f,
                (
                    continuous.roller_radius_mm.lower,
                    "the smallest roller radius of the search, search.roller_radius_mm[0]",
                ),
                (
                    continuous.pin_radius_mm.lower,
                    "the smallest pin radius of the search, search.pin_radius_mm[0]",
                ),
            )
        })
        .transpose()?;
    let needs_friction = |key: String| -> Result<()> {
        match friction {
            Some(_) => Ok(()),
            None => Err(Error::invalid(
                key,
                "needs the friction of the contacts: give `friction` (the keys of a spec's \
                 `reducer.friction`); without it nothing is lost and the efficiency is 1 by \
                 the model, not by the design"
                    .to_string(),
            )),
        }
    };
    for key in [
        "min_mean_efficiency",
        "max_power_loss_w",
        "max_hysteresis_loss_arcmin",
    ] {
        if raw.limits.contains_key(key) {
            needs_friction(format!("limits.{key}"))?;
        }
    }
    if raw.limits.contains_key("max_power_loss_w") && input_speed_rpm.is_none() {
        return Err(Error::invalid(
            "limits.max_power_loss_w",
            "needs `input_speed_rpm` (the losses in watts are the rated scene's losses × its \
             speed; a duty cycle's bins are not judged on it)"
                .to_string(),
        ));
    }
    let whole = |key: &str, v: Option<i64>, default: i64, min: i64, max: i64| -> Result<i64> {
        let v = v.unwrap_or(default);
        if (min..=max).contains(&v) {
            Ok(v)
        } else {
            Err(Error::invalid(
                key,
                format!("must be in [{min}, {max}], got {v}"),
            ))
        }
    };
    let steps = whole(
        "search.steps_per_mesh_period",
        s.steps_per_mesh_period,
        48,
        4,
        3600,
    )?;
    if steps % 4 != 0 {
        return Err(Error::invalid(
            "search.steps_per_mesh_period",
            format!(
                "must be a multiple of 4 (the screen runs every fourth crank angle), got {steps}"
            ),
        ));
    }
    let ratios = ratios(&raw.ratio)?;
    let pin_counts = choices("search.pin_counts", &s.pin_counts, 2, 64)?;
    let (misalignment, face_slices) = face(&raw, &ratios, &pin_counts, steps as usize)?;
    let thermal = raw
        .thermal
        .as_ref()
        .map(|t| super::friction::thermal_at("thermal", t))
        .transpose()?;
    // The temperature is the rated scene's (the one scene with friction and a speed): its
    // mean loss in watts needs the speed, the heat path and the friction.
    if raw.limits.contains_key("max_temperature_c") {
        let missing = [
            (thermal.is_none(), "`thermal` (the housing's heat path)"),
            (
                friction.is_none(),
                "`friction` (without it nothing is lost)",
            ),
            (
                input_speed_rpm.is_none(),
                "`input_speed_rpm` (the losses in watts are the rated scene's losses × its \
                 speed; a duty cycle's bins are not judged on it)",
            ),
        ];
        if let Some((_, what)) = missing.iter().find(|(m, _)| *m) {
            return Err(Error::invalid(
                "limits.max_temperature_c",
                format!(
                    "the steady temperature ambient + P_loss/(h·A) of the rated scene needs {what}"
                ),
            ));
        }
    }
    // Checked against the largest face width of the search; a design of a smaller face that
    // cannot hold the crown is rejected by a design rule (`design_search::rules`).
    let crowning = raw
        .crowning
        .as_ref()
        .map(|c| {
            super::face::crowning_at(
                "crowning",
                c,
                (
                    continuous.face_width_mm.upper,
                    "the largest face width of the search, search.face_width_mm[1]",
                ),
            )
        })
        .transpose()?
        .unwrap_or_default();
    let life_needs = |key: String| -> Result<()> {
        match (
            &crank_bearing,
            input_speed_rpm.is_some() || duty_cycle.is_some(),
        ) {
            (Some(_), true) => Ok(()),
            _ => Err(Error::invalid(
                key,
                "needs `crank_bearing` (its rating) and `input_speed_rpm` or `duty_cycle`"
                    .to_string(),
            )),
        }
    };
    if raw.limits.contains_key("min_bearing_life_h") {
        if duty_cycle.is_some() {
            return Err(Error::invalid(
                "limits.min_bearing_life_h",
                "with a duty cycle the life is the cycle's (Palmgren–Miner over the bins): \
                 bound it with `limits.min_duty_life_h`"
                    .to_string(),
            ));
        }
        life_needs("limits.min_bearing_life_h".into())?;
    }
    if raw.limits.contains_key("min_duty_life_h") {
        if duty_cycle.is_none() {
            return Err(Error::invalid(
                "limits.min_duty_life_h",
                "needs `duty_cycle` (without one, bound the life at the rated torque with \
                 `limits.min_bearing_life_h`)"
                    .to_string(),
            ));
        }
        life_needs("limits.min_duty_life_h".into())?;
    }
    strength_limits(&raw, &strength, crank_bearing.as_ref())?;
    if raw.objectives.len() < 2 || raw.objectives.len() > 3 {
        return Err(Error::invalid(
            "objectives",
            format!(
                "must list two or three objectives to trade, got {}",
                raw.objectives.len()
            ),
        ));
    }
    let mut objectives = Vec::new();
    for (i, name) in raw.objectives.iter().enumerate() {
        let key = format!("objectives[{i}]");
        let Some(kind) = ObjectiveKind::from_name(name) else {
            return Err(Error::invalid(
                key,
                format!(
                    "unknown objective `{name}`; the objectives are {}",
                    ObjectiveKind::names()
                ),
            ));
        };
        if objectives.contains(&kind) {
            return Err(Error::invalid(key, format!("`{name}` is listed twice")));
        }
        if kind == ObjectiveKind::BearingLife {
            life_needs(key)?;
        } else if kind == ObjectiveKind::Efficiency {
            needs_friction(key)?;
        }
        objectives.push(kind);
    }
    let search = Search {
        continuous,
        pin_counts,
        discs: choices(
            "search.discs",
            s.discs.as_deref().unwrap_or(&[1]),
            1,
            MAX_DISCS as i64,
        )?,
        hole_clearance_mm: non_negative(
            "search.hole_clearance_mm",
            s.hole_clearance_mm.unwrap_or(0.0),
        )?,
        samples: whole("search.samples", s.samples, 256, 1, MAX_SAMPLES as i64)? as usize,
        seed: whole("search.seed", s.seed, 1, 0, u32::MAX as i64)? as u32,
        refine_budget: whole("search.refine_budget", s.refine_budget, 48, 0, 100_000)? as usize,
        steps_per_mesh_period: steps as usize,
    };
    let pin_support = raw
        .output_pins
        .as_ref()
        .map(|p| pin_support(&p.support, &search))
        .transpose()?;
    super::values::not_blank("name", &raw.name)?;
    Ok(Requirements {
        name: raw.name,
        ratios,
        rated_torque_nmm: crate::units::nmm(rated),
        peak_torque_nmm: crate::units::nmm(peak),
        input_speed_rpm,
        duty_cycle,
        friction,
        thermal,
        crowning,
        misalignment,
        face_slices,
        envelope,
        material,
        density_kg_per_mm3: crate::units::kg_per_mm3(density),
        roller_material,
        strength,
        pin_support,
        crank_bearing,
        rules,
        limits,
        objectives,
        search,
    })
}
