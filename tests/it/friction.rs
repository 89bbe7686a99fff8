//! Friction, efficiency and heat (issue 28, MODEL.md "Friction, efficiency and heat"), the loss
//! model end to end through `cycloid check --json`: each path's loss against its closed form
//! from the forces the same JSON reports, μ = 0 as the frictionless run, the independence of η
//! from the speed, the mean efficiency from the mean of the losses, the linearity in μ, the
//! discs adding up, and every bad value refused at its key.
//!
//! Expected values are computed here from the definitions (MODEL.md), never copied from a run.

use crate::common::{cycloid, Scratch};
use serde_json::Value;
use std::f64::consts::TAU;

/// The shipped spec: the paper's design, rotating rollers (μ 0.06, r_b 1.5 mm), sleeved pins
/// (μ 0.06, r_bore 2 mm, r_pin 3 mm), a crank bearing (μ 0.0025, d 20 mm), a drag of 30 N·mm,
/// thermal (A 0.06 m², h 20 W/(m²·K), 20 °C), at 20 N·m and 1500 rpm over 108° in 1080 steps.
const EFF: &str = include_str!("../../specs/reducer-efficiency.yaml");

/// nc, e and the torque of the shipped spec.
const NC: f64 = 9.0;
const E_MM: f64 = 2.0;
const TORQUE_NMM: f64 = 20_000.0;

/// `text` with each `(from, to)` replaced (each `from` exactly once).
fn edited(text: &str, edits: &[(&str, &str)]) -> String {
    let mut t = text.to_string();
    for (from, to) in edits {
        assert_eq!(t.matches(from).count(), 1, "`{from}` must occur once");
        t = t.replacen(from, to, 1);
    }
    t
}

/// The shipped spec without its limits (a variant must not fail one on purpose).
fn no_limits(text: &str) -> String {
    text[..text.find("\nlimits:").unwrap() + 1].to_string()
}

/// The scene `rated` of `check --json` on `text` (whether its limits pass or not).
fn rated(text: &str) -> Value {
    let dir = Scratch::new("friction");
    dir.write("s.yaml", text);
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]).parts();
    // 1: a limit failed; the results are written all the same.
    assert!(code == 0 || code == 1, "{out}{err}");
    let doc: Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    doc["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "rated")
        .unwrap()
        .clone()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn rows(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().unwrap().iter().map(floats).collect()
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// ω of 1500 rpm, rad/s.
fn omega(rpm: f64) -> f64 {
    rpm * TAU / 60.0
}

/// |a − b| ≤ rel·|b| (and a tiny absolute floor for zeros).
fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs() + 1e-300
}

/// The pins, the bearing and the drag of the shipped spec lose at their closed forms, computed
/// here from the forces the JSON reports: pins μ·ΣF_j·e·(1 + 1/nc)·r_bore/r_pin·ω, bearing
/// μ·|Fb|·(d/2)·(1 + 1/nc)·ω, drag T0·ω, each a mean over the crank angles, in W (× 1e-3).
/// 1e-12 relative: the same sums in another order.
#[test]
fn pins_bearing_and_drag_lose_at_their_closed_forms() {
    let s = rated(EFF);
    let w = omega(1500.0) * 1e-3;
    let relative = 1.0 + 1.0 / NC;
    let pins = rows(&s["pin_force_n"]);
    let n = pins[0].len();
    let pin_sum: Vec<f64> = (0..n).map(|k| pins.iter().map(|p| p[k]).sum()).collect();
    let expected_pins = 0.06 * mean(&pin_sum) * E_MM * relative * (2.0 / 3.0) * w;
    let bearing = floats(&s["bearing_force_n"]);
    let expected_bearing = 0.0025 * mean(&bearing) * 10.0 * relative * w;
    let p = &s["power_loss_w"];
    let got = |k: &str| p[k].as_f64().unwrap();
    assert!(
        close(got("output_pins"), expected_pins, 1e-12),
        "{p} vs {expected_pins}"
    );
    assert!(
        close(got("crank_bearing"), expected_bearing, 1e-12),
        "{p} vs {expected_bearing}"
    );
    assert!(close(got("no_load"), 30.0 * w, 1e-12), "{p}");
    let sum = got("rollers") + got("output_pins") + got("crank_bearing") + got("no_load");
    assert!(close(got("total"), sum, 1e-12), "{p}");
}

/// Fixed rollers on the unmodified profile slide at (ω/nc)·(|P_i − I| − Rrp), I the pitch
/// point e·np·(cos φ, sin φ): with friction on the rollers alone the loss at each angle,
/// T_in − T/nc (the loss model's input torque), is Σ μ·F_i·(|P_i − I| − Rrp)/nc with the
/// JSON's forces. The loaded disc sits turned by its lag β, which moves a contact point by at
/// most (|C − O_d| + |C − I|)·|β| ≤ 2(Rp + e·np)·|β| along the profile, so the closed form of
/// the ideal pose holds to μ·ΣF·2(Rp + e·np)·|β|/nc at each angle (the tolerance).
#[test]
fn fixed_rollers_slide_at_the_closed_form() {
    let text = edited(
        &no_limits(EFF),
        &[
            (
                "    rollers:                     # each roller turns on a pin: rolls on the disc, slides on the pin\n      mode: rotating\n      mu: 0.06                   # greased steel on steel, sliding (0.04-0.25)\n      bore_radius_mm: 1.5        # r_b, the roller's pin\n",
                "    rollers: { mode: fixed, mu: 0.05 }\n",
            ),
            ("    output_pins:                 # a free sleeve on each pin: rolls in the hole, slides on the pin\n      mode: sleeve\n      mu: 0.06                   # greased steel on steel, sliding\n      bore_radius_mm: 2.0        # r_bore, the pin inside the sleeve\n", ""),
            ("    crank_bearing:\n      mu: 0.0025                 # needle roller bearing, referred to the bore (0.002-0.003)\n      bore_diameter_mm: 20.0     # d\n", ""),
            ("    no_load_torque_nmm: 30.0     # seals and grease churning at the input (our assumption)\n", ""),
            ("  shift_mm: 0.125 ", "  shift_mm: 0.0 "),
            ("  equidistant_mm: 0.1593 ", "  equidistant_mm: 0.0 "),
            ("output_torque_nm: 20.0", "output_torque_nm: 2.0"),
        ],
    );
    let s = rated(&text);
    let crank = floats(&s["crank_deg"]);
    let forces = rows(&s["roller_force_n"]);
    let lag = floats(&s["lag_arcsec"]);
    let input = floats(&s["input_torque_nm"]);
    let (rp, rrp, np) = (30.0_f64, 3.0_f64, 10usize);
    for (k, &deg) in crank.iter().enumerate() {
        let phi = deg.to_radians();
        let pitch = (E_MM * np as f64 * phi.cos(), E_MM * np as f64 * phi.sin());
        let mut expected = 0.0;
        let mut force = 0.0;
        for (i, f) in forces.iter().enumerate() {
            let a = TAU * i as f64 / np as f64;
            let d = ((rp * a.cos() - pitch.0).powi(2) + (rp * a.sin() - pitch.1).powi(2)).sqrt();
            expected += 0.05 * f[k] * (d - rrp) / NC;
            force += f[k];
        }
        let loss = input[k] * 1e3 - 2000.0 / NC;
        let beta = (lag[k] / 3600.0).to_radians().abs();
        let tol = 0.05 * force * 2.0 * (rp + E_MM * np as f64) * beta / NC + 1e-9 * expected;
        assert!(
            (loss - expected).abs() <= tol,
            "crank {deg}°: loss {loss} N·mm, closed form {expected}, tolerance {tol}"
        );
    }
}

/// μ = 0 everywhere and no drag: η = 1 at every angle and on the mean, nothing lost, the input
/// torque T/nc exactly, and every other output of the scene bit for bit that of the same spec
/// without `reducer.friction` (the loss model reads the frictionless forces and changes none).
#[test]
fn no_friction_is_the_frictionless_run() {
    let base = no_limits(EFF);
    let zero = base
        .replace("mu: 0.06", "mu: 0.0")
        .replace("mu: 0.0025", "mu: 0.0")
        .replace("no_load_torque_nmm: 30.0", "no_load_torque_nmm: 0.0");
    let with = rated(&zero);
    for (k, e) in floats(&with["efficiency"]).iter().enumerate() {
        assert_eq!(*e, 1.0, "angle {k}");
    }
    assert_eq!(with["mean_efficiency"].as_f64(), Some(1.0));
    assert_eq!(with["power_loss_w"]["total"].as_f64(), Some(0.0));
    assert_eq!(with["temperature_c"].as_f64(), Some(20.0));
    for t in floats(&with["input_torque_nm"]) {
        assert_eq!(t, 20.0 / NC, "T/nc");
    }
    let start = base.find("  friction:").unwrap();
    let end = base.find("modification:").unwrap();
    let frictionless = format!("{}{}", &base[..start], &base[end..])
        .replace("effects: [efficiency]", "effects: [bearing]");
    let without = rated(&frictionless);
    let without = without.as_object().unwrap();
    for (key, value) in without {
        assert_eq!(&with[key], value, "`{key}` differs with μ = 0");
    }
    for key in [
        "efficiency",
        "mean_efficiency",
        "power_loss_w",
        "input_torque_nm",
    ] {
        assert!(!without.contains_key(key), "`{key}` without friction");
    }
}

/// Coulomb friction: every loss is proportional to ω, so η is the same at 1500 and 3000 rpm
/// bit for bit, every loss in watts doubles (1e-12 relative: ω·1e-3 rounded twice), and the
/// temperature is ambient + P/(h·A) exactly at both speeds.
#[test]
fn efficiency_does_not_depend_on_the_speed() {
    let slow = rated(&no_limits(EFF));
    let fast = rated(&no_limits(EFF).replace("input_speed_rpm: 1500.0", "input_speed_rpm: 3000.0"));
    assert_eq!(slow["efficiency"], fast["efficiency"]);
    assert_eq!(slow["mean_efficiency"], fast["mean_efficiency"]);
    assert_eq!(slow["input_torque_nm"], fast["input_torque_nm"]);
    for path in [
        "rollers",
        "output_pins",
        "crank_bearing",
        "no_load",
        "total",
    ] {
        let (a, b) = (
            slow["power_loss_w"][path].as_f64().unwrap(),
            fast["power_loss_w"][path].as_f64().unwrap(),
        );
        assert!(close(b, 2.0 * a, 1e-12), "{path}: {a} W, {b} W");
    }
    for s in [&slow, &fast] {
        let p = s["power_loss_w"]["total"].as_f64().unwrap();
        let t = s["temperature_c"].as_f64().unwrap();
        assert!(close(t, 20.0 + p / (20.0 * 0.06), 1e-14), "{t} °C at {p} W");
    }
}

/// The mean efficiency is P_out/(P_out + mean loss), the mean of the losses (T_in(φ) − T/nc
/// from the JSON's input torque) and not the mean of η (larger, 1/(P + L) being convex in L:
/// the test would pass a mean of η only if the losses did not vary). The watts are that mean
/// loss × ω. 1e-12 relative: the same sums in another order.
#[test]
fn the_mean_efficiency_is_of_the_mean_loss() {
    let s = rated(EFF);
    let p_out = TORQUE_NMM / NC;
    let loss: Vec<f64> = floats(&s["input_torque_nm"])
        .iter()
        .map(|t| t * 1e3 - p_out)
        .collect();
    let mean_loss = mean(&loss);
    let expected = p_out / (p_out + mean_loss);
    let got = s["mean_efficiency"].as_f64().unwrap();
    assert!(close(got, expected, 1e-12), "{got} vs {expected}");
    let mean_eta = mean(&floats(&s["efficiency"]));
    assert!(
        mean_eta - got > 1e-7,
        "mean of η {mean_eta}, mean efficiency {got}"
    );
    let total = s["power_loss_w"]["total"].as_f64().unwrap();
    assert!(close(total, mean_loss * omega(1500.0) * 1e-3, 1e-12));
    for (k, (e, l)) in floats(&s["efficiency"]).iter().zip(&loss).enumerate() {
        assert!(close(*e, p_out / (p_out + l), 1e-12), "angle {k}");
    }
}

/// The loss model's losses are linear in μ: twice every μ (no drag) loses twice on every path,
/// with the same forces (1e-12 relative: one product rounded differently).
#[test]
fn losses_scale_linearly_with_mu() {
    let base = no_limits(EFF).replace("no_load_torque_nmm: 30.0", "no_load_torque_nmm: 0.0");
    let once = rated(&base);
    let twice = rated(
        &base
            .replace("mu: 0.06", "mu: 0.12")
            .replace("mu: 0.0025", "mu: 0.005"),
    );
    assert_eq!(once["roller_force_n"], twice["roller_force_n"]);
    for path in ["rollers", "output_pins", "crank_bearing", "total"] {
        let (a, b) = (
            once["power_loss_w"][path].as_f64().unwrap(),
            twice["power_loss_w"][path].as_f64().unwrap(),
        );
        assert!(a > 0.0 && close(b, 2.0 * a, 1e-12), "{path}: {a} W, {b} W");
    }
}

/// Two discs: the reducer loses what its discs lose, path by path, and the input's drag once
/// (1e-12 relative: a sum of two).
#[test]
fn the_discs_losses_add_up() {
    let s = rated(&edited(
        &no_limits(EFF),
        &[(
            "  rollers: 10                    # np, rollers in the housing\n",
            "  rollers: 10\n  discs: 2\n",
        )],
    ));
    let discs = s["discs"].as_array().unwrap();
    assert_eq!(discs.len(), 2);
    for path in ["rollers", "output_pins", "crank_bearing"] {
        let sum: f64 = discs
            .iter()
            .map(|d| d["power_loss_w"][path].as_f64().unwrap())
            .sum();
        let total = s["power_loss_w"][path].as_f64().unwrap();
        assert!(
            sum > 0.0 && close(total, sum, 1e-12),
            "{path}: {total} vs {sum}"
        );
    }
    for d in discs {
        assert_eq!(d["power_loss_w"]["no_load"].as_f64(), Some(0.0));
    }
    let no_load = s["power_loss_w"]["no_load"].as_f64().unwrap();
    assert!(close(no_load, 30.0 * omega(1500.0) * 1e-3, 1e-12));
}

/// Without a speed the efficiency is the same and the watts and the temperature are left out
/// with a note (the limits that need them are refused at the scene, before anything runs).
#[test]
fn without_a_speed_the_watts_are_left_out() {
    let with = rated(&no_limits(EFF));
    let text = no_limits(EFF).replace("    input_speed_rpm: 1500.0      # n\n", "");
    let without = rated(&text);
    assert_eq!(with["efficiency"], without["efficiency"]);
    assert!(without.get("power_loss_w").is_none());
    assert!(without.get("temperature_c").is_none());
    assert!(without["power_loss_note"]
        .as_str()
        .unwrap()
        .contains("input_speed_rpm"));
    let dir = Scratch::new("friction-speed");
    dir.write(
        "s.yaml",
        format!("{text}limits:\n  max_power_loss_w: 60.0\n"),
    );
    let (code, _, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("scenes[0]: limits.max_power_loss_w"), "{err}");
}

/// No output torque: nothing is delivered, so η is 0 where friction loses (no NaN).
#[test]
fn no_torque_is_no_efficiency() {
    let s = rated(&no_limits(EFF).replace("output_torque_nm: 20.0", "output_torque_nm: 0.0"));
    for e in floats(&s["efficiency"]) {
        assert_eq!(e, 0.0);
    }
    assert_eq!(s["mean_efficiency"].as_f64(), Some(0.0));
}

/// The shipped spec back-driven (−20 N·m: the output drives) with μ `mu` on the rollers' pins
/// and the sleeves, over 108 angles (the figures compared are of one run, so its sampling does
/// not matter), its limits kept.
fn back_driven_text(mu: &str) -> String {
    edited(
        EFF,
        &[
            ("output_torque_nm: 20.0", "output_torque_nm: -20.0"),
            ("steps: 1080", "steps: 108"),
        ],
    )
    .replace("mu: 0.06 ", &format!("mu: {mu} "))
}

/// `check` on `back_driven_text(mu)`: (exit code, terminal output, the scene's JSON).
fn back_driven(mu: &str) -> (i32, String, Value) {
    let text = back_driven_text(mu);
    let dir = Scratch::new("friction-back");
    dir.write("s.yaml", &text);
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]).parts();
    assert!(code == 0 || code == 1, "{out}{err}");
    let doc: Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    (code, out, doc["scenes"][0].clone())
}

/// The design review's index of `back_driven(mu)`'s spec.
fn back_driven_review(mu: &str) -> String {
    let text = back_driven_text(mu);
    let dir = Scratch::new("friction-back-review");
    dir.write("s.yaml", &text);
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml", "--report", "rev"]).parts();
    assert!(code == 0 || code == 1, "{out}{err}");
    dir.read("rev/index.html")
}

/// The line of `out` that starts (after its indent) with `what`.
fn line_of<'a>(out: &'a str, what: &str) -> &'a str {
    out.lines()
        .find(|l| l.trim_start().starts_with(what))
        .unwrap_or_else(|| panic!("no `{what}` in\n{out}"))
}

/// With the output driving (issue 39 §3) P = |T|·ω_out enters at the output and what the losses
/// leave reaches the input: η = (P − loss)/P, computed here from the watts the JSON reports and
/// P = 20 N·m × 1500 rpm·2π/60 / 9 (349.1 W), and at each angle from the loss model's energy
/// balance T_in = T/nc + loss (so loss = T_in + P per unit speed). The forward formula would
/// give P/(P + loss) (0.66 where this is 0.49). The headline and the limit's row say
/// back-driven. 1e-12 relative on the mean: the same quantities summed in another order.
#[test]
fn back_driven_efficiency_is_what_reaches_the_input() {
    let (code, out, s) = back_driven("0.3");
    assert_eq!(code, 1, "min_mean_efficiency 0.85 fails:\n{out}");
    let p_w = 20.0 * omega(1500.0) / NC;
    let loss_w = s["power_loss_w"]["total"].as_f64().unwrap();
    assert!(loss_w < p_w, "not self-locking: {loss_w} W of {p_w} W");
    let got = s["mean_efficiency"].as_f64().unwrap();
    assert!(close(got, (p_w - loss_w) / p_w, 1e-12), "{got}");
    let p = TORQUE_NMM / NC;
    for (k, (e, t_in)) in floats(&s["efficiency"])
        .iter()
        .zip(floats(&s["input_torque_nm"]))
        .enumerate()
    {
        // η is of order 1: 1e-12 absolute covers the round-off of T_in through N·m.
        let loss = t_in * 1e3 + p;
        assert!((e - (p - loss) / p).abs() < 1e-12, "angle {k}: {e}");
    }
    for what in ["mean efficiency", "rated/min_mean_efficiency"] {
        let line = line_of(&out, what);
        assert!(line.contains("back-driven"), "{line}");
        assert!(!line.contains("SELF-LOCKS"), "{line}");
    }
}

/// At μ 0.9 the mean loss exceeds what the driving output brings: (P − loss)/P < 0 (from the
/// reported watts), the scene self-locks, and the headline, the limit's row (failed) and the
/// review say so, not a bare efficiency; the JSON lists the angles where the input must push
/// (T_in ≥ 0, from its own input torque). 1e-12 relative: as above.
#[test]
fn a_self_locking_scene_says_so() {
    let (code, out, s) = back_driven("0.9");
    assert_eq!(code, 1, "{out}");
    let p_w = 20.0 * omega(1500.0) / NC;
    let loss_w = s["power_loss_w"]["total"].as_f64().unwrap();
    assert!(loss_w > p_w, "{loss_w} W of {p_w} W");
    let got = s["mean_efficiency"].as_f64().unwrap();
    assert!(close(got, (p_w - loss_w) / p_w, 1e-12), "{got}");
    let pushing = floats(&s["input_torque_nm"])
        .iter()
        .filter(|t| **t >= 0.0)
        .count();
    assert_eq!(floats(&s["self_locking_deg"]).len(), pushing);
    for what in ["mean efficiency", "rated/min_mean_efficiency"] {
        let line = line_of(&out, what);
        assert!(line.contains("SELF-LOCKS"), "{line}");
        assert!(
            line.contains(&format!("{pushing} of 108 crank angles")),
            "{line}"
        );
    }
    assert!(line_of(&out, "rated/min_mean_efficiency").contains("FAIL"));
    let review = back_driven_review("0.9");
    assert!(
        review.contains("back-driven: SELF-LOCKS"),
        "the review's table"
    );
}

/// The review's efficiency against torque of a back-driven scene is back-driven too: its torques
/// carry the scene's sign (rising, all negative), and at the scene's own torque (the fraction 1)
/// it is the scene's own mean efficiency, (P − loss)/P from its reported watts (1e-12
/// relative: the same run summed in another order).
#[test]
fn a_back_driven_torque_curve_is_back_driven() {
    let text = back_driven_text("0.3");
    let spec = cycloid::spec::parse("s.yaml", &text).unwrap();
    let scene = &spec.scenes[0];
    let curve = cycloid::engine::torque_curve::torque_curve(&spec, scene)
        .unwrap()
        .unwrap();
    assert!(curve
        .torque_nmm
        .windows(2)
        .all(|w| w[0] < w[1] && w[1] < 0.0));
    let own = curve
        .torque_nmm
        .iter()
        .position(|&t| t == -TORQUE_NMM)
        .unwrap();
    let (_, _, s) = back_driven("0.3");
    let p_w = 20.0 * omega(1500.0) / NC;
    let loss_w = s["power_loss_w"]["total"].as_f64().unwrap();
    let expected = (p_w - loss_w) / p_w;
    let got = curve.mean_efficiency[own];
    assert!(close(got, expected, 1e-12), "{got} against {expected}");
}

/// Every bad value is refused with exit 2 at its key's line and column in the spec.
#[test]
fn bad_values_are_refused_at_their_keys() {
    let cases: &[(&str, &str, &str)] = &[
        // Limits no value of their quantity can meet (η ≤ 1, a loss ≥ 0, above absolute zero).
        (
            "min_mean_efficiency: 0.85",
            "min_mean_efficiency: 1.5",
            "limits.min_mean_efficiency",
        ),
        (
            "max_power_loss_w: 60.0",
            "max_power_loss_w: -3.0",
            "limits.max_power_loss_w",
        ),
        (
            "max_temperature_c: 80.0",
            "max_temperature_c: -300.0",
            "limits.max_temperature_c",
        ),
        ("mu: 0.0025", "mu: 1.0", "reducer.friction.crank_bearing.mu"),
        (
            "mu: 0.0025",
            "mu: -0.1",
            "reducer.friction.crank_bearing.mu",
        ),
        (
            "      bore_radius_mm: 1.5 ",
            "      bore_radius_mm: 3.0 ",
            "reducer.friction.rollers.bore_radius_mm",
        ),
        (
            "      bore_radius_mm: 2.0 ",
            "      bore_radius_mm: 3.5 ",
            "reducer.friction.output_pins.bore_radius_mm",
        ),
        (
            "      bore_radius_mm: 2.0 ",
            "      bore_radius_mm: 0.0 ",
            "reducer.friction.output_pins.bore_radius_mm",
        ),
        (
            "      mode: sleeve",
            "      mode: fixed",
            "reducer.friction.output_pins.bore_radius_mm",
        ),
        (
            "      mode: rotating",
            "      mode: turning",
            "reducer.friction.rollers.mode",
        ),
        (
            "      bore_radius_mm: 1.5        # r_b, the roller's pin\n",
            "",
            "reducer.friction.rollers.mode",
        ),
        (
            "bore_diameter_mm: 20.0",
            "bore_diameter_mm: -20.0",
            "reducer.friction.crank_bearing.bore_diameter_mm",
        ),
        (
            "no_load_torque_nmm: 30.0",
            "no_load_torque_nmm: -1.0",
            "reducer.friction.no_load_torque_nmm",
        ),
        (
            "housing_area_m2: 0.06",
            "housing_area_m2: 0.0",
            "reducer.thermal.housing_area_m2",
        ),
        (
            "heat_transfer_w_per_m2k: 20.0",
            "heat_transfer_w_per_m2k: .nan",
            "reducer.thermal.heat_transfer_w_per_m2k",
        ),
        (
            "ambient_c: 20.0",
            "ambient_c: -300.0",
            "reducer.thermal.ambient_c",
        ),
        ("model: loss", "model: viscous", "reducer.friction.model"),
        // `model: coupled` runs (friction-coupled); its refusal with a compliant bearing is
        // `friction_coupled::coupled_with_a_compliant_bearing_is_refused_at_its_key`.
    ];
    let dir = Scratch::new("friction-bad");
    for (from, to, key) in cases {
        let text = edited(EFF, &[(from, to)]);
        dir.write("s.yaml", &text);
        let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
        assert_eq!(code, 2, "{from} → {to}: {out}{err}");
        // The key's line: its last segment's first occurrence after its parents'.
        let mut at = 0;
        for segment in key.split('.') {
            at += text[at..].find(&format!("{segment}:")).unwrap();
        }
        let line = text[..at].matches('\n').count() + 1;
        let column = at - text[..at].rfind('\n').map_or(0, |n| n + 1) + 1;
        let located = format!("s.yaml:{line}:{column}: invalid value: {key}: ");
        assert!(
            err.starts_with(&located),
            "{from} → {to}: want `{located}`, got {err}"
        );
    }
    let text = EFF.replace("  friction:", "  friction_off:");
    let start = text.find("  friction_off:").unwrap();
    let end = text.find("  thermal:").unwrap();
    let text = format!("{}{}", &text[..start], &text[end..]);
    let text = no_limits(&text);
    dir.write("s.yaml", &text);
    let (code, _, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("scenes[0].effects: `efficiency` needs"),
        "{err}"
    );
}

/// With `reducer.friction` a torsion scene's loop carries it: the terminal's note, the JSON and
/// `--explain` say where its hysteresis comes from, and none claims the frictionless
/// "hysteresis loss 0" (the values themselves: `friction_torsion`).
#[test]
fn a_torsion_loop_with_friction_says_its_hysteresis_comes_from_it() {
    let friction = &EFF[EFF.find("  friction:").unwrap()..EFF.find("  thermal:").unwrap()];
    let torsion = include_str!("../../specs/reducer-torsion.yaml");
    let text = edited(
        &no_limits(torsion),
        &[
            ("modification:", &format!("{}modification:", friction)),
            (
                "{ from_deg: 0.0, to_deg: 36.0, steps: 4 }",
                "{ from_deg: 0.0, to_deg: 36.0, steps: 1 }",
            ),
            ("steps: 1080", "steps: 10"),
        ],
    );
    let dir = Scratch::new("friction-torsion");
    dir.write("s.yaml", &text);
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]).parts();
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("scene `torsion`: hysteresis loss from friction"),
        "{out}"
    );
    assert!(!out.contains("hysteresis loss 0"), "{out}");
    let doc: Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let note = doc["scenes"][0]["hysteresis"].as_str().unwrap().to_string();
    assert!(note.starts_with("hysteresis loss from friction"), "{note}");
    let (_, explain, _) = cycloid(&dir.path, &["check", "s.yaml", "--explain"]).parts();
    assert!(
        explain.contains("hysteresis loss from friction"),
        "{explain}"
    );
}
