//! The terminal table of checks (check, value, limit, verdict, where) and the summary of each
//! scene's headline results.

use crate::engine::plausibility::{Basis, Beyond};
use crate::engine::summary::{Headline, SceneSummary, TorqueShare};
use crate::engine::verdict::{Check, CheckKind, Evidence};
use crate::model::quantity::{find_limit, Quantity};
use crate::model::quantity::{MAX_LOST_MOTION, MAX_TORSION_LOST_MOTION, MIN_CLEARANCE};
use crate::numeric::{number, with_unit};
use crate::report::columns::{columns, Align};
use crate::report::place::{self, counted, ONLY_ANGLE};

/// A value of `q` (in its unit) as every output prints it — headline, checks table, review,
/// plots: a count (`quantity::COUNTS`) as a whole number, any other value as `number` (four
/// significant digits), so that one quantity reads alike everywhere (an efficiency of 1 is
/// "1.000", never "1" in one place and "1.000" in another).
pub fn figure(q: &Quantity, x: f64) -> String {
    if q.is_count() && x.fract() == 0.0 && x.abs() < 1e9 {
        format!("{x:.0}")
    } else {
        number(x)
    }
}

/// The quantity a check bounds, when it is a limit of the registry (`limits.KEY`).
fn checked_quantity(c: &Check) -> Option<&'static Quantity> {
    let key = c.id.rsplit('/').next()?;
    (c.kind == CheckKind::Limit)
        .then(|| find_limit(key))
        .flatten()
        .map(|l| l.quantity)
}

/// A check's value or limit `x` as a person reads it (`shown_in`): its quantity's `figure`.
fn check_figure(c: &Check, x: f64) -> String {
    match (checked_quantity(c), shown_in(c).0) {
        (Some(q), 1.0) => figure(q, x),
        (_, scale) => number(scale * x),
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

/// ANSI styles of the verdicts: the only control sequences the tool itself prints.
pub const FAIL_STYLE: &str = "\x1b[1;31m";
pub const PASS_STYLE: &str = "\x1b[32m";
pub const PLAIN_STYLE: &str = "\x1b[0m";
pub const STYLES: [&str; 3] = [FAIL_STYLE, PASS_STYLE, PLAIN_STYLE];

/// A check's value as a person reads it: a value that passes only by the comparison's
/// round-off tolerance (−8.2e-14 mm against ≥ 0 mm) reads as the limit, said so, not as a
/// negative clearance marked "pass". The JSON keeps the value as computed.
pub fn value(c: &Check) -> String {
    let shown = |x: f64| with_unit(check_figure(c, x), shown_in(c).1);
    let wrong_side = crate::engine::limit::beyond(c.value, c.limit, c.bound) > 0.0;
    if c.passed && wrong_side {
        format!("{} (to round-off)", shown(c.limit))
    } else if is_lost_motion(c) && c.value < 0.0 {
        format!(
            "0 {} (preloaded: overlap {} {})",
            c.unit,
            number(-c.value),
            c.unit
        )
    } else if c.value == f64::MIN {
        "none (the evaluation failed)".to_string()
    } else {
        place::or_unbounded(c.value, shown)
    }
}

/// What a person reads a check's value and limit in, (scale, unit): a failure rate (a fraction
/// in the check, the JSON and JUnit) in percent, as `cycloid tolerance` prints every rate;
/// else as computed, in the check's unit.
pub fn shown_in(c: &Check) -> (f64, &'static str) {
    match c.at {
        Evidence::FailureRate { .. } => (100.0, "%"),
        _ => (1.0, c.unit),
    }
}

/// Whether `c` is a limit on the unloaded lost motion (`limits.max_lost_motion_arcsec`): a
/// signed sum of the closing lags, negative when they overlap (a preload), which a person
/// reads as a free play of 0 and an overlap (`headline_value`'s convention).
fn is_lost_motion(c: &Check) -> bool {
    c.kind == CheckKind::Limit && c.id.rsplit('/').next() == Some(MAX_LOST_MOTION.key)
}

/// A check's limit as a person reads it, with the bound's sign and the unit ("≤ 5.000 %"). A
/// negative limit on the lost motion asks for an overlap (a preload) of at least its
/// magnitude, and reads so ("overlap ≥ 500.0 arcsec"), never as a negative lost motion.
pub fn limit(c: &Check) -> String {
    if is_lost_motion(c) && c.limit < 0.0 {
        return format!("overlap ≥ {} {}", number(-c.limit), c.unit);
    }
    let op = c.bound.symbol();
    with_unit(format!("{op} {}", check_figure(c, c.limit)), shown_in(c).1)
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
        for (cell, w) in row.iter().zip(widths) {
            let pad = " ".repeat(w - cell.chars().count());
            let shown = match (color, *cell) {
                (true, "FAIL") => format!("{FAIL_STYLE}{cell}{PLAIN_STYLE}"),
                (true, "pass") => format!("{PASS_STYLE}{cell}{PLAIN_STYLE}"),
                _ => cell.to_string(),
            };
            s += &format!("{shown}{pad}  ");
        }
        // The last cell's padding and gap go with the line's trailing spaces.
        s.trim_end().to_string() + "\n"
    };
    let mut out = line(header);
    for row in &cells {
        out += &line([&row[0], &row[1], &row[2], &row[3], &row[4]]);
    }
    let failed = checks.iter().filter(|c| !c.passed).count();
    out += &format!(
        "{}: {} passed, {} failed\n",
        counted(checks.len(), "check"),
        checks.len() - failed,
        failed
    );
    out
}

/// The verdict line of a run with no check: nothing was judged.
pub const NOTHING_JUDGED: &str = "NOTHING JUDGED: 0 checks, so neither PASS nor FAIL\n";

/// The last line `check` prints: the verdict in one plain word a script or a person can find,
/// and the counts behind it ("PASS: 7 of 7 checks passed", "FAIL: 2 of 7 checks failed").
pub fn verdict_line(checks: &[Check]) -> String {
    let failed = checks.iter().filter(|c| !c.passed).count();
    let n = checks.len();
    match failed {
        // Exit 0 all the same: nothing failed, but "PASS: 0 of 0" would read as a verdict.
        _ if n == 0 => NOTHING_JUDGED.to_string(),
        0 => format!("PASS: {n} of {} passed\n", counted(n, "check")),
        f => format!("FAIL: {f} of {} failed\n", counted(n, "check")),
    }
}

/// The change from `from` to `to` of `q` as those two print (`figure`): a signed count
/// between counts, else [`numeric::change`](crate::numeric::change).
pub fn figure_change(q: &Quantity, from: f64, to: f64) -> String {
    let whole = |x: f64| x.fract() == 0.0 && x.abs() < 1e9;
    let counts = q.is_count() && whole(from) && whole(to);
    match to - from {
        x if counts && x != 0.0 => format!("{x:+.0}"),
        _ => crate::numeric::change(from, to),
    }
}

/// One row of a scene's headline results as a person reads it (`summary_rows`).
#[derive(Debug, Clone, PartialEq)]
pub struct SummaryRow {
    /// What the value is ("max roller force", "torque share, disc 1").
    pub label: String,
    /// The value with its unit.
    pub value: String,
    /// Where it occurs, with what a reader must know beside it (a preload, a mark).
    pub at: String,
    /// Beyond its plausible band (`engine::plausibility`): marked, not failed.
    pub marked: bool,
}

/// A scene's headline results, one row each, then (with several discs) each disc's torque
/// share: what the terminal and the review both show.
pub fn summary_rows(s: &SceneSummary, all: &[SceneSummary]) -> Vec<SummaryRow> {
    let mut rows: Vec<SummaryRow> = s
        .headlines
        .iter()
        .map(|h| SummaryRow {
            label: headline_label(h, s),
            value: scene_headline_value(h, s),
            at: headline_at(h, s, all),
            marked: h.beyond.is_some(),
        })
        .collect();
    rows.extend(s.shares.iter().map(|t| share_row(t, s)));
    rows
}

/// A disc's torque share: its mean over the scene's crank angles, N·m, with its percentage of
/// the scene's torque and its range.
fn share_row(t: &TorqueShare, s: &SceneSummary) -> SummaryRow {
    use crate::numeric::{number, percent};
    let of = |x: f64| match t.scene_nm {
        0.0 => String::new(),
        total => percent(x / total),
    };
    let mean = match t.scene_nm {
        0.0 => format!("of the scene's {} N·m", number(t.scene_nm)),
        _ => format!(
            "{} of the scene's {} N·m",
            of(t.mean_nm),
            number(t.scene_nm)
        ),
    };
    let over = match s.angles {
        1 => format!("{mean}, at {ONLY_ANGLE}"),
        n => format!(
            "{mean}, mean over its {n} crank angles; range {}–{} N·m{}",
            number(t.min_nm),
            number(t.max_nm),
            match t.scene_nm {
                0.0 => String::new(),
                _ => format!(" ({}–{})", of(t.min_nm), of(t.max_nm)),
            }
        ),
    };
    SummaryRow {
        label: format!("torque share, disc {}", t.disc),
        value: with_unit(number(t.mean_nm), "N·m"),
        at: over,
        marked: false,
    }
}

/// The headline results of each scene, one block per scene: quantity, value with its unit,
/// where it occurs. A scene that computed none of them says so. A value beyond its plausible
/// band starts its line with `!` instead of the indent.
pub fn render_summary(summaries: &[SceneSummary]) -> String {
    let mut out = String::from("headline results:\n");
    for s in summaries {
        out += &format!("scene `{}`:\n", s.scene);
        if s.headlines.is_empty() {
            out += "  no headline results (the scene computes none of them)\n";
            continue;
        }
        let rows: Vec<Vec<String>> = (summary_rows(s, summaries).into_iter())
            .map(|r| {
                let mark = if r.marked { "! " } else { "  " };
                vec![format!("{mark}{}", r.label), r.value, r.at]
            })
            .collect();
        // The values right-aligned, the labels and places left.
        out += &columns(&rows, |c| if c == 1 { Align::Right } else { Align::Left });
    }
    out
}

/// What a headline is, as its line labels it: a lost motion with several discs is one
/// disc's (each disc's closing lags at its own phase), beside the reducer's torsion figures.
pub fn headline_label(h: &Headline, s: &SceneSummary) -> String {
    if h.quantity.key == MAX_LOST_MOTION.key && s.discs > 1 {
        "max lost motion per disc (unloaded)".to_string()
    } else {
        h.quantity.label.to_string()
    }
}

/// A headline's value with its unit as a person reads it. A lost motion is a free play and
/// never negative: the headline's value is the sum of the closing lags both ways (MODEL.md
/// "Angular backlash"), negative when the rollers overlap the profile (a preload or an
/// interference); then it reads 0 and `headline_at` says how far they overlap.
pub fn headline_value(h: &Headline) -> String {
    let x = if preloaded(h) || unresolved(h) {
        0.0
    } else {
        h.value
    };
    with_unit(figure(h.quantity, x), h.quantity.unit)
}

/// A headline's value as its scene's line reads it: `headline_value`, but in a scene with the
/// reducer's torsion figures (in arcmin, the catalogues' unit) the unloaded lost motion reads
/// in arcmin too (`in_arcmin`), so that its line, which compares the two, holds one unit.
pub fn scene_headline_value(h: &Headline, s: &SceneSummary) -> String {
    if !in_arcmin(h, s) {
        return headline_value(h);
    }
    let x = if preloaded(h) { 0.0 } else { h.value };
    with_unit(number(arcsec_to_arcmin(x)), "arcmin")
}

/// Whether `h` is the unloaded lost motion (arcsec, as every TE figure) of a scene that also
/// gives the reducer's torsion lost motion (arcmin): its line then reads in arcmin.
fn in_arcmin(h: &Headline, s: &SceneSummary) -> bool {
    h.quantity.key == MAX_LOST_MOTION.key && torsion_lost_motion(s).is_some()
}

/// The reducer's lost motion at ±3 % of rated torque of a torsion scene, arcmin.
fn torsion_lost_motion(s: &SceneSummary) -> Option<&Headline> {
    s.headlines
        .iter()
        .find(|o| o.quantity.key == MAX_TORSION_LOST_MOTION.key)
}

/// An angle in arcsec as arcmin (1 arcmin = 60 arcsec).
fn arcsec_to_arcmin(x: f64) -> f64 {
    crate::units::arcmin(crate::units::rad_from_arcsec(x))
}

/// Whether `h` is below what its computation resolves (`Headline::resolution`): it reads 0,
/// and `headline_at` says to what resolution.
fn unresolved(h: &Headline) -> bool {
    h.value.abs() < h.resolution
}

/// Whether `h` is a lost motion whose closing lags overlap (no free play).
fn preloaded(h: &Headline) -> bool {
    h.quantity.key == MAX_LOST_MOTION.key && h.value < 0.0
}

/// Where a headline occurs; a preloaded lost motion's overlap first (see `headline_value`);
/// a mark when the value is beyond its plausible band first of all; and, when another scene
/// of `all` gives the same quantity, the scene's sampling, so that two values of one quantity
/// say why they differ (a one-angle scene's headline names its angle once). Not for the min
/// clearance: it is sought over the whole period of the gaps whatever the scene samples, and
/// its line already says over what. An unloaded lost motion beside the reducer's ±3 % figure
/// of the same scene says why the two differ.
pub fn headline_at(h: &Headline, s: &SceneSummary, all: &[SceneSummary]) -> String {
    let mut at = place::text(&h.at);
    if preloaded(h) {
        let (overlap, unit) = match in_arcmin(h, s) {
            true => (arcsec_to_arcmin(-h.value), "arcmin"),
            false => (-h.value, h.quantity.unit),
        };
        at = format!(
            "preloaded: no free play, the closing lags overlap by {} {unit} (interference), {at}",
            number(overlap),
        );
    }
    if unresolved(h) {
        at += &format!(
            "; 0 to the loop's resolution, {} (the lag change of one torque step at the \
             torsional rigidity)",
            with_unit(number(h.resolution), h.quantity.unit)
        );
    }
    let others = all.iter().filter(|o| o.scene != s.scene);
    let shared = h.quantity.key != MIN_CLEARANCE.key
        && others
            .flat_map(|o| &o.headlines)
            .any(|o| o.quantity.key == h.quantity.key);
    if shared && !place::names_only_angle(&h.at) {
        // A place that counts the scene's angles already gets their step alone.
        at += &match place::counts_scene_angles(&h.at) {
            true => format!(", every {}°", step_deg(s)),
            false => format!("; {}", sampling(s)),
        };
    }
    if let (true, Some(t)) = (in_arcmin(h, s), torsion_lost_motion(s)) {
        // The value beside it is in arcmin already (`scene_headline_value`).
        at += &format!(
            "; against the reducer's {} arcmin at ±3 % of rated torque: this is {} \
             free play with no load (the closing lags at the ideal pose), the other the \
             catalogue's figure, the torsion angle of the reducer between ±3 % of rated torque: \
             that free play plus the elastic twist of the contacts at 3 % of rated{}",
            number(t.value),
            if s.discs > 1 {
                "one disc's"
            } else {
                "the disc's"
            },
            if s.discs > 1 {
                ", the discs coupled on one output (the first disc to touch ends the dead band)"
            } else {
                ""
            }
        );
    }
    if let Some(b) = &h.beyond {
        at = format!("{}; {at}", beyond_text(h, b));
    }
    at
}

/// Why a headline is marked: its band and what the band rests on (`engine::plausibility`),
/// and the limit that would judge it.
pub fn beyond_text(h: &Headline, b: &Beyond) -> String {
    let gpa = |mpa: f64| number(crate::units::gpa(mpa));
    let why = match b.basis {
        Basis::Steel {
            disc_e_mpa,
            roller_e_mpa,
        } => format!(
            "beyond the plausible range of hardened steel contacts, {} MPa (ISO 76's static \
             limit of bearing steel in line contact; steel assumed from E {} GPa of the disc, {} \
             GPa of the rollers)",
            number(b.band),
            gpa(disc_e_mpa),
            gpa(roller_e_mpa)
        ),
        Basis::UnknownMaterial {
            disc_e_mpa,
            roller_e_mpa,
        } => format!(
            "beyond {} MPa: E {} GPa of the disc, {} GPa of the rollers is not steel's \
             (190–230 GPa) and the material is unknown to the tool, so the band is the \
             conservative ISO 6336-5 contact endurance limit of case-hardened steel",
            number(b.band),
            gpa(disc_e_mpa),
            gpa(roller_e_mpa)
        ),
        Basis::TorqueScale {
            torque_nmm,
            arm_mm,
            pin_circle,
        } => format!(
            "{} × the {} N the torque needs at the largest arm ({} = {} N·m / {} mm), beyond \
             {} ×: forces this large are balanced by forces against the torque (a preload or \
             an interference), not by the torque",
            number(h.value / (torque_nmm / arm_mm)),
            number(torque_nmm / arm_mm),
            if pin_circle { "T/rw" } else { "T/(e·nc)" },
            number(crate::units::nm(torque_nmm)),
            number(arm_mm),
            crate::engine::plausibility::FORCE_FACTOR
        ),
    };
    format!(
        "IMPLAUSIBLE (not a failed check): {why}; set limits.{} to judge it",
        h.quantity.key
    )
}

/// A scene's sampling of the crank: "sampled at 1080 crank angles, every 0.1000°", or "the
/// scene's only crank angle" (every headline's place names that angle already).
pub fn sampling(s: &SceneSummary) -> String {
    match s.angles {
        1 => ONLY_ANGLE.to_string(),
        n => format!("sampled at {n} crank angles, every {}°", step_deg(s)),
    }
}

/// A scene's crank step, degrees, as people read it.
fn step_deg(s: &SceneSummary) -> String {
    number(crate::units::deg(s.step_rad))
}

/// Where a check's value occurs, or what it rests on, in words: the "where" of every view of
/// the checks (terminal, JSON, JUnit, the review).
pub fn evidence(e: &Evidence) -> String {
    match e {
        Evidence::Place(p) => place::text(p),
        Evidence::Golden { worst, path } => format!(
            "worst at {}: golden {}, now {} ({})",
            super::golden::in_row(worst),
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
            crate::numeric::percent(interval.0),
            crate::numeric::percent(interval.1),
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
    use super::{figure, figure_change};
    use crate::model::quantity::{CONTACTS, MEAN_EFFICIENCY, MIN_ROLLERS_IN_CONTACT};

    /// Counts change by signed whole numbers; anything else as [`numeric::change`](crate::numeric::change), to the
    /// decimals the values print with.
    #[test]
    fn count_changes_are_signed_whole_numbers() {
        assert_eq!(figure_change(&CONTACTS, 3.0, 4.0), "+1");
        assert_eq!(figure_change(&CONTACTS, 4.0, 3.0), "-1");
        assert_eq!(figure_change(&CONTACTS, 3.0, 3.0), "0");
        assert_eq!(figure_change(&MEAN_EFFICIENCY, 3.0, 4.0), "+1.000");
        assert_eq!(figure_change(&CONTACTS, 9.0, 9.5), "+0.500");
    }

    /// One formatter per quantity: a unitless ratio that happens to be whole (an efficiency of
    /// 1) prints to four significant digits like its other values; only counts print whole.
    #[test]
    fn a_whole_efficiency_is_not_a_count() {
        assert_eq!(figure(&MEAN_EFFICIENCY, 1.0), "1.000");
        assert_eq!(figure(&MEAN_EFFICIENCY, 0.8843), "0.8843");
        assert_eq!(figure(&MIN_ROLLERS_IN_CONTACT, 2.0), "2");
    }
}
