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
    Coefficients::new(design, m).at(cos_phi_i, sin_phi_i)
}

/// The design and modification constants of `from_phase`, computed once for a sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coefficients {
    /// 1 + K1².
    one_plus_k1_sq: f64,
    /// 2·K1.
    two_k1: f64,
    /// K1 = e·np/Rp.
    pub k1: f64,
    /// e·nc, mm.
    e_nc_mm: f64,
    equidistant_mm: f64,
    shift_mm: f64,
    rotation_rad: f64,
}

impl Coefficients {
    pub fn new(design: &Design, m: &Modification) -> Self {
        let k1 = design.k1();
        Coefficients {
            one_plus_k1_sq: 1.0 + k1 * k1,
            two_k1: 2.0 * k1,
            k1,
            e_nc_mm: design.eccentricity_mm * design.teeth as f64,
            equidistant_mm: m.equidistant_mm,
            shift_mm: m.shift_mm,
            rotation_rad: m.rotation_rad,
        }
    }

    /// (g_i, l_i): S = sqrt(1 + K1² − 2K1·cos φi), l_i = e·nc·sin φi/S,
    /// g_i = ΔRrp − ΔRp·(1 − K1·cos φi)/S − l_i·Δδ.
    #[inline]
    pub fn at(&self, cos_phi_i: f64, sin_phi_i: f64) -> (f64, f64) {
        let (gap_mm, arm_mm, _) = self.with_inverse_s(cos_phi_i, sin_phi_i);
        (gap_mm, arm_mm)
    }

    /// `at` and 1/S, where S is also |u_i − K1·e_φ|: the distance from the pitch point to the
    /// roller centre in units of Rp. Both quotients by S multiply by 1/S (one division).
    #[inline]
    pub fn with_inverse_s(&self, cos_phi_i: f64, sin_phi_i: f64) -> (f64, f64, f64) {
        let inverse_s = 1.0 / (self.one_plus_k1_sq - self.two_k1 * cos_phi_i).sqrt();
        let arm_mm = self.e_nc_mm * sin_phi_i * inverse_s;
        let gap_mm = self.equidistant_mm
            - self.shift_mm * (1.0 - self.k1 * cos_phi_i) * inverse_s
            - arm_mm * self.rotation_rad;
        (gap_mm, arm_mm, inverse_s)
    }
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
