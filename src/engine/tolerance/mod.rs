//! The tolerance Monte Carlo (`cycloid tolerance`): sample k draws every toleranced part's
//! deviation from (seed, k) alone (`draw`), runs the study's scene on the as-built reducer
//! with the exact engine and evaluates every limit of the spec on it (`verdict::evaluate`, the
//! code path of `check`). The per-sample limit values are the study's records; what the
//! report says of them (quantiles, failure rates with Clopper–Pearson intervals, the worst
//! samples) is `summary`, computed the same way from one process's records or from merged
//! shards (`shard`), so that any split of the samples gives the same report, bit for bit.

pub mod draw;
pub mod sensitivity;
pub mod shard;
pub mod stats;
pub mod summary;

use crate::engine::{scene, verdict};
use crate::error::{Error, Result};
use crate::model::quantity::LimitDef;
use crate::model::tolerances::{self as tol, Parameter, PartTolerances};
use crate::model::{Deviations, Plan};
use crate::progress::Progress;
use crate::spec::Spec;

/// One tolerance study of a spec: what is drawn, what runs, what is judged.
#[derive(Debug, Clone)]
pub struct ToleranceStudy<'a> {
    pub spec: &'a Spec,
    pub tolerances: PartTolerances,
    /// The drawn parameters, in the draw order ([`model::tolerances::parameters`](crate::model::tolerances::parameters)).
    pub params: Vec<Parameter>,
    /// The spec's limits the scene evaluates, in the order of `verdict::evaluate`: (definition,
    /// bound value).
    pub limits: Vec<(&'static LimitDef, f64)>,
    pub plan: Plan,
}

/// Per-sample records of some samples: `values[s·L + l]` is limit l's quantity in the s-th
/// recorded sample, `passed` its verdict (L = the study's limits).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Records {
    pub values: Vec<f64>,
    pub passed: Vec<bool>,
}

impl Records {
    /// Sample k's values, one per limit (`limits` of them).
    pub fn row(&self, k: u64, limits: usize) -> &[f64] {
        let k = k as usize;
        &self.values[k * limits..(k + 1) * limits]
    }

    /// Limit l's values over the samples, in sample order (`limits` per sample).
    pub fn column(&self, l: usize, limits: usize) -> impl Iterator<Item = f64> + '_ {
        self.values.iter().skip(l).step_by(limits).copied()
    }
}

impl<'a> ToleranceStudy<'a> {
    /// The study of `spec`'s `tolerances:` with `samples` samples (the spec's unless given).
    pub fn new(spec: &'a Spec, samples: Option<usize>) -> Result<ToleranceStudy<'a>> {
        let mut tolerances = spec.tolerances.clone().ok_or_else(|| {
            Error::invalid_value(format!(
                "{}: the spec has no `tolerances:` section; add `tolerances: {{scene: NAME, \
                 max_failure_rate: 0.0027, roller_radial_mm: 0.005}}` (bands in mm)",
                spec.path
            ))
        })?;
        if let Some(n) = samples {
            tolerances.samples = crate::spec::tolerances::sample_count(n as i128)
                .map_err(|m| Error::invalid_value(format!("--samples {m}")))?;
        }
        let d = &spec.design;
        let params = tol::parameters(&tolerances, d.rollers, d.pins.count, d.discs);
        let scene = &spec.scenes[tolerances.scene];
        let plan = scene::plan(spec, scene, scene::Writes::default());
        let limits: Vec<_> = (verdict::limits_for(&spec.limits, &plan).into_iter())
            .map(|l| (l.def, l.value))
            .collect();
        if limits.is_empty() {
            return Err(Error::invalid(
                "tolerances.scene",
                format!(
                    "scene `{}` evaluates none of the spec's limits: a study judges the samples by \
                     the limits their scene computes; set a limit of what it computes or choose \
                     another scene",
                    scene.name
                ),
            ));
        }
        held_in_memory(tolerances.samples, limits.len(), samples.is_some())?;
        Ok(ToleranceStudy {
            spec,
            tolerances,
            params,
            limits,
            plan,
        })
    }

    /// What a reader of the study must be told besides its numbers: the samples whose crank
    /// is longer than the pin holes allow preload every pin ([`scene::Note::PinsPreloaded`],
    /// at the largest eccentricity drawn).
    pub fn notes(&self) -> Vec<scene::Note> {
        let scene = &self.spec.scenes[self.tolerances.scene];
        let largest = self.tolerances.largest_draw_mm(tol::Kind::Eccentricity);
        let preload = scene::pins_preloaded(&self.spec.design, (scene, &self.plan), largest, true);
        preload.into_iter().collect()
    }

    pub fn samples(&self) -> usize {
        self.tolerances.samples
    }

    /// The drawn values of sample k (`draw::sample`).
    pub fn draw(&self, k: u64) -> Vec<f64> {
        draw::sample(&self.tolerances, &self.params, k)
    }

    /// The as-built state of drawn (or chosen) parameter values.
    pub fn deviations(&self, values: &[f64]) -> Deviations {
        let d = &self.spec.design;
        tol::deviations(&self.params, values, (d.rollers, d.pins.count, d.discs))
    }

    /// The limits' values and verdicts of the reducer built with `values`: the scene run on
    /// the deviated design, judged by `verdict::evaluate`. `what` names the state in errors.
    pub fn evaluate(&self, values: &[f64], what: &str) -> Result<(Vec<f64>, Vec<bool>)> {
        let spec = self.spec;
        let mut design = spec.design.clone();
        design.deviations = self.deviations(values);
        let context = |e: Error| Error {
            message: format!("{what}: {}", e.message),
            ..e
        };
        crate::spec::deviations::check(&design, &spec.modification).map_err(context)?;
        let scene = &spec.scenes[self.tolerances.scene];
        let result = scene::run_design(
            &design,
            &spec.modification,
            (scene, &self.plan),
            &scene::RunOptions::for_spec(spec),
        )
        .map_err(context)?;
        let summaries = crate::engine::summary::summarise(std::slice::from_ref(&result));
        let checks = verdict::evaluate(spec, &summaries).map_err(context)?;
        let mut values = Vec::with_capacity(self.limits.len());
        let mut passed = Vec::with_capacity(self.limits.len());
        for (def, _) in &self.limits {
            let c = checks.iter().find(|c| c.name() == def.key).ok_or_else(|| {
                Error::computation(format!("{what}: no value of `limits.{}`", def.key))
            })?;
            if !c.value.is_finite() {
                return Err(Error::computation(format!(
                    "{what}: `{}` is {} ({:?})",
                    def.quantity.key, c.value, c.at
                )));
            }
            values.push(c.value);
            passed.push(c.passed);
        }
        Ok((values, passed))
    }

    /// The records of the samples k ≡ `shard.0` (mod `shard.1`), in increasing k, in parallel;
    /// `progress` (the caller's phase) hears of each sample done. The first error (in k order)
    /// is the error.
    pub fn run(&self, shard: (u64, u64), progress: &dyn Progress) -> Result<Records> {
        use rayon::prelude::*;
        let rows = shard_len(self.samples() as u64, shard);
        let cells = rows as usize * self.limits.len();
        let mut records = Records {
            values: Vec::with_capacity(cells),
            passed: Vec::with_capacity(cells),
        };
        // In blocks, so that what is held besides the records stays bounded whatever the
        // sample count; within a block the samples run in parallel, and blocks in k order.
        for block in (0..rows).step_by(RUN_BLOCK) {
            let each: Vec<Result<(Vec<f64>, Vec<bool>)>> = (block
                ..rows.min(block + RUN_BLOCK as u64))
                .into_par_iter()
                .map(|r| {
                    let k = shard.0 + r * shard.1;
                    // An error names the sample and how to replay it.
                    let replay = format!("sample {k} (replay it with --write-sample {k} OUT)");
                    let r = self.evaluate(&self.draw(k), &replay);
                    progress.advance(1);
                    r
                })
                .collect();
            for r in each {
                let (v, p) = r?;
                records.values.extend(v);
                records.passed.extend(p);
            }
        }
        Ok(records)
    }
}

/// Samples evaluated in parallel at a time by `ToleranceStudy::run`.
const RUN_BLOCK: usize = 1 << 14;

/// Most sample-limits one study holds (2²⁸): its records take 9 bytes each (2.4 GB), and the
/// summary sorts one limit's values at a time (8 bytes each) beside them. A merge holds every
/// sample of the study, so the bound is on the whole study, sharded or not.
pub const MAX_SAMPLE_LIMITS: usize = 1 << 28;

/// "1 limit", "3 limits": a count of a study's limits as a message says it.
pub(super) fn limits_counted(limits: usize) -> String {
    format!("{limits} limit{}", if limits == 1 { "" } else { "s" })
}

/// A study of `samples` samples judged by `limits` limits fits the records one process holds;
/// else the error names the bound (`flag`: the count came from `--samples`).
fn held_in_memory(samples: usize, limits: usize, flag: bool) -> Result<()> {
    if samples.saturating_mul(limits) <= MAX_SAMPLE_LIMITS {
        return Ok(());
    }
    let e = Error::invalid_value(format!(
        "{samples} samples × {} are {} sample-limits, beyond the \
         {MAX_SAMPLE_LIMITS} one study holds (9 bytes each, 2.4 GB, held whole by a run \
         and by a merge): at most {} samples with these limits",
        limits_counted(limits),
        samples as u128 * limits as u128,
        MAX_SAMPLE_LIMITS / limits
    ));
    Err(match flag {
        true => Error {
            message: format!("--samples {samples}: {}", e.message),
            ..e
        },
        false => e.at_key("tolerances.samples"),
    })
}

pub use super::shard_file::shard_len;

#[cfg(test)]
mod tests {
    /// The count of a shard is the number of k ≡ I (mod N) below the sample count, listed
    /// one by one here, for every split of up to 12 samples (an empty shard included).
    #[test]
    fn a_shard_holds_the_samples_of_its_residue() {
        for samples in 0..=12u64 {
            for count in 1..=samples.max(1) + 1 {
                for index in 0..count {
                    let listed = (index..samples).step_by(count as usize).count() as u64;
                    assert_eq!(super::shard_len(samples, (index, count)), listed);
                }
            }
        }
    }
}
