//! First-order (closed-form) clearance and moment arms (MODEL.md "First order"), the fast mode.
//!
//! For roller i at crank φ let φi = 2πi/np − φ (the roller's angle from the eccentric direction),
//! S = sqrt(1 + K1² − 2K1·cos φi), K1 = e·np/Rp. Then, to first order in ΔRp, ΔRrp, Δδ, β:
//!   moment arm   l_i = e·nc·sin φi / S                      (exact for the unmodified profile)
//!   gap at β = 0 g_i = ΔRrp − ΔRp·(1 − K1·cos φi)/S
//!   gap at β     g_i(β) = g_i − l_i·(β + Δδ)
//! The literature's closed form Δ(φi) (the gap after the disc turned to close its first gap) is
//! g_i − l_i·β1 with β1 = (ΔRrp − ΔRp·sqrt(1 − K1²))/(e·nc); see `literature_gap`.

use crate::spec::{Design, Modification};

/// First-order gap at zero lag and moment arm of one roller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstOrderRoller {
    pub gap_mm: f64,
    pub arm_mm: f64,
}

/// Roller i at crank φ, lag 0 (the profile rotation Δδ is included as a lag).
pub fn roller(design: &Design, m: &Modification, i: usize, crank_rad: f64) -> FirstOrderRoller {
    let (s, c) = (design.roller_angle(i) - crank_rad).sin_cos();
    let (gap_mm, arm_mm) = from_phase(design, m, c, s);
    FirstOrderRoller { gap_mm, arm_mm }
}

/// (gap at zero lag, arm) of a roller from cos φi and sin φi.
#[inline]
pub fn from_phase(design: &Design, m: &Modification, cos_phi_i: f64, sin_phi_i: f64) -> (f64, f64) {
    let k1 = design.k1();
    let big_s = (1.0 + k1 * k1 - 2.0 * k1 * cos_phi_i).sqrt();
    let arm_mm = design.eccentricity_mm * design.teeth as f64 * sin_phi_i / big_s;
    let gap_mm =
        m.equidistant_mm - m.shift_mm * (1.0 - k1 * cos_phi_i) / big_s - arm_mm * m.rotation_rad;
    (gap_mm, arm_mm)
}

/// The literature's Δ(φi) = ΔRrp(1 − sin φi/S) − ΔRp(1 − K1 cos φi − sqrt(1 − K1²) sin φi)/S.
pub fn literature_gap(design: &Design, m: &Modification, i: usize, crank_rad: f64) -> f64 {
    let k1 = design.k1();
    let phi_i = design.roller_angle(i) - crank_rad;
    let (s, c) = phi_i.sin_cos();
    let big_s = (1.0 + k1 * k1 - 2.0 * k1 * c).sqrt();
    m.equidistant_mm * (1.0 - s / big_s)
        - m.shift_mm * (1.0 - k1 * c - (1.0 - k1 * k1).sqrt() * s) / big_s
}
