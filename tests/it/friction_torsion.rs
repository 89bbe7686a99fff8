//! Friction in the torsion loop (issue 28 item 5, MODEL.md "Friction, efficiency and heat":
//! torsion under a locked input): the loading and unloading branches, the hysteresis loss at
//! zero torque, the loop's area, and the figures on the loop's centre line.
//!
//! What is checked comes from outside the loop's code: a first-order closed form of the
//! hysteresis from the frictionless solution's forces (2·M_f/K), the loop's point symmetry at
//! a mirror-symmetric crank angle, its area recomputed from the drawn curve, the zero
//! hysteresis of a design whose contacts all open at zero torque, and the messages.

use crate::common::{cycloid, paper_spec, PaperSpec, Scratch};
use cycloid::equilibrium::angle::solve_angle;
use cycloid::equilibrium::loaded::{AngleSolution, Model};
use cycloid::model::{Effect, Plan};
use serde_json::Value;

/// The rated torque of the loops here, N·m.
const RATED_NM: f64 = 20.0;

/// The paper's design with the modification (shift, 0) and `friction` (a YAML flow mapping of
/// `reducer.friction`, or none), one torsion scene locked at 0° with `effects`.
fn torsion_spec(shift_mm: f64, friction: Option<&str>, effects: &str) -> String {
    let mut spec = PaperSpec::new()
        .modification(shift_mm, 0.0)
        .scenes(&format!(
            "  - name: torsion\n    torque_sweep: {{ rated_nm: {RATED_NM:?}, steps: 20 }}\n    \
         crank: {{ from_deg: 0.0, to_deg: 36.0, steps: 1 }}\n    effects: [{effects}]\n"
        ));
    if let Some(f) = friction {
        spec = spec.edit("modification:", &format!("  friction: {f}\nmodification:"));
    }
    spec.text().to_string()
}

/// The torsion scene of `check --json` on `text` (exit 0 required).
fn torsion(text: &str) -> Value {
    let dir = Scratch::new("friction-torsion");
    dir.write("s.yaml", text);
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]).parts();
    assert_eq!(code, 0, "{out}{err}\n{text}");
    let doc: Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    doc["scenes"][0].clone()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn rollers_only(mu: f64) -> String {
    format!("{{ rollers: {{ mode: fixed, mu: {mu:?} }} }}")
}

const ALL_PATHS: &str =
    "{ rollers: { mode: fixed, mu: MU }, output_pins: { mode: fixed, mu: MU }, \
     crank_bearing: { mu: 0.005, bore_diameter_mm: 20.0 } }";

/// The loop of the paper's design preloaded by a shift of 3 µm, every path's friction at μ 0.05
/// (the crank bearing's 0.005), rollers, pins and bearing modelled.
fn preloaded_loop() -> Value {
    let friction = ALL_PATHS.replace("MU", "0.05");
    let effects = "roller_contact, output_pins, bearing";
    torsion(&torsion_spec(0.003, Some(&friction), effects))
}

/// The first-order closed form (one disc, rollers only, linear law, preloaded by a shift of
/// 2 µm): at T = 0 each branch balances Σ F_i·(l_i ± μ·|(C_i − O_d)·n_i|) = 0, so to first
/// order in μ the lag moves by ∓M_f/K from the frictionless one, M_f = μ·Σ F_i·|(C_i − O_d)·n_i|
/// with the frictionless forces at T = 0, K = dT/dβ there: the hysteresis is 2·M_f/K. Both
/// from the frictionless solver alone (forces, points, normals; K by a central difference
/// over ±1 N·mm, exact for the linear law while no contact opens).
#[test]
fn hysteresis_matches_the_first_order_closed_form() {
    let spec = paper_spec(0.002, 0.0);
    let scene = |torque_nmm: f64| cycloid::model::Scene {
        output_torque_nmm: torque_nmm,
        ..spec.scenes[0].clone()
    };
    let plan = Plan::of("torsion", &[Effect::RollerContact]);
    let solve = |torque_nmm: f64| {
        let model = Model::new(&spec.design, &spec.modification, &scene(torque_nmm), &plan);
        solve_angle(&model, 0.0, &AngleSolution::default()).unwrap()
    };
    let rest = solve(0.0);
    let centre = nalgebra::Vector2::new(spec.design.eccentricity_mm, 0.0);
    let arm_sum: f64 = rest
        .rollers
        .iter()
        .map(|s| s.force_n * (s.point - centre).dot(&s.normal).abs())
        .sum();
    assert!(arm_sum > 0.0, "the shift of 2 µm preloads the rollers");
    let h = 1.0;
    let k = 2.0 * h / (solve(h).lag_rad.unwrap() - solve(-h).lag_rad.unwrap());
    let arcmin = 60.0 * 180.0 / std::f64::consts::PI;
    for mu in [0.001, 0.01] {
        let expected = 2.0 * mu * arm_sum / k * arcmin;
        let s = torsion(&torsion_spec(
            0.002,
            Some(&rollers_only(mu)),
            "roller_contact",
        ));
        let got = numbers(&s["hysteresis_loss_arcmin"])[0];
        // Each branch is K·δ ± μ·M_f ± μ·S·δ = 0 near the frictionless lag (S = Σ k·l·|a|, the
        // friction's arms stiffening one branch and softening the other), so the width is
        // 2μM_f·K/(K² − μ²S²): the closed form up to O(μ²·(S/K)²) of itself, and the solves'
        // tolerance (1e-9 of the twist). 1e-5 at μ ≤ 0.01 (measured: 1e-8).
        assert!(
            ((got - expected) / expected).abs() < 1e-5,
            "μ {mu}: hysteresis {got} arcmin, 2·M_f/K = {expected} arcmin"
        );
    }
}

/// At a crank angle where the reducer is mirror-symmetric (0°: a roller, a pin and the crank
/// on the x axis) the loop is point-symmetric: the unloading branch at −T is the loading
/// branch at T turned over, γ_u(−T) = −γ_l(T), with every path's friction (a sign of the
/// bearing's or the pins' friction wrong on one branch breaks it).
#[test]
fn the_loop_is_point_symmetric_at_a_mirror_symmetric_angle() {
    let s = preloaded_loop();
    let t = numbers(&s["torque_nm"]);
    let g = numbers(&s["torsion_arcmin"][0]);
    let steps = (t.len() - 1) / 4;
    let mut pairs = 0;
    for m in 0..=2 * steps {
        for n in 2 * steps..t.len() {
            if t[m] != 0.0 && t[n] == -t[m] {
                pairs += 1;
                // Solved to a relative tolerance of ~1e-9 of the twist (≤ 1 arcmin here).
                assert!(
                    (g[n] + g[m]).abs() < 1e-8,
                    "T {}: loading {} arcmin, unloading at −T {} arcmin",
                    t[m],
                    g[m],
                    g[n]
                );
            }
        }
    }
    assert_eq!(pairs, 2 * steps, "every torque but zero is paired");
    let h = numbers(&s["hysteresis_loss_arcmin"])[0];
    assert!(h > 0.0, "the preloaded loop opens: {h}");
}

/// The loop's area ∮ T dγ recomputed from the drawn curve (trapezoids over its points, N·m
/// × rad = J) is the energy per cycle the JSON states. The engine integrates over a finer
/// grid (the figures' torques added), so they agree to the curvature of the branches between
/// the loop's points: 1e-4.
#[test]
fn the_loop_energy_is_the_area_of_the_drawn_loop() {
    let s = preloaded_loop();
    let t = numbers(&s["torque_nm"]);
    let g: Vec<f64> = numbers(&s["torsion_arcmin"][0])
        .iter()
        .map(|a| a.to_radians() / 60.0)
        .collect();
    // The loading branch lies below the unloading one: the loop runs clockwise in (γ, T).
    let area: f64 = (0..t.len() - 1)
        .map(|i| 0.5 * (t[i] + t[i + 1]) * (g[i + 1] - g[i]))
        .sum();
    // The loop closes: after the reversal at −rated the disc is held where unloading left it,
    // so the loop ends where it began (exactly: the same solve).
    assert_eq!(g[0], g[g.len() - 1], "the loop closes");
    let energy = numbers(&s["hysteresis_energy_j"])[0];
    assert!(area > 0.0, "{area} J");
    assert!(
        ((energy - area) / area).abs() < 1e-4,
        "energy {energy} J, drawn loop's area {area} J"
    );
}

/// More friction, more hysteresis; a design whose contacts all open at zero torque (the
/// paper's optimum: a dead band) has none, whatever μ: at either edge of the band no contact
/// is loaded, so none carries friction (MODEL.md). Its figures stay the frictionless ones
/// within the friction at ±1e-6 of the rated torque.
#[test]
fn hysteresis_grows_with_mu_and_vanishes_without_preload() {
    let effects = "roller_contact, output_pins, bearing";
    let h = |shift: f64, mu: &str| {
        let s = torsion(&torsion_spec(
            shift,
            Some(&ALL_PATHS.replace("MU", mu)),
            effects,
        ));
        numbers(&s["hysteresis_loss_arcmin"])[0]
    };
    let (low, high) = (h(0.003, "0.02"), h(0.003, "0.05"));
    assert!(0.0 < low && low < high, "μ 0.02: {low}, μ 0.05: {high}");
    let spec = PaperSpec::new();
    let optimum = spec.text();
    assert!(optimum.contains("shift_mm: 0.125"), "the paper's optimum");
    let free = |friction: Option<&str>| {
        let text = torsion_spec(0.125, friction, effects)
            .replace("equidistant_mm: 0.0\n", "equidistant_mm: 0.1593\n");
        torsion(&text)
    };
    let with = free(Some(&ALL_PATHS.replace("MU", "0.1")));
    let without = free(None);
    let loss = numbers(&with["hysteresis_loss_arcmin"])[0];
    // Zero by the model without preload; what is left comes from the branches' points nearest
    // T = 0 (1.1e-7 arcmin measured), where a contact just touching carries forces of the
    // order of those points' torques. 1e-6 arcmin is 2e-5 of the hysteresis of 1 µm of
    // preload at μ 0.05 (0.047 arcmin), so a friction left in the balance without preload
    // would show far above it.
    assert!(loss.abs() < 1e-6, "no preload: hysteresis {loss} arcmin");
    let backlash = |s: &Value| numbers(&s["backlash_arcmin"])[0];
    assert!(backlash(&without) > 1.0, "the optimum has a dead band");
    assert!(
        (backlash(&with) - backlash(&without)).abs() < 1e-6,
        "backlash with friction {} against {}",
        backlash(&with),
        backlash(&without)
    );
    assert!(without.get("hysteresis_loss_arcmin").is_none());
}

/// A friction moment larger than the rated torque never lets the disc slide back: the loop
/// has no figures, and the run says why, where (scene, crank angle) and what to change, exit
/// 2 — rather than figures read from branches the disc never reaches.
#[test]
fn a_loop_that_friction_holds_throughout_is_refused_by_name() {
    let dir = Scratch::new("friction-torsion-held");
    // A shift of 20 µm presses every roller by thousands of newtons.
    dir.write(
        "s.yaml",
        torsion_spec(0.02, Some(&rollers_only(0.05)), "roller_contact"),
    );
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains(
            "scene `torsion`: crank angle 0.0000° locked, output torque 20.00 N·m: friction \
             holds the disc over the whole torsion loop"
        ),
        "{err}"
    );
    assert!(err.contains("Raise torque_sweep.rated_nm, or lower μ or the preload"));
}

/// `limits.max_hysteresis_loss_arcmin` passes and fails on the computed loss, refuses a
/// negative value, and is refused without `reducer.friction` (the frictionless loop's 0 is the
/// model's, not the design's), each at its key.
#[test]
fn the_hysteresis_limit_checks_and_is_refused_without_friction() {
    let friction = rollers_only(0.002);
    let text = torsion_spec(0.002, Some(&friction), "roller_contact");
    let loss = numbers(&torsion(&text)["hysteresis_loss_arcmin"])[0];
    let dir = Scratch::new("friction-torsion-limit");
    let run = |text: &str| {
        dir.write("s.yaml", text);
        cycloid(&dir.path, &["check", "s.yaml"]).parts()
    };
    let limited = |limit: f64| format!("{text}limits:\n  max_hysteresis_loss_arcmin: {limit:?}\n");
    assert_eq!(run(&limited(1.01 * loss)).0, 0);
    let (code, out, _) = run(&limited(0.99 * loss));
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("max_hysteresis_loss_arcmin"), "{out}");
    let (code, _, err) = run(&limited(-1.0));
    assert_eq!(code, 2);
    assert!(
        err.contains("invalid value: limits.max_hysteresis_loss_arcmin"),
        "{err}"
    );
    let frictionless = format!(
        "{}limits:\n  max_hysteresis_loss_arcmin: 1.0\n",
        torsion_spec(0.002, None, "roller_contact")
    );
    let (code, _, err) = run(&frictionless);
    assert_eq!(code, 2);
    assert!(
        err.contains("limits.max_hysteresis_loss_arcmin: a hysteresis loss needs friction"),
        "{err}"
    );
}

/// A torsion loop with friction balances with a rigid crank bearing: a compliant one in the
/// torque_sweep scene is refused at its key.
#[test]
fn a_compliant_bearing_in_a_loop_with_friction_is_refused() {
    let text = torsion_spec(0.002, Some(&rollers_only(0.01)), "roller_contact, bearing").replace(
        "    effects: [roller_contact, bearing]\n",
        "    effects: [roller_contact, bearing]\n    bearing_stiffness_n_per_mm: 200000.0\n",
    );
    let dir = Scratch::new("friction-torsion-compliant");
    dir.write("s.yaml", &text);
    let (code, _, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(
            "scenes[0].bearing_stiffness_n_per_mm: a torsion loop with `reducer.friction`"
        ),
        "{err}"
    );
}

/// Each loaded pin's friction opposes the sliding its hole makes between two neighbouring
/// points of the loading branch, computed here from the solved lags alone: the hole's
/// material at the contact X moves by Δβ·ẑ × (X − O_d), the pin's by (Δβ + Δβo)·ẑ × X, so
/// along ẑ × u it slides by −Δβ·O_d·u − Δβo·X·u. The pins' deflection βo per turn of the disc
/// (ρ) decides most pins' direction here (the pins are ~4× softer than the rollers), so a
/// branch that ignored it would fail.
#[test]
fn every_pins_friction_opposes_its_sliding_along_the_branch() {
    use cycloid::equilibrium::discs::{CoupledWork, Discs};
    use cycloid::equilibrium::friction::torsion::{set_branch, solve_point};
    let spec = paper_spec(0.125, 0.1593);
    let friction = cycloid::spec::parse(
        "s.yaml",
        &torsion_spec(
            0.125,
            Some(&ALL_PATHS.replace("MU", "0.05")),
            "roller_contact",
        ),
    )
    .unwrap()
    .design
    .friction
    .unwrap();
    let plan = Plan::of(
        "torsion",
        &[Effect::RollerContact, Effect::OutputPins, Effect::Bearing],
    );
    let mut model = Model::new(&spec.design, &spec.modification, &spec.scenes[0], &plan)
        .with_friction(&friction, &spec.design);
    model.coupling = model.coupling.map(|c| c.in_torsion(1.0));
    let mut discs = Discs::new(&model, 1);
    let mut work = CoupledWork::new(&discs);
    set_branch(&mut discs, &mut work, 1.0);
    let crank = 0.3;
    let lags = |work: &CoupledWork| {
        let sol = &work.works[0].sol;
        (sol.lag_rad.unwrap(), sol.output_lag_rad.unwrap())
    };
    let mut checked = 0;
    for step in 0..4 {
        let t = 8_000.0 + 1_000.0 * step as f64;
        solve_point(&mut discs, crank, t, &mut work).unwrap();
        let (b1, o1) = lags(&work);
        solve_point(&mut discs, crank, t + 50.0, &mut work).unwrap();
        let (b2, o2) = lags(&work);
        let (db, dbo) = (b2 - b1, o2 - o1);
        assert!(db > 0.0 && dbo > 0.0, "both lags grow on loading");
        let c = work.models[0].coupling.unwrap();
        let e_phi = nalgebra::Vector2::new(crank.cos(), crank.sin());
        let centre = e_phi * spec.design.eccentricity_mm;
        for p in work.works[0].sol.pins.iter().filter(|p| p.force_n > 0.0) {
            let u = p.direction;
            let slide = -db * centre.dot(&u) - dbo * p.point.dot(&u);
            let along = nalgebra::Vector2::new(-u.y, u.x);
            let d = c.pin_direction(e_phi, centre, p);
            // A sliding within 1e-3 of the largest term is where it changes sign: skipped.
            if slide.abs() > 1e-3 * (db * centre.norm()).max(dbo * p.point.norm()) {
                assert!(
                    d.dot(&along) * slide > 0.0,
                    "pin at {:?}: slides {slide:e} along ẑ × u, friction direction {d:?}",
                    p.point
                );
                checked += 1;
            }
        }
    }
    assert!(checked >= 8, "{checked} loaded pins checked");
}
