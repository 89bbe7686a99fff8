//! The design review of a tolerance study (`cycloid tolerance --report DIR`): the verdict of
//! the failure rate, the bands, the failure-rate table, a histogram of every limited quantity
//! with its limit drawn, the worst samples, and (with `--sensitivity`) the linear stack-up
//! beside the Monte Carlo spread and the Pareto of the tolerances. The page, tables and plots
//! are the design review's own (`shell::shell`, `common::data_table`, `svg::LinePlot`).

use super::common::{data_table, figure, verdict, Section};
use super::shell::shell;
use crate::engine::tolerance::sensitivity::Sensitivity;
use crate::engine::tolerance::summary::{LimitSummary, Summary, CONFIDENCE, QUANTILES};
use crate::engine::tolerance::{Records, ToleranceStudy};
use crate::model::results::is_unbounded;
use crate::numeric::with_unit;
use crate::numeric::{number, percent, percent_label};
use crate::report::svg::{axis_label, LinePlot, Series, PALETTE, RED};
use crate::report::tolerance::{
    distribution_text, rate_text, statistic, value, LINEAR_CAVEAT, MEASURED_NOTE,
    QUANTILE_DEFINITION,
};
use maud::{html, Markup};

/// Bins of a histogram of n values: √n, from 10 to 60.
fn bins(n: usize) -> usize {
    ((n as f64).sqrt().ceil() as usize).clamp(10, 60)
}

/// The histogram of limit `l`'s values as a step outline, with the limit as a dashed red
/// vertical line; the x range holds both the values and the limit.
fn histogram(
    study: &ToleranceStudy,
    records: &Records,
    l: usize,
    ls: &LimitSummary,
) -> Option<String> {
    let step = study.limits.len();
    // An unbounded life or safety has no place on the axis: the bounded samples are drawn.
    let values: Vec<f64> = (records.column(l, step))
        .filter(|&v| !is_unbounded(v))
        .collect();
    let unbounded = study.samples() - values.len();
    let lo = values.iter().copied().reduce(f64::min)?;
    let hi = values.iter().copied().fold(lo, f64::max);
    let nb = bins(values.len());
    let width = if hi > lo { (hi - lo) / nb as f64 } else { 1.0 };
    let mut counts = vec![0usize; nb];
    for v in &values {
        let b = (((v - lo) / width) as usize).min(nb - 1);
        counts[b] += 1;
    }
    let (mut x, mut y) = (vec![lo], vec![0.0]);
    for (b, &c) in counts.iter().enumerate() {
        let left = lo + b as f64 * width;
        x.extend([left, left + width]);
        y.extend([c as f64, c as f64]);
    }
    x.push(lo + nb as f64 * width);
    y.push(0.0);
    let top = counts.iter().copied().max().unwrap_or(1) as f64;
    let mut plot = LinePlot::new(
        &format!("{} over {} samples", ls.label, values.len()),
        &axis_label(ls.quantity, ls.unit),
        "samples per bin",
    );
    plot.subtitle = format!(
        "{nb} bins of {}; limit {} {}; failures {} of {}",
        number(width),
        ls.bound.symbol(),
        number(ls.limit),
        ls.failures,
        study.samples()
    );
    if unbounded > 0 {
        plot.subtitle += &format!("; {unbounded} unbounded samples not drawn");
    }
    plot.include_zero = true;
    plot.series.push(Series::new("samples", x, y, PALETTE[0]));
    let mut limit = Series::new(
        format!("limit {}", number(ls.limit)),
        vec![ls.limit, ls.limit],
        vec![0.0, top * 1.05],
        RED,
    );
    limit.dashed = true;
    plot.series.push(limit);
    plot.x_range = Some(with_margin(lo.min(ls.limit), hi.max(ls.limit)));
    Some(plot.to_svg())
}

/// A histogram's x range: the values and the limit, grown by `MARGIN` of its span at each
/// end so that neither the limit line nor the outermost bin lies on the frame (README: limits
/// are never hidden under the frame); a range of one value gets a unit's width.
fn with_margin(lo: f64, hi: f64) -> (f64, f64) {
    let span = if hi > lo { hi - lo } else { 1.0 };
    (lo - MARGIN * span, hi + MARGIN * span)
}

/// Share of a histogram's range left free at each end.
const MARGIN: f64 = 0.05;

fn rates_section(s: &Summary) -> Section {
    let body = html! {
        p.note { "Per limit, the spread of its quantity over the samples and how many fail it; \
                  a sample fails when it fails any limit. Quantiles: " (QUANTILE_DEFINITION)
                  ". Intervals: " (percent_label(CONFIDENCE)) " Clopper–Pearson." }
        (data_table(
            html! { th { "limit" } th { "min" } th { (percent_label(QUANTILES[0])) } th { "median" }
                th { (percent_label(QUANTILES[2])) } th { "max" } th { "failures" }
                th { "failure rate [" (percent_label(CONFIDENCE)) " CI]" } },
            html! {
                @for l in &s.limits {
                    tr class=(verdict(l.failures == 0)) {
                        td { code { (l.key) } " " (l.bound.symbol()) " "
                            (with_unit(number(l.limit), l.unit)) }
                        td.num { (value(l.min)) }
                        @for q in l.quantiles { td.num { (value(q)) } }
                        td.num { (value(l.max)) }
                        td.num { (l.failures) }
                        td.num { (rate_text(s.limit_rate(l), l.interval)) }
                    }
                }
                tr class=(verdict(s.passed())) {
                    td { b { "any limit" } " (allowed " (percent(s.max_failure_rate)) ")" }
                    td colspan="5" {}
                    td.num { (s.failures) }
                    td.num.verdict { (rate_text(s.rate(), s.interval)) }
                }
            },
        ))
    };
    Section::new("failure-rates", html! { "Failure rates" }, body)
}

fn study_section(study: &ToleranceStudy) -> Section {
    let t = &study.tolerances;
    let body = html! {
        p { "Scene " code { (study.spec.scenes[t.scene].name) } ", " (t.samples) " samples, seed "
            (t.seed) ", " (distribution_text(t.distribution))
            ". Every part's deviation is drawn independently; sample k depends only on (seed, k)." }
        @if let Some(m) = &study.spec.measured {
            p.note { "Samples " (MEASURED_NOTE) ": " code { (m.path) }
                " is one part as made, a study draws every part." }
        }
        (data_table(
            html! { th { "tolerance" } th { "band ±b" } th { "σ" } th { "parts" } },
            html! {
                @for k in t.toleranced() {
                    tr {
                        td { code { (k.name()) } }
                        td.num { (with_unit(number(t.band_mm(k)), "mm")) }
                        td.num { (with_unit(number(t.sigma_mm(k)), "mm")) }
                        td.num { (study.params.iter().filter(|p| p.kind == k).count()) }
                    }
                }
            },
        ))
    };
    Section::new("study", html! { "The study" }, body)
}

fn worst_section(study: &ToleranceStudy, s: &Summary, records: &Records) -> Section {
    let l = study.limits.len();
    let body = html! {
        p.note { "The samples furthest beyond (or least inside) a limit, relative to the limit. \
                  Replay one with " code { "cycloid tolerance SPEC --write-sample K OUT" } " and "
                  code { "cycloid check OUT" } "." }
        (data_table(
            html! { th { "sample" } @for (d, _) in &study.limits { th { (d.quantity.key) } }
                th { "largest draws (by |draw|/σ)" } },
            html! {
                @for &(k, _) in &s.worst {
                    tr {
                        td.num { (k) }
                        @for v in records.row(k, l) { td.num { (value(*v)) } }
                        td { (crate::report::tolerance::largest_draws(study, k, 4)) }
                    }
                }
            },
        ))
    };
    Section::new("worst", html! { "Worst samples" }, body)
}

fn sensitivity_section(study: &ToleranceStudy, s: &Summary, sens: &Sensitivity) -> Section {
    let body = html! {
        p.note { "Derivatives by central differences on the exact engine about the nominal \
                  reducer; linear stack-up σ = √Σ(∂q/∂p·σp)². Note: " (LINEAR_CAVEAT) "." }
        @for (l, ls) in s.limits.iter().enumerate() {
            h3 { code { (ls.quantity) } ": linear σ " (statistic(sens.linear_sigma(l), |x| with_unit(x, ls.unit)))
                ", Monte Carlo σ " (statistic(ls.std, |x| with_unit(x, ls.unit))) }
            (data_table(
                html! { th { "tolerance (tighten first at the top)" } th { "share of the variance" }
                    th { "σ contribution" } },
                html! {
                    @for (kind, var, share) in sens.pareto(study, l) {
                        tr {
                            td { code { (kind.name()) } }
                            td { div style=(format!("display:inline-block;height:12px;background:{};width:{:.0}px;margin-right:8px", PALETTE[0], 240.0 * share)) {} (percent(share)) }
                            td.num { (with_unit(number(var.sqrt()), ls.unit)) }
                        }
                    }
                },
            ))
        }
    };
    Section::new(
        "sensitivity",
        html! { "Sensitivities and the Pareto of the tolerances" },
        body,
    )
}

/// The review's files: one SVG per limit, then `index.html`.
pub fn render(
    study: &ToleranceStudy,
    s: &Summary,
    records: &Records,
    sens: Option<&Sensitivity>,
) -> Vec<(String, String)> {
    let mut files = Vec::new();
    let (mut figures, mut unbounded) = (Vec::new(), Vec::new());
    for (l, ls) in s.limits.iter().enumerate() {
        let name = format!("tolerance-{}.svg", ls.key);
        let Some(svg) = histogram(study, records, l, ls) else {
            unbounded.push(ls.quantity);
            continue;
        };
        files.push((name.clone(), svg));
        figures.push(figure(
            &name,
            &format!("Distribution of {}", ls.quantity),
            &format!(
                "Every sample's {}; the dashed red line is the limit; {} to {}: {} to {}",
                ls.label,
                percent_label(QUANTILES[0]),
                percent_label(QUANTILES[2]),
                value(ls.quantiles[0]),
                value(ls.quantiles[2])
            ),
        ));
    }
    let mut sections = vec![study_section(study), rates_section(s)];
    sections.push(Section::new(
        "distributions",
        html! { "Distributions" },
        html! {
            div.grid { @for f in &figures { (f) } }
            @for q in &unbounded {
                p { code { (q) } ": every sample unbounded (no finite life or safety), so no histogram." }
            }
        },
    ));
    sections.push(worst_section(study, s, records));
    if let Some(sens) = sens {
        sections.push(sensitivity_section(study, s, sens));
    }
    let banner: Markup = if s.passed() {
        html! { p.banner.pass { "PASSED: failure rate " (percent(s.rate())) " within the allowed "
        (percent(s.max_failure_rate)) } }
    } else if s.not_shown() {
        html! { p.banner.fail { "NOT SHOWN: failure rate " (percent(s.rate())) ", but "
        (crate::report::tolerance::not_shown_reason(s.interval.1, s.max_failure_rate)) } }
    } else {
        html! { p.banner.fail { "FAILED: failure rate " (percent(s.rate())) " above the allowed "
        (percent(s.max_failure_rate)) } }
    };
    files.push((
        "index.html".into(),
        shell(study.spec, "Tolerance review", banner, &sections),
    ));
    files
}
