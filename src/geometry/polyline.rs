//! The modified profile as a polyline whose chords stay within a tolerance of the true curve:
//! what the profile export writes and the design review draws.

use super::profile::Profile;
use super::{cross, Vec2};
use std::f64::consts::TAU;

/// One exported profile point. Disc frame, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProfilePoint {
    pub t: f64,
    pub point: Vec2,
    /// Outward unit normal.
    pub normal: Vec2,
    /// Signed curvature of Γ, 1/mm (positive convex).
    pub curvature_per_mm: f64,
}

/// Largest distance of Γ from the chord Γ(a)Γ(b): the largest of 7 interior samples, refined
/// by golden section between its neighbours. The samples alone can miss the maximum by ~1 %
/// when it lies between them, and the chord would then exceed the tolerance.
fn chord_error(profile: &Profile, a: f64, b: f64) -> f64 {
    let (pa, pb) = (profile.point(a), profile.point(b));
    let chord = pb - pa;
    let len = chord.norm();
    let error = |t: f64| {
        let p = profile.point(t) - pa;
        if len > 0.0 {
            cross(p, chord).abs() / len
        } else {
            p.norm()
        }
    };
    let h = (b - a) / 8.0;
    let k = (1..8)
        .max_by(|&i, &j| error(a + h * i as f64).total_cmp(&error(a + h * j as f64)))
        .unwrap_or(4);
    let sampled = error(a + h * k as f64);
    let (mut lo, mut hi) = (a + h * (k - 1) as f64, a + h * (k + 1) as f64);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..40 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if error(x1) > error(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    sampled.max(error(0.5 * (lo + hi)))
}

/// Points of the whole closed profile (t in [0, 2π), the closing chord back to t = 0 implied)
/// with every chord within `tolerance_mm` of the profile. The step starts from the sagitta
/// estimate dt = sqrt(8·tol/(|κ|·|Γ'|²)) and is halved until the measured error meets the bound.
pub fn polyline(profile: &Profile, tolerance_mm: f64) -> Vec<ProfilePoint> {
    let max_step = TAU / (profile.rollers as f64 * 16.0);
    let mut points = Vec::new();
    let mut t = 0.0;
    while t < TAU {
        points.push(ProfilePoint {
            t,
            point: profile.point(t),
            normal: profile.normal(t),
            curvature_per_mm: profile.curvature(t),
        });
        let speed = profile.tangent(t).norm();
        let k = profile.curvature(t).abs().max(1e-12);
        let mut dt = (8.0 * tolerance_mm / k).sqrt() / speed;
        dt = dt.min(max_step).min(TAU - t);
        while chord_error(profile, t, t + dt) > tolerance_mm && dt > 1e-12 {
            dt *= 0.5;
        }
        // This chord closes the profile (its end is point 0, at t = 2π): stop here, rather than
        // let round-off in t + (2π − t) leave a duplicate of point 0 just short of 2π.
        if t + dt >= TAU - 1e-9 * dt {
            break;
        }
        t += dt;
    }
    points
}
