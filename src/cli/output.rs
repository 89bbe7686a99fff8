//! Where the commands write: output paths checked against every input before anything is
//! written, files written atomically, and text for a person printed with its control
//! characters escaped.

use crate::engine::golden::{legacy_meta_path, meta_path};
use crate::error::{Error, ErrorKind, Result};
use crate::{files, spec};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Write an output file atomically (a temporary file renamed into place).
pub(super) fn write_file(path: &str, contents: impl AsRef<[u8]>) -> Result<()> {
    files::write_atomic(Path::new(path), contents.as_ref())
}

/// A usage error `m`, which says that nothing was written.
pub(super) fn usage(m: String) -> Error {
    Error::new(ErrorKind::Usage, format!("{m}; nothing was written"))
}

/// Refuse, before anything is written, outputs that would destroy an input or one another or
/// could not be written: an empty path, a file in a folder that does not exist, an output at
/// the path of one of `inputs` (what it is, its path), or two outputs at one path. `outputs`
/// are (option, path if given); a `--report` directory also claims its `index.html`.
pub(super) fn distinct_outputs(
    inputs: &[(String, PathBuf)],
    outputs: &[(&str, Option<&str>)],
) -> Result<()> {
    let mut claimed: Vec<(String, PathBuf)> = inputs
        .iter()
        .map(|(what, p)| (what.clone(), files::identity(p)))
        .collect();
    for &(flag, path) in outputs {
        let Some(path) = path else { continue };
        if path.is_empty() {
            return Err(usage(format!("{flag} \"\": an empty path names no file")));
        }
        // The kind of target each output needs, checked before any work is done.
        let meta = std::fs::metadata(path).ok();
        if flag == "--report" && meta.as_ref().is_some_and(|m| !m.is_dir()) {
            return Err(usage(format!(
                "{flag} {path} is a file; a design review is a directory: give a new or existing \
                 directory"
            )));
        }
        if flag != "--report" && meta.as_ref().is_some_and(|m| m.is_dir()) {
            return Err(usage(format!(
                "{flag} {path} is a directory; give a file path"
            )));
        }
        let mut ids = vec![files::identity(Path::new(path))];
        if flag == "--report" {
            ids.push(ids[0].join("index.html"));
        }
        for id in ids {
            let clash = |c: &PathBuf| *c == id || (flag == "--report" && in_review(&id, c));
            if let Some((what, _)) = claimed.iter().find(|(_, c)| clash(c)) {
                return Err(usage(format!(
                    "{flag} {path} would overwrite {what}; give another path"
                )));
            }
            claimed.push((format!("the output of {flag}"), id));
        }
    }
    // A file goes into a folder that exists (a review makes its own): found only when it is
    // written, after the outputs before it.
    for &(flag, path) in outputs.iter().filter(|o| o.0 != "--report") {
        let Some(path) = path else { continue };
        let folder = Path::new(path)
            .parent()
            .filter(|f| !f.as_os_str().is_empty());
        if let Some(f) = folder.filter(|f| !f.is_dir()) {
            return Err(usage(format!(
                "{flag} {path}: the folder {} does not exist; create it or give another path",
                f.display()
            )));
        }
    }
    Ok(())
}

/// Whether `file` is one a review written to `dir` may replace: its pages and plots are
/// `.html` and `.svg` files directly in it.
fn in_review(dir: &Path, file: &Path) -> bool {
    file.parent() == Some(dir)
        && file
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("svg") || e.eq_ignore_ascii_case("html"))
}

/// Every file a spec's run reads or owns, which no output may replace: the spec, each golden
/// file with its metadata, and the measured points. Before the spec loads (`spec` None) only
/// the spec's own path is known.
pub(super) fn inputs_of(spec_path: &str, spec: Option<&spec::Spec>) -> Vec<(String, PathBuf)> {
    let mut inputs = vec![("the spec".to_string(), PathBuf::from(spec_path))];
    let Some(spec) = spec else { return inputs };
    for g in &spec.golden {
        inputs.push((format!("the golden file of {}", g.key), g.path.clone()));
        for meta in [meta_path(&g.path), legacy_meta_path(&g.path)] {
            inputs.push((format!("the metadata of {}", g.key), meta));
        }
    }
    if let Some(m) = &spec.measured {
        inputs.push(("the measured points".to_string(), PathBuf::from(&m.path)));
    }
    inputs
}

/// Write a spec that `edit` made from the one at `from` to `path`, its relative paths (goldens,
/// measured points, `golden_root`) rewritten so that it checks from where it is written.
pub(super) fn write_spec(from: &str, path: &str, text: &str) -> Result<()> {
    write_file(path, &spec::relocate::relocate(text, from, path)?)
}

/// Print text for a person, its control characters escaped (names come from the spec).
pub(super) fn print(out: &mut dyn Write, text: &str) -> Result<()> {
    print_keeping(out, text, &[])
}

/// `print`, letting the sequences in `keep` (the tool's own colours) through.
pub(super) fn print_keeping(out: &mut dyn Write, text: &str, keep: &[&str]) -> Result<()> {
    out.write_all(crate::error::printable(text, keep).as_bytes())
        .map_err(stdout_error)
}

/// A failed write to standard output; a reader that closed it (`| head`) is `OutputClosed`.
pub(super) fn stdout_error(e: std::io::Error) -> Error {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        Error::new(ErrorKind::OutputClosed, "standard output was closed")
    } else {
        Error::io("<stdout>", e)
    }
}

/// Write a design review's `pages` into `dir` as one batch, and say where it was written.
pub(super) fn write_review(
    out: &mut dyn Write,
    dir: &str,
    pages: &[(String, String)],
) -> Result<()> {
    crate::report::review::shell::write_files(Path::new(dir), pages)?;
    let (index, files) = (Path::new(dir).join("index.html"), pages.len());
    let line = format!("design review: {} ({files} files)\n", index.display());
    print(out, &line)
}
