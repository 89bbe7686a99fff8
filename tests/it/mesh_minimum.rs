//! The smallest gap over the whole mesh (`geometry::mesh_minimum`), a property of the geometry
//! that `check` computes over the whole crank period of the gaps whatever angles a scene
//! samples (issue 26: a disc with a form error was checked over the scene's 36° alone).
//!
//! Checked against what does not use the code under test: the period against the gaps of every
//! roller evaluated from scratch at φ and φ + T (the set repeats at T and at no shorter whole
//! number of mesh periods); the reported minimum against the true one, found by a sweep eight
//! times finer than the sampling and a golden-section search on the roller's own gap; the
//! reported place against the gap evaluated there. The error bound h²·M/8 the run states must
//! contain the difference: 0 ≤ reported − true ≤ bound.

use crate::common::*;
use cycloid::geometry::clearance::{self, Mesh, Pose, Scope};
use cycloid::model::results::{DiscResult, MinCoverage, SampledPeriod, SceneResult};
use cycloid::progress::Silent;
use cycloid::spec::Spec;
use cycloid::units;
use std::f64::consts::TAU;

/// Gaps formed two ways agree to this (a few ulp of Rp ≈ 30 mm is ~1e-14 mm; 1e-12 leaves room
/// for the closest point's Newton stopping rule).
const SAME_MM: f64 = 1e-12;

/// The paper's optimum with `deviations` (YAML lines under `reducer.deviations:`) and one
/// clearance scene per `(name, from, to, steps)`.
fn spec(deviations: &str, scenes: &[(&str, f64, f64, usize)]) -> Spec {
    let items: String = scenes
        .iter()
        .map(|(name, from, to, steps)| {
            format!(
                "  - name: {name}\n    crank: {{ from_deg: {from:?}, to_deg: {to:?}, steps: {steps} }}\n    effects: [clearance]\n"
            )
        })
        .collect();
    let mut text = PaperSpec::new().scenes(&items);
    if !deviations.is_empty() {
        text = text.edit(
            "  material:",
            &format!("  deviations:\n{deviations}  material:"),
        );
    }
    text.with("limits:\n  min_clearance_mm: 0.015\n")
        .parse("mesh-minimum.yaml")
}

/// A form error of order 2 (4 µm): 2 shares no factor with 9 teeth, so the disc is itself again
/// only after 9 teeth and the smallest gap repeats after 9 mesh periods (324°).
const FORM_2: &str = "    form: [{ order: 2, cos_mm: 0.004 }]\n";

/// Roller 6 pushed in by 4 µm: the rollers are no longer alike.
const ROLLER_6: &str = "    rollers: [{ index: 6, radial_mm: -0.004 }]\n";

fn run(spec: &Spec) -> Vec<SceneResult> {
    let run = cycloid::check(spec, &Default::default(), &Silent).unwrap();
    run.results
}

/// The period the run sampled, with its step and bound, of the disc `what` names.
fn sampled(r: &DiscResult, what: &str) -> SampledPeriod {
    match r.clearance.as_ref().unwrap().coverage {
        MinCoverage::Period(p) => p,
        other => panic!("{what}: the smallest gap over {other:?}"),
    }
}

/// The gaps of every roller at crank φ from scratch, sorted: the set the period repeats.
fn gap_set(mesh: &Mesh, phi: f64) -> Vec<f64> {
    let mut gaps: Vec<f64> = (0..mesh.rollers)
        .map(|i| mesh.roller_gap(i, &Pose::ideal(phi), None).unwrap().gap_mm)
        .collect();
    gaps.sort_by(f64::total_cmp);
    gaps
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The period in mesh periods, from the definition: the set of gaps at φ + T equals that at φ
/// (at six crank angles), and for each prime factor p of the count, T/p does not. Paper's
/// design (np 10, nc 9): a form of order 3 repeats after 3 teeth (108°), of order 2 after 9
/// (324°), of orders 3 and 6 after 3; rollers not alike come back after a turn (360°), with a
/// form of order 2 after lcm(10, 9) = 90 mesh periods (3240°), of order 3 after 30 (1080°).
#[test]
fn the_period_is_where_the_set_of_gaps_repeats() {
    let cases = [
        ("", 1),
        ("    form: [{ order: 3, cos_mm: 0.004 }]\n", 3),
        (FORM_2, 9),
        (
            "    form: [{ order: 3, cos_mm: 0.002 }, { order: 6, sin_mm: 0.003 }]\n",
            3,
        ),
        (ROLLER_6, 10),
        (&format!("{ROLLER_6}{FORM_2}"), 90),
        (
            &format!("{ROLLER_6}    form: [{{ order: 3, cos_mm: 0.004 }}]\n"),
            30,
        ),
        (
            "    eccentricity_mm: 0.003\n    equidistant_mm: -0.002\n",
            1,
        ),
    ];
    for (deviations, periods) in cases {
        let s = spec(deviations, &[("mesh", 0.0, 36.0, 36)]);
        let d = &s.design;
        assert_eq!(d.clearance_periods(), periods, "{deviations}");
        let mesh = Mesh::new(d, &s.modification);
        let mesh_period = TAU / d.rollers as f64;
        let differs_after = |q: usize| {
            (0..6)
                .map(|k| {
                    let phi = 0.37 + 1.1 * k as f64;
                    let shifted = gap_set(&mesh, phi + q as f64 * mesh_period);
                    largest_difference(&gap_set(&mesh, phi), &shifted)
                })
                .fold(0.0, f64::max)
        };
        // 1e-11 mm: the same set formed at crank angles up to 3240° apart (round-off of
        // angles of ~57 rad); a broken symmetry moves gaps by micrometres.
        assert!(differs_after(periods) < 1e-11, "{deviations}");
        for p in [2, 3, 5] {
            if periods % p == 0 {
                assert!(differs_after(periods / p) > 1e-7, "{deviations}: T/{p}");
            }
        }
    }
}

/// The true smallest gap over `period_rad` from crank 0, independently of `mesh_minimum`: a
/// sweep at `step_rad`, then a golden-section search on the lowest roller's own gap over ±step
/// around its lowest sample. Returns (gap, roller, crank).
fn true_minimum(mesh: &Mesh, period_rad: f64, step_rad: f64) -> (f64, usize, f64) {
    let n = (period_rad / step_rad).round() as usize;
    let mut best = (f64::INFINITY, 0, 0.0);
    for block in (0..n).collect::<Vec<_>>().chunks(8192) {
        let crank: Vec<f64> = block.iter().map(|&k| k as f64 * step_rad).collect();
        let s = clearance::sweep(mesh, &crank, Scope::Gaps, &Silent).unwrap();
        for (i, gaps) in s.gap_mm.iter().enumerate() {
            for (k, &g) in gaps.iter().enumerate() {
                if g < best.0 {
                    best = (g, i, crank[k]);
                }
            }
        }
    }
    let (_, roller, at) = best;
    let gap = |phi: f64| {
        mesh.roller_gap(roller, &Pose::ideal(phi), None)
            .unwrap()
            .gap_mm
    };
    let phi = golden_section_min(gap, at - step_rad, at + step_rad);
    (gap(phi).min(best.0), roller, phi)
}

/// The reported minimum of `r` lies in [true, true + bound], and is the gap of the reported
/// roller at the reported crank angle (plus the disc's phase `shift_rad`); `what` names the
/// disc in messages.
fn assert_bounded(mesh: &Mesh, (r, what): (&DiscResult, &str), shift_rad: f64) -> f64 {
    let c = r.clearance.as_ref().unwrap();
    let p = sampled(r, what);
    let (truth, _, _) = true_minimum(mesh, p.period_rad, p.step_rad / 8.0);
    let at = mesh
        .roller_gap(
            c.min.roller,
            &Pose::ideal(c.min.crank_rad + shift_rad),
            None,
        )
        .unwrap()
        .gap_mm;
    assert!(
        (at - c.min.gap_mm).abs() < SAME_MM,
        "{what}: {at} at the place"
    );
    let above = c.min.gap_mm - truth;
    eprintln!(
        "{what}: {:.6} µm, {:.3e} µm above the true minimum, bound {:.3e} µm",
        units::um(c.min.gap_mm),
        units::um(above),
        units::um(p.error_bound_mm)
    );
    assert!(
        (-SAME_MM..=p.error_bound_mm + SAME_MM).contains(&above),
        "{what}: reported {} true {truth}: {above} mm above, bound {}",
        c.min.gap_mm,
        p.error_bound_mm
    );
    above
}

/// The case: a form error on a scene over one mesh period. Before, `check` reported the
/// smallest gap of the scene's 36° (34.68 µm: the tips the form leaves thicker there); the
/// disc's thinnest place (30.54 µm, on the tip that w(t) = 4 µm·cos 2t thins most) lies
/// further round, at crank 72.75° of the 324° period. Every scene of the design, of 360, 8 or
/// 4 crank angles, now reports it, within its stated bound of the true minimum, the bound
/// within the 0.1 µm tolerance.
#[test]
fn a_form_error_is_checked_over_its_whole_period_whatever_the_scene_samples() {
    let s = spec(
        FORM_2,
        &[
            ("mesh", 0.0, 36.0, 360),
            ("eight", 0.0, 36.0, 8),
            ("torsion", 0.0, 36.0, 4),
        ],
    );
    let mesh = Mesh::new(&s.design, &s.modification);
    let results = run(&s);
    for r in &results {
        let p = sampled(&r.discs[0], &r.name);
        assert!(
            (units::deg(p.period_rad) - 324.0).abs() < 1e-9,
            "{}",
            r.name
        );
        assert!(p.error_bound_mm <= 1e-4, "{}: {}", r.name, p.error_bound_mm);
        assert_bounded(&mesh, (&r.discs[0], &r.name), 0.0);
    }
    let c = results[0].discs[0].clearance.as_ref().unwrap();
    let scene_only = c
        .gap_mm
        .iter()
        .flatten()
        .copied()
        .fold(f64::INFINITY, f64::min);
    // Micrometres apart: the scene's own angles miss the thinnest tooth by 4 µm.
    assert!(
        scene_only - c.min.gap_mm > 4e-3,
        "{scene_only} vs {}",
        c.min.gap_mm
    );
    assert!(c.min.crank_rad > units::rad(36.0));
}

/// Rollers as built and a form error: the set of gaps repeats only after 3240°, which a scene
/// of four angles never sees; the run samples all of it.
#[test]
fn rollers_as_built_with_a_form_error_are_checked_over_3240_degrees() {
    let s = spec(&format!("{ROLLER_6}{FORM_2}"), &[("torsion", 0.0, 36.0, 4)]);
    let mesh = Mesh::new(&s.design, &s.modification);
    let r = &run(&s)[0];
    assert!((units::deg(sampled(&r.discs[0], &r.name).period_rad) - 3240.0).abs() < 1e-9);
    assert_bounded(&mesh, (&r.discs[0], &r.name), 0.0);
}

/// Two discs, 180° apart: each samples the same period (once for both) and reports the same
/// smallest gap, at its own crank angle in [0°, 324°) and its own roller — the gap of that
/// roller at that angle plus the disc's phase, which for disc 1 is the sampled place brought
/// back a period, the roller renumbered (`MeshMinimum::in_period`).
#[test]
fn several_discs_report_the_smallest_gap_each_at_its_own_place() {
    let text = PaperSpec::new()
        .edit("  material:", &format!("  deviations:\n{FORM_2}  material:"))
        .edit("  rollers: 10 ", "  discs: 2\n  rollers: 10 ")
        .scenes("  - name: torsion\n    crank: { from_deg: 0.0, to_deg: 36.0, steps: 4 }\n    effects: [clearance]\n");
    let s = text.parse("two.yaml");
    let mesh = Mesh::new(&s.design, &s.modification);
    let r = &run(&s)[0];
    assert_eq!(r.discs.len(), 2);
    let mut values = Vec::new();
    for (k, disc) in r.discs.iter().enumerate() {
        let c = disc.clearance.as_ref().unwrap();
        assert!(
            (0.0..units::rad(324.0)).contains(&c.min.crank_rad),
            "disc {k}"
        );
        let what = format!("{} disc {k}", r.name);
        values.push(assert_bounded(
            &mesh,
            (disc, &what),
            s.design.disc_phase_rad(k),
        ));
    }
    assert_eq!(values[0], values[1]);
}

/// The bound holds beyond the paper's design: the hard cases' designs (K1 = 0.95, a roller at
/// 98.9 % of the undercut limit, 4 and 80 rollers, preload), the paper's negative case
/// (interference, its minimum at mid-flank), and designs whose minimum falls between the
/// samples (the profile turned by 0.013°, a roller moved along its circle, two form terms),
/// each sampled from a scene of four angles.
#[test]
fn the_error_bound_holds_on_hard_designs() {
    let mut designs: Vec<(String, Spec)> = [
        "k1-0.95",
        "undercut-99pct",
        "rollers-4",
        "rollers-80",
        "zero-modification",
        "preload-zero-torque",
    ]
    .iter()
    .map(|name| {
        let path = format!("{}/specs/hard/{name}.yaml", env!("CARGO_MANIFEST_DIR"));
        (name.to_string(), cycloid::spec::load(&path).unwrap())
    })
    .collect();
    designs.push(("negative".into(), paper_spec(-0.15, -0.135)));
    let turned = PaperSpec::new().edit("rotation_deg: 0.0 ", "rotation_deg: 0.013 ");
    designs.push(("turned".into(), turned.parse("turned.yaml")));
    for (name, deviations) in [
        (
            "roller moved",
            "    rollers: [{ index: 3, tangential_mm: 0.005 }]\n",
        ),
        (
            "two form terms",
            "    form: [{ order: 2, cos_mm: 0.003 }, { order: 5, sin_mm: -0.002 }]\n",
        ),
    ] {
        designs.push((name.into(), spec(deviations, &[("mesh", 0.0, 36.0, 4)])));
    }
    for (name, mut s) in designs {
        let mut scene = s.scenes[0].clone();
        let (from, to) = (scene.crank_from_deg, scene.crank_to_deg);
        scene.crank_rad = (0..4)
            .map(|k| units::rad(from + (to - from) * k as f64 / 4.0))
            .collect();
        scene.effects = vec![cycloid::model::Effect::Clearance];
        scene.torque_sweep = None;
        s.scenes[0] = scene.clone();
        let plan = cycloid::model::Plan::for_scene(&scene);
        let r = cycloid::engine::scene::run(&s, &scene, &plan, &Default::default()).unwrap();
        let mesh = Mesh::new(&s.design, &s.modification);
        eprintln!("{name}:");
        assert_bounded(&mesh, (&r.discs[0], &r.name), 0.0);
    }
}

/// The nominal scene over a mesh period is its own sampling: no further sweep (its step is the
/// scene's 0.1°), the smallest of its own gaps, and the bound from its own samples.
#[test]
fn a_nominal_scene_over_a_mesh_period_is_its_own_sampling() {
    let s = spec("", &[("mesh", 0.0, 36.0, 360)]);
    let r = &run(&s)[0];
    let p = sampled(&r.discs[0], &r.name);
    assert!((units::deg(p.step_rad) - 0.1).abs() < 1e-12);
    assert!((units::deg(p.period_rad) - 36.0).abs() < 1e-12);
    let c = r.discs[0].clearance.as_ref().unwrap();
    let own = c
        .gap_mm
        .iter()
        .flatten()
        .copied()
        .fold(f64::INFINITY, f64::min);
    assert_eq!(c.min.gap_mm, own);
    let mesh = Mesh::new(&s.design, &s.modification);
    assert_bounded(&mesh, (&r.discs[0], &r.name), 0.0);
}

/// What the terminal and the JSON say: the whole period, its step and the bound for the
/// smallest gap; the lost motion, sought over the scene's own angles, says how many.
#[test]
fn the_lines_say_what_the_minimum_was_sought_over() {
    let dir = Scratch::new("mesh-minimum-cli");
    let text = PaperSpec::new()
        .edit("  material:", &format!("  deviations:\n{FORM_2}  material:"))
        .scenes("  - name: torsion\n    crank: { from_deg: 0.0, to_deg: 36.0, steps: 4 }\n    effects: [clearance]\nlimits:\n  min_clearance_mm: 0.015\n  max_lost_motion_arcsec: 3600.0\n");
    dir.write("spec.yaml", text.text());
    let out = cycloid(&dir.path, &["check", "spec.yaml", "--json", "out.json"]);
    assert_eq!(out.code(), 0, "{}{}", out.stdout, out.stderr);
    let line = out
        .stdout
        .lines()
        .find(|l| l.starts_with("torsion/min_clearance_mm"))
        .unwrap();
    assert!(
        line.contains("roller 7 at crank 72.75°")
            && line.contains("over the whole period of 324.0° sampled every 0.3750° (error ≤ "),
        "{line}"
    );
    let lost = out
        .stdout
        .lines()
        .find(|l| l.starts_with("torsion/max_lost_motion_arcsec"))
        .unwrap();
    assert!(lost.contains("over the scene's 4 crank angles"), "{lost}");
    let json: serde_json::Value = serde_json::from_str(&dir.read("out.json")).unwrap();
    let over = &json["scenes"][0]["min_clearance_over"];
    let number = |v: &serde_json::Value| v.as_f64().unwrap();
    // 1e-9°: degrees converted from radians.
    assert!((number(&over["period_deg"]) - 324.0).abs() < 1e-9, "{over}");
    assert!((number(&over["step_deg"]) - 0.375).abs() < 1e-9, "{over}");
    let bound = number(&over["error_bound_mm"]);
    assert!(bound > 0.0 && bound <= 1e-4, "{bound}");
    let at = number(&json["scenes"][0]["min_clearance_at"]["crank_deg"]);
    assert!((at - 72.75).abs() < 1e-9, "{at}");
}
