//! Writing a spec back with changes, editing its YAML text in place so that the user's comments
//! and layout survive: a modification (`optimise --write`, `fit --write`), an optimum's name with
//! its goldens removed (`optimise --write`), parts as built (`tolerance --write-sample`, `fit
//! --write` of a form error), a measured profile removed (`tolerance --write-sample`). Values are printed in Rust's shortest round-trip form, and every
//! result is parsed again and must give back exactly what was written.

use super::locate::line_of;
use super::locate_offset;
use crate::error::{Error, Result};
use crate::model::{Crowning, Deviations, Modification};
use crate::units;

/// Replace the scalar after `key:` at `offset` (plain, or in single or double quotes) with
/// `value`.
pub(super) fn replace_value(text: &mut String, offset: usize, value: &str) {
    let span = scalar_span(text, offset);
    text.replace_range(span, value);
}

/// The byte range of the scalar after `key:` at `offset`, quotes included.
pub(super) fn scalar_span(text: &str, offset: usize) -> std::ops::Range<usize> {
    let colon = offset + text[offset..].find(':').unwrap_or(0) + 1;
    let rest = &text[colon..];
    let start = rest.len() - rest.trim_start_matches(' ').len();
    let body = &rest[start..];
    let len = match body.chars().next() {
        Some(q @ ('"' | '\'')) => closing_quote(body, q).map_or(0, |end| end + 1),
        _ => body
            .find([',', '}', '\n', '\r'])
            .map(|end| body[..end].find(" #").unwrap_or(end))
            .unwrap_or_else(|| body.find(" #").unwrap_or(body.len())),
    };
    let len = body[..len].trim_end_matches(' ').len();
    colon + start..colon + start + len
}

/// The byte offset of the quote that closes a scalar opened by `q` at the start of `body`.
fn closing_quote(body: &str, q: char) -> Option<usize> {
    let mut chars = body.char_indices().skip(1);
    while let Some((i, c)) = chars.next() {
        match c {
            '\\' if q == '"' => {
                chars.next();
            }
            c if c == q => {
                // '' inside single quotes is an escaped quote.
                if q == '\'' && body[i + 1..].starts_with('\'') {
                    chars.next();
                } else {
                    return Some(i);
                }
            }
            _ => {}
        }
    }
    None
}

/// Whether `line` starts with `key:`.
fn is_key_line(line: &str, key: &str) -> bool {
    line.strip_prefix(key)
        .is_some_and(|rest| rest.trim_start_matches(' ').starts_with(':'))
}

/// The offset of the top-level line `key:`.
fn key_line(text: &str, key: &str) -> Option<usize> {
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        if is_key_line(line, key) {
            return Some(offset);
        }
        offset += line.len();
    }
    None
}

/// The byte range of a top-level section `key`: the comment lines right above its key line,
/// and everything to the next top-level key or comment. None when there is none.
fn top_level_section(text: &str, key: &str) -> Option<std::ops::Range<usize>> {
    let mut start = None;
    let mut comments_from = None;
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let top = !line.starts_with([' ', '\t', '-', '\n', '\r']);
        match start {
            None if top && is_key_line(line, key) => start = Some(comments_from.unwrap_or(offset)),
            None if line.starts_with('#') => comments_from = comments_from.or(Some(offset)),
            None => comments_from = None,
            Some(from) if top => return Some(from..offset),
            Some(_) => {}
        }
        offset += line.len();
    }
    start.map(|from| from..text.len())
}

/// Insert `key: value` into the mapping whose key is at `at` (block or flow style).
fn insert_under(text: &mut String, at: usize, key: &str, value: &str) {
    let line_end = text[at..].find('\n').map_or(text.len(), |n| at + n);
    if let Some(brace) = text[at..line_end].find('{') {
        text.insert_str(at + brace + 1, &format!(" {key}: {value},"));
    } else {
        let (_, column) = line_of(text, at);
        // The indent of the mapping's own keys where it has any (a spec may indent by 4).
        let child = text[line_end..]
            .lines()
            .map(|l| (l.len() - l.trim_start_matches(' ').len(), l.trim_start()))
            .find(|(_, l)| !l.is_empty() && !l.starts_with('#'))
            .map(|(indent, _)| indent)
            .filter(|&indent| indent > column);
        let indent = child.unwrap_or(column + 2);
        let insert = format!("\n{}{key}: {value}", " ".repeat(indent));
        text.insert_str(line_end, &insert);
    }
}

/// Insert `key: value` into the `modification` mapping (block or flow style), or add the mapping
/// where it usually stands: before `scenes`.
fn insert_value(text: &mut String, key: &str, value: &str) {
    match locate_offset(text, "modification") {
        Some(at) => insert_under(text, at, key, value),
        None => {
            if !text.ends_with('\n') {
                text.push('\n');
            }
            let at = key_line(text, "scenes").unwrap_or(text.len());
            text.insert_str(at, &format!("modification:\n  {key}: {value}\n"));
        }
    }
}

/// The spec text with `m` as its modification: `with_values` of its three keys, read back.
pub fn with_modification(path: &str, text: &str, m: &Modification) -> Result<String> {
    let values = [
        ("shift_mm", m.shift_mm),
        ("equidistant_mm", m.equidistant_mm),
        ("rotation_deg", units::deg(m.rotation_rad)),
    ]
    .map(|(key, value)| (format!("modification.{key}"), format!("{value:?}")));
    let values = values.each_ref().map(|(k, v)| (k.as_str(), v.as_str()));
    let (out, written) = with_values(path, text, &values)?;
    let back = written.modification;
    let same = back.shift_mm == m.shift_mm
        && back.equidistant_mm == m.equidistant_mm
        && (back.rotation_rad - m.rotation_rad).abs() <= 1e-15;
    if !same {
        return Err(Error::computation(format!(
            "the written spec reads back as {back:?}, not the optimum {m:?}"
        )));
    }
    Ok(out)
}

/// The spec text with `crowning`'s circular crown as its `modification.crowning` (its
/// `radius_mm` and `start_mm` replaced, or added to the mapping), comments kept: what a study
/// of the crown (`crown_radius_mm`, `crown_start_mm`) writes back. The spec must have a
/// circular crowning, and the result must read back as exactly `crowning`.
pub fn with_crowning(path: &str, text: &str, crowning: &Crowning) -> Result<String> {
    let Crowning::Circular {
        radius_mm,
        start_mm,
    } = *crowning
    else {
        return Err(Error::invalid_value(format!(
            "{path}: only a circular crowning is written back, not {crowning:?}"
        )));
    };
    if locate_offset(text, "modification.crowning").is_none() {
        return Err(Error::invalid_value(format!(
            "{path}: no `modification.crowning` to write the crown into"
        )));
    }
    // A key the mapping lacks is added to it (`add_key`).
    let values = [("radius_mm", radius_mm), ("start_mm", start_mm)]
        .map(|(key, value)| (format!("modification.crowning.{key}"), format!("{value:?}")));
    let values = values.each_ref().map(|(k, v)| (k.as_str(), v.as_str()));
    let (out, written) = with_values(path, text, &values)?;
    let back = written.scenes.first().map(|s| s.face.crowning);
    if back != Some(*crowning) {
        return Err(Error::computation(format!(
            "the written spec reads back with the crowning {back:?}, not {crowning:?}"
        )));
    }
    Ok(out)
}

/// Spec `text` (read from `path`) with the scalar value of each dotted key
/// (`modification.shift_mm`, `scenes[0].crank.steps`, as in the README's spec table) replaced
/// by its YAML text, comments and layout kept; a key the text lacks is added (`add_key`; a
/// `modification` key into the mapping where it usually stands). The result is parsed and
/// validated again, as the command line validates a spec, so an unknown key or a bad value is
/// an error located in the edited text.
///
/// ```
/// let text = std::fs::read_to_string("specs/reducer.yaml").unwrap();
/// let (edited, spec) =
///     cycloid::spec::edit::with_values("reducer.yaml", &text, &[("modification.shift_mm", "-0.01")])?;
/// assert_eq!(spec.modification.shift_mm, -0.01);
/// assert_eq!(edited.lines().count(), text.lines().count()); // edited in place
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn with_values(
    path: &str,
    text: &str,
    values: &[(&str, &str)],
) -> Result<(String, super::Spec)> {
    let mut out = text.to_string();
    for &(key, value) in values {
        match (locate_offset(&out, key), key.strip_prefix("modification.")) {
            (Some(offset), _) => replace_value(&mut out, offset, value),
            (None, Some(name)) if !name.is_empty() && !name.contains(['.', '[']) => {
                insert_value(&mut out, name, value)
            }
            (None, _) => add_key(&mut out, key, value)
                .map_err(|e| e.at(crate::error::Location::new(path, 1, 1)))?,
        }
    }
    let spec = super::parse(path, &out)?;
    Ok((out, spec))
}

/// Add the dotted `key` the text lacks, with `value`: under the deepest mapping of its path the
/// text has, the missing keys as nested flow mappings on one line (`friction: { rollers: { mu:
/// 0.05 } }` under `reducer`), or at the end as a top-level key. Whether the key exists and its
/// value is valid is the parse's to say, as for any spec; a key under a list item that is not
/// there (an index) cannot be added.
fn add_key(text: &mut String, key: &str, value: &str) -> Result<()> {
    let parts: Vec<&str> = key.split('.').collect();
    let missing = |from: usize| &parts[from..];
    let refuse = || {
        Error::invalid(
            key,
            "is not in the spec text and cannot be added: a list item (`[i]`) must be in the \
             spec first"
                .to_string(),
        )
    };
    let found = (1..parts.len())
        .rev()
        .find_map(|n| locate_offset(text, &parts[..n].join(".")).map(|at| (n, at)));
    let (n, at) = found.unwrap_or((0, text.len()));
    let rest = missing(n);
    if rest.iter().any(|k| k.is_empty() || k.contains(['[', ']'])) {
        return Err(refuse());
    }
    let nested = rest[1..]
        .iter()
        .rev()
        .fold(value.to_string(), |inner, k| format!("{{ {k}: {inner} }}"));
    if n == 0 {
        if !text.ends_with('\n') {
            text.push('\n');
        }
        text.push_str(&format!("{}: {nested}\n", rest[0]));
    } else {
        insert_under(text, at, rest[0], &nested);
    }
    Ok(())
}

/// The spec of an optimum, to be written to `out_path`: the source spec text with `m` as its
/// modification (and `crowning` as its crowning, when the study varied it), `name` as its
/// name and `header` (comment lines) on top. Its `golden` section
/// is removed with a comment saying why: the goldens are curves of the old design, which the
/// optimum's no longer match (and their paths are relative to the old spec's folder). The
/// result parses and reads back as `m`.
pub fn optimum_spec(
    out_path: &str,
    text: &str,
    m: &Modification,
    crowning: Option<&Crowning>,
    name: &str,
    header: &str,
) -> Result<String> {
    let mut out = text.to_string();
    if let Some(range) = top_level_section(&out, "golden") {
        out.replace_range(
            range,
            "# The golden curves of the source spec were removed: they belong to its design, \
             not to this\n# optimum. `cycloid bless` makes new ones once a golden section is \
             written here.\n",
        );
    }
    let quoted = serde_json::to_string(name).unwrap_or_else(|_| format!("{name:?}"));
    match key_line(&out, "name") {
        Some(at) => replace_value(&mut out, at, &quoted),
        None => out.insert_str(0, &format!("name: {quoted}\n")),
    }
    if let Some(c) = crowning {
        out = with_crowning(out_path, &out, c)?;
    }
    let out = format!("{header}{}", with_modification(out_path, &out, m)?);
    let back = super::parse(out_path, &out)?;
    if back.name != name || !back.golden.is_empty() {
        return Err(Error::computation(format!(
            "the written spec reads back with name `{}`, not `{name}`",
            back.name
        )));
    }
    Ok(out)
}

/// Spec `text` (to be written to `out_path`) without its `measured_profile` section, a comment
/// in its place saying why: the spec of a tolerance sample (`tolerance --write-sample`)
/// replays the sample, drawn from the drawing, and with a measured profile `check` would run
/// on the disc identified from its points instead. The result parses back without one.
pub fn without_measured_profile(text: &str, out_path: &str) -> Result<String> {
    let mut out = text.to_string();
    if let Some(range) = top_level_section(&out, "measured_profile") {
        out.replace_range(
            range,
            "# The source spec's measured_profile was removed: the sample's deviations are \
             drawn from the\n# drawing, and with it `cycloid check` would run on the measured \
             disc instead.\n",
        );
    }
    if super::parse(out_path, &out)?.measured.is_some() {
        return Err(Error::computation(format!(
            "the written spec {out_path} still reads back with a measured_profile"
        )));
    }
    Ok(out)
}

/// The YAML block of `d` (keys at `indent` spaces), one line per part that has a deviation.
fn block(d: &Deviations, indent: usize) -> String {
    let pad = " ".repeat(indent);
    let mut s = format!("{pad}deviations:\n");
    let inner = " ".repeat(indent + 2);
    for (key, v) in [
        ("eccentricity_mm", d.eccentricity_mm),
        ("shift_mm", d.shift_mm),
        ("equidistant_mm", d.equidistant_mm),
    ] {
        s += &format!("{inner}{key}: {v:?}\n");
    }
    if !d.rollers.is_empty() {
        s += &format!("{inner}rollers:\n");
        for (i, r) in d.rollers.iter().enumerate() {
            s += &format!(
                "{inner}  - {{index: {i}, radial_mm: {:?}, tangential_mm: {:?}, radius_mm: {:?}}}\n",
                r.centre.radial_mm, r.centre.tangential_mm, r.radius_mm
            );
        }
    }
    if !d.pins.is_empty() {
        s += &format!("{inner}pins:\n");
        for (j, p) in d.pins.iter().enumerate() {
            s += &format!(
                "{inner}  - {{index: {j}, radial_mm: {:?}, tangential_mm: {:?}}}\n",
                p.radial_mm, p.tangential_mm
            );
        }
    }
    if !d.holes.is_empty() {
        s += &format!("{inner}holes:\n");
        for (k, holes) in d.holes.iter().enumerate() {
            for (j, h) in holes.iter().enumerate() {
                s += &format!(
                    "{inner}  - {{disc: {k}, index: {j}, radial_mm: {:?}, tangential_mm: {:?}}}\n",
                    h.radial_mm, h.tangential_mm
                );
            }
        }
    }
    if !d.form.is_empty() {
        s += &format!("{inner}form:\n");
        for f in &d.form {
            s += &format!(
                "{inner}  - {{order: {}, cos_mm: {:?}, sin_mm: {:?}}}\n",
                f.order, f.cos_mm, f.sin_mm
            );
        }
    }
    s
}

/// The end of the block whose key line starts at `start` with its key at `column`: the start
/// of the next line with content at `column` or less.
fn block_end(text: &str, start: usize, column: usize) -> usize {
    let mut offset = start
        + text[start..]
            .find('\n')
            .map_or(text.len() - start, |n| n + 1);
    for line in text[offset..].split_inclusive('\n') {
        let body = line.trim_start_matches(' ');
        let depth = line.len() - body.len();
        let blank = body.trim().is_empty() || body.starts_with('#');
        if !blank && depth <= column {
            break;
        }
        offset += line.len();
    }
    offset
}

/// Spec `text` (read from `path`) with `d` as its `reducer.deviations`, replacing the block
/// there is; the result must parse back (as `out_path`) to exactly `d`.
pub fn with_deviations(text: &str, path: &str, d: &Deviations, out_path: &str) -> Result<String> {
    let mut text = text.to_string();
    if let Some(at) = locate_offset(&text, "reducer.deviations") {
        let (start, column) = line_of(&text, at);
        let end = block_end(&text, start, column);
        text.replace_range(start..end, "");
    }
    let teeth = locate_offset(&text, "reducer.teeth").ok_or_else(|| {
        Error::invalid_value(format!("{path}: no `reducer.teeth` key to write beside"))
    })?;
    let (start, column) = line_of(&text, teeth);
    if text[start..teeth].trim() != "" {
        return Err(Error::invalid_value(format!(
            "{path}: `reducer` is written in flow style ({{...}}); write it as a block mapping \
             to write deviations into it"
        )));
    }
    text.insert_str(start, &block(d, column));
    let back = super::parse(out_path, &text)?;
    if back.design.deviations != *d {
        return Err(Error::computation(format!(
            "the written spec reads back as {:?}, not the deviations written, {d:?}",
            back.design.deviations
        )));
    }
    Ok(text)
}
