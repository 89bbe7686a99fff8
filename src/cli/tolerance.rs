//! `cycloid tolerance`: the Monte Carlo of a spec's `tolerances:`, whole or one shard of it,
//! and `cycloid tolerance merge`.

use super::{distinct_outputs, inputs_of, locate, print, write_file, Outcome};
use super::{ToleranceArgs, ToleranceCommand};
use crate::engine::check;
use crate::engine::tolerance::{sensitivity, shard, summary, write, Records, Study};
use crate::error::{Error, ErrorKind, Result};
use crate::files;
use crate::report::terminal::Bar;
use crate::{report, spec};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Largest shard file read, bytes: 16 GiB. A shard holds 9 bytes per sample and limit (the
/// value and its verdict), so this is 10⁹ sample-limits, far beyond a job array's task.
const MAX_SHARD_BYTES: u64 = 16 << 30;

fn invalid(message: String) -> Error {
    Error::new(ErrorKind::InvalidValue, message)
}

/// `--shard I/N`: 0 ≤ I < N, 1 ≤ N ≤ samples.
pub fn parse_shard(text: &str, samples: u64) -> Result<(u64, u64)> {
    let rule = |why: String| {
        invalid(format!(
            "--shard {text}: {why}; a shard is I/N with 0 <= I < N (0-based) and N at most the \
             {samples} samples"
        ))
    };
    let (i, n) = text
        .split_once('/')
        .ok_or_else(|| rule("not of the form I/N".into()))?;
    let (i, n): (u64, u64) = match (i.trim().parse(), n.trim().parse()) {
        (Ok(i), Ok(n)) => (i, n),
        _ => return Err(rule("I and N must be whole numbers".into())),
    };
    if n == 0 || n > samples {
        return Err(rule(format!("N = {n} shards")));
    }
    if i >= n {
        return Err(rule(format!("shard index {i} is not below N = {n}")));
    }
    Ok((i, n))
}

/// The shard of a Slurm job array task: I = SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN (so
/// `--array=0-99` and `--array=1-100` both give I = 0 … 99), N = SLURM_ARRAY_TASK_COUNT. The
/// array must be contiguous (no step, no list): I must come out below N.
fn slurm_shard(samples: u64) -> Result<Option<(u64, u64)>> {
    let var = |name: &str| std::env::var(name).ok();
    let (Some(id), Some(count)) = (var("SLURM_ARRAY_TASK_ID"), var("SLURM_ARRAY_TASK_COUNT"))
    else {
        return Ok(None);
    };
    let number = |name: &str, v: &str| {
        v.trim().parse::<u64>().map_err(|_| {
            invalid(format!(
                "{name}={v}: not a whole number (from the Slurm job array)"
            ))
        })
    };
    let id = number("SLURM_ARRAY_TASK_ID", &id)?;
    let min = match var("SLURM_ARRAY_TASK_MIN") {
        Some(m) => number("SLURM_ARRAY_TASK_MIN", &m)?,
        None => 0,
    };
    let count = number("SLURM_ARRAY_TASK_COUNT", &count)?;
    let i = id.checked_sub(min).ok_or_else(|| {
        invalid(format!(
            "SLURM_ARRAY_TASK_ID {id} is below SLURM_ARRAY_TASK_MIN {min}"
        ))
    })?;
    parse_shard(&format!("{i}/{count}"), samples)
        .map(Some)
        .map_err(|e| {
            invalid(format!(
                "from the Slurm job array (task id {id}, min {min}, count {count}): {}; give the \
                 array as a contiguous range such as --array=0-{}",
                e.message,
                count.saturating_sub(1)
            ))
        })
}

pub fn run(args: ToleranceArgs, out: &mut dyn Write) -> Result<Outcome> {
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
    check::validate(&spec).map_err(|e| locate(e, &spec))?;
    let study = Study::new(&spec, args.samples).map_err(|e| locate(e, &spec))?;
    let samples = study.samples() as u64;
    let shard = match &args.shard {
        Some(s) => Some(parse_shard(s, samples)?),
        None => slurm_shard(samples)?,
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
            let whole = [
                ("--json", outputs.json.is_some()),
                ("--samples-csv", outputs.csv.is_some()),
                ("--report", outputs.report.is_some()),
                ("--sensitivity", args.sensitivity),
            ];
            if let Some((flag, _)) = whole.iter().find(|(_, given)| *given) {
                return Err(Error::new(
                    ErrorKind::Usage,
                    format!(
                        "{flag} needs every sample: give it to `cycloid tolerance merge`, not to \
                         a shard; nothing was written"
                    ),
                ));
            }
            run_shard(&study, shard, file, out)
        }
        (Some((i, n)), None) => Err(Error::new(
            ErrorKind::Usage,
            format!(
                "shard {i}/{n} (from --shard or the Slurm job array) needs --out SHARD_FILE, the \
                 file it writes for `cycloid tolerance merge`; nothing was written"
            ),
        )),
        (None, Some(_)) => Err(Error::new(
            ErrorKind::Usage,
            "--out writes a shard file: give --shard I/N too (or run in a Slurm job array); \
             nothing was written"
                .to_string(),
        )),
        (None, None) => {
            let bar = Bar::with_rate("tolerance study", "samples", samples);
            let records = study.run((0, 1), &bar).map_err(|e| locate(e, &spec))?;
            drop(bar);
            let sens = if args.sensitivity {
                let bar = Bar::with_rate("sensitivities", "parameters", study.params.len() as u64);
                Some(sensitivity::run(&study, &bar).map_err(|e| locate(e, &spec))?)
            } else {
                None
            };
            finish(&study, &records, sens.as_ref(), &outputs, out)
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

/// Print and write what the records of every sample say; the verdict of the failure rate.
fn finish(
    study: &Study,
    records: &Records,
    sens: Option<&sensitivity::Sensitivity>,
    outputs: &Outputs,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let summary = summary::summarise(study, records);
    print(out, &report::tolerance::render(study, &summary, sens))?;
    if let Some(p) = outputs.json {
        write_file(p, &report::tolerance::json(study, &summary, records, sens))?;
    }
    if let Some(p) = outputs.csv {
        write_file(p, &report::tolerance::samples_csv(study, records))?;
    }
    if let Some(dir) = outputs.report {
        let files =
            report::review::tolerance::write(Path::new(dir), study, &summary, records, sens)?;
        print(
            out,
            &format!(
                "design review: {} ({} files)\n",
                Path::new(dir).join("index.html").display(),
                files
            ),
        )?;
    }
    Ok(if summary.passed() {
        Outcome::Passed
    } else {
        Outcome::ChecksFailed
    })
}

/// One shard: its samples' records, written to `file` for `merge`.
fn run_shard(
    study: &Study,
    (i, n): (u64, u64),
    file: &str,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let spec = study.spec;
    let count = crate::engine::tolerance::shard_len(study.samples() as u64, (i, n));
    let bar = Bar::with_rate(&format!("tolerance shard {i}/{n}"), "samples", count);
    let records = study.run((i, n), &bar).map_err(|e| locate(e, spec))?;
    drop(bar);
    let header = shard::Header {
        spec_sha256: shard::spec_hash(&spec.source),
        seed: study.tolerances.seed,
        samples: study.samples() as u64,
        index: i,
        count: n,
        limits: study.limits.len() as u32,
        spec_path: spec.path.clone(),
        spec_text: spec.source.clone(),
    };
    crate::files::write_atomic(Path::new(file), &shard::encode(&header, &records))?;
    print(
        out,
        &format!(
            "cycloid tolerance `{}`: shard {i}/{n} ({count} of {} samples) written to {file}; \
             join the shards with `cycloid tolerance merge`\n",
            spec.name,
            study.samples()
        ),
    )?;
    Ok(Outcome::Passed)
}

/// `merge`: read, check and join the shards, then report as an unsharded run would.
fn run_merge(paths: &[String], outputs: &Outputs, out: &mut dyn Write) -> Result<Outcome> {
    let inputs: Vec<(String, PathBuf)> = paths
        .iter()
        .map(|p| (format!("the shard file {p}"), PathBuf::from(p)))
        .collect();
    distinct_outputs(&inputs, &outputs.paths())?;
    let shards = paths
        .iter()
        .map(|p| {
            // A regular file, bounded: a FIFO or a device would be read without end.
            let bytes = files::read_bytes(Path::new(p), "shard file", MAX_SHARD_BYTES)?;
            shard::decode(p, &bytes)
        })
        .collect::<Result<Vec<_>>>()?;
    let records = shard::merge(paths, &shards)?;
    let h = &shards[0].header;
    let spec = spec::parse(&h.spec_path, &h.spec_text)?;
    let study = Study::new(&spec, Some(h.samples as usize))?;
    if study.limits.len() != h.limits as usize {
        return Err(invalid(format!(
            "{}: the shards hold {} limits, their spec evaluates {}: written by another version \
             of cycloid",
            paths[0],
            h.limits,
            study.limits.len()
        )));
    }
    finish(&study, &records, None, outputs, out)
}

/// `--write-sample K OUT`.
fn write_sample(study: &Study, k: &str, path: &str, out: &mut dyn Write) -> Result<Outcome> {
    let n = study.samples() as u64;
    let k: u64 = k.parse().ok().filter(|&k| k < n).ok_or_else(|| {
        invalid(format!(
            "--write-sample {k}: the sample must be a whole number 0 to {} (the study has {n} \
                 samples)",
            n - 1
        ))
    })?;
    write_file(path, &write::sample_spec(study, k, path)?)?;
    print(
        out,
        &format!("wrote {path}: sample {k}'s deviations as reducer.deviations; replay it with `cycloid check {path}`\n"),
    )?;
    Ok(Outcome::Passed)
}

/// `check --tolerance`: the study of the spec's `tolerances:` as one check, its failure rate
/// against `max_failure_rate`. `spec` is the drawing: with `measured_profile` the caller's
/// other checks run on the disc as built, but a study draws every part, the disc too, from
/// the drawing (as `cycloid tolerance` does), and its line says so.
pub fn check(spec: &spec::Spec) -> Result<check::Check> {
    let study = Study::new(spec, None).map_err(|e| locate(e, spec))?;
    let bar = Bar::with_rate("tolerance study", "samples", study.samples() as u64);
    let records = study.run((0, 1), &bar).map_err(|e| locate(e, spec))?;
    drop(bar);
    let s = summary::summarise(&study, &records);
    Ok(check::Check {
        id: format!(
            "{}/tolerance_failure_rate",
            spec.scenes[study.tolerances.scene].name
        ),
        kind: check::CheckKind::Limit,
        value: s.rate(),
        limit: s.max_failure_rate,
        unit: "",
        bound: crate::model::quantity::Bound::Max,
        passed: s.passed(),
        at: format!(
            "{} of {} samples fail some limit; {} Clopper–Pearson interval [{}, {}]{}",
            s.failures,
            s.samples,
            report::tolerance::percent_label(summary::CONFIDENCE),
            crate::numeric::number(s.interval.0),
            crate::numeric::number(s.interval.1),
            match spec.measured {
                Some(_) => format!("; {}", report::tolerance::MEASURED_NOTE),
                None => String::new(),
            }
        ),
    })
}
