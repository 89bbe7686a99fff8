//! A spec written to another directory (`optimise --write`, `fit --write`, `tolerance
//! --write-sample`): the paths it names (`golden[].file`, `golden_root`,
//! `measured_profile.file`) are relative to its own directory, so each relative one is rewritten
//! to reach the same file from the new place. Absolute paths stay as written.

use super::edit::{replace_value, scalar_span};
use super::locate_offset;
use crate::error::{Error, Result};
use crate::files::identity;
use std::path::{Component, Path, PathBuf};

/// The paths `spec` names, resolved against its directory, each with its key: `golden[i].file`,
/// `golden_root`, `measured_profile.file`.
fn named_paths(spec: &super::Spec) -> Vec<(String, PathBuf)> {
    let golden = (spec.golden.iter()).map(|g| (format!("{}.file", g.key), g.path.clone()));
    let root = (spec.golden_root.iter()).map(|r| ("golden_root".into(), r.clone()));
    let measured =
        (spec.measured.iter()).map(|m| ("measured_profile.file".into(), PathBuf::from(&m.path)));
    golden.chain(root).chain(measured).collect()
}

/// `text`, a spec read from `from`, as it must read when written to `to`: each relative path it
/// names rewritten from `to`'s directory to the same file (symbolic links followed, as the
/// kernel will when the written spec is read). Unchanged when both are in one directory. The
/// result parses, and names the same files as the original.
pub fn relocate(text: &str, from: &str, to: &str) -> Result<String> {
    let (from_dir, to_dir) = (identity(&directory(from)), identity(&directory(to)));
    if from_dir == to_dir {
        return Ok(text.to_string());
    }
    let named = named_paths(&super::parse(from, text)?);
    let mut out = text.to_string();
    // From the last key to the first, so the offsets of the ones still to do stay valid.
    let mut edits: Vec<(usize, String)> = Vec::new();
    for (key, target) in &named {
        let offset = locate_offset(&out, key).ok_or_else(|| unwritable(key, to))?;
        // Absolute as written: it reaches its file from anywhere. (The resolved `target` is
        // absolute too when the spec's own path is.)
        let written = &out[scalar_span(&out, offset)];
        if Path::new(written.trim_matches(['"', '\''])).is_absolute() {
            continue;
        }
        let target = if target.as_os_str().is_empty() {
            Path::new(".")
        } else {
            target
        };
        let new = relative(&to_dir, &identity(target));
        edits.push((offset, yaml_scalar(&new.to_string_lossy())));
    }
    edits.sort_by_key(|(offset, _)| std::cmp::Reverse(*offset));
    for (offset, value) in edits {
        replace_value(&mut out, offset, &value);
    }
    let back = named_paths(&super::parse(to, &out)?);
    let same = |(k, a): &(String, PathBuf), (l, b): &(String, PathBuf)| {
        k == l && identity(a) == identity(b)
    };
    let kept = back.len() == named.len() && back.iter().zip(&named).all(|(a, b)| same(a, b));
    if !kept {
        return Err(unwritable("the paths it names", to));
    }
    Ok(out)
}

/// The directory a file path is in (`.` for a bare name).
fn directory(path: &str) -> PathBuf {
    match Path::new(path).parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn unwritable(what: &str, to: &str) -> Error {
    Error::computation(format!(
        "{to}: could not rewrite {what} of the spec for its new directory; write it beside \
         the source spec"
    ))
}

/// The path from directory `from` to `to`, both absolute and resolved (`identity`).
fn relative(from: &Path, to: &Path) -> PathBuf {
    let common = (from.components().zip(to.components()))
        .take_while(|(x, y)| x == y)
        .count();
    let up = std::iter::repeat_n(Component::ParentDir, from.components().count() - common);
    let mut out: PathBuf = up.chain(to.components().skip(common)).collect();
    if out.as_os_str().is_empty() {
        out.push(".");
    }
    out
}

/// A path as a YAML scalar: plain when it is made of characters that read back as written,
/// double-quoted (JSON's escapes, which YAML shares) otherwise.
fn yaml_scalar(s: &str) -> String {
    let plain = !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '.' | '/' | '-'))
        && !s.starts_with('-');
    if plain {
        s.to_string()
    } else {
        serde_json::to_string(s).unwrap_or_else(|_| format!("{s:?}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path between two resolved directories climbs to their common ancestor.
    #[test]
    fn relative_paths_climb_to_the_common_ancestor() {
        let r = |a: &str, b: &str| relative(Path::new(a), Path::new(b)).display().to_string();
        assert_eq!(r("/w/out", "/w/specs/disc.csv"), "../specs/disc.csv");
        assert_eq!(r("/w", "/w/golden/te.csv"), "golden/te.csv");
        assert_eq!(r("/w/a/b", "/w/c.csv"), "../../c.csv");
    }

    /// Plain, double- and single-quoted scalars are replaced whole, and what follows them (a
    /// comment, the rest of a flow mapping) stays.
    #[test]
    fn a_scalar_is_replaced_whole_in_every_style() {
        for (line, want) in [
            ("file: a.csv  # points\n", "file: NEW  # points\n"),
            ("file: \"a b.csv\"\n", "file: NEW\n"),
            ("file: 'it''s.csv' # x\n", "file: NEW # x\n"),
            ("{file: a.csv, format: csv}\n", "{file: NEW, format: csv}\n"),
        ] {
            let mut text = line.to_string();
            let at = text.find("file").unwrap();
            replace_value(&mut text, at, "NEW");
            assert_eq!(text, want, "{line:?}");
        }
        assert_eq!(yaml_scalar("../golden/te.csv"), "../golden/te.csv");
        assert_eq!(yaml_scalar("a b#c.csv"), "\"a b#c.csv\"");
    }
}
