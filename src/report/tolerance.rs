//! Outputs of a tolerance study: the terminal table, the JSON document and the per-sample CSV.
//! Every number written to a file is in Rust's shortest round-trip form (serde_json, `{:?}`),
//! so that the files of a sharded and an unsharded run compare byte for byte.

use super::columns::{columns, Align};
use super::finite::Finite;
use crate::engine::tolerance::sensitivity::Sensitivity;
use crate::engine::tolerance::summary::{Summary, CONFIDENCE, QUANTILES};
use crate::engine::tolerance::{Records, ToleranceStudy};
use crate::error::{Error, Result};
use crate::model::quantity::Bound;
use crate::model::tolerances::{Distribution, NORMAL_CUT_SIGMA};
use crate::numeric::{number, percent, percent_label, with_unit};
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};
use std::collections::BTreeMap;

/// How the report's quantiles are defined (printed and in the JSON).
pub const QUANTILE_DEFINITION: &str =
    "order statistic of rank ceil(p*n) (inverse empirical distribution, Hyndman-Fan type 1)";

/// The linearisation caveat of the sensitivities.
pub const LINEAR_CAVEAT: &str = "the limited quantities are maxima or minima over rollers and \
    crank angles: the linear stack-up holds only while the worst roller and angle stay the same \
    over the band; the Monte Carlo spread is the answer where they do not";

/// What a study on a spec with `measured_profile` says of its samples (`check --tolerance`'s
/// line too).
pub const MEASURED_NOTE: &str = "drawn from the drawing, not the measured disc";

/// The bound in the JSON, in ASCII (`<=`, `>=`): what a script compares against; the terminal
/// and the review print `Bound::symbol` like every other table.
fn bound_sign(b: Bound) -> &'static str {
    match b {
        Bound::Min => ">=",
        Bound::Max => "<=",
    }
}

/// A distribution for people, with its band and cut: "normal distribution (band = 3σ, draws
/// beyond 6σ drawn again)", "uniform distribution over the band".
pub fn distribution_text(d: Distribution) -> String {
    match d {
        Distribution::Normal => {
            format!("normal distribution (band = 3σ, draws beyond {NORMAL_CUT_SIGMA}σ drawn again)")
        }
        Distribution::Uniform => "uniform distribution over the band".to_string(),
    }
}

/// The bands in force, `kind ±b` (mm).
fn bands(study: &ToleranceStudy) -> String {
    let t = &study.tolerances;
    t.toleranced()
        .map(|k| format!("{} ±{}", k.name(), crate::numeric::input(t.band_mm(k))))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The terminal report.
pub fn render(
    study: &ToleranceStudy,
    s: &Summary,
    records: &Records,
    sens: Option<&Sensitivity>,
) -> String {
    let t = &study.tolerances;
    let mut out = format!(
        "cycloid tolerance `{}`: scene `{}`, {} samples, {}, seed {}\n\
         toleranced (mm): {}\n\n",
        study.spec.name,
        study.spec.scenes[t.scene].name,
        s.samples,
        distribution_text(t.distribution),
        t.seed,
        bands(study),
    );
    if let Some(m) = &study.spec.measured {
        out.insert_str(
            out.len() - 1,
            &format!(
                "samples {MEASURED_NOTE}: `{}` is one part as made, a study draws every part\n",
                m.path
            ),
        );
    }
    let mut header = vec!["limit".to_string(), "min".to_string()];
    header.extend(QUANTILES.map(percent_label));
    header.extend([
        "max".to_string(),
        "failures".to_string(),
        format!("rate [{} CI]", percent_label(CONFIDENCE)),
    ]);
    let mut rows = vec![header];
    for l in &s.limits {
        let mut row = vec![format!(
            "{} {} {}",
            l.key,
            l.bound.symbol(),
            with_unit(number(l.limit), l.unit)
        )];
        row.push(value(l.min));
        row.extend(l.quantiles.iter().map(|&q| value(q)));
        row.push(value(l.max));
        row.push(l.failures.to_string());
        row.push(rate_text(s.limit_rate(l), l.interval));
        rows.push(row);
    }
    out += &columns(&rows, |_| Align::Left);
    out += &format!(
        "\nfailure rate (a sample fails when any limit fails): {} of {} = {} ({} \
         Clopper–Pearson), allowed {}: {}\n",
        s.failures,
        s.samples,
        rate_text(s.rate(), s.interval),
        percent_label(CONFIDENCE),
        percent(s.max_failure_rate),
        verdict(s)
    );
    out += &format!("quantiles: {QUANTILE_DEFINITION}\n");
    out += "\nworst samples (replay one with --write-sample K OUT):\n";
    for &(k, excess) in &s.worst {
        out += &format!(
            "  sample {k}: {}; largest draws {}\n",
            worst_values(study, records, k, excess),
            largest_draws(study, k, 3)
        );
    }
    if let Some(sens) = sens {
        out += &sensitivity_text(study, s, sens);
    }
    for note in study.notes() {
        out += &format!("note: {}\n", super::explain::note(&note));
    }
    out
}

/// A failure rate with its Clopper–Pearson interval: "1.250 % [0.4100 %, 2.900 %]".
pub fn rate_text(rate: f64, (lo, hi): (f64, f64)) -> String {
    format!("{} [{}, {}]", percent(rate), percent(lo), percent(hi))
}

/// Sample k's value of the limit(s) it is worst on (those whose excess over the limit,
/// relative to the limit, is its largest, `excess`), with the unit and the limit:
/// "min_clearance 0.004100 mm (≥ 0.005000 mm)".
pub fn worst_values(study: &ToleranceStudy, records: &Records, k: u64, excess: f64) -> String {
    let row = records.row(k, study.limits.len());
    study
        .limits
        .iter()
        .zip(row)
        .filter(|((def, limit), &v)| {
            crate::engine::limit::excess(v, *limit, def.bound)
                .total_cmp(&excess)
                .is_eq()
        })
        .map(|((def, limit), &v)| {
            let unit = |x: f64| with_unit(number(x), def.quantity.unit);
            format!(
                "{} {} ({} {})",
                def.quantity.key,
                unit(v),
                def.bound.symbol(),
                unit(*limit)
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The `count` draws of sample k largest relative to their σ (what made it bad), named, µm.
pub fn largest_draws(study: &ToleranceStudy, k: u64, count: usize) -> String {
    let values = study.draw(k);
    let z = |i: usize| (values[i] / study.tolerances.sigma_mm(study.params[i].kind)).abs();
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| z(b).total_cmp(&z(a)).then(a.cmp(&b)));
    let discs = study.spec.design.discs;
    order
        .iter()
        .take(count)
        .map(|&i| format!("{} {:+.3} µm", study.params[i].name(discs), values[i] * 1e3))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A statistic of a limited quantity with its unit (`show`), or why there is none: a sample's
/// value without a finite bound (an unbounded life or safety) has no mean, spread or
/// derivative (in the JSON: null).
pub fn statistic(x: Option<f64>, show: impl Fn(String) -> String) -> String {
    x.map_or_else(
        || "none (a sample is unbounded)".to_string(),
        |x| show(number(x)),
    )
}

/// A sample's value of a limited quantity (`report::place::or_unbounded`).
pub fn value(x: f64) -> String {
    super::place::or_unbounded(x, number)
}

/// The sensitivities: per limit the linear σ beside the Monte Carlo σ, and the Pareto of the
/// kinds (share of the linear variance).
fn sensitivity_text(study: &ToleranceStudy, s: &Summary, sens: &Sensitivity) -> String {
    let mut out = format!(
        "\nsensitivities (central differences, step {} mm, about the nominal reducer)\n",
        crate::numeric::input(crate::engine::tolerance::sensitivity::STEP_MM)
    );
    for (l, ls) in s.limits.iter().enumerate() {
        out += &format!(
            "{}: linear stack-up σ = {}, Monte Carlo σ = {}\n",
            ls.quantity,
            statistic(sens.linear_sigma(l), |x| with_unit(x, ls.unit)),
            statistic(ls.std, |x| with_unit(x, ls.unit)),
        );
        let mut rows = vec![vec![
            "  tolerance".to_string(),
            "share of variance".to_string(),
            "σ contribution".to_string(),
        ]];
        for (kind, var, share) in sens.pareto(study, l) {
            rows.push(vec![
                format!("  {}", kind.name()),
                percent(share),
                with_unit(number(var.sqrt()), ls.unit),
            ]);
        }
        out += &columns(&rows, |_| Align::Left);
    }
    out += &format!("note: {LINEAR_CAVEAT}\n");
    out
}

/// The JSON document of a study (`tolerance --json`). Its fields, and those of the documents
/// in it, are in alphabetical order, as its keys have always been written (it was built as a
/// `serde_json` map, which sorts them); the maps keyed by a part's or a quantity's name are
/// sorted maps for the same reason.
#[derive(Serialize)]
struct StudyDoc<'a> {
    bands_mm: BTreeMap<&'static str, Finite>,
    distribution: &'static str,
    failure_rate: Finite,
    failure_rate_ci95: [Finite; 2],
    failures: u64,
    limits: Vec<LimitDoc>,
    max_failure_rate: Finite,
    passed: bool,
    quantile_definition: &'static str,
    samples: u64,
    scene: &'a str,
    seed: u64,
    #[serde(skip_serializing_if = "Option::is_none")]
    sensitivity: Option<SensitivityDoc>,
    spec: SpecDoc<'a>,
    worst: Vec<WorstDoc>,
}

#[derive(Serialize)]
struct SpecDoc<'a> {
    name: &'a str,
    path: &'a str,
}

/// The distribution of one limited quantity over the samples, and its failures.
#[derive(Serialize)]
struct LimitDoc {
    bound: &'static str,
    failure_rate: Finite,
    failure_rate_ci95: [Finite; 2],
    failures: u64,
    key: &'static str,
    limit: Finite,
    max: Finite,
    mean: Option<Finite>,
    min: Finite,
    quantiles: Vec<QuantileDoc>,
    quantity: &'static str,
    std: Option<Finite>,
    unit: &'static str,
}

/// The value below which the fraction `p` of the samples lie (`QUANTILE_DEFINITION`).
#[derive(Serialize)]
struct QuantileDoc {
    p: Finite,
    value: Finite,
}

/// One of the worst samples: its draws and its limited quantities.
#[derive(Serialize)]
struct WorstDoc {
    deviations_mm: BTreeMap<String, Finite>,
    excess: Finite,
    sample: u64,
    values: BTreeMap<&'static str, Finite>,
}

/// The sensitivities about the nominal reducer (`--sensitivity`).
#[derive(Serialize)]
struct SensitivityDoc {
    caveat: &'static str,
    limits: Vec<LimitSensitivityDoc>,
    step_mm: Finite,
}

#[derive(Serialize)]
struct LimitSensitivityDoc {
    derivative_per_mm: BTreeMap<String, Option<Finite>>,
    linear_sigma: Option<Finite>,
    monte_carlo_sigma: Option<Finite>,
    pareto: Vec<ParetoDoc>,
    quantity: &'static str,
}

/// A kind of tolerance's share of a limit's linear variance.
#[derive(Serialize)]
struct ParetoDoc {
    share: Finite,
    tolerance: &'static str,
    variance: Finite,
}

/// Named values, a sorted map from each name to its value.
fn named<K: Ord>(pairs: impl Iterator<Item = (K, f64)>) -> BTreeMap<K, Finite> {
    pairs.map(|(name, v)| (name, Finite(v))).collect()
}

/// The drawn values of sample k by column name.
fn draws(study: &ToleranceStudy, k: u64) -> BTreeMap<String, Finite> {
    let discs = study.spec.design.discs;
    named((study.params.iter().map(|p| p.name(discs))).zip(study.draw(k)))
}

/// A Clopper–Pearson interval as its JSON pair.
fn interval(i: (f64, f64)) -> [Finite; 2] {
    [Finite(i.0), Finite(i.1)]
}

/// The JSON document of a study; an error if a number in it is not finite.
pub fn json(
    study: &ToleranceStudy,
    s: &Summary,
    records: &Records,
    sens: Option<&Sensitivity>,
) -> Result<String> {
    let t = &study.tolerances;
    let l = study.limits.len();
    let limits = (s.limits.iter())
        .map(|x| LimitDoc {
            bound: bound_sign(x.bound),
            failure_rate: Finite(s.limit_rate(x)),
            failure_rate_ci95: interval(x.interval),
            failures: x.failures,
            key: x.key,
            limit: Finite(x.limit),
            max: Finite(x.max),
            mean: x.mean.map(Finite),
            min: Finite(x.min),
            quantiles: (QUANTILES.iter().zip(x.quantiles))
                .map(|(&p, q)| QuantileDoc {
                    p: Finite(p),
                    value: Finite(q),
                })
                .collect(),
            quantity: x.quantity,
            std: x.std.map(Finite),
            unit: x.unit,
        })
        .collect();
    let worst = (s.worst.iter())
        .map(|&(k, excess)| WorstDoc {
            deviations_mm: draws(study, k),
            excess: Finite(excess),
            sample: k,
            values: named(
                (study.limits.iter().map(|(d, _)| d.quantity.key))
                    .zip(records.row(k, l).iter().copied()),
            ),
        })
        .collect();
    let doc = StudyDoc {
        bands_mm: named(t.toleranced().map(|k| (k.name(), t.band_mm(k)))),
        distribution: t.distribution.name(),
        failure_rate: Finite(s.rate()),
        failure_rate_ci95: interval(s.interval),
        failures: s.failures,
        limits,
        max_failure_rate: Finite(s.max_failure_rate),
        passed: s.passed(),
        quantile_definition: QUANTILE_DEFINITION,
        samples: s.samples,
        scene: &study.spec.scenes[t.scene].name,
        seed: t.seed,
        sensitivity: sens.map(|sens| sensitivity_doc(study, s, sens)),
        spec: SpecDoc {
            name: &study.spec.name,
            path: &study.spec.path,
        },
        worst,
    };
    let mut text = serde_json::to_string_pretty(&doc)
        .map_err(|e| Error::computation(format!("the study's JSON: {e}")))?;
    text.push('\n');
    Ok(text)
}

fn sensitivity_doc(study: &ToleranceStudy, s: &Summary, sens: &Sensitivity) -> SensitivityDoc {
    let discs = study.spec.design.discs;
    let limits = (s.limits.iter().enumerate())
        .map(|(l, x)| LimitSensitivityDoc {
            derivative_per_mm: (study.params.iter().map(|p| p.name(discs)))
                .zip(sens.derivative[l].iter().map(|d| d.map(Finite)))
                .collect(),
            linear_sigma: sens.linear_sigma(l).map(Finite),
            monte_carlo_sigma: x.std.map(Finite),
            pareto: (sens.pareto(study, l).into_iter())
                .map(|(k, var, share)| ParetoDoc {
                    share: Finite(share),
                    tolerance: k.name(),
                    variance: Finite(var),
                })
                .collect(),
            quantity: x.quantity,
        })
        .collect();
    SensitivityDoc {
        caveat: LINEAR_CAVEAT,
        limits,
        step_mm: Finite(crate::engine::tolerance::sensitivity::STEP_MM),
    }
}

/// The name of the samples' index column.
const SAMPLE_COLUMN: &str = "sample";

/// The samples of a study as columns: `sample` (the index k), then each drawn deviation (mm)
/// and each limited quantity (in its unit), named as the CSV's header names them; one value
/// per sample, in sample order. The deviations are drawn again from (seed, k). What
/// `--samples-csv` writes and the Python `tolerance` returns as arrays.
pub struct SamplesDoc {
    pub sample: Vec<u64>,
    /// (column name, values), deviations first, then limits, as the CSV's header orders them.
    pub columns: Vec<(String, Vec<f64>)>,
}

/// A map from column name to its values, in column order (names are data: one per part and
/// limit of the study).
impl Serialize for SamplesDoc {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(1 + self.columns.len()))?;
        map.serialize_entry(SAMPLE_COLUMN, &self.sample)?;
        for (name, values) in &self.columns {
            map.serialize_entry(name, values)?;
        }
        map.end()
    }
}

/// The samples document of a study's records.
pub fn samples(study: &ToleranceStudy, records: &Records) -> SamplesDoc {
    let discs = study.spec.design.discs;
    let l = study.limits.len();
    let n = records.values.len().checked_div(l).unwrap_or(0);
    let mut columns: Vec<(String, Vec<f64>)> = (study.params.iter())
        .map(|p| (p.name(discs), Vec::with_capacity(n)))
        .collect();
    for k in 0..n as u64 {
        for ((_, column), v) in columns.iter_mut().zip(study.draw(k)) {
            column.push(v);
        }
    }
    columns.extend(
        (study.limits.iter().enumerate())
            .map(|(i, (d, _))| (d.quantity.key.to_string(), records.column(i, l).collect())),
    );
    SamplesDoc {
        sample: (0..n as u64).collect(),
        columns,
    }
}

/// The per-sample CSV: the samples document's columns under their names, a row per sample;
/// numbers in shortest round-trip form.
pub fn samples_csv(study: &ToleranceStudy, records: &Records) -> String {
    let doc = samples(study, records);
    let mut header = vec![SAMPLE_COLUMN.to_string()];
    header.extend(doc.columns.iter().map(|(name, _)| name.clone()));
    let mut out = header.join(",");
    out.push('\n');
    for (row, k) in doc.sample.iter().enumerate() {
        out += &k.to_string();
        for (_, values) in &doc.columns {
            out += &format!(",{:?}", values[row]);
        }
        out.push('\n');
    }
    out
}

/// The comment on top of a spec written by `--write-sample K`: which sample of which study.
pub fn sample_header(study: &ToleranceStudy, k: u64) -> String {
    let t = &study.tolerances;
    format!(
        "# Written by `cycloid tolerance {} --write-sample {k}`: sample {k} of {} (seed {}) as \
         reducer.deviations.\n",
        study.spec.path, t.samples, t.seed
    )
}

/// The study's verdict in words: PASS, FAIL, or NOT SHOWN when the rate is within the limit
/// but its interval is not, with the samples that would show it.
pub fn verdict(s: &Summary) -> String {
    if s.passed() {
        return "PASS".to_string();
    }
    if !s.not_shown() {
        return "FAIL".to_string();
    }
    format!(
        "NOT SHOWN: {}",
        not_shown_reason(s.interval.1, s.max_failure_rate)
    )
}

/// Why a rate within its limit is no pass: its interval's upper end `upper` is above `max`,
/// and how many samples would show it.
pub fn not_shown_reason(upper: f64, max: f64) -> String {
    let needed = match crate::engine::tolerance::summary::samples_to_show(max) {
        Some(n) => format!("{n} samples with no failure would show it (more with failures)"),
        None => "no number of samples shows a rate of 0".to_string(),
    };
    format!(
        "the {} upper bound {} is above the allowed {}; {needed}",
        percent_label(CONFIDENCE),
        percent(upper),
        percent(max)
    )
}

#[cfg(test)]
mod tests {
    use super::{percent_label, CONFIDENCE, QUANTILES};

    /// The labels the reports print for the quantiles and the confidence: the numbers the
    /// reader knows (±3σ of a normal, the median, 95 %), with no float residue (100 × 0.00135
    /// is not 0.135 exactly) and no trailing zeros.
    #[test]
    fn the_labels_are_the_percentages() {
        assert_eq!(
            QUANTILES.map(percent_label),
            ["0.135 %", "50 %", "99.865 %"].map(String::from)
        );
        assert_eq!(percent_label(CONFIDENCE), "95 %");
        assert_eq!(percent_label(0.1), "10 %");
    }
}
