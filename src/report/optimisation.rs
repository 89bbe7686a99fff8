//! Text of an optimisation study: start, references and optimum with objective values, every
//! constraint's margin, evaluations, time and why it stopped; the objective map CSV; and the
//! same study as a view for the design-review report (`view`).

use crate::engine::limit::passes;
use crate::engine::optimise::local::StopReason;
use crate::engine::optimise::problem::Evaluation;
use crate::engine::optimise::verify::Verification;
use crate::engine::optimise::{Found, StudyResult};
use crate::model::{Study, VariableKind};
use crate::numeric::{number, with_unit};
use crate::report::place::counted;
use crate::report::review::plots::capitalised;
use crate::report::review::{OptimisationView, StudyPoint};
use crate::report::svg::MapCell;
use crate::spec::Spec;

fn objective_label(study: &Study) -> String {
    study
        .objective
        .iter()
        .map(|(o, w)| {
            let unit = if o.quantity.unit.is_empty() {
                String::new()
            } else {
                format!(" [{}]", o.quantity.unit)
            };
            if study.objective.len() == 1 {
                format!("{}{unit}", o.name)
            } else {
                format!("{w}·{}{unit}", o.name)
            }
        })
        .collect::<Vec<_>>()
        .join(" + ")
}

fn variables(study: &Study, e: &Evaluation) -> String {
    study
        .variables
        .iter()
        .map(|v| format!("{} {:.6}", v.kind.key(), v.kind.spec_value(&e.point)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The objective of a point, or why it has none (never "inf").
fn objective_text(e: &Evaluation) -> String {
    match &e.failure {
        Some(why) => format!("not evaluated ({why})"),
        None if !e.objective.is_finite() => "not evaluated".to_string(),
        None => format!("objective {}", number(e.objective)),
    }
}

/// What the objective alone hides: the whole-mesh min clearance (µm) and the unloaded lost
/// motion (arcsec) of a point.
fn geometry_text(e: &Evaluation) -> String {
    let clearance = e.min_clearance.map_or("—".to_string(), |m| {
        format!("{} µm", number(crate::units::um(m.gap_mm)))
    });
    let lost = e
        .lost_motion_arcsec
        .map_or("—".to_string(), |a| match a < 0.0 {
            // A free play is never negative: overlapping closing lags are a preload.
            true => format!("0 arcsec (preloaded: overlap {} arcsec)", number(-a)),
            false => format!("{} arcsec", number(a)),
        });
    format!("min clearance {clearance}, lost motion {lost}")
}

fn row(study: &Study, label: &str, e: &Evaluation) -> String {
    let verdict = if e.feasible() {
        "feasible"
    } else {
        "INFEASIBLE"
    };
    format!(
        "  {label:<16} {}: {}, {verdict}; {}\n",
        variables(study, e),
        objective_text(e),
        geometry_text(e)
    )
}

/// Where the optimum was found, in words ("found by local run 2 (converged: …)").
pub fn found(f: Found) -> String {
    match f {
        Found::Start => "the start is the best point evaluated".to_string(),
        Found::GlobalSample(i) => format!(
            "the best point is global sample {}; every local run ended higher",
            i + 1
        ),
        Found::LocalRun(k, stop) => format!("found by local run {} ({})", k + 1, stop_text(stop)),
        Found::GridPoint => {
            "the best point is a point of the verification grid; its refinements ended higher"
                .to_string()
        }
        Found::Refinement(k, stop) => format!(
            "found by refinement {} from the verification grid ({})",
            k + 1,
            stop_text(stop)
        ),
    }
}

/// Why a local run stopped.
fn stop_text(s: StopReason) -> &'static str {
    match s {
        StopReason::StepBelowTolerance => "converged: step below the variable tolerance",
        StopReason::ObjectiveChangeBelowTolerance => {
            "converged: objective change below the tolerance"
        }
        StopReason::BudgetUsedUp => "stopped: evaluation budget used up",
        StopReason::Ended => "stopped: COBYLA ended without a tolerance met",
        StopReason::RoundoffLimited => "stopped: progress limited by round-off",
        StopReason::Failed => "COBYLA failed",
    }
}

/// How the search went: evaluations, time and where the optimum was found.
pub fn outcome(r: &StudyResult) -> String {
    format!(
        "{} evaluations ({} global, {}{}) in {:.2} s; {}",
        r.evaluations,
        r.global.len(),
        counted(r.local_runs.len(), "local run"),
        r.verification.as_ref().map_or(String::new(), |v| format!(
            ", {} grid points{}",
            v.points,
            match v.refinements.len() {
                0 => String::new(),
                n => format!(", {}", counted(n, "refinement")),
            }
        )),
        r.elapsed.as_secs_f64(),
        found(r.found)
    )
}

/// A note per variable whose optimum sits on a bound of its range (within 1e-6 of the range:
/// the local runs' step tolerance): the best point inside the box may not be the optimum the
/// design has, which may lie beyond the bound.
fn on_bounds(study: &Study, r: &StudyResult) -> String {
    let mut out = String::new();
    for v in &study.variables {
        let x = v.kind.get(&r.optimum.point);
        let near = 1e-6 * (v.upper - v.lower).abs();
        let side = if (x - v.lower).abs() <= near {
            "lower"
        } else if (v.upper - x).abs() <= near {
            "upper"
        } else {
            continue;
        };
        if v.kind == VariableKind::CrownStart && side == "lower" && v.lower == 0.0 {
            // Nothing lies beyond: a flat middle of no length is a crown over the whole face.
            out += "  note: the optimum is crowned over the whole face (crown_start_mm at 0, \
                    its least)\n";
            continue;
        }
        out += &format!(
            "  note: the optimum sits on the {side} bound of {} ({}): the best point may lie \
             beyond it; widen the range to see\n",
            v.kind.key(),
            crate::numeric::input(v.kind.to_spec_unit(x))
        );
    }
    out
}

/// The verification grid's size: "41 × 41".
fn grid(v: &Verification, dims: usize) -> String {
    vec![v.steps.to_string(); dims.max(1)].join(" × ")
}

/// How good the optimum is against the verification grid, in one sentence.
pub fn verification_text(study: &Study, r: &StudyResult) -> Option<String> {
    let v = r.verification.as_ref()?;
    let grid = grid(v, study.variables.len());
    // A difference at the objective's round-off (1e-9 of it, the local runs' stop tolerance)
    // is a tie, not a grid point beating the search.
    let round_off = |d: f64| d <= 1e-9 * r.optimum.objective.abs();
    let n = v.refinements.len();
    let refined = format!("{} from there; ", counted(n, "refinement"));
    let searched = match v.beat_search_by() {
        Some(d) if round_off(d) => format!(
            "a grid point tied with the search (by {}, round-off), {refined}",
            number(d)
        ),
        Some(d) => format!("a grid point beat the search by {}, {refined}", number(d)),
        None => String::new(),
    };
    Some(match (&v.best, v.margin) {
        (None, _) => format!(
            "verification: none of the {} points of the {grid} grid is feasible",
            v.points
        ),
        (Some(_), None) => format!(
            "verification: {searched}the optimum is infeasible, {} of the {} points of the \
             {grid} grid are feasible",
            v.feasible, v.points
        ),
        (Some(b), Some(0.0)) => format!(
            "verification: {searched}no point of the {grid} grid is better than the optimum: the \
             best of its {} feasible points equals it, {}",
            v.feasible,
            number(b.objective)
        ),
        (Some(b), Some(margin)) if margin >= 0.0 => format!(
            "verification: {searched}no point of the {grid} grid is better than the optimum: the \
             best of its {} feasible points, {}, is higher by {}",
            v.feasible,
            number(b.objective),
            number(margin)
        ),
        (Some(b), Some(margin)) => format!(
            "verification: {searched}the best of the {} feasible points of the {grid} grid, {}, \
             is better than the optimum by {}",
            v.feasible,
            number(b.objective),
            number(-margin)
        ),
    })
}

/// Say when a point satisfies the paper's Eq. 8 (tip clearance) but not the whole-mesh check.
fn eq8_note(label: &str, e: &Evaluation, study: &Study) -> Option<String> {
    let (lo, _) = study.tip_clearance_mm?;
    let min = e.min_clearance?;
    let dt = study.min_clearance_mm?;
    let tip = e.point.modification.tip_clearance_mm();
    let at_least = |x: f64, limit: f64| passes(x, limit, crate::model::quantity::Bound::Min);
    (at_least(tip, lo) && !at_least(min.gap_mm, dt)).then(|| {
        format!(
            "  note: the {label} satisfies the paper's Eq. 8 (ΔRrp − ΔRp = {:.4} mm ≥ {lo} mm) but \
             violates the whole-mesh clearance: {:.1} µm < {:.1} µm at roller {}, crank {:.2}°, \
             tooth phase {} (0 root, 0.5 tip){}\n",
            tip,
            crate::units::um(min.gap_mm),
            crate::units::um(dt),
            min.roller,
            crate::units::deg(min.crank_rad),
            crate::numeric::phase(min.tooth_phase),
            if min.gap_mm < 0.0 { " — interference" } else { "" }
        )
    })
}

/// The full text of one study result.
pub fn render(spec: &Spec, study: &Study, r: &StudyResult) -> String {
    let scene = &spec.scenes[study.scene];
    let mut out = format!(
        "study `{}`: minimise {} on scene `{}` ({} N·m, {} crank angles)\n",
        r.name,
        objective_label(study),
        scene.name,
        crate::units::nm(scene.output_torque_nmm),
        scene.crank_rad.len()
    );
    for (label, e) in listed(r) {
        out += &row(study, label, e);
    }
    for (label, _, diff) in against_references(r) {
        let verdict = match diff {
            d if d < 0.0 => "better",
            0.0 => "equal",
            _ => "WORSE",
        };
        out += &format!("  optimum vs {label}: {} ({verdict})\n", number(diff));
    }
    out += &on_bounds(study, r);
    out += "  constraints at the optimum:\n";
    for m in &r.optimum.margins {
        out += &format!(
            "    {:<40} value {:>10}  bound {:>8}  margin {:>10}  {}\n",
            m.name,
            number(m.value),
            number(m.bound),
            number(m.margin()),
            if m.satisfied() { "ok" } else { "VIOLATED" }
        );
    }
    for (label, e) in listed(r) {
        if let Some(note) = eq8_note(label, e, study) {
            out += &note;
        }
    }
    if let Some(v) = verification_text(study, r) {
        out += &format!("  {v}\n");
    }
    if !r.optimum.feasible() {
        out += "  no feasible point was found: every point evaluated violates a constraint or \
                a design rule (the optimum above is the least infeasible)\n";
    }
    out += &format!("  {}\n", outcome(r));
    out
}

/// CSV of an objective map: the first two variables, objective, feasibility and margins.
pub fn map_csv(study: &Study, cells: &[Evaluation]) -> String {
    let vars = &study.variables;
    let mut out = String::new();
    for v in vars.iter().take(2) {
        out += &format!("{},", v.kind.key());
    }
    out += "objective,feasible,min_clearance_mm,tip_clearance_mm\n";
    for e in cells {
        for v in vars.iter().take(2) {
            out += &format!("{},", v.kind.spec_value(&e.point));
        }
        let objective = if e.objective.is_finite() {
            format!("{}", e.objective)
        } else {
            String::new()
        };
        let min = e
            .min_clearance
            .map_or(String::new(), |m| format!("{}", m.gap_mm));
        out += &format!(
            "{objective},{},{min},{}\n",
            e.feasible(),
            e.point.modification.tip_clearance_mm()
        );
    }
    out
}

/// A spec input as written (0.015, 0.5), or to 4 significant digits when longer.
fn short(v: f64) -> String {
    let plain = format!("{v}");
    if plain.len() <= 8 {
        plain
    } else {
        number(v)
    }
}

/// Axis label of a variable, with its unit.
pub fn variable_label(kind: VariableKind) -> &'static str {
    match kind {
        VariableKind::Shift => "shift ΔRp (mm)",
        VariableKind::Equidistant => "equidistant ΔRrp (mm)",
        VariableKind::Rotation => "rotation Δδ (deg)",
        VariableKind::CrownRadius => "crown radius Rc (mm)",
        VariableKind::CrownStart => "crown start z0 (mm)",
    }
}

/// Axis label of a study's objective, with its unit.
pub fn objective_axis_label(study: &Study) -> String {
    match study.objective.as_slice() {
        [(o, _)] => o.label.to_string(),
        _ => format!("weighted objective {}", objective_label(study)),
    }
}

/// A point of the study in the map's plane: its first two variables in the spec's units (0 for
/// a variable the study does not have).
fn xy(study: &Study, e: &Evaluation) -> (f64, f64) {
    let at = |k: usize| {
        study
            .variables
            .get(k)
            .map_or(0.0, |v| v.kind.spec_value(&e.point))
    };
    (at(0), at(1))
}

/// The design-review view of one study: `map` is `optimise::map` of the study over a
/// `steps` × `steps` grid around the optimum (empty: no map). One builder per part of the
/// section: what the study is, its map, the search on it, its table, its notes and outcome.
pub fn view(
    spec: &Spec,
    study: &Study,
    r: &StudyResult,
    map: &[Evaluation],
    steps: usize,
) -> OptimisationView {
    let vars = &study.variables;
    let (path, path_label, path_evaluations) = winning_path(study, r);
    OptimisationView {
        name: r.name.clone(),
        summary: summary(spec, study),
        x_label: vars.first().map_or("", |v| variable_label(v.kind)).into(),
        y_label: vars
            .get(1)
            .map_or("(one variable)", |v| variable_label(v.kind))
            .into(),
        log_axes: (
            vars.first().is_some_and(|v| v.logarithmic()),
            vars.get(1).is_some_and(|v| v.logarithmic()),
        ),
        objective_label: objective_axis_label(study),
        map: map_cells(study, map),
        map_note: map_note(study, r, map, steps),
        global: r
            .global
            .iter()
            .map(|e| {
                let (x, y) = xy(study, e);
                (x, y, e.feasible())
            })
            .collect(),
        path,
        path_label,
        path_evaluations,
        start: Some(xy(study, &r.start)),
        optimum: Some(xy(study, &r.optimum)),
        references: r
            .references
            .iter()
            .map(|(l, e)| {
                let (x, y) = xy(study, e);
                (x, y, l.clone())
            })
            .collect(),
        variables: vars
            .iter()
            .map(|v| variable_label(v.kind).to_string())
            .collect(),
        points: table_points(study, r),
        outcome: match verification_text(study, r) {
            Some(v) => format!("{}; {v}.", outcome(r)),
            None => format!("{}.", outcome(r)),
        },
        notes: notes(study, r),
    }
}

/// What the study minimises, on which scene, over which bounds, subject to what (a sentence).
fn summary(spec: &Spec, study: &Study) -> String {
    let vars = &study.variables;
    let scene = &spec.scenes[study.scene];
    let bounds: Vec<String> = vars
        .iter()
        .map(|v| {
            let unit = if v.kind == VariableKind::Rotation {
                "deg"
            } else {
                "mm"
            };
            format!(
                "{} in [{}, {}] {unit}",
                v.kind.key(),
                short(v.kind.to_spec_unit(v.lower)),
                short(v.kind.to_spec_unit(v.upper))
            )
        })
        .collect();
    let mut constraints = Vec::new();
    if let Some((lo, hi)) = study.tip_clearance_mm {
        constraints.push(format!(
            "tip clearance ΔRrp − ΔRp in [{}, {}] mm (paper Eqs. 8, 21)",
            short(lo),
            short(hi)
        ));
    }
    if let Some(dt) = study.min_clearance_mm {
        constraints.push(format!(
            "whole-mesh clearance ≥ {} mm on the exact geometry",
            short(dt)
        ));
    }
    for (o, bound) in &study.objective_limits {
        let bound = with_unit(short(*bound), o.quantity.unit);
        constraints.push(format!("{} ≤ {bound}", o.name));
    }
    format!(
        "Minimise {} on scene “{}” ({} N·m, {} crank angles) over {}{}.",
        objective_label(study),
        scene.name,
        short(crate::units::nm(scene.output_torque_nmm)),
        scene.crank_rad.len(),
        bounds.join(", "),
        if constraints.is_empty() {
            String::new()
        } else {
            format!(", subject to {}", constraints.join(" and "))
        }
    )
}

/// The objective map's cells (non-finite where a design rule fails).
fn map_cells(study: &Study, map: &[Evaluation]) -> Vec<MapCell> {
    map.iter()
        .map(|e| {
            let (x, y) = xy(study, e);
            MapCell {
                x,
                y,
                z: if e.failure.is_none() {
                    e.objective
                } else {
                    f64::NAN
                },
                feasible: e.feasible(),
            }
        })
        .collect()
}

/// How the map was made: its grid, its evaluations and the variables held fixed.
fn map_note(study: &Study, r: &StudyResult, map: &[Evaluation], steps: usize) -> String {
    let vars = &study.variables;
    if map.is_empty() {
        "no map computed".to_string()
    } else {
        let grid = if vars.len() > 1 {
            format!("{steps} × {steps} grid")
        } else {
            format!("{steps} points")
        };
        let mut note = format!("{grid}, {} evaluations", map.len());
        for v in vars.iter().skip(2) {
            note += &format!(
                "; {} held at the optimum's {}",
                v.kind.key(),
                number(v.kind.spec_value(&r.optimum.point))
            );
        }
        note
    }
}

/// The winning local run, from its start up to the optimum: (its points, what it is, its
/// evaluations up to the optimum); empty when no local run found the optimum.
fn winning_path(study: &Study, r: &StudyResult) -> (Vec<(f64, f64)>, String, usize) {
    match r.winner().map(|k| (k, &r.local_runs[k])) {
        Some((k, run)) => {
            let end = run
                .path
                .iter()
                .position(|e| *e == r.optimum)
                .map_or(run.path.len(), |i| i + 1);
            let mut points = Vec::new();
            if run.path.first() != Some(&run.start) {
                points.push(xy(study, &run.start));
            }
            points.extend(run.path[..end].iter().map(|e| xy(study, e)));
            let from = if run.start == r.start {
                "from the start".to_string()
            } else {
                match r.global.iter().position(|g| *g == run.start) {
                    Some(i) => format!("from global sample {}", i + 1),
                    None => "from a global sample".to_string(),
                }
            };
            (
                points,
                format!("local run {} of {}, {from}", k + 1, r.local_runs.len()),
                end,
            )
        }
        None => (Vec::new(), String::new(), 0),
    }
}

/// The study's points as every list of them runs: the start, each reference, the optimum.
fn listed(r: &StudyResult) -> impl Iterator<Item = (&str, &Evaluation)> {
    std::iter::once(("start", &r.start))
        .chain(r.references.iter().map(|(l, e)| (l.as_str(), e)))
        .chain(std::iter::once(("optimum", &r.optimum)))
}

/// The references whose objective and the optimum's are finite, each with the optimum's less its.
fn against_references(r: &StudyResult) -> impl Iterator<Item = (&str, &Evaluation, f64)> {
    (r.references.iter())
        .filter(|(_, e)| e.objective.is_finite() && r.optimum.objective.is_finite())
        .map(|(l, e)| (l.as_str(), e, r.optimum.objective - e.objective))
}

/// The table's columns: start, references, optimum.
fn table_points(study: &Study, r: &StudyResult) -> Vec<StudyPoint> {
    let point = |label: &str, e: &Evaluation| StudyPoint {
        label: label.to_string(),
        variables: study
            .variables
            .iter()
            .map(|v| v.kind.spec_value(&e.point))
            .collect(),
        objective: e.failure.is_none().then_some(e.objective),
        failure: e.failure.clone(),
        feasible: e.feasible(),
        margins: e.margins.clone(),
    };
    listed(r).map(|(l, e)| point(l, e)).collect()
}

/// The remarks under the table: what the objective hides, the optimum against each reference,
/// a point that satisfies the paper's Eq. 8 but not the whole-mesh clearance.
fn notes(study: &Study, r: &StudyResult) -> Vec<String> {
    let mut notes = vec![format!(
        "What the objective hides: {}.",
        listed(r)
            .map(|(label, e)| format!("{label}: {}", geometry_text(e)))
            .collect::<Vec<_>>()
            .join("; ")
    )];
    for (label, e, diff) in against_references(r) {
        notes.push(format!(
            "The optimum's objective is {} {} than the {label}'s ({} vs {}).",
            number(diff.abs()),
            if diff <= 0.0 { "lower" } else { "HIGHER" },
            number(r.optimum.objective),
            number(e.objective)
        ));
    }
    for (label, e) in listed(r) {
        if let Some(note) = eq8_note(label, e, study) {
            let note = note.trim().trim_start_matches("note: ");
            notes.push(format!("{}.", capitalised(note)));
        }
    }
    notes
}
