//! The lean first-order sweep (`equilibrium::first_order_sweep`) against the general solve of
//! the same model (`angle::solve_angle`, which builds every roller and pin state, takes Hertz
//! from `Rollers::hertz` and the residual from `residual::residual`). Both evaluate the same
//! closed forms, so they must agree to round-off; what differs is how: the lean kernel takes
//! the contact curvature from cos(φi + nc·β) instead of cos(nc·t), forms the normal from S
//! instead of normalising, settles the root from its own Newton step, and records only what
//! the curves need. Tolerances below are round-off bounds of those differences.

use approx::relative_eq;
use cycloid::equilibrium::angle::solve_angle;
use cycloid::equilibrium::discs_sweep;
use cycloid::equilibrium::first_order_sweep::{FirstOrderSweep, Row, Scratch};
use cycloid::equilibrium::loaded::{AngleSolution, Model};
use cycloid::equilibrium::residual::residual;
use cycloid::model::results::LoadedSweep;
use cycloid::model::{ContactLaw, GeometryMode};
use cycloid::spec::{self, Spec};

/// The spec's scene `scene` as a first-order, linear-law, rigid-bearing model with rollers,
/// pins and bearing: the models the lean sweep applies to.
fn model(spec: &Spec, scene: usize) -> Model {
    let mut s = spec.scenes[scene].clone();
    s.geometry = GeometryMode::FirstOrder;
    s.contact_law = ContactLaw::PaperLinear;
    s.bearing_stiffness_n_per_mm = None;
    Model::new(
        &spec.design,
        &spec.modification,
        &s,
        &cycloid::model::Plan::of("rated", &[cycloid::model::Effect::Bearing]),
    )
}

fn load(path: &str) -> Spec {
    spec::load(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn grid(spec: &Spec, scene: usize, n: usize) -> Vec<f64> {
    let s = &spec.scenes[scene];
    let (from, to) = (s.crank_from_deg.to_radians(), s.crank_to_deg.to_radians());
    (0..n)
        .map(|k| from + (to - from) * k as f64 / n as f64)
        .collect()
}

/// The general solve, angle by angle, warm-started from the previous angle.
fn general(model: &Model, angles: &[f64]) -> Vec<AngleSolution> {
    let mut previous = AngleSolution::default();
    angles
        .iter()
        .map(|&phi| {
            let sol = solve_angle(model, phi, &previous).expect("general solve");
            previous = sol.clone();
            sol
        })
        .collect()
}

/// Each column as a slice (a row of one angle for `Row`).
fn slices(columns: &mut [Vec<f64>]) -> Vec<&mut [f64]> {
    columns.iter_mut().map(|v| v.as_mut_slice()).collect()
}

/// The kernel alone at crank `phi`, its one-angle rows in `columns` (roller forces, pressures,
/// half-widths, pin forces; zeroed first: the kernel writes the entries of contacts only).
fn solve_one(
    lean: &FirstOrderSweep,
    phi: f64,
    guess: (f64, f64),
    scratch: &mut Scratch,
    columns: &mut [Vec<Vec<f64>>; 4],
) -> Option<cycloid::equilibrium::first_order_sweep::Summary> {
    for c in columns.iter_mut() {
        c.iter_mut().for_each(|v| v[0] = 0.0);
    }
    let [f, p, w, pf] = columns;
    let (mut f, mut p, mut w, mut pf) = (slices(f), slices(p), slices(w), slices(pf));
    let mut row = Row {
        k: 0,
        roller_force_n: &mut f,
        pressure_mpa: &mut p,
        half_width_mm: &mut w,
        pin_force_n: &mut pf,
    };
    lean.solve(phi, (phi.cos(), phi.sin()), || guess, scratch, &mut row)
}

/// One-angle rows for `solve_one`: `rollers` and `pins` columns of one entry.
fn one_angle_columns(rollers: usize, pins: usize) -> [Vec<Vec<f64>>; 4] {
    [rollers, rollers, rollers, pins].map(|n| vec![vec![0.0; 1]; n])
}

/// The lean sweep's curves agree with the general solve at every angle.
///
/// Tolerances: lags 1e-12 relative (two exact roots of the same piecewise-linear balance,
/// reached from different guesses: round-off of Σ k·l·g over the contacts, ~1e-15 relative);
/// forces 1e-9 relative plus 1e-6 N (k·|l|·δβ with k ~ 1e6 N/mm, |l| ≤ e·nc, δβ the lag's
/// round-off; a contact that is just closing has a force of that size in one and 0 in the other);
/// pressures and half-widths compared squared, as p² = F·E*/(πLR*) and b² = 4F·R*/(πLE*) are
/// linear in F: 1e-9 relative plus the force tolerance times the largest p²/F (b²/F); the
/// number of contacts equal, unless a contact is just closing (a force within the force
/// tolerance in one of the two); bearing force 1e-9 relative plus 1e-5 N (the sum of up to
/// 2·np force tolerances), and its angle from e_φ within that error over the force's magnitude
/// (plus 1e-14 rad for the angle's own round-off); residual ≤ 1e-9 in both (the product's
/// bound).
fn assert_agrees(name: &str, model: &Model, angles: &[f64], lean: &LoadedSweep) {
    let solutions = general(model, angles);
    let rollers = lean.rollers.as_ref().expect("rollers");
    let pins = lean.pins.as_ref().expect("pins");
    let bearing = lean.bearing.as_ref().expect("bearing");
    let r = model.rollers.as_ref().unwrap();
    let hertz: Vec<Vec<(f64, f64, f64)>> = solutions
        .iter()
        .map(|s| {
            s.rollers
                .iter()
                .map(|st| {
                    let h = r.hertz(st);
                    (st.force_n, h.peak_pressure_mpa, h.half_width_mm)
                })
                .collect()
        })
        .collect();
    let largest_per_force = |value: fn(&(f64, f64, f64)) -> f64| {
        hertz
            .iter()
            .flatten()
            .filter(|h| h.0 > 1e-3)
            .map(|h| value(h).powi(2) / h.0)
            .fold(0.0, f64::max)
    };
    let (p2_per_force, b2_per_force) = (largest_per_force(|h| h.1), largest_per_force(|h| h.2));
    for (k, (sol, &phi)) in solutions.iter().zip(angles).enumerate() {
        let at = format!("{name}: crank {:.4}°", phi.to_degrees());
        let (lag, out) = (sol.lag_rad.unwrap(), sol.output_lag_rad.unwrap());
        assert!(
            relative_eq!(
                rollers.lag_rad[k],
                lag,
                epsilon = 1e-300,
                max_relative = 1e-12
            ),
            "{at}: β {} vs {lag}",
            rollers.lag_rad[k]
        );
        assert!(
            relative_eq!(
                pins.output_lag_rad[k],
                out,
                epsilon = 1e-300,
                max_relative = 1e-12
            ),
            "{at}: βo {} vs {out}",
            pins.output_lag_rad[k]
        );
        for (i, &(force, p, b)) in hertz[k].iter().enumerate() {
            let (lf, lp) = (rollers.force_n[i][k], rollers.pressure_mpa[i][k]);
            let lb = rollers.half_width_mm[i][k];
            let b2_tol = 1e-9 * (lb * lb).max(b * b) + 1e-6 * b2_per_force;
            assert!(
                (lb * lb - b * b).abs() <= b2_tol,
                "{at}: roller {i} half-width {lb} vs {b}"
            );
            assert!(
                relative_eq!(lf, force, epsilon = 1e-6, max_relative = 1e-9),
                "{at}: roller {i} force {lf} vs {force}"
            );
            let p2_tol = 1e-9 * (lp * lp).max(p * p) + 1e-6 * p2_per_force;
            assert!(
                (lp * lp - p * p).abs() <= p2_tol,
                "{at}: roller {i} pressure {lp} vs {p}"
            );
        }
        for (j, st) in sol.pins.iter().enumerate() {
            let lf = pins.force_n[j][k];
            assert!(
                relative_eq!(lf, st.force_n, epsilon = 1e-6, max_relative = 1e-9),
                "{at}: pin {j} force {lf} vs {}",
                st.force_n
            );
        }
        let contacts =
            |f: &dyn Fn(usize) -> f64| (0..hertz[k].len()).filter(|&i| f(i) > 0.0).count();
        let (lean_contacts, general_contacts) = (
            contacts(&|i| rollers.force_n[i][k]),
            contacts(&|i| hertz[k][i].0),
        );
        let closing = (0..hertz[k].len()).any(|i| {
            let (lf, f) = (rollers.force_n[i][k], hertz[k][i].0);
            (lf > 0.0) != (f > 0.0) && lf.max(f) <= 1e-6
        });
        assert!(
            rollers.contacts[k] == lean_contacts && (lean_contacts == general_contacts || closing),
            "{at}: contacts {} ({lean_contacts} forces) vs {general_contacts}",
            rollers.contacts[k]
        );
        let fb = sol.bearing_force_n.unwrap();
        assert!(
            relative_eq!(
                bearing.force_n[k],
                fb.norm(),
                epsilon = 1e-5,
                max_relative = 1e-9
            ),
            "{at}: bearing {} vs {}",
            bearing.force_n[k],
            fb.norm()
        );
        if fb.norm() > 0.0 {
            let e = cycloid::geometry::Vec2::new(phi.cos(), phi.sin());
            let angle = (e.x * fb.y - e.y * fb.x).atan2(e.dot(&fb));
            let turn = (bearing.angle_rad[k] - angle + std::f64::consts::PI)
                .rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            let tol = 1e-9 + 1e-5 / fb.norm() + 1e-14;
            assert!(
                turn.abs() <= tol,
                "{at}: bearing angle {} vs {angle}",
                bearing.angle_rad[k]
            );
        }
        assert!(
            bearing.residual[k] <= 1e-9,
            "{at}: lean residual {}",
            bearing.residual[k]
        );
        assert!(
            residual(model, phi, sol, fb) <= 1e-9,
            "{at}: general residual"
        );
    }
}

/// The paper design at its rated torque: every angle settles in the lean kernel itself (no
/// fallback to the general solve), and the kernel agrees with the general solve.
#[test]
fn kernel_settles_every_angle_of_the_paper_design_and_agrees() {
    let spec = load("specs/paper.yaml");
    let scene = spec.scenes.iter().position(|s| s.name == "rated").unwrap();
    let model = model(&spec, scene);
    let lean = FirstOrderSweep::new(&model).expect("the lean sweep applies");
    let angles = grid(&spec, scene, 720);
    let (nr, np) = (
        model.rollers.as_ref().unwrap().count(),
        model.pins.as_ref().unwrap().count,
    );
    let mut scratch = Scratch::default();
    let mut columns = one_angle_columns(nr, np);
    let mut guess = (0.0, 0.0);
    for &phi in &angles {
        let s = solve_one(&lean, phi, guess, &mut scratch, &mut columns)
            .unwrap_or_else(|| panic!("fell back at {:.3}°", phi.to_degrees()));
        guess = (s.lag_rad, s.output_lag_rad);
        // Balance of the recorded forces, independently of the kernel's own residual: the
        // rollers' moment about the disc centre equals the torque (1e-9, the product bound).
        let sol = solve_angle(&model, phi, &AngleSolution::default()).unwrap();
        let moment: f64 = columns[0]
            .iter()
            .zip(&sol.rollers)
            .map(|(f, st)| f[0] * st.arm_mm)
            .sum();
        assert!(
            relative_eq!(moment, model.torque_nmm, epsilon = 0.0, max_relative = 1e-9),
            "moment {moment} at {phi}"
        );
    }
    let (sweep, _) = crate::common::one_disc_sweep(&model, &angles, false).unwrap();
    assert_agrees("paper", &model, &angles, &sweep);
}

/// Cases that exercise the fall-back to the general solve (zero torque, a torque so small
/// that the balance straddles it, more than 64 rollers for the kernel's active-set mask) and
/// cases with unusual load sharing: the sweep still agrees angle by angle.
#[test]
fn sweep_agrees_with_the_general_solve_on_hard_cases() {
    for case in [
        "torque-1e-6",
        "preload-zero-torque",
        "zero-modification",
        "rollers-80",
        "rollers-4",
        "hole-clearance",
        "k1-0.95",
        "multi-revolution",
    ] {
        let spec = load(&format!("specs/hard/{case}.yaml"));
        // The spec's first scene, whatever its effects: the model asks for everything.
        let scene = 0;
        let model = model(&spec, scene);
        let angles = grid(&spec, scene, 240);
        let (sweep, _) = crate::common::one_disc_sweep(&model, &angles, false)
            .unwrap_or_else(|f| panic!("{case}: {:?}", f.failure));
        assert_agrees(case, &model, &angles, &sweep);
    }
}

/// Chunks are solved from nothing before them, with scratch space reused across the chunks a
/// thread takes: the curves are the same bit for bit on one thread (every chunk after the first
/// inherits the scratch of the one before) and on four (each thread's first chunk starts fresh).
/// The paper design settles every angle in the lean kernel; at 1e-6 N·m every angle falls back
/// to the general solve (the balance straddles the torque by round-off), whose warm starts
/// follow the chunk too.
#[test]
fn sweep_is_the_same_on_one_and_on_four_threads() {
    for (path, model, angles) in thread_cases() {
        let on = |threads| {
            crate::common::on_threads(threads, || {
                crate::common::one_disc_sweep(&model, &angles, true).unwrap()
            })
        };
        assert_eq!(on(1), on(4), "{path}");
    }
}

/// The thread tests' cases: the paper design at its rated torque and the design at 1e-6 N·m,
/// each over 1000 angles of its scene: (spec path, model, angles).
fn thread_cases() -> Vec<(&'static str, Model, Vec<f64>)> {
    [
        ("specs/paper.yaml", "rated"),
        ("specs/hard/torque-1e-6.yaml", ""),
    ]
    .into_iter()
    .map(|(path, scene)| {
        let spec = load(path);
        let scene = spec
            .scenes
            .iter()
            .position(|s| s.name == scene)
            .unwrap_or(0);
        (path, model(&spec, scene), grid(&spec, scene, 1000))
    })
    .collect()
}

/// The same for two discs (`discs_sweep::sweep_discs`), whose lean kernels and scratch
/// space are built once per thread and restarted at every chunk: on one thread each chunk
/// after the first inherits the screens, active sets and followed rotations of the one
/// before, on four each thread's first chunk starts fresh, and the curves and the shares must
/// be the same bit for bit. At 1e-6 N·m every angle goes to the coupled solve instead.
#[test]
fn two_discs_sweep_the_same_on_one_and_on_four_threads() {
    for (path, model, angles) in thread_cases() {
        let discs = cycloid::equilibrium::discs::Discs::new(&model, 2);
        let silent = &cycloid::progress::Silent;
        let sweep = || discs_sweep::sweep_discs(&discs, &angles, true, silent).unwrap();
        let (one, four) = (
            crate::common::on_threads(1, sweep),
            crate::common::on_threads(4, sweep),
        );
        assert_eq!(one.discs, four.discs, "{path}");
        assert_eq!(one.torque_nmm, four.torque_nmm, "{path}");
        assert_eq!(one.transmission, four.transmission, "{path}");
    }
}

/// The kernel's compliance d(β + βo)/dT (what several discs weigh their shares by) against a
/// central difference of its own lags at T ± h, h = 1e-4·T, on the paper design with pins
/// over a mesh period. Between contact changes each balance is linear in its lag, so the
/// difference is exact (to the lags' round-off over 2h, ~1e-12 relative) but for the pins'
/// arms turning with β, which the compliance leaves out: over evenly spaced pins Σk·a² and
/// Σk·a·c of those in contact hardly change with the turn (measured: the whole difference
/// stays below 4e-11 relative over the period). 1e-6 bounds both with room; a compliance
/// without the pins' part or without the rollers' fails by far more. Angles where a contact
/// opens or closes within ±h are skipped.
#[test]
fn the_kernel_compliance_is_the_slope_of_its_lag_in_torque() {
    let spec = load("specs/paper.yaml");
    let scene = spec.scenes.iter().position(|s| s.name == "rated").unwrap();
    let model = model(&spec, scene);
    let (nr, np) = (
        model.rollers.as_ref().unwrap().count(),
        model.pins.as_ref().unwrap().count,
    );
    let t = model.torque_nmm;
    let h = 1e-4 * t;
    let mut checked = 0;
    for &phi in &grid(&spec, scene, 90) {
        let at = |torque: f64| {
            let mut lean = FirstOrderSweep::new(&model).unwrap();
            lean.set_torque(torque);
            let mut columns = one_angle_columns(nr, np);
            solve_one(
                &lean,
                phi,
                (0.0, 0.0),
                &mut Scratch::default(),
                &mut columns,
            )
            .expect("the kernel settles the paper design")
        };
        let (lo, mid, hi) = (at(t - h), at(t), at(t + h));
        if lo.contacts != hi.contacts {
            continue;
        }
        let slope =
            ((hi.lag_rad + hi.output_lag_rad) - (lo.lag_rad + lo.output_lag_rad)) / (2.0 * h);
        let c = mid.compliance_rad_per_nmm;
        assert!(
            (c - slope).abs() <= 1e-6 * slope,
            "at {:.3}°: compliance {c:e} against the lags' slope {slope:e}",
            phi.to_degrees()
        );
        checked += 1;
    }
    assert!(
        checked >= 60,
        "only {checked} angles without a contact change"
    );
}
