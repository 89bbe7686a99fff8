//! Outputs of a tolerance study: the terminal table, the JSON document and the per-sample CSV.
//! Every number written to a file is in Rust's shortest round-trip form (serde_json, `{:?}`),
//! so that the files of a sharded and an unsharded run compare byte for byte.

use crate::engine::tolerance::sensitivity::Sensitivity;
use crate::engine::tolerance::summary::{Summary, CONFIDENCE, QUANTILES};
use crate::engine::tolerance::{Records, ToleranceStudy};
use crate::model::quantity::Bound;
use crate::model::tolerances::{Distribution, NORMAL_CUT_SIGMA};
use crate::numeric::number;
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};
use serde_json::{json, Map, Value};

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

pub use crate::numeric::percent_label;

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

/// A fraction as a percentage for people.
pub(super) fn percent(x: f64) -> String {
    crate::numeric::percent(x)
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
            "{} {} {} {}",
            l.key,
            l.bound.symbol(),
            number(l.limit),
            l.unit
        )];
        row.push(number(l.min));
        row.extend(l.quantiles.iter().map(|&q| number(q)));
        row.push(number(l.max));
        row.push(l.failures.to_string());
        row.push(format!(
            "{} [{}, {}]",
            percent(s.limit_rate(l)),
            percent(l.interval.0),
            percent(l.interval.1)
        ));
        rows.push(row);
    }
    out += &columns(&rows);
    out += &format!(
        "\nfailure rate (a sample fails when any limit fails): {} of {} = {} [{}, {}] ({} \
         Clopper–Pearson), allowed {}: {}\n",
        s.failures,
        s.samples,
        percent(s.rate()),
        percent(s.interval.0),
        percent(s.interval.1),
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
            let unit = |x: f64| match def.quantity.unit {
                "" => number(x),
                u => format!("{} {u}", number(x)),
            };
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

/// Rows of cells in left-aligned columns.
fn columns(rows: &[Vec<String>]) -> String {
    let widths: Vec<usize> = (0..rows[0].len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut out = String::new();
    for r in rows {
        let cells: Vec<String> = r
            .iter()
            .zip(&widths)
            .map(|(cell, w)| format!("{cell:<w$}"))
            .collect();
        out += cells.join("  ").trim_end();
        out.push('\n');
    }
    out
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
            "{}: linear stack-up σ = {} {}, Monte Carlo σ = {} {}\n",
            ls.quantity,
            number(sens.linear_sigma(l)),
            ls.unit,
            number(ls.std),
            ls.unit
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
                format!("{} {}", number(var.sqrt()), ls.unit),
            ]);
        }
        out += &columns(&rows);
    }
    out += &format!("note: {LINEAR_CAVEAT}\n");
    out
}

/// The drawn values of sample k by column name.
fn draws(study: &ToleranceStudy, k: u64) -> Map<String, Value> {
    let discs = study.spec.design.discs;
    study
        .params
        .iter()
        .zip(study.draw(k))
        .map(|(p, v)| (p.name(discs), json!(v)))
        .collect()
}

/// The JSON document of a study.
pub fn json(
    study: &ToleranceStudy,
    s: &Summary,
    records: &Records,
    sens: Option<&Sensitivity>,
) -> String {
    let t = &study.tolerances;
    let l = study.limits.len();
    let limits: Vec<Value> = s
        .limits
        .iter()
        .map(|x| {
            json!({
                "key": x.key,
                "quantity": x.quantity,
                "unit": x.unit,
                "bound": bound_sign(x.bound),
                "limit": x.limit,
                "min": x.min,
                "quantiles": QUANTILES.iter().zip(x.quantiles).map(|(p, q)| json!({"p": p, "value": q})).collect::<Vec<_>>(),
                "max": x.max,
                "mean": x.mean,
                "std": x.std,
                "failures": x.failures,
                "failure_rate": s.limit_rate(x),
                "failure_rate_ci95": [x.interval.0, x.interval.1],
            })
        })
        .collect();
    let worst: Vec<Value> = s
        .worst
        .iter()
        .map(|&(k, excess)| {
            let row = records.row(k, l);
            let values: Map<String, Value> = study
                .limits
                .iter()
                .zip(row)
                .map(|((d, _), v)| (d.quantity.key.to_string(), json!(v)))
                .collect();
            json!({"sample": k, "excess": excess, "values": values, "deviations_mm": draws(study, k)})
        })
        .collect();
    let bands: Map<String, Value> = t
        .toleranced()
        .map(|k| (k.name().to_string(), json!(t.band_mm(k))))
        .collect();
    let mut doc = json!({
        "spec": {"name": study.spec.name, "path": study.spec.path},
        "scene": study.spec.scenes[t.scene].name,
        "samples": s.samples,
        "seed": t.seed,
        "distribution": t.distribution.name(),
        "bands_mm": bands,
        "quantile_definition": QUANTILE_DEFINITION,
        "limits": limits,
        "failures": s.failures,
        "failure_rate": s.rate(),
        "failure_rate_ci95": [s.interval.0, s.interval.1],
        "max_failure_rate": s.max_failure_rate,
        "passed": s.passed(),
        "worst": worst,
    });
    if let Some(sens) = sens {
        doc["sensitivity"] = sensitivity_json(study, s, sens);
    }
    let mut text = serde_json::to_string_pretty(&doc).unwrap_or_default();
    text.push('\n');
    text
}

fn sensitivity_json(study: &ToleranceStudy, s: &Summary, sens: &Sensitivity) -> Value {
    let discs = study.spec.design.discs;
    let per_limit: Vec<Value> = s
        .limits
        .iter()
        .enumerate()
        .map(|(l, x)| {
            let d: Map<String, Value> = study
                .params
                .iter()
                .zip(&sens.derivative[l])
                .map(|(p, d)| (p.name(discs), json!(d)))
                .collect();
            let pareto: Vec<Value> = sens
                .pareto(study, l)
                .into_iter()
                .map(|(k, var, share)| json!({"tolerance": k.name(), "variance": var, "share": share}))
                .collect();
            json!({
                "quantity": x.quantity,
                "derivative_per_mm": d,
                "linear_sigma": sens.linear_sigma(l),
                "monte_carlo_sigma": x.std,
                "pareto": pareto,
            })
        })
        .collect();
    json!({
        "step_mm": crate::engine::tolerance::sensitivity::STEP_MM,
        "caveat": LINEAR_CAVEAT,
        "limits": per_limit,
    })
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
