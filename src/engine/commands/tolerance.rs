//! `tolerance`: the Monte Carlo of a spec's `tolerances:`, whole, as one shard of a split run,
//! or merged from the shards; and the study as one check of `check --tolerance`.

use crate::engine::limit::passes;
use crate::engine::tolerance::sensitivity::{self, Sensitivity};
use crate::engine::tolerance::summary::{self, Summary};
use crate::engine::tolerance::{shard, shard_len, Records, ToleranceStudy};
use crate::engine::verdict::{Check, CheckKind, Evidence};
use crate::error::{Error, Result};
use crate::model::quantity::Bound;
use crate::progress::{Phase, Progress};
use crate::spec::Spec;

/// A whole study: every sample's records, their summary, and the sensitivities if asked for.
pub struct ToleranceRun<'a> {
    pub study: ToleranceStudy<'a>,
    pub records: Records,
    pub summary: Summary,
    pub sensitivity: Option<Sensitivity>,
}

/// Run the whole study of `spec` (`samples` in place of the spec's count), and the
/// sensitivities when `sensitivity` is set.
///
/// ```
/// let text = std::fs::read_to_string("specs/reducer.yaml").unwrap()
///     + "tolerances: {scene: rated, equidistant_mm: 0.002, max_failure_rate: 0.5}\n";
/// let spec = cycloid::spec::parse("reducer.yaml", &text)?;
/// let run = cycloid::tolerance(&spec, Some(50), false, &cycloid::progress::Silent)?;
/// assert_eq!(run.summary.samples, 50);
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn tolerance<'a>(
    spec: &'a Spec,
    samples: Option<usize>,
    sensitivity: bool,
    progress: &dyn Progress,
) -> Result<ToleranceRun<'a>> {
    let study = ToleranceStudy::new(spec, samples).map_err(|e| spec.locate(e))?;
    let records = samples_of(&study, (0, 1), "tolerance study", progress)?;
    let sensitivity = match sensitivity {
        true => {
            let phase = Phase::slow("sensitivities", "parameters", study.params.len() as u64);
            let heard = progress.phase(&phase);
            Some(sensitivity::run(&study, &*heard).map_err(|e| spec.locate(e))?)
        }
        false => None,
    };
    let summary = summary::summarise(&study, &records);
    Ok(ToleranceRun {
        study,
        records,
        summary,
        sensitivity,
    })
}

/// The samples of shard `(i, n)` of a study, heard as `what`.
fn samples_of(
    study: &ToleranceStudy,
    (i, n): (u64, u64),
    what: &str,
    progress: &dyn Progress,
) -> Result<Records> {
    let count = shard_len(study.samples() as u64, (i, n));
    let phase = Phase::slow(what, "samples", count);
    let heard = progress.phase(&phase);
    study.run((i, n), &*heard).map_err(|e| study.spec.locate(e))
}

/// Shard `(i, n)` of `study` (0-based: the samples k with k mod n = i), encoded as the shard
/// file that `merge_shards` reads.
///
/// ```
/// use cycloid::engine::tolerance::ToleranceStudy;
/// use cycloid::progress::Silent;
/// let text = std::fs::read_to_string("specs/reducer.yaml").unwrap()
///     + "tolerances: {scene: rated, equidistant_mm: 0.002, samples: 20, max_failure_rate: 0.5}\n";
/// let spec = cycloid::spec::parse("reducer.yaml", &text)?;
/// let study = ToleranceStudy::new(&spec, None)?;
/// let shards: Vec<(String, Vec<u8>)> = (0..2)
///     .map(|i| Ok((format!("shard{i}"), cycloid::tolerance_shard(&study, (i, 2), &Silent)?)))
///     .collect::<cycloid::Result<_>>()?;
/// // The merged shards are the unsharded run's records, bit for bit.
/// let merged = cycloid::merge_shards(&shards)?;
/// let whole = cycloid::tolerance(&spec, None, false, &Silent)?;
/// assert_eq!(merged.records.values, whole.records.values);
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn tolerance_shard(
    study: &ToleranceStudy,
    (i, n): (u64, u64),
    progress: &dyn Progress,
) -> Result<Vec<u8>> {
    let spec = study.spec;
    let what = format!("tolerance shard {i}/{n}");
    let records = samples_of(study, (i, n), &what, progress)?;
    let header = shard::Header {
        text_sha256: shard::spec_hash(&spec.source),
        seed: study.tolerances.seed,
        items: study.samples() as u64,
        index: i,
        count: n,
        text_path: spec.path.clone(),
        text: spec.source.clone(),
    };
    Ok(shard::encode(&header, study.limits.len() as u32, &records))
}

/// The shards of one run joined: the spec they carry and every sample's records.
pub struct Merged {
    pub spec: Spec,
    pub records: Records,
    samples: u64,
    limits: usize,
    first: String,
    /// The file each shard was read from, by shard index (as many as the run has shards).
    files: Vec<String>,
}

impl Merged {
    /// The study the shards belong to, as an unsharded run of their spec sets it up.
    pub fn study(&self) -> Result<ToleranceStudy<'_>> {
        let study = ToleranceStudy::new(&self.spec, Some(self.samples as usize))?;
        if study.limits.len() != self.limits {
            return Err(Error::invalid_value(format!(
                "{}: the shards hold {} limits, their spec evaluates {}: written by another \
                 version of cycloid",
                self.first,
                self.limits,
                study.limits.len()
            )));
        }
        self.verdicts_follow(&study)?;
        Ok(study)
    }

    /// Every verdict of the shards is the one its value gives against the spec's limit: a
    /// shard altered consistently (its checksum written again) still cannot pass a value
    /// beyond its limit.
    fn verdicts_follow(&self, study: &ToleranceStudy) -> Result<()> {
        let (l, count) = (study.limits.len(), self.files.len() as u64);
        let cells = self.records.values.iter().zip(&self.records.passed);
        for (cell, (&value, &passed)) in cells.enumerate() {
            let (def, limit) = study.limits[cell % l];
            let shard = (cell / l) as u64 % count;
            if passes(value, limit, def.bound) != passed {
                return Err(Error::invalid_value(format!(
                    "{}: shard {} of {} holds sample {} with `{}` = {value} marked {}, which its \
                     limit {limit} does not give: the shard was altered",
                    self.files[shard as usize],
                    shard,
                    count,
                    cell / l,
                    def.key,
                    if passed { "passed" } else { "failed" }
                )));
            }
        }
        Ok(())
    }
}

/// Check and join the shard files `(name, bytes)` of one run.
pub fn merge_shards(files: &[(String, Vec<u8>)]) -> Result<Merged> {
    let shards = files
        .iter()
        .map(|(name, bytes)| shard::decode(name, bytes))
        .collect::<Result<Vec<_>>>()?;
    let names: Vec<String> = files.iter().map(|(name, _)| name.clone()).collect();
    let records = shard::merge(&names, &shards)?;
    // `merge` checked that the shards hold each index below the count once. The spec is shard
    // 0's, whatever the order the files are given in: shards of one spec may name it by two
    // spellings of its path (its text and hash are one), and the merged study must not depend
    // on which file is named first.
    let zero = shards.iter().find(|s| s.header.index == 0);
    let h = &zero.unwrap_or(&shards[0]).header;
    let mut files = vec![String::new(); h.count as usize];
    for (s, name) in shards.iter().zip(&names) {
        files[s.header.index as usize] = name.clone();
    }
    Ok(Merged {
        spec: crate::spec::parse(&h.text_path, &h.text)?,
        records,
        samples: h.items,
        limits: shards[0].limits as usize,
        first: names[0].clone(),
        files,
    })
}

/// `check --tolerance`: the study of the spec's `tolerances:` as one check, its failure rate
/// against `max_failure_rate`. `spec` is the drawing: with `measured_profile` the other checks
/// run on the disc as built, but a study draws every part, the disc too, from the drawing (as
/// `cycloid tolerance` does), and its line says so.
pub fn failure_rate_check(spec: &Spec, progress: &dyn Progress) -> Result<Check> {
    let run = tolerance(spec, None, false, progress)?;
    let s = &run.summary;
    Ok(Check {
        id: format!(
            "{}/tolerance_failure_rate",
            spec.scenes[run.study.tolerances.scene].name
        ),
        kind: CheckKind::Limit,
        value: s.rate(),
        limit: s.max_failure_rate,
        unit: "",
        bound: Bound::Max,
        passed: s.passed(),
        at: Evidence::FailureRate {
            failures: s.failures,
            samples: s.samples,
            confidence: summary::CONFIDENCE,
            interval: s.interval,
            measured: spec.measured.is_some(),
            max_failure_rate: s.max_failure_rate,
        },
    })
}
