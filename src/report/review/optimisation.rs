//! The review's optimisation studies: per study the objective map with the global sample, the
//! winning local run's path, the start, the references and the optimum, and a table of those
//! points with every constraint's margin. Drawn from an `OptimisationView`, which
//! [`report::optimisation::view`](crate::report::optimisation::view) builds from a study's result.

use super::common::{figure, numbered, scrolling, signed, verdict, Section};
use crate::engine::optimise::problem::Margin;
use crate::numeric::number;
use crate::report::svg::{MapCell, MapPlot, Marker, Shape, RED};
use maud::{html, Markup};

/// One optimisation study as the report shows it: the objective map over the study's first two
/// variables with the global sample, the winning local run's path, the start, the references
/// and the optimum; and a table of start, references and optimum. Built from a study result by
/// [`report::optimisation::view`](crate::report::optimisation::view); the report only draws it.
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
    /// Whether the first (x) and second (y) variables are searched, and so drawn, on a log
    /// scale (the crown radius: the map's cells are spaced evenly in its logarithm).
    pub log_axes: (bool, bool),
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

pub(super) fn section(views: &[OptimisationView], files: &mut Vec<(String, String)>) -> Section {
    let mut studies = Vec::new();
    for (k, o) in views.iter().enumerate() {
        let file = format!("{}.svg", numbered("optimisation", k, &o.name));
        files.push((file.clone(), optimisation_svg(o)));
        studies.push(study(o, &file));
    }
    let body = html! {
        p.note { "Every study of the spec: the objective over its first two variables, where the \
                  optimiser looked and what it found; the table gives the objective and every \
                  constraint at the start, the references and the optimum." }
        @for s in studies { (s) }
    };
    Section::new("optimisation", html! { "Optimisation" }, body)
}

pub(super) fn optimisation_svg(o: &OptimisationView) -> String {
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
        log_axes: o.log_axes,
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

/// A study's heading, table (one column per point: start, references, optimum), outcome,
/// notes and figure.
pub(super) fn study(o: &OptimisationView, file: &str) -> Markup {
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
                        td.verdict class=(verdict(p.feasible)) {
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
pub(super) fn constraint_row(c: &Margin, points: &[StudyPoint]) -> Markup {
    let (name, qualifier) = match c.name.split_once(" (") {
        Some((n, q)) => (n, format!(" ({q}")),
        None => (c.name.as_str(), String::new()),
    };
    html! {
        tr {
            th { (name) br; small { (c.side.symbol()) " " (number(c.bound)) (qualifier) } }
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

/// A constraint's margin as the table shows it: on the bound within the checker's tolerance
/// (decimal inputs such as 0.150 − 0.135 land a few 1e-17 mm off), else signed.
pub(super) fn margin_text(m: &Margin) -> String {
    let margin = m.margin();
    if margin.abs() <= crate::engine::limit::tolerance(m.bound) {
        "margin 0 (on the bound)".into()
    } else {
        let sign = if margin > 0.0 { "+" } else { "" };
        signed(format!("margin {sign}{}", number(margin)))
    }
}
