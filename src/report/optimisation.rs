//! Text of an optimisation study: start, references and optimum with objective values, every
//! constraint's margin, evaluations, time and why it stopped; plus the objective map CSV.

use crate::optimise::problem::Evaluation;
use crate::optimise::StudyResult;
use crate::report::table::number;
use crate::spec::{Spec, Study};

fn objective_label(study: &Study) -> String {
    study
        .objective
        .iter()
        .map(|(o, w)| {
            let unit = if o.unit().is_empty() {
                String::new()
            } else {
                format!(" [{}]", o.unit())
            };
            if study.objective.len() == 1 {
                format!("{}{unit}", o.name())
            } else {
                format!("{w}·{}{unit}", o.name())
            }
        })
        .collect::<Vec<_>>()
        .join(" + ")
}

fn variables(study: &Study, e: &Evaluation) -> String {
    study
        .variables
        .iter()
        .map(|v| {
            format!(
                "{} {:.6}",
                v.kind.key(),
                v.kind.to_spec_unit(v.kind.get(&e.modification))
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn row(study: &Study, label: &str, e: &Evaluation) -> String {
    let objective = match &e.failure {
        Some(why) => format!("not evaluated ({why})"),
        None => format!("objective {}", number(e.objective)),
    };
    let verdict = if e.feasible() {
        "feasible"
    } else {
        "INFEASIBLE"
    };
    format!(
        "  {label:<16} {}: {objective}, {verdict}\n",
        variables(study, e)
    )
}

/// Say when a point satisfies the paper's Eq. 8 (tip clearance) but not the whole-mesh check.
fn eq8_note(label: &str, e: &Evaluation, study: &Study) -> Option<String> {
    let (lo, _) = study.tip_clearance_mm?;
    let min = e.min_clearance?;
    let dt = study.min_clearance_mm?;
    let tip = e.modification.tip_clearance_mm();
    let eq8 = tip >= lo - crate::check::tolerance(lo);
    (eq8 && !crate::check::passes(min.gap_mm, dt, crate::check::Bound::Min)).then(|| {
        format!(
            "  note: the {label} satisfies the paper's Eq. 8 (ΔRrp − ΔRp = {:.4} mm ≥ {lo} mm) but \
             violates the whole-mesh clearance: {:.1} µm < {:.1} µm at roller {}, crank {:.2}°, \
             tooth phase {:.3} (0 root, 0.5 tip){}\n",
            tip,
            min.gap_mm * 1000.0,
            dt * 1000.0,
            min.roller,
            min.crank_rad.to_degrees(),
            min.tooth_phase,
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
        scene.output_torque_nmm / 1000.0,
        scene.crank_rad.len()
    );
    out += &row(study, "start", &r.start);
    for (label, e) in &r.references {
        out += &row(study, label, e);
    }
    out += &row(study, "optimum", &r.optimum);
    for (label, e) in r.references.iter().map(|(l, e)| (l.as_str(), e)) {
        if e.failure.is_none() && r.optimum.failure.is_none() {
            let diff = r.optimum.objective - e.objective;
            out += &format!(
                "  optimum vs {label}: {} ({})\n",
                number(diff),
                if diff <= 0.0 { "no worse" } else { "WORSE" }
            );
        }
    }
    out += "  constraints at the optimum:\n";
    for m in &r.optimum.margins {
        out += &format!(
            "    {:<40} value {:>10}  bound {:>8}  margin {:>10}  {}\n",
            m.name,
            number(m.value),
            number(m.bound),
            number(m.margin),
            if m.satisfied() { "ok" } else { "VIOLATED" }
        );
    }
    for (label, e) in std::iter::once(("start", &r.start))
        .chain(r.references.iter().map(|(l, e)| (l.as_str(), e)))
        .chain(std::iter::once(("optimum", &r.optimum)))
    {
        if let Some(note) = eq8_note(label, e, study) {
            out += &note;
        }
    }
    out += &format!(
        "  {} evaluations ({} global, {} local runs), {:.2} s; {}\n",
        r.evaluations,
        r.global.len(),
        r.local_runs.len(),
        r.elapsed.as_secs_f64(),
        r.stop_reason
    );
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
            out += &format!("{},", v.kind.to_spec_unit(v.kind.get(&e.modification)));
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
            e.modification.tip_clearance_mm()
        );
    }
    out
}
