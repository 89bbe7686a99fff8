//! Profile export (issue 2): the polyline meets its chordal tolerance against the true profile,
//! its size follows the sagitta law, and the CSV and DXF texts carry exactly its points.

use crate::common::*;
use cycloid::geometry::profile::Profile;
use cycloid::geometry::{cross, Vec2};
use cycloid::report::export::{self, ProfilePoint};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// Distance from x to the segment ab.
fn distance_to_segment(x: Vec2, a: Vec2, b: Vec2) -> f64 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let s = if len2 > 0.0 {
        ((x - a).dot(&ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (x - (a + ab * s)).norm()
}

/// The true chordal error of the chord Γ(ta)Γ(tb): the largest distance of Γ between ta and tb
/// from the segment, by 16 samples and a golden-section refinement around the largest (the
/// distance is smooth and single-peaked between the ends of a short chord, so the refinement
/// finds the maximum to round-off; no reliance on where the exporter itself looked).
fn chordal_error(profile: &Profile, ta: f64, tb: f64) -> f64 {
    let (a, b) = (profile.point(ta), profile.point(tb));
    let err = |t: f64| distance_to_segment(profile.point(t), a, b);
    let n = 16;
    let h = (tb - ta) / n as f64;
    let k = (1..n)
        .max_by(|&i, &j| err(ta + i as f64 * h).total_cmp(&err(ta + j as f64 * h)))
        .unwrap();
    let (mut lo, mut hi) = (ta + (k - 1) as f64 * h, ta + (k + 1) as f64 * h);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if err(x1) > err(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    err(0.5 * (lo + hi)).max(err(ta + k as f64 * h))
}

/// Largest chordal error over every chord, the closing one (last point back to t = 2π) included.
fn worst_chordal_error(profile: &Profile, points: &[ProfilePoint]) -> f64 {
    (0..points.len())
        .map(|k| {
            let ta = points[k].t;
            let tb = points.get(k + 1).map_or(TAU, |p| p.t);
            chordal_error(profile, ta, tb)
        })
        .fold(0.0, f64::max)
}

/// Checks every polyline must pass: starts at t = 0, t increasing within [0, 2π), points on Γ,
/// no zero-length chord (a duplicate closing point would be one), unit normals.
fn check_polyline(profile: &Profile, points: &[ProfilePoint]) -> std::result::Result<(), String> {
    if points.first().map(|p| p.t) != Some(0.0) {
        return Err("the polyline must start at t = 0 (the root)".into());
    }
    for (k, p) in points.iter().enumerate() {
        let next_t = points.get(k + 1).map_or(TAU, |q| q.t);
        if next_t <= p.t || p.t >= TAU {
            return Err(format!("t not increasing in [0, 2π) at point {k}: {}", p.t));
        }
        // Points are Γ(t) exactly (same evaluation), up to round-off.
        if (p.point - profile.point(p.t)).norm() > 1e-12 {
            return Err(format!("point {k} is not on Γ"));
        }
        if (p.normal.norm() - 1.0).abs() > 1e-12 {
            return Err(format!("normal {k} is not unit: {}", p.normal.norm()));
        }
        let next = points.get(k + 1).unwrap_or(&points[0]).point;
        // Chords are at least the step a 1e-3 µm tolerance would need anywhere (≫ 1e-9 mm).
        if (next - p.point).norm() < 1e-9 {
            return Err(format!(
                "zero-length chord after point {k} (t = {} → {next_t})",
                p.t
            ));
        }
    }
    Ok(())
}

/// The fewest chords any polyline within `tol` can have: a chord of sagitta ≤ tol on an arc of
/// curvature κ spans at most sqrt(8·tol/|κ|) of arc length, so N ≥ ∫ sqrt(|κ|/(8·tol)) ds.
/// κ and ds from central differences of Γ (midpoint rule over 20 000 steps: the integrand is
/// smooth except for |κ|^½ kinks at inflections, which cost ≪ 1 %).
fn sagitta_lower_bound(profile: &Profile, tol: f64) -> f64 {
    let n = 20_000;
    let dt = TAU / n as f64;
    let h = 1e-4;
    (0..n)
        .map(|k| {
            let t = (k as f64 + 0.5) * dt;
            let (a, m, b) = (profile.point(t - h), profile.point(t), profile.point(t + h));
            let d1 = (b - a) / (2.0 * h);
            let d2 = (b - 2.0 * m + a) / (h * h);
            let kappa = cross(d1, d2) / d1.norm().powi(3);
            (kappa.abs() / (8.0 * tol)).sqrt() * d1.norm() * dt
        })
        .sum()
}

fn paper_profile() -> (cycloid::spec::Spec, Profile) {
    let spec = paper_spec(0.125, 0.1593);
    let profile = Profile::new(&spec.design, &spec.modification);
    (spec, profile)
}

/// The paper's optimum profile at 0.5 µm and 5 µm: every chord, the closing one included, is
/// within the tolerance of the true profile.
#[test]
fn polyline_meets_its_chordal_tolerance() {
    let (_, profile) = paper_profile();
    for tol_um in [0.5, 5.0] {
        let tol = tol_um * 1e-3;
        let points = export::polyline(&profile, tol);
        check_polyline(&profile, &points).unwrap();
        let worst = worst_chordal_error(&profile, &points);
        println!(
            "tolerance {tol_um} µm: {} points, worst chordal error {:.4} µm",
            points.len(),
            worst * 1e3
        );
        // The refined maximum is exact to round-off (~1e-13 mm); nothing else to allow for.
        assert!(
            worst <= tol + 1e-12,
            "worst chordal error {worst} mm over the tolerance {tol} mm"
        );
    }
}

/// Point count follows the sagitta law N ∝ tol^(−½): between the lower bound of any polyline
/// within the tolerance and twice it (the exporter halves a step until it fits, so a chord's
/// error lies in (tol/4, tol], i.e. its length is at least half the longest admissible)
/// plus the 16·np points that its cap on the step (2π/(16·np) in t) can add. Tenfold
/// tolerance then gives about sqrt(10) ≈ 3.16 times fewer points.
#[test]
fn point_count_grows_as_one_over_sqrt_tolerance() {
    let (spec, profile) = paper_profile();
    let np = spec.design.rollers as f64;
    let mut counts = Vec::new();
    for tol_um in [0.5, 5.0] {
        let tol = tol_um * 1e-3;
        let n = export::polyline(&profile, tol).len() as f64;
        let bound = sagitta_lower_bound(&profile, tol);
        println!("tolerance {tol_um} µm: {n} points, sagitta lower bound {bound:.1}");
        // 2 % for the asymptotic (small-chord) form of the bound at 5 µm.
        assert!(n >= 0.98 * bound, "{n} points beat the lower bound {bound}");
        assert!(n <= 2.0 * bound + 16.0 * np, "{n} points, bound {bound}");
        counts.push(n);
    }
    let ratio = counts[0] / counts[1];
    println!("count ratio 0.5 µm / 5 µm: {ratio:.3} (sqrt(10) = 3.162)");
    // The halving quantises steps by factors of 2 at each tolerance independently: the ratio
    // can move from sqrt(10) by up to that factor in principle, by far less in aggregate.
    assert!((2.5..4.0).contains(&ratio), "count ratio {ratio}");
}

proptest! {
    /// Random valid designs and modifications at 5 µm: every chord within tolerance, points on
    /// Γ, no zero-length chord.
    #[test]
    fn polyline_meets_its_tolerance_for_any_design(c in cases()) {
        let profile = Profile::new(&c.design, &c.m);
        let tol = 5e-3;
        let points = export::polyline(&profile, tol);
        if let Err(e) = check_polyline(&profile, &points) {
            return Err(TestCaseError::fail(e));
        }
        let worst = worst_chordal_error(&profile, &points);
        prop_assert!(worst <= tol + 1e-12, "worst chordal error {worst} mm");
    }
}

/// DXF (R12) structure: pairs of (group code, value) lines; a HEADER section with
/// $INSUNITS = 4 (mm); an ENTITIES section with one POLYLINE on layer PROFILE, flag 70 = 1
/// (closed), one VERTEX per point with its coordinates, SEQEND; one CIRCLE per output-pin hole
/// on layer HOLE_j; ENDSEC; EOF last.
#[test]
fn dxf_is_a_closed_polyline_in_mm_with_every_point() {
    let (spec, profile) = paper_profile();
    let tol = 5e-3;
    let points = export::polyline(&profile, tol);
    let text = export::dxf(&spec, &points, tol);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len() % 2, 0, "DXF is made of code/value line pairs");
    let pairs: Vec<(i32, &str)> = lines
        .chunks(2)
        .map(|p| {
            let code = p[0].trim().parse::<i32>().unwrap_or_else(|_| {
                panic!("group code `{}` is not an integer", p[0]);
            });
            (code, p[1].trim())
        })
        .collect();
    // Comments (999) may come first and nowhere else.
    let body: Vec<(i32, &str)> = pairs.iter().copied().skip_while(|p| p.0 == 999).collect();
    assert!(body.iter().all(|p| p.0 != 999));
    let mut it = body.iter().copied();
    let mut expect = |code: i32, value: &str| {
        let got = it.next().expect("DXF ends early");
        assert_eq!(got, (code, value), "expected ({code}, {value})");
    };
    for (c, v) in [
        (0, "SECTION"),
        (2, "HEADER"),
        (9, "$INSUNITS"),
        (70, "4"),
        (0, "ENDSEC"),
        (0, "SECTION"),
        (2, "ENTITIES"),
        (0, "POLYLINE"),
        (8, "PROFILE"),
        (66, "1"),
        (70, "1"),
    ] {
        expect(c, v);
    }
    // POLYLINE's dummy point, then the vertices.
    let rest: Vec<(i32, &str)> = body.iter().copied().skip(11).collect();
    assert_eq!(&rest[..3], &[(10, "0.0"), (20, "0.0"), (30, "0.0")]);
    let vertices: Vec<&[(i32, &str)]> = rest[3..]
        .chunks(5)
        .take_while(|c| c[0] == (0, "VERTEX"))
        .collect();
    assert_eq!(vertices.len(), points.len(), "one VERTEX per point");
    for (v, p) in vertices.iter().zip(&points) {
        assert_eq!(v[1], (8, "PROFILE"));
        assert_eq!((v[2].0, v[3].0, v[4]), (10, 20, (30, "0.0")));
        let (x, y): (f64, f64) = (v[2].1.parse().unwrap(), v[3].1.parse().unwrap());
        // Written with 9 decimals: ±5e-10 mm.
        assert!((x - p.point.x).abs() <= 5e-10 && (y - p.point.y).abs() <= 5e-10);
    }
    let tail: Vec<(i32, &str)> = rest[3 + 5 * vertices.len()..].to_vec();
    assert_eq!(&tail[..2], &[(0, "SEQEND"), (8, "PROFILE")]);
    // The paper's 6 holes: on the pin circle rw = 18 mm at 60° steps, radius pin + e + clearance.
    let pins = &spec.design.pins;
    let circles: Vec<&[(i32, &str)]> = tail[2..].chunks(6).take(pins.count).collect();
    for (j, c) in circles.iter().enumerate() {
        assert_eq!(&c[..2], &[(0, "CIRCLE"), (8, format!("HOLE_{j}").as_str())]);
        let (x, y, r): (f64, f64, f64) = (
            c[2].1.parse().unwrap(),
            c[3].1.parse().unwrap(),
            c[5].1.parse().unwrap(),
        );
        let a = (60.0 * j as f64).to_radians();
        assert!((x - pins.circle_radius_mm * a.cos()).abs() <= 5e-10);
        assert!((y - pins.circle_radius_mm * a.sin()).abs() <= 5e-10);
        let radius = pins.pin_radius_mm + spec.design.eccentricity_mm + pins.hole_clearance_mm;
        assert!((r - radius).abs() <= 5e-10);
    }
    assert_eq!(&tail[2 + 6 * pins.count..], &[(0, "ENDSEC"), (0, "EOF")]);
}

/// CSV: `#` header lines (they state the point count), the column header, one row per point
/// with the point, a unit outward normal and the curvature. Outward: the normal is
/// perpendicular to the polyline there (to within the tangent's turn over the neighbouring
/// chords) and points away from the disc centre (the disc is star-shaped about it).
#[test]
fn csv_has_the_header_and_a_row_per_point_with_unit_outward_normals() {
    let (spec, profile) = paper_profile();
    let tol = 5e-3;
    let points = export::polyline(&profile, tol);
    let text = export::csv(&spec, &points, tol);
    let comments: Vec<&str> = text.lines().take_while(|l| l.starts_with('#')).collect();
    assert!(!comments.is_empty());
    assert!(comments
        .iter()
        .any(|l| l.contains(&format!("{} points", points.len()))));
    let mut lines = text.lines().skip(comments.len());
    assert_eq!(
        lines.next(),
        Some("x_mm,y_mm,normal_x,normal_y,curvature_per_mm")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse::<f64>().expect("a number"))
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), points.len(), "one row per point");
    let n = rows.len();
    let mut worst_tilt: f64 = 0.0;
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(r.len(), 5);
        let (p, normal) = (Vec2::new(r[0], r[1]), Vec2::new(r[2], r[3]));
        // x, y with 9 decimals (±5e-10 mm); normal components with 12 (±5e-13 each).
        assert!((p - points[k].point).norm() <= 1e-9);
        assert!(
            (normal.norm() - 1.0).abs() <= 1e-12,
            "row {k}: |n| = {}",
            normal.norm()
        );
        assert!(normal.dot(&p) > 0.0, "row {k}: normal points into the disc");
        let prev = Vec2::new(rows[(k + n - 1) % n][0], rows[(k + n - 1) % n][1]);
        let next = Vec2::new(rows[(k + 1) % n][0], rows[(k + 1) % n][1]);
        let chord = (next - prev).normalize();
        worst_tilt = worst_tilt.max(normal.dot(&chord).abs());
        // Curvature in the same units as the profile's (1/mm), from the same point.
        assert!((r[4] - points[k].curvature_per_mm).abs() <= 1e-9 * (1.0 + r[4].abs()));
        // And counter-clockwise order: the chord turns left of the outward normal.
        assert!(
            cross(normal, chord) > 0.0,
            "row {k}: points not counter-clockwise"
        );
    }
    // A chord of sagitta ≤ tol on curvature κ turns the tangent by sqrt(8·tol·|κ|) at most;
    // with |κ_Γ| ≤ 1/(ρ_min − r') on convex parts and ≤ 1/r' on the concave root, at 5 µm the
    // tilt of the neighbour chord against the tangent stays below ~0.1 rad.
    println!("largest |n·chord| {worst_tilt:.4}");
    assert!(worst_tilt < 0.1);
}

/// The profile document (what the Python `profile` returns) holds the CSV's columns to their
/// printed decimals and the DXF's holes: M holes, hole j at angle 2πj/M on the pin circle rw,
/// radius pin + e + hole clearance (the spec's 3 + 2 + 0 mm).
#[test]
fn the_profile_document_is_the_csv_with_the_dxf_holes() {
    let (spec, profile) = paper_profile();
    let tol = 5e-3;
    let points = export::polyline(&profile, tol);
    let doc = export::ProfileDoc::new(&spec, &points);
    let text = export::csv(&spec, &points, tol);
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let columns = [
        &doc.x_mm,
        &doc.y_mm,
        &doc.normal_x,
        &doc.normal_y,
        &doc.curvature_per_mm,
    ];
    assert_eq!(
        header,
        ["x_mm", "y_mm", "normal_x", "normal_y", "curvature_per_mm"]
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), points.len());
    for (k, row) in rows.iter().enumerate() {
        for (c, cell) in row.split(',').enumerate() {
            let read: f64 = cell.parse().unwrap();
            let value = columns[c][k];
            // Half a unit of the CSV's last printed decimal: 9 for x, y (mm), 12 for the
            // normal, 10 significant digits for the curvature; doubled for the value's own
            // round-off at that size.
            let half_unit = match c {
                0 | 1 => 5e-10,
                2 | 3 => 5e-13,
                _ => 5e-10 * value.abs(),
            };
            assert!(
                (read - value).abs() <= 2.0 * half_unit,
                "{} row {k}",
                header[c]
            );
        }
    }
    let pins = &spec.design.pins;
    assert_eq!(pins.count, 6);
    assert_eq!((doc.holes_x_mm.len(), doc.holes_y_mm.len()), (6, 6));
    for j in 0..6 {
        let a = TAU * j as f64 / 6.0;
        // The centre's two products of rw with cos, sin: a few ulp of 18 mm.
        assert!(
            (doc.holes_x_mm[j] - 18.0 * a.cos()).abs() < 1e-13,
            "hole {j}"
        );
        assert!(
            (doc.holes_y_mm[j] - 18.0 * a.sin()).abs() < 1e-13,
            "hole {j}"
        );
    }
    assert_eq!(doc.hole_radius_mm, 3.0 + 2.0 + 0.0);
}
