//! Spec loading: YAML text → `raw` (serde) → `model` (validated, engine units).
//!
//! Errors carry `file:line:column` and the key path. Syntax errors take their location from the
//! YAML parser; value and design-rule errors locate their key in the text (`locate`).

pub mod model;
pub mod raw;

use crate::error::{Error, ErrorKind, Location, Result};
use crate::geometry::validity;
use crate::scene::Effect;
pub use model::*;
use raw::*;

/// Read and validate a spec file.
pub fn load(path: &str) -> Result<Spec> {
    let text = std::fs::read_to_string(path).map_err(|e| Error::io(path, e))?;
    parse(path, &text)
}

/// Parse and validate spec text; `path` is used in messages only.
pub fn parse(path: &str, text: &str) -> Result<Spec> {
    let raw = parse_raw(path, text)?;
    build(path, text, raw).map_err(|e| locate_error(e, path, text))
}

fn parse_raw(path: &str, text: &str) -> Result<RawSpec> {
    let de = serde_yaml::Deserializer::from_str(text);
    serde_path_to_error::deserialize(de).map_err(|err| {
        let key_path = err.path().to_string();
        let inner = err.into_inner();
        let mut message = inner.to_string();
        // serde_yaml appends " at line L column C"; the location goes in front instead.
        if let Some(cut) = message.find(" at line ") {
            message.truncate(cut);
        }
        // serde may repeat the path (or, for an unknown field, its parent) in front.
        let mut prefix = key_path.as_str();
        loop {
            if let Some(cut) = message.strip_prefix(&format!("{prefix}: ")) {
                message = cut.to_string();
                break;
            }
            match prefix.rfind(['.', '[']) {
                Some(at) => prefix = &prefix[..at],
                None => break,
            }
        }
        let mut error = Error::new(ErrorKind::Syntax, message);
        if key_path != "." && !key_path.is_empty() {
            error = error.at_key(key_path);
        }
        match inner.location() {
            Some(loc) => error.at(Location {
                file: path.to_string(),
                line: loc.line(),
                column: loc.column(),
            }),
            None => error.at(Location {
                file: path.to_string(),
                line: 1,
                column: 1,
            }),
        }
    })
}

/// Attach a location to a value/design error from its key path, if the key is in the text.
fn locate_error(mut error: Error, path: &str, text: &str) -> Error {
    if error.location.is_none() {
        let (line, column) = error
            .key_path
            .as_deref()
            .and_then(|k| locate(text, k))
            .unwrap_or((1, 1));
        error.location = Some(Location {
            file: path.to_string(),
            line,
            column,
        });
    }
    error
}

/// Find the 1-based line and column of a dotted key path (`scenes[0].crank.steps`) in YAML text.
/// Best effort: keys are matched in order as `key:` outside comments; list items by indentation.
pub fn locate(text: &str, key_path: &str) -> Option<(usize, usize)> {
    let mut pos = 0usize;
    let mut hit = None;
    for segment in key_path.split('.') {
        let (key, index) = match segment.find('[') {
            Some(b) => (
                &segment[..b],
                segment[b + 1..segment.len() - 1].parse::<usize>().ok(),
            ),
            None => (segment, None),
        };
        if !key.is_empty() {
            pos = find_key(text, pos, key)?;
            hit = Some(pos);
        }
        if let Some(i) = index {
            pos = find_item(text, pos, i)?;
            hit = Some(pos);
        }
    }
    hit.map(|offset| line_column(text, offset))
}

fn find_key(text: &str, from: usize, key: &str) -> Option<usize> {
    let mut start = from;
    while let Some(rel) = text[start..].find(key) {
        let at = start + rel;
        let before_ok = text[..at]
            .chars()
            .next_back()
            .is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        let after = text[at + key.len()..].trim_start_matches(' ');
        let line_start = text[..at].rfind('\n').map_or(0, |n| n + 1);
        let in_comment = text[line_start..at].contains('#');
        if before_ok && after.starts_with(':') && !in_comment {
            return Some(at);
        }
        start = at + key.len();
    }
    None
}

fn find_item(text: &str, from: usize, index: usize) -> Option<usize> {
    let mut indent = None;
    let mut count = 0;
    let mut offset = text[from..].find('\n').map(|n| from + n + 1)?;
    for line in text[offset..].split_inclusive('\n') {
        let trimmed = line.trim_start_matches(' ');
        let this_indent = line.len() - trimmed.len();
        if trimmed.starts_with("- ") || trimmed.trim_end() == "-" {
            if indent.is_none_or(|i| i == this_indent) {
                indent = Some(this_indent);
                if count == index {
                    return Some(offset + this_indent);
                }
                count += 1;
            }
        } else if let Some(i) = indent {
            let content = !trimmed.trim().is_empty() && !trimmed.starts_with('#');
            if content && this_indent < i {
                return None;
            }
        }
        offset += line.len();
    }
    None
}

fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = offset - before.rfind('\n').map_or(0, |n| n + 1) + 1;
    (line, column)
}

fn invalid(key: &str, message: String) -> Error {
    Error::new(ErrorKind::InvalidValue, message).at_key(key)
}

fn positive(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(invalid(
            key,
            format!("must be a positive number, got {value}"),
        ))
    }
}

fn finite(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(invalid(
            key,
            format!("must be a finite number, got {value}"),
        ))
    }
}

fn count(key: &str, value: i64, min: i64) -> Result<usize> {
    if value >= min {
        Ok(value as usize)
    } else {
        Err(invalid(key, format!("must be at least {min}, got {value}")))
    }
}

fn material(key: &str, raw: RawMaterial) -> Result<Material> {
    let youngs_gpa = positive(&format!("{key}.youngs_modulus_gpa"), raw.youngs_modulus_gpa)?;
    let nu = raw.poisson_ratio;
    if !(nu.is_finite() && (0.0..0.5).contains(&nu)) {
        return Err(invalid(
            &format!("{key}.poisson_ratio"),
            format!("must lie in [0, 0.5), got {nu}"),
        ));
    }
    Ok(Material {
        youngs_modulus_mpa: youngs_gpa * 1000.0,
        poisson_ratio: nu,
    })
}

fn design(raw: RawReducer) -> Result<Design> {
    let teeth = count("reducer.teeth", raw.teeth, 2)?;
    let rollers = count("reducer.rollers", raw.rollers, 3)?;
    if rollers != teeth + 1 {
        return Err(Error::new(
            ErrorKind::ImpossibleDesign,
            format!(
                "rollers must equal teeth + 1 (one-tooth-difference reducer): \
                 rollers = {rollers}, teeth = {teeth}"
            ),
        )
        .at_key("reducer.rollers"));
    }
    let pins = &raw.output_pins;
    let disc_material = material("reducer.material", raw.material)?;
    let roller_material = match raw.roller_material {
        Some(m) => material("reducer.roller_material", m)?,
        None => disc_material,
    };
    let clearance = raw.output_pins.hole_clearance_mm;
    if !(clearance.is_finite() && clearance >= 0.0) {
        return Err(invalid(
            "reducer.output_pins.hole_clearance_mm",
            format!("must be zero or positive, got {clearance}"),
        ));
    }
    Ok(Design {
        teeth,
        rollers,
        eccentricity_mm: positive("reducer.eccentricity_mm", raw.eccentricity_mm)?,
        roller_circle_radius_mm: positive(
            "reducer.roller_circle_radius_mm",
            raw.roller_circle_radius_mm,
        )?,
        roller_radius_mm: positive("reducer.roller_radius_mm", raw.roller_radius_mm)?,
        face_width_mm: positive("reducer.face_width_mm", raw.face_width_mm)?,
        pins: OutputPins {
            count: count("reducer.output_pins.count", pins.count, 2)?,
            circle_radius_mm: positive(
                "reducer.output_pins.circle_radius_mm",
                pins.circle_radius_mm,
            )?,
            pin_radius_mm: positive("reducer.output_pins.pin_radius_mm", pins.pin_radius_mm)?,
            hole_clearance_mm: clearance,
        },
        disc_material,
        roller_material,
    })
}

fn modification(raw: &RawModification) -> Result<Modification> {
    Ok(Modification {
        shift_mm: finite("modification.shift_mm", raw.shift_mm)?,
        equidistant_mm: finite("modification.equidistant_mm", raw.equidistant_mm)?,
        rotation_rad: finite("modification.rotation_deg", raw.rotation_deg)?.to_radians(),
    })
}

fn crank(key: &str, raw: &RawCrank) -> Result<Vec<f64>> {
    let from = finite(&format!("{key}.from_deg"), raw.from_deg)?;
    let to = finite(&format!("{key}.to_deg"), raw.to_deg)?;
    let steps = raw.steps;
    if steps < 1 {
        return Err(invalid(
            &format!("{key}.steps"),
            format!("a crank range needs at least 1 step, got {steps}"),
        ));
    }
    if to <= from {
        return Err(invalid(
            &format!("{key}.to_deg"),
            format!("the crank range is empty: to_deg = {to} must exceed from_deg = {from}"),
        ));
    }
    let step = (to - from) / steps as f64;
    Ok((0..steps)
        .map(|k| (from + step * k as f64).to_radians())
        .collect())
}

fn scene(index: usize, raw: RawScene) -> Result<Scene> {
    let key = format!("scenes[{index}]");
    if raw.name.trim().is_empty() {
        return Err(invalid(&format!("{key}.name"), "must not be empty".into()));
    }
    let mut effects = Vec::new();
    for (j, name) in raw.effects.iter().enumerate() {
        let effect = Effect::from_name(name).ok_or_else(|| {
            invalid(
                &format!("{key}.effects[{j}]"),
                format!(
                    "unknown effect `{name}`; known effects: {}",
                    Effect::ALL.map(|e| e.name()).join(", ")
                ),
            )
            .at_key(format!("{key}.effects"))
        })?;
        if !effects.contains(&effect) {
            effects.push(effect);
        }
    }
    if effects.is_empty() {
        return Err(invalid(
            &format!("{key}.effects"),
            "a scene must ask for at least one effect".into(),
        ));
    }
    let contact_law = match raw.contact_law.as_deref() {
        None | Some("paper_linear") => ContactLaw::PaperLinear,
        Some("hertz_nonlinear") => ContactLaw::HertzNonlinear,
        Some(other) => {
            return Err(invalid(
                &format!("{key}.contact_law"),
                format!("unknown contact law `{other}`; known: paper_linear, hertz_nonlinear"),
            ))
        }
    };
    let geometry = match raw.geometry.as_deref() {
        None | Some("exact") => GeometryMode::Exact,
        Some("first_order") => GeometryMode::FirstOrder,
        Some(other) => {
            return Err(invalid(
                &format!("{key}.geometry"),
                format!("unknown geometry mode `{other}`; known: exact, first_order"),
            ))
        }
    };
    let bearing_stiffness_n_per_mm = raw
        .bearing_stiffness_n_per_mm
        .map(|k| positive(&format!("{key}.bearing_stiffness_n_per_mm"), k))
        .transpose()?;
    Ok(Scene {
        output_torque_nmm: finite(&format!("{key}.output_torque_nm"), raw.output_torque_nm)?
            * 1000.0,
        crank_rad: crank(&format!("{key}.crank"), &raw.crank)?,
        name: raw.name,
        effects,
        contact_law,
        geometry,
        bearing_stiffness_n_per_mm,
    })
}

fn limits(raw: &RawLimits) -> Result<Limits> {
    let f = |key: &str, v: Option<f64>| v.map(|x| finite(&format!("limits.{key}"), x)).transpose();
    Ok(Limits {
        min_clearance_mm: f("min_clearance_mm", raw.min_clearance_mm)?,
        max_roller_force_n: f("max_roller_force_n", raw.max_roller_force_n)?,
        max_pin_force_n: f("max_pin_force_n", raw.max_pin_force_n)?,
        max_bearing_force_n: f("max_bearing_force_n", raw.max_bearing_force_n)?,
        max_contact_pressure_mpa: f("max_contact_pressure_mpa", raw.max_contact_pressure_mpa)?,
        max_te_fluctuation_arcsec: f("max_te_fluctuation_arcsec", raw.max_te_fluctuation_arcsec)?,
        max_ratio_fluctuation: f("max_ratio_fluctuation", raw.max_ratio_fluctuation)?,
        min_rollers_in_contact: raw
            .min_rollers_in_contact
            .map(|n| count("limits.min_rollers_in_contact", n, 0))
            .transpose()?,
    })
}

fn build(path: &str, text: &str, raw: RawSpec) -> Result<Spec> {
    if raw.name.trim().is_empty() {
        return Err(invalid("name", "must not be empty".into()));
    }
    let design = design(raw.reducer)?;
    let modification = modification(&raw.modification)?;
    validity::check(&design, &modification)?;
    if raw.scenes.is_empty() {
        return Err(invalid("scenes", "a spec needs at least one scene".into()));
    }
    let mut scenes: Vec<Scene> = Vec::new();
    for (i, s) in raw.scenes.into_iter().enumerate() {
        let s = scene(i, s)?;
        if scenes.iter().any(|other| other.name == s.name) {
            return Err(invalid(
                &format!("scenes[{i}].name"),
                format!("scene name `{}` is used twice", s.name),
            ));
        }
        scenes.push(s);
    }
    let limits = limits(&raw.limits)?;
    let mut golden = Vec::new();
    for (i, g) in raw.golden.into_iter().enumerate() {
        let g = golden_entry(path, i, g, &scenes)?;
        if let Some(other) = golden.iter().find(|o: &&Golden| o.path == g.path) {
            return Err(invalid(
                &format!("golden[{i}].file"),
                format!(
                    "golden file `{}` is already used by {}; every golden curve needs its own file",
                    g.file, other.key
                ),
            ));
        }
        golden.push(g);
    }
    Ok(Spec {
        name: raw.name,
        path: path.to_string(),
        source: text.to_string(),
        design,
        modification,
        scenes,
        limits,
        golden,
    })
}

/// Resolve a golden path against the spec file's directory, dropping `.` and `dir/..` pairs
/// so messages show `golden/x.csv` rather than `specs/../golden/x.csv`.
pub fn resolve(spec_path: &str, file: &str) -> std::path::PathBuf {
    use std::path::{Component, Path, PathBuf};
    let base = Path::new(spec_path).parent().unwrap_or(Path::new(""));
    let mut out = PathBuf::new();
    for c in base.join(file).components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                let last = out.components().next_back();
                if matches!(last, Some(Component::Normal(_))) {
                    out.pop();
                } else {
                    out.push("..");
                }
            }
            other => out.push(other.as_os_str()),
        }
    }
    out
}

fn golden_entry(path: &str, i: usize, raw: RawGolden, scenes: &[Scene]) -> Result<Golden> {
    let key = format!("golden[{i}]");
    if !scenes.iter().any(|s| s.name == raw.scene) {
        let names: Vec<String> = scenes.iter().map(|s| format!("`{}`", s.name)).collect();
        return Err(invalid(
            &format!("{key}.scene"),
            format!(
                "unknown scene `{}`; scenes in this spec: {}",
                raw.scene,
                names.join(", ")
            ),
        ));
    }
    let quantity = crate::quantity::find(&raw.quantity).ok_or_else(|| {
        invalid(
            &format!("{key}.quantity"),
            format!(
                "unknown quantity `{}`; known quantities: {}",
                raw.quantity,
                crate::quantity::known_keys()
            ),
        )
    })?;
    if raw.file.trim().is_empty() {
        return Err(invalid(&format!("{key}.file"), "must not be empty".into()));
    }
    let (abs, rel) = (raw.tolerance.abs, raw.tolerance.rel);
    for (name, v) in [("abs", abs), ("rel", rel)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(invalid(
                &format!("{key}.tolerance.{name}"),
                format!("must be zero or positive, got {v}"),
            ));
        }
    }
    if abs == 0.0 && rel == 0.0 {
        return Err(invalid(
            &format!("{key}.tolerance"),
            "abs and rel are both zero: no computed curve matches to the last bit on every \
             machine; give a band"
                .into(),
        ));
    }
    Ok(Golden {
        path: resolve(path, &raw.file),
        key,
        scene: raw.scene,
        quantity: quantity.key,
        file: raw.file,
        tolerance: Tolerance { abs, rel },
    })
}
