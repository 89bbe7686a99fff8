//! The clearance sweep (`clearance::sweep`, `clearance::min_gap`), which follows every roller's
//! closest point and closing lag from one crank angle to the next, against the evaluation of
//! every roller and angle from scratch that it replaced: `Mesh::roller_gap` without a warm
//! start (Newton from the roller's own locus parameter, cross-checked by the scanning search)
//! and `Mesh::closing_lag_toward` both ways (Newton from β = 0 on the nearest flank, the other
//! way from where the march reaches a flank that closes). Both find the same closest points and closing
//! lags; the tolerances are the brief's (gaps within 1e-9 mm, backlash within 1e-6 arcsec)
//! and cover the round-off of two routes to the same foot (~1e-13 mm) and the closing lags'
//! stopping rule (a relative step of 1e-12, ~1e-14 rad here). The backlash tolerance adds the
//! reference's own stopping error where it is larger: a lag is accepted when its gap is within
//! 32 ulp of Rp, |gap|/|arm| from the root, ~6e-12 rad (1.3e-6 arcsec) for a roller closing
//! near a tip with an arm of 0.02 mm (found by the property test).
//!
//! Also: the reach bound that lets a followed foot skip the scanning search, against a brute
//! force; a design whose rollers are lifted onto both sides of a sharp root (where following a
//! foot without that proof would stay on the wrong side); and the same curves on one and four
//! threads.

use crate::common::*;
use cycloid::geometry::clearance::{self, Mesh, Pose, Scope};
use cycloid::geometry::profile::Profile;
use cycloid::geometry::Vec2;
use cycloid::model::results::ClearanceSweep;
use cycloid::model::{Design, Modification};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// Gaps within 1e-9 mm of the reference.
const GAP_MM: f64 = 1e-9;
/// Backlash within 1e-6 arcsec of the reference, in rad.
const BACKLASH_RAD: f64 = 1e-6 / 206_264.806_247_096_36;

/// Today's sweep from scratch, one roller and angle at a time: gaps [roller][angle], forward
/// and reverse backlash [angle] (`Mesh::closing_lag_toward` of every roller, each way).
struct Reference {
    gap_mm: Vec<Vec<f64>>,
    forward_rad: Vec<f64>,
    reverse_rad: Vec<f64>,
    /// How far a closing lag that sets the forward (reverse) backlash at each angle may be
    /// from the root, by the stopping rule the reference and the sweep share: the iteration
    /// stops once |gap| is within 32·ε·Rp, a lag error of up to that gap over the roller's
    /// arm |l| (rad), which exceeds 1e-6 arcsec for a roller closing near a tip, where its arm
    /// is small. The bound, not the reference's own residual: the sweep may stop anywhere
    /// within it (a case with the reference's residual near 0 and the sweep 7.7e-12 rad off,
    /// at |l| ≈ 0.04 mm, is in the regressions).
    stop_rad: Vec<(f64, f64)>,
}

fn reference(mesh: &Mesh, crank: &[f64]) -> Reference {
    let mut r = Reference {
        gap_mm: vec![Vec::new(); mesh.rollers],
        forward_rad: Vec::new(),
        reverse_rad: Vec::new(),
        stop_rad: Vec::new(),
    };
    for &phi in crank {
        // (closing lag, its stopping bound) of each roller, forward and reverse.
        let (mut forward, mut reverse) = (Vec::new(), Vec::new());
        let closed_mm = 32.0 * f64::EPSILON * mesh.roller_circle_radius_mm;
        for i in 0..mesh.rollers {
            let g = mesh
                .roller_gap(i, &Pose::ideal(phi), None)
                .unwrap_or_else(|f| panic!("{f}"));
            r.gap_mm[i].push(g.gap_mm);
            for (sign, lags) in [(1.0, &mut forward), (-1.0, &mut reverse)] {
                let Some(b) = mesh.closing_lag_toward(i, phi, sign).unwrap() else {
                    continue;
                };
                let stop = match mesh.roller_gap(i, &Pose::lagging(phi, b), None) {
                    Ok(at) => at.gap_mm.abs().max(closed_mm) / at.arm_mm.abs(),
                    Err(_) => 0.0,
                };
                lags.push((sign * b, stop));
            }
        }
        let (forward, forward_stop) = smallest_lag(&forward);
        let (reverse, reverse_stop) = smallest_lag(&reverse);
        r.forward_rad.push(forward);
        r.reverse_rad.push(reverse);
        r.stop_rad.push((forward_stop, reverse_stop));
    }
    r
}

/// The smallest closing lag of `lags` (infinite when none) and the largest stopping bound of
/// the rollers that may set it (their lags within 1e-9 rad of it: the sweep may pick another
/// of them, each off its root by up to its own bound).
fn smallest_lag(lags: &[(f64, f64)]) -> (f64, f64) {
    let least = lags.iter().map(|l| l.0).fold(f64::INFINITY, f64::min);
    let stop = (lags.iter())
        .filter(|l| l.0 <= least + 1e-9)
        .map(|l| l.1)
        .fold(0.0, f64::max);
    (least, stop)
}

/// Equal within `tol`, or both infinite (no roller closes that way).
fn agree(a: f64, b: f64, tol: f64) -> bool {
    a == b || (a - b).abs() <= tol
}

/// The sweep against the reference: every gap, the smallest gap and its place, and (when
/// computed) the backlash both ways and the lost motion.
fn assert_matches(what: &str, mesh: &Mesh, crank: &[f64], s: &ClearanceSweep, r: &Reference) {
    for i in 0..mesh.rollers {
        for (k, at) in crank.iter().enumerate() {
            let (got, want) = (s.gap_mm[i][k], r.gap_mm[i][k]);
            assert!(
                (got - want).abs() <= GAP_MM,
                "{what}: roller {i} at crank {at}: gap {got} mm, from scratch {want} mm"
            );
        }
    }
    let smallest = r
        .gap_mm
        .iter()
        .flatten()
        .fold(f64::INFINITY, |a, &b| a.min(b));
    assert!(
        (s.min.gap_mm - smallest).abs() <= GAP_MM,
        "{what}: min {:?}",
        s.min
    );
    let k = crank.iter().position(|&c| c == s.min.crank_rad).unwrap();
    assert!(
        (r.gap_mm[s.min.roller][k] - smallest).abs() <= GAP_MM,
        "{what}: {:?}",
        s.min
    );
    let Some(b) = &s.backlash else {
        return;
    };
    for (k, at) in crank.iter().enumerate() {
        // The brief's 1e-6 arcsec, plus the reference's own stopping error (twice: the sweep
        // stops by the same rule on the other side of the root).
        let (forward_stop, reverse_stop) = r.stop_rad[k];
        assert!(
            agree(
                b.forward_rad[k],
                r.forward_rad[k],
                BACKLASH_RAD + 2.0 * forward_stop
            ),
            "{what}: backlash at crank {at}: {} rad, from scratch {} rad",
            b.forward_rad[k],
            r.forward_rad[k]
        );
        assert!(
            agree(
                b.reverse_rad[k],
                r.reverse_rad[k],
                BACKLASH_RAD + 2.0 * reverse_stop
            ),
            "{what}: reverse backlash at crank {at}: {} rad, from scratch {} rad",
            b.reverse_rad[k],
            r.reverse_rad[k]
        );
        assert_eq!(
            b.lost_motion_rad[k],
            b.forward_rad[k] + b.reverse_rad[k],
            "{what}"
        );
    }
}

/// `n` crank angles from `from`, 0.1° apart: chunks of 64 see a roller move by 6.4°.
fn crank(from: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| from + (0.1 * k as f64).to_radians())
        .collect()
}

proptest! {
    /// Random designs with interference or clearance (tests/it/common `cases`), six angles per
    /// mesh period over two periods: every roller moves a sixth of a tooth between angles, far
    /// from where it was, so that warm starts meet other roots and other flanks.
    #[test]
    fn coarse_sweeps_match_the_evaluation_from_scratch(c in cases(), phi0 in 0.0..TAU) {
        let mesh = Mesh::new(&c.design, &c.m);
        let period = c.design.mesh_period_rad();
        let crank: Vec<f64> = (0..12).map(|k| phi0 + k as f64 * period / 6.0).collect();
        let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent).unwrap_or_else(|f| panic!("{f}"));
        assert_matches(&format!("{c:?}"), &mesh, &crank, &s, &reference(&mesh, &crank));
    }

    /// Random valid designs, modifications and profile rotations (tests/it/common): 70 angles
    /// (two chunks, the second started in the middle of a mesh period), gaps and backlash.
    #[test]
    fn sweep_matches_the_evaluation_from_scratch(c in rotated_cases(), phi0 in 0.0..TAU) {
        let mesh = Mesh::new(&c.design, &c.m);
        let crank = crank(phi0, 70);
        let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent).unwrap_or_else(|f| panic!("{f}"));
        assert_matches(&format!("{c:?}"), &mesh, &crank, &s, &reference(&mesh, &crank));
    }

    /// The reach bound of the locus is a reach: a point on the normal of the locus closer than
    /// the bound has that foot as its nearest point, by brute force over the whole locus
    /// (200,000 samples refined by golden section: the distance to ~1e-12 mm, allowed 1e-9).
    #[test]
    fn the_reach_bound_is_a_reach(c in rotated_cases(), t in 0.0..TAU, side in -1.0..1.0f64) {
        let p = Profile::new(&c.design, &c.m);
        let reach = p.locus_reach_bound_mm();
        prop_assert!(reach > 0.0);
        let j = p.locus_jet(t);
        let normal = Vec2::new(j.d1.y, -j.d1.x) / j.d1.norm();
        let q = j.c + normal * (side * reach);
        let nearest = nearest_on_locus(&p, q, 200_000);
        prop_assert!(nearest >= (side * reach).abs() - 1e-9,
            "a point {} mm off the locus at t = {t} is {nearest} mm from it (reach bound {reach} mm)",
            side * reach);
    }
}

/// The distance from q to the locus C by brute force: dense samples, then golden section around
/// the nearest.
fn nearest_on_locus(p: &Profile, q: Vec2, samples: usize) -> f64 {
    let dist = |t: f64| (p.locus_jet(t).c - q).norm();
    let h = TAU / samples as f64;
    let best = (0..samples)
        .map(|k| k as f64 * h)
        .min_by(|a, b| dist(*a).total_cmp(&dist(*b)))
        .unwrap();
    dist(golden_section_min(dist, best - h, best + h))
}

/// The paper's design with each modification of specs/paper*.yaml (its optimum, the start
/// points and optima of the positive and negative studies; the negative start interferes at
/// mid-flank), one mesh period at 0.1° like `specs/reducer.yaml`: gaps, backlash, `min_gap`.
#[test]
fn paper_sweeps_match_the_evaluation_from_scratch() {
    for (shift, equidistant) in [
        (0.125, 0.1593),
        (0.135, 0.15),
        (0.16964106759699482, 0.22917929821048158),
        (-0.15, -0.135),
        (-0.020129994269645513, 0.0),
    ] {
        let spec = paper_spec(shift, equidistant);
        let mesh = Mesh::new(&spec.design, &spec.modification);
        let crank = &spec.scenes[0].crank_rad;
        let r = reference(&mesh, crank);
        let what = format!("({shift}, {equidistant})");
        let full =
            clearance::sweep(&mesh, crank, Scope::Backlash, &cycloid::progress::Silent).unwrap();
        assert_matches(&what, &mesh, crank, &full, &r);
        let gaps = clearance::sweep(&mesh, crank, Scope::Gaps, &cycloid::progress::Silent).unwrap();
        assert_eq!(gaps.gap_mm, full.gap_mm, "{what}");
        assert_eq!(gaps.min, full.min, "{what}");
        assert!(gaps.backlash.is_none());
        assert_eq!(
            clearance::min_gap(&mesh, crank).unwrap(),
            full.min,
            "{what}"
        );
    }
}

/// A profile turned by a whole tooth pitch (40°) is the same disc, and one turned by 40.3° the
/// disc turned by 0.3°: the sweep seeds each roller from its parameter turned by the reduced
/// rotation (`Mesh::foot_guess`) and must agree with the evaluation from scratch, and the whole
/// pitch with the unturned profile (to the rounding of the reduced rotation, ~1e-15 rad times
/// the arm: far below 1e-9 mm).
#[test]
fn turned_profiles_match_the_evaluation_from_scratch() {
    let spec = paper_spec(0.125, 0.1593);
    let crank = &spec.scenes[0].crank_rad;
    let at = |deg: f64| {
        let m = Modification {
            rotation_rad: deg.to_radians(),
            ..spec.modification
        };
        let mesh = Mesh::new(&spec.design, &m);
        let s =
            clearance::sweep(&mesh, crank, Scope::Backlash, &cycloid::progress::Silent).unwrap();
        assert_matches(
            &format!("{deg}°"),
            &mesh,
            crank,
            &s,
            &reference(&mesh, crank),
        );
        s
    };
    let (unturned, pitch) = (at(0.0), at(40.0));
    at(40.3);
    at(-19.9);
    for (a, b) in unturned
        .gap_mm
        .iter()
        .flatten()
        .zip(pitch.gap_mm.iter().flatten())
    {
        assert!(
            (a - b).abs() <= GAP_MM,
            "{a} mm unturned, {b} mm turned by a pitch"
        );
    }
}

/// A thinning shift deeper than the radius of a sharp concave root lifts the roller out of the
/// root onto both of its sides (tests/it/geometry.rs, `gap_at_tip_and_root_is_equidistant_minus_shift`):
/// two feet, equally near when the roller sits at the root, and the nearer one changes side as
/// the roller passes it. Followed from angle to angle, a foot would stay on the side it started
/// on; the sweep must notice (the locus distance there is beyond the reach bound) and find the
/// nearer side from scratch, as the reference does.
#[test]
fn rollers_lifted_onto_both_sides_of_a_sharp_root_match_from_scratch() {
    // K1 = 0.8 and 12 rollers: root radius Rp(1 − K1)²/(K1·np − 1) = 0.14 mm at Rp = 40; a shift
    // of −0.3 mm is deeper.
    let design: Design = design(12, 0.8 * 40.0 / 12.0, 40.0, 2.0);
    let m = Modification {
        shift_mm: -0.3,
        equidistant_mm: -0.25,
        rotation_rad: 0.0,
    };
    let mesh = Mesh::new(&design, &m);
    let reach = mesh.profile.locus_reach_bound_mm();
    assert!(reach < 0.2, "reach bound {reach} mm");
    // Roller 0 passes the root at φ = 0: sweep through it, one chunk either side.
    let crank = crank(-(6.4f64).to_radians(), 128);
    let r = reference(&mesh, &crank);
    let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent).unwrap();
    assert_matches("sharp root", &mesh, &crank, &s, &r);
    // The case is what it says: at the root, the two feet of roller 0 lie on either side.
    let at_root = crank.iter().position(|c| c.abs() < 1e-12).unwrap();
    let left = mesh
        .roller_gap(0, &Pose::ideal(crank[at_root - 1]), None)
        .unwrap();
    let right = mesh
        .roller_gap(0, &Pose::ideal(crank[at_root + 1]), None)
        .unwrap();
    let side = |t: f64| (t + 0.5 * TAU).rem_euclid(TAU) - 0.5 * TAU;
    assert!(
        side(left.t) * side(right.t) < 0.0,
        "feet at t = {} and {}",
        left.t,
        right.t
    );
}

/// Chunks are swept from nothing before them: the curves are the same bit for bit on one thread
/// and on four.
#[test]
fn sweep_is_the_same_on_one_and_on_four_threads() {
    let spec = paper_spec(0.125, 0.1593);
    let mesh = Mesh::new(&spec.design, &spec.modification);
    let crank = crank(0.0, 1000);
    let on = |threads: usize| {
        crate::common::on_threads(threads, || {
            (
                clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent)
                    .unwrap(),
                clearance::min_gap(&mesh, &crank).unwrap(),
            )
        })
    };
    assert_eq!(on(1), on(4));
}

/// Coarse steps (six per mesh period) move every roller far between angles, and at φ = P/2 a
/// roller of this interfering design sits on the centreline of a tooth (arm 0 at β = 0): the
/// evaluation from scratch says it does not close, while its closing lag followed from the
/// angle before lands on a root of its gap at β = 0.135 rad. The sweep must say what the
/// evaluation from scratch says (found by the mirror test of tests/it/geometry.rs).
#[test]
fn a_roller_on_a_tooth_centreline_closes_as_from_scratch() {
    let d = design(9, 1.8428811071417235, 20.0, 0.41553740648602533);
    let m = Modification {
        shift_mm: 0.14549986451839367,
        equidistant_mm: -0.20776870324301266,
        rotation_rad: 0.0,
    };
    let mesh = Mesh::new(&d, &m);
    let period = d.mesh_period_rad();
    let crank: Vec<f64> = (0..6).map(|k| k as f64 * period / 6.0).collect();
    let at_centre = mesh.roller_gap(5, &Pose::ideal(crank[3]), None).unwrap();
    assert!(at_centre.arm_mm.abs() < 1e-9, "arm {}", at_centre.arm_mm);
    let s = clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent).unwrap();
    assert_matches("centreline", &mesh, &crank, &s, &reference(&mesh, &crank));
}
