//! Profile export: the modified disc profile as CSV points and as a closed DXF polyline,
//! spaced so that the chordal error (distance of the true profile from each chord) stays
//! under a tolerance.

use crate::geometry::profile::Profile;
use crate::geometry::Vec2;
use crate::spec::Spec;
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
            (p.x * chord.y - p.y * chord.x).abs() / len
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

fn header_lines(spec: &Spec, tolerance_mm: f64, count: usize) -> Vec<String> {
    let m = &spec.modification;
    vec![
        format!("cycloid profile of spec `{}` ({})", spec.name, spec.path),
        format!(
            "modification: shift {} mm, equidistant {} mm, rotation {} deg",
            m.shift_mm,
            m.equidistant_mm,
            m.rotation_rad.to_degrees()
        ),
        format!(
            "units: mm, disc frame (origin at disc centre, tooth root on +x); \
             {count} points, chordal error <= {} um",
            tolerance_mm * 1000.0
        ),
    ]
}

/// CSV text: `#` header lines, then x_mm,y_mm,normal_x,normal_y,curvature_per_mm.
pub fn csv(spec: &Spec, points: &[ProfilePoint], tolerance_mm: f64) -> String {
    let mut out: String = header_lines(spec, tolerance_mm, points.len())
        .iter()
        .map(|l| format!("# {l}\n"))
        .collect();
    out += "x_mm,y_mm,normal_x,normal_y,curvature_per_mm\n";
    for p in points {
        out += &format!(
            "{:.9},{:.9},{:.12},{:.12},{:.9e}\n",
            p.point.x, p.point.y, p.normal.x, p.normal.y, p.curvature_per_mm
        );
    }
    out
}

/// DXF (R12) text: one closed POLYLINE on layer PROFILE, and the output-pin holes as CIRCLE
/// entities on layers HOLE_0 … HOLE_{M−1} (hole j at angle 2πj/M on the pin circle, its radius
/// the pin's plus e plus the hole clearance; cut in the same set-up, they fix the rotation
/// modification), units mm ($INSUNITS = 4).
pub fn dxf(spec: &Spec, points: &[ProfilePoint], tolerance_mm: f64) -> String {
    let mut out = String::new();
    let mut pair = |code: i32, value: &str| out += &format!("{code}\n{value}\n");
    for line in header_lines(spec, tolerance_mm, points.len()) {
        pair(999, &line);
    }
    for (code, value) in [(0, "SECTION"), (2, "HEADER"), (9, "$INSUNITS"), (70, "4")] {
        pair(code, value);
    }
    pair(0, "ENDSEC");
    for (code, value) in [
        (0, "SECTION"),
        (2, "ENTITIES"),
        (0, "POLYLINE"),
        (8, "PROFILE"),
    ] {
        pair(code, value);
    }
    for (code, value) in [(66, "1"), (70, "1"), (10, "0.0"), (20, "0.0"), (30, "0.0")] {
        pair(code, value);
    }
    for p in points {
        pair(0, "VERTEX");
        pair(8, "PROFILE");
        pair(10, &format!("{:.9}", p.point.x));
        pair(20, &format!("{:.9}", p.point.y));
        pair(30, "0.0");
    }
    for (code, value) in [(0, "SEQEND"), (8, "PROFILE")] {
        pair(code, value);
    }
    let pins = &spec.design.pins;
    for j in 0..pins.count {
        let a = std::f64::consts::TAU * j as f64 / pins.count as f64;
        pair(0, "CIRCLE");
        pair(8, &format!("HOLE_{j}"));
        pair(10, &format!("{:.9}", pins.circle_radius_mm * a.cos()));
        pair(20, &format!("{:.9}", pins.circle_radius_mm * a.sin()));
        pair(30, "0.0");
        pair(40, &format!("{:.9}", spec.design.hole_radius_mm()));
    }
    for (code, value) in [(0, "ENDSEC"), (0, "EOF")] {
        pair(code, value);
    }
    out
}
