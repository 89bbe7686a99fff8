//! Per-flank deviation summaries of a measured disc (`measure::flanks`, issue 16's inspection
//! sheet): the arc length along the profile against a closed form and a polyline, and the
//! summaries over arc length of deviations built with a known form and slope.

use crate::common::*;
use cycloid::geometry::profile::Profile;
use cycloid::measure::fitted::{FittedPoint, FormError};
use cycloid::measure::flanks::{arc_length_mm, flanks, FlankSummary};
use cycloid::model::{Design, Modification};
use std::f64::consts::{PI, TAU};

fn paper() -> Design {
    design(10, 2.0, 30.0, 3.0)
}

/// The paper's optimum turned by 0.2°.
fn modified() -> Modification {
    modification(0.125, 0.1593, 0.2f64.to_radians())
}

/// The complete elliptic integral of the second kind E(k) by the arithmetic–geometric mean
/// (Abramowitz & Stegun 17.6.3–4): a₀ = 1, g₀ = √(1 − k²), c₀ = k; K = π/(2·a_N),
/// E = K·(1 − Σ 2^{n−1}·c_n²).
fn elliptic_e(k: f64) -> f64 {
    let (mut a, mut g, mut c) = (1.0f64, (1.0 - k * k).sqrt(), k);
    let (mut sum, mut power) = (0.5 * c * c, 0.5);
    while c.abs() > 1e-17 {
        let next = (0.5 * (a + g), (a * g).sqrt(), 0.5 * (a - g));
        (a, g, c) = next;
        power *= 2.0;
        sum += power * c * c;
    }
    PI / (2.0 * a) * (1.0 - sum)
}

/// Arc length of the profile from t0 to t1 as the chord sum of `n` chords of
/// `Profile::point`, extrapolated (Richardson) from n and 2n chords: the chord sum's error is
/// c·h² + O(h⁴), so (4·L_2n − L_n)/3 leaves O(h⁴).
fn polyline_length(p: &Profile, t0: f64, t1: f64, n: usize) -> f64 {
    let chords = |n: usize| {
        (0..n)
            .map(|k| {
                let (a, b) = (k as f64 / n as f64, (k + 1) as f64 / n as f64);
                (p.point(t0 + (t1 - t0) * b) - p.point(t0 + (t1 - t0) * a)).norm()
            })
            .sum::<f64>()
    };
    (4.0 * chords(2 * n) - chords(n)) / 3.0
}

/// The whole profile's length in closed form: |C'|² = a − b·cos((n−1)t) with a = R'² + e²n²,
/// b = 2R'en, so L_C = ∫₀^{2π} √(a − b·cos u) du = 4·√(a + b)·E(k), k² = 2b/(a + b); and
/// |Γ'| = |C'|·(1 − r'κ_C) on a regular profile, whose ∫κ_C·|C'| dt is the locus's total
/// turning 2π: L_Γ = L_C − 2π·r'. Each of the 2·nc flanks (mirror images, turned copies) is
/// L_Γ/(2nc). For the design's own profile and a modified, turned one the quadrature matches
/// to 4e-13 mm of 191 mm (the AGM is exact to round-off; summing 288 panels rounds to ~1e-13 mm):
/// 1e-11 mm for the whole, 1e-12 mm for a flank (seen: 3e-14 mm). A rule of 3 points on
/// panels of 1/64 flank is off by 4e-10 mm on part of a flank, a chord sum by far more.
#[test]
fn arc_length_of_the_whole_profile_is_the_closed_form() {
    let d = paper();
    for m in [Modification::default(), modified()] {
        let p = Profile::new(&d, &m);
        let (r, e, n) = (p.locus_radius_mm, p.eccentricity_mm, p.rollers as f64);
        let (a, b) = (r * r + e * e * n * n, 2.0 * r * e * n);
        let closed =
            4.0 * (a + b).sqrt() * elliptic_e((2.0 * b / (a + b)).sqrt()) - TAU * p.offset_mm;
        let whole = arc_length_mm(&p, 0.0, TAU);
        assert!((whole - closed).abs() < 1e-11, "{whole} vs {closed}");
        let flank = closed / (2.0 * d.teeth as f64);
        for k in 0..2 * d.teeth {
            let half = PI / d.teeth as f64;
            let l = arc_length_mm(&p, half * k as f64, half * (k + 1) as f64);
            assert!((l - flank).abs() < 1e-12, "flank {k}: {l} vs {flank}");
        }
        // Backwards is the negative length.
        let back = arc_length_mm(&p, 1.3, 0.2);
        assert!((back + arc_length_mm(&p, 0.2, 1.3)).abs() < 1e-12);
    }
}

/// On parts of a flank, between any two parameters (not panel-aligned), the quadrature
/// matches the extrapolated polyline of `Profile::point` (its O(h⁴) remainder at 4·10⁴ chords
/// over 0.3 rad is ~1e-15 mm; the chords' round-off ~1e-13 mm; seen: 1.2e-13 mm): 1e-12 mm.
#[test]
fn arc_length_between_points_matches_a_fine_polyline() {
    let p = Profile::new(&paper(), &modified());
    for (t0, t1) in [
        (0.0, 0.05),
        (0.013, 0.29),
        (0.17, 0.35),
        (2.0, 2.31),
        (5.9, 6.2),
    ] {
        let (quad, line) = (
            arc_length_mm(&p, t0, t1),
            polyline_length(&p, t0, t1, 20_000),
        );
        assert!(
            (quad - line).abs() < 1e-12,
            "[{t0}, {t1}]: {quad} vs {line}"
        );
    }
}

/// Points on flank `side` of tooth 3 at `count` parameters spread over the middle 80 % of
/// its half pitch (not the whole flank: the extent is what was measured), out of order, with
/// the deviation `deviation(t, s)` (s their arc length from the flank's root by the polyline).
fn flank_points(
    p: &Profile,
    side: usize,
    count: usize,
    deviation: impl Fn(f64, f64) -> f64,
) -> (Vec<FittedPoint>, Vec<f64>) {
    let teeth = 9;
    let half = PI / teeth as f64;
    let root = TAU * (3 + side) as f64 / teeth as f64;
    let towards_tip = if side == 0 { 1.0 } else { -1.0 };
    let mut points = Vec::new();
    let mut arcs = Vec::new();
    for k in 0..count {
        // A permutation of 0..count (count odd, 7 coprime with it): out of order.
        let j = (7 * k) % count;
        let dt = half * (0.1 + 0.8 * j as f64 / (count - 1) as f64);
        let t = root + towards_tip * dt;
        let s = polyline_length(p, root.min(t), root.max(t), 4000);
        points.push(FittedPoint {
            t,
            residual_mm: deviation(t, s),
            line: k + 1,
        });
        arcs.push(s);
    }
    (points, arcs)
}

fn summary_of(p: &Profile, points: &[FittedPoint], side: usize) -> FlankSummary {
    let all = flanks(p, points, &FormError::default(), 9);
    assert_eq!(all.len(), 18);
    let f = all[2 * 3 + side];
    assert_eq!(
        (f.tooth, f.side, f.points),
        (3, ['a', 'b'][side], points.len())
    );
    f.summary.expect("a flank with points")
}

/// A deviation linear in arc length, d = 3 µm + α·s, on either flank: its form deviation is
/// zero, its slope deviation is α times the measured extent, and so is its total deviation
/// (monotone); the extent is the points' own arc lengths from the root. With α > 0 material
/// missing grows towards the tip on both flanks, and f_H > 0 on both: s runs from the root on
/// flank b too, against t. The extent to 1e-12 mm (the quadrature's and the 4000-chord
/// polyline's errors, ~1e-14 mm, seen 1.4e-14 mm); f_f, f_H and F to 1e-14 mm: the errors in s
/// times α ≤ 2e-3, and the round-off of deviations of ~0.02 mm (seen: 1.5e-16 mm).
#[test]
fn deviation_linear_in_arc_length_has_no_form_deviation() {
    let p = Profile::new(&paper(), &modified());
    for side in [0, 1] {
        for alpha in [2e-3, -0.7e-3] {
            let (points, arcs) = flank_points(&p, side, 41, |_, s| 3e-3 + alpha * s);
            let s = summary_of(&p, &points, side);
            let lo = arcs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = arcs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            assert!(
                (s.from_mm - lo).abs() < 1e-12 && (s.to_mm - hi).abs() < 1e-12,
                "side {side}: extent {}..{} vs {lo}..{hi}",
                s.from_mm,
                s.to_mm
            );
            assert!(s.form_mm < 1e-14, "side {side}: f_f {}", s.form_mm);
            assert!(
                (s.slope_mm - alpha * (hi - lo)).abs() < 1e-14,
                "side {side}: f_H {} vs {}",
                s.slope_mm,
                alpha * (hi - lo)
            );
            assert!((s.total_mm - alpha.abs() * (hi - lo)).abs() < 1e-14);
        }
    }
}

/// A deviation linear in the locus parameter t instead, on a flank along which ds/dt = |Γ'|
/// varies (here by a factor of ~3 from root to tip), is not linear in s: it keeps a form
/// deviation, a clear share of its total (a summary over t would show none). Its total
/// deviation is still the range of the deviations, α times the points' span in t.
#[test]
fn deviation_linear_in_the_parameter_is_not_straight_along_the_profile() {
    let p = Profile::new(&paper(), &modified());
    let speeds: Vec<f64> = (0..=20)
        .map(|k| p.tangent(PI / 9.0 * k as f64 / 20.0).norm())
        .collect();
    let (slow, fast) = (
        speeds.iter().copied().fold(f64::INFINITY, f64::min),
        speeds.iter().copied().fold(0.0, f64::max),
    );
    assert!(
        fast > 1.5 * slow,
        "ds/dt varies on the flank: {slow}..{fast}"
    );
    let alpha = 0.05; // mm/rad: 14 µm over the 80 % of a 0.35 rad flank
    for side in [0, 1] {
        let (points, _) = flank_points(&p, side, 41, |t, _| alpha * t);
        let s = summary_of(&p, &points, side);
        let span = 0.8 * PI / 9.0;
        assert!((s.total_mm - alpha * span).abs() < 1e-12 * alpha);
        assert!(
            s.form_mm > 0.05 * s.total_mm,
            "side {side}: f_f {} of F {}",
            s.form_mm,
            s.total_mm
        );
    }
}

/// A flank with fewer than 3 points has no summary; every point lands on its flank.
#[test]
fn flanks_with_fewer_than_three_points_have_no_summary() {
    let p = Profile::new(&paper(), &modified());
    let (points, _) = flank_points(&p, 1, 3, |_, s| 1e-3 * s);
    let all = flanks(&p, &points[..2], &FormError::default(), 9);
    assert_eq!(all[7].points, 2);
    assert!(all[7].summary.is_none());
    assert_eq!(all.iter().map(|f| f.points).sum::<usize>(), 2);
}

/// |Γ'| in closed form (`Profile::speed`) is the norm of `Profile::tangent` (its Frenet form,
/// to round-off) and of a central difference of `Profile::point` (h = 1e-5 rad: truncation
/// ~h²·|Γ‴|/6 ~ 1e-8, round-off ~ε·30 mm/h ~ 1e-9 mm/rad; 1e-6 relative), around the profile.
#[test]
fn speed_is_the_norm_of_the_tangent() {
    let p = Profile::new(&paper(), &modified());
    let h = 1e-5;
    for k in 0..211 {
        let t = TAU * (k as f64 + 0.37) / 211.0;
        let v = p.speed(t);
        assert!((v - p.tangent(t).norm()).abs() < 1e-12 * v, "at {t}");
        let fd = (p.point(t + h) - p.point(t - h)).norm() / (2.0 * h);
        assert!((v - fd).abs() < 1e-6 * v, "at {t}: {v} vs {fd}");
    }
}

/// The form error's value by powers of e^{it} is the series summed term by term, for orders
/// up to 200 in any order (one below the previous falls back to its own sine and cosine):
/// 1e-15 mm for amplitudes of 1 µm (k products lose ~k·ε: 200·2e-16·1e-3 per term, ~70 terms,
/// ~3e-15 at worst, ~3e-16 as random errors).
#[test]
fn form_error_value_is_the_series() {
    use cycloid::measure::fitted::{Estimate, Harmonic};
    let e = |v: f64| Estimate {
        value: v,
        sigma: 0.0,
    };
    let orders: Vec<usize> = (2..=200).step_by(3).chain([7, 5, 190]).collect();
    let form = FormError {
        harmonics: orders
            .iter()
            .enumerate()
            .map(|(i, &order)| Harmonic {
                order,
                cos_mm: e(1e-3 * ((i as f64) * 0.7).sin()),
                sin_mm: e(1e-3 * ((i as f64) * 1.3).cos()),
            })
            .collect(),
    };
    for k in 0..97 {
        let t = TAU * (k as f64 + 0.21) / 97.0 - 1.0;
        let direct: f64 = form
            .harmonics
            .iter()
            .map(|h| {
                let (s, c) = (h.order as f64 * t).sin_cos();
                h.cos_mm.value * c + h.sin_mm.value * s
            })
            .sum();
        assert!((form.value_mm(t) - direct).abs() < 1e-15, "at {t}");
    }
}
