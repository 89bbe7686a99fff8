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
    let at = |line: usize, column: usize| Location {
        file: path.to_string(),
        line,
        column,
    };
    // YAML syntax first, on an untyped value: a syntax error then carries no key path (the
    // typed pass would name whatever key it had reached, e.g. `name` for a tab on line 2).
    // Duplicate keys and integers too large for any YAML value are left to the typed pass,
    // which knows their key path.
    let typed_error = |m: &str| {
        [
            "duplicate entry with key",
            "invalid type: ",
            "invalid value: ",
        ]
        .iter()
        .any(|p| m.contains(p))
    };
    match serde_yaml::from_str::<serde_yaml::Value>(text) {
        Ok(serde_yaml::Value::Null) => {
            return Err(Error::new(
                ErrorKind::Syntax,
                "the spec is empty; it needs at least `name`, `reducer` and `scenes`",
            )
            .at(at(1, 1)))
        }
        Err(err) if !typed_error(&err.to_string()) => {
            let (line, column) = err.location().map_or((1, 1), |l| (l.line(), l.column()));
            return Err(
                Error::new(ErrorKind::Syntax, yaml_message(&err.to_string())).at(at(line, column)),
            );
        }
        _ => {}
    }
    match deserialize::<RawOptimise>(path, text) {
        // An untagged `optimise` that matched no form: parse again as the form the YAML has
        // (a mapping is one study, a list is many) to get the precise key and location.
        Err(e) if e.key_path.as_deref() == Some("optimise") => {
            let shape: serde_yaml::Value = serde_yaml::from_str(text).unwrap_or_default();
            let precise = match shape.get("optimise") {
                Some(serde_yaml::Value::Sequence(_)) => {
                    deserialize::<Vec<RawStudy>>(path, text).err()
                }
                _ => deserialize::<RawStudy>(path, text).err(),
            };
            Err(precise.unwrap_or(e))
        }
        other => other,
    }
}

fn deserialize<O>(path: &str, text: &str) -> Result<RawSpecOf<RawOptimise>>
where
    O: serde::de::DeserializeOwned + Into<RawOptimise>,
{
    let at = |line: usize, column: usize| Location {
        file: path.to_string(),
        line,
        column,
    };
    let de = serde_yaml::Deserializer::from_str(text);
    let raw: RawSpecOf<O> = serde_path_to_error::deserialize(de).map_err(|err| {
        let key_path = err.path().to_string();
        let key_path = if key_path == "." {
            String::new()
        } else {
            key_path
        };
        let inner = err.into_inner();
        let (line, column) = inner.location().map_or((1, 1), |l| (l.line(), l.column()));
        let (key_path, message, relocated) =
            user_message(text, &key_path, &yaml_message(&inner.to_string()));
        let (line, column) = relocated.unwrap_or((line, column));
        let mut error = Error::new(ErrorKind::Syntax, message).at(at(line, column));
        if !key_path.is_empty() {
            error = error.at_key(key_path);
        }
        error
    })?;
    Ok(RawSpecOf {
        name: raw.name,
        reducer: raw.reducer,
        modification: raw.modification,
        scenes: raw.scenes,
        limits: raw.limits,
        optimise: raw.optimise.map(Into::into),
        golden: raw.golden,
        accuracy: raw.accuracy,
    })
}

impl From<RawStudy> for RawOptimise {
    fn from(s: RawStudy) -> Self {
        RawOptimise::One(Box::new(s))
    }
}

impl From<Vec<RawStudy>> for RawOptimise {
    fn from(v: Vec<RawStudy>) -> Self {
        RawOptimise::Many(v)
    }
}

/// serde_yaml's message without what the error already says elsewhere: its own key-path prefix
/// (`reducer: `) and the first ` at line L column C` (the location goes in front instead).
fn yaml_message(message: &str) -> String {
    if message.starts_with("deserializing from YAML containing more than one document") {
        return "more than one YAML document (`---`); a spec is a single document".to_string();
    }
    let mut message = message.to_string();
    if let Some((head, tail)) = message.split_once(": ") {
        let is_path = !head.is_empty()
            && head
                .chars()
                .all(|c| c.is_alphanumeric() || "_.[]?".contains(c));
        if is_path {
            message = tail.to_string();
        }
    }
    if let Some(start) = message.find(" at line ") {
        let rest = &message[start + " at line ".len()..];
        let number = |s: &str| s.len() - s.trim_start_matches(|c: char| c.is_ascii_digit()).len();
        let n = number(rest);
        if n > 0 && rest[n..].starts_with(" column ") {
            let tail = &rest[n + " column ".len()..];
            let m = number(tail);
            if m > 0 {
                message = format!("{}{}", &message[..start], &tail[m..]);
            }
        }
    }
    message
}

/// The names between backticks in a serde message, in order.
fn backticked(message: &str) -> Vec<&str> {
    message.split('`').skip(1).step_by(2).collect()
}

/// Turn serde's wording (fields, Rust types) into the spec's (keys, numbers). Returns the key
/// path, the message and, for a duplicate key, the location of the second occurrence.
fn user_message(
    text: &str,
    key_path: &str,
    message: &str,
) -> (String, String, Option<(usize, usize)>) {
    let join = |parent: &str, key: &str| {
        if parent.is_empty() {
            key.to_string()
        } else {
            format!("{parent}.{key}")
        }
    };
    if let Some(rest) = message.strip_prefix("unknown field ") {
        // serde_path_to_error's path already ends with the unknown key.
        let names = backticked(rest);
        let (unknown, known) = names.split_first().map_or(("", &[][..]), |(u, k)| (*u, k));
        let message = match did_you_mean(unknown, known.iter().copied()) {
            Some(close) => format!("unknown key; did you mean `{close}`?"),
            None if known.is_empty() => "unknown key; this mapping takes no keys".to_string(),
            None => format!("unknown key; the keys here are {}", known.join(", ")),
        };
        return (key_path.to_string(), message, None);
    }
    if let Some(rest) = message.strip_prefix("missing field ") {
        return (
            key_path.to_string(),
            format!("missing required key {rest}"),
            None,
        );
    }
    if let Some(rest) = message.strip_prefix("duplicate field ") {
        let key = backticked(rest).first().copied().unwrap_or("");
        let full = join(key_path, key);
        let second = locate_duplicate(text, key_path, key);
        return (full, "key appears twice".to_string(), second);
    }
    // An integer beyond i64: serde_yaml says "invalid value: integer `N`, expected i64" or
    // "invalid type: integer `N` as u128, expected i64".
    let integer = ["invalid value: integer `", "invalid type: integer `"]
        .iter()
        .any(|p| message.starts_with(p));
    if integer && message.ends_with(", expected i64") {
        let digits = backticked(message).first().copied().unwrap_or("");
        return (
            key_path.to_string(),
            format!("integer `{digits}` is out of range"),
            None,
        );
    }
    if message.contains("untagged enum RawObjective") {
        return (
            key_path.to_string(),
            "expected an objective name or a map of objective names to weights".to_string(),
            None,
        );
    }
    let message = message
        .replace("unit value", "null")
        .replace(", expected i64", ", expected an integer")
        .replace(", expected f64", ", expected a number");
    (key_path.to_string(), message, None)
}

/// The closest of `known` to `unknown` when it is close enough to be a misspelling.
fn did_you_mean<'a>(unknown: &str, known: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let limit = (unknown.chars().count() / 3).max(2);
    known
        .map(|k| (edit_distance(unknown, k), k))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

/// Levenshtein distance over chars.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (prev + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(row[j + 1] + 1);
            prev = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// The second `key:` at the same column as the first, inside the mapping at `parent`.
fn locate_duplicate(text: &str, parent: &str, key: &str) -> Option<(usize, usize)> {
    let start = if parent.is_empty() {
        0
    } else {
        locate_offset(text, parent)?
    };
    let first = find_key(text, start, key)?;
    let column = line_column(text, first).1;
    let mut from = first + key.len();
    loop {
        let next = find_key(text, from, key)?;
        let (line, col) = line_column(text, next);
        if col == column {
            return Some((line, col));
        }
        from = next + key.len();
    }
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
/// Best effort: keys are matched in order as `key:` outside comments; list items of block
/// sequences by indentation, of flow sequences (`[a, b]`) by commas. A list item's location is
/// its value (after `- `), so `scenes[0].effects[1]` points at the effect's name.
pub fn locate(text: &str, key_path: &str) -> Option<(usize, usize)> {
    locate_offset(text, key_path).map(|offset| line_column(text, offset))
}

/// Byte offset of a dotted key path in YAML text (see `locate`).
pub fn locate_offset(text: &str, key_path: &str) -> Option<usize> {
    let mut pos = 0usize;
    let mut hit = None;
    for segment in key_path.split('.') {
        let (key, indices) = match segment.find('[') {
            Some(b) => (&segment[..b], &segment[b..]),
            None => (segment, ""),
        };
        if !key.is_empty() {
            pos = find_key(text, pos, key)?;
            hit = Some(pos);
        }
        for index in indices.split(']').filter(|s| !s.is_empty()) {
            let index = index.strip_prefix('[')?.parse::<usize>().ok()?;
            pos = find_item(text, pos, index)?;
            hit = Some(pos);
        }
    }
    hit
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

/// Item `index` of the sequence that is the value of the key (or item) at `from`.
fn find_item(text: &str, from: usize, index: usize) -> Option<usize> {
    let line_end = text[from..].find('\n').map_or(text.len(), |n| from + n);
    // The value on the key's own line: `key: [a, b]` or `- [a, b]`.
    let value = match text[from..line_end].find(": ") {
        Some(colon) => from + colon + 1,
        None => text[from..line_end]
            .find(':')
            .map_or(line_end, |colon| from + colon + 1),
    };
    let value = value + (text[value..line_end].len() - text[value..line_end].trim_start().len());
    if text[value..].starts_with('[') {
        return find_flow_item(text, value, index);
    }
    find_block_item(text, from, line_end, index)
}

/// Item `index` of the flow sequence whose `[` is at `open`.
fn find_flow_item(text: &str, open: usize, index: usize) -> Option<usize> {
    let mut depth = 0usize;
    let mut count = 0usize;
    let mut expect_item = false;
    let mut quote: Option<char> = None;
    let mut comment = false;
    let mut prev = ' ';
    for (rel, c) in text[open..].char_indices() {
        let at = open + rel;
        if comment {
            comment = c != '\n';
        } else if let Some(q) = quote {
            if c == q {
                quote = None;
            }
        } else if c == '#' && prev.is_whitespace() {
            comment = true;
        } else if expect_item && !c.is_whitespace() && c != ']' {
            if count == index {
                return Some(at);
            }
            count += 1;
            expect_item = false;
            if c == '"' || c == '\'' {
                quote = Some(c);
            } else if c == '[' || c == '{' {
                depth += 1;
            }
        } else {
            match c {
                '"' | '\'' => quote = Some(c),
                '[' | '{' => {
                    depth += 1;
                    expect_item = depth == 1;
                }
                ']' | '}' => {
                    depth = depth.checked_sub(1)?;
                    if depth == 0 {
                        return None;
                    }
                }
                ',' if depth == 1 => expect_item = true,
                _ => {}
            }
        }
        prev = c;
    }
    None
}

/// Item `index` of the block sequence on the lines after the key at `from`.
fn find_block_item(text: &str, from: usize, line_end: usize, index: usize) -> Option<usize> {
    let line_start = text[..from].rfind('\n').map_or(0, |n| n + 1);
    let key_indent = from - line_start;
    let mut indent: Option<usize> = None;
    let mut count = 0;
    let mut offset = (line_end + 1).min(text.len());
    for line in text[offset..].split_inclusive('\n') {
        let trimmed = line.trim_start_matches(' ');
        let this_indent = line.len() - trimmed.len();
        let content = trimmed.trim_end();
        if content.is_empty() || content.starts_with('#') {
            offset += line.len();
            continue;
        }
        let is_item = trimmed.starts_with("- ") || content == "-";
        let list_indent = match indent {
            // The value is a block sequence only if its first line is an item under the key.
            None if is_item && this_indent >= key_indent => *indent.insert(this_indent),
            None => return None,
            Some(i) => i,
        };
        if this_indent < list_indent || (this_indent == list_indent && !is_item) {
            return None;
        }
        if this_indent == list_indent {
            if count == index {
                let after_dash = &trimmed[1..];
                let value = after_dash.trim_start_matches(' ');
                return Some(if value.trim_end().is_empty() {
                    offset + this_indent
                } else {
                    offset + this_indent + 1 + (after_dash.len() - value.len())
                });
            }
            count += 1;
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

/// Largest length the engine accepts, mm. Beyond 100 m a double's ~1e-16 relative precision
/// no longer resolves the micrometre gaps this tool exists to check.
const MAX_LENGTH_MM: f64 = 1e5;

/// Largest crank angle magnitude, degrees (~28,000 revolutions): an angle's rounding stays
/// below 1e-9 rad.
const MAX_CRANK_DEG: f64 = 1e7;

/// A positive length no larger than `MAX_LENGTH_MM`.
fn length(key: &str, value: f64) -> Result<f64> {
    let value = positive(key, value)?;
    if value > MAX_LENGTH_MM {
        return Err(invalid(
            key,
            format!(
                "{value} mm is larger than the {MAX_LENGTH_MM} mm (100 m) this tool handles: \
                 beyond it double precision cannot resolve micrometre gaps"
            ),
        ));
    }
    Ok(value)
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
        eccentricity_mm: length("reducer.eccentricity_mm", raw.eccentricity_mm)?,
        roller_circle_radius_mm: length(
            "reducer.roller_circle_radius_mm",
            raw.roller_circle_radius_mm,
        )?,
        roller_radius_mm: length("reducer.roller_radius_mm", raw.roller_radius_mm)?,
        face_width_mm: length("reducer.face_width_mm", raw.face_width_mm)?,
        pins: OutputPins {
            count: count("reducer.output_pins.count", pins.count, 2)?,
            circle_radius_mm: length(
                "reducer.output_pins.circle_radius_mm",
                pins.circle_radius_mm,
            )?,
            pin_radius_mm: length("reducer.output_pins.pin_radius_mm", pins.pin_radius_mm)?,
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

/// Largest rollers × crank angles of one scene: every per-roller, per-angle array of the results
/// must fit in memory (10⁷ f64 are 80 MB).
pub const MAX_ROLLER_ANGLES: i64 = 10_000_000;

fn crank(key: &str, raw: &RawCrank, rollers: usize) -> Result<Vec<f64>> {
    let angle = |name: &str, value: f64| -> Result<f64> {
        let k = format!("{key}.{name}");
        let value = finite(&k, value)?;
        if value.abs() > MAX_CRANK_DEG {
            return Err(invalid(
                &k,
                format!(
                    "{value}° is beyond ±{MAX_CRANK_DEG}° (about 28,000 revolutions), where \
                     the crank angle's rounding would exceed 1e-9 rad"
                ),
            ));
        }
        Ok(value)
    };
    let from = angle("from_deg", raw.from_deg)?;
    let to = angle("to_deg", raw.to_deg)?;
    let steps = raw.steps;
    if steps < 1 {
        return Err(invalid(
            &format!("{key}.steps"),
            format!("a crank range needs at least 1 step, got {steps}"),
        ));
    }
    let max_steps = MAX_ROLLER_ANGLES / rollers.max(1) as i64;
    if steps > max_steps {
        return Err(invalid(
            &format!("{key}.steps"),
            format!(
                "at most {max_steps} steps with {rollers} rollers \
                 (rollers × steps ≤ {MAX_ROLLER_ANGLES}), got {steps}"
            ),
        ));
    }
    if to <= from {
        return Err(invalid(
            &format!("{key}.to_deg"),
            format!("the crank range is empty: to_deg = {to} must exceed from_deg = {from}"),
        ));
    }
    Ok(crank_angles(from, to, steps as usize))
}

/// Crank angles of a range in rad: `from + k·(to − from)/steps` degrees, k = 0 … steps − 1.
/// Grids of `steps` and `steps·2^m` over the same range nest exactly: every angle of the coarser
/// is, bit for bit, the angle 2^m·k of the finer (division and multiplication by a power of two
/// are exact in binary floating point).
pub fn crank_angles(from_deg: f64, to_deg: f64, steps: usize) -> Vec<f64> {
    let step = (to_deg - from_deg) / steps as f64;
    (0..steps)
        .map(|k| (from_deg + step * k as f64).to_radians())
        .collect()
}

fn scene(index: usize, raw: RawScene, rollers: usize) -> Result<Scene> {
    let key = format!("scenes[{index}]");
    if raw.name.trim().is_empty() {
        return Err(invalid(&format!("{key}.name"), "must not be empty".into()));
    }
    let mut effects = Vec::new();
    for (j, name) in raw.effects.iter().enumerate() {
        let effect = Effect::from_name(name).ok_or_else(|| {
            let known = Effect::ALL.map(|e| e.name());
            let message = match did_you_mean(name, known.into_iter()) {
                Some(close) => format!("unknown effect `{name}`; did you mean `{close}`?"),
                None => format!(
                    "unknown effect `{name}`; known effects: {}",
                    known.join(", ")
                ),
            };
            invalid(&format!("{key}.effects[{j}]"), message)
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
        crank_rad: crank(&format!("{key}.crank"), &raw.crank, rollers)?,
        crank_from_deg: raw.crank.from_deg,
        crank_to_deg: raw.crank.to_deg,
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
        optimum_max_objective: f("optimum_max_objective", raw.optimum_max_objective)?,
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
        let s = scene(i, s, design.rollers)?;
        if scenes.iter().any(|other| other.name == s.name) {
            return Err(invalid(
                &format!("scenes[{i}].name"),
                format!("scene name `{}` is used twice", s.name),
            ));
        }
        scenes.push(s);
    }
    let studies = match raw.optimise {
        Some(o) => {
            let many = matches!(o, RawOptimise::Many(_));
            let raws = o.into_studies();
            let mut studies: Vec<Study> = Vec::new();
            for (i, r) in raws.into_iter().enumerate() {
                let key = if many {
                    format!("optimise[{i}]")
                } else {
                    "optimise".to_string()
                };
                let s = study(&key, i, r, &scenes, &modification)?;
                if studies.iter().any(|o| o.name == s.name) {
                    return Err(invalid(
                        &format!("{key}.name"),
                        format!("study name `{}` is used twice", s.name),
                    ));
                }
                studies.push(s);
            }
            studies
        }
        None => Vec::new(),
    };
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
    let accuracy = raw
        .accuracy
        .map(|a| accuracy_section(a, &scenes, &design))
        .transpose()?;
    Ok(Spec {
        name: raw.name,
        path: path.to_string(),
        source: text.to_string(),
        design,
        modification,
        scenes,
        limits,
        golden,
        studies,
        accuracy,
    })
}

/// `accuracy:`: the scene exists and computes something the ladder compares, the rungs are
/// rungs of the ladder, the tolerances are positive.
fn accuracy_section(raw: RawAccuracy, scenes: &[Scene], design: &Design) -> Result<Accuracy> {
    use crate::accuracy as acc;
    let scene = scenes
        .iter()
        .position(|s| s.name == raw.scene)
        .ok_or_else(|| {
            invalid(
                "accuracy.scene",
                format!(
                    "no scene named `{}`; scenes: {}",
                    raw.scene,
                    scene_names(scenes)
                ),
            )
        })?;
    let steps = |key: &str, value: Option<i64>, min: usize| {
        value
            .map(|n| acc::ladder_steps(n, min).map_err(|m| invalid(&format!("accuracy.{key}"), m)))
            .transpose()
    };
    let finest = steps(
        "finest_steps_per_period",
        raw.finest_steps_per_period,
        2 * acc::COARSEST,
    )?
    .unwrap_or(acc::DEFAULT_FINEST);
    let settings_steps = steps(
        "settings_steps_per_period",
        raw.settings_steps_per_period,
        acc::COARSEST,
    )?;
    let defaults = acc::Tolerances::default();
    let t = &raw.tolerance;
    let tol = |key: &str, value: Option<f64>, default: f64| {
        value.map_or(Ok(default), |v| {
            acc::tolerance(v).map_err(|m| invalid(&format!("accuracy.tolerance.{key}"), m))
        })
    };
    let options = acc::Options {
        finest,
        settings_steps,
        tolerances: acc::Tolerances {
            te_arcsec: tol("te_arcsec", t.te_arcsec, defaults.te_arcsec)?,
            force_n: tol("force_n", t.force_n, defaults.force_n)?,
            ratio: tol("ratio", t.ratio, defaults.ratio)?,
            clearance_um: tol("clearance_um", t.clearance_um, defaults.clearance_um)?,
        },
    };
    acc::check(design, &scenes[scene], &options).map_err(|(which, m)| {
        let key = match which {
            acc::Setting::Scene => "accuracy.scene",
            acc::Setting::Finest => "accuracy.finest_steps_per_period",
            acc::Setting::SettingsSteps => "accuracy.settings_steps_per_period",
        };
        invalid(key, m)
    })?;
    Ok(Accuracy { scene, options })
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

fn bounds(key: &str, b: [f64; 2]) -> Result<(f64, f64)> {
    let [lo, hi] = b;
    if !(lo.is_finite() && hi.is_finite() && lo < hi) {
        return Err(invalid(
            key,
            format!("bounds must be two finite numbers [lower, upper] with lower < upper, got [{lo}, {hi}]"),
        ));
    }
    Ok((lo, hi))
}

fn objective(key: &str, raw: RawObjective) -> Result<Vec<(Objective, f64)>> {
    let known = || Objective::ALL.map(|o| o.name()).join(", ");
    let named = |name: &str| {
        Objective::from_name(name).ok_or_else(|| {
            invalid(
                key,
                format!("unknown objective `{name}`; known objectives: {}", known()),
            )
        })
    };
    match raw {
        RawObjective::Name(name) => Ok(vec![(named(&name)?, 1.0)]),
        RawObjective::Weighted(map) => {
            if map.is_empty() {
                return Err(invalid(
                    key,
                    "a weighted objective needs at least one term".into(),
                ));
            }
            map.into_iter()
                .map(|(name, w)| {
                    if !(w.is_finite() && w > 0.0) {
                        return Err(invalid(
                            key,
                            format!("the weight of `{name}` must be a positive number, got {w}"),
                        ));
                    }
                    Ok((named(&name)?, w))
                })
                .collect()
        }
    }
}

fn study(
    key: &str,
    index: usize,
    raw: RawStudy,
    scenes: &[Scene],
    modification: &Modification,
) -> Result<Study> {
    let scene = scenes
        .iter()
        .position(|s| s.name == raw.scene)
        .ok_or_else(|| {
            invalid(
                &format!("{key}.scene"),
                format!(
                    "no scene named `{}`; scenes: {}",
                    raw.scene,
                    scene_names(scenes)
                ),
            )
        })?;
    let mut variables = Vec::new();
    let v = &raw.variables;
    for (kind, b) in [
        (VariableKind::Shift, v.shift_mm),
        (VariableKind::Equidistant, v.equidistant_mm),
        (VariableKind::Rotation, v.rotation_deg),
    ] {
        if let Some(b) = b {
            let (lo, hi) = bounds(&format!("{key}.variables.{}", kind.key()), b)?;
            let scale = if kind == VariableKind::Rotation {
                1f64.to_radians()
            } else {
                1.0
            };
            variables.push(Variable {
                kind,
                lower: lo * scale,
                upper: hi * scale,
            });
        }
    }
    if variables.is_empty() {
        return Err(invalid(
            &format!("{key}.variables"),
            "a study needs at least one variable (shift_mm, equidistant_mm, rotation_deg)".into(),
        ));
    }
    let mut start = *modification;
    if let Some(p) = raw.start {
        for (kind, value) in [
            (VariableKind::Shift, p.shift_mm),
            (VariableKind::Equidistant, p.equidistant_mm),
            (VariableKind::Rotation, p.rotation_deg.map(f64::to_radians)),
        ] {
            if let Some(x) = value {
                kind.set(
                    &mut start,
                    finite(&format!("{key}.start.{}", kind.key()), x)?,
                );
            }
        }
    }
    for var in &variables {
        let x = var.kind.get(&start);
        if !(var.lower..=var.upper).contains(&x) {
            let unit = |x| var.kind.to_spec_unit(x);
            return Err(invalid(
                &format!("{key}.start"),
                format!(
                    "the start {} = {} lies outside its bounds [{}, {}] (give a start inside \
                     the bounds; the spec's modification is the start when none is given)",
                    var.kind.key(),
                    unit(x),
                    unit(var.lower),
                    unit(var.upper)
                ),
            ));
        }
    }
    let c = &raw.constraints;
    let tip_clearance_mm = c
        .tip_clearance_mm
        .map(|b| bounds(&format!("{key}.constraints.tip_clearance_mm"), b))
        .transpose()?;
    let min_clearance_mm = c
        .min_clearance_mm
        .map(|x| finite(&format!("{key}.constraints.min_clearance_mm"), x))
        .transpose()?;
    let mut references = Vec::new();
    for (j, r) in raw.references.into_iter().enumerate() {
        let rk = format!("{key}.references[{j}]");
        references.push((
            r.label,
            Modification {
                shift_mm: finite(&format!("{rk}.shift_mm"), r.shift_mm)?,
                equidistant_mm: finite(&format!("{rk}.equidistant_mm"), r.equidistant_mm)?,
                rotation_rad: finite(&format!("{rk}.rotation_deg"), r.rotation_deg)?.to_radians(),
            },
        ));
    }
    Ok(Study {
        name: raw.name.unwrap_or_else(|| format!("study-{}", index + 1)),
        scene,
        objective: objective(&format!("{key}.objective"), raw.objective)?,
        variables,
        start,
        tip_clearance_mm,
        min_clearance_mm,
        references,
        optimum_max_objective: raw
            .optimum_max_objective
            .map(|x| finite(&format!("{key}.optimum_max_objective"), x))
            .transpose()?,
        global_samples: count(
            &format!("{key}.global_samples"),
            raw.global_samples.unwrap_or(64),
            1,
        )?,
        local_evaluations: count(
            &format!("{key}.local_evaluations"),
            raw.local_evaluations.unwrap_or(200),
            10,
        )?,
    })
}

/// The scenes' names, comma-separated, for messages about an unknown scene.
pub fn scene_names(scenes: &[Scene]) -> String {
    scenes
        .iter()
        .map(|s| s.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}
