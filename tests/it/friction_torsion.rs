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

/// The loop of the paper's design preloaded by a shift of 2 µm, every path's friction at μ 0.05
/// (the crank bearing's 0.005), rollers, pins and bearing modelled. (At 3 µm the rollers'
/// friction moment alone, 22.9 N·m, exceeds the rated 20 N·m: friction holds that loop shut.)
fn preloaded_loop() -> Value {
    let friction = ALL_PATHS.replace("MU", "0.05");
    let effects = "roller_contact, output_pins, bearing";
    torsion(&torsion_spec(0.002, Some(&friction), effects))
}

/// The torques (N·m) and the first locked angle's torsion curve (arcmin) of a torsion scene.
fn drawn_loop(s: &Value) -> (Vec<f64>, Vec<f64>) {
    (numbers(&s["torque_nm"]), numbers(&s["torsion_arcmin"][0]))
}

/// The drawn loop's width at T = 0 (arcmin): its falling half minus its rising half there,
/// each interpolated linearly between the two points of the half that bracket T = 0.
fn width_at_zero(t: &[f64], g: &[f64]) -> f64 {
    let half = (t.len() - 1) / 2;
    let at_zero = |range: std::ops::Range<usize>| {
        range
            .filter(|&i| t[i] * t[i + 1] <= 0.0 && t[i] != t[i + 1])
            .map(|i| g[i] + (g[i + 1] - g[i]) * (0.0 - t[i]) / (t[i + 1] - t[i]))
            .next()
            .expect("the half crosses T = 0")
    };
    at_zero(half..t.len() - 1) - at_zero(0..half)
}

/// The drawn loop's area ∮ T dγ (J: N·m × rad), by trapezoids over its points.
fn loop_area_j(t: &[f64], g: &[f64]) -> f64 {
    let g: Vec<f64> = g.iter().map(|a| a / ARCMIN).collect();
    (0..t.len() - 1)
        .map(|i| 0.5 * (t[i] + t[i + 1]) * (g[i + 1] - g[i]))
        .sum()
}

/// The paper's design preloaded by a shift of `shift_mm` (ΔRrp = 0), from the frictionless
/// solver alone at crank 0°: Σ F_i·|(C_i − O_d)·n_i| at T = 0 (N·mm per unit μ: the fixed
/// rollers' friction moment is μ times it) and K = dT/dβ there (N·mm/rad, a central difference
/// over ±1 N·mm, exact for the linear law while no contact opens).
fn preload_arms_and_stiffness(shift_mm: f64) -> (f64, f64) {
    let spec = paper_spec(shift_mm, 0.0);
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
    assert!(
        arm_sum > 0.0,
        "the shift of {shift_mm} mm preloads the rollers"
    );
    let h = 1.0;
    let k = 2.0 * h / (solve(h).lag_rad.unwrap() - solve(-h).lag_rad.unwrap());
    (arm_sum, k)
}

/// arcmin per rad.
const ARCMIN: f64 = 60.0 * 180.0 / std::f64::consts::PI;

/// The first-order closed form (one disc, rollers only, linear law, preloaded by a shift of
/// 2 µm): at T = 0 each branch balances Σ F_i·(l_i ± μ·|(C_i − O_d)·n_i|) = 0, so to first
/// order in μ the lag moves by ∓M_f/K from the frictionless one, M_f = μ·Σ F_i·|(C_i − O_d)·n_i|
/// with the frictionless forces at T = 0, K = dT/dβ there: the hysteresis is 2·M_f/K while
/// M_f ≤ T_r/2 (the disc slides back onto each branch before T = 0). Both from the frictionless
/// solver alone (forces, points, normals; K by a central difference).
#[test]
fn hysteresis_matches_the_first_order_closed_form() {
    let (arm_sum, k) = preload_arms_and_stiffness(0.002);
    for mu in [0.001, 0.01] {
        assert!(mu * arm_sum < 0.5 * RATED_NM * 1e3, "M_f below T_r/2");
        let expected = 2.0 * mu * arm_sum / k * ARCMIN;
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

/// When the friction moment M_f lies between T_r/2 and T_r (a shift of 2 µm, fixed rollers at
/// μ 0.05: M_f ≈ 15.3 N·m against 20 N·m rated), the disc, held after each reversal, never
/// reaches the sliding branches at T = 0: held at β_l(T_r) ≈ (T_r − M_f)/K coming down and at
/// β_u(−T_r) ≈ −(T_r − M_f)/K going up, the loop it traverses is 2·(T_r − M_f)/K wide there,
/// not the branches' 2·M_f/K. The figure is checked against that closed form (M_f and K from
/// the frictionless solver) and against the drawn curve's own width at T = 0; the energy
/// against the drawn curve's area.
#[test]
fn the_hysteresis_is_the_width_of_the_traversed_loop_at_zero_torque() {
    let (arm_sum, k) = preload_arms_and_stiffness(0.002);
    let (mu, rated) = (0.05, RATED_NM * 1e3);
    let m_f = mu * arm_sum;
    assert!(0.5 * rated < m_f && m_f < rated, "M_f {m_f} N·mm");
    let s = torsion(&torsion_spec(
        0.002,
        Some(&rollers_only(mu)),
        "roller_contact",
    ));
    let got = numbers(&s["hysteresis_loss_arcmin"])[0];
    let expected = 2.0 * (rated - m_f) / k * ARCMIN;
    // β_l(T_r) balances K·β − M_f − μ·S·β = T_r (S = Σ k·l·|a|, the friction's arms' growth
    // with the lag), and β_u(−T_r) is its mirror at 0°, so the width is 2(T_r − M_f)/(K − μS):
    // the closed form to μ·S/K of itself, with K and M_f at T = 0 held over ±(T_r − M_f) (the
    // linear law, no contact opening there). 1e-4 (measured: 1.8e-5).
    assert!(
        ((got - expected) / expected).abs() < 1e-4,
        "hysteresis {got} arcmin, 2·(T_r − M_f)/K = {expected} arcmin"
    );
    let (t, g) = drawn_loop(&s);
    let drawn = width_at_zero(&t, &g);
    // The same loop: its points at 0⁻ (rising) and 0⁺ (falling) are the figure's, both held
    // flat here (rollers only), so they agree to round-off.
    assert!(
        (got - drawn).abs() <= 1e-12 * drawn,
        "hysteresis {got} arcmin, the drawn loop's width at T = 0 {drawn} arcmin"
    );
    let energy = numbers(&s["hysteresis_energy_j"])[0];
    let area = loop_area_j(&t, &g);
    // The engine's trapezoids also pass through the figures' torques (±3 %, ±1e-6 of rated),
    // on the flat held segment here: only the sliding parts' curvature between the curve's
    // points differs, 1e-4.
    assert!(
        ((energy - area) / area).abs() < 1e-4,
        "energy {energy} J, drawn loop's area {area} J"
    );
}

/// An elastic stage in series with the disc (frictionless output pins, the structure's given
/// compliance) stores and returns its energy: the disc's own lag, which friction holds, is
/// the same, the stage adds a twist that follows the torque both ways, so the hysteresis and
/// the loop's energy are those of the rollers alone (only fixed rollers carry friction here,
/// and the rollers' balance does not see the pins). Shifts of 2 µm (the disc held through
/// T = 0) and 1 µm (sliding there).
#[test]
fn an_elastic_stage_in_series_opens_no_loop() {
    for shift in [0.002, 0.001] {
        let friction = rollers_only(0.05);
        let alone = torsion(&torsion_spec(shift, Some(&friction), "roller_contact"));
        let pins = torsion_spec(shift, Some(&friction), "roller_contact, output_pins");
        let structure = pins.replace(
            "modification:",
            "  structure_compliance_arcmin_per_knm: 50.0\nmodification:",
        );
        let figure = |s: &Value, key: &str| numbers(&s[key])[0];
        for (name, text) in [("pins", pins.as_str()), ("pins and structure", &structure)] {
            let s = torsion(text);
            for key in ["hysteresis_loss_arcmin", "hysteresis_energy_j"] {
                let (got, expected) = (figure(&s, key), figure(&alone, key));
                // The pins' deflection depends on the disc's lag only through the holes'
                // turn with it (the branches' lags differ by ~1e-5 rad), and on a held
                // segment is taken at the branch's lag; the solves' tolerance is 1e-9 of the
                // twist. 1e-6 (measured: 2e-9).
                assert!(
                    ((got - expected) / expected).abs() < 1e-6,
                    "shift {shift} mm, {name}: {key} {got} against the rollers alone's {expected}"
                );
            }
            let (t, g) = drawn_loop(&s);
            let area = loop_area_j(&t, &g);
            let energy = figure(&s, "hysteresis_energy_j");
            // As `the_loop_energy_is_the_area_of_the_drawn_loop`: the engine's trapezoids also
            // pass through the figures' torques, 1e-4 (measured: 5e-6).
            assert!(
                ((energy - area) / area).abs() < 1e-4,
                "shift {shift} mm, {name}: energy {energy} J, drawn loop's area {area} J"
            );
        }
    }
}

/// A loop that friction holds shut is refused whatever is in series with the disc: at a shift
/// of 3 µm the fixed rollers' friction moment alone at μ 0.05 (from the frictionless forces)
/// exceeds the rated 20 N·m, so the disc never slides back, with or without output pins.
#[test]
fn a_loop_friction_holds_shut_is_refused_whatever_is_in_series() {
    let (arm_sum, _) = preload_arms_and_stiffness(0.003);
    assert!(
        0.05 * arm_sum > RATED_NM * 1e3,
        "M_f {} N·mm",
        0.05 * arm_sum
    );
    let dir = Scratch::new("friction-torsion-shut");
    for effects in ["roller_contact", "roller_contact, output_pins"] {
        dir.write(
            "s.yaml",
            torsion_spec(0.003, Some(&rollers_only(0.05)), effects),
        );
        let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
        assert_eq!(code, 2, "{effects}: {out}{err}");
        assert!(
            err.contains("friction holds the disc over the whole torsion loop"),
            "{effects}: {err}"
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
    let (t, g) = drawn_loop(&s);
    // The loading branch lies below the unloading one: the loop runs clockwise in (γ, T).
    let area = loop_area_j(&t, &g);
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
    // At 1 µm M_f stays below T_r/2 up to μ 0.05: the disc slides back onto each branch before
    // T = 0, where the width is the branches' 2·M_f/K.
    let (low, high) = (h(0.001, "0.02"), h(0.001, "0.05"));
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

/// Friction that takes the whole moment of the rollers' normal forces locks the disc, at any
/// torque: μ 0.5 on every path of a torsion loop (locked at 0°, 9°, 18°, 27°), and the coupled
/// model of a running reducer at μ 0.8, both at 0.01 N·m on the paper's optimum. Each is
/// refused with exit 2 at its scene, naming self-locking and giving the friction moment
/// against the torque, not as a load beyond what the contacts can hold; and what the message
/// states is self-locking: the friction moment at least the normal forces' moment, or the
/// normal forces alone carrying more than the torque.
#[test]
fn friction_beyond_the_normal_forces_is_refused_as_self_locking() {
    let optimum = |text: String| text.replace("equidistant_mm: 0.0\n", "equidistant_mm: 0.1593\n");
    let every_path = "{ rollers: { mode: fixed, mu: 0.5 }, output_pins: { mode: fixed, mu: 0.5 }, \
                      crank_bearing: { mu: 0.5, bore_diameter_mm: 20.0 } }";
    let torsion_text = optimum(torsion_spec(
        0.125,
        Some(every_path),
        "roller_contact, output_pins, bearing",
    ))
    .replace("rated_nm: 20.0", "rated_nm: 0.01")
    .replace("to_deg: 36.0, steps: 1", "to_deg: 36.0, steps: 4");
    let coupled = every_path
        .replace("0.5", "0.8")
        .replacen("{ ", "{ model: coupled, ", 1);
    let drive_text = optimum(
        PaperSpec::new()
            .modification(0.125, 0.0)
            .scenes(
                "  - name: rated\n    output_torque_nm: 0.01\n    \
                 crank: { from_deg: 0.0, to_deg: 36.0, steps: 36 }\n    effects: [efficiency]\n",
            )
            .edit(
                "modification:",
                &format!("  friction: {coupled}\nmodification:"),
            )
            .text()
            .to_string(),
    );
    let dir = Scratch::new("friction-self-locking");
    for (name, text, key) in [
        ("torsion", &torsion_text, "scenes[0].torque_sweep.rated_nm"),
        ("drive", &drive_text, "scenes[0]:"),
    ] {
        dir.write("s.yaml", text);
        let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
        assert_eq!(code, 2, "{name}: {out}{err}");
        assert!(err.contains(key), "{name}: {err}");
        assert!(
            err.contains("self-locking: friction holds the disc against an output torque of"),
            "{name}: {err}"
        );
        // The two moments the message gives, N·m, in the torque's direction.
        let after = |label: &str| -> f64 {
            let rest =
                &err[err.find(label).unwrap_or_else(|| panic!("{label}: {err}")) + label.len()..];
            rest.split_whitespace().next().unwrap().parse().unwrap()
        };
        let friction = after("the friction moment is ");
        let normal = after("against the normal forces' ");
        assert!(friction.is_finite() && normal.is_finite(), "{name}: {err}");
        assert!(
            friction.abs() >= normal.abs() || normal.abs() >= 0.01,
            "{name}: friction {friction} N·m, normal {normal} N·m: {err}"
        );
        assert!(
            !err.contains("beyond what this disc can hold"),
            "{name}: {err}"
        );
    }
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
    use cycloid::equilibrium::torsion::{set_branch, solve_point};
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

/// Several discs with friction: the paper's two discs half a crank turn apart mesh alike (π is
/// five of np = 10 mesh periods, and without the pins nothing else breaks the symmetry), so
/// they share the output torque equally and each turns its own loop at T/2. The reducer's loop
/// at ±20 N·m must then be the one disc's loop at ±10 N·m, point by point (torques halved,
/// the same twist): the same hysteresis width, twice the rigidity and twice the energy per
/// cycle. A model that split the friction lag wrongly between the discs, held one disc and
/// not the other, or summed their lags, fails it.
#[test]
fn two_discs_half_a_turn_apart_turn_the_loop_of_one_disc_at_half_the_torque() {
    let spec = |discs: usize, rated_nm: f64| {
        let text = torsion_spec(0.002, Some(&rollers_only(0.02)), "roller_contact");
        assert_eq!(text.matches("\nreducer:\n").count(), 1);
        text.replace(
            &format!("rated_nm: {RATED_NM:?}"),
            &format!("rated_nm: {rated_nm:?}"),
        )
        .replace("\nreducer:\n", &format!("\nreducer:\n  discs: {discs}\n"))
    };
    let one = torsion(&spec(1, RATED_NM / 2.0));
    let two = torsion(&spec(2, RATED_NM));
    let (t1, g1) = drawn_loop(&one);
    let (t2, g2) = drawn_loop(&two);
    assert_eq!(t1.len(), t2.len());
    // The loop must be open, or equal widths say nothing.
    let width = width_at_zero(&t1, &g1);
    assert!(width > 1e-3, "hysteresis {width} arcmin");
    let scale = g1.iter().fold(0.0f64, |m, g| m.max(g.abs()));
    for i in 0..t1.len() {
        assert_eq!(t2[i], 2.0 * t1[i], "the torque steps scale exactly");
        // The two runs solve the same contacts in another order of the rollers: solver
        // round-off, 1e-9 of the loop's largest twist.
        assert!(
            (g2[i] - g1[i]).abs() <= 1e-9 * scale,
            "T {}: {} vs {}",
            t2[i],
            g2[i],
            g1[i]
        );
    }
    let first = |s: &Value, key: &str| numbers(&s[key])[0];
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    let rigidity = "torsional_rigidity_nm_per_arcmin";
    assert!(rel(first(&two, rigidity), 2.0 * first(&one, rigidity)) < 1e-9);
    let energy = "hysteresis_energy_j";
    assert!(rel(first(&two, energy), 2.0 * first(&one, energy)) < 1e-9);
}
