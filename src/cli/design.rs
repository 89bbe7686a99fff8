//! `cycloid design REQUIREMENTS [--out DIR]`: search the design space, print the front, and
//! write its specs, CSV and review page into DIR as one batch; with `--shard I/N --out FILE`
//! (or in a Slurm job array) one shard of the global stage; `cycloid design merge --out DIR
//! SHARD...` the rest of the search from the shards, written as the unsharded run writes it.

use super::args::{DesignArgs, DesignCommand};
use super::output::{distinct_outputs, print, usage, write_file};
use super::shard::{parse_shard, read_shard_files, shard_inputs, slurm_shard};
use super::Outcome;
use crate::engine::commands::{self, DesignRun};
use crate::error::Result;
use crate::files::{self, identity};
use crate::model::requirements::Requirements;
use crate::report::design::Timing;
use crate::report::terminal::Terminal;
use crate::{report, spec};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Largest shard file read, bytes: 64 MiB of requirements text and 1 GiB of evaluations (a
/// million candidates at under 1 KiB each), a bound on what a wrong path makes the merge read.
const MAX_SHARD_BYTES: u64 = files::MAX_INPUT_BYTES + (1 << 30);

pub(super) fn run(args: DesignArgs, out: &mut dyn Write) -> Result<Outcome> {
    if let Some(DesignCommand::Merge { shards, out: dir }) = args.merge {
        return run_merge(&shards, dir.as_deref(), out);
    }
    let path = args.requirements.unwrap_or_default();
    // As `spec::requirements::load`, keeping the text for a shard's header.
    let text = files::read_text(Path::new(&path), "requirements", files::MAX_INPUT_BYTES)?;
    let req = spec::requirements::parse(&path, &text)?;
    let candidates = crate::engine::design_search::global_candidate_count(&req);
    let noun = "candidates of the global stage";
    let shard = match &args.shard {
        Some(s) => Some(parse_shard(s, candidates, noun)?),
        None => slurm_shard(candidates, noun)?,
    };
    let inputs = [(
        format!("the requirements file {path}"),
        PathBuf::from(&path),
    )];
    match (shard, args.out.as_deref()) {
        (Some(shard), Some(file)) => {
            distinct_outputs(&inputs, &[("--out", Some(file))])?;
            run_shard(&req, (&path, &text), (shard, candidates), file, out)
        }
        (Some((i, n)), None) => Err(usage(format!(
            "shard {i}/{n} (from --shard or the Slurm job array) needs --out SHARD_FILE, the \
             file it writes for `cycloid design merge`"
        ))),
        (None, dir) => {
            check_out_dir(dir)?;
            let started = std::time::Instant::now();
            let run = commands::design(&req, &path, &Terminal)?;
            let time = Timing::Whole(started.elapsed().as_secs_f64());
            finish(&req, &run, dir, &time, (&inputs, None), out)
        }
    }
}

/// `--out DIR` names a directory or nothing yet.
fn check_out_dir(dir: Option<&str>) -> Result<()> {
    if let Some(dir) = dir {
        if dir.is_empty() {
            return Err(usage("--out \"\": an empty path names no directory".into()));
        }
        if std::fs::metadata(dir).is_ok_and(|m| !m.is_dir()) {
            return Err(usage(format!(
                "--out {dir} is a file; the designs are written into a directory"
            )));
        }
    }
    Ok(())
}

/// Inputs no output may replace: files by their path, and the requirements text by its SHA-256
/// (a merge's requirements file, whose recorded path is relative to an unknown directory).
type Inputs<'a> = (&'a [(String, PathBuf)], Option<&'a [u8; 32]>);

/// Write the front's files into `out_dir` (never over one of `inputs`) and print the report.
fn finish(
    req: &Requirements,
    run: &DesignRun,
    out_dir: Option<&str>,
    time: &Timing,
    (inputs, requirements_sha256): Inputs,
    out: &mut dyn Write,
) -> Result<Outcome> {
    if let Some(dir) = out_dir {
        let dir = Path::new(dir);
        let checks = commands::front_checks(run, &Terminal)?;
        let mut files: Vec<(String, String)> = run.specs.clone();
        files.extend(report::design::front_reviews(&checks));
        files.push(("front.csv".into(), report::design::csv(req, &run.search)));
        files.extend(report::design::plots(req, &run.search));
        files.push((
            "index.html".into(),
            report::design::page(req, &run.search, time),
        ));
        for (what, input) in inputs {
            let input = identity(input);
            if let Some((name, _)) = files.iter().find(|(n, _)| identity(&dir.join(n)) == input) {
                return Err(usage(format!(
                    "--out {} would overwrite {what} with {name}; give another directory",
                    dir.display()
                )));
            }
        }
        if let Some(hash) = requirements_sha256 {
            let holds_it = |name: &str| {
                files::read_text(&dir.join(name), "output", files::MAX_INPUT_BYTES)
                    .is_ok_and(|t| crate::engine::shard_file::text_hash(&t) == *hash)
            };
            if let Some((name, _)) = files.iter().find(|(n, _)| holds_it(n)) {
                return Err(usage(format!(
                    "--out {} would overwrite {name}, which holds the requirements the shards \
                     were made from; give another directory",
                    dir.display()
                )));
            }
        }
        report::review::shell::write_files(dir, &files)?;
    }
    print(
        out,
        &report::design::render(req, &run.search, out_dir, time),
    )?;
    Ok(Outcome::of(run.feasible()))
}

/// One shard `(i, n)` of the global stage's `all` candidates, written to `file` for `merge`.
fn run_shard(
    req: &Requirements,
    (path, text): (&str, &str),
    ((i, n), all): ((u64, u64), u64),
    file: &str,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let bytes = commands::design_shard(req, path, text, (i, n), &Terminal)?;
    write_file(file, &bytes)?;
    let count = crate::engine::design_search::shard::shard_len(all, (i, n));
    print(
        out,
        &format!(
            "cycloid design `{}`: shard {i}/{n} ({count} of the global stage's {all} \
             candidates) written to {file}; finish the search with `cycloid design merge`\n",
            req.name,
        ),
    )?;
    Ok(Outcome::Passed)
}

/// `merge`: read, check and join the shards, finish the search, and report and write as the
/// unsharded run would.
fn run_merge(paths: &[String], out_dir: Option<&str>, out: &mut dyn Write) -> Result<Outcome> {
    check_out_dir(out_dir)?;
    let started = std::time::Instant::now();
    let files = read_shard_files(paths, MAX_SHARD_BYTES)?;
    let merged = commands::merge_design_shards(&files)?;
    let mut inputs = shard_inputs(paths);
    let named = format!(
        "the requirements file {} the shards name",
        merged.requirements_path
    );
    // The recorded path is relative to where the shards ran: also beside each shard.
    let beside = paths
        .iter()
        .map(|p| Path::new(p).parent().unwrap_or(Path::new("")));
    for dir in std::iter::once(Path::new("")).chain(beside) {
        inputs.push((named.clone(), dir.join(&merged.requirements_path)));
    }
    // The requirements outlive the merge the evaluations are moved into.
    let (requirements, shards) = (merged.requirements.clone(), merged.shards);
    let hash = merged.requirements_sha256;
    let run = commands::design_from_shards(merged, &Terminal)?;
    let time = Timing::Merged {
        seconds: started.elapsed().as_secs_f64(),
        shards,
    };
    finish(
        &requirements,
        &run,
        out_dir,
        &time,
        (&inputs, Some(&hash)),
        out,
    )
}
