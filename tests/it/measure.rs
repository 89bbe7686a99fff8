//! Identification of a measured disc (issue 16): synthetic measurements of a disc with known
//! modifications and form error, turned and shifted into a machine frame with noise, are
//! identified within their reported uncertainties; bad measurements are refused with a reason.

use crate::common::*;
use cycloid::geometry::profile::Profile;
use cycloid::geometry::Vec2;
use cycloid::measure::fit::{self, Identification, Request};
use cycloid::measure::fitted::{Estimate, FormError};
use cycloid::measure::{Feature, MeasuredPoint};
use cycloid::model::measured::Fitted;
use cycloid::model::{Design, Modification};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// A disc as made and put on the machine.
#[derive(Debug, Clone)]
struct Truth {
    modification: Modification,
    centre: Vec2,
    orientation: f64,
    /// (order, cos, sin) of w, mm.
    form: Vec<(usize, f64, f64)>,
}

impl Truth {
    /// The design's own profile (no modification, no form error) at a pose.
    fn unmodified(centre: Vec2, orientation: f64) -> Truth {
        Truth {
            modification: Modification::default(),
            centre,
            orientation,
            form: Vec::new(),
        }
    }
}

/// Deterministic normal deviates (splitmix64 + Box–Muller), so a case replays from its seed.
struct Noise(u64);

impl Noise {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn normal(&mut self) -> f64 {
        let u = self.uniform().max(1e-300);
        (-2.0 * u.ln()).sqrt() * (TAU * self.uniform()).cos()
    }
}

fn paper() -> Design {
    let mut d = design(10, 2.0, 30.0, 3.0);
    d.pins.circle_radius_mm = 18.0;
    d
}

fn form_value(form: &[(usize, f64, f64)], t: f64) -> f64 {
    form.iter()
        .map(|&(k, a, b)| a * (k as f64 * t).cos() + b * (k as f64 * t).sin())
        .sum()
}

/// `count` profile points at random t in [start, start + span) on Γ_w = Γ − w·N (the profile
/// of `truth.modification` with the form error along its normal), and `per_hole` points around
/// every hole; all turned by the orientation, moved by the centre, with isotropic Gaussian
/// noise of `sigma_mm` on each coordinate.
fn measure(
    d: &Design,
    truth: &Truth,
    count: usize,
    (start, span): (f64, f64),
    per_hole: usize,
    sigma_mm: f64,
    seed: u64,
) -> Vec<MeasuredPoint> {
    let m = truth.modification;
    let profile = Profile::from_parts(
        d.rollers,
        d.eccentricity_mm,
        d.roller_circle_radius_mm + m.shift_mm,
        d.roller_radius_mm + m.equidistant_mm,
        m.rotation_rad,
    );
    let mut noise = Noise(seed);
    let (s, c) = truth.orientation.sin_cos();
    let place = |p: Vec2, noise: &mut Noise| {
        let turned = Vec2::new(c * p.x - s * p.y, s * p.x + c * p.y);
        turned + truth.centre + Vec2::new(noise.normal(), noise.normal()) * sigma_mm
    };
    let mut points = Vec::new();
    for i in 0..count {
        let t = start + span * noise.uniform();
        let p = profile.point(t) - profile.normal(t) * form_value(&truth.form, t);
        points.push(MeasuredPoint {
            point: place(p, &mut noise),
            feature: Feature::Profile,
            line: i + 2,
        });
    }
    let pins = &d.pins;
    for j in 0..pins.count {
        let a = TAU * j as f64 / pins.count as f64;
        let centre = Vec2::new(a.cos(), a.sin()) * pins.circle_radius_mm;
        for k in 0..per_hole {
            let b = TAU * k as f64 / per_hole as f64;
            let p = centre + Vec2::new(b.cos(), b.sin()) * d.hole_radius_mm();
            points.push(MeasuredPoint {
                point: place(p, &mut noise),
                feature: Feature::Hole(j),
                line: count + 2 + j * per_hole + k,
            });
        }
    }
    points
}

/// ΔRp and ΔRrp, without Δδ (no hole points needed).
const TEETH: Fitted = Fitted {
    shift: true,
    equidistant: true,
    rotation: false,
};

const ALL: Fitted = Fitted {
    shift: true,
    equidistant: true,
    rotation: true,
};

fn identify(d: &Design, fit: Fitted, harmonics: usize, points: &[MeasuredPoint]) -> Identification {
    let request = Request {
        design: d,
        nominal: Modification::default(),
        fit,
        harmonics,
    };
    fit::identify(&request, points).unwrap_or_else(|e| panic!("fit: {e}"))
}

/// |estimate − truth| within Z standard uncertainties. Z = 6: a correct σ is exceeded with
/// probability 2.0e-9 per value, so the 27 values of a case over the 64 cases of a CI run
/// fail by chance once in 3e5 runs (once in 2e3 runs of 10⁴ cases on demand), while a σ too
/// small by a factor 3 fails within a case or two (|z| > 2 of the true spread: 4.6 % per
/// value). Z = 4.5 (7e-6 per value, 1 % of CI runs) failed CI once with everything correct:
/// the committed case at seed 8326706660925026273 has a₄ at 4.8 σ. Whether σ is right to a
/// few per cent is the business of `reported_uncertainties_are_the_spread_of_the_estimates`.
const Z: f64 = 6.0;

fn within(what: &str, e: Estimate, truth: f64) -> std::result::Result<(), TestCaseError> {
    prop_assert!(
        (e.value - truth).abs() <= Z * e.sigma,
        "{what}: identified {:.6e} ± {:.2e}, truth {truth:.6e} (off by {:.1} σ)",
        e.value,
        e.sigma,
        (e.value - truth).abs() / e.sigma
    );
    Ok(())
}

/// Every unknown of a fit of `ALL` with hole points, as (name, estimate, truth). The
/// orientation is compared modulo a turn.
fn unknowns(truth: &Truth, id: &Identification) -> Vec<(String, Estimate, f64)> {
    let m = truth.modification;
    let turn =
        (id.orientation_rad.value - truth.orientation + TAU / 2.0).rem_euclid(TAU) - TAU / 2.0;
    let mut all = vec![
        ("x0".to_string(), id.centre_mm[0], truth.centre.x),
        ("y0".to_string(), id.centre_mm[1], truth.centre.y),
        (
            "θ0".to_string(),
            Estimate {
                value: turn,
                ..id.orientation_rad
            },
            0.0,
        ),
        ("ΔRp".to_string(), id.shift_mm.unwrap(), m.shift_mm),
        (
            "ΔRrp".to_string(),
            id.equidistant_mm.unwrap(),
            m.equidistant_mm,
        ),
        ("Δδ".to_string(), id.rotation_rad.unwrap(), m.rotation_rad),
        (
            "hole radius".to_string(),
            id.hole_radius_offset_mm.unwrap(),
            0.0,
        ),
    ];
    assert_eq!(id.form.harmonics.len(), truth.form.len());
    for (h, &(k, a, b)) in id.form.harmonics.iter().zip(&truth.form) {
        assert_eq!(h.order, k);
        all.push((format!("a{k}"), h.cos_mm, a));
        all.push((format!("b{k}"), h.sin_mm, b));
    }
    all
}

/// The proptest's disc: the paper's design with modifications and pose in the given ranges and
/// the form error of orders 2..=12 that are not multiples of 9, a few µm each.
#[allow(clippy::too_many_arguments)]
fn random_truth(
    d: &Design,
    shift: f64,
    gap: f64,
    rotation: f64,
    centre: Vec2,
    orientation: f64,
    coefficients: &[f64],
) -> Truth {
    let orders = FormError::orders(12, d.teeth);
    assert_eq!(orders, vec![2, 3, 4, 5, 6, 7, 8, 10, 11, 12]);
    Truth {
        modification: Modification {
            shift_mm: shift,
            equidistant_mm: shift + gap,
            rotation_rad: rotation,
        },
        centre,
        orientation,
        form: (orders.iter().enumerate())
            .map(|(i, &k)| (k, coefficients[2 * i], coefficients[2 * i + 1]))
            .collect(),
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    /// Random modifications, pose and form error (orders 2..=12 that are not multiples of 9,
    /// a few µm each); 1 µm noise on 3000 points over the whole profile and 24 on each hole:
    /// every unknown is identified within Z of its reported uncertainty, the form series holds
    /// exactly the orders the module documents, and the residual RMS is the noise's normal
    /// component (σ = 1 µm; within 8 %, 6 standard errors of the RMS of 3000 samples).
    #[test]
    fn known_disc_is_identified_within_its_uncertainty(
        shift in -0.2f64..0.2,
        gap in 0.0f64..0.2,
        rotation in -0.01f64..0.01,
        x in -200.0f64..200.0,
        y in -200.0f64..200.0,
        orientation in 0.0f64..TAU,
        coefficients in proptest::collection::vec(-0.004f64..0.004, 2 * 10),
        seed in any::<u64>(),
    ) {
        let d = paper();
        let truth = random_truth(&d, shift, gap, rotation, Vec2::new(x, y), orientation, &coefficients);
        let points = measure(&d, &truth, 3000, (0.0, TAU), 24, 1e-3, seed);
        let id = identify(&d, ALL, 12, &points);
        for (name, estimate, value) in unknowns(&truth, &id) {
            within(&name, estimate, value)?;
        }
        // σ̂/σ: Σd²/σ² is χ² with m − n degrees of freedom (m ≈ 3000 points, n ≈ 30
        // unknowns), so σ̂/σ has mean √((m − n)/m) ≈ 0.995 and standard deviation 1/√(2m) ≈
        // 0.013. 8 % is 6 standard deviations (2e-9 per case): the 64 cases of a CI run fail
        // by chance once in 10⁷ runs. (5 %, 3.9 of them, failed once in a few hundred runs:
        // the committed case at seed 3179311507229564268 has σ̂ = 0.946 µm, 4.2 below.)
        prop_assert!((id.residual_rms_mm / 1e-3 - 1.0).abs() < 0.08, "rms {}", id.residual_rms_mm);
        // The uncertainties are those of ~3000 points with 1 µm noise, so that "within σ"
        // above is a real test: 1 µm/√3000 ≈ 0.02 µm for a lone constant offset, ~10× that for
        // ΔRp and ΔRrp, which move the profile alike but for the variation of (cos t, sin t)·N
        // along the flank (0.2 µm measured); 0.5 µm bounds them.
        prop_assert!(id.shift_mm.unwrap().sigma < 5e-4 && id.equidistant_mm.unwrap().sigma < 5e-4);
        prop_assert!(id.coverage.fraction > 0.99 && id.coverage.teeth_measured == d.teeth);
    }
}

/// The reported σ is the spread of the estimates. 100 discs drawn as in the proptest above (a
/// fixed sequence, so the test is the same at every run), each measured with its own noise:
/// z = (estimate − truth)/σ of every unknown should have mean square 1.
/// - All 27 unknowns pooled (2700 values): within 0.15 of 1. Were they independent, the mean of
///   2700 z² would have a standard deviation of √(2/2700) = 0.027; the unknowns of one case
///   share its points, and ten batches of 100 cases gave 0.961–1.022. 0.15 is more than five
///   of those. This sequence gives 0.965; every σ 10 % too small makes it 1.19, 10 % too
///   large 0.80 (both tried).
/// - Each unknown alone (100 values, χ²₁₀₀/100): within [0.3, 1.8], beyond which a correct σ
///   lies with probability 2e-6 (Wilson–Hilferty); here they lie in 0.65–1.39. One unknown's σ
///   25 % too small, which the pool hides, fails here (a₄: 1.16 → 2.07, tried).
#[test]
fn reported_uncertainties_are_the_spread_of_the_estimates() {
    let d = paper();
    let mut draw = Noise(12345);
    let mut between = |low: f64, high: f64| low + (high - low) * draw.uniform();
    let mut squares: Vec<(String, f64)> = Vec::new();
    let cases = 100;
    for case in 0..cases {
        let (shift, gap, rotation) = (between(-0.2, 0.2), between(0.0, 0.2), between(-0.01, 0.01));
        let centre = Vec2::new(between(-200.0, 200.0), between(-200.0, 200.0));
        let orientation = between(0.0, TAU);
        let coefficients: Vec<f64> = (0..20).map(|_| between(-0.004, 0.004)).collect();
        let truth = random_truth(&d, shift, gap, rotation, centre, orientation, &coefficients);
        let points = measure(&d, &truth, 3000, (0.0, TAU), 24, 1e-3, 7919 * case + 1);
        let id = identify(&d, ALL, 12, &points);
        let all = unknowns(&truth, &id);
        squares.resize(all.len(), (String::new(), 0.0));
        for ((name, sum), (unknown, e, value)) in squares.iter_mut().zip(all) {
            *name = unknown;
            *sum += ((e.value - value) / e.sigma).powi(2);
        }
    }
    let pooled = squares.iter().map(|s| s.1).sum::<f64>() / (cases as f64 * squares.len() as f64);
    assert!(
        (pooled - 1.0).abs() < 0.15,
        "mean z² of all unknowns {pooled:.3}"
    );
    for (name, sum) in &squares {
        let mean = sum / cases as f64;
        assert!(
            (0.3..1.8).contains(&mean),
            "{name}: mean z² {mean:.3} over {cases} discs"
        );
    }
}

/// A form error of one harmonic (order 5, 3 µm) shows up as that harmonic: its amplitude is
/// found within Z·σ, and every other order of a 20-harmonic fit stays within Z·σ of zero.
/// Without hole points the teeth are counted from wherever the fit lands on the disc (the
/// orientation is known modulo a tooth pitch, which turns the phase of order k by 2πk/nc), so
/// the amplitudes are compared, not the phases.
#[test]
fn single_harmonic_form_error_shows_as_that_harmonic() {
    let d = paper();
    let truth = Truth {
        modification: Modification {
            shift_mm: 0.1,
            equidistant_mm: 0.13,
            rotation_rad: 0.0,
        },
        centre: Vec2::new(12.0, -7.0),
        orientation: 1.0,
        form: vec![(5, 0.003 * 0.6, 0.003 * 0.8)],
    };
    let points = measure(&d, &truth, 4000, (0.0, TAU), 0, 1e-3, 7);
    let id = identify(&d, TEETH, 20, &points);
    for h in &id.form.harmonics {
        let truth = if h.order == 5 { 0.003 } else { 0.0 };
        let sigma = h.cos_mm.sigma.max(h.sin_mm.sigma);
        // The amplitude of a zero harmonic is Rayleigh distributed: beyond Z·σ with
        // probability exp(−Z²/2) = 4e-5.
        assert!(
            (h.amplitude_mm() - truth).abs() <= Z * sigma,
            "order {}: amplitude {:.3e} ± {:.1e}, truth {truth}",
            h.order,
            h.amplitude_mm(),
            sigma
        );
    }
    let largest = id
        .form
        .harmonics
        .iter()
        .max_by(|a, b| a.amplitude_mm().total_cmp(&b.amplitude_mm()))
        .unwrap();
    assert_eq!(largest.order, 5);
}

/// Points on part of the disc (a third of a turn, 3 of 9 teeth) still identify the
/// modifications, and the coverage says how much was measured.
#[test]
fn partial_coverage_is_reported() {
    let d = paper();
    let truth = Truth {
        modification: Modification {
            shift_mm: -0.05,
            equidistant_mm: -0.03,
            rotation_rad: 0.0,
        },
        centre: Vec2::new(-40.0, 3.0),
        orientation: -2.0,
        form: Vec::new(),
    };
    let points = measure(&d, &truth, 1500, (0.0, TAU / 3.0), 0, 1e-3, 11);
    let id = identify(&d, TEETH, 0, &points);
    let e = id.equidistant_mm.unwrap();
    assert!((e.value + 0.03).abs() <= Z * e.sigma, "{e:?}");
    // The points span 1/3 of t; the bins of 1/16 pitch hold 1500 random points, all filled.
    assert!(
        (id.coverage.fraction - 1.0 / 3.0).abs() < 0.02,
        "{:?}",
        id.coverage
    );
    assert_eq!(id.coverage.teeth_measured, 3);
}

fn error_of(d: &Design, fit: Fitted, harmonics: usize, points: &[MeasuredPoint]) -> String {
    let request = Request {
        design: d,
        nominal: Modification::default(),
        fit,
        harmonics,
    };
    match fit::identify(&request, points) {
        Ok(_) => panic!("the fit was expected to be refused"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn rotation_without_hole_points_is_refused_saying_why() {
    let d = paper();
    let truth = Truth::unmodified(Vec2::zeros(), 0.0);
    let points = measure(&d, &truth, 500, (0.0, TAU), 0, 1e-3, 1);
    let e = error_of(&d, ALL, 0, &points);
    assert!(
        e.contains("`rotation_deg` cannot be fitted without points on the pin holes"),
        "{e}"
    );
}

#[test]
fn fewer_points_than_unknowns_are_refused() {
    let d = paper();
    let truth = Truth::unmodified(Vec2::zeros(), 0.0);
    // 12 harmonics: 10 orders, 20 coefficients, + centre (2), orientation, 2 modifications = 25.
    let points = measure(&d, &truth, 25, (0.0, TAU), 0, 1e-3, 1);
    let e = error_of(&d, TEETH, 12, &points);
    assert!(e.contains("25 profile points for 25 unknowns"), "{e}");
}

/// Points of another design (eccentricity 2.3 mm instead of 2) do not fit within the limit.
#[test]
fn points_of_another_design_are_refused() {
    let d = paper();
    let mut other = paper();
    other.eccentricity_mm = 2.3;
    let truth = Truth {
        modification: Modification::default(),
        centre: Vec2::new(5.0, 5.0),
        orientation: 0.3,
        form: Vec::new(),
    };
    let points = measure(&other, &truth, 800, (0.0, TAU), 0, 1e-3, 3);
    let e = error_of(&d, TEETH, 0, &points);
    assert!(
        e.contains("the points are not a disc of this design"),
        "{e}"
    );
}

/// A sixth of the disc cannot carry a 40-harmonic form error: refused as ill-posed, naming
/// the condition number.
#[test]
fn ill_posed_fit_is_refused() {
    let d = paper();
    let truth = Truth::unmodified(Vec2::zeros(), 0.0);
    let points = measure(&d, &truth, 3000, (0.0, TAU / 6.0), 0, 1e-3, 5);
    let e = error_of(&d, TEETH, 40, &points);
    assert!(e.contains("the identification is ill-posed"), "{e}");
}
