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
        peak_pressure_mpa: (f * c.contact_modulus_mpa / (PI * c.length_mm * c.effective_radius_mm))
            .sqrt(),
        half_width_mm: half_width_mm(c, f),
    }
}
