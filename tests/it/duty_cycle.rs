//! The duty cycle (issue 31): a scene's bins of torque, speed and time share, each run as the
//! scene loaded at its torque and speed, the crank bearing rated under the whole cycle by ISO
//! 281 with the Palmgren–Miner rule. Every expected value here comes from the ordinary scene
//! path (one scene per bin, its own `bearing_life_h`) combined by hand, from a closed form, or
//! from a property (one bin, identical bins, speed scaling); none from the duty code's output.

use crate::common::{cycloid, cycloid_here, Scratch};
use cycloid::model::quantity::{
    Quantity, BEARING_LIFE, DUTY_LIFE, DUTY_MEAN_EFFICIENCY, EQUIVALENT_TORQUE,
    MAX_CONTACT_PRESSURE, MEAN_EFFICIENCY, MEAN_SPEED, TOTAL_POWER_LOSS,
};
use cycloid::model::results::SceneResult;

/// The shipped spec: the paper's design, C = 12 kN, and a robot joint's four bins (accelerate
/// 30 N·m at 1000 rpm 20 %, run 15 N·m at 2000 rpm 40 %, decelerate −20 N·m at 1000 rpm 20 %,
/// dwell 8 N·m at a standstill 20 %) over the loaded period 0°–108°.
const SHIPPED: &str = include_str!("../../specs/reducer-duty-cycle.yaml");

/// The shipped efficiency spec: the same design with friction (`loss` model), C = 12 kN.
const EFFICIENCY: &str = include_str!("../../specs/reducer-efficiency.yaml");

/// The shipped spec up to its `scenes:` (the design, bearing and modification).
fn design_of(spec: &str) -> &str {
    &spec[..spec.find("scenes:").unwrap()]
}

/// The loaded period of the paper's design with pins, 108°, at 0.1°.
const LOADED_PERIOD: &str = "{ from_deg: 0.0, to_deg: 108.0, steps: 1080 }";

/// A bin (torque N·m, speed rpm, time share).
type Bin = (f64, f64, f64);

/// The shipped spec's bins, as its comments state them.
const ROBOT: [Bin; 4] = [
    (30.0, 1000.0, 0.2),
    (15.0, 2000.0, 0.4),
    (-20.0, 1000.0, 0.2),
    (8.0, 0.0, 0.2),
];

/// A spec of `head`'s design with one duty-cycle scene of `bins` over 0°–108° (1080 steps)
/// computing `effects`.
fn duty_spec(head: &str, bins: &[Bin], effects: &str) -> String {
    let mut text = format!("{head}scenes:\n  - name: duty\n    duty_cycle:\n");
    for (t, n, s) in bins {
        text += &format!(
            "      - {{ output_torque_nm: {t:?}, input_speed_rpm: {n:?}, time_share: {s:?} }}\n"
        );
    }
    text + &format!("    crank: {LOADED_PERIOD}\n    effects: [{effects}]\n")
}

/// A spec of `head`'s design with one ordinary scene at torque `t` and speed `n` (none at a
/// standstill: an ordinary scene's speed is positive) over the same range.
fn ordinary_spec(head: &str, (t, n, _): Bin, effects: &str) -> String {
    let speed = match n > 0.0 {
        true => format!("    input_speed_rpm: {n:?}\n"),
        false => String::new(),
    };
    format!(
        "{head}scenes:\n  - name: one\n    output_torque_nm: {t:?}\n{speed}    crank: \
         {LOADED_PERIOD}\n    effects: [{effects}]\n"
    )
}

/// The first scene's result of `text`, run by `cycloid::check`.
fn run(text: &str) -> SceneResult {
    let spec = cycloid::spec::parse("s.yaml", text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    let run = cycloid::check(
        &spec,
        &cycloid::CheckOptions::default(),
        &cycloid::progress::Silent,
    )
    .unwrap();
    run.results.into_iter().next().unwrap()
}

fn value(q: &Quantity, r: &SceneResult) -> f64 {
    q.scalar(r)
        .unwrap_or_else(|| panic!("{} not computed in `{}`", q.key, r.name))
        .value
}

/// |a/b − 1|.
fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

/// One bin of share 1 is the ordinary scene at its torque and speed: the same bearing life,
/// peak pressure, equivalent torque (|T|) and mean speed. The power mean of one value is that
/// value (×1^(1/p)), so they agree to round-off of the one division by the weight (1e-12).
#[test]
fn one_bin_is_the_ordinary_scene() {
    let head = design_of(SHIPPED);
    let bin = (20.0, 1500.0, 1.0);
    let duty = run(&duty_spec(head, &[bin], "bearing"));
    let one = run(&ordinary_spec(head, bin, "bearing"));
    let (life, ordinary) = (value(&DUTY_LIFE, &duty), value(&BEARING_LIFE, &one));
    assert!(rel(life, ordinary) < 1e-12, "{life} h against {ordinary} h");
    assert!(
        rel(
            value(&MAX_CONTACT_PRESSURE, &duty),
            value(&MAX_CONTACT_PRESSURE, &one)
        ) < 1e-12
    );
    assert!(rel(value(&EQUIVALENT_TORQUE, &duty), 20.0) < 1e-12);
    assert!(rel(value(&MEAN_SPEED, &duty), 1500.0) < 1e-12);
}

/// Hours to failure by Miner's rule from each bin's own ordinary run: an hour of the cycle
/// spends sᵢ hours in bin i, which uses up sᵢ/L10h,i of the bearing (L10h,i the ordinary
/// scene's life at that bin's load and speed); the bearing lasts 1/Σ sᵢ/L10h,i hours. A
/// standstill turns no revolution and uses none. Per disc (`bearing_life` of each disc with
/// several).
fn miner_hours(
    head: &str,
    bins: &[Bin],
    disc: Option<usize>,
    edit: impl Fn(String) -> String,
) -> f64 {
    let damage_per_hour: f64 = bins
        .iter()
        .filter(|b| b.1 > 0.0)
        .map(|&b| {
            let r = run(&edit(ordinary_spec(head, b, "bearing")));
            let own = match disc {
                Some(k) => r.discs[k].bearing_life.unwrap().life_h.unwrap(),
                None => value(&BEARING_LIFE, &r),
            };
            b.2 / own
        })
        .sum();
    1.0 / damage_per_hour
}

/// The shipped spec's duty life against an independent Palmgren–Miner sum of damage fractions
/// over the bins' ordinary runs: the issue asks 0.5 %; both are the same algebra (Σ sᵢ·nᵢ·Pᵢ^p
/// against Σ sᵢ/L10h,i), so they agree to round-off of a few powers and sums (1e-9).
#[test]
fn the_duty_life_is_miners_rule_over_the_bins() {
    let head = design_of(SHIPPED);
    let duty = run(SHIPPED);
    let life = value(&DUTY_LIFE, &duty);
    let miner = miner_hours(head, &ROBOT, None, |t| t);
    eprintln!("shipped duty cycle: duty_life_h {life}, Palmgren–Miner {miner}");
    assert!(
        rel(life, miner) < 1e-9,
        "{life} h against Miner's {miner} h"
    );
}

/// With two discs each disc has its own bearing and its own Miner sum; the reducer's duty
/// life is the shorter (as `bearing_life_h` with several discs). A hole of disc 0 moved by
/// 3 µm makes the discs' loads differ (two identical discs of an even roller count share
/// equally) and the loaded period a whole turn of the disc, 3240°. Round-off as above.
#[test]
fn with_two_discs_each_disc_has_its_miner_life() {
    let head = design_of(SHIPPED).replace(
        "  crank_bearing:",
        "  discs: 2\n  deviations: { holes: [{ index: 2, disc: 0, tangential_mm: 0.003 }] }\n  crank_bearing:",
    );
    let turn = |text: String| {
        text.replace(
            LOADED_PERIOD,
            "{ from_deg: 0.0, to_deg: 3240.0, steps: 3240 }",
        )
    };
    let head = head.as_str();
    let bins = [(25.0, 1200.0, 0.5), (10.0, 3000.0, 0.5)];
    let duty = run(&turn(duty_spec(head, &bins, "bearing")));
    let cycle = duty.duty.as_ref().unwrap();
    assert_eq!(cycle.life.len(), 2);
    let each: Vec<f64> = (0..2)
        .map(|k| miner_hours(head, &bins, Some(k), turn))
        .collect();
    assert!(
        rel(each[0], each[1]) > 1e-3,
        "the discs' lives {each:?} should differ"
    );
    for (k, m) in each.iter().enumerate() {
        let life = cycle.life[k].life_h.unwrap();
        assert!(rel(life, *m) < 1e-9, "disc {k}: {life} h against {m} h");
    }
    let shortest = each[0].min(each[1]);
    assert!(rel(value(&DUTY_LIFE, &duty), shortest) < 1e-9);
}

/// Without friction the loads do not depend on the speed: twice every speed turns the bearing
/// twice as fast through the same loads, so the life in hours halves (exactly, up to the
/// round-off of the divisions, 1e-12), and the equivalent torque stays.
#[test]
fn doubling_every_speed_halves_the_hours() {
    let head = design_of(SHIPPED);
    let twice: Vec<Bin> = ROBOT.iter().map(|&(t, n, s)| (t, 2.0 * n, s)).collect();
    let (slow, fast) = (run(SHIPPED), run(&duty_spec(head, &twice, "bearing")));
    let (a, b) = (value(&DUTY_LIFE, &slow), value(&DUTY_LIFE, &fast));
    assert!(rel(b, a / 2.0) < 1e-12, "{a} h, then {b} h");
    assert!(
        rel(
            value(&EQUIVALENT_TORQUE, &fast),
            value(&EQUIVALENT_TORQUE, &slow)
        ) < 1e-12
    );
    assert!(rel(value(&MEAN_SPEED, &fast), 2.0 * value(&MEAN_SPEED, &slow)) < 1e-12);
}

/// Two identical bins of half the time each are that bin for all the time: the same life,
/// equivalent torque and mean speed (the weights' sums differ from 1 by round-off only).
#[test]
fn two_identical_halves_are_one_bin() {
    let head = design_of(SHIPPED);
    let one = run(&duty_spec(head, &[(25.0, 1200.0, 1.0)], "bearing"));
    let halves = run(&duty_spec(
        head,
        &[(25.0, 1200.0, 0.5), (25.0, 1200.0, 0.5)],
        "bearing",
    ));
    for q in [&DUTY_LIFE, &EQUIVALENT_TORQUE, &MEAN_SPEED] {
        let (a, b) = (value(q, &one), value(q, &halves));
        assert!(rel(a, b) < 1e-12, "{}: {a} against {b}", q.key);
    }
}

/// The equivalent torque on a hand case: 10 N·m at 1000 rpm and 20 N·m at 500 rpm, half the
/// time each: weights sᵢ·nᵢ = 500 and 250, T_eq = ((500·10³ + 250·20³)/750)^(1/3) =
/// (10000/3)^(1/3) = 14.938 N·m (not the time-weighted 15, nor the revolution-weighted
/// arithmetic 13.33); a reversed torque counts by its magnitude; mean speed 750 rpm.
#[test]
fn the_equivalent_torque_is_the_revolution_weighted_root_mean_cube() {
    let head = design_of(SHIPPED);
    let r = run(&duty_spec(
        head,
        &[(10.0, 1000.0, 0.5), (-20.0, 500.0, 0.5)],
        "bearing",
    ));
    let t = value(&EQUIVALENT_TORQUE, &r);
    assert!(rel(t, (10000.0f64 / 3.0).cbrt()) < 1e-12, "{t}");
    assert!(rel(value(&MEAN_SPEED, &r), 750.0) < 1e-12);
}

/// With friction, the cycle's efficiency is its output energy over its input energy: from each
/// bin's ordinary mean efficiency ηᵢ = P_out,i/(P_out,i + lossᵢ) and its output power
/// |Tᵢ|·ωᵢ/nc (∝ |Tᵢ|·nᵢ), η = Σ sᵢ·|Tᵢ|·nᵢ / Σ sᵢ·|Tᵢ|·nᵢ/ηᵢ; a standstill moves no energy.
/// Round-off of the sums (1e-12).
#[test]
fn the_mean_efficiency_is_weighted_by_energy() {
    let head = design_of(EFFICIENCY);
    let bins = [(20.0, 1500.0, 0.5), (5.0, 3000.0, 0.3), (12.0, 0.0, 0.2)];
    let duty = run(&duty_spec(head, &bins, "efficiency"));
    let (mut out, mut input) = (0.0, 0.0);
    for &b in bins.iter().filter(|b| b.1 > 0.0) {
        let eta = value(
            &MEAN_EFFICIENCY,
            &run(&ordinary_spec(head, b, "efficiency")),
        );
        let p = b.2 * b.0.abs() * b.1;
        out += p;
        input += p / eta;
    }
    let eta = value(&DUTY_MEAN_EFFICIENCY, &duty);
    assert!(
        rel(eta, out / input) < 1e-12,
        "{eta} against {}",
        out / input
    );
}

/// The cycle's energy as each bin's power flows (issue 39 §3), worked by hand from each turning
/// bin's ordinary run: its power P = |T|·ω/nc and its mean loss L (`total_power_loss_w`), in W:
/// a forward bin takes P + L in and delivers P; a back-driven bin (T < 0, a deceleration) takes
/// P in at the output and delivers P − L to the input; one whose loss exceeds P self-locks,
/// takes L (P at the output, L − P from the input) and delivers nothing. η = Σ s·D / Σ s·E.
/// At μ 0.3 the back-driven bin runs, at μ 0.9 it self-locks. A bin at a standstill moves no
/// power and has no efficiency (not the run's speed-free 0.87). 1e-12: round-off of the sums.
#[test]
fn the_cycle_efficiency_follows_each_bins_power_flow() {
    let bins = [(20.0, 1500.0, 0.5), (-20.0, 1000.0, 0.3), (12.0, 0.0, 0.2)];
    for (mu, locks) in [("0.3", false), ("0.9", true)] {
        let head = design_of(EFFICIENCY).replace("mu: 0.06 ", &format!("mu: {mu} "));
        let duty = run(&duty_spec(&head, &bins, "efficiency"));
        let (mut delivered, mut entering) = (0.0, 0.0);
        for &b in bins.iter().filter(|b| b.1 > 0.0) {
            let loss = value(
                &TOTAL_POWER_LOSS,
                &run(&ordinary_spec(&head, b, "efficiency")),
            );
            let p = b.0.abs() * (b.1 * std::f64::consts::TAU / 60.0) / 9.0; // N·m × rad/s
            let (e, d) = match (b.0 < 0.0, loss > p) {
                (false, _) => (p + loss, p),
                (true, false) => (p, p - loss),
                (true, true) => (loss, 0.0),
            };
            assert_eq!(
                b.0 < 0.0 && loss > p,
                b.0 < 0.0 && locks,
                "μ {mu}: {loss} W of {p} W"
            );
            delivered += b.2 * d;
            entering += b.2 * e;
        }
        let eta = value(&DUTY_MEAN_EFFICIENCY, &duty);
        let expected = delivered / entering;
        assert!(
            rel(eta, expected) < 1e-12,
            "μ {mu}: {eta} against {expected}"
        );
        let standstill = &duty.duty.as_ref().unwrap().bins[2].result;
        assert!(MEAN_EFFICIENCY.scalar(standstill).is_none());
    }
}

/// (exit code, stdout, stderr) of `cycloid check s.yaml` on `text`.
fn check(dir: &Scratch, text: &str) -> (i32, String, String) {
    dir.write("s.yaml", text);
    cycloid(&dir.path, &["check", "s.yaml"]).parts()
}

/// `limits.min_duty_life_h` passes below the shipped cycle's life and fails (exit 1) above it,
/// its line naming the value; the shipped spec passes `cycloid check`.
#[test]
fn the_duty_life_limit_passes_and_fails() {
    let dir = Scratch::new("duty-limit");
    let (code, out, err) = check(&dir, SHIPPED);
    assert_eq!(code, 0, "{out}{err}");
    let life = value(&DUTY_LIFE, &run(SHIPPED));
    for (limit, expected) in [(0.9 * life, 0), (1.1 * life, 1)] {
        let text = SHIPPED.replace(
            "min_duty_life_h: 5000.0",
            &format!("min_duty_life_h: {limit}"),
        );
        let (code, out, err) = check(&dir, &text);
        assert_eq!(code, expected, "limit {limit}: {out}{err}");
        let line = out
            .lines()
            .find(|l| l.starts_with("robot-joint/min_duty_life_h"))
            .unwrap_or_else(|| panic!("{out}"));
        let verdict = if expected == 0 { "pass" } else { "fail" };
        assert!(line.to_lowercase().contains(verdict), "{line}");
    }
}

/// Bad duty cycles are refused before anything runs, with exit 2 and the key's file:line:column
/// (the shipped spec's scene at line 29; its cycle at line 30, its bins at 31–34, its effects at
/// 37, its limits from 39).
#[test]
fn bad_duty_cycles_are_located() {
    let dir = Scratch::new("duty-errors");
    let bin0 = "{ output_torque_nm: 30.0, input_speed_rpm: 1000.0, time_share: 0.2 }";
    let cases: &[(&str, &str, &str)] = &[
        (
            "time_share: 0.2 }   # accelerate",
            "time_share: -0.2 }   # accelerate",
            "s.yaml:31:60: invalid value: scenes[0].duty_cycle[0].time_share: must be a share of \
             the time in [0, 1], got -0.2",
        ),
        (
            "time_share: 0.4 }",
            "time_share: 0.3 }",
            "s.yaml:30:5: invalid value: scenes[0].duty_cycle: the time shares sum to 0.9, not 1 \
             (within 1e-9)",
        ),
        (
            "input_speed_rpm: 1000.0, time_share: 0.2 }   # accelerate",
            "input_speed_rpm: .nan, time_share: 0.2 }   # accelerate",
            "s.yaml:31:35: invalid value: scenes[0].duty_cycle[0].input_speed_rpm: must be a \
             finite speed of at least 0 rpm (0: a standstill), got NaN",
        ),
        (
            "input_speed_rpm: 1000.0, time_share: 0.2 }   # accelerate",
            "input_speed_rpm: -5.0, time_share: 0.2 }   # accelerate",
            "s.yaml:31:35: invalid value: scenes[0].duty_cycle[0].input_speed_rpm: must be a \
             finite speed of at least 0 rpm (0: a standstill), got -5",
        ),
        (
            "{ output_torque_nm: 30.0,",
            "{ output_torque_nm: .inf,",
            "s.yaml:31:11: invalid value: scenes[0].duty_cycle[0].output_torque_nm: must be a \
             finite number",
        ),
        (
            "  - name: robot-joint\n",
            "  - name: robot-joint\n    output_torque_nm: 10.0\n",
            "s.yaml:30:5: invalid value: scenes[0].output_torque_nm: a scene with `duty_cycle` \
             runs each bin at the bin's own torque and speed",
        ),
        (
            "  - name: robot-joint\n",
            "  - name: robot-joint\n    input_speed_rpm: 100.0\n",
            "s.yaml:30:5: invalid value: scenes[0].input_speed_rpm: a scene with `duty_cycle`",
        ),
        (
            "effects: [bearing]",
            "effects: [clearance]",
            "s.yaml:37:5: invalid value: scenes[0].effects: a duty cycle rates the crank bearing",
        ),
        (
            "min_duty_life_h: 5000.0",
            "min_bearing_life_h: 5000.0",
            "s.yaml:40:3: invalid value: limits.min_bearing_life_h: no scene computes this limit's quantity; \
             a scene with a `duty_cycle` has its own figures",
        ),
    ];
    for (from, to, expected) in cases {
        assert_eq!(SHIPPED.matches(from).count(), 1, "`{from}`");
        let (code, out, err) = check(&dir, &SHIPPED.replacen(from, to, 1));
        assert_eq!(code, 2, "{to}: {out}{err}");
        assert!(err.contains(expected), "{to}:\n{err}\nexpected: {expected}");
        assert!(!err.contains("panicked"), "{err}");
    }
    // An empty cycle, and one at a standstill, at the cycle's key.
    let start = SHIPPED.find("    duty_cycle:").unwrap();
    let end = SHIPPED[start..].find("    # 108 deg").unwrap() + start;
    for (cycle, expected) in [
        (
            "    duty_cycle: []\n".to_string(),
            "s.yaml:30:5: invalid value: scenes[0].duty_cycle: a duty cycle needs at least one bin",
        ),
        (
            format!(
                "    duty_cycle:\n      - {}\n",
                bin0.replace("1000.0", "0.0").replace("0.2 }", "1.0 }")
            ),
            "s.yaml:30:5: invalid value: scenes[0].duty_cycle: no bin turns the crank",
        ),
    ] {
        let text = format!("{}{cycle}{}", &SHIPPED[..start], &SHIPPED[end..]);
        let (code, out, err) = check(&dir, &text);
        assert_eq!(code, 2, "{cycle}: {out}{err}");
        assert!(
            err.contains(expected),
            "{cycle}:\n{err}\nexpected: {expected}"
        );
    }
}

/// The JSON and the design review of the shipped cycle: every number finite (no null, NaN or
/// ∞), one record per bin with its time share as given, revolution shares sᵢ·nᵢ/Σ sⱼ·nⱼ (each
/// from the bins as given) that sum to 1 (1e-12: four rounded quotients) and are 0 at the standstill, the cycle's figures
/// among the scene's keys, and a "Duty cycle" section with one table row per bin.
#[test]
fn the_json_and_the_review_show_every_bin() {
    let dir = Scratch::new("duty-outputs");
    dir.write("s.yaml", SHIPPED);
    let (code, out, err) = cycloid(
        &dir.path,
        &["check", "s.yaml", "--json", "r.json", "--report", "rep"],
    )
    .parts();
    assert_eq!(code, 0, "{out}{err}");
    let json: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    fn finite(v: &serde_json::Value) -> bool {
        match v {
            serde_json::Value::Null => false,
            serde_json::Value::Number(n) => n.as_f64().is_some_and(f64::is_finite),
            serde_json::Value::Array(a) => a.iter().all(finite),
            serde_json::Value::Object(o) => o.values().all(finite),
            _ => true,
        }
    }
    assert!(finite(&json), "a number is not finite or null");
    let scene = &json["scenes"][0];
    for key in [
        "duty_life_h",
        "equivalent_torque_nm",
        "mean_speed_rpm",
        "duty_equivalent_load_n",
    ] {
        assert!(scene[key].is_number(), "{key} missing");
    }
    let bins = scene["duty_cycle"]["bins"].as_array().unwrap();
    assert_eq!(bins.len(), ROBOT.len());
    let mut total = 0.0;
    let revolutions: f64 = ROBOT.iter().map(|&(_, n, s)| s * n).sum();
    for (b, &(t, n, s)) in bins.iter().zip(&ROBOT) {
        assert_eq!(b["output_torque_nm"].as_f64(), Some(t));
        assert_eq!(b["time_share"].as_f64(), Some(s));
        let share = b["revolution_share"].as_f64().unwrap();
        assert_eq!(share == 0.0, n == 0.0, "{b}");
        // The bin's own sᵢ·nᵢ over the cycle's Σ sⱼ·nⱼ, from the spec's inputs: a share by time
        // or by speed alone also sums to 1 (round-off of two products and a quotient: 1e-15).
        assert!((share - s * n / revolutions).abs() < 1e-15, "{b}");
        total += share;
        assert!(b["results"]["bearing_force_n"].is_array());
    }
    assert!((total - 1.0).abs() < 1e-12, "{total}");
    let html = dir.read("rep/index.html");
    let section = &html[html
        .find("id=\"duty-cycle\"")
        .expect("a Duty cycle section")..];
    let table = &section[..section.find("</table>").unwrap()];
    assert_eq!(table.matches("<tr>").count(), 1 + ROBOT.len(), "{table}");
}

/// The unloaded clearance does not depend on the torque or speed a bin changes: every bin of a
/// duty cycle asking for `clearance` carries exactly the clearance of the scene run alone (any
/// torque: the ordinary scene at the first bin's), disc by disc with two discs at their crank
/// phases. Exact equality: the same computation on the same mesh and crank angles.
#[test]
fn every_bin_carries_the_clearance_of_the_scene_alone() {
    let head = design_of(SHIPPED);
    for discs in [1, 2] {
        let head = match discs {
            1 => head.to_string(),
            _ => head.replacen("  face_width_mm:", "  discs: 2\n  face_width_mm:", 1),
        };
        let duty = run(&duty_spec(&head, &ROBOT, "bearing, clearance"));
        let alone = run(&ordinary_spec(&head, ROBOT[0], "bearing, clearance"));
        let of = |r: &SceneResult| -> Vec<_> {
            (r.discs.iter())
                .map(|d| d.clearance.clone().expect("clearance"))
                .collect()
        };
        let expected = of(&alone);
        assert_eq!(expected.len(), discs);
        let bins = &duty.duty.as_ref().expect("duty cycle").bins;
        assert_eq!(bins.len(), ROBOT.len());
        for (j, b) in bins.iter().enumerate() {
            assert!(of(&b.result) == expected, "{discs} discs: bin {j}");
        }
    }
}

/// Counts the crank angles the scenes' phase hears, and the total it announced.
#[derive(Default)]
struct Angles {
    total: std::sync::atomic::AtomicU64,
    done: std::sync::atomic::AtomicU64,
}

struct Heard<'a>(&'a Angles);

impl cycloid::progress::Progress for Heard<'_> {
    fn advance(&self, n: u64) {
        self.0
            .done
            .fetch_add(n, std::sync::atomic::Ordering::Relaxed);
    }
}

impl cycloid::progress::Progress for Angles {
    fn phase(&self, p: &cycloid::progress::Phase) -> Box<dyn cycloid::progress::Progress + '_> {
        if p.what != "solving the scenes" {
            return Box::new(cycloid::progress::Silent);
        }
        self.total
            .fetch_add(p.total, std::sync::atomic::Ordering::Relaxed);
        Box::new(Heard(self))
    }
}

/// The clearance of a duty cycle is computed once, not once per bin: the crank angles swept
/// are those of each disc's clearance once (D·N) and of one loaded sweep per bin (B·N), N the
/// scene's crank angles; per bin it would be B·(D + 1)·N. The scenes' phase announces as many
/// as it hears.
#[test]
fn a_duty_cycle_sweeps_its_clearance_once() {
    let head = design_of(SHIPPED);
    for discs in [1u64, 2] {
        let head = match discs {
            1 => head.to_string(),
            _ => head.replacen("  face_width_mm:", "  discs: 2\n  face_width_mm:", 1),
        };
        let text = duty_spec(&head, &ROBOT, "bearing, clearance");
        let spec = cycloid::spec::parse("s.yaml", &text).unwrap();
        let n = spec.scenes[0].crank_rad.len() as u64;
        let bins = ROBOT.len() as u64;
        let heard = Angles::default();
        cycloid::check(&spec, &cycloid::CheckOptions::default(), &heard).unwrap();
        let done = heard.done.into_inner();
        assert_eq!(done, (discs + bins) * n, "{discs} discs: angles swept");
        assert_eq!(heard.total.into_inner(), done, "{discs} discs: announced");
    }
}

/// A duty cycle runs at its bins' speeds, so `inertia` is open to it as to a scene with its own
/// `input_speed_rpm` (the spec accepts it and the run gives the centripetal force at the fastest
/// bin): `--explain` lists it among what the shipped cycle does not ask for. Before, the plan
/// read the scene's own speed alone and left inertia out of a duty cycle's list.
#[test]
fn the_plan_of_a_duty_cycle_offers_inertia_as_a_scene_at_speed_does() {
    let plan = cycloid_here(&["check", "specs/reducer-duty-cycle.yaml", "--explain"]).stdout;
    assert!(
        plan.contains("  skip    clearance, inertia (not asked for)\n"),
        "{plan}"
    );
    let dir = Scratch::new("duty-inertia");
    let with_inertia = SHIPPED.replace("effects: [bearing]", "effects: [bearing, inertia]");
    let (code, out, err) = check(&dir, &with_inertia);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        out.contains("at 2000 rpm: each disc's centripetal force"),
        "{out}"
    );
}
