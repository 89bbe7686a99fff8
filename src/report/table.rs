//! The terminal table of checks (check, value, limit, verdict, where) and the summary of each
//! scene's headline results.

use crate::engine::check::{Bound, Check, Evidence};
use crate::engine::summary::{Headline, SceneSummary};

/// Format a number for a person: 4 significant figures, no exponent for ordinary magnitudes.
pub fn number(x: f64) -> String {
    if x == 0.0 || (1e-3..1e6).contains(&x.abs()) {
        let digits = (3 - x.abs().log10().floor() as i32).clamp(0, 6) as usize;
        format!("{x:.digits$}")
    } else {
        format!("{x:.3e}")
    }
}

/// A value followed by its unit, if any ("2.000 mm", "3").
pub fn with_unit(x: String, unit: &str) -> String {
    if unit.is_empty() {
        x
    } else {
        format!("{x} {unit}")
    }
}

/// The order a reader wants: failures first, the furthest outside its limit (relative to the
/// limit) first; then the passes in spec order.
pub fn ordered(checks: &[Check]) -> Vec<&Check> {
    let mut rows: Vec<&Check> = checks.iter().collect();
    rows.sort_by(|a, b| {
        a.passed.cmp(&b.passed).then_with(|| {
            if a.passed {
                std::cmp::Ordering::Equal
            } else {
                b.excess().total_cmp(&a.excess())
            }
        })
    });
    rows
}

/// Whether the terminal table should be coloured: only on a terminal, never with NO_COLOR set
/// (to anything but the empty string, as no-color.org asks).
pub fn use_color(is_terminal: bool) -> bool {
    is_terminal && std::env::var_os("NO_COLOR").is_none_or(|v| v.is_empty())
}

/// The table without colour, one check a row, worst failures first.
pub fn render(checks: &[Check]) -> String {
    render_styled(checks, false)
}

/// ANSI styles of the verdicts: the only control sequences the tool itself prints.
pub const FAIL_STYLE: &str = "\x1b[1;31m";
pub const PASS_STYLE: &str = "\x1b[32m";
pub const PLAIN_STYLE: &str = "\x1b[0m";
pub const STYLES: [&str; 3] = [FAIL_STYLE, PASS_STYLE, PLAIN_STYLE];

/// A check's value as a person reads it: a value that passes only by the comparison's
/// round-off tolerance (−8.2e-14 mm against ≥ 0 mm) reads as the limit, said so, not as a
/// negative clearance marked "pass". The JSON keeps the value as computed.
pub fn value(c: &Check) -> String {
    let shown = |x: f64| with_unit(number(shown_scale(c) * x), shown_unit(c));
    let wrong_side = match c.bound {
        Bound::Max => c.value > c.limit,
        Bound::Min => c.value < c.limit,
    };
    if c.passed && wrong_side {
        format!("{} (to round-off)", shown(c.limit))
    } else if c.value == f64::MAX {
        // The engine's "no bound" (a bearing no load wears, a study with no constraint).
        "unbounded".to_string()
    } else if c.value == f64::MIN {
        "none (the evaluation failed)".to_string()
    } else {
        shown(c.value)
    }
}

/// What a person reads a check's value and limit in: a failure rate (a fraction in the check,
/// the JSON and JUnit) in percent, as `cycloid tolerance` prints every rate; else as computed.
pub fn shown_scale(c: &Check) -> f64 {
    match c.at {
        Evidence::FailureRate { .. } => 100.0,
        _ => 1.0,
    }
}

/// The unit a person reads a check in: `%` for a failure rate (see `shown_scale`).
pub fn shown_unit(c: &Check) -> &'static str {
    match c.at {
        Evidence::FailureRate { .. } => "%",
        _ => c.unit,
    }
}

/// A check's limit as a person reads it, with the bound's sign and the unit ("≤ 5.000 %").
pub fn limit(c: &Check) -> String {
    let op = match c.bound {
        Bound::Max => "≤",
        Bound::Min => "≥",
    };
    with_unit(
        format!("{op} {}", number(shown_scale(c) * c.limit)),
        shown_unit(c),
    )
}

/// The table, one check a row, worst failures first; `color` adds ANSI colour to the verdicts.
pub fn render_styled(checks: &[Check], color: bool) -> String {
    if checks.is_empty() {
        // No table without rows: say why there is nothing to judge.
        return "no checks: the spec sets no limits, golden curves or studies\n".to_string();
    }
    let rows = ordered(checks);
    let header = ["check", "value", "limit", "verdict", "where"];
    let cells: Vec<[String; 5]> = rows
        .iter()
        .map(|c| {
            [
                c.id.clone(),
                value(c),
                limit(c),
                if c.passed { "pass" } else { "FAIL" }.to_string(),
                evidence(&c.at),
            ]
        })
        .collect();
    let mut widths = header.map(|h| h.chars().count());
    for row in &cells {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |row: [&str; 5]| {
        let mut s = String::new();
        for (k, (cell, w)) in row.iter().zip(widths).enumerate() {
            let pad = " ".repeat(w - cell.chars().count());
            let shown = match (color, *cell) {
                (true, "FAIL") => format!("{FAIL_STYLE}{cell}{PLAIN_STYLE}"),
                (true, "pass") => format!("{PASS_STYLE}{cell}{PLAIN_STYLE}"),
                _ => cell.to_string(),
            };
            if k + 1 == row.len() {
                s += &shown;
            } else {
                s += &format!("{shown}{pad}  ");
            }
        }
        s.trim_end().to_string() + "\n"
    };
    let mut out = line(header);
    for row in &cells {
        out += &line([&row[0], &row[1], &row[2], &row[3], &row[4]]);
    }
    let failed = checks.iter().filter(|c| !c.passed).count();
    out += &format!(
        "{} check{}: {} passed, {} failed\n",
        checks.len(),
        if checks.len() == 1 { "" } else { "s" },
        checks.len() - failed,
        failed
    );
    out
}

/// The last line `check` prints: the verdict in one plain word a script or a person can find,
/// and the counts behind it ("PASS: 7 of 7 checks passed", "FAIL: 2 of 7 checks failed").
pub fn verdict_line(checks: &[Check]) -> String {
    let failed = checks.iter().filter(|c| !c.passed).count();
    let n = checks.len();
    let noun = if n == 1 { "check" } else { "checks" };
    match failed {
        0 => format!("PASS: {n} of {n} {noun} passed\n"),
        f => format!("FAIL: {f} of {n} {noun} failed\n"),
    }
}

/// A count (a whole dimensionless value, e.g. rollers in contact) as an integer, else `number`.
pub fn count_or_number(x: f64, unit: &str) -> String {
    if is_count(x, unit) {
        format!("{x:.0}")
    } else {
        number(x)
    }
}

/// A unitless whole number (rollers in contact) prints as a count.
fn is_count(x: f64, unit: &str) -> bool {
    unit.is_empty() && x.fract() == 0.0 && x.abs() < 1e9
}

/// The change from `from` to `to` as those two print (`count_or_number`): a signed count
/// between counts, else [`numeric::change`](crate::numeric::change).
pub fn count_or_change(from: f64, to: f64, unit: &str) -> String {
    match to - from {
        x if is_count(from, unit) && is_count(to, unit) && x != 0.0 => format!("{x:+.0}"),
        _ => crate::numeric::change(from, to),
    }
}

/// The headline results of each scene, one block per scene: quantity, value with its unit,
/// where it occurs. A scene that computed none of them says so.
pub fn render_summary(summaries: &[SceneSummary]) -> String {
    let mut out = String::from("headline results:\n");
    for s in summaries {
        out += &format!("scene `{}`:\n", s.scene);
        if s.headlines.is_empty() {
            out += "  no headline results (the scene computes none of them)\n";
            continue;
        }
        let label_w = s
            .headlines
            .iter()
            .map(|h| h.quantity.label.chars().count())
            .max()
            .unwrap_or(0);
        let values: Vec<String> = s.headlines.iter().map(headline_value).collect();
        let value_w = values.iter().map(|v| v.chars().count()).max().unwrap_or(0);
        for (h, v) in s.headlines.iter().zip(&values) {
            let label = h.quantity.label;
            let line = format!(
                "  {label}{}  {}{v}  {}",
                " ".repeat(label_w - label.chars().count()),
                " ".repeat(value_w - v.chars().count()),
                headline_at(h, s, summaries)
            );
            out += line.trim_end();
            out += "\n";
        }
    }
    out
}

/// A headline's value with its unit as a person reads it. A lost motion is a free play and
/// never negative: the headline's value is the sum of the closing lags both ways (MODEL.md
/// "Angular backlash"), negative when the rollers overlap the profile (a preload or an
/// interference); then it reads 0 and `headline_at` says how far they overlap.
pub fn headline_value(h: &Headline) -> String {
    let unit = h.quantity.unit;
    let x = if preloaded(h) { 0.0 } else { h.value };
    with_unit(count_or_number(x, unit), unit)
}

/// Whether `h` is a lost motion whose closing lags overlap (no free play).
fn preloaded(h: &Headline) -> bool {
    h.quantity.key == crate::model::quantity::MAX_LOST_MOTION.key && h.value < 0.0
}

/// Where a headline occurs; a preloaded lost motion's overlap first (see `headline_value`);
/// and, when another scene of `all` gives the same quantity, the scene's sampling, so that two
/// values of one quantity say why they differ. Not for the min clearance: it is sought over
/// the whole period of the gaps whatever the scene samples, and its line already says over
/// what.
pub fn headline_at(h: &Headline, s: &SceneSummary, all: &[SceneSummary]) -> String {
    let mut at = h.at.clone();
    if preloaded(h) {
        at = format!(
            "preloaded: no free play, the closing lags overlap by {} {} (interference), {at}",
            number(-h.value),
            h.quantity.unit
        );
    }
    let others = all.iter().filter(|o| o.scene != s.scene);
    let shared = h.quantity.key != crate::model::quantity::MIN_CLEARANCE.key
        && others
            .flat_map(|o| &o.headlines)
            .any(|o| o.quantity.key == h.quantity.key);
    if shared {
        at += &format!("; {}", sampling(s));
    }
    at
}

/// A scene's sampling of the crank: "sampled at 1080 crank angles, every 0.1000°".
pub fn sampling(s: &SceneSummary) -> String {
    match s.angles {
        1 => "sampled at 1 crank angle".to_string(),
        n => format!(
            "sampled at {n} crank angles, every {}°",
            crate::numeric::number(crate::units::deg(s.step_rad))
        ),
    }
}

/// Where a check's value occurs, or what it rests on, in words: the "where" of every view of
/// the checks (terminal, JSON, JUnit, the review).
pub fn evidence(e: &Evidence) -> String {
    match e {
        Evidence::Place(place) => place.clone(),
        Evidence::Golden { worst, path } => format!(
            "worst at {}: golden {}, now {} ({})",
            super::golden::place(worst),
            number(worst.golden),
            number(worst.value),
            path.display()
        ),
        Evidence::Tightest(name) => name
            .as_ref()
            .map_or(String::new(), |n| format!("tightest: {n}")),
        Evidence::Optimum(variables) => (variables.iter())
            .map(|(key, value)| format!("{key} {value:.5}"))
            .collect::<Vec<_>>()
            .join(", "),
        Evidence::Resolution(r) if r.resolved() => {
            "crank steps per mesh period meet the accuracy tolerances".to_string()
        }
        Evidence::Resolution(r) => super::accuracy::misses_text(r),
        Evidence::FailureRate {
            failures,
            samples,
            confidence,
            interval,
            measured,
            max_failure_rate,
        } => format!(
            "{failures} of {samples} samples fail some limit; {} Clopper–Pearson interval [{}, \
             {}]{}{}",
            crate::numeric::percent_label(*confidence),
            super::tolerance::percent(interval.0),
            super::tolerance::percent(interval.1),
            match crate::engine::tolerance::summary::not_shown(
                *failures,
                *samples,
                interval.1,
                *max_failure_rate,
            ) {
                true => format!(
                    "; not shown within the limit: {}",
                    super::tolerance::not_shown_reason(interval.1, *max_failure_rate)
                ),
                false => String::new(),
            },
            match measured {
                true => format!("; {}", super::tolerance::MEASURED_NOTE),
                false => String::new(),
            }
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::count_or_change;

    /// Counts change by signed whole numbers; anything else as [`numeric::change`](crate::numeric::change), to the
    /// decimals the values print with.
    #[test]
    fn count_changes_are_signed_whole_numbers() {
        assert_eq!(count_or_change(3.0, 4.0, ""), "+1");
        assert_eq!(count_or_change(4.0, 3.0, ""), "-1");
        assert_eq!(count_or_change(3.0, 3.0, ""), "0");
        assert_eq!(count_or_change(3.0, 4.0, "N"), "+1.000");
        assert_eq!(count_or_change(9.0, 9.5, ""), "+0.500");
    }
}
