//! `--write-sample K OUT`: the spec with sample K's deviations as its `reducer.deviations`, so
//! that `cycloid check` replays that reducer. The YAML text is edited in place (comments and
//! layout kept): an existing `reducer.deviations` block is replaced by the sample's, written in
//! Rust's shortest round-trip form, and the result must parse back to exactly those deviations.

use super::ToleranceStudy;
use crate::error::{Error, ErrorKind, Result};
use crate::model::Deviations;
use crate::spec::locate_offset;

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

/// The start of the line holding `offset`, and the column of `offset` in it.
fn line_of(text: &str, offset: usize) -> (usize, usize) {
    let start = text[..offset].rfind('\n').map_or(0, |n| n + 1);
    (start, offset - start)
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

/// The spec text of `study` with sample `k`'s deviations and a header comment saying so.
pub fn sample_spec(study: &ToleranceStudy, k: u64, out_path: &str) -> Result<String> {
    let spec = study.spec;
    let d = study.deviations(&study.draw(k));
    let text = with_deviations(&spec.source, &spec.path, &d, out_path)?;
    let t = &study.tolerances;
    let header = format!(
        "# Written by `cycloid tolerance {} --write-sample {k}`: sample {k} of {} (seed {}) as \
         reducer.deviations.\n",
        spec.path, t.samples, t.seed
    );
    Ok(header + &text)
}

/// Spec `text` (read from `path`) with `d` as its `reducer.deviations`, replacing the block
/// there is; the result must parse back (as `out_path`) to exactly `d`.
pub fn with_deviations(text: &str, path: &str, d: &Deviations, out_path: &str) -> Result<String> {
    let refuse = |m: String| Error::new(ErrorKind::InvalidValue, m);
    let mut text = text.to_string();
    if let Some(at) = locate_offset(&text, "reducer.deviations") {
        let (start, column) = line_of(&text, at);
        let end = block_end(&text, start, column);
        text.replace_range(start..end, "");
    }
    let teeth = locate_offset(&text, "reducer.teeth")
        .ok_or_else(|| refuse(format!("{path}: no `reducer.teeth` key to write beside")))?;
    let (start, column) = line_of(&text, teeth);
    if text[start..teeth].trim() != "" {
        return Err(refuse(format!(
            "{path}: `reducer` is written in flow style ({{...}}); write it as a block mapping \
             to write deviations into it"
        )));
    }
    text.insert_str(start, &block(d, column));
    let back = crate::spec::parse(out_path, &text)?;
    if back.design.deviations != *d {
        return Err(Error::new(
            ErrorKind::Computation,
            format!(
                "the written spec reads back as {:?}, not the deviations written, {d:?}",
                back.design.deviations
            ),
        ));
    }
    Ok(text)
}
