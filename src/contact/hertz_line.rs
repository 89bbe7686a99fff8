//! Hertz line contact between two parallel cylinders (Johnson 1985, §4.2):
//!   peak pressure p0 = sqrt(F·E*/(π·L·R*)),   half-width b = sqrt(4·F·R*/(π·L·E*)),
//! with 1/R* = 1/ρ1 + 1/ρ2, signed radii (a concave surface has a negative radius, making R*
//! larger). Units: N, mm, MPa.

use super::law::{half_width_mm, LineContact};
use std::f64::consts::PI;

/// Peak pressure and half-width of one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzLine {
    pub peak_pressure_mpa: f64,
    pub half_width_mm: f64,
}

/// Hertz line contact under force F (N) ≥ 0.
pub fn hertz(c: &LineContact, force_n: f64) -> HertzLine {
    let f = force_n.max(0.0);
    HertzLine {
        // The half-width as the contact laws compute it (Johnson's law takes its logarithm).
        half_width_mm: half_width_mm(c, f),
        ..HertzFactors::of(c).at(f, 1.0 / c.effective_radius_mm)
    }
}

/// The factors of a line contact's pressure and width that do not change with the contact
/// point: E*/(π·L) and 4/(π·L·E*), so that p0 = sqrt(F·(1/R*)·E*/(πL)) and
/// b = sqrt(F·R*·4/(πLE*)). The first-order sweep holds them once per scene and evaluates
/// every roller and angle with `at`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzFactors {
    pressure: f64,
    width: f64,
}

impl HertzFactors {
    pub fn of(c: &LineContact) -> Self {
        HertzFactors {
            pressure: c.contact_modulus_mpa / (PI * c.length_mm),
            width: 4.0 / (PI * c.length_mm * c.contact_modulus_mpa),
        }
    }

    /// The contact under force F (N; a negative force is none) with effective curvature
    /// 1/R* (1/mm).
    #[inline(always)]
    pub fn at(&self, force_n: f64, inverse_radius_per_mm: f64) -> HertzLine {
        let f = force_n.max(0.0);
        HertzLine {
            peak_pressure_mpa: (f * inverse_radius_per_mm * self.pressure).sqrt(),
            half_width_mm: (f / inverse_radius_per_mm * self.width).sqrt(),
        }
    }
}
