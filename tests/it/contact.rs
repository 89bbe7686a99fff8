//! Contact laws and Hertz line contact (MODEL.md "Contact", paper §3.1).
//!
//! Expected values come from the textbook formulas (Johnson, Contact Mechanics, §4.2 and §5.6),
//! restated here independently of `contact::law`, and from finite differences.

use crate::common;

use cycloid::contact::hertz_line::hertz;
use cycloid::contact::law::{
    self, half_width_mm, johnson_approach_mm, johnson_force, paper_linear_stiffness, LineContact,
};
use cycloid::equilibrium::pins::Pins;
use cycloid::equilibrium::rollers::Rollers;
use cycloid::model::{ContactLaw, GeometryMode};
use cycloid::spec::Spec;
use proptest::prelude::*;
use std::f64::consts::PI;

/// Steel on steel, E = 206 GPa, ν = 0.3: E* = E/(2(1 − ν²)) = 113 186.8 MPa.
const E_STAR: f64 = 206_000.0 / (2.0 * (1.0 - 0.09));
const COMPLIANCE: f64 = (1.0 - 0.09) / 206_000.0;

fn paper_spec() -> Spec {
    common::PaperSpec::new()
        .modification(0.0, 0.0)
        .scenes(
            "  - name: s\n    output_torque_nm: 10.0\n    \
             crank: { from_deg: 0.0, to_deg: 36.0, steps: 36 }\n    effects: [roller_contact]\n",
        )
        .parse("paper.yaml")
}

fn steel(length_mm: f64, radii_mm: [f64; 2], effective_radius_mm: f64) -> LineContact {
    LineContact {
        contact_modulus_mpa: E_STAR,
        compliance_per_mpa: [COMPLIANCE, COMPLIANCE],
        length_mm,
        radii_mm,
        effective_radius_mm,
    }
}

/// Johnson's approach of the axes of two steel cylinders, equal materials (Johnson 1985,
/// eq. 5.36 for each body, d_k = (P·c_k/π)·(2·ln(4R_k/b) − 1), P = F/L, c_k = 1/(2E*)):
/// d = (F/(πLE*))·(ln(4R1/b) + ln(4R2/b) − 1), b = sqrt(4FR*/(πLE*)).
fn textbook_approach(c: &LineContact, f: f64) -> f64 {
    let b = (4.0 * f * c.effective_radius_mm / (PI * c.length_mm * E_STAR)).sqrt();
    f / (PI * c.length_mm * E_STAR)
        * ((4.0 * c.radii_mm[0] / b).ln() + (4.0 * c.radii_mm[1] / b).ln() - 1.0)
}

/// The paper's Eq. 9 with the paper's data: k = (π/4)·E*·L = 7.112e5 N/mm for L = 8 mm
/// (MODEL.md quotes four digits: ±50 N/mm), and F = k·d; E* built by the engine from the spec
/// (E 206 GPa, ν 0.3 on both bodies) for rollers and pins alike.
#[test]
fn paper_linear_law_has_the_quoted_stiffness() {
    let spec = paper_spec();
    assert!((spec.design.contact_modulus_mpa() - E_STAR).abs() <= 1e-9 * E_STAR);
    let rollers = Rollers::new(
        &spec.design,
        &spec.modification,
        ContactLaw::PaperLinear,
        GeometryMode::Exact,
    );
    let pins = Pins::new(&spec.design, ContactLaw::PaperLinear);
    for c in [rollers.line_contact(0.1), *pins.line_contact()] {
        let k = paper_linear_stiffness(&c);
        assert!((k - 7.112e5).abs() <= 50.0, "k = {k}");
        assert!((k - 0.25 * PI * E_STAR * 8.0).abs() <= 1e-9 * k);
        for d in [1e-6, 3e-4, 2e-2] {
            let f = law::force(ContactLaw::PaperLinear, &c, d);
            assert!((f.force_n - k * d).abs() <= 1e-12 * k * d);
            assert_eq!(f.stiffness_n_per_mm, k);
        }
        // No force without overlap.
        assert_eq!(law::force(ContactLaw::PaperLinear, &c, 0.0).force_n, 0.0);
        assert_eq!(law::force(ContactLaw::PaperLinear, &c, -1e-3).force_n, 0.0);
    }
}

/// Effective radii: 1/R* = κ_profile + 1/Rrp for a roller on the disc (a concave flank, κ < 0,
/// makes R* larger than Rrp); a pin of radius 3 in its hole of radius 3 + e = 5 (concave):
/// 1/R* = 1/3 − 1/5, R* = 7.5 mm.
#[test]
fn effective_radii_of_rollers_and_pins() {
    let spec = paper_spec();
    let rollers = Rollers::new(
        &spec.design,
        &spec.modification,
        ContactLaw::HertzNonlinear,
        GeometryMode::Exact,
    );
    let convex = rollers.line_contact(0.1);
    assert!((convex.effective_radius_mm - 1.0 / (0.1 + 1.0 / 3.0)).abs() <= 1e-12);
    let concave = rollers.line_contact(-0.05);
    assert!((concave.effective_radius_mm - 1.0 / (-0.05 + 1.0 / 3.0)).abs() <= 1e-12);
    assert!(concave.effective_radius_mm > 3.0);
    let pins = Pins::new(&spec.design, ContactLaw::HertzNonlinear);
    assert!((pins.line_contact().effective_radius_mm - 7.5).abs() <= 1e-12);
}

fn contact_strategy() -> impl Strategy<Value = LineContact> {
    (2.0f64..40.0, 1.0f64..10.0, 4.0f64..25.0, any::<bool>()).prop_map(
        |(flank, roller, length, concave)| {
            // Signed curvatures: a concave flank must be larger than the roller it holds.
            let flank = if concave { flank + roller + 0.5 } else { flank };
            let inv = if concave { -1.0 / flank } else { 1.0 / flank } + 1.0 / roller;
            steel(length, [flank, roller], 1.0 / inv)
        },
    )
}

proptest! {
    /// Johnson's law: the force found for an approach reproduces that approach (Newton in ln F
    /// stops at a step of 1e-14: relative 1e-12 with rounding margin); the approach agrees
    /// with the textbook formula for equal materials; the reported stiffness is the
    /// derivative of F(d), checked by a central difference with relative step h = 1e-4
    /// (truncation ~h²/6 ≈ 2e-9, inversion noise 1e-12/h ≈ 1e-8: tolerance 1e-7).
    #[test]
    fn johnson_law_inverts_and_its_stiffness_is_the_derivative(
        c in contact_strategy(),
        log_d in -7.0f64..-1.5,
    ) {
        let d = 10f64.powf(log_d);
        let f = johnson_force(&c, d);
        prop_assert!(f.force_n > 0.0 && f.stiffness_n_per_mm > 0.0);
        let (back, _) = johnson_approach_mm(&c, f.force_n);
        prop_assert!((back - d).abs() <= 1e-12 * d, "{} vs {}", back, d);
        let textbook = textbook_approach(&c, f.force_n);
        prop_assert!((textbook - back).abs() <= 1e-13 * back);
        let h = 1e-4;
        let fd = (johnson_force(&c, d * (1.0 + h)).force_n - johnson_force(&c, d * (1.0 - h)).force_n)
            / (2.0 * h * d);
        prop_assert!(
            (fd - f.stiffness_n_per_mm).abs() <= 1e-7 * f.stiffness_n_per_mm,
            "stiffness {} vs finite difference {}", f.stiffness_n_per_mm, fd
        );
        // The dispatcher uses the same law.
        let g = law::force(ContactLaw::HertzNonlinear, &c, d);
        prop_assert_eq!(g, f);
    }

    /// Hertz line contact: the elliptical pressure p(x) = p0·sqrt(1 − x²/b²) integrates over the
    /// width and the length to (π/2)·b·p0·L, which must be the force (exact identity of the
    /// formulas: rounding only); b² = 4FR*/(πLE*) and p0² = FE*/(πLR*) from the textbook.
    #[test]
    fn hertz_pressure_integrates_to_the_force(
        c in contact_strategy(),
        log_f in -2.0f64..5.0,
    ) {
        let f = 10f64.powf(log_f);
        let h = hertz(&c, f);
        let integral = 0.5 * PI * h.half_width_mm * h.peak_pressure_mpa * c.length_mm;
        prop_assert!((integral - f).abs() <= 1e-14 * f * 8.0);
        let (r, l) = (c.effective_radius_mm, c.length_mm);
        prop_assert!((h.half_width_mm.powi(2) - 4.0 * f * r / (PI * l * E_STAR)).abs()
            <= 1e-14 * h.half_width_mm.powi(2) * 8.0);
        prop_assert!((h.peak_pressure_mpa.powi(2) - f * E_STAR / (PI * l * r)).abs()
            <= 1e-14 * h.peak_pressure_mpa.powi(2) * 8.0);
        prop_assert_eq!(h.half_width_mm, half_width_mm(&c, f));
    }
}

/// Johnson's law stiffens with load (∂d/∂F = (2/(πL))·Σ c_k·(ln(4R_k/b) − 1) falls as b grows)
/// and starts from zero stiffness (the logarithm diverges as F → 0), unlike the paper's
/// constant k. No force without overlap.
#[test]
fn johnson_law_stiffens_from_zero() {
    let c = steel(8.0, [10.0, 3.0], 1.0 / (0.1 + 1.0 / 3.0));
    let stiffness: Vec<f64> = [1e-9, 1e-7, 1e-5, 1e-3, 1e-2]
        .iter()
        .map(|&d| johnson_force(&c, d).stiffness_n_per_mm)
        .collect();
    assert!(stiffness.windows(2).all(|w| w[0] < w[1]), "{stiffness:?}");
    // At 1e-9 mm the stiffness is a small fraction of the paper's linear constant.
    assert!(stiffness[0] < 0.5 * paper_linear_stiffness(&c));
    assert_eq!(johnson_force(&c, 0.0).force_n, 0.0);
    assert_eq!(johnson_force(&c, -1e-3).force_n, 0.0);
    assert_eq!(johnson_approach_mm(&c, 0.0).0, 0.0);
}
