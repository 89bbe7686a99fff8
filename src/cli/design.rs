//! `cycloid design REQUIREMENTS [--out DIR]`: search the design space, print the front, and
//! write its specs, CSV and review page into DIR as one batch.

use super::output::print;
use super::Outcome;
use crate::engine::commands;
use crate::error::{Error, ErrorKind, Result};
use crate::files::{identity, Batch};
use crate::report::terminal::Terminal;
use crate::{report, spec};
use std::io::Write;
use std::path::Path;

pub(super) fn run(path: &str, out_dir: Option<&str>, out: &mut dyn Write) -> Result<Outcome> {
    let req = spec::requirements::load(path)?;
    let usage = |m: String| Error::new(ErrorKind::Usage, format!("{m}; nothing was written"));
    if let Some(dir) = out_dir {
        if dir.is_empty() {
            return Err(usage("--out \"\": an empty path names no directory".into()));
        }
        if std::fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
            return Err(usage(format!(
                "--out {dir} is a file; the designs are written into a directory"
            )));
        }
    }
    let started = std::time::Instant::now();
    let run = commands::design(&req, path, &Terminal)?;
    let seconds = started.elapsed().as_secs_f64();
    if let Some(dir) = out_dir {
        let dir = Path::new(dir);
        let mut files: Vec<(String, String)> = run.specs.clone();
        files.push(("front.csv".into(), report::design::csv(&req, &run.search)));
        files.extend(report::design::plots(&req, &run.search));
        files.push((
            "index.html".into(),
            report::design::page(&req, &run.search, seconds),
        ));
        let input = identity(Path::new(path));
        if let Some((name, _)) = files.iter().find(|(n, _)| identity(&dir.join(n)) == input) {
            return Err(usage(format!(
                "--out {} would overwrite the requirements file with {name}; give another directory",
                dir.display()
            )));
        }
        std::fs::create_dir_all(dir).map_err(|e| Error::io(&dir.display().to_string(), e))?;
        let mut batch = Batch::new();
        for (name, text) in &files {
            batch.add(&dir.join(name), text.as_bytes())?;
        }
        batch.commit()?;
    }
    print(
        out,
        &report::design::render(&req, &run.search, out_dir, seconds),
    )?;
    Ok(if run.feasible() {
        Outcome::Passed
    } else {
        Outcome::ChecksFailed
    })
}
