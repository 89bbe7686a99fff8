//! `reducer.friction` and `reducer.thermal` (MODEL.md "Friction, efficiency and heat"): every
//! value checked at its key, so that no friction path is silently changed or ignored: μ in
//! [0, 1), every radius positive and physically possible (a bore inside its roller or its
//! sleeve), a bore given exactly when its mode has one.

use super::raw::{
    RawBearingFriction, RawFriction, RawNoLoad, RawPinFriction, RawRollerFriction, RawThermal,
};
use super::values::{
    finite, length, named, within, HEAT_TRANSFER_W_PER_M2K, HOUSING_AREA_M2, MAX_SPEED_RPM,
};
use crate::error::{Error, Result};
use crate::model::{
    BearingFriction, Design, Effect, Friction, FrictionModel, Limits, NoLoadTorque, PinFriction,
    PinMode, Plan, RollerFriction, RollerMode, Scene, Thermal, MAX_NO_LOAD_POINTS,
};
use crate::numeric;

const KEY: &str = "reducer.friction";

/// Absolute zero, °C: an ambient temperature must lie above it.
const ABSOLUTE_ZERO_C: f64 = -273.15;

/// A friction coefficient in [0, 1): 0 is no friction; at 1 and above a contact holds by
/// friction alone whatever pushes it (no lubricated or dry engineering pair reaches it).
fn mu(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && (0.0..1.0).contains(&value) {
        return Ok(value);
    }
    // Below 0 (or no number) is another mistake than a coefficient too large.
    let why = if value.is_nan() || value < 0.0 {
        "a friction coefficient is a ratio of forces, 0 (no friction) or more"
    } else {
        "a friction coefficient of 1 or more is no engineering contact's (lubricated steel \
         ~0.001–0.1, dry polymer on steel ~0.2–0.5)"
    };
    Err(Error::invalid(
        key,
        format!("must lie in [0, 1), got {}: {why}", numeric::input(value)),
    ))
}

/// The bore of a mode that has one (`with` names the mode), or an error at the mode's key.
fn bore(key: &str, mode: &str, bore: Option<f64>, below: (f64, &str)) -> Result<f64> {
    let Some(b) = bore else {
        return Err(Error::invalid(
            format!("{key}.mode"),
            format!("mode `{mode}` needs `bore_radius_mm`, the radius of the pin it turns on"),
        ));
    };
    let b = length(&format!("{key}.bore_radius_mm"), b)?;
    let (outer, what) = below;
    if b >= outer {
        return Err(Error::invalid(
            format!("{key}.bore_radius_mm"),
            format!(
                "{} mm must be smaller than {what} ({} mm): the pin turns inside it",
                numeric::input(b),
                numeric::input(outer)
            ),
        ));
    }
    Ok(b)
}

/// A `fixed` mode's bore is refused: it would be silently ignored.
fn no_bore(key: &str, bore: Option<f64>) -> Result<()> {
    match bore {
        None => Ok(()),
        Some(_) => Err(Error::invalid(
            format!("{key}.bore_radius_mm"),
            "is only read with a turning mode (`rotating` rollers, `sleeve` pins); with `fixed` \
             it would be ignored: remove it or change the mode"
                .into(),
        )),
    }
}

/// The bore of a contact's mode at `key` (`mode` and `bore` as written): `None` for `fixed`,
/// the bore below `radius` for its one turning mode (`turning`); `part` names the contact in
/// an unknown mode's error.
fn turning_bore(
    key: &str,
    (mode, bore_mm): (&str, Option<f64>),
    radius: (f64, &str),
    (turning, part): (&str, &str),
) -> Result<Option<f64>> {
    match mode {
        "fixed" => no_bore(key, bore_mm).map(|()| None),
        m if m == turning => bore(key, turning, bore_mm, radius).map(Some),
        other => Err(Error::invalid(
            format!("{key}.mode"),
            format!("unknown {part} mode `{other}`; known: fixed, {turning}"),
        )),
    }
}

fn rollers(base: &str, raw: &RawRollerFriction, radius: (f64, &str)) -> Result<RollerFriction> {
    let key = &format!("{base}.rollers");
    let mode = (&*raw.mode, raw.bore_radius_mm);
    let bore = turning_bore(key, mode, radius, ("rotating", "roller"))?;
    Ok(RollerFriction {
        mode: bore.map_or(RollerMode::Fixed, |bore_radius_mm| RollerMode::Rotating {
            bore_radius_mm,
        }),
        mu: mu(&format!("{key}.mu"), raw.mu)?,
    })
}

fn output_pins(base: &str, raw: &RawPinFriction, radius: (f64, &str)) -> Result<PinFriction> {
    let key = &format!("{base}.output_pins");
    let mode = (&*raw.mode, raw.bore_radius_mm);
    let bore = turning_bore(key, mode, radius, ("sleeve", "output-pin"))?;
    Ok(PinFriction {
        mode: bore.map_or(PinMode::Fixed, |bore_radius_mm| PinMode::Sleeve {
            bore_radius_mm,
        }),
        mu: mu(&format!("{key}.mu"), raw.mu)?,
    })
}

fn crank_bearing(base: &str, raw: &RawBearingFriction) -> Result<BearingFriction> {
    let key = format!("{base}.crank_bearing");
    Ok(BearingFriction {
        mu: mu(&format!("{key}.mu"), raw.mu)?,
        bore_diameter_mm: length(&format!("{key}.bore_diameter_mm"), raw.bore_diameter_mm)?,
    })
}

/// `reducer.friction` of `design` (its radii bound the bores).
pub(super) fn friction(raw: &RawFriction, design: &Design) -> Result<Friction> {
    friction_at(
        KEY,
        raw,
        (
            design.roller_radius_mm,
            "the roller's radius, reducer.roller_radius_mm",
        ),
        (
            design.pins.pin_radius_mm,
            "the sleeve's outer radius, reducer.output_pins.pin_radius_mm",
        ),
    )
}

/// A no-load torque at `key`: a drag ≥ 0, or a table of 1 to `MAX_NO_LOAD_POINTS` pairs
/// [input_rpm, N·mm], speeds ≥ 0 strictly increasing, torques ≥ 0.
fn no_load(key: &str, raw: &RawNoLoad) -> Result<NoLoadTorque> {
    // `what`: which torque, before "must be" ("" for the one number).
    let drag = |t: f64, what: &str| -> Result<f64> {
        let t = finite(key, t)?;
        if t < 0.0 {
            return Err(Error::invalid(
                key,
                format!(
                    "{what}must be zero or positive, got {}: a drag resists the input's turn",
                    numeric::input(t)
                ),
            ));
        }
        Ok(t)
    };
    let points = match raw {
        RawNoLoad::Constant(t) => return Ok(NoLoadTorque::constant(drag(*t, "")?)),
        RawNoLoad::Table(points) => points,
    };
    if points.is_empty() || points.len() > MAX_NO_LOAD_POINTS {
        return Err(Error::invalid(
            key,
            format!(
                "a table of [input_rpm, N·mm] pairs has 1 to {MAX_NO_LOAD_POINTS} pairs, got {}",
                points.len()
            ),
        ));
    }
    for (i, &[n, t]) in points.iter().enumerate() {
        let n = finite(key, n)?;
        drag(t, &format!("the torque of pair {i} "))?;
        if !(0.0..=MAX_SPEED_RPM).contains(&n) {
            return Err(Error::invalid(
                key,
                format!(
                    "the speed of pair {i} must lie in [0, {MAX_SPEED_RPM}] rpm, got {}",
                    numeric::input(n)
                ),
            ));
        }
        if i > 0 && n <= points[i - 1][0] {
            return Err(Error::invalid(
                key,
                format!(
                    "the speeds must increase: pair {i} at {} rpm follows {} rpm",
                    numeric::input(n),
                    numeric::input(points[i - 1][0])
                ),
            ));
        }
    }
    Ok(NoLoadTorque::table(points))
}

/// A friction block at `base` (`reducer.friction`, or a requirements file's `friction`):
/// the bores bounded by `roller` and `pin`, each the radius a bore must stay below and its
/// name for the message.
pub(crate) fn friction_at(
    base: &str,
    raw: &RawFriction,
    roller: (f64, &str),
    pin: (f64, &str),
) -> Result<Friction> {
    let model =
        named(&format!("{base}.model"), raw.model.as_deref())?.unwrap_or(FrictionModel::Coupled);
    let no_load = match &raw.no_load_torque_nmm {
        None => NoLoadTorque::constant(0.0),
        Some(t) => no_load(&format!("{base}.no_load_torque_nmm"), t)?,
    };
    Ok(Friction {
        model,
        rollers: raw
            .rollers
            .as_ref()
            .map(|r| rollers(base, r, roller))
            .transpose()?,
        output_pins: raw
            .output_pins
            .as_ref()
            .map(|p| output_pins(base, p, pin))
            .transpose()?,
        crank_bearing: raw
            .crank_bearing
            .as_ref()
            .map(|b| crank_bearing(base, b))
            .transpose()?,
        no_load_torque_nmm: no_load,
    })
}

/// `reducer.thermal` (or a requirements file's `thermal`, at `key`): an area and a
/// heat-transfer coefficient within a housing's bounds (`values::HOUSING_AREA_M2`,
/// `HEAT_TRANSFER_W_PER_M2K`), an ambient above absolute zero.
pub(super) fn thermal_at(key: &str, raw: &RawThermal) -> Result<Thermal> {
    let ambient = finite(&format!("{key}.ambient_c"), raw.ambient_c)?;
    if ambient <= ABSOLUTE_ZERO_C {
        return Err(Error::invalid(
            format!("{key}.ambient_c"),
            format!(
                "{} °C is at or below absolute zero ({ABSOLUTE_ZERO_C} °C)",
                numeric::input(ambient)
            ),
        ));
    }
    Ok(Thermal {
        housing_area_m2: within(
            &format!("{key}.housing_area_m2"),
            raw.housing_area_m2,
            HOUSING_AREA_M2,
            "m²",
            "a housing's outer area, from a thumbnail's to a room's",
        )?,
        heat_transfer_w_per_m2k: within(
            &format!("{key}.heat_transfer_w_per_m2k"),
            raw.heat_transfer_w_per_m2k,
            HEAT_TRANSFER_W_PER_M2K,
            "W/(m²·K)",
            "still air is ~5–25, forced liquid cooling up to ~10⁴",
        )?,
        ambient_c: ambient,
    })
}

/// A scene that asks for `efficiency` needs `reducer.friction`; the coupled model needs a rigid
/// crank bearing in such a scene (refused at the scene's bearing stiffness).
pub(super) fn check_scenes(design: &Design, scenes: &[Scene]) -> Result<()> {
    // A torsion loop balances with its friction, which a compliant bearing's centre search
    // does not carry.
    if design.friction.is_some() {
        if let Some(k) = scenes
            .iter()
            .position(|s| s.torque_sweep.is_some() && s.bearing_stiffness_n_per_mm.is_some())
        {
            return Err(Error::invalid(
                format!("scenes[{k}].bearing_stiffness_n_per_mm"),
                "a torsion loop with `reducer.friction` balances its friction with a rigid crank \
                 bearing: leave out bearing_stiffness_n_per_mm in this torque_sweep scene"
                    .into(),
            ));
        }
    }
    if let Some(i) = scenes
        .iter()
        .position(|s| s.effects.contains(&Effect::Efficiency))
    {
        match design.friction {
            None => {
                return Err(Error::invalid(
                    format!("scenes[{i}].effects"),
                    "`efficiency` needs the friction of the contacts: give `reducer.friction` \
                     (see docs/effects/friction.md)"
                        .into(),
                ))
            }
            // The coupled model balances with a rigid crank bearing only (its friction
            // moment in a compliant bearing's centre search is not built).
            Some(f) if f.model == FrictionModel::Coupled => {
                if let Some(k) = scenes.iter().position(|s| {
                    s.effects.contains(&Effect::Efficiency)
                        && s.bearing_stiffness_n_per_mm.is_some()
                }) {
                    return Err(Error::invalid(
                        format!("scenes[{k}].bearing_stiffness_n_per_mm"),
                        "the coupled friction model needs a rigid crank bearing: leave out \
                         bearing_stiffness_n_per_mm, or give `reducer.friction.model: loss`"
                            .into(),
                    ));
                }
            }
            Some(_) => {}
        }
    }
    no_load_speeds(design, scenes)
}

/// A no-load torque table is read at each scene's speed (a duty cycle's bins at theirs): a
/// scene that computes the efficiency without `input_speed_rpm` or a duty cycle is refused at
/// the scene (no silent choice of a speed).
fn no_load_speeds(design: &Design, scenes: &[Scene]) -> Result<()> {
    if (design.friction).is_none_or(|f| f.no_load_torque_nmm.is_constant()) {
        return Ok(());
    }
    match scenes
        .iter()
        .position(|s| Plan::for_scene(s).computes(Effect::Efficiency) && !s.has_speed())
    {
        Some(i) => Err(Error::invalid(
            format!("scenes[{i}]"),
            format!(
                "`reducer.friction.no_load_torque_nmm` is a table over the input speed, and \
                 scene `{}` computes the efficiency without `input_speed_rpm`: give the scene \
                 its speed, or the no-load torque as one number",
                scenes[i].name
            ),
        )),
        None => Ok(()),
    }
}

/// The limits in watts and degrees need what makes them: a speed in every scene that computes
/// the efficiency (the losses in watts are the losses × ω), and `reducer.thermal` for a
/// temperature. Refused before anything runs, at the scene or the limit.
pub(super) fn check_limits(limits: &Limits, design: &Design, scenes: &[Scene]) -> Result<()> {
    let set = |key: &str| limits.get(key).is_some();
    if set("max_hysteresis_loss_arcmin") && design.friction.is_none() {
        return Err(Error::invalid(
            "limits.max_hysteresis_loss_arcmin",
            "a hysteresis loss needs friction in the torsion loop: give `reducer.friction` \
             (without it the loop's branches coincide and the loss is 0 by the model, not by \
             the design)"
                .into(),
        ));
    }
    for key in ["max_power_loss_w", "max_temperature_c"] {
        if !set(key) {
            continue;
        }
        if key == "max_temperature_c" && design.thermal.is_none() {
            return Err(Error::invalid(
                format!("limits.{key}"),
                "a temperature needs the housing's heat path: give `reducer.thermal: \
                 {housing_area_m2, heat_transfer_w_per_m2k, ambient_c}`"
                    .into(),
            ));
        }
        for (i, s) in scenes.iter().enumerate() {
            let plan = Plan::for_scene(s);
            if plan.computes_quantity(&crate::model::quantity::TOTAL_POWER_LOSS)
                && s.input_speed_rpm.is_none()
            {
                return Err(Error::invalid(
                    format!("scenes[{i}]"),
                    format!(
                        "limits.{key} applies to scene `{}`, which computes the efficiency: it \
                         needs `input_speed_rpm` (the losses in watts are the losses per unit \
                         speed × ω)",
                        s.name
                    ),
                ));
            }
        }
    }
    Ok(())
}
