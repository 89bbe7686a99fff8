//! The design-review report (`--report DIR`): `index.html` plus one SVG per plot, for a
//! reviewer who opens it in a browser. No JavaScript; the page links the SVGs with `<img>`.
//! Built with maud: every text is escaped by construction.
//!
//! Contents: verdict and warnings, a table of contents, the headline results of every scene,
//! the design, every check and golden curve with its verdict; the disc at a crank angle as the
//! engine computed it (`engine::drawing`) and a close-up of the smallest gap; per scene, the
//! plots of its curves (`plots`); per optimisation study, the objective map with the global
//! sample, the winning local run's path, start, references and optimum, and a table of those
//! points; the accuracy ladder when one was run; the spec's source.

use super::accuracy::{self as text, description, skipped_text};
use super::svg::{MapCell, MapPlot, Marker, Shape, FONT, RED};
use super::table::{self, with_unit};
use super::{disc, plots};
use crate::engine::accuracy::{self as acc, Ladder, Variation};
use crate::engine::check::Check;
use crate::engine::drawing::Disc;
use crate::engine::golden::{sha256_hex, today, GoldenResult};
use crate::engine::optimise::problem::Margin;
use crate::engine::summary::summarise;
use crate::error::{Error, Result};
use crate::files::Batch;
use crate::model::results::SceneResult;
use crate::model::{ContactLaw, Effect, Modification, Plan, Scene};
use crate::numeric::number;
use crate::spec::Spec;
use crate::units;
use maud::{html, Markup, PreEscaped, DOCTYPE};
use std::path::{Path, PathBuf};

/// One optimisation study as the report shows it: the objective map over the study's first two
/// variables with the global sample, the winning local run's path, the start, the references
/// and the optimum; and a table of start, references and optimum. Built from a study result by
/// `report::optimisation::view`; the report only draws it.
#[derive(Debug, Clone, PartialEq)]
pub struct OptimisationView {
    /// The study's name.
    pub name: String,
    /// What it minimises, on which scene, over which bounds (a sentence).
    pub summary: String,
    /// E.g. "shift ΔRp (mm)".
    pub x_label: String,
    /// E.g. "equidistant ΔRrp (mm)".
    pub y_label: String,
    /// E.g. "ratio fluctuation κmax − κmin".
    pub objective_label: String,
    /// The objective on a grid (`MapCell::z` non-finite where a design rule fails); empty when
    /// no map was computed.
    pub map: Vec<MapCell>,
    /// How the map was made (grid, variables held fixed).
    pub map_note: String,
    /// Global-stage samples (x, y, feasible).
    pub global: Vec<(f64, f64, bool)>,
    /// The winning local run's iterates, from its start to the optimum.
    pub path: Vec<(f64, f64)>,
    /// What the path is (which run, from where).
    pub path_label: String,
    /// Evaluations of that run up to the optimum.
    pub path_evaluations: usize,
    pub start: Option<(f64, f64)>,
    pub optimum: Option<(f64, f64)>,
    /// Further labelled points (e.g. a published optimum).
    pub references: Vec<(f64, f64, String)>,
    /// Column headers of the variables in the table, with units.
    pub variables: Vec<String>,
    /// Table rows: start, references, optimum.
    pub points: Vec<StudyPoint>,
    /// Evaluations, time and why the search stopped.
    pub outcome: String,
    /// Remarks: the optimum against each reference, a point that satisfies the paper's Eq. 8
    /// but not the whole-mesh clearance.
    pub notes: Vec<String>,
}

/// One row of a study's table.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyPoint {
    /// "start", a reference's label, "optimum".
    pub label: String,
    /// Variable values in the spec's units, in `OptimisationView::variables` order.
    pub variables: Vec<f64>,
    /// None when the point could not be evaluated.
    pub objective: Option<f64>,
    /// Why the point could not be evaluated.
    pub failure: Option<String>,
    pub feasible: bool,
    /// Every constraint's value, bound and margin (≥ 0 satisfied).
    pub margins: Vec<Margin>,
}

/// Everything the report shows.
pub struct ReportInput<'a> {
    pub spec: &'a Spec,
    /// Limit and golden checks.
    pub checks: &'a [Check],
    pub results: &'a [SceneResult],
    pub goldens: &'a [GoldenResult],
    /// The disc at the drawing's crank angle, as the engine computed it.
    pub disc: &'a Disc,
    /// Optimisation studies to draw and tabulate (none: no optimisation section).
    pub optimisation: &'a [OptimisationView],
    /// The accuracy ladder of a scene (`accuracy:` in the spec), when one was run.
    pub accuracy: Option<&'a Ladder>,
    /// Lines shown as a warning banner under the verdict (e.g. a crank resolution coarser
    /// than the accuracy tolerances need).
    pub warnings: &'a [String],
    /// The disc as built (`measured_profile:`): its identification and the results as
    /// designed, beside `results` (which are as built).
    pub as_built: Option<super::as_built::AsBuiltView<'a>>,
}

/// A section of the page: its anchor, its heading (in the table of contents too) and body.
pub(super) struct Section {
    id: String,
    heading: Markup,
    body: Markup,
}

pub(super) fn section(id: impl Into<String>, heading: Markup, body: Markup) -> Section {
    let id = id.into();
    Section { id, heading, body }
}

/// The report's files, (file name, content): the SVGs, then `index.html` last.
pub fn render(input: &ReportInput) -> Vec<(String, String)> {
    let mut files = Vec::new();
    let designed = input
        .as_built
        .as_ref()
        .map_or(input.spec.modification, |v| v.designed_modification);
    let mut sections = vec![
        summary_section(input.results),
        design_section(input.spec, &designed),
    ];
    if let Some(view) = &input.as_built {
        let built = super::as_built::section_of(input.spec, view, input.results, &mut files);
        sections.push(built);
    }
    if !input.checks.is_empty() {
        sections.push(checks_section(input.checks));
    }
    sections.extend(golden_section(input.goldens));
    sections.push(disc_section(input, &mut files));
    for (k, (scene, r)) in input.spec.scenes.iter().zip(input.results).enumerate() {
        sections.extend(scene_section(input.spec, k, scene, r, &mut files));
    }
    let prefix = |k: usize, s: &Scene| format!("scene-{}-{}", k + 1, slug(&s.name));
    sections.extend(super::torsion::sections(
        input.spec,
        input.results,
        prefix,
        &mut files,
    ));
    if !input.optimisation.is_empty() {
        sections.push(optimisation_section(input.optimisation, &mut files));
    }
    sections.extend(input.accuracy.map(accuracy_section));
    files.push(("index.html".into(), page(input, &sections)));
    files
}

/// Write the report into `dir` (created if missing) as one batch: every file is staged, then
/// all are renamed into place, `index.html` last, so a reader never sees a page that links
/// figures of another run; returns the files written.
pub fn write(dir: &Path, input: &ReportInput) -> Result<Vec<PathBuf>> {
    write_files(dir, &render(input))
}

/// `files` (name, text) into `dir` (created if missing) as one batch, in their order: the
/// page that links the others comes last. Returns the paths written.
pub(super) fn write_files(dir: &Path, files: &[(String, String)]) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(&dir.display().to_string(), e))?;
    let mut batch = Batch::new();
    let mut written = Vec::new();
    for (name, text) in files {
        let path = dir.join(name);
        batch.add(&path, text.as_bytes())?;
        written.push(path);
    }
    batch.commit()?;
    Ok(written)
}

/// A file-name part from a name: ASCII letters, digits, `-` and `_`; anything else `_`. Not
/// unique (`a b` and `a_b` give the same), so file names also carry an index.
fn slug(name: &str) -> String {
    let kept = |c: char| c.is_ascii_alphanumeric() || c == '-' || c == '_';
    name.replace(|c: char| !kept(c), "_")
}

pub(super) fn figure(file: &str, title: &str, caption: &str) -> Markup {
    html! {
        figure {
            img src=(file) alt=(title);
            figcaption { b { (title) } ". " (caption) }
        }
    }
}

/// A table that scrolls sideways instead of running off a narrow window.
fn scrolling(table: Markup) -> Markup {
    html! { div.scroll { (table) } }
}

/// A number with a true minus sign.
fn signed(text: String) -> String {
    text.replace('-', "−")
}

/// A table (in a `scrolling` box) with one header row of `head`'s cells above `rows`.
pub(super) fn data_table(head: Markup, rows: Markup) -> Markup {
    scrolling(html! { table { thead { tr { (head) } } tbody { (rows) } } })
}

fn verdict(passed: bool) -> &'static str {
    if passed {
        "pass"
    } else {
        "fail"
    }
}

/// The headline results of every scene (`engine::summary`).
fn summary_section(results: &[SceneResult]) -> Section {
    let summaries = summarise(results);
    let body = html! {
        p.note { "What each scene computed, at a glance: the extremes of its curves and where \
                  they occur." }
        (data_table(
            html! { th { "scene" } th { "result" } th { "value" } th { "where" } },
            html! {
                @for s in &summaries {
                    @if s.headlines.is_empty() {
                        tr { td { code { (s.scene) } } td colspan="3" {
                            "no headline results (the scene computes none of them)" } }
                    }
                    @for (k, h) in s.headlines.iter().enumerate() {
                        tr {
                            @if k == 0 {
                                td rowspan=(s.headlines.len()) { code { (s.scene) } }
                            }
                            td { (h.quantity.label) }
                            td.num { (with_unit(table::count_or_number(h.value, h.quantity.unit),
                                h.quantity.unit)) }
                            td { (h.at) }
                        }
                    }
                }
            },
        ))
    };
    section("summary", html! { "Headline results" }, body)
}

/// The design as the spec gives it, with the modification `m` it was designed with (the
/// spec's own; with a measured disc the scenes ran on the identified one, `as_built`).
fn design_section(spec: &Spec, m: &Modification) -> Section {
    let d = &spec.design;
    let mm = |x: f64| format!("{} mm", number(x));
    let (disc, rollers) = (&d.disc_material, &d.roller_material);
    let pairs = |head: &str, rows: Markup| data_table(html! { th colspan="2" { (head) } }, rows);
    let row = |k: &str, v: String| html! { tr { th { (k) } td { (v) } } };
    let reducer = html! {
        (row("teeth nc / rollers np", format!("{} / {}", d.teeth, d.rollers)))
        (row("eccentricity e", mm(d.eccentricity_mm)))
        (row("roller circle Rp / roller radius Rrp",
            format!("{} / {}", mm(d.roller_circle_radius_mm), mm(d.roller_radius_mm))))
        (row("face width B", mm(d.face_width_mm)))
        (row("output pins", format!("{} on rw {}, pin radius {}, hole radius {}", d.pins.count,
            mm(d.pins.circle_radius_mm), mm(d.pins.pin_radius_mm), mm(d.hole_radius_mm()))))
        (row("material", format!("E {} GPa, ν {} (rollers and pins: E {} GPa, ν {}); E* {} GPa",
            number(units::gpa(disc.youngs_modulus_mpa)), number(disc.poisson_ratio),
            number(units::gpa(rollers.youngs_modulus_mpa)), number(rollers.poisson_ratio),
            number(units::gpa(d.contact_modulus_mpa())))))
        (row("K1 = e·np/Rp", number(d.k1())))
        @if d.discs > 1 {
            (row("discs", format!("{}, at crank phases {}", d.discs,
                (0..d.discs).map(|k| format!("{}°", number(units::deg(d.disc_phase_rad(k)))))
                    .collect::<Vec<_>>().join(", "))))
        }
        @if let Some(b) = &d.crank_bearing {
            (row("crank bearing (each disc)", format!("C {} N, life exponent p {}",
                number(b.dynamic_load_rating_n), number(b.life_exponent))))
        }
    };
    let modification = html! {
        (row("shift ΔRp", mm(m.shift_mm)))
        (row("equidistant ΔRrp", mm(m.equidistant_mm)))
        (row("rotation Δδ", format!("{} deg", number(units::deg(m.rotation_rad)))))
        (row("tip clearance ΔRrp − ΔRp", format!("{} µm", number(units::um(m.tip_clearance_mm())))))
    };
    let body = html! {
        div.cols { (pairs("reducer", reducer)) (pairs("tooth-profile modification", modification)) }
    };
    section("design", html! { "Design" }, body)
}

fn checks_section(checks: &[Check]) -> Section {
    let body = html! {
        p.note { "Failures first, the furthest outside its limit first." }
        (data_table(
            html! { th { "check" } th { "value" } th { "limit" } th { "verdict" } th { "where" } },
            html! {
                @for c in table::ordered(checks) {
                    tr class=(verdict(c.passed)) {
                        td { code { (c.id) } }
                        td.num { (with_unit(number(c.value), c.unit)) }
                        td.num { (with_unit(format!("{} {}", c.bound.symbol(),
                            number(c.limit)), c.unit)) }
                        td.verdict { (if c.passed { "pass" } else { "FAIL" }) }
                        td { (c.at) }
                    }
                }
            },
        ))
    };
    section("checks", html! { "Checks" }, body)
}

fn golden_section(goldens: &[GoldenResult]) -> Option<Section> {
    if goldens.is_empty() {
        return None;
    }
    let body = html! {
        p.note { "Each curve compared point by point with its reviewed reference; the worst \
                  point is the one furthest outside (or least inside) its band abs + rel·|golden|." }
        (data_table(
            html! { th { "curve" } th { "golden file" } th { "worst |deviation|" }
                th { "band there" } th { "where" } th { "points" } th { "verdict" } },
            html! {
                @for g in goldens {
                    @let w = &g.comparison.worst;
                    tr class=(verdict(g.comparison.passed)) {
                        td { code { (g.golden.scene) "/" (g.golden.quantity.key) (g.golden.disc_suffix()) } }
                        td { code { (g.golden.path.display()) } }
                        td.num { (with_unit(number(w.deviation), g.unit)) }
                        td.num { (with_unit(number(w.band), g.unit)) }
                        td { (w.place()) }
                        td.num { (g.comparison.points) }
                        td.verdict { (if g.comparison.passed { "pass" } else { "FAIL" }) }
                    }
                }
            },
        ))
    };
    Some(section("golden", html! { "Golden curves" }, body))
}

/// The disc at the drawing's crank angle and the close-up of its tightest roller.
fn disc_section(input: &ReportInput, files: &mut Vec<(String, String)>) -> Section {
    let d = &input.spec.design;
    let phi = format!("{:.2}", units::deg(input.disc.crank_rad));
    let (whole, whole_caption) = disc::whole(input.disc, d.teeth, d.eccentricity_mm);
    let (detail, detail_caption) = disc::close_up(input.disc);
    files.push(("disc.svg".into(), whole));
    files.push(("disc-detail.svg".into(), detail));
    let body = html! {
        div.grid {
            (figure("disc.svg", &format!("Disc, rollers and output pins at crank φ = {phi}°"),
                &whole_caption))
            (figure("disc-detail.svg", "Close-up of the smallest gap", &detail_caption))
        }
    };
    section("disc", html! { "The disc at crank φ = " (phi) "°" }, body)
}

/// A scene's plots, or nothing when it computed no curve a plot draws.
fn scene_section(
    spec: &Spec,
    k: usize,
    scene: &Scene,
    r: &SceneResult,
    files: &mut Vec<(String, String)>,
) -> Option<Section> {
    let prefix = format!("scene-{}-{}", k + 1, slug(&scene.name));
    let plots = plots::scene_plots(spec, r, &prefix);
    // With several discs, each disc's own curves (forces, lags, bearing, its torque share).
    let discs: Vec<(usize, Vec<plots::Plot>)> = r
        .discs
        .iter()
        .enumerate()
        .map(|(d, disc)| {
            (
                d,
                plots::scene_plots(spec, disc, &format!("{prefix}-disc-{d}")),
            )
        })
        .filter(|(_, p)| !p.is_empty())
        .collect();
    if plots.is_empty() && discs.is_empty() {
        return None;
    }
    let phase = |d: usize| number(units::deg(spec.design.disc_phase_rad(d)));
    let body = html! {
        p.note { (scene_summary(spec, scene)) }
        @if !plots.is_empty() {
            div.grid { @for p in &plots { (figure(&p.file, &p.title, &p.caption)) } }
        }
        @for (d, disc) in &discs {
            h3 { "Disc " (d) " (crank phase " (phase(*d)) "°)" }
            div.grid { @for p in disc { (figure(&p.file, &p.title, &p.caption)) } }
        }
    };
    files.extend(plots.into_iter().map(|p| (p.file, p.svg)));
    files.extend(
        discs
            .into_iter()
            .flat_map(|(_, p)| p)
            .map(|p| (p.file, p.svg)),
    );
    let heading = html! { "Scene " code { (scene.name) } };
    Some(section(prefix, heading, body))
}

fn scene_summary(spec: &Spec, scene: &Scene) -> String {
    let plan = Plan::for_scene(scene);
    let step = match scene.crank_rad.as_slice() {
        [a, b, ..] => units::deg(b - a),
        _ => 0.0,
    };
    let effects: Vec<&str> = plan.effects.iter().map(|p| p.effect.name()).collect();
    let load = match &scene.torque_sweep {
        Some(t) => format!(
            "Input locked; output torque swept ±{} N·m ({} steps per quarter loop)",
            number(units::nm(t.rated_nmm)),
            t.steps
        ),
        None => format!(
            "Output torque {} N·m",
            number(units::nm(scene.output_torque_nmm))
        ),
    };
    let discs = match spec.design.discs {
        1 => String::new(),
        n => format!(", shared by {n} discs"),
    };
    let mut s = format!(
        "{load}{discs}; {} crank angles from {:.2}° in steps of {}°; computes {}.",
        scene.crank_rad.len(),
        scene.crank_rad.first().map_or(0.0, |&a| units::deg(a)),
        number(step),
        effects.join(", ")
    );
    if plan.has(Effect::RollerContact) {
        s += &format!(
            " Contact law {}, {} geometry, {} crank bearing.",
            match scene.contact_law {
                ContactLaw::PaperLinear => "F = (π/4)·E*·L·d (paper Eq. 9)",
                ContactLaw::HertzNonlinear => "Hertz line contact (Johnson, non-linear)",
            },
            scene.geometry,
            match scene.bearing_stiffness_n_per_mm {
                Some(k) => format!("compliant ({} N/mm)", number(k)),
                None => "rigid".into(),
            }
        );
    }
    let pins = plan.has(Effect::OutputPins);
    // (A torsion scene's crank angles are where the input is locked, not a sweep.)
    if scene.torque_sweep.is_none() && !scene.spans_loaded_periods(&spec.design, &plan) {
        s += if pins {
            " The sweep does not cover whole periods of the loaded disc (mesh and output pins)."
        } else {
            " The sweep does not cover whole mesh periods."
        };
    }
    s
}

fn optimisation_section(views: &[OptimisationView], files: &mut Vec<(String, String)>) -> Section {
    let mut studies = Vec::new();
    for (k, o) in views.iter().enumerate() {
        let file = format!("optimisation-{}-{}.svg", k + 1, slug(&o.name));
        files.push((file.clone(), optimisation_svg(o)));
        studies.push(study(o, &file));
    }
    let body = html! {
        p.note { "Every study of the spec: the objective over its first two variables, where the \
                  optimiser looked and what it found; the table gives the objective and every \
                  constraint at the start, the references and the optimum." }
        @for s in studies { (s) }
    };
    section("optimisation", html! { "Optimisation" }, body)
}

fn optimisation_svg(o: &OptimisationView) -> String {
    let marker = |(x, y): (f64, f64), label: &str, color: &str, shape| Marker {
        x,
        y,
        label: label.into(),
        color: color.into(),
        shape,
    };
    let start = o
        .start
        .map(|p| marker(p, "start", "#ff7f0e", Shape::Circle));
    let references = o
        .references
        .iter()
        .map(|(x, y, l)| marker((*x, *y), l, "#111111", Shape::Diamond));
    let optimum = o.optimum.map(|p| marker(p, "optimum", RED, Shape::Star));
    let markers = start.into_iter().chain(references).chain(optimum).collect();
    MapPlot {
        title: format!("Study {}: objective over the modification", o.name),
        subtitle: o.map_note.clone(),
        x_label: o.x_label.clone(),
        y_label: o.y_label.clone(),
        z_label: o.objective_label.clone(),
        cells: o.map.clone(),
        samples: o.global.clone(),
        samples_label: "global sample".into(),
        path: o.path.clone(),
        path_label: o.path_label.clone(),
        markers,
        width: 700.0,
    }
    .to_svg()
}

/// A constraint's margin as the table shows it: on the bound within the checker's tolerance
/// (decimal inputs such as 0.150 − 0.135 land a few 1e-17 mm off), else signed.
fn margin_text(m: &Margin) -> String {
    if m.margin.abs() <= crate::engine::check::tolerance(m.bound) {
        "margin 0 (on the bound)".into()
    } else {
        let sign = if m.margin > 0.0 { "+" } else { "" };
        signed(format!("margin {sign}{}", number(m.margin)))
    }
}

/// A study's heading, table (one column per point: start, references, optimum), outcome,
/// notes and figure.
fn study(o: &OptimisationView, file: &str) -> Markup {
    let constraints: Vec<&Margin> = o
        .points
        .iter()
        .max_by_key(|p| p.margins.len())
        .map(|p| p.margins.iter().collect())
        .unwrap_or_default();
    let optimum = |p: &StudyPoint| (p.label == "optimum").then_some("optimum");
    let path = if o.path.len() > 1 {
        format!(
            "Red: the iterates of {} up to the optimum ({} evaluations; COBYLA probes around \
             its trust region, so the path zig-zags).",
            o.path_label, o.path_evaluations
        )
    } else {
        "No path: the optimum is a point of the global stage.".to_string()
    };
    let caption = format!(
        "Colour: {} on the grid ({}); hatched cells violate a constraint, and the colour range \
         is that of the feasible cells. White dots and crosses: the feasible and infeasible \
         points of the global stage. {path} Orange circle: the start;{} red star: the \
         optimum, the best feasible point evaluated anywhere.",
        o.objective_label,
        if o.map.is_empty() {
            "no map computed"
        } else {
            &o.map_note
        },
        if o.references.is_empty() {
            ""
        } else {
            " black diamonds: the references;"
        },
    );
    let table = html! {
        table.study {
            thead { tr { th {} @for p in &o.points { th class=[optimum(p)] { (p.label) } } } }
            tbody {
                @for (k, v) in o.variables.iter().enumerate() {
                    tr {
                        th { (v) }
                        @for p in &o.points {
                            td.num.optimum[optimum(p).is_some()] {
                                (p.variables.get(k).map_or(String::new(),
                                    |x| signed(format!("{x:.6}"))))
                            }
                        }
                    }
                }
                tr {
                    th { (o.objective_label) }
                    @for p in &o.points {
                        @match p.objective {
                            Some(z) => td.num.optimum[optimum(p).is_some()] { (signed(number(z))) },
                            None => td.violated { "not evaluated: "
                                (p.failure.as_deref().unwrap_or("no value")) },
                        }
                    }
                }
                @for c in &constraints { (constraint_row(c, &o.points)) }
                tr {
                    th { "verdict" }
                    @for p in &o.points {
                        td.verdict class=(if p.feasible { "pass" } else { "fail" }) {
                            (if p.feasible { "feasible" } else { "INFEASIBLE" })
                        }
                    }
                }
            }
        }
    };
    html! {
        h3 { "Study " code { (o.name) } }
        p.note { (o.summary) }
        div.grid {
            (figure(file, &format!("Study {}: objective map and search", o.name), &caption))
            div {
                (scrolling(table))
                p.note { (o.outcome) }
                @if !o.notes.is_empty() { ul.note { @for n in &o.notes { li { (n) } } } }
            }
        }
    }
}

/// A constraint's row: its name and bound, then each point's value and margin.
fn constraint_row(c: &Margin, points: &[StudyPoint]) -> Markup {
    let (name, qualifier) = match c.name.split_once(" (") {
        Some((n, q)) => (n, format!(" ({q}")),
        None => (c.name.as_str(), String::new()),
    };
    // A lower bound has margin value − bound, an upper one bound − value.
    let op = if (c.margin - (c.value - c.bound)).abs() <= (c.margin - (c.bound - c.value)).abs() {
        "≥"
    } else {
        "≤"
    };
    html! {
        tr {
            th { (name) br; small { (op) " " (number(c.bound)) (qualifier) } }
            @for p in points {
                @match p.margins.iter().find(|m| m.name == c.name) {
                    Some(m) => td.num.violated[!m.satisfied()] {
                        (signed(number(m.value))) br; small { (margin_text(m)) }
                    },
                    None => td.num { "—" },
                }
            }
        }
    }
}

/// The accuracy ladder as a table: one row per rung, errors against the reference, times, the
/// cheapest rung that meets every tolerance highlighted; observed orders and notes below.
fn accuracy_section(ladder: &Ladder) -> Section {
    let l = &ladder.layout;
    let missing: Vec<String> = acc::Quantity::ALL
        .into_iter()
        .filter(|q| !l.quantities.contains(q))
        .map(description)
        .collect();
    let settings_rungs = ladder.rungs.iter().any(|r| r.variation != Variation::Steps);
    let other_law = ladder
        .rungs
        .iter()
        .any(|r| r.variation == Variation::ContactLaw);
    let time = |s: f64| {
        if s < 1.0 {
            format!("{:.1} ms", s * 1000.0)
        } else {
            format!("{s:.2} s")
        }
    };
    let orders: Vec<_> = l
        .quantities
        .iter()
        .map(|&q| (q, ladder.orders(q)))
        .filter(|(_, o)| !o.is_empty())
        .collect();
    let order_text = |p: Option<f64>| p.map_or("—".to_string(), text::order_text);
    let body = html! {
        p.note {
            "Scene " code { (l.scene) } " over crank " (number(l.from_deg)) "° to "
            (number(l.to_deg)) "° (" (text::steps_text(l.periods)) " mesh periods) on a ladder of \
            settings. The reference is the finest rung: " (l.finest) " steps per mesh period, "
            (l.geometry.name()) " geometry, " (l.law.name()) ", solver rel_tol 1e-11. Each error \
            is |rung − reference| in the quantity's unit; the TE curve's is the largest difference \
            between the reference and the rung's curve interpolated linearly between its crank \
            angles. Times are wall-clock measurements of the rung's run (the fastest of up to "
            (acc::REPEATS) " runs for runs under " (acc::REPEAT_BELOW_S * 1000.0) " ms)."
            @if !missing.is_empty() { " Not computed by this scene (no column): "
                (missing.join(", ")) "." }
            @if settings_rungs {
                " The rungs that change one setting run at " (ladder.settings_steps)
                " steps per mesh period"
                @if ladder.settings_steps == l.finest {
                    " (the finest, so their errors are the setting's own effect)."
                } @else { "; their errors include that resolution's, shown by its steps rung." }
            }
            @if other_law { " Another contact law is another model: its difference from the \
                reference is a model difference, not a discretisation error, and it is never the \
                cheapest." }
            @for &k in &ladder.skipped { " Skipped: " (skipped_text(k)) "." }
        }
        p {
            @match ladder.cheapest {
                Some(i) if ladder.rungs[i].is_reference => "Only the reference meets every \
                    tolerance; its own error is not measured (no finer rung).",
                Some(i) => { "Cheapest rung meeting every tolerance: " b { (ladder.rungs[i].label) }
                    " (" (text::steps_text(ladder.rungs[i].steps_per_period)) " steps per mesh period)." },
                None => "No rung meets every tolerance.",
            }
        }
        (data_table(
            html! {
                th { "rung" } th { "steps per mesh period" } th { "crank angles" }
                th { "geometry" } th { "contact law" } th { "solver rel_tol" } th { "time" }
                @for q in &l.quantities {
                    th { (q.label()) @if !q.unit().is_empty() { " (" (q.unit()) ")" }
                        br; span.note { "tol " (text::short(q.tolerance(&l.tolerances))) } }
                }
                th { "tolerances" }
            },
            html! {
                @for (i, r) in ladder.rungs.iter().enumerate() {
                    @let cheapest = ladder.cheapest == Some(i);
                    @let (class, verdict) = text::verdict(r, &l.tolerances);
                    tr class=(if cheapest { "pass cheapest" } else { class }) {
                        td { (r.label) }
                        td.num { (text::steps_text(r.steps_per_period)) }
                        td.num { (r.angles) }
                        td { (r.geometry.name()) }
                        td { (r.law.name()) }
                        td.num { (format!("{:e}", r.rel_tol)) }
                        td.num { (time(r.seconds)) }
                        @for &q in &l.quantities {
                            @let over = !r.is_reference && !r.model_difference
                                && r.error(q).is_some_and(|e| !q.within(e, &l.tolerances));
                            td.num.over[over] {
                                @if r.is_reference { "—" }
                                @else { (r.error(q).map_or("n/a".to_string(), text::short)) }
                            }
                        }
                        td.verdict { (verdict) @if cheapest { " — " b { "cheapest" } } }
                    }
                }
            },
        ))
        @if let Some((first, _)) = orders.first() {
            p.note { "Observed order of convergence log2(e(N)/e(2N)) of the steps rungs (— where \
                      an error is at round-off), and the least-squares fit over N = 12 … \
                      finest/4." }
            (data_table(
                html! { th { "quantity" }
                    @for (n, _) in ladder.orders(*first) { th { (n) "→" (2 * n) } } th { "fit" } },
                html! {
                    @for (q, o) in &orders {
                        tr {
                            td { (q.label()) }
                            @for (_, p) in o { td.num { (order_text(*p)) } }
                            td.num { b { (order_text(ladder.fitted_order(*q))) } }
                        }
                    }
                },
            ))
        }
    };
    let heading = html! { "Accuracy ladder: what accuracy costs in time" };
    section("accuracy", heading, body)
}

const STYLE: &str = r#"
body { font-family: FONT; color: #222; margin: 24px auto; max-width: 1360px; padding: 0 16px; line-height: 1.4; }
h1 { font-size: 26px; margin: 0 0 6px; }
h2 { font-size: 20px; margin: 28px 0 10px; border-bottom: 1px solid #ddd; padding-bottom: 4px; }
h3 { font-size: 17px; margin: 22px 0 4px; }
.meta { color: #555; font-size: 13px; overflow-wrap: anywhere; }
.meta code { font-size: 12px; }
.banner { font-size: 18px; font-weight: bold; padding: 10px 14px; border-radius: 4px; margin: 12px 0; }
.banner.pass { background: #e3f4e1; color: #1d6b1a; border: 1px solid #9fd39a; }
.banner.fail { background: #fde2e2; color: #a11212; border: 1px solid #f0a1a1; }
.banner.warn { background: #fff4d6; color: #6b4a00; border: 1px solid #e8c768; font-size: 15px; }
.banner.warn p { margin: 2px 0; }
nav.toc { font-size: 14px; background: #f7f7f7; border: 1px solid #e3e3e3; border-radius: 4px; padding: 6px 14px; }
nav.toc ol { margin: 4px 0; padding-left: 22px; columns: 2 260px; }
.scroll { overflow-x: auto; max-width: 100%; }
table { border-collapse: collapse; font-size: 14px; margin: 6px 0; }
th, td { text-align: left; padding: 4px 10px; border-bottom: 1px solid #eee; vertical-align: top; }
thead th { background: #f3f3f3; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
tr.fail td.verdict { color: #b00; font-weight: bold; }
tr.pass td.verdict { color: #1d6b1a; }
tr.fail { background: #fff3f3; }
tr.cheapest { background: #e3f4e1; font-weight: bold; }
tr.reference { background: #f3f3f3; }
td.over { color: #b00; }
table.study th { font-weight: normal; }
table.study thead th { font-weight: bold; text-align: right; }
table.study .optimum { font-weight: bold; }
table.study small { font-weight: normal; color: #666; }
td.verdict.pass { color: #1d6b1a; }
td.verdict.fail, td.violated { color: #b00; font-weight: bold; }
.cols { display: flex; gap: 40px; flex-wrap: wrap; }
.grid { display: grid; grid-template-columns: repeat(auto-fill, minmax(min(660px, 100%), 1fr)); gap: 18px; }
figure { margin: 0; }
figure img { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption { font-size: 13px; color: #444; max-width: 660px; }
.note { color: #555; font-size: 14px; }
pre { background: #f7f7f7; padding: 10px; font-size: 12px; overflow-x: auto; }
"#;

fn page(input: &ReportInput, sections: &[Section]) -> String {
    let failed = input.checks.iter().filter(|c| !c.passed).count();
    let total = input.checks.len();
    let banner = html! {
        @if total == 0 {
            p.banner.pass { "No checks: the spec sets no limits and no golden curves; \
                the headline results below are what it computed" }
        } @else if failed == 0 {
            p.banner.pass { "PASSED: " (if total == 1 { "the one check passes".to_string() }
                else { format!("all {total} checks pass") }) }
        } @else {
            p.banner.fail { "FAILED: " (failed) " of " (total) " checks fail" }
        }
        @if !input.warnings.is_empty() {
            div.banner.warn { @for w in input.warnings { p { "Warning: " (w) } } }
        }
    };
    shell(input.spec, "Design review", banner, sections)
}

/// A page of the report's look: `title` of the spec, its identity, the `banner`, a table of
/// contents of `sections`, the sections and the spec's source.
pub(super) fn shell(spec: &Spec, title: &str, banner: Markup, sections: &[Section]) -> String {
    let page = html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                meta name="viewport" content="width=device-width, initial-scale=1";
                title { (title) ": " (spec.name) }
                style { (PreEscaped(STYLE.replace("FONT", FONT))) }
            }
            body {
                h1 { (title) ": " (spec.name) }
                p.meta {
                    "spec " code { (spec.path) } " · SHA-256 " code { (sha256_hex(&spec.source)) }
                    " · cycloid " (env!("CARGO_PKG_VERSION")) " · generated " (today())
                }
                (banner)
                nav.toc {
                    b { "Contents" }
                    ol { @for s in sections { li { a href=(format!("#{}", s.id)) { (s.heading) } } } }
                }
                @for s in sections {
                    section id=(s.id) { h2 { (s.heading) } (s.body) }
                }
                section #source {
                    details { summary { "Spec source" } pre { (spec.source) } }
                }
            }
        }
    };
    page.into_string()
}
