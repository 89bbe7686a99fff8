//! The output pins' stresses (issue 41): the bending moment and shear force along a pin from
//! every disc's force on it, the largest of each, and the stresses they give in its round
//! section.
//!
//! The pin is the beam of `pin_beam` (clamped in the flange at z = 0; free at z = L, or simply
//! supported there with `both_ends`), disc k loading it at its mid-plane z = a_k with the
//! force F_k (a vector in the plane of the flange). Per unit force at a, the bending moment at
//! a section z (taken from the part of the pin beyond z) and the shear force just beyond z are
//! (Roark's *Formulas for Stress and Strain*, Table 8.1 cases 1a and 1c; Gere & Goodno,
//! *Mechanics of Materials*):
//!
//! - `cantilever`: m(z) = (a − z)⁺, v(z) = 1 for z < a, else 0;
//! - `both_ends` (a propped cantilever): the prop at L carries R = a²·(3L − a)/(2L³) of the
//!   load, so m(z) = (a − z)⁺ − R·(L − z) and v(z) = (1 for z < a, else 0) − R. At the clamp
//!   m(0) = a·(L − a)·(2L − a)/(2L²), under the load m(a) = −R·(L − a).
//!
//! Several discs superpose (linear statics): M(z) = Σ_k F_k·m_k(z), a vector. M is linear in z
//! between the clamp, the load points and the end (where it is 0), so |M|, convex along each
//! piece, is largest at the clamp or under a load; V is constant between them.
//!
//! Stresses in a round section of diameter d: the bending stress at its outer fibre
//! σ_b = M·(d/2)/I = 32·M/(π·d³), and the peak transverse shear stress at its neutral axis
//! τ = 4·V/(3·A), A = π·d²/4 (Jourawski's formula for a circle; the mean V/A is ¾ of it).

use crate::geometry::Vec2;
use crate::model::{PinSupport, PinSupportKind};
use std::f64::consts::PI;

/// The share of a unit load at `a_mm` that the far support of `pin` carries: 0 for a
/// cantilever, `pin_beam::prop_share` (R = a²·(3L − a)/(2L³)) for a propped one.
fn prop_share(pin: &PinSupport, a_mm: f64) -> f64 {
    match pin.kind {
        PinSupportKind::Cantilever => 0.0,
        PinSupportKind::BothEnds => super::pin_beam::prop_share(a_mm, pin.length_mm),
    }
}

/// m(z), the bending moment of `pin` at section `z_mm` per unit force at `a_mm`, mm.
pub fn moment_per_force_mm(pin: &PinSupport, a_mm: f64, z_mm: f64) -> f64 {
    (a_mm - z_mm).max(0.0) - prop_share(pin, a_mm) * (pin.length_mm - z_mm)
}

/// v(z), the shear force of `pin` just beyond section `z_mm` per unit force at `a_mm`.
pub fn shear_per_force(pin: &PinSupport, a_mm: f64, z_mm: f64) -> f64 {
    let inside = if z_mm < a_mm { 1.0 } else { 0.0 };
    inside - prop_share(pin, a_mm)
}

/// The largest |M| (N·mm) and |V| (N) along `pin` under the loads `(a_k in mm, F_k in N)`:
/// |Σ F_k·m_k(z)| at the clamp and under each load, |Σ F_k·v_k(z)| just beyond each.
pub fn largest(pin: &PinSupport, loads: &[(f64, Vec2)]) -> (f64, f64) {
    let sections = std::iter::once(0.0).chain(loads.iter().map(|l| l.0));
    let (mut moment, mut shear) = (0.0f64, 0.0f64);
    for z in sections {
        let m: Vec2 = loads
            .iter()
            .map(|&(a, f)| f * moment_per_force_mm(pin, a, z))
            .sum();
        let v: Vec2 = loads
            .iter()
            .map(|&(a, f)| f * shear_per_force(pin, a, z))
            .sum();
        moment = moment.max(m.norm());
        shear = shear.max(v.norm());
    }
    (moment, shear)
}

/// σ_b = 32·M/(π·d³), MPa, of a bending moment `moment_nmm` (N·mm) in a round section of
/// diameter `diameter_mm`.
pub fn bending_stress_mpa(moment_nmm: f64, diameter_mm: f64) -> f64 {
    32.0 * moment_nmm / (PI * diameter_mm.powi(3))
}

/// τ = 4·V/(3·A) = 16·V/(3·π·d²), MPa, the peak shear stress of a shear force `shear_n` (N) in
/// a round section of diameter `diameter_mm`.
pub fn shear_stress_mpa(shear_n: f64, diameter_mm: f64) -> f64 {
    16.0 * shear_n / (3.0 * PI * diameter_mm * diameter_mm)
}
