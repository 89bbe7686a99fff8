//! What a study's records say: per limit the distribution of its quantity and its failure
//! rate, the overall failure rate against `max_failure_rate`, and the worst samples. Computed
//! from the records in sample order only, so that one process's records and merged shards give
//! the same numbers, bit for bit.

use super::stats::{clopper_pearson, quantile};
use super::{Records, ToleranceStudy};
use crate::model::quantity::Bound;
use crate::model::results::is_unbounded;

/// The quantiles the report gives: ±3σ of a normal (0.135 %, 99.865 %) and the median.
pub const QUANTILES: [f64; 3] = [0.00135, 0.5, 0.99865];

/// Confidence of the failure-rate intervals.
pub const CONFIDENCE: f64 = 0.95;

/// Worst samples the report lists.
pub const WORST: usize = 5;

/// One limit over the samples.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitSummary {
    /// The limit's key (`min_clearance_mm`).
    pub key: &'static str,
    /// Its quantity's results-JSON name.
    pub quantity: &'static str,
    pub unit: &'static str,
    pub label: &'static str,
    pub limit: f64,
    pub bound: Bound,
    pub min: f64,
    /// At `QUANTILES`.
    pub quantiles: [f64; 3],
    pub max: f64,
    /// The mean; `None` when a sample's value has no finite bound (`UNBOUNDED_LIFE_H`: a life
    /// or safety without load or damage), whose mean and spread are no number.
    pub mean: Option<f64>,
    /// Sample standard deviation (n − 1); `None` as `mean`.
    pub std: Option<f64>,
    pub failures: u64,
    /// 95 % Clopper–Pearson interval of the failure rate.
    pub interval: (f64, f64),
}

/// The study's verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    pub samples: u64,
    pub limits: Vec<LimitSummary>,
    /// Samples that fail some limit.
    pub failures: u64,
    pub interval: (f64, f64),
    pub max_failure_rate: f64,
    /// The worst samples, worst first: (k, its largest excess over the limits, relative to
    /// each limit as the checks table sorts them, `verdict::Check::excess`).
    pub worst: Vec<(u64, f64)>,
}

impl Summary {
    /// The fraction of the samples that fail some limit.
    pub fn rate(&self) -> f64 {
        self.failures as f64 / self.samples as f64
    }

    /// The fraction of the samples that fail limit `l`.
    pub fn limit_rate(&self, l: &LimitSummary) -> f64 {
        l.failures as f64 / self.samples as f64
    }

    /// The samples show the failure rate within `max_failure_rate`: the upper end of its
    /// `CONFIDENCE` interval is within it. A rate within the limit whose interval reaches
    /// beyond it is not a pass (`not_shown`): the samples cannot tell it from a rate above.
    pub fn passed(&self) -> bool {
        self.interval.1 <= self.max_failure_rate
    }

    /// The rate is within `max_failure_rate` but the samples are too few to show it: with no
    /// failure, `samples_to_show` would (more with failures).
    pub fn not_shown(&self) -> bool {
        not_shown(
            self.failures,
            self.samples,
            self.interval.1,
            self.max_failure_rate,
        )
    }
}

/// `Summary::not_shown` of `failures` in `samples` whose interval reaches up to `upper`,
/// against `max`: the rate is within it, the interval is not.
pub fn not_shown(failures: u64, samples: u64, upper: f64, max: f64) -> bool {
    upper > max && failures as f64 / samples as f64 <= max
}

/// The fewest samples whose interval, with no failure, lies within `max`, the limit on the
/// failure rate: 1 − (α/2)^(1/n) ≤ max, n = ⌈ln(α/2)/ln(1 − max)⌉ checked against the interval
/// itself; `None` when no count can (a max of 0).
pub fn samples_to_show(max: f64) -> Option<u64> {
    if max <= 0.0 {
        return None;
    }
    let alpha = 1.0 - CONFIDENCE;
    if max >= 1.0 {
        return Some(1);
    }
    let mut n = ((alpha / 2.0).ln() / (1.0 - max).ln()).ceil().max(1.0) as u64;
    // The closed form's round-off either way: the interval decides.
    while n > 1 && clopper_pearson(0, n - 1, alpha).1 <= max {
        n -= 1;
    }
    while clopper_pearson(0, n, alpha).1 > max {
        n += 1;
    }
    Some(n)
}

/// The mean and the sample standard deviation (n − 1; 0 for one value) of `values`.
fn mean_and_std(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = match values.len() > 1 {
        true => values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0),
        false => 0.0,
    };
    (mean, var.sqrt())
}

/// The summary of `records`, which hold every sample of the study in sample order.
pub fn summarise(study: &ToleranceStudy, records: &Records) -> Summary {
    let l = study.limits.len();
    let n = study.samples();
    let alpha = 1.0 - CONFIDENCE;
    let limits = study
        .limits
        .iter()
        .enumerate()
        .map(|(i, (def, limit))| {
            let values: Vec<f64> = records.column(i, l).collect();
            let failures = records
                .passed
                .iter()
                .skip(i)
                .step_by(l)
                .filter(|p| !**p)
                .count() as u64;
            let (mean, std) = match values.iter().any(|&v| is_unbounded(v)) {
                true => (None, None),
                false => {
                    let (mean, std) = mean_and_std(&values);
                    (Some(mean), Some(std))
                }
            };
            let mut sorted = values;
            sorted.sort_unstable_by(f64::total_cmp);
            LimitSummary {
                key: def.key,
                quantity: def.quantity.key,
                unit: def.quantity.unit,
                label: def.quantity.label,
                limit: *limit,
                bound: def.bound,
                min: sorted[0],
                quantiles: QUANTILES.map(|p| quantile(&sorted, p)),
                max: sorted[n - 1],
                mean,
                std,
                failures,
                interval: clopper_pearson(failures, n as u64, alpha),
            }
        })
        .collect();
    let failures = records
        .passed
        .chunks(l)
        .filter(|p| p.iter().any(|x| !x))
        .count() as u64;
    Summary {
        samples: n as u64,
        limits,
        failures,
        interval: clopper_pearson(failures, n as u64, alpha),
        max_failure_rate: study.tolerances.max_failure_rate,
        worst: worst(study, records),
    }
}

/// The `WORST` samples by their largest excess over the limits, worst first (ties: lower k).
fn worst(study: &ToleranceStudy, records: &Records) -> Vec<(u64, f64)> {
    let l = study.limits.len();
    let mut all: Vec<(u64, f64)> = records
        .values
        .chunks(l)
        .enumerate()
        .map(|(k, v)| {
            let e = v
                .iter()
                .zip(&study.limits)
                .map(|(&v, (def, limit))| crate::engine::limit::excess(v, *limit, def.bound))
                .fold(f64::NEG_INFINITY, f64::max);
            (k as u64, e)
        })
        .collect();
    let cmp = |a: &(u64, f64), b: &(u64, f64)| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0));
    let keep = WORST.min(all.len());
    if keep < all.len() {
        all.select_nth_unstable_by(keep, cmp);
        all.truncate(keep);
    }
    all.sort_by(cmp);
    all
}
