//! Parts as built (MODEL.md "Part deviations"): each deviation checked against an independent
//! statement of the same reducer — a nominal design with a dimension moved, a rotated housing,
//! the first-order change of a gap, or a bearing offset — and the symmetries it must break.

use crate::common;

use crate::common::{paper_design, PaperSpec};
use cycloid::engine::scene;
use cycloid::geometry::clearance::{self, Mesh, Pose};
use cycloid::geometry::Vec2;
use cycloid::model::results::SceneResult;
use cycloid::model::{
    CentreDeviation, Design, Deviations, Modification, Plan, RollerDeviation, Scene,
};

const PAPER_OPTIMUM: Modification = Modification {
    shift_mm: 0.125,
    equidistant_mm: 0.1593,
    rotation_rad: 0.0,
};

/// Every roller moved alike.
fn all_rollers(design: &Design, d: RollerDeviation) -> Deviations {
    Deviations {
        rollers: vec![d; design.rollers],
        ..Deviations::default()
    }
}

fn radial(mm: f64) -> RollerDeviation {
    RollerDeviation {
        centre: CentreDeviation {
            radial_mm: mm,
            tangential_mm: 0.0,
        },
        radius_mm: 0.0,
    }
}

/// Crank angles over one full turn, off the grid points where rollers sit on a tooth tip.
fn turn(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| std::f64::consts::TAU * (k as f64 + 0.37) / n as f64)
        .collect()
}

/// A loaded scene of the paper's design: rollers, pins and a rigid bearing, linear law (the
/// Hertz law caps a flat flank's radius at Rp, which a test that moves Rp would feel).
fn loaded_scene(from_deg: f64, to_deg: f64, steps: usize, effects: &str) -> Scene {
    let text = PaperSpec::new()
        .scenes(&common::scene_item(
            "loaded",
            10.0,
            &format!("{{ from_deg: {from_deg:?}, to_deg: {to_deg:?}, steps: {steps} }}"),
            effects,
        ))
        .text()
        .to_string();
    cycloid::spec::parse("loaded.yaml", &text)
        .expect("valid")
        .scenes
        .remove(0)
}

fn run(design: &Design, m: &Modification, scene: &Scene) -> SceneResult {
    let plan = Plan::for_scene(scene);
    scene::run_design(design, m, (scene, &plan), &Default::default()).expect("solves")
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Every roller moved outward by dr is the nominal reducer with Rp + dr, its profile ground
/// with the shift ΔRp − dr so that the locus radius Rp + ΔRp (the disc as ground) is the same.
/// Gaps agree to 1e-10 mm: both are exact closest-point solutions (Newton to ~1e-15 relative of
/// Rp, ~1e-13 mm) of the same geometry formed in two ways; ignoring the deviation would be off
/// by dr = 20 µm. Loaded forces and lags agree to 1e-7 relative: the balances are solved to
/// 1e-9 relative, and the rest is that rounding through the solve.
#[test]
fn every_roller_moved_outward_is_a_larger_roller_circle() {
    let dr = 0.02;
    let mut moved = paper_design();
    moved.deviations = all_rollers(&moved, radial(dr));
    let mut larger = paper_design();
    larger.roller_circle_radius_mm += dr;
    let ground = Modification {
        shift_mm: PAPER_OPTIMUM.shift_mm - dr,
        ..PAPER_OPTIMUM
    };
    let (a, b) = (
        Mesh::new(&moved, &PAPER_OPTIMUM),
        Mesh::new(&larger, &ground),
    );
    let mut worst: f64 = 0.0;
    for phi in turn(37) {
        for i in 0..moved.rollers {
            let ga = a.roller_gap(i, &Pose::ideal(phi), None).unwrap();
            let gb = b.roller_gap(i, &Pose::ideal(phi), None).unwrap();
            worst = worst.max((ga.gap_mm - gb.gap_mm).abs());
            assert!((ga.arm_mm - gb.arm_mm).abs() < 1e-9, "arm of roller {i}");
        }
    }
    assert!(worst < 1e-10, "gaps differ by {worst:e} mm");
    // The clearance sweep follows each roller in its own frame (a second code path).
    let crank = turn(720);
    let (ca, cb) = (
        clearance::sweep(
            &a,
            &crank,
            clearance::Scope::Backlash,
            &cycloid::progress::Silent,
        )
        .unwrap(),
        clearance::sweep(
            &b,
            &crank,
            clearance::Scope::Backlash,
            &cycloid::progress::Silent,
        )
        .unwrap(),
    );
    assert!((ca.min.gap_mm - cb.min.gap_mm).abs() < 1e-10);
    let scene = loaded_scene(0.0, 108.0, 108, "roller_contact, output_pins, bearing");
    let (la, lb) = (
        run(&moved, &PAPER_OPTIMUM, &scene),
        run(&larger, &ground, &scene),
    );
    let (ra, rb) = (
        la.discs[0].loaded.rollers.as_ref().unwrap(),
        lb.discs[0].loaded.rollers.as_ref().unwrap(),
    );
    for (fa, fb) in ra.force_n.iter().zip(&rb.force_n) {
        let scale = fb.iter().fold(1.0_f64, |m, f| m.max(f.abs()));
        assert!(max_abs_diff(fa, fb) < 1e-7 * scale);
    }
    let lag_scale = rb.lag_rad.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    assert!(max_abs_diff(&ra.lag_rad, &rb.lag_rad) < 1e-7 * lag_scale);
}

/// Every roller moved counter-clockwise by dt along its circle is the housing turned by
/// α = dt/Rp. Turning the whole picture back by α, the rollers are nominal, the crank is at
/// φ − α and the disc at ψ − α: its lag behind its ideal rotation −(φ − α)/nc is
/// β − α·np/nc. So gap(φ, β = 0) as built = nominal gap at (φ − α, −α·np/nc), roller for
/// roller (tolerance as above; a deviation ignored would be off by ~dt·sin(pressure angle)).
#[test]
fn every_roller_moved_along_the_circle_is_a_turned_housing() {
    let dt = 0.03;
    let mut moved = paper_design();
    moved.deviations = all_rollers(
        &moved,
        RollerDeviation {
            centre: CentreDeviation {
                radial_mm: 0.0,
                tangential_mm: dt,
            },
            radius_mm: 0.0,
        },
    );
    let nominal = paper_design();
    let alpha = dt / nominal.roller_circle_radius_mm;
    let lag = -alpha * nominal.rollers as f64 / nominal.teeth as f64;
    let (a, b) = (
        Mesh::new(&moved, &PAPER_OPTIMUM),
        Mesh::new(&nominal, &PAPER_OPTIMUM),
    );
    let mut worst: f64 = 0.0;
    for phi in turn(37) {
        for i in 0..nominal.rollers {
            let ga = a.roller_gap(i, &Pose::ideal(phi), None).unwrap();
            let gb = b
                .roller_gap(i, &Pose::lagging(phi - alpha, lag), None)
                .unwrap();
            worst = worst.max((ga.gap_mm - gb.gap_mm).abs());
        }
    }
    assert!(worst < 1e-10, "gaps differ by {worst:e} mm");
    // Loaded, rollers and a rigid bearing (no pins: they are not turned with the housing):
    // the lag as built is the nominal lag at φ − α, plus α·np/nc.
    let effects = "roller_contact, bearing";
    let built = run(
        &moved,
        &PAPER_OPTIMUM,
        &loaded_scene(0.0, 36.0, 36, effects),
    );
    let from = (0.0 - alpha).to_degrees();
    let turned = run(
        &nominal,
        &PAPER_OPTIMUM,
        &loaded_scene(from, from + 36.0, 36, effects),
    );
    let (ra, rb) = (
        built.discs[0].loaded.rollers.clone().unwrap(),
        turned.discs[0].loaded.rollers.clone().unwrap(),
    );
    let shifted: Vec<f64> = rb.lag_rad.iter().map(|l| l - lag).collect();
    let scale = shifted.iter().fold(0.0_f64, |m, l| m.max(l.abs()));
    assert!(max_abs_diff(&ra.lag_rad, &shifted) < 1e-7 * scale);
}

/// One roller pushed by a small vector d changes its own gap by d·n to first order (n the
/// outward normal of the profile at its contact, in the fixed frame: the gap is the signed
/// distance of the roller centre), and no other roller's gap at all. The remainder r is the
/// distance field's second order: |r| ≤ |d|²·κmax/2 with κmax the largest |curvature| of the
/// roller-centre locus (its concave root, radius ~0.6 mm for the paper's design; the roller
/// centre sits micrometres from the locus, so the field's Hessian is ~κ there), bounded here
/// by |d|²·κmax; and r grows as |d|²: r(2d) = 4·r(d) to the third order's share, |d|·κmax
/// ≈ 0.2 % (5 % allowed). A gap that ignored the deviation has r = −d·n, which grows as |d|.
#[test]
fn one_roller_pushed_in_closes_its_own_gap_by_the_push() {
    let nominal = paper_design();
    let roller = 4;
    let locus = nominal.locus(&PAPER_OPTIMUM);
    let kmax = (0..=2000)
        .map(|k| locus.curvature_at(-1.0 + k as f64 / 1000.0).abs())
        .fold(0.0, f64::max);
    let mesh = |push: f64| {
        let mut moved = paper_design();
        moved.deviations.rollers = vec![RollerDeviation::default(); nominal.rollers];
        moved.deviations.rollers[roller].centre = CentreDeviation {
            radial_mm: -push * 0.6,
            tangential_mm: push * 0.8,
        };
        Mesh::new(&moved, &PAPER_OPTIMUM)
    };
    let b = Mesh::new(&nominal, &PAPER_OPTIMUM);
    let push = 1e-3;
    let (a, a2) = (mesh(push), mesh(2.0 * push));
    // |d|² = dr² + dt²·(1 + dr/Rp): the move follows the roller circle, not a chord, and |d|
    // differs from |(dr, dt)| by dt²·|dr|/(2·Rp·|d|) ≈ 6.4e-9 mm.
    let d = a.roller_centre(roller) - b.roller_centre(roller);
    assert!((d.norm() - push).abs() < 1e-8);
    let d2 = a2.roller_centre(roller) - b.roller_centre(roller);
    for phi in turn(29) {
        let pose = Pose::ideal(phi);
        for i in 0..nominal.rollers {
            let ga = a.roller_gap(i, &pose, None).unwrap();
            let gb = b.roller_gap(i, &pose, None).unwrap();
            if i != roller {
                assert_eq!(ga.gap_mm, gb.gap_mm, "roller {i} at {phi}");
                continue;
            }
            // The normal in the fixed frame: the disc frame's normal turned by ψ = −φ/nc.
            let psi = -phi / nominal.teeth as f64;
            let (s, c) = psi.sin_cos();
            let n = Vec2::new(
                c * gb.normal.x - s * gb.normal.y,
                s * gb.normal.x + c * gb.normal.y,
            );
            let r = ga.gap_mm - gb.gap_mm - d.dot(&n);
            let r2 = a2.roller_gap(i, &pose, None).unwrap().gap_mm - gb.gap_mm - d2.dot(&n);
            assert!(r.abs() <= push * push * kmax, "remainder {r:e} at {phi}");
            // 1e-12 mm: the rounding of the three gaps.
            assert!(
                (r2 - 4.0 * r).abs() <= 0.05 * (4.0 * r).abs() + 1e-12,
                "remainder {r:e}, doubled push {r2:e} at {phi}"
            );
        }
    }
}

/// A roller's own radius as built adds to its gap one for one (the gap is the distance to Γ
/// less the roller's radius), exactly up to rounding.
#[test]
fn a_larger_roller_closes_its_gap_by_its_growth() {
    let nominal = paper_design();
    let mut grown = paper_design();
    grown.deviations.rollers = vec![RollerDeviation::default(); nominal.rollers];
    grown.deviations.rollers[7].radius_mm = 0.004;
    let (a, b) = (
        Mesh::new(&grown, &PAPER_OPTIMUM),
        Mesh::new(&nominal, &PAPER_OPTIMUM),
    );
    for phi in turn(11) {
        let pose = Pose::ideal(phi);
        let (ga, gb) = (
            a.roller_gap(7, &pose, None).unwrap(),
            b.roller_gap(7, &pose, None).unwrap(),
        );
        // 1e-12 mm: the rounding of Rrp + 0.004 against 3 mm.
        assert!((ga.gap_mm - (gb.gap_mm - 0.004)).abs() < 1e-12);
    }
}

/// The crank's eccentricity e + de with the profile ground for e: the disc centre sits de
/// further out along e_φ, which is a bearing offset u = de·e_φ of the nominal reducer
/// (`Pose::centre_offset_mm`, a path the compliant bearing has long used).
#[test]
fn a_longer_crank_is_the_disc_centre_moved_outward() {
    let de = 0.005;
    let mut longer = paper_design();
    longer.deviations.eccentricity_mm = de;
    let nominal = paper_design();
    let (a, b) = (
        Mesh::new(&longer, &PAPER_OPTIMUM),
        Mesh::new(&nominal, &PAPER_OPTIMUM),
    );
    for phi in turn(23) {
        let mut offset = Pose::ideal(phi);
        offset.centre_offset_mm = Vec2::new(phi.cos(), phi.sin()) * de;
        for i in 0..nominal.rollers {
            let ga = a.roller_gap(i, &Pose::ideal(phi), None).unwrap();
            let gb = b.roller_gap(i, &offset, None).unwrap();
            assert!((ga.gap_mm - gb.gap_mm).abs() < 1e-12);
        }
    }
    // The crank's excess pushes the disc into the rollers on its eccentric side: less
    // clearance than nominal, by up to de (the normal of the contact nearest e_φ).
    let crank = turn(360);
    let (ca, cb) = (
        clearance::min_gap(&a, &crank).unwrap(),
        clearance::min_gap(&b, &crank).unwrap(),
    );
    assert!(ca.gap_mm < cb.gap_mm && ca.gap_mm > cb.gap_mm - de - 1e-12);
}

/// Every pin and every hole moved outward by the same dr is the nominal reducer with the pin
/// circle rw + dr: the pin forces, the output lag and the disc lag agree (solve tolerance).
#[test]
fn pins_and_holes_moved_outward_are_a_larger_pin_circle() {
    let dr = 0.01;
    let outward = CentreDeviation {
        radial_mm: dr,
        tangential_mm: 0.0,
    };
    let mut moved = paper_design();
    moved.deviations.pins = vec![outward; 6];
    moved.deviations.holes = vec![vec![outward; 6]];
    let mut larger = paper_design();
    larger.pins.circle_radius_mm += dr;
    let scene = loaded_scene(0.0, 108.0, 54, "roller_contact, output_pins, bearing");
    let (a, b) = (
        run(&moved, &PAPER_OPTIMUM, &scene),
        run(&larger, &PAPER_OPTIMUM, &scene),
    );
    let (pa, pb) = (
        a.discs[0].loaded.pins.clone().unwrap(),
        b.discs[0].loaded.pins.clone().unwrap(),
    );
    for (fa, fb) in pa.force_n.iter().zip(&pb.force_n) {
        let scale = fb.iter().fold(1.0_f64, |m, f| m.max(f.abs()));
        assert!(max_abs_diff(fa, fb) < 1e-7 * scale);
    }
    let ta = a.reducer.transmission.unwrap().te_rad;
    let tb = b.reducer.transmission.unwrap().te_rad;
    let scale = tb.iter().fold(0.0_f64, |m, t| m.max(t.abs()));
    assert!(max_abs_diff(&ta, &tb) < 1e-7 * scale);
}

/// A pin and its hole moved by the same vector are a pin in its hole as designed, only
/// elsewhere: at zero output lag the gap is unchanged, so a pin whose hole alone moves
/// carries a different load — the forces change, and the balance still holds (every
/// residual ≤ 1e-9, the documented solve tolerance).
#[test]
fn a_hole_moved_alone_changes_its_pins_load_and_keeps_the_balance() {
    let mut moved = paper_design();
    moved.deviations.holes = vec![vec![CentreDeviation::default(); 6]];
    moved.deviations.holes[0][2] = CentreDeviation {
        radial_mm: 0.0,
        tangential_mm: 0.004,
    };
    let scene = loaded_scene(0.0, 108.0, 54, "roller_contact, output_pins, bearing");
    let (a, b) = (
        run(&moved, &PAPER_OPTIMUM, &scene),
        run(&paper_design(), &PAPER_OPTIMUM, &scene),
    );
    let bearing = a.discs[0].loaded.bearing.as_ref().unwrap();
    assert!(bearing.residual.iter().all(|r| *r <= 1e-9));
    let (pa, pb) = (
        a.discs[0].loaded.pins.clone().unwrap(),
        b.discs[0].loaded.pins.clone().unwrap(),
    );
    let changed = max_abs_diff(&pa.force_n[2], &pb.force_n[2]);
    // 4 µm of a hole against a pin stiffness of ~7e5 N/mm: hundreds of newtons.
    assert!(changed > 10.0, "pin 2's force changed by {changed} N");
}

/// Symmetry shortcuts the parts as built break: a roller off its place makes the gaps repeat
/// only after a whole crank turn, so the whole-mesh minimum is sought over every angle (a
/// sweep of the first mesh period alone misses roller 6 pushed in at its worst angle).
#[test]
fn a_moved_roller_is_found_at_its_worst_angle_anywhere_in_the_turn() {
    let mut moved = paper_design();
    moved.deviations.rollers = vec![RollerDeviation::default(); 10];
    moved.deviations.rollers[6] = radial(-0.004);
    assert_eq!(moved.mesh_period_rad(), std::f64::consts::TAU);
    let mesh = Mesh::new(&moved, &PAPER_OPTIMUM);
    let crank: Vec<f64> = (0..3600).map(|k| (k as f64).to_radians() / 10.0).collect();
    let min = clearance::min_gap(&mesh, &crank).unwrap();
    let full = clearance::sweep(
        &mesh,
        &crank,
        clearance::Scope::Gaps,
        &cycloid::progress::Silent,
    )
    .unwrap();
    assert_eq!(min.roller, 6);
    assert_eq!(min.gap_mm, full.min.gap_mm);
    // Against the nominal minimum: pushed in by 4 µm radially, roller 6 loses at most 4 µm
    // and, the normal being within 60° of radial where the gap is smallest, at least 2 µm.
    let nominal = clearance::min_gap(&Mesh::new(&paper_design(), &PAPER_OPTIMUM), &crank).unwrap();
    let lost = nominal.gap_mm - min.gap_mm;
    assert!((0.002..=0.004 + 1e-12).contains(&lost), "lost {lost} mm");
}

/// Two discs of an even roller count share the torque equally when nominal (MODEL.md); a hole
/// of disc 1 off its place breaks the equality, and the shares still sum to the output torque.
#[test]
fn a_hole_of_one_disc_unbalances_the_shares() {
    let spec = PaperSpec::new()
        .edit("  rollers: 10 ", "  rollers: 10\n  discs: 2 ")
        .scenes(&common::scene_item(
            "two",
            10.0,
            "{ from_deg: 0.0, to_deg: 36.0, steps: 18 }",
            "roller_contact, output_pins, bearing",
        ))
        .parse("two.yaml");
    let mut design = spec.design.clone();
    design.deviations.holes = vec![vec![CentreDeviation::default(); 6]; 2];
    design.deviations.holes[1][0] = CentreDeviation {
        radial_mm: 0.003,
        tangential_mm: -0.003,
    };
    let r = run(&design, &spec.modification, &spec.scenes[0]);
    let shares: Vec<&Vec<f64>> = r
        .discs
        .iter()
        .map(|d| d.loaded.torque_nmm.as_ref().unwrap())
        .collect();
    let mut unequal: f64 = 0.0;
    for (t0, t1) in shares[0].iter().zip(shares[1]) {
        // Shares sum to T within the coupled solve's guard, 1e-9 of T.
        assert!((t0 + t1 - 10_000.0).abs() <= 1e-9 * 10_000.0);
        unequal = unequal.max((t0 - t1).abs());
    }
    assert!(unequal > 1.0, "shares differ by at most {unequal} N·mm");
}

/// The three code paths that meet a roller — the closest point from scratch
/// (`Mesh::roller_gap`), the clearance sweep that follows each roller in its frame, and the
/// loaded contact (`Rollers::evaluate`) — see the same parts as built: a longer crank, a roller
/// moved and one grown, a form error on the disc. And the pins see the longer crank as the nominal pins see the disc
/// centre moved by de·e_φ. Agreement to 1e-12 mm: the same geometry formed in different
/// orders (a few ulp of Rp); a path that ignored any one deviation would be off by microns.
#[test]
fn every_path_sees_the_same_parts_as_built() {
    use cycloid::equilibrium::{pins::Pins, rollers::Rollers};
    use cycloid::model::{ContactLaw, GeometryMode};
    let mut built = paper_design();
    built.deviations.eccentricity_mm = -0.003;
    built.deviations.rollers = vec![RollerDeviation::default(); 10];
    built.deviations.rollers[2] = radial(0.002);
    built.deviations.rollers[5].radius_mm = -0.005;
    built.deviations.form = form();
    let mesh = Mesh::new(&built, &PAPER_OPTIMUM);
    let rollers = Rollers::new(
        &built,
        &PAPER_OPTIMUM,
        ContactLaw::PaperLinear,
        GeometryMode::Exact,
    );
    let crank = turn(64);
    let sweep = clearance::sweep(
        &mesh,
        &crank,
        clearance::Scope::Gaps,
        &cycloid::progress::Silent,
    )
    .unwrap();
    let mut states = Vec::new();
    for (k, &phi) in crank.iter().enumerate() {
        for lag in [0.0, 2e-4] {
            let pose = Pose::lagging(phi, lag);
            states.clear();
            rollers.evaluate(&pose, &mut states).unwrap();
            for (i, st) in states.iter().enumerate() {
                let g = mesh.roller_gap(i, &pose, None).unwrap();
                assert!(
                    (st.gap_mm - g.gap_mm).abs() < 1e-12,
                    "roller {i} at {phi}, lag {lag}"
                );
                assert!((st.arm_mm - g.arm_mm).abs() < 1e-9, "arm of roller {i}");
                if lag == 0.0 {
                    assert!((sweep.gap_mm[i][k] - g.gap_mm).abs() < 1e-12);
                }
            }
        }
    }
    let nominal_pins = Pins::new(&paper_design(), ContactLaw::PaperLinear);
    let built_pins = Pins::new(&built, ContactLaw::PaperLinear);
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for phi in turn(16) {
        let psi = -phi / 9.0;
        let de = Vec2::new(phi.cos(), phi.sin()) * built.deviations.eccentricity_mm;
        let (e_phi, rotation) = (cycloid::geometry::unit(phi), psi.sin_cos());
        built_pins.evaluate_at(e_phi, rotation, Vec2::zeros(), 1e-4, &mut a);
        nominal_pins.evaluate_at(e_phi, rotation, de, 1e-4, &mut b);
        for (p, q) in a.iter().zip(&b) {
            assert!((p.gap_mm - q.gap_mm).abs() < 1e-12 && (p.arm_mm - q.arm_mm).abs() < 1e-12);
        }
    }
}

/// A spec with `reducer.deviations`, end to end. At crank 216° roller 6 (at 216°), the disc
/// centre and the input axis are on one line and roller 6 faces a tooth root, where the gap
/// has the closed form (MODEL.md "Clearance": ΔRrp − ΔRp at tip and root) with every
/// deviation along that line: (ΔRrp + its grinding error) − ΔRp + the roller's radial
/// deviation − the crank's: 0.1593 − 0.001 − 0.125 − 0.004 − 0.002 = 0.0273 mm. Roller 6
/// pushed in and the disc pushed towards it, that is the smallest gap of the whole turn
/// (the nominal minimum, 34.3 µm, is at the roots too). `--explain` lists every deviation.
#[test]
fn a_spec_with_deviations_checks_the_reducer_as_built() {
    let text = PaperSpec::new()
        .edit(
            "  material:",
            "  deviations:\n    eccentricity_mm: 0.002\n    rollers: [{ index: 6, radial_mm: -0.004 }]\n    \
             holes: [{ index: 2, tangential_mm: 0.003 }]\n    equidistant_mm: -0.001\n  material:",
        )
        .scenes(&common::scene_item(
            "turn",
            10.0,
            "{ from_deg: 0.0, to_deg: 360.0, steps: 720 }",
            "clearance, roller_contact, output_pins, bearing",
        ))
        .text()
        .to_string();
    let dir = common::Scratch::new("deviations-spec");
    dir.write("built.yaml", &text);
    let run = common::cycloid(
        dir.join("").as_path(),
        &["check", "built.yaml", "--json", "out.json"],
    );
    assert_eq!(run.code(), 0, "{}{}", run.stdout, run.stderr);
    let json: serde_json::Value = serde_json::from_str(&dir.read("out.json")).unwrap();
    let scene = &json["scenes"][0];
    // 1e-12 mm: the exact gap's rounding (a few ulp of Rp).
    let min = scene["min_clearance_mm"].as_f64().unwrap();
    assert!((min - 0.0273).abs() < 1e-12, "{min}");
    assert_eq!(scene["min_clearance_at"]["roller"], 6);
    assert_eq!(scene["min_clearance_at"]["crank_deg"], 216.0);
    let explain = common::cycloid(
        dir.join("").as_path(),
        &["check", "built.yaml", "--explain"],
    );
    let expected = "parts as built (reducer.deviations), in force in every scene, exact geometry; \
         gaps repeat every 360.0°, loaded curves with the pins every 3240°:\n  \
         deviation crank eccentricity +2.000 µm\n  \
         deviation grinding: shift +0.000 µm, equidistant -1.000 µm\n  \
         deviation roller 6: radial -4.000 µm, tangential +0.000 µm, radius +0.000 µm\n  \
         deviation disc 0 hole 2: radial +0.000 µm, tangential +3.000 µm\n";
    assert!(explain.stdout.contains(expected), "{}", explain.stdout);
}

/// A form error of three harmonics (orders 3, 11 and 40; 2, 1.5 and 0.8 µm), enough to bend
/// the flank visibly at order 40 (w'' up to 1.3 mm/rad²).
fn form() -> Vec<cycloid::model::FormTerm> {
    use cycloid::model::FormTerm;
    vec![
        FormTerm {
            order: 3,
            cos_mm: 0.002,
            sin_mm: -0.0005,
        },
        FormTerm {
            order: 11,
            cos_mm: -0.001,
            sin_mm: 0.0011,
        },
        FormTerm {
            order: 40,
            cos_mm: 0.0006,
            sin_mm: 0.0005,
        },
    ]
}

/// The formed profile's tangent and curvature (closed forms from the locus's Frenet frame)
/// against central differences of its points: h = 1e-4 rad, truncation h²/6·|Γ'''| ≈ 1e-6
/// of |Γ'| and h²/12·|Γ''''| for the second difference, well inside 1e-5 relative; the
/// curvature through both differences to 1e-4 relative (a missing w'' term is 10 % off at
/// order 40).
#[test]
fn the_formed_profile_has_the_tangent_and_curvature_of_its_points() {
    use cycloid::geometry::profile::Profile;
    let p = Profile::new(&paper_design(), &PAPER_OPTIMUM).with_form(&form());
    let h = 1e-4;
    for k in 0..97 {
        let t = std::f64::consts::TAU * (k as f64 + 0.3) / 97.0;
        let (a, b, c) = (p.point(t - h), p.point(t), p.point(t + h));
        let d1 = (c - a) / (2.0 * h);
        let d2 = (c - 2.0 * b + a) / (h * h);
        let tangent = p.tangent(t);
        assert!(
            (tangent - d1).norm() < 1e-5 * tangent.norm(),
            "tangent at {t}"
        );
        let fd_curvature = cycloid::geometry::cross(d1, d2) / d1.norm().powi(3);
        let curvature = p.curvature(t);
        assert!(
            (curvature - fd_curvature).abs() < 1e-4 * curvature.abs().max(0.01),
            "curvature at {t}: {curvature} vs {fd_curvature}"
        );
        // The normal is the tangent turned clockwise: outward of a counter-clockwise profile.
        let n = p.normal(t);
        assert!(
            n.dot(&tangent).abs() < 1e-12 * tangent.norm()
                && cycloid::geometry::cross(tangent, n) < 0.0
        );
    }
}

/// A roller's gap on the disc with a form error is its distance to the formed profile, less
/// its radius: against a search over the points of the series (golden section on |q − Γ(t)|,
/// Γ from the offset curve and w summed from its harmonics, not the profile's table,
/// within ±0.05 rad of the foot, to the argument's round-off), 1e-9 mm. And a form error of
/// order 0 — a constant w, not allowed in a spec but a limit case here — is an equidistant
/// modification of that size: gaps to 1e-12 mm.
#[test]
fn the_gap_with_a_form_error_is_the_distance_to_the_formed_profile() {
    let mut built = paper_design();
    built.deviations.form = form();
    let mesh = Mesh::new(&built, &PAPER_OPTIMUM);
    let drawn = cycloid::geometry::profile::Profile::new(&built, &PAPER_OPTIMUM);
    for phi in turn(41) {
        let pose = Pose::lagging(phi, 1e-4);
        for i in 0..built.rollers {
            let g = mesh.roller_gap(i, &pose, None).unwrap();
            let q = mesh.roller_in_disc(i, &pose);
            // The formed point from the series itself, not the profile's table: the offset
            // curve's point moved inward by w(t) along its normal.
            let dist = |t: f64| {
                let w = mesh.profile.form().series_jet(t).0;
                (q - (drawn.point(t) - drawn.normal(t) * w)).norm()
            };
            let t = common::golden_section_min(dist, g.t - 0.05, g.t + 0.05);
            let expected = dist(t) - mesh.roller_radius(i);
            assert!(
                (g.gap_mm - expected).abs() < 1e-9,
                "roller {i} at {phi}: {} vs {expected}",
                g.gap_mm
            );
        }
    }
    let mut constant = paper_design();
    constant.deviations.form = vec![cycloid::model::FormTerm {
        order: 0,
        cos_mm: 0.003,
        sin_mm: 0.0,
    }];
    let thinner = Modification {
        equidistant_mm: PAPER_OPTIMUM.equidistant_mm + 0.003,
        ..PAPER_OPTIMUM
    };
    let (a, b) = (
        Mesh::new(&constant, &PAPER_OPTIMUM),
        Mesh::new(&paper_design(), &thinner),
    );
    for phi in turn(13) {
        for i in 0..10 {
            let pose = Pose::ideal(phi);
            let (ga, gb) = (
                a.roller_gap(i, &pose, None).unwrap(),
                b.roller_gap(i, &pose, None).unwrap(),
            );
            assert!((ga.gap_mm - gb.gap_mm).abs() < 1e-12);
        }
    }
}

/// `check` with `measured_profile:` runs its scenes on the disc as built. Points are drawn from
/// a known disc — the paper's optimum with the three-harmonic form error of `form()` — in a
/// machine frame (moved by (5, −3) mm, turned by 17°), 3,600 of them printed to round-trip;
/// the spec starts the fit elsewhere (0.1, 0.15 mm). Its min clearance over a whole turn of the
/// disc (3240°, where every roller has met every tooth) must be that of the known disc given
/// directly as `modification` and `reducer.deviations.form`: the fit recovers the generating
/// parameters from noise-free points (to ~1e-9 mm), and the minimum over the whole turn does
/// not depend on which tooth the fit counts first. 1e-7 mm covers the fit's convergence (it
/// agrees to 2e-15 mm); a check that ran on the spec's own modification would be ~20 µm off
/// (tip clearance 50 µm), the known disc without its form error 4.2 µm (34.30 against
/// 30.10 µm).
#[test]
fn check_with_a_measured_profile_runs_on_the_disc_as_built() {
    use cycloid::geometry::profile::Profile;
    let truth = Profile::new(&paper_design(), &PAPER_OPTIMUM).with_form(&form());
    let (s, c) = 17f64.to_radians().sin_cos();
    let mut csv = String::from("x_mm,y_mm\n");
    for k in 0..3600 {
        let p = truth.point(std::f64::consts::TAU * k as f64 / 3600.0);
        let q = Vec2::new(c * p.x - s * p.y + 5.0, s * p.x + c * p.y - 3.0);
        csv += &format!("{:?},{:?}\n", q.x, q.y);
    }
    let scene = common::scene_item(
        "turn",
        10.0,
        "{ from_deg: 0.0, to_deg: 3240.0, steps: 6480 }",
        "clearance",
    );
    let dir = common::Scratch::new("as-built-check");
    dir.write("points.csv", &csv);
    let measured = PaperSpec::new()
        .modification(0.1, 0.15)
        .scenes(&scene)
        .with("measured_profile: {file: points.csv, format: csv, harmonics: 45, fit: [shift_mm, equidistant_mm]}\n");
    dir.write("measured.yaml", measured.text());
    let terms: Vec<String> = form()
        .iter()
        .map(|f| {
            format!(
                "{{ order: {}, cos_mm: {:?}, sin_mm: {:?} }}",
                f.order, f.cos_mm, f.sin_mm
            )
        })
        .collect();
    let known = PaperSpec::new().scenes(&scene).edit(
        "  material:",
        &format!(
            "  deviations:\n    form: [{}]\n  material:",
            terms.join(", ")
        ),
    );
    dir.write("known.yaml", known.text());
    let min = |spec: &str| {
        let run = common::cycloid(
            &dir.path,
            &["check", spec, "--json", &format!("{spec}.json")],
        );
        assert_eq!(run.code(), 0, "{}{}", run.stdout, run.stderr);
        let json: serde_json::Value =
            serde_json::from_str(&dir.read(&format!("{spec}.json"))).unwrap();
        (
            json["scenes"][0]["min_clearance_mm"].as_f64().unwrap(),
            run.stdout,
        )
    };
    let ((as_built, stdout), (direct, _)) = (min("measured.yaml"), min("known.yaml"));
    assert!((as_built - direct).abs() < 1e-7, "{as_built} vs {direct}");
    assert!(
        stdout.contains("as built: the scenes run on the disc identified from `"),
        "{stdout}"
    );
    // The design review puts the disc as designed beside as built: the spec's modification
    // (tip clearance 0.15 − 0.1 = 50 µm, its min clearance) against the identified one and
    // the min clearance as built, and the deviation figure.
    let run = common::cycloid(&dir.path, &["check", "measured.yaml", "--report", "review"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    let page = dir.read("review/index.html");
    let section = &page[page
        .find("Disc as built</h2>")
        .expect("the as-built section")..];
    let row = |label: &str| {
        let at = section
            .find(label)
            .unwrap_or_else(|| panic!("{label} in {section}"));
        section[at..section[at..].find("</tr>").unwrap() + at].to_string()
    };
    assert!(row("shift ΔRp").contains("0.1000 mm") && row("shift ΔRp").contains("0.1250 mm"));
    // Changes in µm to the nanometre, signed as the results' changes are: 25 µm more shift
    // and 9.3 µm more equidistant (0.1593 against 0.15 mm); noise-free points leave a residual
    // at the fit's round-off (~1e-12 mm), which reads as zero, not as 1e-9 µm or −0.000.
    assert!(
        row("shift ΔRp").contains(">+25.000 µm<"),
        "{}",
        row("shift ΔRp")
    );
    assert!(
        row("equidistant ΔRrp").contains(">+9.300 µm<"),
        "{}",
        row("equidistant ΔRrp")
    );
    let form_row = row("<th>form error");
    assert!(form_row.contains("residual RMS 0.000 µm"), "{form_row}");
    assert!(
        row("min clearance").contains("0.05000 mm") && row("min clearance").contains("0.03010 mm")
    );
    assert!(dir.exists("review/as-built-deviation.svg"));
    // `fit --write` writes the identified form into `reducer.deviations.form`: the amplitudes
    // of the three harmonics come back (their phases depend on which tooth the fit counts
    // first, the amplitudes do not), every other order of the series is zero, to 1e-9 mm
    // (noise-free points).
    let run = common::cycloid(&dir.path, &["fit", "measured.yaml", "--write", "out.yaml"]);
    assert_eq!(run.code(), 0, "{}", run.stderr);
    assert!(run
        .stdout
        .contains("wrote out.yaml with the identified modification and form error"));
    let written = cycloid::spec::parse("out.yaml", &dir.read("out.yaml")).unwrap();
    let amplitude = |order: usize| {
        written
            .design
            .deviations
            .form
            .iter()
            .find(|f| f.order == order)
            .map_or(0.0, |f| f.amplitude_mm())
    };
    for f in form() {
        assert!(
            (amplitude(f.order) - f.amplitude_mm()).abs() < 1e-9,
            "order {}",
            f.order
        );
    }
    let others: f64 = written
        .design
        .deviations
        .form
        .iter()
        .filter(|f| ![3, 11, 40].contains(&f.order))
        .map(|f| f.amplitude_mm())
        .fold(0.0, f64::max);
    assert!(others < 1e-9, "{others}");
    // The form error matters: the known disc without it is microns away.
    let plain = PaperSpec::new().scenes(&scene);
    dir.write("plain.yaml", plain.text());
    assert!((min("plain.yaml").0 - direct).abs() > 1e-3);
}

/// A crank longer than the pin holes were bored for (issue 26): a hole's radius is pin + e +
/// c, the pin's centre sits e + de from the hole's, so with de > c every pin is pressed de − c
/// into its hole at every crank angle. At zero torque nothing else loads the disc (its rollers
/// sit at the touch of T → 0⁺, the pins' moments cancel by symmetry, βo = 0), and all six pins
/// push along the eccentric direction: the crank bearing carries M·k·(de − c), k = (π/4)·E*·L
/// = 7.1117e5 N/mm, 8534 N for de = 2 µm and c = 0 (1e-9 relative: gaps of micrometres formed
/// to ~1e-16 mm). The run says so in a note naming the depth, and no note is given once the
/// clearance takes the longer crank up.
#[test]
fn a_crank_longer_than_the_holes_allow_preloads_every_pin_and_says_so() {
    let dir = common::Scratch::new("pin-preload");
    let k = 0.25 * std::f64::consts::PI * 206_000.0 / (2.0 * (1.0 - 0.09)) * 8.0;
    for (clearance, depth_um) in [(0.0, Some("2.000")), (0.0005, Some("1.500")), (0.003, None)] {
        let text = PaperSpec::new()
            .edit(
                "hole_clearance_mm: 0.0 ",
                &format!("hole_clearance_mm: {clearance:?} "),
            )
            .edit(
                "modification:\n",
                "  deviations: { eccentricity_mm: 0.002 }\nmodification:\n",
            )
            .scenes(
                "  - name: idle\n    output_torque_nm: 0.0\n    crank: { from_deg: 0.0, to_deg: \
                 36.0, steps: 6 }\n    effects: [bearing]\n",
            )
            .text()
            .to_string();
        dir.write("s.yaml", &text);
        let run = common::cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]);
        assert_eq!(run.code(), 0, "{}{}", run.stdout, run.stderr);
        let note = run.stdout.lines().find(|l| l.contains("pressed"));
        match depth_um {
            Some(depth) => {
                let note = note.unwrap_or_else(|| panic!("no note in {}", run.stdout));
                assert!(
                    note.starts_with(
                        "note: scene `idle`: `reducer.deviations` make the crank \
                                      longer than the pin holes were bored for"
                    ) && note.contains(&format!("every output pin is pressed {depth} µm")),
                    "{note}"
                );
                let json: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
                let force = json["scenes"][0]["bearing_force_n"].as_array().unwrap();
                let expected = 6.0 * k * (0.002 - clearance);
                for f in force {
                    let f = f.as_f64().unwrap();
                    assert!((f - expected).abs() <= 1e-9 * expected, "{f} vs {expected}");
                }
            }
            None => assert!(note.is_none(), "{}", run.stdout),
        }
    }
}

/// A tolerance study that draws the crank's eccentricity (band b, normal: drawn up to the cut
/// at 6σ = 2b) with zero hole clearance says that its longest cranks press every pin by up to
/// 2b (4 µm for b = 2 µm); with a clearance above 2b no draw reaches the pins.
#[test]
fn a_study_drawing_a_longer_crank_says_its_pins_are_preloaded() {
    let dir = common::Scratch::new("pin-preload-study");
    for (clearance, said) in [(0.0, true), (0.005, false)] {
        let text = PaperSpec::new()
            .edit(
                "hole_clearance_mm: 0.0 ",
                &format!("hole_clearance_mm: {clearance:?} "),
            )
            .scenes(
                "  - name: rated\n    output_torque_nm: 10.0\n    crank: { from_deg: 0.0, to_deg: \
                 108.0, steps: 12 }\n    effects: [bearing]\n",
            )
            .with(
                "limits:\n  max_bearing_force_n: 1.0e6\ntolerances:\n  scene: rated\n  \
                 eccentricity_mm: 0.002\n  samples: 4\n  max_failure_rate: 0.5\n",
            )
            .text()
            .to_string();
        dir.write("s.yaml", &text);
        let run = common::cycloid(&dir.path, &["tolerance", "s.yaml"]);
        assert!(
            run.code() == 0 || run.code() == 1,
            "{}{}",
            run.stdout,
            run.stderr
        );
        let note = "note: scene `rated`: samples drawn with the crank longer than the pin holes \
                    were bored for (e + hole clearance): every output pin is pressed up to 4.000 \
                    µm into its hole";
        assert_eq!(run.stdout.contains(note), said, "{}", run.stdout);
    }
}
