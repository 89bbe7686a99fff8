//! The reducer at speed (issue 42, `Effect::Inertia`): each disc's centripetal force
//! m·(e + de)·ω² in its force balance. Checked against what must hold whatever the solver:
//! with no torque the crank bearing carries exactly m·e·ω², pulling the disc in (−e_φ), at
//! every angle; under load the bearing's force differs from the one without the effect by
//! exactly that vector (the force acts at the disc centre, so it moves no moment about it and
//! no contact); two discs at 180°, side by side, leave no force on the crank but the couple
//! F_c·B.

use crate::common::*;
use std::f64::consts::TAU;

const SPEC: &str = include_str!("../../specs/reducer-at-speed.yaml");
const FAST: &str = "    output_torque_nm: 10.0\n    input_speed_rpm: 3000.0\n";

/// The results JSON of `text` checked in a scratch directory.
fn results(name: &str, text: &str) -> serde_json::Value {
    let dir = Scratch::new(name);
    dir.write("s.yaml", text);
    let run = cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]);
    assert!(run.code() == 0 || run.code() == 1, "{}", run.stderr);
    serde_json::from_str(&dir.read("r.json")).unwrap()
}

/// F_c = m·e·ω² of the JSON's disc mass at e = 2 mm and 3000 rpm, N, worked out here.
fn centripetal_n(json: &serde_json::Value) -> f64 {
    let m = json["disc_mass_kg"].as_f64().unwrap();
    let w = 3000.0 * TAU / 60.0;
    m * 2e-3 * w * w
}

/// Disc k's bearing force at each angle of scene 1, as (along e_φk, across it), N.
fn bearing(json: &serde_json::Value, k: usize) -> Vec<[f64; 2]> {
    let d = &json["scenes"][1]["discs"][k];
    let column = |key: &str| -> Vec<f64> {
        (d[key].as_array().unwrap().iter())
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (f, a) = (column("bearing_force_n"), column("bearing_angle_deg"));
    (f.iter().zip(&a))
        .map(|(f, a)| [f * a.to_radians().cos(), f * a.to_radians().sin()])
        .collect()
}

#[test]
fn with_no_torque_the_bearing_carries_m_e_omega_squared_inward_at_every_angle() {
    let json = results(
        "inertia-zero",
        &SPEC.replace(
            FAST,
            "    output_torque_nm: 0.0\n    input_speed_rpm: 3000.0\n",
        ),
    );
    let fc = centripetal_n(&json);
    for k in 0..2 {
        for (i, [along, across]) in bearing(&json, k).into_iter().enumerate() {
            // 1e-9 relative: the JSON's degrees round-trip through f64 trigonometry.
            assert!(
                (along + fc).abs() <= 1e-9 * fc && across.abs() <= 1e-9 * fc,
                "disc {k}, angle {i}: ({along}, {across}) N, F_c {fc} N"
            );
        }
    }
}

#[test]
fn under_load_the_effect_adds_exactly_the_centripetal_pull_to_the_bearing() {
    let with = results("inertia-with", SPEC);
    let without = results(
        "inertia-without",
        &SPEC.replace("effects: [bearing, inertia]", "effects: [bearing]"),
    );
    let fc = centripetal_n(&with);
    for k in 0..2 {
        let (a, b) = (bearing(&with, k), bearing(&without, k));
        assert_eq!(a.len(), 72);
        for (i, (a, b)) in a.iter().zip(&b).enumerate() {
            // The contacts are the same solve (the force moves no moment about the disc
            // centre); 1e-9 of the ~450 N bearing force covers the degrees' round trip.
            let scale = 1e-9 * (a[0].hypot(a[1]) + fc);
            assert!(
                (a[0] - b[0] + fc).abs() <= scale && (a[1] - b[1]).abs() <= scale,
                "disc {k}, angle {i}: {a:?} with, {b:?} without, F_c {fc} N"
            );
        }
    }
}

#[test]
fn two_discs_at_half_a_turn_leave_a_couple_and_no_force_on_the_crank() {
    let json = results("inertia-unbalance", SPEC);
    let fc = centripetal_n(&json);
    let u = &json["unbalance"][0];
    assert_eq!(u["scene"], "fast");
    let force = u["unbalance_force_n"].as_f64().unwrap();
    let moment = u["unbalance_moment_nm"].as_f64().unwrap();
    // Side by side, mid-planes B = 8 mm apart: F_c·e_φ at z = 4 mm and −F_c·e_φ at 12 mm.
    assert!(force <= 1e-12 * fc, "{force} N");
    assert!((moment - fc * 8e-3).abs() <= 1e-12 * moment, "{moment} N·m");
    let f = u["disc_centripetal_force_n"].as_f64().unwrap();
    assert!((f - fc).abs() <= 1e-12 * fc);
}

#[test]
fn inertia_is_refused_where_it_is_not_built_or_has_no_speed() {
    let dir = Scratch::new("inertia-bad");
    for (name, text, rule) in [
        (
            "no speed",
            SPEC.replace("    input_speed_rpm: 3000.0\n", ""),
            "needs `input_speed_rpm`",
        ),
        (
            "compliant bearing",
            SPEC.replace(FAST, &format!("{FAST}    bearing_stiffness_n_per_mm: 1.0e5\n")),
            "rigid crank bearing only",
        ),
        (
            "coupled friction",
            SPEC.replace(
                "  output_inertia_kgm2:",
                "  friction: { model: coupled, rollers: { mode: fixed, mu: 0.05 } }\n  output_inertia_kgm2:",
            ),
            "coupled friction model",
        ),
    ] {
        let shown = cycloid::spec::parse("bad.yaml", &text)
            .expect_err(name)
            .to_string();
        // Located at the scene's effects list, written out here from the text.
        let line = 1 + text
            .lines()
            .position(|l| l.contains("effects: [bearing, inertia]"))
            .unwrap();
        assert!(
            shown.starts_with(&format!("bad.yaml:{line}:"))
                && shown.contains("scenes[1].effects")
                && shown.contains(rule),
            "{name}: {shown}"
        );
        dir.write("bad.yaml", &text);
        assert_eq!(cycloid(&dir.path, &["check", "bad.yaml"]).code(), 2, "{name}");
    }
}

/// F_c = m·e·ω² as a person reads it (four significant digits, `numeric::number`), from the
/// JSON's disc mass and worked out here.
fn shown(x: f64) -> String {
    cycloid::numeric::number(x)
}

/// What a person reads of the scene at speed: the terminal's unbalance line, `--explain`'s
/// formula with its numbers and where the force enters, the review's crank-bearing plot
/// ("at 3000 rpm, includes m·(e+de)·ω² = …") and the scene's note with the couple F_c·B
/// (B = 8 mm between the mid-planes of the two discs side by side).
#[test]
fn the_terminal_explain_and_review_say_the_force_at_speed_and_the_unbalance() {
    let dir = Scratch::new("inertia-text");
    dir.write("s.yaml", SPEC);
    let run = cycloid(
        &dir.path,
        &["check", "s.yaml", "--json", "r.json", "--report", "review"],
    );
    assert_eq!(run.code(), 0, "{}", run.stderr);
    let json: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let fc = centripetal_n(&json);
    let m = json["disc_mass_kg"].as_f64().unwrap();
    let (force, couple) = (shown(fc), shown(fc * 8e-3));
    let line = (run.stdout.lines())
        .find(|l| l.starts_with("scene `fast` at 3000 rpm"))
        .unwrap_or_else(|| panic!("{}", run.stdout));
    // The net force is round-off of 2·F_c (cos π = −1 to an ulp; the JSON's ~1e-16·F_c):
    // said as none, not printed as a number.
    assert_eq!(
        line,
        format!(
            "scene `fast` at 3000 rpm: each disc's centripetal force {force} N; no unbalance \
             force on the crank (the discs' forces cancel), couple {couple} N·m"
        )
    );
    assert!(json["unbalance"][0]["unbalance_force_n"].as_f64().unwrap() <= 1e-12 * fc);

    let explain = cycloid(&dir.path, &["check", "s.yaml", "--explain"]).stdout;
    let w = 3000.0 * TAU / 60.0;
    let formula = format!(
        "  note    inertia: each disc's centripetal force F_c = m·(e+de)·ω² = {} kg × 0.002000 m \
         × ({} rad/s)² = {force} N at 3000 rpm, pulled by its crank bearing toward the crank \
         (−e_φ): in the crank bearing's force at every angle, its life and (with strength) its \
         static safety",
        shown(m),
        shown(w)
    );
    assert!(explain.contains(&formula), "{explain}");
    assert!(
        explain.contains(&format!(
            "  note    unbalance at 3000 rpm: the 2 discs leave on the crank no force (their \
             forces cancel) and a couple of {couple} N·m about their mean mid-plane\n"
        )),
        "{explain}"
    );

    let html = dir.read("review/index.html");
    let title = format!("Crank-bearing force at 3000 rpm, includes m·(e+de)·ω² = {force} N");
    for k in 0..2 {
        let svg = dir.read(&format!("review/scene-2-fast-disc-{k}-bearing-force.svg"));
        assert!(svg.contains(&title), "disc {k}");
    }
    assert!(html.contains(&format!("<b>{title}</b>")));
    assert!(html.contains(&format!(
        "F_c = m·(e+de)·ω² = {force} N (effect inertia): in the bearing's force at every \
         angle, its life and static safety; the contacts are those without it. The 2 discs \
         leave on the crank no unbalance force (their forces cancel) and a couple of {couple} \
         N·m.</p>"
    )));
    // The scene without `inertia` says nothing of speed.
    assert!(!dir
        .read("review/scene-1-rated-disc-0-clearance.svg")
        .contains("rpm"));
}

/// One disc leaves its whole F_c on the crank (Σ F_c·e_φk of one term): a real force, which
/// the terminal prints as a number, the disc's centripetal force itself (worked out here from
/// the JSON's mass), while two discs' round-off is said as none (above).
#[test]
fn one_disc_leaves_its_centripetal_force_on_the_crank_as_a_number() {
    let dir = Scratch::new("inertia-one-disc");
    dir.write("s.yaml", SPEC.replacen("  discs: 2 ", "  discs: 1 ", 1));
    let run = cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    let json: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let force = shown(centripetal_n(&json));
    let line = format!(
        "scene `fast` at 3000 rpm: each disc's centripetal force {force} N; unbalance on the \
         crank {force} N, couple 0 N·m\n"
    );
    assert!(run.stdout.contains(&line), "{}", run.stdout);
}
