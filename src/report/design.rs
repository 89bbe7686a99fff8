//! What `cycloid design` shows: the search's counts and the front as a terminal table, a CSV
//! and a review page with the front plotted.

use crate::engine::commands::{self, CheckRun};
use crate::engine::design_search::failure::{Failure, Miss, Requirement};
use crate::engine::design_search::missed::{Cause, Count, Infeasible};
use crate::engine::design_search::{Evaluation, SearchRun, Tally};
use crate::model::requirements::{ObjectiveKind, Requirements};
use crate::numeric::{number, with_unit};
use crate::report::columns::{self, Align};
use crate::report::place::listed;
use crate::report::review::disc::thumbnail;
use crate::report::svg::base::{document, px};
use crate::report::svg::labels::{Bounds, Label, Layout, Obstacle};
use crate::report::svg::ticks;
use maud::{html, Markup, DOCTYPE};
use std::fmt::Write;

/// A column: its header and the value of a front design.
type Column<'a> = (String, Box<dyn Fn(&Evaluation) -> f64 + 'a>);

/// The columns of the table, CSV and page.
fn columns(req: &Requirements) -> Vec<Column<'_>> {
    let mut cols: Vec<Column<'_>> = vec![
        (
            "ratio".into(),
            Box::new(|e: &Evaluation| e.candidate.choice.teeth as f64),
        ),
        (
            "pins".into(),
            Box::new(|e: &Evaluation| e.candidate.choice.pins as f64),
        ),
        (
            "discs".into(),
            Box::new(|e: &Evaluation| e.candidate.choice.discs as f64),
        ),
    ];
    for (k, key) in crate::model::requirements::Continuous::KEYS
        .into_iter()
        .enumerate()
    {
        cols.push((
            key.to_string(),
            Box::new(move |e: &Evaluation| e.candidate.x.to_array()[k]),
        ));
    }
    cols.push((
        "outer_diameter_mm".into(),
        Box::new(|e: &Evaluation| e.candidate.outer_diameter_mm(req)),
    ));
    cols.push((
        "axial_length_mm".into(),
        Box::new(|e: &Evaluation| e.candidate.axial_length_mm(req)),
    ));
    cols.push((
        "mass_kg".into(),
        Box::new(|e: &Evaluation| e.candidate.mass_kg(req)),
    ));
    for (i, o) in req.objectives.iter().enumerate() {
        if !cols.iter().any(|(h, _)| h == o.name()) {
            cols.push((
                o.name().to_string(),
                Box::new(move |e: &Evaluation| e.objectives[i]),
            ));
        }
    }
    cols
}

/// How long the run took, for the report.
#[derive(Debug, Clone, Copy)]
pub enum Timing {
    /// An unsharded search: its wall time, s.
    Whole(f64),
    /// A merge of `shards` shards: its own wall time, s (the local refinement and the front;
    /// the global stage's time is the shards').
    Merged { seconds: f64, shards: u64 },
}

impl Timing {
    /// `wall time 12.3 s`, and for a merge what that time covers.
    pub fn text(&self) -> String {
        match *self {
            Timing::Whole(seconds) => format!("wall time {seconds:.1} s"),
            Timing::Merged { seconds, shards } => format!(
                "wall time {seconds:.1} s (the merge of {shards} shards: the local refinement; \
                 the global stage ran in the shards)"
            ),
        }
    }
}

fn tally_line(what: &str, t: &Tally) -> String {
    format!(
        "{what}: {} designs generated, {} rejected by the rules and the envelope, {} screened \
         ({} rejected), {} fully checked, {} feasible\n",
        t.generated, t.rule_rejected, t.screened, t.screen_rejected, t.fully_checked, t.feasible
    )
}

/// A miss in words: the design's value and the limit (`best 731.2 MPa, required ≤ 300.0
/// MPa`), or what the engine said.
pub fn miss_text(f: &Failure) -> String {
    match &f.miss {
        Miss::Bound { value, limit } => {
            let unit = |x: f64| with_unit(number(x), f.requirement.unit());
            format!(
                "best {}, required {} {}",
                unit(*value),
                f.requirement.bound().symbol(),
                unit(*limit)
            )
        }
        Miss::Said(m) => crate::error::printable(m, &[]).into_owned(),
    }
}

/// A requirement's key for people (a rule of the spec's key escaped: it comes from the
/// spec's refusal).
fn key_text(r: &Requirement) -> String {
    crate::error::printable(&r.key(), &[]).into_owned()
}

/// One requirement over the designs evaluated: `limits.max_lost_motion_arcsec: met by 0,
/// passed at the screen by 700, missed by 205 (best 300.5 arcsec, required ≤ 300.0 arcsec),
/// not reached by 631`.
fn count_text(c: &Count) -> String {
    let mut parts = vec![format!("met by {}", c.met)];
    if c.passed_screen > 0 {
        parts.push(format!("passed at the screen by {}", c.passed_screen));
    }
    if let (true, Some(f)) = (c.missed > 0, &c.closest) {
        parts.push(format!("missed by {} ({})", c.missed, miss_text(f)));
    }
    if c.not_judged > 0 {
        parts.push(format!("not reached by {}", c.not_judged));
    }
    format!("{}: {}", key_text(&c.requirement), parts.join(", "))
}

/// Why no design is feasible, in words: the requirements no design met, each with its best
/// miss, or the smallest combinations no design met together.
fn cause_text(inf: &Infeasible) -> String {
    let closest = |r: &Requirement| {
        inf.counts
            .iter()
            .find(|c| &c.requirement == r)
            .and_then(|c| c.closest.as_ref())
            .map_or(String::new(), |f| format!(" ({})", miss_text(f)))
    };
    match &inf.cause {
        Cause::NeverMet(rs) => {
            let each: Vec<String> = rs
                .iter()
                .map(|r| format!("{}{}", key_text(r), closest(r)))
                .collect();
            format!("no design meets {}", each.join(", nor "))
        }
        Cause::Together(sets) => {
            let each: Vec<String> = sets
                .iter()
                .map(|set| listed(&set.iter().map(key_text).collect::<Vec<_>>(), "and"))
                .collect();
            format!(
                "each requirement is met by some design, never all by one: no design meets {} \
                 together",
                each.join(" together, nor ")
            )
        }
        Cause::NoDesign => "no design was generated".into(),
    }
}

/// The front's cells, `[design][column]`: each column by one rule (`numeric::column`: counts
/// as integers, the rest to four significant digits, in decimals or, where the column's
/// magnitudes need it, all with an exponent).
fn cells(cols: &[Column<'_>], front: &[Evaluation]) -> Vec<Vec<String>> {
    let by_column: Vec<Vec<String>> = cols
        .iter()
        .map(|(_, f)| crate::numeric::column(&front.iter().map(f).collect::<Vec<_>>()))
        .collect();
    (0..front.len())
        .map(|k| by_column.iter().map(|c| c[k].clone()).collect())
        .collect()
}

/// The terminal text: the counts, the front's table (or why there is none) and the verdict.
pub fn render(req: &Requirements, run: &SearchRun, out_dir: Option<&str>, time: &Timing) -> String {
    let mut s = String::new();
    let objectives: Vec<String> = req
        .objectives
        .iter()
        .map(|o| format!("{o} ({})", if o.maximise() { "max" } else { "min" }))
        .collect();
    let _ = writeln!(
        s,
        "design search of `{}`: ratios {:?}, objectives {}",
        crate::error::printable(&req.name, &[]),
        req.ratios,
        objectives.join(", ")
    );
    s.push_str(&tally_line("global stage", &run.global));
    s.push_str(&tally_line("local refinement", &run.local));
    let _ = writeln!(s, "{}", time.text());
    if let Some(inf) = &run.infeasible {
        let _ = writeln!(
            s,
            "no design meets every requirement; of the {} designs evaluated:",
            inf.evaluated
        );
        for c in &inf.counts {
            let _ = writeln!(s, "  {}", count_text(c));
        }
        let _ = writeln!(s, "FAIL: {}", cause_text(inf));
        return s;
    }
    let cols = columns(req);
    let _ = writeln!(s, "\nPareto front, {} designs:", run.front.len());
    // The header, then each design numbered from 1; every column as wide as its widest cell.
    let mut rows = vec![std::iter::once("#".to_string())
        .chain(cols.iter().map(|(h, _)| h.clone()))
        .collect::<Vec<_>>()];
    for (k, c) in cells(&cols, &run.front).into_iter().enumerate() {
        rows.push(std::iter::once(format!("{}", k + 1)).chain(c).collect());
    }
    s += &columns::columns(&rows, |_| Align::Right);
    if let Some(dir) = out_dir {
        let _ = writeln!(
            s,
            "\nwrote {} specs (design-01.yaml …), their reviews (design-01/index.html …), \
             front.csv and index.html to {dir}",
            run.front.len()
        );
    }
    let _ = writeln!(
        s,
        "PASS: {} designs on the front, each meets every requirement",
        run.front.len()
    );
    s
}

/// The front as CSV: one row per design, its spec file, variables, figures and objectives.
pub fn csv(req: &Requirements, run: &SearchRun) -> String {
    let cols = columns(req);
    let mut s = String::from("spec");
    for (h, _) in &cols {
        let _ = write!(s, ",{h}");
    }
    s.push('\n');
    for (k, e) in run.front.iter().enumerate() {
        s.push_str(&crate::engine::commands::design_file(k));
        for (_, f) in &cols {
            let _ = write!(s, ",{}", f(e));
        }
        s.push('\n');
    }
    s
}

/// An objective as a plot axis names it for a person: the quantity in words and its unit in
/// parentheses ("mass (kg)", "max contact pressure (MPa)"), not the YAML key (`mass_kg`).
pub fn axis_label(kind: ObjectiveKind) -> String {
    let (what, unit) = words(kind);
    crate::report::svg::axis_label(what, unit)
}

/// An objective's (quantity in words, unit): ("mass", "kg"); the unit "" for a ratio.
fn words(kind: ObjectiveKind) -> (&'static str, &'static str) {
    match kind {
        ObjectiveKind::OuterDiameter => ("outer diameter", "mm"),
        ObjectiveKind::AxialLength => ("axial length", "mm"),
        ObjectiveKind::Mass => ("mass", "kg"),
        ObjectiveKind::ContactPressure => ("max contact pressure", "MPa"),
        ObjectiveKind::TeFluctuation => ("TE fluctuation", "arcsec"),
        ObjectiveKind::LostMotion => ("max unloaded lost motion", "arcsec"),
        ObjectiveKind::BearingLife => ("crank-bearing life L10h", "h"),
        ObjectiveKind::Rigidity => ("torsional rigidity", "N·m/arcmin"),
        ObjectiveKind::Efficiency => ("mean efficiency", ""),
    }
}

/// A scatter plot of the front on objectives `i` (x) and `j` (y), each point labelled by its
/// design number, as an SVG document: round ticks (`svg::ticks`) and labels placed clear of
/// the points and of each other (`svg::labels::Layout`, with a leader where moved far).
pub fn front_plot(req: &Requirements, run: &SearchRun, i: usize, j: usize) -> String {
    let (x_obj, y_obj) = (req.objectives[i], req.objectives[j]);
    let title = format!(
        "Pareto front: {} against {}",
        axis_label(y_obj),
        axis_label(x_obj)
    );
    let aim = |o: ObjectiveKind| {
        format!(
            "{} {}",
            words(o).0,
            if o.maximise() {
                "maximised"
            } else {
                "minimised"
            }
        )
    };
    let subtitle = format!(
        "{} designs, numbered as in the table; {}, {}",
        run.front.len(),
        aim(x_obj),
        aim(y_obj)
    );
    let (left, right) = (80.0, 620.0);
    let top = crate::report::svg::frame::top(1);
    let bottom = top + 350.0;
    let (w, h) = (640.0, bottom + 60.0);
    let xs: Vec<f64> = run.front.iter().map(|e| e.objectives[i]).collect();
    let ys: Vec<f64> = run.front.iter().map(|e| e.objectives[j]).collect();
    let span = |v: &[f64]| {
        let (lo, hi) = crate::numeric::extent(v.iter().copied());
        ticks(lo, hi, 5, true)
    };
    let (tx, ty) = (span(&xs), span(&ys));
    let fx = |x: f64| left + (x - tx.lo) / (tx.hi - tx.lo) * (right - left);
    let fy = |y: f64| bottom - (y - ty.lo) / (ty.hi - ty.lo) * (bottom - top);
    let spots: Vec<(f64, f64)> = xs.iter().zip(&ys).map(|(&x, &y)| (fx(x), fy(y))).collect();
    let mut layout = Layout::new(Bounds::new(left, top, right, bottom));
    layout
        .obstacles
        .extend(spots.iter().map(|&c| Obstacle::Disc(c, 5.0)));
    let placed: Vec<_> = spots
        .iter()
        .enumerate()
        .map(|(k, &c)| {
            layout.place(&Label {
                text: (k + 1).to_string(),
                size: 10.0,
                anchor: c,
                gap: 5.0,
                toward: (1.0, -1.0),
            })
        })
        .collect();
    let body: Markup = html! {
        (crate::report::svg::frame::titles(left, &title, &[subtitle]))
        rect x=(px(left)) y=(px(top)) width=(px(right - left)) height=(px(bottom - top))
            fill="none" stroke="#999" {}
        @for &t in &tx.values {
            line x1=(px(fx(t))) x2=(px(fx(t))) y1=(px(bottom)) y2=(px(bottom + 5.0)) stroke="#999" {}
            text x=(px(fx(t))) y=(px(bottom + 18.0)) font-size="11" text-anchor="middle" { (tx.label(t)) }
        }
        @for &t in &ty.values {
            line x1=(px(left - 5.0)) x2=(px(left)) y1=(px(fy(t))) y2=(px(fy(t))) stroke="#999" {}
            text x=(px(left - 8.0)) y=(px(fy(t) + 4.0)) font-size="11" text-anchor="end" { (ty.label(t)) }
        }
        text x=(px((left + right) / 2.0)) y=(px(bottom + 40.0)) font-size="13" text-anchor="middle" {
            (axis_label(x_obj))
        }
        text x="16" y=(px((top + bottom) / 2.0)) font-size="13" text-anchor="middle"
            transform=(format!("rotate(-90 16 {})", px((top + bottom) / 2.0))) {
            (axis_label(y_obj))
        }
        @for &(x, y) in &spots {
            circle cx=(px(x)) cy=(px(y)) r="4" fill="#1f77b4" {}
        }
        @for p in &placed {
            (p.draw("#333", true))
        }
    };
    document(w, h, body)
}

/// The plots of the page: (file name, SVG), objective 1 against each other objective.
pub fn plots(req: &Requirements, run: &SearchRun) -> Vec<(String, String)> {
    if run.front.is_empty() {
        return Vec::new();
    }
    (1..req.objectives.len())
        .map(|j| (format!("front-{}.svg", j), front_plot(req, run, 0, j)))
        .collect()
}

/// Size of a front design's disc drawing in the table, px.
const THUMBNAIL_PX: f64 = 64.0;

/// The file of front design `k`'s small disc drawing, in its review's folder.
fn thumbnail_file(k: usize) -> String {
    format!("{}/disc-small.svg", commands::design_name(k))
}

/// Each front design's own review (the review `check --report` writes of its spec, from
/// `checks`, in the front's order) in its folder `design-01/`, …, with a small drawing of its
/// disc for the front's table: (path under the output directory, text), each folder's
/// `index.html` after its figures.
pub fn front_reviews(checks: &[CheckRun]) -> Vec<(String, String)> {
    let mut files = Vec::new();
    for (k, run) in checks.iter().enumerate() {
        let dir = commands::design_name(k);
        let Some(review) = &run.review else {
            continue;
        };
        files.push((thumbnail_file(k), thumbnail(&review.disc, THUMBNAIL_PX)));
        let pages = crate::report::check_review::render(run, review);
        files.extend(
            pages
                .into_iter()
                .map(|(name, text)| (format!("{dir}/{name}"), text)),
        );
    }
    files
}

/// The review page: the counts, the plots and the front's table, each design with its disc
/// drawn small and linked to its own review and its spec.
pub fn page(req: &Requirements, run: &SearchRun, time: &Timing) -> String {
    let cols = columns(req);
    let table = cells(&cols, &run.front);
    let plots = plots(req, run);
    let markup = html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                title { "Design search: " (req.name) }
                style { "body{font-family:sans-serif;margin:24px auto;max-width:1360px;padding:0 16px}\
                         .scroll{overflow-x:auto;max-width:100%}\
                         table{border-collapse:collapse;font-size:13px}\
                         th,td{padding:3px 8px;border-bottom:1px solid #eee;text-align:right;vertical-align:middle}td a{white-space:nowrap}\
                         td.design{text-align:center}td.design img{display:block;margin:0 auto}\
                         .fail{color:#a11212;font-weight:bold}.pass{color:#1d6b1a;font-weight:bold}" }
            }
            body {
                h1 { "Design search: " (req.name) }
                p { (tally_line("global stage", &run.global)) br; (tally_line("local refinement", &run.local))
                    br; (time.text()) }
                @if let Some(inf) = &run.infeasible {
                    p.fail { "No design meets every requirement: " (cause_text(inf)) "." }
                    p { "Of the " (inf.evaluated) " designs evaluated, per requirement:" }
                    ul { @for c in &inf.counts { li { (count_text(c)) } } }
                } @else {
                    p.pass { (run.front.len()) " designs on the Pareto front; each meets every requirement and passes " code { "cycloid check" } "." }
                    @for (name, _) in &plots { img src=(name) alt="the front"; }
                    h2 { "The front" }
                    p { "Each design links to its own review (the one " code { "cycloid check SPEC --report DIR" }
                        " writes) and to its spec; the table scrolls sideways." }
                    div.scroll { table {
                        thead { tr { th { "design" } th { "spec" } @for (h, _) in &cols { th { (h) } } } }
                        tbody {
                            @for (k, row) in table.iter().enumerate() {
                                @let review = format!("{}/index.html", commands::design_name(k));
                                tr {
                                    td.design { a href=(review) {
                                        img src=(thumbnail_file(k)) width=(THUMBNAIL_PX) height=(THUMBNAIL_PX)
                                            alt=(format!("disc of design {}", k + 1));
                                        (commands::design_name(k))
                                    } }
                                    td { a href=(commands::design_file(k)) { (commands::design_file(k)) } }
                                    @for c in row { td { (c) } }
                                }
                            }
                        }
                    } }
                }
            }
        }
    };
    markup.into_string()
}
