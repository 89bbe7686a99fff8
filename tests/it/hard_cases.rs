//! Hard cases (issue 6): every spec under specs/hard/ runs through the CLI and finishes with
//! finite, balanced results or a clear error, never a panic or NaN. Each case then checks the
//! physics it probes through the library (see the comment at the top of each spec).
//!
//! Common to every run that computes: exit code as expected; no null (a non-finite number)
//! anywhere in the scenes of the results JSON; the residual of the paper's Eqs. 12–14
//! (`max_residual`) ≤ 1e-9.

use crate::common;
use cycloid::engine::scene;
use cycloid::equilibrium::angle::solve_angle;
use cycloid::equilibrium::loaded::{AngleSolution, Model};
use cycloid::geometry::first_order;
use cycloid::model::results::{BacklashCurves, SceneResult};
use cycloid::model::GeometryMode;
use cycloid::model::Plan;
use cycloid::spec::{self, Spec};
use serde_json::Value;
use std::f64::consts::{PI, TAU};
use std::path::PathBuf;

const ARCSEC_PER_RAD: f64 = 180.0 * 3600.0 / PI;

/// Every spec under specs/hard/ and its exit code (also in tests/it/specs_exit_codes.rs).
const HARD: &[(&str, i32)] = &[
    ("zero-modification", 0),
    ("nano-modification", 0),
    ("torque-1e-6", 0),
    ("torque-1e5", 1),
    ("torque-1e5-beyond-capacity", 2),
    ("preload-zero-torque", 0),
    ("k1-0.95", 0),
    ("k1-1.0", 2),
    ("undercut-99pct", 0),
    ("undercut-101pct", 2),
    ("rollers-3", 0),
    ("rollers-4", 0),
    ("rollers-80", 0),
    ("hole-clearance", 0),
    ("multi-revolution", 0),
    ("tiny-face-width", 0),
    ("zero-modification-zero-torque", 0),
    ("preload-compliant-bearing", 0),
    ("sharp-root", 0),
];

fn path(case: &str) -> String {
    format!("specs/hard/{case}.yaml")
}

fn load(case: &str) -> Spec {
    spec::load(&path(case)).unwrap_or_else(|e| panic!("{case}: {e}"))
}

/// What `cycloid check specs/hard/CASE.yaml --json ...` did.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    json: Option<Value>,
}

fn check(case: &str) -> Run {
    let dir = common::Scratch::new(&format!("hard-{case}"));
    let json: PathBuf = dir.join("results.json");
    let out = common::cycloid_here(&["check", &path(case), "--json", json.to_str().unwrap()]);
    let text = std::fs::read_to_string(&json).ok();
    Run {
        code: out.code,
        stdout: out.stdout,
        stderr: out.stderr,
        json: text.map(|t| serde_json::from_str(&t).unwrap()),
    }
}

/// Every value in `v` is a finite number, a string, a bool or a container of those: never null
/// (the JSON writer turns a non-finite number into null).
fn assert_no_null(v: &Value, at: &str) {
    match v {
        Value::Null => panic!("null (a non-finite number) at {at}"),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, x)| assert_no_null(x, &format!("{at}[{i}]"))),
        Value::Object(o) => o
            .iter()
            .for_each(|(k, x)| assert_no_null(x, &format!("{at}.{k}"))),
        Value::Number(n) => assert!(n.as_f64().unwrap().is_finite(), "{at}"),
        _ => {}
    }
}

/// Run a case through the CLI: exit code, finite results, balance ≤ 1e-9. Returns the JSON.
fn cli_case(case: &str, code: i32) -> Run {
    let run = check(case);
    assert_eq!(
        run.code,
        Some(code),
        "{case}: exit code\n{}{}",
        run.stdout,
        run.stderr
    );
    assert!(
        !run.stderr.contains("panicked"),
        "{case}: panic\n{}",
        run.stderr
    );
    if code != 2 {
        let json = run.json.as_ref().expect("results JSON written");
        for (i, s) in json["scenes"].as_array().unwrap().iter().enumerate() {
            assert_no_null(s, &format!("{case}: scenes[{i}]"));
            if let Some(r) = s.get("max_residual") {
                let r = r.as_f64().unwrap();
                assert!(r <= 1e-9, "{case}: scene {i} max_residual {r:e}");
            }
        }
        assert!(!run.stdout.contains("NaN"), "{case}:\n{}", run.stdout);
    } else {
        assert!(run.json.is_none(), "{case}: no results on an error");
    }
    run
}

fn run_scene(spec: &Spec, index: usize) -> SceneResult {
    let s = &spec.scenes[index];
    scene::run(spec, s, &Plan::for_scene(s), &Default::default())
        .unwrap_or_else(|e| panic!("{}: {e}", spec.name))
}

/// Roller forces [roller][angle], N.
fn roller_forces(r: &SceneResult) -> &Vec<Vec<f64>> {
    &r.discs[0].loaded.rollers.as_ref().unwrap().force_n
}

fn pin_forces(r: &SceneResult) -> &Vec<Vec<f64>> {
    &r.discs[0].loaded.pins.as_ref().unwrap().force_n
}

fn max_abs(rows: &[Vec<f64>]) -> f64 {
    rows.iter().flatten().fold(0.0, |m, v| m.max(v.abs()))
}

/// Linear-law contact stiffness k = (π/4)·E*·L, N/mm.
fn stiffness(spec: &Spec) -> f64 {
    0.25 * PI * spec.design.contact_modulus_mpa() * spec.design.face_width_mm
}

/// Every spec of the table exists and nothing else is under specs/hard/.
#[test]
fn the_table_lists_every_hard_spec() {
    let mut found: Vec<String> = std::fs::read_dir("specs/hard")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    found.sort();
    let mut listed: Vec<String> = HARD.iter().map(|(c, _)| format!("{c}.yaml")).collect();
    listed.sort();
    assert_eq!(found, listed);
}

/// Zero modification: every roller touches at every angle; under load every roller whose arm
/// is clearly positive (|sin φi| > 0.1, away from the line of centres) carries load and every
/// roller with a clearly negative arm none.
#[test]
fn zero_modification_loads_the_whole_loaded_half() {
    cli_case("zero-modification", 0);
    let spec = load("zero-modification");
    let r = run_scene(&spec, 0);
    let gaps = &r.discs[0].clearance.as_ref().unwrap().gap_mm;
    assert!(max_abs(gaps) <= 1e-12, "gaps {:e}", max_abs(gaps));
    let forces = roller_forces(&r);
    let d = &spec.design;
    let reference = d.eccentricity_mm * d.teeth as f64;
    for (k, &phi) in r.crank_rad.iter().enumerate() {
        for (i, f) in forces.iter().enumerate() {
            let arm = first_order::roller(d, &spec.modification, i, phi).arm_mm;
            if arm > 0.1 * reference {
                assert!(f[k] > 0.0, "roller {i} at {}° idle", phi.to_degrees());
            } else if arm < -0.1 * reference {
                assert_eq!(f[k], 0.0, "roller {i} at {}°", phi.to_degrees());
            }
        }
    }
}

/// Modifications of 1e-9 mm agree with zero modification within a bound derived from the
/// change of the gaps. With δ = max |Δgap| (measured at β = 0; first order it is at most
/// ΔRrp + ΔRp·(1 + K1)/(1 − K1) = 7e-9 mm), the moment at any lag moves by at most
/// k·δ·Σ|l|, while its slope at the answer is at least k·l*², l* the largest positive arm,
/// so |Δβ| ≤ δ·Σ|l|/l*²; each force moves by at most k·(δ + |l|·|Δβ|) (max(0, ·) is
/// 1-Lipschitz). Arms are first order, exact to O(β) ~ 1e-5: a 1 % margin covers them.
#[test]
fn nano_modification_matches_zero_within_the_derived_bound() {
    cli_case("nano-modification", 0);
    let (zero, nano) = (load("zero-modification"), load("nano-modification"));
    let (rz, rn) = (run_scene(&zero, 0), run_scene(&nano, 0));
    let (gz, gn) = (
        &rz.discs[0].clearance.as_ref().unwrap().gap_mm,
        &rn.discs[0].clearance.as_ref().unwrap().gap_mm,
    );
    let delta = gz
        .iter()
        .flatten()
        .zip(gn.iter().flatten())
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let k1 = nano.design.k1();
    let first_order_bound = 2e-9 + 1e-9 * (1.0 + k1) / (1.0 - k1);
    assert!(
        delta > 0.5e-9 && delta <= first_order_bound * (1.0 + 1e-6),
        "max |Δgap| = {delta:e} mm, bound {first_order_bound:e}"
    );
    // The smallest gap is the tip gap, 1 nm, resolved to 1e-15 mm.
    let min = rn.discs[0].clearance.as_ref().unwrap().min.gap_mm;
    assert!((min - 1e-9).abs() <= 1e-15, "min gap {min:e}");
    let k = stiffness(&nano);
    let d = &nano.design;
    let (lz, ln) = (
        &rz.discs[0].loaded.rollers.as_ref().unwrap().lag_rad,
        &rn.discs[0].loaded.rollers.as_ref().unwrap().lag_rad,
    );
    let (fz, fnano) = (roller_forces(&rz), roller_forces(&rn));
    for (j, &phi) in rz.crank_rad.iter().enumerate() {
        let arms: Vec<f64> = (0..d.rollers)
            .map(|i| first_order::roller(d, &nano.modification, i, phi).arm_mm)
            .collect();
        let sum: f64 = arms.iter().map(|l| l.abs()).sum();
        let top = arms.iter().fold(0.0f64, |m, &l| m.max(l));
        let lag_bound = 1.01 * delta * sum / (top * top);
        let dlag = (lz[j] - ln[j]).abs();
        assert!(
            dlag <= lag_bound,
            "{}°: Δβ {dlag:e} > {lag_bound:e}",
            phi.to_degrees()
        );
        for i in 0..d.rollers {
            let bound = 1.01 * k * (delta + arms[i].abs() * lag_bound) + 1e-9;
            let df = (fz[i][j] - fnano[i][j]).abs();
            assert!(
                df <= bound,
                "roller {i} at {}°: ΔF {df:e} N",
                phi.to_degrees()
            );
        }
    }
    // Ideal pins share the torque by their arms alone: the 1e-9 rad change of ψ moves them
    // by ~1e-9 relative.
    let (pz, pn) = (pin_forces(&rz), pin_forces(&rn));
    let scale = max_abs(pz);
    for (a, b) in pz.iter().flatten().zip(pn.iter().flatten()) {
        assert!((a - b).abs() <= 1e-7 * scale);
    }
}

/// 1e-6 N·m: balanced in every geometry, law and bearing; the loaded TE is the unloaded one
/// (the backlash) plus the contact approach, T/(k·l²) ~ 1e-11 rad; forces are linear in T.
#[test]
fn torque_1e_6_is_balanced_and_linear() {
    let run = cli_case("torque-1e-6", 0);
    let json = run.json.unwrap();
    let scenes = json["scenes"].as_array().unwrap();
    for s in &scenes[..4] {
        assert!(s["min_rollers_in_contact"].as_f64().unwrap() >= 1.0);
        assert!(s["max_roller_force_n"].as_f64().unwrap() > 0.0);
    }
    // The limit T → 0 in the closed form: no force at all (the touching contact's round-off
    // force used to leave an unbalanced moment: residual 1), the same TE as at 1e-6 N·m.
    let idle = &scenes[4];
    assert_eq!(idle["name"], "first-order-idle");
    assert_eq!(idle["max_roller_force_n"].as_f64(), Some(0.0));
    assert_eq!(idle["max_residual"].as_f64(), Some(0.0));
    let te = |s: &Value| -> Vec<f64> {
        s["te_arcsec"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    for (a, b) in te(idle).iter().zip(te(&scenes[1])) {
        assert!((a - b).abs() <= 1e-5, "TE {a} vs {b} arcsec");
    }
    let exact = &json["scenes"][0];
    let te = exact["te_arcsec"].as_array().unwrap();
    let backlash = exact["backlash_arcsec"].as_array().unwrap();
    for (t, b) in te.iter().zip(backlash) {
        let (t, b) = (t.as_f64().unwrap(), b.as_f64().unwrap());
        assert!((t - b).abs() <= 1e-5, "TE {t} vs backlash {b} arcsec");
    }
    // Linear in T between torques that close the same contacts, in the exact and the
    // first-order scenes: from 1e-6 to 1e-9 N·m (the contacts' approaches of ~1e-10 mm), and
    // from 1e-100 to 1e-300 N·m, where only the first roller to close within the gaps'
    // round-off carries load (1e-100 N·m once failed where 1e-50 worked: Newton's step
    // cancelled to noise far above the root and only bisection was left).
    let base = load("torque-1e-6");
    for scene in [0, 1] {
        for (from, factor) in [(1.0, 1e-3), (1e-94, 1e-200)] {
            let at = |factor: f64| {
                let mut spec = base.clone();
                spec.scenes[scene].output_torque_nmm *= factor;
                run_scene(&spec, scene)
            };
            let (large, small) = (at(from), at(from * factor));
            for (rows_a, rows_b) in [
                (roller_forces(&large), roller_forces(&small)),
                (pin_forces(&large), pin_forces(&small)),
            ] {
                let scale = max_abs(rows_a);
                assert!(
                    scale > 0.0,
                    "scene {scene} at {from:e} × 1e-6 N·m carries load"
                );
                for (a, b) in rows_a.iter().flatten().zip(rows_b.iter().flatten()) {
                    assert!(
                        (a - b / factor).abs() <= 1e-6 * scale,
                        "scene {scene}, {from:e} × 1e-6 N·m and {factor:e} of it: {a:e} vs {b:e}"
                    );
                }
            }
            let residual = &small.discs[0].loaded.bearing.as_ref().unwrap().residual;
            let worst = residual.iter().cloned().fold(0.0, f64::max);
            assert!(
                worst <= 1e-9,
                "scene {scene} at {from:e} × {factor:e}: residual {worst:e} at {}",
                residual.iter().position(|r| *r == worst).unwrap()
            );
        }
    }
    let mut spec = base.clone();
    let micro = run_scene(&spec, 0);
    spec.scenes[0].output_torque_nmm *= 1e-3;
    let deviation = pin_share_deviation(&spec, &micro, 1e-3);
    assert!(deviation <= 1e-6, "pin share off by {deviation}");
}

/// Ideal pins (no hole clearance) share the torque by their arms alone: F_j = T·a_j/Σ a² over
/// the pins with a positive arm a_j = rw·sin(γj − φ), γj = 2πj/M + ψ, ψ = −φ/nc + β (first
/// order in the output lag βo). Returns the largest deviation from that share, relative to
/// the largest pin force.
fn pin_share_deviation(spec: &Spec, r: &SceneResult, torque_nmm: f64) -> f64 {
    let d = &spec.design;
    let (m, rw, nc) = (d.pins.count, d.pins.circle_radius_mm, d.teeth as f64);
    let forces = pin_forces(r);
    let beta = &r.discs[0].loaded.rollers.as_ref().unwrap().lag_rad;
    let mut worst = 0.0f64;
    for (k, &phi) in r.crank_rad.iter().enumerate() {
        let psi = -phi / nc + beta[k];
        let arms: Vec<f64> = (0..m)
            .map(|j| rw * (TAU * j as f64 / m as f64 + psi - phi).sin())
            .collect();
        let sum: f64 = arms.iter().filter(|a| **a > 0.0).map(|a| a * a).sum();
        for j in 0..m {
            let share = torque_nmm * arms[j].max(0.0) / sum;
            worst = worst.max((forces[j][k] - share).abs());
        }
    }
    worst / max_abs(forces)
}

/// 1e5 N·m on a reducer that can hold it: solved and balanced, the Hertz pressure far beyond
/// steel reported as a number (the limit check fails: exit 1). Torque scaling: the ideal pins'
/// share T·a_j/Σa² holds from 1e-6 N·m (tests above) to 1e5 N·m, to the second order of the
/// output lag (βo ≈ 0.02 rad here: 2 %); the rollers' total force is at least T/l_max.
#[test]
fn torque_1e5_reports_the_pressure_as_a_number() {
    let run = cli_case("torque-1e5", 1);
    let json = run.json.unwrap();
    let check = &json["checks"][0];
    assert_eq!(check["id"], "overload/max_contact_pressure_mpa");
    assert_eq!(check["passed"], false);
    let p = check["value"].as_f64().unwrap();
    assert!(p > 1e4 && p < 1e5, "pressure {p} MPa");
    assert!(run.stdout.contains("FAIL"), "{}", run.stdout);
    let s = &json["scenes"][0];
    assert_eq!(s["max_contact_pressure_mpa"].as_f64(), Some(p));
    assert!(s["min_rollers_in_contact"].as_f64().unwrap() >= 3.0);
    let mut spec = load("torque-1e5");
    let heavy = run_scene(&spec, 0);
    // The share is first order in the pin's travel w ≈ rw·βo against the eccentricity: the
    // gap e − |w − O| has a second-order part |w|²/(2e), relative rw·βo/(2e) to the first.
    let d = &spec.design;
    let lag = &heavy.discs[0].loaded.pins.as_ref().unwrap().output_lag_rad;
    let travel = d.pins.circle_radius_mm * lag.iter().fold(0.0f64, |m, b| m.max(b.abs()));
    let bound = travel / d.eccentricity_mm;
    let deviation = pin_share_deviation(&spec, &heavy, 1e8);
    assert!(
        deviation <= bound && bound < 0.2,
        "pin share off by {deviation} (bound {bound})"
    );
    spec.scenes[0].output_torque_nmm = 1e4; // 10 N·m
    let rated = run_scene(&spec, 0);
    let deviation = pin_share_deviation(&spec, &rated, 1e4);
    assert!(deviation <= 1e-5, "pin share off by {deviation}");
    let l_max = d.eccentricity_mm * d.teeth as f64 / (1.0 - d.k1());
    let forces = roller_forces(&heavy);
    for j in 0..heavy.crank_rad.len() {
        let total: f64 = forces.iter().map(|f| f[j]).sum();
        assert!(total >= 1e8 / l_max, "Σ F {total} N");
    }
}

/// 1e5 N·m on the paper's design: a clear error, naming what happened.
#[test]
fn torque_1e5_beyond_capacity_says_so() {
    let run = cli_case("torque-1e5-beyond-capacity", 2);
    let e = run.stderr.trim();
    assert!(
        e.starts_with(
            "specs/hard/torque-1e5-beyond-capacity.yaml:22:5: computation failed: \
             scenes[0].output_torque_nm: scene `overload`: crank angle 0.0000°"
        ),
        "{e}"
    );
    for part in [
        "the rollers cannot balance an output torque of 100000 N·m",
        "the largest moment found is",
        "is pressed",
        "roller radius 3 mm",
        "beyond what this disc can hold",
    ] {
        assert!(e.contains(part), "missing `{part}` in: {e}");
    }
    // The largest moment the search found is near the true capacity, 8.5e4 N·m.
    let found: f64 = e
        .split("the largest moment found is ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap();
    assert!((7e4..1e5).contains(&found), "{found}");
}

/// Interference at zero torque: forces on both flanks, moments cancelling, pins idle.
#[test]
fn preload_at_zero_torque_loads_both_flanks() {
    cli_case("preload-zero-torque", 0);
    let spec = load("preload-zero-torque");
    let r = run_scene(&spec, 0);
    let forces = roller_forces(&r);
    let d = &spec.design;
    for (k, &phi) in r.crank_rad.iter().enumerate() {
        let (mut driving, mut braking) = (0.0, 0.0);
        for (i, f) in forces.iter().enumerate() {
            let arm = first_order::roller(d, &spec.modification, i, phi).arm_mm;
            assert!(f[k] > 0.0, "roller {i} idle at {}°", phi.to_degrees());
            if arm > 1.0 {
                driving += f[k] * arm;
            } else if arm < -1.0 {
                braking -= f[k] * arm;
            }
        }
        // Both flanks carry half of Σ|F·l| (exactly so in max_residual below; with the
        // first-order arms used here, to the O(ΔRp/e) = 1 % the modification moves them).
        assert!(driving > 0.0 && braking > 0.0);
        assert!((driving - braking).abs() <= 0.05 * (driving + braking));
    }
    assert_eq!(max_abs(pin_forces(&r)), 0.0);
    let b = r.discs[0].loaded.bearing.as_ref().unwrap();
    assert!(b.force_n.iter().all(|f| *f > 1e3));
    assert!(b.residual.iter().all(|x| *x <= 1e-9));
}

/// K1 = 0.95 works; K1 = 1 is an impossible design that names its rule.
#[test]
fn k1_near_one_works_and_k1_of_one_is_refused() {
    let run = cli_case("k1-0.95", 0);
    let s = &run.json.unwrap()["scenes"][0];
    let tip = 0.1593 - 0.125;
    assert!((s["min_clearance_mm"].as_f64().unwrap() - tip).abs() <= 1e-9);
    let run = cli_case("k1-1.0", 2);
    let e = run.stderr.trim();
    assert!(
        e.starts_with("specs/hard/k1-1.0.yaml:")
            && e.contains(
                "impossible design: reducer.eccentricity_mm: short-amplitude coefficient K1"
            )
            && e.contains("= 1.0000 must be below 1"),
        "{e}"
    );
}

/// A roller radius 1 % inside the undercut limit works; 0.1 % beyond it is refused.
#[test]
fn undercut_limit_is_sharp() {
    let spec = load("undercut-99pct");
    let limit = cycloid::geometry::profile::Profile::new(&spec.design, &spec.modification)
        .locus()
        .min_convex_radius()
        .radius_mm;
    let offset = spec.design.roller_radius_mm + spec.modification.equidistant_mm;
    assert!(
        offset < limit && offset > 0.98 * limit,
        "{offset} vs {limit}"
    );
    cli_case("undercut-99pct", 0);
    let run = cli_case("undercut-101pct", 2);
    let e = run.stderr.trim();
    assert!(
        e.starts_with("specs/hard/undercut-101pct.yaml:")
            && e.contains("impossible design: reducer.roller_radius_mm: undercut:")
            && e.contains("7.7000 mm")
            && e.contains("7.6911 mm"),
        "{e}"
    );
}

#[test]
fn four_and_eighty_rollers() {
    let run = cli_case("rollers-4", 0);
    let s = &run.json.unwrap()["scenes"][0];
    assert!(s["min_rollers_in_contact"].as_f64().unwrap() >= 1.0);
    let run = cli_case("rollers-80", 0);
    let s = &run.json.unwrap()["scenes"][0];
    assert!(s["min_rollers_in_contact"].as_f64().unwrap() >= 4.0);
    assert_eq!(s["roller_force_n"].as_array().unwrap().len(), 80);
}

/// 3 rollers and 2 pins: the torsion loop crosses a dead band of ~0.21 rad, beyond the
/// 0.164 rad that the bracket search used to reach from the far side of it (its doubling steps
/// of 1.6e-4·(2ⁿ − 1) rad stopped short of the 0.3 rad range), where the solve at +0.5 N·m
/// said the rollers could not balance it. Now every locked angle solves, and the dead band is
/// the clearance effect's unloaded lost motion there: two independent computations (the
/// closing lags of the unloaded mesh, the loaded solves at ±1e-6·Trated) that differ by the
/// elastic twist over ±1e-6·Trated = ±5e-3 N·mm. At 0°, the worst angle, one roller closes,
/// with the arm l = e·nc·sin 120°/S = 1.64 mm (K1 = 0.1), compliance 1/(k·l²) = 5.2e-7
/// rad/(N·mm) (k = 7.11e5 N/mm), and one pin bears, its arm only rw·sin β = 12·sin 0.104 =
/// 1.25 mm there (the pin pattern's arms vanish at 0°), 9.0e-7 rad/(N·mm): the twist on both
/// sides is 2·5e-3·1.4e-6 = 1.4e-8 rad = 2.9e-3 arcsec (measured 3.3e-3); 1e-2 arcsec holds
/// it, far inside the figure's 0.01 arcmin = 0.6 arcsec.
#[test]
fn three_rollers_cross_their_dead_band_in_torsion() {
    let (figures, _) = dead_band_is_the_unloaded_lost_motion("rollers-3", 1e-2);
    assert!(figures[0] > 0.164, "{figures:?}");
}

/// A root sharper than the modification (3 teeth, K1 = 0.88: the locus's radius of curvature
/// at the root 0.11 mm, the roller centre 0.39 mm from the flank): at crank 0° roller 0 is as
/// near both sides of its tooth space and closes both ways at the same lag. The mesh is then
/// mirror-symmetric about the line of centres, so the backlash is the same both ways (to the
/// closing lags' stopping rule, 1e-12 rad); and the dead band of the loaded solves, which find
/// every contact at each lag, is the unloaded lost motion that counts every roller both ways
/// (12,481 arcsec; counted only the way its nearest flank closes, 14,547). The two differ by
/// the elastic twist over ±1e-6·Trated = ±5e-4 N·mm. At 0°, the worst angle, the roller closes
/// with an arm of 12.6 to 13.2 mm, 1/(k·l²) ≤ 8.9e-9 rad/(N·mm) (k = 7.11e5 N/mm), and a pin bears with
/// the arm rw·sin β = 7·sin 0.0303 = 0.212 mm (the two pins' arms vanish at 0°), 3.1e-5
/// rad/(N·mm): 2·5e-4·3.1e-5 = 3.1e-8 rad = 6.5e-3 arcsec (measured 6.47e-3); 1e-2 arcsec
/// holds it.
#[test]
fn a_roller_at_a_sharp_root_closes_both_ways() {
    let (_, backlash) = dead_band_is_the_unloaded_lost_motion("sharp-root", 1e-2);
    let (forward, reverse) = (backlash.forward_rad[0], backlash.reverse_rad[0]);
    assert!(
        (forward - reverse).abs() <= 1e-12,
        "{forward} vs {reverse} rad at 0°"
    );
}

/// Runs `case` (exit 0) and its second scene, a torsion loop, and checks that its dead band at
/// each locked angle is the clearance effect's unloaded lost motion there within `tol_arcsec`;
/// the dead bands (rad) and the unloaded backlash.
fn dead_band_is_the_unloaded_lost_motion(
    case: &str,
    tol_arcsec: f64,
) -> (Vec<f64>, BacklashCurves) {
    cli_case(case, 0);
    let spec = load(case);
    let s = &spec.scenes[1];
    let writes = scene::Writes {
        json: true,
        report: false,
    };
    let plan = scene::plan(&spec, s, writes);
    let r = scene::run(&spec, s, &plan, &Default::default()).unwrap();
    let backlash = (r.discs[0].clearance.as_ref())
        .and_then(|c| c.backlash.clone())
        .unwrap();
    let figures = &r.reducer.torsion.as_ref().unwrap().figures;
    for (f, l) in figures.iter().zip(&backlash.lost_motion_rad) {
        let (band, unloaded) = (f.backlash_rad * ARCSEC_PER_RAD, l * ARCSEC_PER_RAD);
        assert!(
            (band - unloaded).abs() <= tol_arcsec,
            "{case}: {band} vs {unloaded} arcsec"
        );
    }
    (figures.iter().map(|f| f.backlash_rad).collect(), backlash)
}

/// Hole clearance larger than the roller clearance: the output takes up its free play first
/// (βo·rw ≥ c), fewer pins bear than with ideal holes, the pin with the largest arm bears
/// most, and as the torque grows the pins come in one by one.
#[test]
fn hole_clearance_loads_pins_one_by_one() {
    cli_case("hole-clearance", 0);
    let spec = load("hole-clearance");
    let c = spec.design.pins.hole_clearance_mm;
    let rw = spec.design.pins.circle_radius_mm;
    let loose = run_scene(&spec, 0);
    let mut ideal_spec = spec.clone();
    ideal_spec.design.pins.hole_clearance_mm = 0.0;
    let ideal = run_scene(&ideal_spec, 0);
    let (pl, pi) = (pin_forces(&loose), pin_forces(&ideal));
    let lag = &loose.discs[0].loaded.pins.as_ref().unwrap().output_lag_rad;
    let beta = &loose.discs[0].loaded.rollers.as_ref().unwrap().lag_rad;
    let (m, nc) = (spec.design.pins.count, spec.design.teeth as f64);
    for (k, &phi) in loose.crank_rad.iter().enumerate() {
        assert!(lag[k] * rw >= c, "βo·rw = {} < c", lag[k] * rw);
        let count = |rows: &Vec<Vec<f64>>| rows.iter().filter(|f| f[k] > 0.0).count();
        assert!(count(pl) >= 1 && count(pl) <= count(pi));
        let psi = -phi / nc + beta[k];
        let arm = |j: usize| rw * (TAU * j as f64 / m as f64 + psi - phi).sin();
        let most = (0..m)
            .max_by(|&a, &b| pl[a][k].total_cmp(&pl[b][k]))
            .unwrap();
        let longest = (0..m).max_by(|&a, &b| arm(a).total_cmp(&arm(b))).unwrap();
        assert_eq!(most, longest, "at {}°", phi.to_degrees());
    }
    // One angle, torque from 1 mN·m up: loaded pins never decrease, starting with one.
    let scene = &spec.scenes[0];
    let mut model = Model::new(
        &spec.design,
        &spec.modification,
        scene,
        &cycloid::model::Plan::of("rated", &[cycloid::model::Effect::Bearing]),
    );
    let mut counts = Vec::new();
    for t in [1.0, 1e2, 1e3, 1e4, 1e5, 1e6, 3e6, 1e7] {
        model.torque_nmm = t;
        let sol = solve_angle(&model, 0.3, &AngleSolution::default()).unwrap();
        assert!(sol.residual.unwrap() <= 1e-9);
        counts.push(sol.pins.iter().filter(|p| p.force_n > 0.0).count());
    }
    assert_eq!(counts[0], 1, "{counts:?}");
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    assert!(counts[counts.len() - 1] >= 3, "{counts:?}");
}

/// A crank range from mid-period over three revolutions: every curve repeats with the loaded
/// period, and the samples equal a sweep from 0° at the same angles.
#[test]
fn multi_revolution_curves_repeat_with_the_loaded_period() {
    let run = cli_case("multi-revolution", 0);
    let json = run.json.unwrap();
    let s = &json["scenes"][0];
    let spec = load("multi-revolution");
    let period = spec.design.loaded_period_rad(true, false);
    assert!((period.to_degrees() - 108.0).abs() < 1e-9);
    let step = spec.scenes[0].crank_rad[1] - spec.scenes[0].crank_rad[0];
    let shift = (period / step).round() as usize;
    assert_eq!(shift, 216);
    let curves = |key: &str| -> Vec<Vec<f64>> {
        let v = &s[key];
        let row = |r: &Value| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        match v.as_array().unwrap().first() {
            Some(Value::Array(_)) => v.as_array().unwrap().iter().map(row).collect(),
            _ => vec![row(v)],
        }
    };
    // Per-angle curves repeat exactly; per-roller and per-pin curves with their index moved by
    // the number of mesh periods (roller i + 3 in roller i's place) and of pin periods (pin
    // j + 2 in pin j's place) in one loaded period.
    let d = &spec.design;
    let roller_shift = (period / d.mesh_period_rad()).round() as usize;
    let pin_shift = (period / d.pin_period_rad()).round() as usize;
    assert_eq!((roller_shift, pin_shift), (3, 2));
    for (key, moved) in [
        ("clearance_mm", roller_shift),
        ("lag_arcsec", 0),
        ("te_arcsec", 0),
        ("ratio", 0),
        ("roller_force_n", roller_shift),
        ("contact_pressure_mpa", roller_shift),
        ("output_lag_arcsec", 0),
        ("pin_force_n", pin_shift),
        ("bearing_force_n", 0),
        ("bearing_angle_deg", 0),
    ] {
        let rows = curves(key);
        let scale = rows.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for (i, row) in rows.iter().enumerate() {
            assert_eq!(row.len(), 2160);
            let later = &rows[(i + moved) % rows.len()];
            for k in 0..row.len() - shift {
                let (a, b) = (row[k], later[k + shift]);
                assert!(
                    (a - b).abs() <= 1e-8 * scale + 1e-12,
                    "{key}[{i}]: sample {k} {a} vs {b}"
                );
            }
        }
    }
    // The same angles from a sweep that starts at 0°: 19.5° + 0.5°·k is sample 39 + k of the
    // base period, w = (39 + k)/216 periods later, where roller i sits in roller i − 3w's place.
    let mut from_zero = spec.clone();
    from_zero.scenes[0].crank_rad = (0..216).map(|k| (0.5 * k as f64).to_radians()).collect();
    let base = run_scene(&from_zero, 0);
    let turns = run_scene(&spec, 0);
    let te = |r: &SceneResult| r.reducer.transmission.as_ref().unwrap().te_rad.clone();
    let (tb, tt) = (te(&base), te(&turns));
    let (fb, ft) = (roller_forces(&base), roller_forces(&turns));
    let scale = max_abs(fb);
    let n = fb.len();
    for k in 0..2160 {
        let (j, w) = ((39 + k) % 216, (39 + k) / 216);
        assert!(
            (tb[j] - tt[k]).abs() * ARCSEC_PER_RAD <= 1e-6,
            "TE at sample {k}"
        );
        for (i, row) in ft.iter().enumerate() {
            let b = (i + n * w - (roller_shift * w) % n) % n;
            assert!(
                (fb[b][j] - row[k]).abs() <= 1e-8 * scale,
                "roller {i} sample {k}"
            );
        }
    }
}

/// A 1 µm face at the rated torque per width: the same lags, forces ×1e-3/8, the same
/// pressures as the paper's 8 mm face at 10 N·m. At the same torque, forces of an unmodified
/// profile (shared by arms alone, F = T·l/Σl²) are the same and pressures scale 1/sqrt(L).
#[test]
fn tiny_face_width_scales_forces_and_pressures() {
    cli_case("tiny-face-width", 0);
    let tiny = load("tiny-face-width");
    let mut wide = tiny.clone();
    wide.design.face_width_mm = 8.0;
    wide.scenes[0].output_torque_nmm = 1e4;
    let ratio = tiny.design.face_width_mm / wide.design.face_width_mm;
    let (rt, rw) = (run_scene(&tiny, 0), run_scene(&wide, 0));
    let lag = |r: &SceneResult| r.discs[0].loaded.rollers.as_ref().unwrap().lag_rad.clone();
    for (a, b) in lag(&rt).iter().zip(&lag(&rw)) {
        assert!((a - b).abs() <= 1e-9 * b.abs(), "β {a} vs {b}");
    }
    let scale = max_abs(roller_forces(&rw));
    for (a, b) in roller_forces(&rt)
        .iter()
        .flatten()
        .zip(roller_forces(&rw).iter().flatten())
    {
        assert!(
            (a - ratio * b).abs() <= 1e-8 * ratio * scale,
            "{a} vs {ratio} × {b}"
        );
    }
    let pressure = |r: &SceneResult| {
        r.discs[0]
            .loaded
            .rollers
            .as_ref()
            .unwrap()
            .pressure_mpa
            .clone()
    };
    let (pt, pw) = (pressure(&rt), pressure(&rw));
    let scale = max_abs(&pw);
    for (a, b) in pt.iter().flatten().zip(pw.iter().flatten()) {
        assert!((a - b).abs() <= 1e-6 * scale, "p {a} vs {b}");
    }
    // Same torque (10 mN·m: lags of 1.5e-4 rad even on the 1 µm face), unmodified profile.
    // First order the arms do not move with the lag: the forces agree to round-off. Exact, the
    // gaps carry a second-order term c·β² besides −l·β, whose force k·c·β² grows as 1/L: the
    // roller on the line of centres (l ≈ 0) picks up 0.5 % of the largest force on the 1 µm
    // face (1 % allowed). The pressures follow sqrt(F/L) up to the change of the flank
    // curvature at contact points 1.5e-4 rad apart (0.14 % seen, 1 % allowed).
    for (geometry, tolerance) in [
        (GeometryMode::FirstOrder, 1e-9),
        (GeometryMode::Exact, 1e-2),
    ] {
        let at = |width: f64| {
            let mut s = tiny.clone();
            s.design.face_width_mm = width;
            s.modification = Default::default();
            s.scenes[0].output_torque_nmm = 10.0;
            s.scenes[0].geometry = geometry;
            s.scenes[0].crank_rad.truncate(36);
            run_scene(&s, 0)
        };
        let (narrow, broad) = (at(1e-3), at(8.0));
        let (fn_, fb) = (roller_forces(&narrow), roller_forces(&broad));
        let scale = max_abs(fb);
        let (pn, pb) = (pressure(&narrow), pressure(&broad));
        for i in 0..fb.len() {
            for k in 0..fb[i].len() {
                let (a, b) = (fn_[i][k], fb[i][k]);
                assert!(
                    (a - b).abs() <= tolerance * scale,
                    "{geometry:?}: F {a} vs {b}"
                );
                if b > 1e-3 * scale {
                    // p = sqrt(F·E*/(π·L·R*)): at equal forces the ratio is sqrt(8000).
                    let r = pn[i][k] / pb[i][k] / (a / b / ratio).sqrt();
                    assert!((r - 1.0).abs() <= 1e-2, "{geometry:?}: p ratio {r}");
                }
            }
        }
    }
}

/// Found while probing: zero modification at zero torque reports lag 0 and no force.
#[test]
fn zero_modification_at_zero_torque_is_at_rest() {
    let run = cli_case("zero-modification-zero-torque", 0);
    let s = &run.json.unwrap()["scenes"][0];
    for key in [
        "max_roller_force_n",
        "max_pin_force_n",
        "max_bearing_force_n",
    ] {
        assert_eq!(s[key].as_f64(), Some(0.0), "{key}");
    }
    assert!(s["lag_arcsec"]
        .as_array()
        .unwrap()
        .iter()
        .all(|v| v.as_f64().unwrap().abs() <= 1e-12));
}

/// Found while probing: a preloaded disc on a soft compliant bearing converges.
#[test]
fn preload_on_a_compliant_bearing_converges() {
    let run = cli_case("preload-compliant-bearing", 0);
    let s = &run.json.unwrap()["scenes"][0];
    assert_eq!(s["min_rollers_in_contact"].as_f64(), Some(10.0));
    assert!(s["bearing_deflection_mm"]
        .as_array()
        .unwrap()
        .iter()
        .all(|v| v.as_f64().unwrap() > 0.0));
}
