//! The shipped golden curves obey the physics on their own, whatever code wrote them.
//!
//! A golden copied from the code's output is only self-consistent; these checks read the CSV
//! files under golden/ and the design of their spec and verify, independently of the solver:
//! - clearance: a brute-force distance from each roller to a dense polygon of the profile,
//!   written here from the closed form of MODEL.md (no library geometry), at every 3°; the
//!   root/tip gap ΔRrp − ΔRp; mirror symmetry gap_i(φ) = gap_(11−i) mod 10(36° − φ);
//! - roller forces: the paper's law F = (π/4)·E*·B·max(0, −gap) at the loaded pose (β from the
//!   TE golden less the pin lag βo), Σ F·l = T, and F ≥ 0;
//! - pin forces: the same law on the exact pin-in-hole gap, Σ F·a = T;
//! - crank bearing: Fb = −(Σ roller + Σ pin forces) in magnitude and direction;
//! - transmission: ratio golden = 1/(1/nc − dδ/dφ) of the TE golden, harmonic mean nc;
//! - periodicity: roller forces, TE and ratio repeat every mesh period (36°, roller i+1 in
//!   roller i's place); pins and bearing after 108° (pin j+2 in pin j's place), checked by
//!   extrapolating the last samples past the end and landing on the first.

use cycloid::geometry::clearance::{Mesh, Pose};
use cycloid::geometry::{cross, rotate, Vec2};
use cycloid::spec::Spec;
use std::f64::consts::{PI, TAU};

const ARCSEC: f64 = PI / (180.0 * 3600.0);
const CASES: [&str; 5] = [
    "paper",
    "paper-positive-start",
    "paper-negative-start",
    "paper-negative-optimum",
    "paper-positive-optimum",
];

struct Csv {
    deg: Vec<f64>,
    /// [column][angle]
    cols: Vec<Vec<f64>>,
}

fn read(case: &str, quantity: &str) -> Csv {
    let path = format!("golden/{case}/{quantity}.csv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "crank_deg");
    let mut deg = Vec::new();
    let mut cols = vec![Vec::new(); header.len() - 1];
    for line in lines {
        let v: Vec<f64> = line.split(',').map(|c| c.parse().unwrap()).collect();
        deg.push(v[0]);
        for (c, x) in cols.iter_mut().zip(&v[1..]) {
            c.push(*x);
        }
    }
    Csv { deg, cols }
}

fn spec(case: &str) -> Spec {
    let path = format!("specs/{case}.yaml");
    cycloid::spec::parse(&path, &std::fs::read_to_string(&path).unwrap()).unwrap()
}

/// k of the paper's law, N/mm: (π/4)·E*·B with E* = 1/(2(1−ν²)/E) for like materials.
fn stiffness(s: &Spec) -> f64 {
    let m = s.design.disc_material;
    let e_star = 1.0 / (2.0 * (1.0 - m.poisson_ratio.powi(2)) / m.youngs_modulus_mpa);
    PI / 4.0 * e_star * s.design.face_width_mm
}

#[test]
fn goldens_cover_their_periods_at_0_1_deg() {
    for case in CASES {
        for q in [
            "clearance_mm",
            "te_arcsec",
            "ratio",
            "roller_force_n",
            "pin_force_n",
            "bearing_force_n",
            "bearing_angle_deg",
        ] {
            let g = read(case, q);
            // Clearance over one mesh period; the loaded curves over 108°, the period of the
            // loaded disc (3 mesh periods of 36°, 2 output-pin periods of 54°).
            let n = if q == "clearance_mm" { 360 } else { 1080 };
            assert_eq!(g.deg.len(), n, "{case}/{q}");
            for (k, d) in g.deg.iter().enumerate() {
                assert!((d - 0.1 * k as f64).abs() < 1e-9, "{case}/{q}");
            }
            assert!(g.cols.iter().flatten().all(|v| v.is_finite()), "{case}/{q}");
            let meta = std::fs::read_to_string(format!("golden/{case}/{q}.csv.meta.yaml")).unwrap();
            assert!(
                meta.contains(&format!("spec: specs/{case}.yaml")),
                "{case}/{q}"
            );
            assert!(meta.contains("reviewed:"), "{case}/{q}");
            // A shipped golden says what was reviewed; bless resets that when a curve moves.
            assert!(!meta.contains("NOT REVIEWED"), "{case}/{q} is not reviewed");
        }
    }
}

/// The profile Γ(t) of MODEL.md, written out here: C(t) − r'·N(t).
fn gamma(s: &Spec, t: f64) -> Vec2 {
    let (d, m) = (&s.design, &s.modification);
    let (r, e, n) = (
        d.roller_circle_radius_mm + m.shift_mm,
        d.eccentricity_mm,
        d.rollers as f64,
    );
    let c = Vec2::new(
        r * t.cos() - e * (n * t).cos(),
        r * t.sin() - e * (n * t).sin(),
    );
    let dc = Vec2::new(
        -r * t.sin() + e * n * (n * t).sin(),
        r * t.cos() - e * n * (n * t).cos(),
    );
    let normal = Vec2::new(dc.y, -dc.x) / dc.norm();
    c - (d.roller_radius_mm + m.equidistant_mm) * normal
}

fn segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f64 {
    let ab = b - a;
    let w = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (p - (a + w * ab)).norm()
}

fn inside(p: Vec2, polygon: &[Vec2]) -> bool {
    let mut odd = false;
    for k in 0..polygon.len() {
        let (a, b) = (polygon[k], polygon[(k + 1) % polygon.len()]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            odd = !odd;
        }
    }
    odd
}

#[test]
fn clearance_goldens_match_a_brute_force_distance_to_a_dense_profile() {
    for case in CASES {
        let s = spec(case);
        let d = &s.design;
        let g = read(case, "clearance_mm");
        let polygon: Vec<Vec2> = (0..180_000)
            .map(|k| gamma(&s, TAU * k as f64 / 180_000.0))
            .collect();
        let mut worst: f64 = 0.0;
        for k in (0..360).step_by(30) {
            let phi = g.deg[k].to_radians();
            let centre = Vec2::new(phi.cos(), phi.sin()) * d.eccentricity_mm;
            let psi = -phi / d.teeth as f64;
            for i in 0..d.rollers {
                let a = TAU * i as f64 / d.rollers as f64;
                let roller = Vec2::new(a.cos(), a.sin()) * d.roller_circle_radius_mm;
                let p = rotate(roller - centre, psi.cos(), -psi.sin());
                let dist = (0..polygon.len())
                    .map(|j| segment_distance(p, polygon[j], polygon[(j + 1) % polygon.len()]))
                    .fold(f64::INFINITY, f64::min);
                let signed = if inside(p, &polygon) { -dist } else { dist };
                let brute = signed - d.roller_radius_mm;
                worst = worst.max((brute - g.cols[i][k]).abs());
            }
        }
        eprintln!("{case}: clearance vs brute force: worst {worst:.2e} mm");
        // Chord sag of the polygon: ≤ (perimeter/N)²·κmax/8, a few 1e-7 mm.
        assert!(worst < 1e-6, "{case}: brute force differs by {worst} mm");
        // At φ = 0 roller 0 sits in a root: the gap is ΔRrp − ΔRp exactly.
        let tip = s.modification.tip_clearance_mm();
        assert!(
            (g.cols[0][0] - tip).abs() < 1e-9,
            "{case}: {}",
            g.cols[0][0]
        );
    }
}

#[test]
fn clearance_goldens_are_mirror_symmetric() {
    for case in CASES {
        let g = read(case, "clearance_mm");
        for k in 1..360 {
            for i in 0..10 {
                let mirror = g.cols[(11 - i) % 10][360 - k];
                assert!(
                    (g.cols[i][k] - mirror).abs() < 1e-9,
                    "{case}: roller {i} at {}°",
                    g.deg[k]
                );
            }
        }
    }
}

/// Quadratic extrapolation of a sampled curve one step past its end.
fn next(v: &[f64]) -> f64 {
    let n = v.len();
    3.0 * v[n - 1] - 3.0 * v[n - 2] + v[n - 3]
}

#[test]
fn goldens_repeat_over_their_periods() {
    for case in CASES {
        // One mesh period later roller i+1 stands where roller i stood: the unloaded gaps
        // continue past 36° into those at 0°.
        let g = read(case, "clearance_mm");
        for i in 0..10 {
            let at_36 = next(&g.cols[(i + 1) % 10]);
            assert!((at_36 - g.cols[i][0]).abs() < 1e-6, "{case}: roller {i}");
        }
        // Under load, with a rigid bearing the roller balance does not see the pins: roller
        // forces, TE and ratio repeat every 36° (βo is constant: Σ a² over the loaded pins of
        // six equally spaced ones is 1.5·rw² at every angle).
        let shift = 360;
        let f = read(case, "roller_force_n");
        for k in 0..1080 - shift {
            for i in 0..10 {
                let (a, b) = (f.cols[(i + 1) % 10][k + shift], f.cols[i][k]);
                assert!(
                    (a - b).abs() < 0.01 + 1e-6 * b,
                    "{case}: roller {i} at {}°",
                    f.deg[k]
                );
            }
        }
        for (q, tol) in [("te_arcsec", 0.01), ("ratio", 1e-5)] {
            let g = read(case, q);
            for k in 0..1080 - shift {
                let (a, b) = (g.cols[0][k + shift], g.cols[0][k]);
                assert!(
                    (a - b).abs() < tol,
                    "{case}/{q} at {}°: {a} vs {b}",
                    g.deg[k]
                );
            }
        }
        // Pins and bearing repeat after 108°, pin j+2 standing where pin j stood: the curves
        // continue past 108° into those at 0°.
        let p = read(case, "pin_force_n");
        for j in 0..6 {
            let at_108 = next(&p.cols[(j + 2) % 6]);
            assert!((at_108 - p.cols[j][0]).abs() < 0.05, "{case}: pin {j}");
        }
        for (q, tol) in [("bearing_force_n", 0.5), ("bearing_angle_deg", 0.01)] {
            let g = read(case, q);
            let at_108 = next(&g.cols[0]);
            let at_0 = g.cols[0][0];
            assert!(
                (at_108 - at_0).abs() < tol,
                "{case}/{q}: {at_108} vs {at_0}"
            );
        }
    }
}

#[test]
fn ratio_golden_is_the_derivative_of_the_te_golden_with_harmonic_mean_nc() {
    for case in CASES {
        let te = read(case, "te_arcsec");
        let ratio = read(case, "ratio");
        let n = te.deg.len();
        let h = 0.1f64.to_radians();
        let nc = 9.0;
        let mut mean_inverse = 0.0;
        for k in 0..n {
            let (before, after) = (te.cols[0][(k + n - 1) % n], te.cols[0][(k + 1) % n]);
            let d = (after - before) * ARCSEC / (2.0 * h);
            let kappa = 1.0 / (1.0 / nc - d);
            // The CSV keeps 10 significant digits: each TE value is off by up to half a unit in
            // its last place, which the difference quotient turns into up to
            // κ²·ulp/2·ARCSEC/h of ratio (1.1e-7 for a TE above 1000 arcsec, 1.1e-8 below).
            let half_ulp = 0.5 * 10f64.powf(before.abs().max(after.abs()).log10().floor() - 9.0);
            let rounding = kappa * kappa * half_ulp * ARCSEC / h;
            assert!(
                (kappa - ratio.cols[0][k]).abs() < 1e-8 + rounding,
                "{case}: at {}°: {kappa} vs {}",
                te.deg[k],
                ratio.cols[0][k]
            );
            mean_inverse += 1.0 / ratio.cols[0][k] / n as f64;
        }
        assert!(
            (1.0 / mean_inverse - nc).abs() < 1e-8,
            "{case}: {}",
            1.0 / mean_inverse
        );
    }
}

/// Pin j's force direction on the disc, gap and moment arm at crank φ, disc rotation ψ and
/// output lag βo (ideal hole centres: disc centre + rw·e^{iγ}, pins at rw·e^{i(γ+βo)}).
fn pin(s: &Spec, j: usize, phi: f64, psi: f64, output_lag: f64) -> (Vec2, f64, f64) {
    let d = &s.design;
    let gamma = TAU * j as f64 / d.pins.count as f64 + psi;
    let rw = d.pins.circle_radius_mm;
    let centre = Vec2::new(phi.cos(), phi.sin()) * d.eccentricity_mm;
    let arm = Vec2::new(gamma.cos(), gamma.sin()) * rw;
    let q = Vec2::new((gamma + output_lag).cos(), (gamma + output_lag).sin()) * rw;
    let dq = q - (centre + arm);
    let u = dq / dq.norm();
    let gap = d.eccentricity_mm + d.pins.hole_clearance_mm - dq.norm();
    (u, gap, cross(arm, u))
}

#[test]
fn force_goldens_obey_the_contact_law_and_the_balance_of_the_disc() {
    for case in CASES {
        let s = spec(case);
        let d = &s.design;
        let k = stiffness(&s);
        let torque = s
            .scenes
            .iter()
            .find(|c| c.name == "rated")
            .unwrap()
            .output_torque_nmm;
        let te = read(case, "te_arcsec");
        let rollers = read(case, "roller_force_n");
        let pins = read(case, "pin_force_n");
        let fb = read(case, "bearing_force_n");
        let eps = read(case, "bearing_angle_deg");
        let mesh = Mesh::new(&s.design, &s.modification);
        let (mut worst_law, mut worst_pin_law, mut worst_balance) = (0.0f64, 0.0f64, 0.0f64);
        for a in (0..1080).step_by(7) {
            let phi = te.deg[a].to_radians();
            assert!(rollers.cols.iter().all(|c| c[a] >= 0.0));
            assert!(pins.cols.iter().all(|c| c[a] >= 0.0));
            // βo from the most loaded pin (F = k·(−gap), gap linear in βo near 0), β = δ − βo.
            let psi0 = -phi / d.teeth as f64 + te.cols[0][a] * ARCSEC;
            let (j, fj) = pins
                .cols
                .iter()
                .enumerate()
                .map(|(j, c)| (j, c[a]))
                .fold((0, 0.0), |b, x| if x.1 > b.1 { x } else { b });
            let mut output_lag = fj / (k * pin(&s, j, phi, psi0, 0.0).2);
            for _ in 0..3 {
                // Refine: solve k·(−gap_j(βo)) = F_j by Newton with a numerical slope.
                let lag = te.cols[0][a] * ARCSEC - output_lag;
                let psi = -phi / d.teeth as f64 + lag;
                let f = |x: f64| -k * pin(&s, j, phi, psi, x).1 - fj;
                let slope = (f(output_lag + 1e-9) - f(output_lag - 1e-9)) / 2e-9;
                output_lag -= f(output_lag) / slope;
            }
            let lag = te.cols[0][a] * ARCSEC - output_lag;
            let psi = -phi / d.teeth as f64 + lag;
            // Rollers: the law on the exact gap at the loaded pose, and the moment balance.
            let pose = Pose::lagging(phi, lag);
            let mut moment = 0.0;
            let mut force = Vec2::zeros();
            for i in 0..d.rollers {
                let g = mesh.roller_gap(i, &pose, None).unwrap();
                let law = k * (-g.gap_mm).max(0.0);
                let f = rollers.cols[i][a];
                worst_law = worst_law.max((law - f).abs() / (1.0 + f));
                moment += f * g.arm_mm;
                let n = rotate(g.normal, psi.cos(), psi.sin());
                force -= f * n;
            }
            worst_balance = worst_balance.max((moment - torque).abs() / torque);
            // Pins: the law on the exact pin-in-hole gap, and their moment.
            let mut pin_moment = 0.0;
            for j in 0..d.pins.count {
                let (u, gap, arm) = pin(&s, j, phi, psi, output_lag);
                let f = pins.cols[j][a];
                worst_pin_law = worst_pin_law.max((k * (-gap).max(0.0) - f).abs());
                pin_moment += f * arm;
                force += f * u;
            }
            worst_balance = worst_balance.max((pin_moment - torque).abs() / torque);
            // Crank bearing: the rest of the force balance, magnitude and direction.
            let bearing = -force;
            let e = Vec2::new(phi.cos(), phi.sin());
            let angle = cross(e, bearing).atan2(e.dot(&bearing)).to_degrees();
            assert!(
                (bearing.norm() - fb.cols[0][a]).abs() < 1e-6 * fb.cols[0][a] + 0.01,
                "{case} at {}°: |Fb| {} vs golden {}",
                te.deg[a],
                bearing.norm(),
                fb.cols[0][a]
            );
            assert!(
                (angle - eps.cols[0][a]).abs() < 1e-4,
                "{case} at {}°: ε {angle} vs golden {}",
                te.deg[a],
                eps.cols[0][a]
            );
        }
        eprintln!(
            "{case}: roller law {worst_law:.1e} (relative), pin law {worst_pin_law:.1e} N, \
             moment balance {worst_balance:.1e} (relative)"
        );
        assert!(
            worst_law < 1e-5,
            "{case}: roller law off by {worst_law} (relative)"
        );
        assert!(
            worst_pin_law < 1e-3,
            "{case}: pin law off by {worst_pin_law} N"
        );
        assert!(
            worst_balance < 1e-7,
            "{case}: moment balance off by {worst_balance}"
        );
    }
}
