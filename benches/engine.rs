//! Engine benchmarks (divan). Run: `cargo bench --bench engine`. Numbers go in BENCHMARKS.md.
//! Single-threaded by default (RAYON_NUM_THREADS=1 recommended for the per-core targets).

use cycloid::equilibrium::discs_sweep;
use cycloid::geometry::clearance::{self, Mesh, Scope};
use cycloid::model::GeometryMode;
use cycloid::spec::{self, Spec};
use std::hint::black_box;

mod common;

fn main() {
    divan::main();
}

fn paper() -> Spec {
    spec::load("specs/paper.yaml").expect("specs/paper.yaml")
}

fn crank(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| std::f64::consts::TAU / 10.0 * k as f64 / n as f64)
        .collect()
}

/// Unloaded clearance of every roller with backlash both ways and lost motion, one mesh period
/// at 0.1° (3,600 roller-angles).
#[divan::bench]
fn clearance_sweep_360(b: divan::Bencher) {
    let s = paper();
    let mesh = Mesh::new(&s.design, &s.modification);
    let c = crank(360);
    b.bench(|| {
        clearance::sweep(
            black_box(&mesh),
            &c,
            Scope::Backlash,
            &cycloid::progress::Silent,
        )
        .unwrap()
    });
}

/// Unloaded gaps of every roller and the smallest, one mesh period at 0.1° (what a
/// `min_clearance_mm` limit needs).
#[divan::bench]
fn clearance_gaps_360(b: divan::Bencher) {
    let s = paper();
    let mesh = Mesh::new(&s.design, &s.modification);
    let c = crank(360);
    b.bench(|| {
        clearance::sweep(
            black_box(&mesh),
            &c,
            Scope::Gaps,
            &cycloid::progress::Silent,
        )
        .unwrap()
    });
}

/// Whole-mesh minimum clearance (the optimiser's constraint), 360 angles.
#[divan::bench]
fn min_gap_360(b: divan::Bencher) {
    let s = paper();
    let mesh = Mesh::new(&s.design, &s.modification);
    let c = crank(360);
    b.bench(|| clearance::min_gap(black_box(&mesh), &c).unwrap());
}

/// `check specs/reducer.yaml` in-process: the paper optimum's clearance over one mesh period at
/// 0.1° (360 angles) against its `min_clearance_mm` limit; compare `loaded_sweep_360_*`.
#[divan::bench]
fn check_clearance_only_360(b: divan::Bencher) {
    b.bench(|| {
        let mut out = Vec::new();
        let cli = <cycloid::cli::Cli as clap::Parser>::parse_from([
            "cycloid",
            "check",
            "specs/reducer.yaml",
        ]);
        cycloid::cli::run(cli, &mut out).unwrap()
    });
}

fn loaded(b: divan::Bencher, geometry: GeometryMode) {
    loaded_with(b, geometry, 10);
}

fn loaded_with(b: divan::Bencher, geometry: GeometryMode, rollers: usize) {
    let (model, c) = common::rated_sweep(geometry, 3600, rollers);
    b.bench(|| {
        discs_sweep::sweep_reducer(black_box(&model), 1, &c, (true, &cycloid::progress::Silent))
            .unwrap()
    });
}

/// Loaded sweep of 360 crank angles (the angles of `check_clearance_only_360`), exact geometry.
#[divan::bench]
fn loaded_sweep_360_exact(b: divan::Bencher) {
    let (model, c) = common::rated_sweep(GeometryMode::Exact, 360, 10);
    b.bench(|| {
        discs_sweep::sweep_reducer(black_box(&model), 1, &c, (true, &cycloid::progress::Silent))
            .unwrap()
    });
}

/// Loaded sweep of 360 crank angles, first-order geometry.
#[divan::bench]
fn loaded_sweep_360_first_order(b: divan::Bencher) {
    let (model, c) = common::rated_sweep(GeometryMode::FirstOrder, 360, 10);
    b.bench(|| {
        discs_sweep::sweep_reducer(black_box(&model), 1, &c, (true, &cycloid::progress::Silent))
            .unwrap()
    });
}

/// Loaded sweep of 3,600 crank angles, exact geometry (target < 10 ms on one core).
#[divan::bench(sample_count = 60)]
fn loaded_sweep_3600_exact(b: divan::Bencher) {
    loaded(b, GeometryMode::Exact);
}

/// Loaded sweep of 3,600 crank angles, first-order geometry (target < 1 ms on one core).
#[divan::bench(sample_count = 300)]
fn loaded_sweep_3600_first_order(b: divan::Bencher) {
    loaded(b, GeometryMode::FirstOrder);
}

/// The coupled friction model (issue 28): `loaded_sweep_3600_exact`'s model and angles with
/// friction inside every balance (rotating rollers μ 0.06 on pins of r_b 1.5 mm, sleeves μ 0.06
/// on pins of 2 mm, a crank bearing μ 0.0025 of bore 20 mm: the shipped
/// specs/reducer-efficiency.yaml's) (target: at most 2× the frictionless sweep).
#[divan::bench(sample_count = 60)]
fn coupled_sweep_3600_exact(b: divan::Bencher) {
    use cycloid::model::{
        BearingFriction, Friction, FrictionModel, PinFriction, PinMode, RollerFriction, RollerMode,
    };
    let (model, c) = common::rated_sweep(GeometryMode::Exact, 3600, 10);
    let design = paper().design;
    let friction = Friction {
        model: FrictionModel::Coupled,
        rollers: Some(RollerFriction {
            mode: RollerMode::Rotating {
                bore_radius_mm: 1.5,
            },
            mu: 0.06,
        }),
        output_pins: Some(PinFriction {
            mode: PinMode::Sleeve {
                bore_radius_mm: 2.0,
            },
            mu: 0.06,
        }),
        crank_bearing: Some(BearingFriction {
            mu: 0.0025,
            bore_diameter_mm: 20.0,
        }),
        no_load_torque_nmm: cycloid::model::NoLoadTorque::constant(0.0),
    };
    let model = model.with_friction(&friction, &design);
    b.bench(|| {
        discs_sweep::sweep_reducer(black_box(&model), 1, &c, (true, &cycloid::progress::Silent))
            .unwrap()
    });
}

/// Two discs (issue 14): the coupled sweep of `loaded_sweep_3600_exact`'s model and angles
/// with the torque shared by two discs half a turn apart (target: at most 2.2× the one-disc
/// sweep).
#[divan::bench(sample_count = 60)]
fn two_discs_sweep_3600_exact(b: divan::Bencher) {
    two_discs(b, GeometryMode::Exact);
}

/// As `two_discs_sweep_3600_exact`, first-order geometry (against
/// `loaded_sweep_3600_first_order`, whose one-disc kernel is a lean closed form). As many
/// samples as that baseline: the ratio is of fastest samples, and on a shared host more
/// samples find a lower fastest.
#[divan::bench(sample_count = 300)]
fn two_discs_sweep_3600_first_order(b: divan::Bencher) {
    two_discs(b, GeometryMode::FirstOrder);
}

/// The one-disc baseline of `two_discs_sweep_3600_first_order_11_rollers`: the paper's design
/// with 11 rollers and 10 teeth, 3,600 angles over its mesh period.
#[divan::bench(sample_count = 300)]
fn loaded_sweep_3600_first_order_11_rollers(b: divan::Bencher) {
    loaded_with(b, GeometryMode::FirstOrder, 11);
}

/// Two discs with an odd roller count (issue 14): they do not mesh in one phase, so their
/// split of the torque moves with the crank (19 % to 81 % of T) and the Newton on the shares
/// works at every angle, where on the paper's even design the split is T/2 throughout.
/// Target: at most 2.2× `loaded_sweep_3600_first_order_11_rollers`.
#[divan::bench(sample_count = 300)]
fn two_discs_sweep_3600_first_order_11_rollers(b: divan::Bencher) {
    two_discs_with(b, GeometryMode::FirstOrder, 11);
}

/// The one-disc baseline of `two_discs_sweep_3600_exact_11_rollers`.
#[divan::bench(sample_count = 60)]
fn loaded_sweep_3600_exact_11_rollers(b: divan::Bencher) {
    loaded_with(b, GeometryMode::Exact, 11);
}

/// As `two_discs_sweep_3600_first_order_11_rollers`, exact geometry (the general coupled
/// solve). Target: at most 2.2× `loaded_sweep_3600_exact_11_rollers`.
#[divan::bench(sample_count = 60)]
fn two_discs_sweep_3600_exact_11_rollers(b: divan::Bencher) {
    two_discs_with(b, GeometryMode::Exact, 11);
}

fn two_discs(b: divan::Bencher, geometry: GeometryMode) {
    two_discs_with(b, geometry, 10);
}

fn two_discs_with(b: divan::Bencher, geometry: GeometryMode, rollers: usize) {
    let (model, c) = common::rated_sweep(geometry, 3600, rollers);
    let discs = cycloid::equilibrium::discs::Discs::new(&model, 2);
    b.bench(|| {
        discs_sweep::sweep_discs(black_box(&discs), &c, true, &cycloid::progress::Silent).unwrap()
    });
}

/// The paper's design with its pins as cantilevers (issue 29), `discs` discs: one disc 10 mm
/// from the flange on a 14 mm pin (`specs/reducer-pin-beams.yaml`'s), two at 6 and 16 mm on a
/// 20 mm pin (`tests/it/pin_beam.rs`'s, where the pins carry both discs).
fn pin_beams(b: divan::Bencher, geometry: GeometryMode, discs: usize) {
    use cycloid::model::{PinSupport, PinSupportKind};
    let (length_mm, disc_positions_mm) = match discs {
        1 => (14.0, [10.0, 0.0, 0.0, 0.0]),
        _ => (20.0, [6.0, 16.0, 0.0, 0.0]),
    };
    let (model, c) = common::rated_sweep_of(geometry, 3600, 10, |d| {
        d.discs = discs;
        d.pins.support = Some(PinSupport {
            kind: PinSupportKind::Cantilever,
            length_mm,
            disc_positions_mm,
        });
    });
    let discs = cycloid::equilibrium::discs::Discs::new(&model, discs);
    b.bench(|| {
        discs_sweep::sweep_discs(black_box(&discs), &c, true, &cycloid::progress::Silent).unwrap()
    });
}

/// Pins as beams, one disc, against `loaded_sweep_3600_exact` (the bending is a series spring
/// in each pin's law).
#[divan::bench(sample_count = 60)]
fn pin_beams_sweep_3600_exact(b: divan::Bencher) {
    pin_beams(b, GeometryMode::Exact, 1);
}

/// Pins as beams, one disc, first order, against `loaded_sweep_3600_first_order`.
#[divan::bench(sample_count = 300)]
fn pin_beams_sweep_3600_first_order(b: divan::Bencher) {
    pin_beams(b, GeometryMode::FirstOrder, 1);
}

/// Pins as beams carrying two discs, against `two_discs_sweep_3600_exact` (the fixed point
/// on the gaps the discs open at each other's planes).
#[divan::bench(sample_count = 60)]
fn pin_beams_two_discs_sweep_3600_exact(b: divan::Bencher) {
    pin_beams(b, GeometryMode::Exact, 2);
}

/// As `pin_beams_two_discs_sweep_3600_exact`, first order, against
/// `two_discs_sweep_3600_first_order` (the lean kernel does not take coupled pins).
#[divan::bench(sample_count = 60)]
fn pin_beams_two_discs_sweep_3600_first_order(b: divan::Bencher) {
    pin_beams(b, GeometryMode::FirstOrder, 2);
}

/// Torsion under a locked input (issue 14): the paper optimum (`specs/reducer-torsion.yaml`'s
/// scene `torsion`, pins and a rigid bearing, exact geometry) at 4 locked crank angles × 40
/// steps per quarter loop (161 loop solves and 8 figure solves per angle); target < 20 ms.
#[divan::bench]
fn torsion_4_angles_40_steps(b: divan::Bencher) {
    let s = spec::load("specs/reducer-torsion.yaml").expect("specs/reducer-torsion.yaml");
    let scene = s
        .scenes
        .iter()
        .find(|c| c.name == "torsion")
        .expect("torsion");
    let plan = cycloid::model::Plan::of("torsion", &[cycloid::model::Effect::Bearing]);
    let model = cycloid::equilibrium::loaded::Model::new(&s.design, &s.modification, scene, &plan);
    torsion_loops(b, &model, scene, s.design.discs);
}

/// Bench the torsion loops of `scene` on `count` discs of `model`.
fn torsion_loops(
    b: divan::Bencher,
    model: &cycloid::equilibrium::loaded::Model,
    scene: &cycloid::model::Scene,
    count: usize,
) {
    let discs = cycloid::equilibrium::discs::Discs::new(model, count);
    let sweep = scene.torque_sweep.expect("a torque sweep");
    assert_eq!((scene.crank_rad.len(), sweep.steps), (4, 40));
    let compliances = cycloid::model::results::TorsionCompliances {
        contact_law: scene.contact_law,
        geometry: scene.geometry,
        pin_contacts: true,
        bearing_stiffness_n_per_mm: None,
        pin_bending: None,
        structure_rad_per_nmm: 0.0,
    };
    b.bench(|| {
        cycloid::engine::torsion::run(
            black_box(&discs),
            &sweep,
            &scene.crank_rad,
            compliances,
            &cycloid::progress::Silent,
        )
        .unwrap()
    });
}

/// The same torsion scene with friction in the loop (issue 28): `specs/reducer-efficiency.yaml`'s
/// friction (rotating rollers, sleeved pins, crank bearing) on both branches, each through the
/// loop's and the figures' torques (2 × 84 solves per angle, a point solved again where ρ turns
/// a pin's sliding).
#[divan::bench]
fn torsion_4_angles_40_steps_friction(b: divan::Bencher) {
    let s = spec::load("specs/reducer-torsion.yaml").expect("specs/reducer-torsion.yaml");
    let friction = spec::load("specs/reducer-efficiency.yaml")
        .expect("specs/reducer-efficiency.yaml")
        .design
        .friction
        .expect("friction");
    let scene = s
        .scenes
        .iter()
        .find(|c| c.name == "torsion")
        .expect("torsion");
    let plan = cycloid::model::Plan::of("torsion", &[cycloid::model::Effect::Bearing]);
    let mut model =
        cycloid::equilibrium::loaded::Model::new(&s.design, &s.modification, scene, &plan)
            .with_friction(&friction, &s.design);
    model.coupling = model.coupling.map(|c| c.in_torsion(1.0));
    torsion_loops(b, &model, scene, s.design.discs);
}

/// One full optimisation study (the paper's positive ratio study).
#[divan::bench(sample_count = 3)]
fn optimisation_positive_ratio(b: divan::Bencher) {
    let s = paper();
    b.bench(|| cycloid::engine::optimise::run_study(&s, &s.studies[0], &cycloid::progress::Silent));
}

/// `check specs/paper.yaml` end to end, all four optimisations included (target < 2 s).
#[divan::bench(sample_count = 3)]
fn check_paper_end_to_end(b: divan::Bencher) {
    b.bench(|| {
        let mut out = Vec::new();
        let cli = <cycloid::cli::Cli as clap::Parser>::parse_from([
            "cycloid",
            "check",
            "specs/paper.yaml",
        ]);
        cycloid::cli::run(cli, &mut out).unwrap()
    });
}

/// The paper's four optimisation studies (`specs/paper.yaml`), the whole search: global
/// sample, local runs and 41 × 41 verification grid (target: a few seconds on one core; run
/// with RAYON_NUM_THREADS=1).
#[divan::bench(sample_count = 3, sample_size = 1)]
fn paper_studies(b: divan::Bencher) {
    let s = paper();
    b.bench(|| {
        s.studies
            .iter()
            .map(|study| {
                cycloid::engine::optimise::run_study(
                    black_box(&s),
                    study,
                    &cycloid::progress::Silent,
                )
                .evaluations
            })
            .sum::<usize>()
    });
}

/// The crown study of `specs/reducer-crown-study.yaml`: the circular crown's radius and start
/// for a 0.3 mrad tilt, 360 crank angles with 20 slices each, global sample, local runs and the
/// 21 × 21 verification grid (run with RAYON_NUM_THREADS=1).
#[divan::bench(sample_count = 3, sample_size = 1)]
fn crown_study(b: divan::Bencher) {
    let s = cycloid::spec::load("specs/reducer-crown-study.yaml").expect("crown study spec");
    b.bench(|| {
        cycloid::engine::optimise::run_study(
            black_box(&s),
            &s.studies[0],
            &cycloid::progress::Silent,
        )
        .evaluations
    });
}

/// The spec of the JSON benchmarks: the paper optimum at 10 N·m (`specs/reducer-loaded.yaml`)
/// with rollers, pins and a rigid bearing over 3,600 crank angles (its loaded period of 108° at
/// 0.03°: a limit over part of the loaded period, as one mesh period at 0.01° was, is refused),
/// no clearance sweep, no accuracy section, written into a scratch directory (the same one at every run, so that
/// runs leave one set of files behind). Returns (spec, results JSON in the temporary
/// directory, results JSON in memory-backed /dev/shm when there is one).
fn json_scene() -> (String, String, String) {
    let dir = std::env::temp_dir().join("cycloid-bench-json");
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let text = std::fs::read_to_string("specs/reducer-loaded.yaml")
        .expect("specs/reducer-loaded.yaml")
        .replace(
            "crank: { from_deg: 0.0, to_deg: 108.0, steps: 1080 }",
            "crank: { from_deg: 0.0, to_deg: 108.0, steps: 3600 }",
        )
        .replace("effects: [clearance, bearing]", "effects: [bearing]")
        .replace("  min_clearance_mm: 0.015", "  max_roller_force_n: 1.0e6");
    // Without its `accuracy:` section, whose resolution check would run ladder rungs.
    let text = &text[..text.find("\naccuracy:").map_or(text.len(), |at| at + 1)];
    let spec = dir.join("rated-3600.yaml");
    std::fs::write(&spec, text).expect("bench spec written");
    let shm = std::path::Path::new("/dev/shm");
    let memory = if shm.is_dir() { shm } else { dir.as_path() };
    let file = "cycloid-bench-results.json";
    let path = |p: std::path::PathBuf| p.display().to_string();
    (path(spec), path(dir.join(file)), path(memory.join(file)))
}

fn check(args: &[&str]) {
    let mut out = Vec::new();
    let cli = <cycloid::cli::Cli as clap::Parser>::parse_from(args);
    cycloid::cli::run(cli, &mut out).expect("check runs");
}

/// `check` of the 3,600-angle loaded scene (`json_scene`) without `--json`: the baseline of
/// `check_json_3600*` (target: those at most 1.5× this).
#[divan::bench(sample_count = 60)]
fn check_3600(b: divan::Bencher) {
    let (spec, _, _) = json_scene();
    b.bench(|| check(&["cycloid", "check", &spec]));
}

/// `check --json` of the same scene into the temporary directory (on disk): 3,600 angles ×
/// (10 rollers × 3 curves, 6 pins, bearing, TE, ratio) written atomically, the fsync included.
#[divan::bench(sample_count = 60)]
fn check_json_3600(b: divan::Bencher) {
    let (spec, json, _) = json_scene();
    b.bench(|| check(&["cycloid", "check", &spec, "--json", &json]));
}

/// `check --json` of the same scene into /dev/shm (memory): the tool's own cost of the JSON,
/// without the disk's.
#[divan::bench(sample_count = 60)]
fn check_json_3600_memory(b: divan::Bencher) {
    let (spec, _, json) = json_scene();
    b.bench(|| check(&["cycloid", "check", &spec, "--json", &json]));
}

/// `specs/reducer-efficiency.yaml`'s scene over 3,600 crank angles (one mesh period at 0.01°)
/// with the plan `effects` (the one scene's run, in-process).
fn efficiency_scene(b: divan::Bencher, effects: &[cycloid::model::Effect]) {
    let spec = spec::load("specs/reducer-efficiency.yaml").expect("specs/reducer-efficiency.yaml");
    let scene = cycloid::model::Scene {
        crank_rad: crank(3600),
        ..spec.scenes[0].clone()
    };
    let plan = cycloid::model::Plan::of(&scene.name, effects);
    b.bench(|| {
        cycloid::engine::scene::run(&spec, black_box(&scene), &plan, &Default::default()).unwrap()
    });
}

/// Issue 28: the effect `efficiency` with the loss model, 3,600 crank angles, exact geometry
/// (target: at most 1.3× `efficiency_base_3600_exact`, the loaded sweep it builds on).
#[divan::bench(sample_count = 30)]
fn efficiency_loss_3600_exact(b: divan::Bencher) {
    efficiency_scene(b, &[cycloid::model::Effect::Efficiency]);
}

/// The loaded sweep `efficiency_loss_3600_exact` builds on: the same scene with `bearing`
/// (roller contact, output pins and the bearing) and no efficiency.
#[divan::bench(sample_count = 30)]
fn efficiency_base_3600_exact(b: divan::Bencher) {
    efficiency_scene(b, &[cycloid::model::Effect::Bearing]);
}

/// Issue 31: a 4-bin duty cycle (`specs/reducer-duty-cycle.yaml`: bearing over the loaded
/// period 0°–108°, 1080 angles, exact geometry) against one loaded scene of the same plan at
/// its first bin's torque and speed: the cycle is four such runs (in parallel on more than one
/// thread) and their combination.
fn duty_scene(b: divan::Bencher, single: bool) {
    let spec = spec::load("specs/reducer-duty-cycle.yaml").expect("specs/reducer-duty-cycle.yaml");
    let duty = spec.scenes[0].clone();
    let scene = match single {
        true => duty.duty_cycle.as_ref().unwrap()[0].scene(&duty, 0),
        false => duty,
    };
    let plan = cycloid::model::Plan::for_scene(&scene);
    b.bench(|| {
        cycloid::engine::scene::run(&spec, black_box(&scene), &plan, &Default::default()).unwrap()
    });
}

#[divan::bench(sample_count = 60)]
fn duty_cycle_4_bins_1080_exact(b: divan::Bencher) {
    duty_scene(b, false);
}

#[divan::bench(sample_count = 60)]
fn duty_cycle_one_bin_scene_1080_exact(b: divan::Bencher) {
    duty_scene(b, true);
}

/// Issue 29: the loaded sweep of `loaded_sweep_360_exact` (rollers, pins, rigid bearing, 360
/// crank angles) with `face` (20 slices unless said), by the linear law's closed form or, with
/// `by_slices`, summed slice by slice as the Winkler reference; `law` the contact law.
fn face_sweep(
    b: divan::Bencher,
    face: cycloid::model::Face,
    law: cycloid::model::ContactLaw,
    by_slices: bool,
) {
    let s = paper();
    let mut scene = s
        .scenes
        .iter()
        .find(|c| c.name == "rated")
        .expect("rated")
        .clone();
    scene.contact_law = law;
    scene.face = face;
    let plan = cycloid::model::Plan::of("rated", &[cycloid::model::Effect::Bearing]);
    let mut model =
        cycloid::equilibrium::loaded::Model::new(&s.design, &s.modification, &scene, &plan);
    if by_slices {
        model.rollers = model.rollers.map(|r| r.with_face_by_slices(&face));
    }
    let c = crank(360);
    b.bench(|| {
        discs_sweep::sweep_reducer(black_box(&model), 1, &c, (true, &cycloid::progress::Silent))
            .unwrap()
    });
}

/// A crowned disc (Rc 1 m, flat over 4 mm) tilted 0.3 mrad about x and y, cut into `slices`.
fn tilted(slices: usize) -> cycloid::model::Face {
    cycloid::model::Face {
        crowning: cycloid::model::Crowning::Circular {
            radius_mm: 1000.0,
            start_mm: 2.0,
        },
        misalignment: cycloid::model::Misalignment {
            about_x_rad: 0.3e-3,
            about_y_rad: 0.3e-3,
        },
        slices,
    }
}

/// The 2-D scene the face benchmarks compare with (`face_sweep` with the default face).
#[divan::bench(sample_count = 30)]
fn face_2d_360_exact(b: divan::Bencher) {
    face_sweep(
        b,
        cycloid::model::Face::default(),
        cycloid::model::ContactLaw::PaperLinear,
        false,
    );
}

/// Crowned and tilted, 20 slices, the linear law's closed form (target: ≤ 1.5× `face_2d_360_exact`).
#[divan::bench(sample_count = 30)]
fn face_closed_form_20_360_exact(b: divan::Bencher) {
    face_sweep(
        b,
        tilted(20),
        cycloid::model::ContactLaw::PaperLinear,
        false,
    );
}

/// The same summed over 20 Winkler slices (the reference the closed form is the limit of).
#[divan::bench(sample_count = 30)]
fn face_winkler_20_360_exact(b: divan::Bencher) {
    face_sweep(b, tilted(20), cycloid::model::ContactLaw::PaperLinear, true);
}

/// Johnson's law in 2-D, and crowned and tilted over 5 and 20 slices (the cost per slice).
#[divan::bench(sample_count = 10)]
fn face_johnson_2d_360_exact(b: divan::Bencher) {
    face_sweep(
        b,
        cycloid::model::Face::default(),
        cycloid::model::ContactLaw::HertzNonlinear,
        false,
    );
}

#[divan::bench(sample_count = 10)]
fn face_johnson_5_360_exact(b: divan::Bencher) {
    face_sweep(
        b,
        tilted(5),
        cycloid::model::ContactLaw::HertzNonlinear,
        false,
    );
}

#[divan::bench(sample_count = 10)]
fn face_johnson_20_360_exact(b: divan::Bencher) {
    face_sweep(
        b,
        tilted(20),
        cycloid::model::ContactLaw::HertzNonlinear,
        false,
    );
}
