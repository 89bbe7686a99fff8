//! The disc's mass properties and the inertia at the input (issue 42) against closed forms: the
//! polygon integration on a polygonal circle (πr², πr⁴/2), a hole by the parallel-axis theorem,
//! the face of the shipped disc by Steiner's formula for the area inside an offset curve, and
//! the e → 0 limit of a whole spec (a plain annulus with holes), its inertia at the input.

use cycloid::geometry::disc_solid::{circle_polygon, Circle};
use cycloid::geometry::mass_properties::{circle_moments, polygon_moments};
use cycloid::geometry::Vec2;
use cycloid::{check, progress::Silent, CheckOptions};
use std::f64::consts::PI;

/// The circle of radius 12 mm as a polygon whose chords stay within 1 µm of it has A and J of
/// the circle, low by at most the sliver between chord and arc: at most tol × perimeter of
/// area, and that area at most r² from the centre, so ΔA ≤ 2πr·tol and ΔJ ≤ r²·2πr·tol.
#[test]
fn a_polygonal_circle_has_the_circles_area_and_polar_moment() {
    let (r, tol) = (12.0_f64, 1e-3);
    let points = circle_polygon(
        &Circle {
            centre: Vec2::zeros(),
            radius_mm: r,
        },
        tol,
        false,
    );
    let m = polygon_moments(&points);
    let (area, polar) = (PI * r * r, 0.5 * PI * r.powi(4));
    let sliver = 2.0 * PI * r * tol;
    assert!(m.area_mm2 <= area && area - m.area_mm2 <= sliver, "{m:?}");
    assert!(
        m.polar_mm4 <= polar && polar - m.polar_mm4 <= r * r * sliver,
        "{m:?}"
    );
    // Clockwise, the same moments negated.
    let cw = polygon_moments(&circle_polygon(
        &Circle {
            centre: Vec2::zeros(),
            radius_mm: r,
        },
        tol,
        true,
    ));
    assert!((cw.area_mm2 + m.area_mm2).abs() < 1e-9 * area);
}

/// A hole of radius 5 mm centred 18 mm off the disc centre, integrated as a fine polygon about
/// the disc centre, has the closed form of the parallel-axis theorem the disc subtracts its
/// holes by: A = πr², S = A·c, J = A·(r²/2 + |c|²). The polygon is low by the sliver of
/// 2πr·tol of area lying at most |c| + r from the disc centre.
#[test]
fn a_hole_off_centre_follows_the_parallel_axis_theorem() {
    let (r, tol) = (5.0_f64, 1e-5);
    let hole = Circle {
        centre: Vec2::new(18.0 * 0.6, 18.0 * 0.8),
        radius_mm: r,
    };
    let polygon = polygon_moments(&circle_polygon(&hole, tol, false));
    let closed = circle_moments(&hole);
    let sliver = 2.0 * PI * r * tol;
    let far = 18.0 + r;
    assert!((closed.area_mm2 - polygon.area_mm2).abs() <= sliver);
    assert!((closed.first_mm3 - polygon.first_mm3).norm() <= far * sliver);
    assert!((closed.polar_mm4 - polygon.polar_mm4).abs() <= far * far * sliver);
    let expected = PI * r * r * (0.5 * r * r + 18.0 * 18.0);
    assert!((closed.polar_mm4 / expected - 1.0).abs() < 1e-14);
}

/// The shipped disc (specs/reducer.yaml: R' = 30.125, r' = 3.1593, e = 2, np = 10, six holes of
/// radius 5 on an 18 mm circle, B = 8, steel). The profile is the inward parallel curve at r' of
/// the locus C(t) = R'·e^{it} − e·e^{i·np·t}, regular (no undercut), so Steiner's formula gives
/// the area inside it: A_C − r'·L_C + π·r'², with A_C = ½∮ C × C' = π(R'² + np·e²) and L_C the
/// locus's length ∫|C'| (|C'|² = R'² + np²e² − 2·np·R'·e·cos((np − 1)t)), here by the periodic
/// trapezoid rule on 20,000 points (exponentially convergent: round-off). The disc's face is
/// that less six πr²; its mass ρ·B times it. The check integrates the profile itself, Γ and
/// Γ', not the locus, to 1e-13 (`PROFILE_MOMENTS_REL_TOL`): the two agree to round-off, and
/// 1e-11 of the face is allowed (sums of 20,000 terms). Before, a polygon at 0.1 µm was off by
/// up to tol × perimeter (~170 mm): 0.02 mm², and by 2.6e-3 mm² in fact.
#[test]
fn the_shipped_discs_area_is_steiners_formula_for_its_offset_profile() {
    let spec = cycloid::spec::load("specs/reducer.yaml").unwrap();
    let run = check(&spec, &CheckOptions::default(), &Silent).unwrap();
    let face = steiner_face((30.125, 3.1593, 2.0, 10.0), 6.0 * PI * 25.0);
    let got = run.mass.disc.face.area_mm2;
    assert!((face - got).abs() <= 1e-11 * face, "{got} vs {face}");
    let mass = 7850e-9 * 8.0 * face;
    assert!((run.mass.disc.mass_kg / mass - 1.0).abs() < 1e-11);
    // By its symmetry the disc's centroid is its centre, to round-off (as above).
    assert!(run.mass.disc.centroid_offset_mm < 1e-10);
}

/// The same near the undercut (specs/hard/undercut-99pct.yaml: R' = 30, r' = 7.58 + 0.03,
/// e = 2.4, np = 10, six holes of radius 2.5 + 2.4 on 11 mm): the profile's convex radius
/// falls to 0.08 mm at its tips (Γ' small there; the sums still converge at 1,281 points, the
/// rate being set by K1, next test). Its first moment's harmonics (±1 mod 9 lobes) once
/// aliased onto the mean in two sums alike and left a centroid 1.1e-5 mm off centre; the area
/// is held to Steiner's formula as above, the centroid to round-off.
#[test]
fn a_disc_near_its_undercut_has_steiners_area_and_its_centroid_at_its_centre() {
    let spec = cycloid::spec::load("specs/hard/undercut-99pct.yaml").unwrap();
    let run = check(&spec, &CheckOptions::default(), &Silent).unwrap();
    let face = steiner_face((30.0, 7.61, 2.4, 10.0), 6.0 * PI * 4.9 * 4.9);
    let got = run.mass.disc.face.area_mm2;
    assert!((face - got).abs() <= 1e-11 * face, "{got} vs {face}");
    assert!(
        run.mass.disc.centroid_offset_mm < 1e-10,
        "{:?}",
        run.mass.disc
    );
}

/// The face inside the inward parallel curve at r' of the locus C(t) = R'·e^{it} −
/// e·e^{i·np·t} (regular: no undercut), less `holes_mm2`, by Steiner's formula
/// A_C − r'·L_C + π·r'² with A_C = π(R'² + np·e²) and L_C = ∫|C'| on 20,000 points of the
/// periodic trapezoid rule (|C'|² = R'² + np²e² − 2·np·R'·e·cos((np − 1)t)).
pub(crate) fn steiner_face((rp, rr, e, np): (f64, f64, f64, f64), holes_mm2: f64) -> f64 {
    let n = 20_000;
    let length: f64 = (0..n)
        .map(|k| {
            let t = 2.0 * PI * k as f64 / n as f64;
            (rp * rp + np * np * e * e - 2.0 * np * rp * e * ((np - 1.0) * t).cos()).sqrt()
        })
        .sum::<f64>()
        * (2.0 * PI / n as f64);
    PI * (rp * rp + np * e * e) - rr * length + PI * rr * rr - holes_mm2
}

/// A spec at e = 1e-7 mm: its profile is the circle of radius R' − r' (the lobes are e·np
/// deep; their area and moment change by O(e), 1e-9 of the face), with M holes of radius
/// pin + e, a bore, a density and an output inertia given. Mass and J_c are the annulus's,
/// πR² less the holes' πrh² and the bore's by the parallel-axis theorem, times ρ·B; the inertia
/// at the input is discs·(m·e² + J_c/nc²) + J_out/nc² (the m·e² term is 1e-14 of it here).
/// Tolerance: `NEAR_CIRCLE_REL`.
const NEAR_CIRCLE: &str = "\
name: near-circle
reducer:
  teeth: 11
  rollers: 12
  discs: 2
  eccentricity_mm: 1.0e-7
  roller_circle_radius_mm: 40.0
  roller_radius_mm: 4.0
  face_width_mm: 10.0
  output_pins: { count: 8, circle_radius_mm: 22.0, pin_radius_mm: 4.0, hole_clearance_mm: 0.0 }
  material: { youngs_modulus_gpa: 206.0, poisson_ratio: 0.3, density_kg_per_m3: 2700.0 }
  crank_bearing: { dynamic_load_rating_n: 12000.0, outer_diameter_mm: 20.0 }
  output_inertia_kgm2: 0.002
scenes:
  - name: geometry
    crank: { from_deg: 0.0, to_deg: 30.0, steps: 4 }
    effects: [clearance]
";

/// How far `NEAR_CIRCLE`'s mass, J_c and J_in may be from the annulus's closed form,
/// relative: the lobes' O(e) = 1e-9 of the face (above), the profile's moments converged to
/// 1e-13 (`PROFILE_MOMENTS_REL_TOL`) and round-off far below that.
const NEAR_CIRCLE_REL: f64 = 2e-9;

/// `NEAR_CIRCLE`'s face in closed form: the area (mm²) and polar moment (mm⁴) of the circle of
/// its outer radius r less its 8 holes of radius rh on rw (parallel axes) and the
/// bore.
fn near_circle_face() -> (f64, f64) {
    let (r, rh, rw, bore) = (36.0_f64, 4.0 + 1e-7, 22.0_f64, 10.0_f64);
    let area = PI * r * r - 8.0 * PI * rh * rh - PI * bore * bore;
    let polar = 0.5 * PI * r.powi(4)
        - 8.0 * PI * rh * rh * (0.5 * rh * rh + rw * rw)
        - 0.5 * PI * bore.powi(4);
    (area, polar)
}

#[test]
fn the_e_to_zero_limit_is_an_annulus_with_holes() {
    let spec = cycloid::spec::parse("near-circle.yaml", NEAR_CIRCLE).unwrap();
    let run = check(&spec, &CheckOptions::default(), &Silent).unwrap();
    let (area, polar) = near_circle_face();
    let per_mm2 = 2700e-9 * 10.0;
    let (mass, jc) = (per_mm2 * area, per_mm2 * polar * 1e-6);
    let m = &run.mass;
    assert!(
        (m.disc.mass_kg / mass - 1.0).abs() < NEAR_CIRCLE_REL,
        "{m:?}"
    );
    assert!((m.disc.inertia_kgmm2 * 1e-6 / jc - 1.0).abs() < NEAR_CIRCLE_REL);
    let j_in = 2.0 * (mass * 1e-20 + jc / 121.0) + 0.002 / 121.0;
    let got = m.input_inertia_kgmm2 * 1e-6;
    assert!(
        (got / j_in - 1.0).abs() < NEAR_CIRCLE_REL,
        "{got} vs {j_in}"
    );
}

/// The results JSON carries the mass properties at the top level, in kg and kg·m², equal to the
/// engine's (`--json` of the spec above).
#[test]
fn the_results_json_has_the_mass_properties() {
    let dir = crate::common::Scratch::new("mass-json");
    dir.write("s.yaml", NEAR_CIRCLE);
    let out = crate::common::cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    let doc: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let spec = cycloid::spec::parse("near-circle.yaml", NEAR_CIRCLE).unwrap();
    let run = check(&spec, &CheckOptions::default(), &Silent).unwrap();
    // The number as written, read back by the standard library's correctly rounded parser
    // (serde_json's default reader may be one ulp off): the shortest text that round-trips.
    let text = dir.read("r.json");
    let written = text.split("\"disc_mass_kg\":").nth(1).unwrap();
    let written = &written[..written.find([',', '}']).unwrap()];
    assert_eq!(written.parse::<f64>().unwrap(), run.mass.disc.mass_kg);
    let j = doc["input_inertia_kgm2"].as_f64().unwrap();
    assert!((j / (run.mass.input_inertia_kgmm2 * 1e-6) - 1.0).abs() < 1e-15);
    // J_c against the annulus's closed form (as above).
    let (_, polar) = near_circle_face();
    let jc = 2700e-9 * 10.0 * polar * 1e-6;
    let got = doc["disc_inertia_kgm2"].as_f64().unwrap();
    assert!((got / jc - 1.0).abs() < NEAR_CIRCLE_REL, "{got} vs {jc}");
    // By its symmetry the disc's centroid is its centre: round-off of sums of size A·R
    // (1e-16 × 36 mm, summed over some thousand points), 1e-10 mm allowed.
    assert!(doc["disc_centroid_offset_mm"].as_f64().unwrap() < 1e-10);
}

/// A density of zero or less, or beyond any solid's (1e300 kg/m³ made the mass and the
/// unbalance inf, and the run failed without a place), and a negative output inertia, are
/// refused where written.
#[test]
fn bad_mass_inputs_are_refused_where_written() {
    let cases = [
        (
            "density_kg_per_m3: 2700.0",
            "density_kg_per_m3: 0.0",
            "near-circle.yaml:11:",
            "reducer.material.density_kg_per_m3",
        ),
        (
            "density_kg_per_m3: 2700.0",
            "density_kg_per_m3: 1.0e300",
            "near-circle.yaml:11:",
            "must lie in [1, 100000] kg/m³, got 1e300",
        ),
        (
            "output_inertia_kgm2: 0.002",
            "output_inertia_kgm2: -0.002",
            "near-circle.yaml:13:3:",
            "reducer.output_inertia_kgm2",
        ),
    ];
    for (from, to, at, key) in cases {
        let text = NEAR_CIRCLE.replacen(from, to, 1);
        let e = cycloid::spec::parse("near-circle.yaml", &text).unwrap_err();
        let shown = e.to_string();
        assert!(shown.starts_with(at) && shown.contains(key), "{shown}");
    }
}

/// The annulus's closed forms of `NEAR_CIRCLE` (above): one disc's mass and J_c, and J_in, kg
/// and kg·m², as numbers for a person (`numeric::number`, four significant digits). The
/// polygon's 1e-6 relative sliver is far from moving a fourth digit here (the closed forms
/// are 0.0905910, 6.54691e-5, 5.41067e-7, 1.761106e-5).
fn near_circle_figures() -> [String; 6] {
    let (area, polar) = near_circle_face();
    let per_mm2 = 2700e-9 * 10.0;
    let (mass, jc) = (per_mm2 * area, per_mm2 * polar * 1e-6);
    let orbit = mass * 1e-20;
    let j_in = 2.0 * (orbit + jc / 121.0) + 0.002 / 121.0;
    [mass, jc, j_in, orbit, jc / 121.0, 0.002 / 121.0].map(cycloid::numeric::number)
}

/// The terminal states each disc's mass and J_c and the inertia at the input after the
/// headline results, and what J_in includes; `--explain` gives J_in's formula with its
/// numbers: the annulus's closed forms.
#[test]
fn the_terminal_and_explain_state_the_mass_and_the_inertia_at_the_input() {
    let dir = crate::common::Scratch::new("mass-text");
    dir.write("s.yaml", NEAR_CIRCLE);
    let [mass, jc, j_in, orbit, turning, output] = near_circle_figures();
    let out = crate::common::cycloid(&dir.path, &["check", "s.yaml"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    let line = format!(
        "mass: each disc {mass} kg, J_c {jc} kg·m²; inertia at the input J_in {j_in} kg·m² (the \
         discs' orbit and turning and the output; not the crank shaft, its bearings or the \
         rollers)\n"
    );
    assert!(out.stdout.contains(&line), "{}", out.stdout);
    let out = crate::common::cycloid(&dir.path, &["check", "s.yaml", "--explain"]);
    let formula = format!(
        "  inertia at the input J_in = Σ(m·e² + J_c/nc²) + J_out/i² = 2 × ({orbit} + {turning}) \
         + {output} = {j_in} kg·m² (m·e² at e 1.000e-7 mm, nc = i = 11, J_out 0.002000 kg·m²)"
    );
    assert!(out.stdout.contains(&formula), "{}", out.stdout);
    assert!(out.stdout.contains(&format!(
        "mass (density ρ 2700 kg/m³): each disc {mass} kg from its exact profile less the pin \
         holes and the bore, J_c {jc} kg·m² about its centre\n"
    )));
}

/// The review's design table has the mass-properties row (mass, density, J_c, centroid offset)
/// and J_in with what it includes: the annulus's closed forms.
#[test]
fn the_reviews_design_table_has_the_mass_properties() {
    let dir = crate::common::Scratch::new("mass-review");
    dir.write("s.yaml", NEAR_CIRCLE);
    let out = crate::common::cycloid(&dir.path, &["check", "s.yaml", "--report", "review"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    let html = dir.read("review/index.html");
    let [mass, jc, j_in, ..] = near_circle_figures();
    let row = format!(
        "<tr><th>mass properties (each disc)</th><td>mass {mass} kg at density ρ 2700 kg/m³, \
         polar inertia J_c {jc} kg·m² about its centre, centroid "
    );
    assert!(html.contains(&row), "{html}");
    assert!(html.contains(&format!(
        "<tr><th>inertia at the input J_in</th><td>{j_in} kg·m²: the discs' orbit and turning \
         and the output; not the crank shaft, its bearings or the rollers</td></tr>"
    )));
}

/// specs/reducer.yaml's disc with a form error of `order` and 2 µm along the normal.
fn with_form(order: usize, cos_mm: f64) -> String {
    std::fs::read_to_string("specs/reducer.yaml").unwrap().replacen(
        "  output_pins:\n",
        &format!(
            "  deviations:\n    form:\n      - {{order: {order}, cos_mm: {cos_mm:?}, sin_mm: 0.0}}\n  \
             output_pins:\n"
        ),
        1,
    )
}

/// The review's mass row of `text`, from "centroid" to the end of its cell.
fn centroid_words(name: &str, text: &str) -> String {
    let dir = crate::common::Scratch::new(name);
    dir.write("s.yaml", text);
    let out = crate::common::cycloid(&dir.path, &["check", "s.yaml", "--report", "review"]);
    assert!(out.code() <= 1, "{}{}", out.stdout, out.stderr);
    let html = dir.read("review/index.html");
    let row = html
        .split("<tr><th>mass properties (each disc)</th><td>")
        .nth(1)
        .unwrap();
    let row = &row[..row.find("</td>").unwrap()];
    row[row.find("centroid").unwrap()..].to_string()
}

/// The review says a centroid on the disc's centre in words and prints a real offset as a
/// number. The disc is invariant under a turn by 2π/3 (the common symmetry of its 9 lobes and
/// 6 holes), and with a form error of order 3 still under it (t → t + 2π/3 turns C(t) by
/// 2π/3, as 10·2π/3 ≡ 2π/3): its centroid is its centre by symmetry, the computed offset round-off. A form
/// error of order 10 (≡ 1 mod 9) breaks every symmetry but the mirror: its first-order
/// change of S, −∮ w·Γ·|Γ'| dt, has a mean against Γ's harmonics 1 + 9m, so the centroid
/// moves in proportion to the amplitude: doubling it doubles the offset, to within the second
/// order (a relative 1e-3 here: w/r_g ~ 1e-4, with a generous factor).
#[test]
fn the_review_says_a_centred_centroid_in_words_and_prints_a_real_offset() {
    let shipped = std::fs::read_to_string("specs/reducer.yaml").unwrap();
    assert_eq!(
        centroid_words("centroid-shipped", &shipped),
        "centroid on the centre"
    );
    assert_eq!(
        centroid_words("centroid-order-3", &with_form(3, 0.002)),
        "centroid on the centre"
    );
    let offset = |cos_mm: f64| {
        let spec = cycloid::spec::parse("s.yaml", &with_form(10, cos_mm)).unwrap();
        check(&spec, &CheckOptions::default(), &Silent)
            .unwrap()
            .mass
            .disc
            .centroid_offset_mm
    };
    let (single, double) = (offset(0.002), offset(0.004));
    assert!((double / single - 2.0).abs() < 1e-3, "{single} {double}");
    assert_eq!(
        centroid_words("centroid-order-10", &with_form(10, 0.002)),
        format!("centroid {} mm off it", cycloid::numeric::number(single))
    );
}

/// `NEAR_CIRCLE` at eccentricity `e_mm` with rollers that turn on their pins and the given
/// `reducer.roller_inertia_kgm2` line (`""`: none).
fn spinning(e_mm: &str, inertia: &str) -> String {
    NEAR_CIRCLE
        .replacen(
            "eccentricity_mm: 1.0e-7",
            &format!("eccentricity_mm: {e_mm}"),
            1,
        )
        .replacen(
            "  output_inertia_kgm2: 0.002\n",
            &format!(
                "  output_inertia_kgm2: 0.002\n  friction:\n    rollers: {{ mode: rotating, \
                 bore_radius_mm: 2.0, mu: 0.05 }}\n{inertia}"
            ),
            1,
        )
}

/// The complete elliptic integral of the second kind E(k) by the arithmetic-geometric mean:
/// a₀ = 1, b₀ = √(1 − k²), c₀ = k; E = K·(1 − Σ 2ⁿ⁻¹·cₙ²), K = π/(2·a_N) (Abramowitz & Stegun
/// 17.6), to round-off.
fn elliptic_e(k: f64) -> f64 {
    let (mut a, mut b, mut c) = (1.0_f64, (1.0 - k * k).sqrt(), k);
    let (mut sum, mut weight) = (0.5 * c * c, 0.5);
    while c.abs() > 1e-17 {
        let next = (0.5 * (a + b), (a * b).sqrt(), 0.5 * (a - b));
        (a, b, c) = next;
        weight *= 2.0;
        sum += weight * c * c;
    }
    PI / (2.0 * a) * (1.0 - sum)
}

/// The rollers' spin in the inertia at the input: each roller rolls on the disc at
/// Ωᵢ = (ω/nc)·(dᵢ − Rrp)/Rrp, dᵢ its centre's distance from the pitch point e·np
/// (`geometry::roller_spin`), so J_r·Σ(Ωᵢ/ω)² averaged over a turn is
/// J_r·np·⟨(d − Rrp)²⟩/(nc·Rrp)², with ⟨d²⟩ = Rp² + (e·np)² and ⟨d⟩ = (2(a + b)/π)·E(k),
/// a = Rp, b = e·np, k = 2√(ab)/(a + b): at e = 1 mm (K1 = 0.3) against that closed form, and
/// in the e → 0 limit against np·J_r·((Rp − Rrp)/(nc·Rrp))² (every roller spins alike).
/// Tolerance 1e-12: the engine's trapezoid rule on a periodic analytic integrand is exact to
/// round-off, as is the AGM.
#[test]
fn the_rollers_spin_adds_its_closed_form_to_the_inertia_at_the_input() {
    let (rp, rr, np, nc, jr) = (40.0_f64, 4.0_f64, 12.0_f64, 11.0_f64, 2.0e-8);
    let rollers_kgm2 = |e_mm: &str| {
        let with =
            cycloid::spec::parse("s.yaml", &spinning(e_mm, "  roller_inertia_kgm2: 2.0e-8\n"));
        let without = cycloid::spec::parse("s.yaml", &spinning(e_mm, ""));
        let j = |spec: cycloid::spec::Spec| {
            let run = check(&spec, &CheckOptions::default(), &Silent).unwrap();
            (
                run.mass.input_inertia_kgmm2 * 1e-6,
                run.mass.rollers_kgmm2 * 1e-6,
            )
        };
        let ((with, share), (without, none)) = (j(with.unwrap()), j(without.unwrap()));
        assert_eq!(none, 0.0);
        assert!((with - without - share).abs() <= 1e-15 * with);
        share
    };
    let (a, b) = (rp, 1.0 * np);
    let mean_d = 2.0 * (a + b) / PI * elliptic_e(2.0 * (a * b).sqrt() / (a + b));
    let mean_square = a * a + b * b + rr * rr - 2.0 * rr * mean_d;
    let closed = jr * np * mean_square / (nc * rr).powi(2);
    let got = rollers_kgm2("1.0");
    assert!((got / closed - 1.0).abs() < 1e-12, "{got} vs {closed}");
    let limit = jr * np * ((rp - rr) / (nc * rr)).powi(2);
    let got = rollers_kgm2("1.0e-7");
    // The limit is off by O(e²·np²/Rp²) = 1e-14 at e = 1e-7 mm.
    assert!((got / limit - 1.0).abs() < 1e-12, "{got} vs {limit}");
}

/// `reducer.roller_inertia_kgm2` is refused where written for rollers that do not turn (fixed,
/// or no friction mode given) and when negative.
#[test]
fn a_roller_inertia_for_rollers_that_do_not_turn_is_refused_where_written() {
    let given = spinning("1.0", "  roller_inertia_kgm2: 2.0e-8\n");
    let cases = [
        (
            given.replace("mode: rotating, bore_radius_mm: 2.0,", "mode: fixed,"),
            "are fixed",
        ),
        (
            given.replace(
                "  friction:\n    rollers: { mode: rotating, bore_radius_mm: 2.0, mu: 0.05 }\n",
                "",
            ),
            "have no friction mode given",
        ),
        (
            given.replace("2.0e-8", "-2.0e-8"),
            "must be zero or positive",
        ),
    ];
    for (text, rule) in cases {
        let line = 1 + text
            .lines()
            .position(|l| l.starts_with("  roller_inertia_kgm2:"))
            .unwrap();
        let shown = cycloid::spec::parse("s.yaml", &text)
            .unwrap_err()
            .to_string();
        assert!(
            shown.starts_with(&format!("s.yaml:{line}:3:"))
                && shown.contains("reducer.roller_inertia_kgm2")
                && shown.contains(rule),
            "{shown}"
        );
    }
}

/// As the locus factor K1 = e·np/R' nears 1 the trapezoid sums converge ever slower (the
/// branch point of |C'| nears the real axis), and the spec accepts any K1 < 1. The shipped
/// disc with the rollers shrunk to 0.05 mm (no undercut) and no modification, at K1 = 0.999
/// (converged sums, held to Steiner's formula within 1e-11 of the face as above) and at
/// K1 = 0.9999 (beyond the sums' cap: the 0.1 µm polygon, off by at most tol × perimeter,
/// about 0.02 mm² of a 2,180 mm² face; its chords also move the centroid by up to that sliver
/// over the area's reach). Before the polygon took over, the K1 = 0.9999 disc's unconverged
/// sums put its centroid 0.0062 mm off centre, silently.
#[test]
fn a_locus_factor_near_one_keeps_the_mass_exact_or_within_the_polygons_bound() {
    for (e, tolerance_mm2) in [(2.997, 1e-11 * 2200.0), (2.9997, 1e-4 * 200.0)] {
        let spec = crate::common::PaperSpec::new()
            .edit("eccentricity_mm: 2.0 ", &format!("eccentricity_mm: {e} "))
            .edit("roller_radius_mm: 3.0 ", "roller_radius_mm: 0.05 ")
            .modification(0.0, 0.0)
            .parse("k1-near-one.yaml");
        let disc = cycloid::geometry::mass_properties::disc_mass(&spec.design, &spec.modification);
        let face = steiner_face((30.0, 0.05, e, 10.0), 6.0 * PI * (3.0 + e).powi(2));
        let got = disc.face.area_mm2;
        assert!(
            (face - got).abs() <= tolerance_mm2,
            "K1 {}: {got} vs {face}",
            e / 3.0
        );
        assert!(disc.centroid_offset_mm < 1e-4, "K1 {}: {disc:?}", e / 3.0);
    }
}

/// The disc as ground: `reducer.deviations.shift_mm` and `equidistant_mm` are the grinding
/// errors, added to the spec's modification for every check (`Deviations::ground`, the mesh
/// of `geometry::clearance`), so the disc the mass is of must be ground the same way: R' =
/// 30 + 0.125 + 0.02 and r' = 3 + 0.1593 + 0.03 here. Expected: Steiner's formula for that
/// offset profile (`steiner_face`, independent of the code's integration), less the six holes
/// of radius 5 on 18 mm and the 24 mm bore, times ρ·B; and at zero torque the crank bearing
/// carries that mass's m·e·ω² (e = 2 mm, 3000 rpm, worked out here) at every angle. Before,
/// the mass was of the drawing's profile (R' = 30.125, r' = 3.1593): 1.6e-3 heavier than the
/// disc the checks ran on. Tolerances: the face as in the shipped disc's test above (1e-11),
/// the bearing force 1e-9 (its angle's round trip through degrees in the JSON).
#[test]
fn a_disc_with_grinding_errors_has_the_mass_of_the_disc_as_ground() {
    let text = std::fs::read_to_string("specs/reducer-at-speed.yaml")
        .unwrap()
        .replacen(
            "  output_inertia_kgm2: 0.002",
            "  deviations: { shift_mm: 0.02, equidistant_mm: 0.03 }\n  output_inertia_kgm2: 0.002",
            1,
        )
        .replacen(
            "    output_torque_nm: 10.0\n    input_speed_rpm: 3000.0\n",
            "    output_torque_nm: 0.0\n    input_speed_rpm: 3000.0\n",
            1,
        );
    assert!(text.contains("shift_mm: 0.02,") && text.contains("output_torque_nm: 0.0"));
    let holes = 6.0 * PI * 25.0 + PI * 144.0;
    let face = steiner_face((30.145, 3.1893, 2.0, 10.0), holes);
    let mass = 7850e-9 * 8.0 * face;
    let spec = cycloid::spec::parse("as-ground.yaml", &text).unwrap();
    let run = check(&spec, &CheckOptions::default(), &Silent).unwrap();
    let got = run.mass.disc.face.area_mm2;
    assert!((face - got).abs() <= 1e-11 * face, "{got} vs {face} mm²");

    let dir = crate::common::Scratch::new("mass-as-ground");
    dir.write("s.yaml", &text);
    let out = crate::common::cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]);
    assert_eq!(out.code, Some(0), "{}{}", out.stdout, out.stderr);
    let doc: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let w = 3000.0 * 2.0 * PI / 60.0;
    let fc = mass * 2e-3 * w * w;
    for k in 0..2 {
        let forces = doc["scenes"][1]["discs"][k]["bearing_force_n"]
            .as_array()
            .unwrap();
        assert_eq!(forces.len(), 72);
        for (i, f) in forces.iter().enumerate() {
            let f = f.as_f64().unwrap();
            assert!(
                (f - fc).abs() <= 1e-9 * fc,
                "disc {k}, angle {i}: {f} N vs m·e·ω² = {fc} N"
            );
        }
    }
}

/// The crank as built, e + de (`reducer.deviations.eccentricity_mm`), is the orbit of every
/// disc centre: the centripetal force takes it (m·(e + de)·ω²), and so must the orbit's share
/// of the inertia at the input, m·(e + de)². The profile keeps the e it was ground with, so the
/// disc's mass and J_c do not change with de, and the inertia at the input of two discs must
/// grow by exactly 2·m·((e + de)² − e²), with m from Steiner's formula (`steiner_face`, the
/// shipped spec's profile R' = 30.125, r' = 3.1593, six holes of radius 3 + 2 + 0.01 on 18 mm
/// and the 24 mm bore). Both specs have a hole clearance of 10 µm (no preload from the longer
/// crank). Tolerance 1e-9 of the 7.1e-9 kg·m² difference: the two J_in (2.6e-5 kg·m²) are
/// sums to round-off (1e-21 kg·m²). Before, J_in used the nominal e and did not move at all.
#[test]
fn the_inertia_at_the_input_takes_the_orbit_of_the_crank_as_built() {
    let base = std::fs::read_to_string("specs/reducer-at-speed.yaml")
        .unwrap()
        .replacen("hole_clearance_mm: 0.0 ", "hole_clearance_mm: 0.01 ", 1);
    let built = base.replacen(
        "  output_inertia_kgm2: 0.002",
        "  deviations: { eccentricity_mm: 0.01 }\n  output_inertia_kgm2: 0.002",
        1,
    );
    assert!(base.contains("hole_clearance_mm: 0.01 ") && built.contains("eccentricity_mm: 0.01 }"));
    let j_in = |name: &str, text: &str| {
        let spec = cycloid::spec::parse(name, text).unwrap();
        check(&spec, &CheckOptions::default(), &Silent)
            .unwrap()
            .mass
            .input_inertia_kgmm2
            * 1e-6
    };
    let holes = 6.0 * PI * 5.01 * 5.01 + PI * 144.0;
    let mass = 7850e-9 * 8.0 * steiner_face((30.125, 3.1593, 2.0, 10.0), holes);
    let expected = 2.0 * mass * (2.01_f64.powi(2) - 4.0) * 1e-6;
    let got = j_in("built.yaml", &built) - j_in("base.yaml", &base);
    assert!(
        (got - expected).abs() <= 1e-9 * expected,
        "ΔJ_in {got} vs 2·m·((e + de)² − e²) = {expected} kg·m²"
    );
}
