//! The period of the reducer as run (`Scene::run_period_rad`, issue 39 §1): one
//! function for every consumer, which a tilt fixed in the housing lengthens to whole crank
//! turns, and the output flange that tilts with the disc.
//!
//! Expected values come from outside the code: the period as the least common multiple of the
//! symmetries, written out here; a fluctuation over part of a period is at most the whole
//! period's; pins with a negative arm cannot carry a positive torque's load through 2-D
//! contacts; and, for the property test, the curves themselves repeating over the period.

use crate::common::{assert_refused_at, Scratch};
use cycloid::equilibrium::loaded::Model;
use cycloid::model::results::{LoadedSweep, Transmission};
use cycloid::model::Plan;
use cycloid::spec::Spec;
use proptest::prelude::*;

/// A reducer of `rollers` np (nc = np − 1 teeth) and `pins` M output pins, Rp 30, e 15/np (K1
/// 0.5), Rrp 3, B 8, pins on rw 18 of radius 3, with `reducer` extra keys (deviations), one
/// scene `rated` at 10 N·m over `crank` (its YAML flow mapping) with `scene` extra keys, and
/// `rest` (limits) after it.
fn text(
    rollers: usize,
    pins: usize,
    reducer: &str,
    crank: &str,
    scene: &str,
    rest: &str,
) -> String {
    format!(
        "name: period\n\
         reducer:\n  teeth: {}\n  rollers: {rollers}\n  eccentricity_mm: {}\n  \
         roller_circle_radius_mm: 30.0\n  roller_radius_mm: 3.0\n  face_width_mm: 8.0\n  \
         output_pins: {{ count: {pins}, circle_radius_mm: 18.0, pin_radius_mm: 3.0 }}\n  \
         material: {{ youngs_modulus_gpa: 206.0, poisson_ratio: 0.3 }}\n{reducer}\
         modification:\n  shift_mm: 0.125\n  equidistant_mm: 0.1593\n\
         scenes:\n  - name: rated\n    output_torque_nm: 10.0\n    crank: {crank}\n    \
         effects: [bearing]\n{scene}{rest}",
        rollers - 1,
        if rollers == 10 {
            2.0
        } else {
            15.0 / rollers as f64
        },
    )
}

/// The paper's design (9/10, e 2, 6 pins) with the tilt: 1 mrad about y, 20 slices.
fn paper_tilted(crank: &str, rest: &str) -> String {
    text(
        10,
        6,
        "",
        crank,
        "    misalignment: { about_y_mrad: 1.0 }\n    face_slices: 20\n",
        rest,
    )
}

fn parse(text: &str) -> Spec {
    cycloid::spec::parse("period.yaml", text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

/// The period of a reducer whose disc is tilted in the housing, deg, by hand: each roller
/// closes by its own fixed place, so the mesh repeats after a whole crank turn (360°); the pin
/// pattern after 360°·nc/(np·M); the loaded curves after the least common multiple. In
/// units of 360°/(np·M): np·M and nc.
fn tilted_period_deg(rollers: usize, pins: usize) -> f64 {
    let (mesh, pin) = (rollers * pins, rollers - 1);
    let lcm = mesh / gcd(mesh, pin) * pin;
    360.0 * lcm as f64 / mesh as f64
}

/// The case: a limit on the TE fluctuation and the face load factor judged over 0–36°
/// of the paper's design tilted by 1 mrad (8.3″ and 6.89 there, 22.0″ and 8.97 over the
/// whole period with the pins tilted against their holes) passed limits of 15″ and 8. The
/// period is 1080° (`tilted_period_deg`): the scene is refused at its crank, naming it and the
/// nearest whole range; the same tilt as built (`reducer.deviations.misalignment`) alike.
#[test]
fn a_limit_over_part_of_a_tilted_period_is_refused_at_the_crank() {
    assert_eq!(tilted_period_deg(10, 6), 1080.0);
    let dir = Scratch::new("period-limits");
    let crank = "{ from_deg: 0.0, to_deg: 36.0, steps: 360 }";
    let limits = "limits:\n  max_te_fluctuation_arcsec: 15.0\n  max_face_load_factor: 8.0\n";
    let rule = "not a whole number of loaded periods (1080°): a fluctuation, an extreme or a \
                mean over part of a period is not the reducer's; the nearest ranges of whole \
                periods: 0° to 1080° (1 period)";
    assert_refused_at(
        &dir,
        "period.yaml",
        &paper_tilted(crank, limits),
        "scenes[0].crank",
        rule,
    );
    let built = text(
        10,
        6,
        "  deviations:\n    misalignment: { about_y_mrad: 1.0 }\n",
        crank,
        "    face_slices: 20\n",
        limits,
    );
    assert_refused_at(&dir, "period.yaml", &built, "scenes[0].crank", rule);
    // Over the whole period the same limits are judged; a limit on the unloaded gaps is not
    // a loaded figure (the minimum clearance is sought over its own period) and stays allowed.
    parse(&paper_tilted(
        "{ from_deg: 0.0, to_deg: 1080.0, steps: 1080 }",
        limits,
    ));
    let clearance = paper_tilted(crank, "limits:\n  min_clearance_mm: 0.001\n");
    parse(&clearance.replace("effects: [bearing]", "effects: [clearance, bearing]"));
}

/// An optimisation study whose objective is a loaded figure is refused on a scene over part
/// of the period, as a limit is (the shipped crown study ran its tilted scene over 108°).
#[test]
fn a_study_over_part_of_a_tilted_period_is_refused_at_the_crank() {
    let dir = Scratch::new("period-study");
    let study = "optimise:\n  scene: rated\n  objective: max_face_load_factor\n  variables:\n    \
                 shift_mm: [0.1, 0.15]\n";
    let crank = "{ from_deg: 0.0, to_deg: 108.0, steps: 108 }";
    let rule = "objective max_face_load_factor applies to scene `rated`, whose crank range 0° to \
                108° is not a whole number of loaded periods (1080°)";
    assert_refused_at(
        &dir,
        "period.yaml",
        &paper_tilted(crank, study),
        "scenes[0].crank",
        rule,
    );
}

/// The engine's curves of `spec`'s one scene (its own plan and settings).
fn run(spec: &Spec) -> LoadedSweep {
    let scene = &spec.scenes[0];
    let plan = Plan::for_scene(scene);
    cycloid::engine::scene::run(spec, scene, &plan, &Default::default())
        .unwrap_or_else(|e| panic!("{e}"))
        .discs
        .remove(0)
        .loaded
}

fn fluctuation(values: &[f64]) -> f64 {
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    hi - lo
}

/// The ratio of `specs/reducer-misaligned.yaml`'s tilted scene over 108° was differenced as
/// if the curve wrapped (it does not: its period is 1080°), with false spikes at both ends
/// (9.066 against a ratio near nc = 9, a fluctuation of 0.0764 against 0.0366 over the whole
/// period). A fluctuation over part of the period is at most the whole period's; the part's
/// ends are differenced one-sidedly and the whole's across its wrap, two second-order
/// stencils of the same 0.1° step, which agree to O(h²·κ''') — 1e-4 leaves room for that and
/// is a tenth of the spikes' excess.
#[test]
fn the_ratio_wraps_only_over_whole_periods() {
    let tilt = "    misalignment: { about_x_mrad: 0.3, about_y_mrad: 0.3 }\n    face_slices: 20\n";
    let ratio = |to_deg: usize| {
        let crank = format!(
            "{{ from_deg: 0.0, to_deg: {to_deg}.0, steps: {} }}",
            10 * to_deg
        );
        let spec = parse(&text(10, 6, "", &crank, tilt, ""));
        solve_at(&spec, &spec.scenes[0].crank_rad)
            .1
            .unwrap()
            .ratio
            .unwrap()
    };
    let (part, whole) = (ratio(108), ratio(1080));
    let (fp, fw) = (fluctuation(&part), fluctuation(&whole));
    assert!(fp <= fw + 1e-4, "over 108°: {fp}; over 1080°: {fw}");
    // The part's samples are the whole's first 1080: away from the ends they are the same
    // central differences.
    for k in [1, 540, 1078] {
        // Lags solved to ~1e-12 rad, differenced over 2h = 3.5e-3 rad: κ to ~κ²·3e-10.
        assert!((part[k] - whole[k]).abs() <= 1e-6, "angle {k}");
    }
}

/// The output flange tilts with the disc (README "Along the face width"): a pin sees no tilt
/// against its hole, so its contact is the 2-D one, which a pin whose arm about the disc's
/// centre is negative (rw·sin(2πj/M) at crank 0, pins 4 and 5 of 6) opens under a positive
/// output torque: it carries nothing. With the pins tilted against their holes (as the engine
/// had it) all six carried load at zero hole clearance, pins 4 and 5 83 N each.
#[test]
fn pins_see_no_tilt_against_their_holes() {
    let tilt = "    misalignment: { about_x_mrad: 0.3, about_y_mrad: 0.3 }\n    face_slices: 20\n";
    let spec = parse(&text(
        10,
        6,
        "",
        "{ from_deg: 0.0, to_deg: 54.0, steps: 6 }",
        tilt,
        "",
    ));
    let tilted = run(&spec);
    let forces = &tilted.pins.as_ref().unwrap().force_n;
    for (j, f) in forces.iter().enumerate() {
        let arm = (std::f64::consts::TAU * j as f64 / 6.0).sin();
        if arm < -0.1 {
            assert_eq!(f[0], 0.0, "pin {j}, arm {arm}: {} N", f[0]);
        }
    }
}

/// The loaded curves of `spec`'s one scene solved at `crank_rad` (no wrap), by the sweep.
fn solve_at(spec: &Spec, crank_rad: &[f64]) -> (LoadedSweep, Option<Transmission>) {
    let scene = &spec.scenes[0];
    let plan = Plan::for_scene(scene);
    let model = Model::new(&spec.design, &spec.modification, scene, &plan);
    crate::common::one_disc_sweep(&model, crank_rad, false).unwrap_or_else(|f| panic!("{f:?}"))
}

/// The forces of angle `k` that must repeat: the bearing force's magnitude and the roller and
/// pin forces as sets (a period may carry roller i to roller i + k's place), N.
fn forces(l: &LoadedSweep, k: usize) -> Vec<f64> {
    let r = l.rollers.as_ref().unwrap();
    let mut rollers: Vec<f64> = r.force_n.iter().map(|f| f[k]).collect();
    let mut pins: Vec<f64> = l
        .pins
        .as_ref()
        .unwrap()
        .force_n
        .iter()
        .map(|f| f[k])
        .collect();
    rollers.sort_by(f64::total_cmp);
    pins.sort_by(f64::total_cmp);
    let mut out = vec![l.bearing.as_ref().unwrap().force_n[k]];
    out.extend(rollers);
    out.extend(pins);
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(16)
    ))]

    /// Over random designs (np 5–12, 3–8 pins), tilts in the scene or as built, and a roller
    /// off its place or not, the period of the reducer as run is a period: the curves at φ and
    /// φ + P agree. Each angle is solved to the solver's tolerance (a relative residual of
    /// 1e-10, the forces to ~1e-9 of their size), so 1e-6 of the largest force (and of the
    /// lag in mrad) bounds the solve and leaves a tilt's effect (a 0.1 mrad tilt moves a
    /// roller's force by percents) far outside it.
    #[test]
    fn the_period_is_a_period(
        rollers in 5usize..=12,
        pins in 3usize..=8,
        tilt in (-1.0f64..1.0, -1.0f64..1.0),
        where_tilt in 0usize..3,
        moved in any::<bool>(),
        start in 0.0f64..360.0,
    ) {
        let tilt = format!("{{ about_x_mrad: {:?}, about_y_mrad: {:?} }}", tilt.0, tilt.1);
        let mut reducer = String::new();
        let mut scene = "    face_slices: 4\n".to_string();
        if where_tilt == 1 || moved {
            reducer += "  deviations:\n";
        }
        if where_tilt == 1 {
            reducer += &format!("    misalignment: {tilt}\n");
        } else if where_tilt == 2 {
            scene += &format!("    misalignment: {tilt}\n");
        }
        if moved {
            reducer += "    rollers: [{ index: 1, radial_mm: 0.002 }]\n";
        }
        let crank = "{ from_deg: 0.0, to_deg: 360.0, steps: 10 }";
        let spec = match cycloid::spec::parse("p.yaml", &text(rollers, pins, &reducer, crank, &scene, "")) {
            Ok(s) => s,
            Err(_) => return Err(TestCaseError::reject("not a valid design")),
        };
        let s = &spec.scenes[0];
        let p = s.run_period_rad(&spec.design, &Plan::for_scene(s));
        if where_tilt > 0 && !moved {
            prop_assert!((p.to_degrees() - tilted_period_deg(rollers, pins)).abs() < 1e-9);
        }
        let phi: Vec<f64> = [0.0, 7.3, 21.1].iter().map(|d| (start + d).to_radians()).collect();
        let angles: Vec<f64> = phi.iter().copied().chain(phi.iter().map(|a| a + p)).collect();
        let (l, _) = solve_at(&spec, &angles);
        let lag = &l.rollers.as_ref().unwrap().lag_rad;
        let n = phi.len();
        for k in 0..n {
            let (a, b) = (forces(&l, k), forces(&l, k + n));
            let scale = a.iter().chain(&b).fold(1.0f64, |m, v| m.max(v.abs()));
            for (x, y) in a.iter().zip(&b) {
                prop_assert!((x - y).abs() <= 1e-6 * scale, "forces at {k}:\n{a:?}\n{b:?}");
            }
            prop_assert!(
                (lag[k] - lag[k + n]).abs() <= 1e-6 * lag[k].abs().max(lag[k + n].abs()),
                "lag at {k}: {} {}", lag[k], lag[k + n]
            );
        }
    }
}

/// A design search writes its scenes before its design exists, so it counts the period in
/// mesh periods (`model::requirements::loaded_mesh_periods`); the count must be the same
/// period as the design's own (`Design::loaded_period_rad`, what a spec's scene is judged
/// over). Counted here by stepping: the first whole number of mesh periods (2π/np, or a whole
/// turn when tilted) that is also a whole number of pin periods (2π·nc/(np·M)), in units of
/// 2π/(np·M) where both are integers, for every nc 2..=40 and M 1..=12.
#[test]
fn a_searchs_period_counts_the_least_common_multiple_of_mesh_and_pins() {
    use cycloid::model::requirements::loaded_mesh_periods;
    for teeth in 2..=40 {
        for pins in 1..=12 {
            let rollers = teeth + 1;
            for tilted in [false, true] {
                let mesh_units = if tilted { rollers * pins } else { pins };
                let periods = (1..)
                    .find(|k| (k * mesh_units) % teeth == 0)
                    .expect("k = nc is a common multiple");
                let tilt_factor = if tilted { rollers } else { 1 };
                assert_eq!(
                    loaded_mesh_periods(teeth, pins, tilted),
                    periods * tilt_factor,
                    "nc {teeth}, M {pins}, tilted {tilted}"
                );
            }
            // The design's own period, for designs `text` can build (its pins fit on rw 18).
            if (6..=12).contains(&teeth) && (3..=6).contains(&pins) {
                let spec = parse(&text(
                    teeth + 1,
                    pins,
                    "",
                    "{ from_deg: 0, to_deg: 1, steps: 1 }",
                    "",
                    "",
                ));
                let mesh_rad = std::f64::consts::TAU / rollers as f64;
                let counted = loaded_mesh_periods(teeth, pins, false) as f64 * mesh_rad;
                // Both are a few float operations on small integers: 1e-12 rad.
                assert!((spec.design.loaded_period_rad(true, false) - counted).abs() < 1e-12);
            }
        }
    }
}
