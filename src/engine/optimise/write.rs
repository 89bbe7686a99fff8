//! Write a spec with a modification filled in, editing the YAML text in place so that the
//! user's comments and layout survive. The result is parsed again and must give back exactly
//! the modification written (values are printed in Rust's shortest round-trip form).

use crate::error::{Error, ErrorKind, Result};
use crate::model::Modification;
use crate::spec::{self, locate_offset};
use crate::units;

/// Replace the scalar after `key:` at `offset` with `value`.
fn replace_value(text: &mut String, offset: usize, value: &str) {
    let colon = offset + text[offset..].find(':').unwrap_or(0) + 1;
    let rest = &text[colon..];
    let end = rest.find([',', '}', '#', '\n']).unwrap_or(rest.len());
    let trailing = if rest[..end].ends_with(' ') { " " } else { "" };
    text.replace_range(colon..colon + end, &format!(" {value}{trailing}"));
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

/// Insert `key: value` into the `modification` mapping (block or flow style), or add the mapping
/// where it usually stands: before `scenes`.
fn insert_value(text: &mut String, key: &str, value: &str) {
    match locate_offset(text, "modification") {
        Some(at) => {
            let line_end = text[at..].find('\n').map_or(text.len(), |n| at + n);
            if let Some(brace) = text[at..line_end].find('{') {
                text.insert_str(at + brace + 1, &format!(" {key}: {value},"));
            } else {
                let line_start = text[..at].rfind('\n').map_or(0, |n| n + 1);
                let indent = at - line_start + 2;
                let insert = format!("\n{}{key}: {value}", " ".repeat(indent));
                text.insert_str(line_end, &insert);
            }
        }
        None => {
            if !text.ends_with('\n') {
                text.push('\n');
            }
            let at = key_line(text, "scenes").unwrap_or(text.len());
            text.insert_str(at, &format!("modification:\n  {key}: {value}\n"));
        }
    }
}

/// The spec text with `m` as its modification.
pub fn with_modification(path: &str, text: &str, m: &Modification) -> Result<String> {
    let mut out = text.to_string();
    for (key, value) in [
        ("shift_mm", m.shift_mm),
        ("equidistant_mm", m.equidistant_mm),
        ("rotation_deg", units::deg(m.rotation_rad)),
    ] {
        let value = format!("{value:?}");
        match locate_offset(&out, &format!("modification.{key}")) {
            Some(offset) => replace_value(&mut out, offset, &value),
            None => insert_value(&mut out, key, &value),
        }
    }
    let written = spec::parse(path, &out)?;
    let back = written.modification;
    let same = back.shift_mm == m.shift_mm
        && back.equidistant_mm == m.equidistant_mm
        && (back.rotation_rad - m.rotation_rad).abs() <= 1e-15;
    if !same {
        return Err(Error::new(
            ErrorKind::Computation,
            format!("the written spec reads back as {back:?}, not the optimum {m:?}"),
        ));
    }
    Ok(out)
}

/// The spec of an optimum, to be written to `out_path`: the source spec text with `m` as its
/// modification, `name` as its name and `header` (comment lines) on top. Its `golden` section
/// is removed with a comment saying why: the goldens are curves of the old design, which the
/// optimum's no longer match (and their paths are relative to the old spec's folder). The
/// result parses and reads back as `m`.
pub fn optimum_spec(
    out_path: &str,
    text: &str,
    m: &Modification,
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
    let out = format!("{header}{}", with_modification(out_path, &out, m)?);
    let back = spec::parse(out_path, &out)?;
    if back.name != name || !back.golden.is_empty() {
        return Err(Error::new(
            ErrorKind::Computation,
            format!(
                "the written spec reads back with name `{}`, not `{name}`",
                back.name
            ),
        ));
    }
    Ok(out)
}
