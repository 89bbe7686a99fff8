//! The accuracy ladder ([`engine::accuracy`](crate::engine::accuracy)) in words: its table for the terminal, printed row by
//! row as the rungs finish (`header`, `row`, `footer`, or `render` at once), the numbers and
//! verdicts the design review's table shares, and the warning `check` prints when a scene's
//! crank resolution is coarser than its tolerances need (`resolution_warning`).
//!
//! Columns have fixed widths so rows can be printed as they finish.

use crate::engine::accuracy::{
    misses, tol_text, Ladder, LadderQuantity, LadderTolerances, Layout, Rung, Skipped, Variation,
    FACE_SLICES,
};
use crate::engine::resolution::Resolution;
use crate::equilibrium::solve::Settings;
use crate::model::{ContactLaw, GeometryMode};
use crate::numeric::{number, with_unit};

/// What a quantity's error is, in words.
pub fn description(q: LadderQuantity) -> String {
    match q {
        LadderQuantity::TeCurve => {
            "loaded TE curve, max |difference| between the curves".to_string()
        }
        q => q.registry().label.to_string(),
    }
}

/// A rung's verdict: a class (`reference`, `model`, `pass`, `fail`) and its text ("met", or
/// "not met: …" naming the quantities over their tolerance).
pub fn verdict(r: &Rung, t: &LadderTolerances) -> (&'static str, String) {
    if r.is_reference {
        return ("reference", "reference".to_string());
    }
    if r.model_difference {
        return ("model", "model difference".to_string());
    }
    let missed = misses(&r.errors, t);
    if missed.is_empty() {
        ("pass", "met".to_string())
    } else {
        let names: Vec<&str> = missed.iter().map(|(q, _)| q.label()).collect();
        ("fail", format!("not met: {}", names.join(", ")))
    }
}

/// A model's settings (a rung's, the reference's): "exact geometry, paper_linear, rel_tol 1e-11".
fn settings(geometry: GeometryMode, law: ContactLaw, rel_tol: f64) -> String {
    format!(
        "{} geometry, {}, rel_tol {}",
        geometry.name(),
        law.name(),
        tol_text(rel_tol)
    )
}

/// Why rungs were left out.
pub fn skipped_text(s: Skipped) -> &'static str {
    match s {
        Skipped::ToleranceRungs => {
            "solver tolerance rungs: first-order geometry with the linear law is solved in \
             closed form, without a tolerance"
        }
        Skipped::SettingsRungs => {
            "settings rungs: the scene computes no roller contact, and clearance depends on \
             the crank steps only"
        }
    }
}

/// The warning `check` prints under its verdict when the scene is unresolved (after `warning: `).
pub fn resolution_warning(r: &Resolution) -> Option<String> {
    (!r.resolved()).then(|| {
        format!(
            "scene `{}` is solved at {} crank steps per mesh period; its accuracy \
             ladder needs {} to meet the tolerances ({}); refine the crank steps or loosen \
             `accuracy.tolerance`",
            r.scene,
            number(r.scene_steps),
            r.needed_steps(),
            misses_text(r)
        )
    })
}

/// Widths of the rung's label and of a number's column, characters (`{:>w$}` pads by
/// characters: "—" is one).
const LABEL_W: usize = 26;
const NUM_W: usize = 13;

/// A number for the table: 3 significant digits, exponent form below 0.01.
pub fn short(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else if (0.01..1e5).contains(&x.abs()) {
        number(x)
    } else {
        format!("{x:.2e}")
    }
}

/// A run's time: milliseconds below a second, else seconds.
pub fn seconds_text(s: f64) -> String {
    if s < 1.0 {
        format!("{:.1} ms", s * 1000.0)
    } else {
        format!("{s:.2} s")
    }
}

/// An observed order, two decimals (no "-0.00" for an error that did not move); "—" where an
/// error is at round-off.
pub fn order_text(p: Option<f64>) -> String {
    p.map_or("—".to_string(), |p| crate::numeric::fixed(p, 2))
}

/// Steps per period (or periods): an integer as such, else two decimals.
pub fn steps_text(x: f64) -> String {
    if (x - x.round()).abs() < 1e-9 {
        format!("{}", x.round())
    } else {
        format!("{x:.2}")
    }
}

fn tolerance_text(q: LadderQuantity, t: &LadderTolerances) -> String {
    with_unit(short(q.tolerance(t)), q.unit())
}

/// The quantities of the ladder this scene does not compute, described. The face quantities
/// exist only for a crowned or tilted face: a 2-D scene's ladder does not name them.
pub fn not_computed(l: &Layout) -> Vec<String> {
    LadderQuantity::ALL
        .into_iter()
        .filter(|q| !q.is_face() && !l.quantities.contains(q))
        .map(description)
        .collect()
}

/// The lines before the first row: scene, reference, tolerances, column headings.
pub fn header(l: &Layout) -> String {
    let mut s = format!(
        "accuracy ladder of scene `{}` (spec `{}`): crank {}° to {}° ({} mesh periods)\n",
        l.scene,
        l.spec_name,
        number(l.from_deg),
        number(l.to_deg),
        steps_text(l.periods)
    );
    s += &format!(
        "reference: {} steps per mesh period ({} crank angles), {}\n",
        l.finest,
        l.angles(l.finest),
        settings(l.geometry, l.law, Settings::default().rel_tol)
    );
    let tolerances: Vec<String> = l
        .quantities
        .iter()
        .map(|&q| format!("{} {}", q.label(), tolerance_text(q, &l.tolerances)))
        .collect();
    s += &format!(
        "errors are |rung − reference| in each quantity's unit; tolerances: {}\n",
        tolerances.join(", ")
    );
    if l.face {
        s += &format!(
            "face-slices rungs: the scene's own {} crank angles with the face cut into {} \
             slices; their reference is {} slices\n",
            l.angles_own,
            FACE_SLICES.map(|n| n.to_string()).join(", "),
            FACE_SLICES[FACE_SLICES.len() - 1]
        );
    }
    let missing = not_computed(l);
    if !missing.is_empty() {
        s += &format!(
            "not computed by this scene (no column): {}\n",
            missing.join(", ")
        );
    }
    let mut h1 = leading("rung", "steps/period", "angles", "time");
    let mut h2 = leading("", "", "", "");
    for q in &l.quantities {
        h1 += &format!("{:>w$}", q.label(), w = NUM_W + 1);
        h2 += &format!("{:>w$}", q.unit(), w = NUM_W + 1);
    }
    h1 += "  tolerances";
    s += h1.trim_end();
    s += "\n";
    s += h2.trim_end();
    s += "\n";
    s
}

/// The cells before the errors, at their columns' widths: rung, steps per period, angles,
/// time.
fn leading(rung: &str, steps: &str, angles: &str, time: &str) -> String {
    format!("{rung:<LABEL_W$}{steps:>13}{angles:>8}{time:>11}")
}

/// A rung's error in `q` for the table: "—" for the reference, "n/a" where not computed.
pub fn error_cell(r: &Rung, q: LadderQuantity) -> String {
    match r.error(q) {
        _ if r.is_reference => "—".to_string(),
        Some(e) => short(e),
        None => "n/a".to_string(),
    }
}

/// One row of the table; `cheapest` appends the mark.
pub fn row(l: &Layout, r: &Rung, cheapest: bool) -> String {
    let mut s = leading(
        &r.label,
        &steps_text(r.steps_per_period),
        &r.angles.to_string(),
        &seconds_text(r.seconds),
    );
    for &q in &l.quantities {
        s += &format!("{:>w$}", error_cell(r, q), w = NUM_W + 1);
    }
    let (_, verdict) = verdict(r, &l.tolerances);
    s += "  ";
    s += &verdict;
    if cheapest {
        s += "  <- cheapest";
    }
    s + "\n"
}

/// Whether the ladder has rungs that change one setting (geometry, contact law, solver
/// tolerance) rather than the crank steps or the face slices.
pub fn has_settings_rungs(ladder: &Ladder) -> bool {
    (ladder.rungs.iter()).any(|r| !matches!(r.variation, Variation::Steps | Variation::FaceSlices))
}

/// The lines after the last row: the cheapest rung, the observed orders, the notes.
pub fn footer(ladder: &Ladder) -> String {
    let l = &ladder.layout;
    let reference = ladder.reference();
    let mut s = String::new();
    if ladder.layout.loaded && has_settings_rungs(ladder) {
        s += &format!(
            "settings rungs at {} steps per mesh period{}\n",
            ladder.settings_steps,
            if ladder.settings_steps == l.finest {
                " (the finest: their errors are the settings' own effect)"
            } else {
                " (their errors include that resolution's, shown by its steps rung)"
            }
        );
    }
    match ladder.cheapest {
        Some(i) if ladder.rungs[i].is_reference => {
            s += "cheapest rung meeting every tolerance: only the reference, whose own error is not \
                  measured (no finer rung): ask for looser tolerances or a finer reference\n";
        }
        Some(i) => {
            let r = &ladder.rungs[i];
            s += &format!(
                "cheapest rung meeting every tolerance (the least work: {} crank angles, then the \
                 coarsest settings): `{}` ({} steps per mesh period, {}): {} against {} for the \
                 reference (times for information)\n",
                r.angles,
                r.label,
                steps_text(r.steps_per_period),
                settings(r.geometry, r.law, r.rel_tol),
                seconds_text(r.seconds),
                seconds_text(reference.seconds)
            );
        }
        None => s += "no rung meets every tolerance\n",
    }
    if let Some(i) = ladder.cheapest_slices {
        let r = &ladder.rungs[i];
        if r.is_reference {
            s += &format!(
                "fewest face slices meeting every tolerance: only the reference, {} slices, \
                 whose own error is not measured (no finer count)\n",
                r.slices
            );
        } else {
            let finest = ladder
                .rungs
                .iter()
                .find(|f| f.variation == Variation::FaceSlices && f.is_reference)
                .map_or(0.0, |f| f.seconds);
            s += &format!(
                "fewest face slices meeting every tolerance: `{}`: {} against {} for the \
                 reference (times for information)\n",
                r.label,
                seconds_text(r.seconds),
                seconds_text(finest)
            );
        }
    }
    let orders: Vec<String> = l
        .quantities
        .iter()
        .filter_map(|&q| {
            let o = ladder.orders(q);
            if o.is_empty() {
                return None;
            }
            let text: Vec<String> = o.iter().map(|&(_, p)| order_text(p)).collect();
            let fit = order_text(ladder.fitted_order(q));
            Some(format!("  {:<15}{}   fit {fit}", q.label(), text.join(" ")))
        })
        .collect();
    if !orders.is_empty() {
        let ns: Vec<String> = ladder
            .orders(l.quantities[0])
            .iter()
            .map(|(n, _)| n.to_string())
            .collect();
        s += &format!(
            "observed order log2(e(N)/e(2N)) of the steps rungs, N = {}; fit: least squares \
             over N = 12 … finest/4:\n",
            ns.join(", ")
        );
        for o in orders {
            s += &o;
            s += "\n";
        }
    }
    if ladder
        .rungs
        .iter()
        .any(|r| r.variation == Variation::ContactLaw)
    {
        s += "note: another contact law is another model: its \"error\" is the difference between \
              the models, not a discretisation error, and it is never chosen as the cheapest\n";
    }
    if ladder
        .rungs
        .iter()
        .any(|r| r.variation == Variation::Geometry && r.model_difference)
    {
        s += "note: the scene asks for first_order geometry, so the reference is first_order; the \
              exact rung's difference is the first-order model's error\n";
    }
    for &k in &ladder.skipped {
        s += &format!("skipped: {}\n", skipped_text(k));
    }
    s
}

/// The whole table (header, rows with the cheapest marked, footer).
pub fn render(ladder: &Ladder) -> String {
    let mut s = header(&ladder.layout);
    for (i, r) in ladder.rungs.iter().enumerate() {
        s += &row(
            &ladder.layout,
            r,
            ladder.cheapest == Some(i) || ladder.cheapest_slices == Some(i),
        );
    }
    s + &footer(ladder)
}

/// The line `check --report` prints about the ladder.
pub fn ladder_line(ladder: &Ladder, seconds: f64) -> String {
    format!(
        "accuracy ladder of scene `{}`: {} rungs in {seconds:.2} s; cheapest meeting every \
         tolerance: {}\n",
        ladder.layout.scene,
        ladder.rungs.len(),
        match ladder.cheapest {
            Some(i) => format!("`{}`", ladder.rungs[i].label),
            None => "none".to_string(),
        }
    )
}

/// What the misses of `evidence` are, "TE curve 0.1105 > 0.1 arcsec, …".
pub fn misses_text(res: &Resolution) -> String {
    let Some(r) = res.evidence() else {
        return String::new();
    };
    let parts: Vec<String> = r
        .misses
        .iter()
        .map(|&(q, e)| {
            format!(
                "{} {} > {}",
                q.label(),
                number(e),
                with_unit(number(q.tolerance(&res.tolerances)), q.unit())
            )
        })
        .collect();
    format!("at {} steps: {}", r.steps, parts.join(", "))
}
