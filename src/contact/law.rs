//! Force–approach laws of a line contact of length L (the face width).
//!
//! The approach d (mm) is the overlap of the undeformed bodies along the contact normal,
//! d = −gap; no force for d ≤ 0. Forces in N, stiffnesses dF/dd in N/mm.

use crate::model::ContactLaw;
use std::f64::consts::PI;

/// What a contact law needs to know about one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineContact {
    /// E* = 1/((1−ν1²)/E1 + (1−ν2²)/E2), MPa.
    pub contact_modulus_mpa: f64,
    /// (1−ν²)/E of each body, 1/MPa (for the logarithmic law).
    pub compliance_per_mpa: [f64; 2],
    /// Contact length L, mm.
    pub length_mm: f64,
    /// Magnitude of each body's radius of curvature at the contact, mm.
    pub radii_mm: [f64; 2],
    /// Effective radius R*, 1/R* = Σ signed curvatures (a concave body counts negative), mm.
    pub effective_radius_mm: f64,
}

/// Force and stiffness at one approach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactForce {
    pub force_n: f64,
    pub stiffness_n_per_mm: f64,
}

impl ContactForce {
    pub const NONE: ContactForce = ContactForce {
        force_n: 0.0,
        stiffness_n_per_mm: 0.0,
    };

    /// A linear law of stiffness `k` (N/mm) at approach `approach_mm`: F = k·d.
    #[inline]
    pub fn linear(k: f64, approach_mm: f64) -> ContactForce {
        ContactForce {
            force_n: k * approach_mm,
            stiffness_n_per_mm: k,
        }
    }
}

/// Paper Eq. 9: F = (π/4)·E*·L·d, a constant stiffness k = (π/4)·E*·L.
pub fn paper_linear_stiffness(c: &LineContact) -> f64 {
    0.25 * PI * c.contact_modulus_mpa * c.length_mm
}

/// Hertz half-width b = sqrt(4·F·R*/(π·L·E*)), mm.
pub fn half_width_mm(c: &LineContact, force_n: f64) -> f64 {
    (4.0 * force_n * c.effective_radius_mm / (PI * c.length_mm * c.contact_modulus_mpa)).sqrt()
}

/// Johnson's logarithmic line-contact compliance (K. L. Johnson, *Contact Mechanics*, CUP 1985,
/// §5.6; Puttock & Thwaite, CSIRO 1969): the approach of the axes of two cylinders pressed
/// together by F over a length L is the sum over both bodies k of
///   d_k = (2F/(πL))·c_k·(ln(4R_k/b) − 1/2),   c_k = (1−ν_k²)/E_k,
/// with b the Hertz half-width. With equal materials it is (F/(πLE*))·(ln(4R1/b) + ln(4R2/b) − 1).
/// Its derivative, using ∂ln b/∂F = 1/(2F), is
///   ∂d/∂F = (2/(πL))·Σ c_k·(ln(4R_k/b) − 1),
/// positive while every b < 4R_k/e: the law stiffens with load and starts with zero stiffness.
///
/// Validity: the formula describes cylinders whose radii are much larger than the contact
/// half-width. A body whose radius falls below e·b (a sharp concave root under a heavy
/// preload) is no longer such a cylinder, and the formula would turn over (∂d/∂F < 0, two
/// forces for one approach). Its radius is therefore floored at e·b in the log term: that term
/// becomes (2F/(πL))·c_k·(ln 4 + 1/2), linear in F, so d(F) stays continuous and strictly
/// increasing and its inverse unique.
pub fn johnson_approach_mm(c: &LineContact, force_n: f64) -> (f64, f64) {
    if force_n <= 0.0 {
        return (0.0, f64::INFINITY);
    }
    let b = half_width_mm(c, force_n);
    let scale = 2.0 / (PI * c.length_mm);
    let (mut d, mut dd) = (0.0, 0.0);
    for k in 0..2 {
        let c_k = c.compliance_per_mpa[k];
        let log = (4.0 * c.radii_mm[k] / b).ln();
        if log >= 1.0 + 4f64.ln() {
            d += scale * force_n * c_k * (log - 0.5);
            dd += scale * c_k * (log - 1.0);
        } else {
            // Radius floored at e·b: ln(4·e·b/b) = 1 + ln 4, independent of F.
            let floored = 1.0 + 4f64.ln();
            d += scale * force_n * c_k * (floored - 0.5);
            dd += scale * c_k * (floored - 0.5);
        }
    }
    (d, dd)
}

/// Invert Johnson's law: the force that produces approach `d` (safeguarded Newton in ln F,
/// started from the linear law; d(ln F) steps are bounded so the iteration cannot overshoot).
pub fn johnson_force(c: &LineContact, approach_mm: f64) -> ContactForce {
    johnson_force_in_series(c, (0.0, paper_linear_stiffness(c)), approach_mm)
}

/// `johnson_force` of the contact in series with a spring of compliance `compliance` (mm/N; 0:
/// the contact alone, bit for bit): the force F with d(F) + c·F = approach and the series
/// stiffness 1/(∂d/∂F + c), Newton started from F = k0·approach (`k0` the linear law's
/// stiffness, in series with the spring).
#[inline]
pub fn johnson_force_in_series(
    c: &LineContact,
    (compliance, k0): (f64, f64),
    approach_mm: f64,
) -> ContactForce {
    if approach_mm <= 0.0 {
        return ContactForce::NONE;
    }
    let mut ln_f = (k0 * approach_mm).ln();
    for _ in 0..100 {
        let f = ln_f.exp();
        let (d, dd) = johnson_approach_mm(c, f);
        // Newton on g(ln F) = d(F) + c·F − d_target, g' = F·(∂d/∂F + c).
        let slope = (dd + compliance).max(1e-300);
        let step = ((approach_mm - d - compliance * f) / (f * slope)).clamp(-2.0, 2.0);
        ln_f += step;
        if step.abs() < 1e-14 {
            break;
        }
    }
    let f = ln_f.exp();
    let (_, dd) = johnson_approach_mm(c, f);
    ContactForce {
        force_n: f,
        stiffness_n_per_mm: 1.0 / (dd + compliance),
    }
}

/// Force and stiffness of a contact under `law` at approach `d` (mm).
pub fn force(law: ContactLaw, c: &LineContact, approach_mm: f64) -> ContactForce {
    if approach_mm <= 0.0 {
        return ContactForce::NONE;
    }
    match law {
        ContactLaw::PaperLinear => ContactForce::linear(paper_linear_stiffness(c), approach_mm),
        ContactLaw::HertzNonlinear => johnson_force(c, approach_mm),
    }
}
