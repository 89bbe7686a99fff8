//! One result shape for any number of discs (issue 40 §5): a scene's result is the reducer's
//! curves over all its discs and each disc's own results, one disc being `discs.len() == 1`;
//! the registry knows from its reader whether a quantity is the reducer's or a disc's.

use crate::common::{scene_item, PaperSpec};
use cycloid::model::quantity::{self, QUANTITIES};
use cycloid::model::results::SceneResult;
use cycloid::model::Plan;
use cycloid::spec::Spec;
use std::f64::consts::TAU;

/// The paper's design (10 rollers, 9 teeth) with `discs` discs, one scene at 10 N·m over one
/// mesh period in 12 angles, with the clearance and the loaded effects.
fn paper(discs: usize) -> Spec {
    let crank = "{ from_deg: 0.0, to_deg: 36.0, steps: 12 }";
    PaperSpec::new()
        .edit("face_width_mm", &format!("discs: {discs}\n  face_width_mm"))
        .scenes(&scene_item("rated", 10.0, crank, "clearance, bearing"))
        .parse("paper.yaml")
}

/// `spec`'s scene run at the crank angles `crank_rad`, as `check` runs it.
fn run_at(spec: &Spec, crank_rad: Vec<f64>) -> SceneResult {
    let scene = cycloid::model::Scene {
        crank_rad,
        ..spec.scenes[0].clone()
    };
    let plan = Plan::for_scene(&scene);
    cycloid::engine::scene::run(spec, &scene, &plan, &Default::default())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// With one, two and three discs the result has the same shape: the reducer's transmission,
/// and one result per disc with its clearance and loaded curves. Disc k's curves are at its
/// crank phase 2πk/N (MODEL.md "Several discs"): its unloaded gaps at crank φ are those of the
/// one-disc reducer at φ + 2πk/N, computed here by a one-disc run at those angles. Tolerance
/// 1e-9 mm: each gap is a Newton projection on the profile (converged to ~1e-12 mm) at an
/// angle summed in a different order (~1e-15 rad, times |dg/dφ| ≤ e = 2 mm/rad). Before the
/// one shape, a one-disc result held its disc's curves itself and had no `discs`.
#[test]
fn every_number_of_discs_has_the_same_shape_each_disc_at_its_phase() {
    let one = paper(1);
    for n in 1..=3 {
        let spec = paper(n);
        let r = run_at(&spec, spec.scenes[0].crank_rad.clone());
        assert_eq!(r.discs.len(), n, "{n} discs");
        assert!(
            r.reducer.transmission.is_some(),
            "{n} discs: the reducer's TE"
        );
        assert_eq!(r.only_disc().is_some(), n == 1, "{n} discs");
        for (k, d) in r.discs.iter().enumerate() {
            assert!(d.loaded.rollers.is_some(), "{n} discs: disc {k}'s rollers");
            let phase = TAU * k as f64 / n as f64;
            let shifted = r.crank_rad.iter().map(|&phi| phi + phase).collect();
            let alone = run_at(&one, shifted);
            let want = &alone.discs[0].clearance.as_ref().unwrap().gap_mm;
            let got = &d.clearance.as_ref().unwrap().gap_mm;
            for (i, (g, w)) in got.iter().zip(want).enumerate() {
                for (a, (x, y)) in g.iter().zip(w).enumerate() {
                    assert!(
                        (x - y).abs() <= 1e-9,
                        "{n} discs: disc {k} roller {i} angle {a}: {x} against {y}"
                    );
                }
            }
        }
        // A disc's curves are the scene's own with one disc only; a reducer's curve is the
        // scene's for any N and no disc's.
        for q in QUANTITIES.iter().filter(|q| !q.is_scalar()) {
            let scene = q.curves(&r);
            let each: Vec<_> = r.discs.iter().map(|d| q.disc_curves(d)).collect();
            if q.of_reducer() {
                assert!(each.iter().all(Option::is_none), "{n} discs: {}", q.key);
            } else if n == 1 {
                assert_eq!(scene, each[0], "{n} discs: {}", q.key);
            } else {
                assert!(scene.is_none(), "{n} discs: {}", q.key);
            }
        }
    }
}

/// The quantities of the reducer as a whole (MODEL.md "Several discs", README "Results
/// JSON"): the output's TE and ratio and their fluctuations, the torsion under a locked input,
/// the efficiency and its losses, the pins' stresses (every disc's force on a pin) and a duty
/// cycle's figures. Every other quantity is each disc's. Written here from the documents, not
/// from the registry: moving one quantity's reader to the other side fails it.
#[test]
fn the_reducers_quantities_are_the_documented_ones() {
    let mut documented = vec![
        "te_arcsec",
        "ratio",
        "te_fluctuation_arcsec",
        "ratio_fluctuation",
        "lost_motion_arcmin",
        "backlash_arcmin",
        "torsional_rigidity_nm_per_arcmin",
        "hysteresis_loss_arcmin",
        "hysteresis_energy_j",
        "max_lost_motion_arcmin",
        "max_backlash_arcmin",
        "min_torsional_rigidity_nm_per_arcmin",
        "max_hysteresis_loss_arcmin",
        "efficiency",
        "input_torque_nm",
        "mean_efficiency",
        "total_power_loss_w",
        "temperature_c",
        "pin_bending_stress_mpa",
        "max_pin_bending_stress_mpa",
        "max_pin_shear_stress_mpa",
        "pin_bending_safety",
        "equivalent_torque_nm",
        "mean_speed_rpm",
        "duty_equivalent_load_n",
        "duty_life_h",
        "duty_mean_efficiency",
    ];
    documented.sort_unstable();
    let mut registry: Vec<&str> = (QUANTITIES.iter().filter(|q| q.of_reducer()))
        .map(|q| q.key)
        .collect();
    registry.sort_unstable();
    assert_eq!(registry, documented);
    // Where the two-disc run has a value, it is read where the registry says.
    let spec = paper(2);
    let r = run_at(&spec, spec.scenes[0].crank_rad.clone());
    let te = quantity::find("te_arcsec").unwrap();
    assert!(te.curves(&r).is_some());
    let force = quantity::find("roller_force_n").unwrap();
    assert!(r.discs.iter().all(|d| force.disc_curves(d).is_some()));
    let max_force = quantity::find("max_roller_force_n").unwrap();
    assert!(
        max_force.scalar(&r).unwrap().at.disc.is_some(),
        "named by its disc"
    );
}
