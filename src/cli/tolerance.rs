//! `cycloid tolerance`: the Monte Carlo of a spec's `tolerances:`, whole or one shard of it,
//! and `cycloid tolerance merge`.

use super::args::{ToleranceArgs, ToleranceCommand};
use super::output::write_spec;
use super::output::{distinct_outputs, inputs_of, print, usage, write_file, write_review};
use super::shard::{parse_shard, read_shard_files, shard_inputs, slurm_shard};
use super::Outcome;
use crate::engine::commands;
use crate::engine::tolerance::sensitivity::Sensitivity;
use crate::engine::tolerance::summary::Summary;
use crate::engine::tolerance::Records;
use crate::engine::tolerance::ToleranceStudy;
use crate::error::{Error, Result};
use crate::report::terminal::Terminal;
use crate::{report, spec};
use std::io::Write;

/// Largest shard file read, bytes: the records of the most sample-limits a study holds (9
/// bytes each) and a spec of the largest input size, with room for the header.
const MAX_SHARD_BYTES: u64 =
    (crate::engine::tolerance::MAX_SAMPLE_LIMITS as u64) * 9 + 2 * crate::files::MAX_INPUT_BYTES;

pub(super) fn run(args: ToleranceArgs, out: &mut dyn Write) -> Result<Outcome> {
    if let Some(ToleranceCommand::Merge {
        shards,
        json,
        samples_csv,
        report,
    }) = args.merge
    {
        let outputs = Outputs {
            json: json.as_deref(),
            csv: samples_csv.as_deref(),
            report: report.as_deref(),
        };
        return run_merge(&shards, &outputs, out);
    }
    let path = args.spec.unwrap_or_default();
    let spec = spec::load(&path)?;
    let study = ToleranceStudy::new(&spec, args.samples).map_err(|e| spec.locate(e))?;
    let samples = study.samples() as u64;
    let shard = match &args.shard {
        Some(s) => Some(parse_shard(s, samples, "samples")?),
        None => slurm_shard(samples, "samples")?,
    };
    let sample_out = args.write_sample.as_ref().map(|v| v[1].as_str());
    let outputs = Outputs {
        json: args.json.as_deref(),
        csv: args.samples_csv.as_deref(),
        report: args.report.as_deref(),
    };
    let mut claimed = outputs.paths().to_vec();
    claimed.extend([
        ("--out", args.out.as_deref()),
        ("--write-sample", sample_out),
    ]);
    distinct_outputs(&inputs_of(&path, Some(&spec)), &claimed)?;
    if let Some(v) = &args.write_sample {
        return write_sample(&study, &v[0], &v[1], out);
    }
    match (shard, &args.out) {
        (Some(shard), Some(file)) => {
            let whole = outputs.paths().map(|(flag, path)| (flag, path.is_some()));
            let mut whole = whole
                .into_iter()
                .chain([("--sensitivity", args.sensitivity)]);
            if let Some((flag, _)) = whole.find(|(_, given)| *given) {
                // The sensitivities are derivatives about the nominal reducer, not a sum over
                // samples: an unsharded run computes them, and a merge does not.
                let instead = match flag {
                    "--sensitivity" => {
                        "run it without --shard (`cycloid tolerance SPEC \
                         --sensitivity`: derivatives about the nominal reducer, \
                         whatever the samples)"
                    }
                    _ => "give it to `cycloid tolerance merge`",
                };
                return Err(usage(format!("{flag} is not for a shard: {instead}")));
            }
            run_shard(&study, shard, file, out)
        }
        (Some((i, n)), None) => Err(usage(format!(
            "shard {i}/{n} (from --shard or the Slurm job array) needs --out SHARD_FILE, the \
             file it writes for `cycloid tolerance merge`"
        ))),
        (None, Some(_)) => Err(usage(
            "--out writes a shard file: give --shard I/N too (or run in a Slurm job array)".into(),
        )),
        (None, None) => {
            let run = commands::tolerance(&spec, args.samples, args.sensitivity, &Terminal)?;
            let sens = run.sensitivity.as_ref();
            finish(&run.study, &run.records, &run.summary, sens, &outputs, out)
        }
    }
}

/// Where a whole study's outputs go.
struct Outputs<'a> {
    json: Option<&'a str>,
    csv: Option<&'a str>,
    report: Option<&'a str>,
}

impl Outputs<'_> {
    fn paths(&self) -> [(&'static str, Option<&str>); 3] {
        [
            ("--json", self.json),
            ("--samples-csv", self.csv),
            ("--report", self.report),
        ]
    }
}

/// Print and write what the records of every sample of a whole study say, with their summary
/// and the sensitivities, if computed; the verdict of the failure rate.
fn finish(
    study: &ToleranceStudy,
    records: &Records,
    summary: &Summary,
    sens: Option<&Sensitivity>,
    outputs: &Outputs,
    out: &mut dyn Write,
) -> Result<Outcome> {
    print(
        out,
        &report::tolerance::render(study, summary, records, sens),
    )?;
    if let Some(p) = outputs.json {
        write_file(p, &report::tolerance::json(study, summary, records, sens)?)?;
    }
    if let Some(p) = outputs.csv {
        write_file(p, report::tolerance::samples_csv(study, records))?;
    }
    if let Some(dir) = outputs.report {
        let pages = report::review::tolerance::render(study, summary, records, sens);
        write_review(out, dir, &pages)?;
    }
    Ok(Outcome::of(summary.passed()))
}

/// One shard: its samples' records, written to `file` for `merge`.
fn run_shard(
    study: &ToleranceStudy,
    (i, n): (u64, u64),
    file: &str,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let bytes = commands::tolerance_shard(study, (i, n), &Terminal)?;
    write_file(file, &bytes)?;
    let count = crate::engine::tolerance::shard_len(study.samples() as u64, (i, n));
    print(
        out,
        &format!(
            "cycloid tolerance `{}`: shard {i}/{n} ({count} of {} samples) written to {file}; \
             join the shards with `cycloid tolerance merge`\n",
            study.spec.name,
            study.samples()
        ),
    )?;
    Ok(Outcome::Passed)
}

/// `merge`: read, check and join the shards, then report as an unsharded run would.
fn run_merge(paths: &[String], outputs: &Outputs, out: &mut dyn Write) -> Result<Outcome> {
    let mut inputs = shard_inputs(paths);
    distinct_outputs(&inputs, &outputs.paths())?;
    let files = read_shard_files(paths, MAX_SHARD_BYTES)?;
    let merged = commands::merge_shards(&files)?;
    // The shards name their spec and, through it, its goldens and measured points: none of
    // them may be replaced either.
    inputs.extend(inputs_of(&merged.spec.path, Some(&merged.spec)));
    distinct_outputs(&inputs, &outputs.paths())?;
    let study = merged.study()?;
    let summary = crate::engine::tolerance::summary::summarise(&study, &merged.records);
    finish(&study, &merged.records, &summary, None, outputs, out)
}

/// `--write-sample K OUT`.
fn write_sample(
    study: &ToleranceStudy,
    k: &str,
    path: &str,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let n = study.samples() as u64;
    let k: u64 = k.parse().ok().filter(|&k| k < n).ok_or_else(|| {
        Error::invalid_value(format!(
            "--write-sample {k}: the sample must be a whole number 0 to {} (the study has {n} \
             samples)",
            n - 1
        ))
    })?;
    let spec = study.spec;
    let deviations = study.deviations(&study.draw(k));
    // The sample is the drawing's parts as drawn: a measured disc would replace the drawing's
    // in the replay (`check` runs on the disc as built), so the written spec has none.
    let (source, without) = match &spec.measured {
        Some(m) => (
            spec::edit::without_measured_profile(&spec.source, path)?,
            format!(
                ", without the measured profile `{}` (the sample is drawn from the drawing)",
                m.path
            ),
        ),
        None => (spec.source.clone(), String::new()),
    };
    let text = spec::edit::with_deviations(&source, &spec.path, &deviations, path)?;
    let text = report::tolerance::sample_header(study, k) + &text;
    write_spec(&spec.path, path, &text)?;
    print(
        out,
        &format!("wrote {path}: sample {k}'s deviations as reducer.deviations{without}; replay it with `cycloid check {path}`\n"),
    )?;
    Ok(Outcome::Passed)
}
