//! The design review's drawing of the disc as built (issue 16: "the measured points against
//! the design profile, deviation magnified, with the scale stated"): each point drawn on the
//! design profile's normal at M times its deviation, checked against a closest point found
//! independently and, end to end, by reading the drawn SVG back.

use crate::common::*;
use cycloid::geometry::profile::Profile;
use cycloid::geometry::Vec2;
use cycloid::measure::fit::{self, Request};
use cycloid::measure::{Feature, MeasuredPoint};
use cycloid::model::measured::Fitted;
use cycloid::model::{FormTerm, Modification};
use cycloid::report::review::as_built::{against_design, magnification};
use std::f64::consts::TAU;

/// The disc as made: the paper's optimum with a form error of orders 3 and 6 (4 and 2 µm):
/// over a whole turn it runs from −3 to +6 µm, so that −w and w are not alike.
fn made() -> (Modification, Vec<FormTerm>) {
    let form = vec![
        FormTerm {
            order: 3,
            cos_mm: 0.004,
            sin_mm: 0.0,
        },
        FormTerm {
            order: 6,
            cos_mm: 0.002,
            sin_mm: 0.0,
        },
    ];
    (modification(0.125, 0.1593, 0.0), form)
}

fn w(form: &[FormTerm], t: f64) -> f64 {
    form.iter()
        .map(|f| f.cos_mm * (f.order as f64 * t).cos() + f.sin_mm * (f.order as f64 * t).sin())
        .sum()
}

/// `count` points of the made disc at evenly spread t, in a machine frame moved by (5, −3) mm
/// and turned by 17°, with the t of each.
fn measured(count: usize) -> (Vec<MeasuredPoint>, Vec<f64>) {
    let (m, form) = made();
    let truth = Profile::new(&paper_design(), &m).with_form(&form);
    let (s, c) = 17f64.to_radians().sin_cos();
    (0..count)
        .map(|k| {
            let t = TAU * (k as f64 + 0.5) / count as f64;
            let p = truth.point(t);
            let point = MeasuredPoint {
                point: Vec2::new(c * p.x - s * p.y + 5.0, s * p.x + c * p.y - 3.0),
                feature: Feature::Profile,
                line: k + 2,
            };
            (point, t)
        })
        .unzip()
}

/// Each point against the design profile (the spec's modification, 25 µm of shift and 9 µm of
/// equidistant away from the made disc): its deviation is its distance to the design profile
/// found by golden section on |q − Γ(t)| (within ±0.05 rad of the point's t: the foot moves by
/// ~1e-3 rad for 25 µm), positive inside (the design normal pointing away from the point);
/// its foot is that closest point; drawn at magnification m it sits at foot + m·(q − foot), on
/// the same side, m·|d| from the outline. Tolerances: the golden section's t to ~1e-8 rad
/// (square root of ε on a quadratic minimum), ~6e-7 mm along the profile at |Γ'| ≤ 63 mm/rad,
/// so 1e-5 mm on the foot; the distance is stationary there, 1e-10 mm.
#[test]
fn drawn_points_are_their_deviation_from_the_design_magnified() {
    let d = paper_design();
    let (points, _) = measured(360);
    let designed = modification(0.1, 0.15, 0.0);
    let request = Request {
        design: &d,
        nominal: designed,
        fit: Fitted {
            shift: true,
            equidistant: true,
            rotation: false,
        },
        harmonics: 12,
    };
    let id = fit::identify(&request, &points).expect("the made disc is identified");
    let spec = PaperSpec::new().modification(0.1, 0.15).parse("spec.yaml");
    let against = against_design(&spec, &designed, &id);
    assert_eq!(against.len(), 360, "every point has its foot");
    let design = Profile::new(&d, &designed);
    let mut inside = 0;
    for a in &against {
        let q = a.point;
        let dist = |t: f64| (q - design.point(t)).norm();
        let t = golden_section_min(dist, a.t - 0.05, a.t + 0.05);
        let foot = design.point(t);
        let sign = if (q - foot).dot(&design.normal(t)) < 0.0 {
            1.0
        } else {
            -1.0
        };
        assert!(
            (a.deviation_mm - sign * dist(t)).abs() < 1e-10,
            "at t = {}: {} vs {}",
            a.t,
            a.deviation_mm,
            sign * dist(t)
        );
        assert!((a.foot - foot).norm() < 1e-5, "foot at t = {}", a.t);
        assert!((a.magnified(1.0) - q).norm() < 1e-12);
        let m = 200.0;
        let drawn = a.magnified(m);
        assert!(((drawn - a.foot) - (q - a.foot) * m).norm() < 1e-9);
        assert!((((drawn - foot).norm()) - m * a.deviation_mm.abs()).abs() < 1e-3);
        inside += usize::from(a.deviation_mm > 0.0);
    }
    // The disc as made has thicker teeth than designed (ΔRp 25 µm more) and a form error of
    // 6 µm at most: most points are outside the design's outline, where material was added,
    // and some inside (the tip clearance grew by 9 µm less than the shift).
    assert!(
        inside < against.len() / 2,
        "{inside} of {} inside",
        against.len()
    );
}

/// The magnification is the largest 1, 2 or 5 × 10^k that draws the largest deviation within
/// half the tooth height, and 1 when nothing deviates (no NaN, no infinity).
#[test]
fn the_magnification_is_a_round_number_within_half_a_tooth() {
    for (largest, height, expected) in [
        (0.006, 4.0, 200.0),
        (0.004, 4.0, 500.0),
        (0.0101, 4.0, 100.0),
        (0.02, 4.0, 100.0),
        (0.021, 4.0, 50.0),
        (0.5, 4.0, 2.0),
        (3.0, 4.0, 1.0),
        (0.0, 4.0, 1.0),
    ] {
        assert_eq!(
            magnification(largest, height),
            expected,
            "{largest} of {height}"
        );
    }
}

/// The value of attribute `name` in an SVG tag's text.
fn attr(tag: &str, name: &str) -> f64 {
    let key = format!(" {name}=\"");
    let at = tag.find(&key).unwrap_or_else(|| panic!("{name} in {tag}")) + key.len();
    tag[at..at + tag[at..].find('"').unwrap()].parse().unwrap()
}

/// Distance from p to the segment ab.
fn to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let l2 = dx * dx + dy * dy;
    let u = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / l2).clamp(0.0, 1.0);
    (p.0 - a.0 - u * dx).hypot(p.1 - a.1 - u * dy)
}

/// Even-odd point in polygon.
fn inside(p: (f64, f64), polygon: &[(f64, f64)]) -> bool {
    let mut odd = false;
    for (i, &a) in polygon.iter().enumerate() {
        let b = polygon[(i + 1) % polygon.len()];
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            odd = !odd;
        }
    }
    odd
}

/// End to end: `check --report` with 720 points of the made disc and the made modification as
/// the spec's (nothing fitted but the frame and the form), so that each point's deviation from
/// the design profile is the form error w(t) at the t it was made at (the point is on the
/// design's normal at t). Read back from the SVG: the magnification stated in the title (and
/// the caption) is the round number for the largest |w|, the true-scale bar gives the pixels
/// per mm, and every drawn point's signed distance to the drawn outline (outside positive),
/// over the scale and M, is −w of one point: the sorted lists agree (w is not symmetric, so a
/// point drawn on the wrong side fails, as does one drawn at another magnification), and the
/// points drawn inside are those with w > 0. Tolerance: the outline is a polyline within
/// (Rp + Rrp)/20000 = 1.65e-3 mm of the curve, and both its vertices and the points are written
/// to 0.005 px in x and y (7e-4 mm at 10.4 px/mm): 3.1e-3 mm, 5e-3 mm on the drawing (seen:
/// 2.5e-3 mm), 25 nm of deviation at M = 200, against deviations of up to 6 µm.
/// A spec without measured points has no such section or drawing.
#[test]
fn the_review_draws_the_points_at_their_magnified_deviation() {
    let dir = Scratch::new("as-built-drawing");
    let (points, ts) = measured(720);
    let mut csv = String::from("x_mm,y_mm\n");
    for p in &points {
        csv += &format!("{:?},{:?}\n", p.point.x, p.point.y);
    }
    dir.write("points.csv", &csv);
    let scene = scene_item(
        "mesh",
        0.0,
        "{ from_deg: 0.0, to_deg: 36.0, steps: 36 }",
        "clearance",
    );
    let plain = PaperSpec::new().modification(0.125, 0.1593).scenes(&scene);
    let spec = plain
        .clone()
        .with("measured_profile: {file: points.csv, format: csv, harmonics: 12, fit: []}\n");
    dir.write("measured.yaml", spec.text());
    let run = cycloid(&dir.path, &["check", "measured.yaml", "--report", "review"]);
    assert_eq!(run.code(), 0, "{}{}", run.stdout, run.stderr);
    let (_, form) = made();
    let deviations: Vec<f64> = ts.iter().map(|&t| w(&form, t)).collect();
    let largest = deviations.iter().map(|d| d.abs()).fold(0.0, f64::max);
    // Half the tooth height 2e = 4 mm over the largest deviation, rounded down to 1-2-5.
    let raw = 2.0 / largest;
    let decade = 10f64.powf(raw.log10().floor());
    let m = [5.0, 2.0, 1.0]
        .iter()
        .map(|k| k * decade)
        .find(|&k| k <= raw)
        .unwrap();
    assert_eq!(m, 200.0, "largest {largest} mm");
    let svg = dir.read("review/as-built-disc.svg");
    assert!(svg.contains("deviation ×200</text>"), "the title states M");
    let page = dir.read("review/index.html");
    assert!(page.contains("The disc as built against the design, deviation ×200"));
    // Pixels per mm from the true-scale bar: the line before its label.
    let label = svg.find(">10 mm</text>").expect("a 10 mm bar");
    let bar = &svg[svg[..label].rfind("<line ").unwrap()..label];
    let scale = (attr(bar, "x2") - attr(bar, "x1")) / 10.0;
    // The outline: the path's first subpath.
    let d_at = svg.find("<path d=\"M").expect("the outline") + "<path d=\"M".len();
    let outline: Vec<(f64, f64)> = svg[d_at..d_at + svg[d_at..].find(" Z").unwrap()]
        .split(' ')
        .map(|xy| {
            let (x, y) = xy.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect();
    assert!(outline.len() > 200, "{} vertices", outline.len());
    let mut drawn: Vec<f64> = svg
        .split("<circle class=\"measured\"")
        .skip(1)
        .map(|tag| {
            let p = (attr(tag, "cx"), attr(tag, "cy"));
            let distance = (0..outline.len())
                .map(|i| to_segment(p, outline[i], outline[(i + 1) % outline.len()]))
                .fold(f64::INFINITY, f64::min);
            let side = if inside(p, &outline) { -1.0 } else { 1.0 };
            side * distance / scale / m
        })
        .collect();
    assert_eq!(drawn.len(), 720, "one dot per point");
    let mut expected: Vec<f64> = deviations.iter().map(|d| -d).collect();
    drawn.sort_by(f64::total_cmp);
    expected.sort_by(f64::total_cmp);
    let worst = drawn
        .iter()
        .zip(&expected)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(worst < 0.005 / m, "worst {worst} mm of deviation");
    // Inside where material is missing: every point with w beyond the tolerance is drawn on
    // its side, those within it on either.
    let clear = 0.005 / m;
    let drawn_inside = drawn.iter().filter(|d| **d < 0.0).count();
    let surely = deviations.iter().filter(|w| **w > clear).count();
    let maybe = deviations.iter().filter(|w| **w > -clear).count();
    assert!(
        (surely..=maybe).contains(&drawn_inside),
        "{drawn_inside} inside, {surely}..{maybe} expected"
    );
    // The scene's smallest gap over the crank, designed against as built, beside the drawing.
    assert!(page.contains("src=\"as-built-1-clearance.svg\""));
    let compared = dir.read("review/as-built-1-clearance.svg");
    assert!(compared.contains("mesh: smallest gap, designed and as built"));
    dir.write("plain.yaml", plain.text());
    let run = cycloid(&dir.path, &["check", "plain.yaml", "--report", "plain"]);
    assert_eq!(run.code(), 0, "{}{}", run.stdout, run.stderr);
    assert!(!dir.read("plain/index.html").contains("Disc as built"));
    assert!(!dir.exists("plain/as-built-disc.svg"));
    assert!(!dir.exists("plain/as-built-1-clearance.svg"));
}
