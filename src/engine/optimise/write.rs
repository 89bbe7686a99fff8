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

/// Insert `key: value` into the `modification` mapping (block or flow style), or add the mapping.
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
            text.push_str(&format!("modification:\n  {key}: {value}\n"));
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
