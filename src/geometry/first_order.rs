//! First-order (closed-form) clearance and moment arms (MODEL.md "First order"), the fast mode.
//!
//! For roller i at crank φ let φi = 2πi/np − φ (the roller's angle from the eccentric direction),
//! S = sqrt(1 + K1² − 2K1·cos φi), K1 = e·np/Rp. Then, to first order in ΔRp, ΔRrp, Δδ, β:
//!   moment arm   l_i = e·nc·sin φi / S                      (exact for the unmodified profile)
//!   gap at β = 0 g_i = ΔRrp − ΔRp·(1 − K1·cos φi)/S
//!   gap at β     g_i(β) = g_i − l_i·(β + Δδ)
//! The literature's closed form Δ(φi) (the gap after the disc turned to close its first gap) is
//! g_i − l_i·β1 with β1 = (ΔRrp − ΔRp·sqrt(1 − K1²))/(e·nc); see `literature_gap`.

use crate::model::{Design, Modification};

/// First-order gap at zero lag and moment arm of one roller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstOrderRoller {
    pub gap_mm: f64,
    pub arm_mm: f64,
}

/// Roller i at crank φ, lag 0 (the profile rotation Δδ is included as a lag).
pub fn roller(design: &Design, m: &Modification, i: usize, crank_rad: f64) -> FirstOrderRoller {
    let (s, c) = (design.roller_angle(i) - crank_rad).sin_cos();
    let (gap_mm, arm_mm) = Coefficients::new(design, m).at(c, s);
    FirstOrderRoller { gap_mm, arm_mm }
}

/// The design and modification constants of the first-order gaps and arms, computed once for
/// a sweep.
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
            rotation_rad: m.rotation_within_pitch(design.teeth),
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

impl Coefficients {
    /// S at the angle φi nearest the pitch point (φi = 0, where S is least) within `reach` rad
    /// of the angle whose (cos φi, sin φi) is given: a lower bound of S over that window.
    pub fn least_s_within(&self, (cos_phi_i, sin_phi_i): (f64, f64), reach: f64) -> f64 {
        let from_pitch = sin_phi_i.atan2(cos_phi_i).abs();
        let nearest = (from_pitch - reach).max(0.0);
        (self.one_plus_k1_sq - self.two_k1 * nearest.cos())
            .max(0.0)
            .sqrt()
    }

    /// Bounds of how fast the closing h = g_i − l_i·β = ΔRrp − ΔRp·f − e·nc·(β + Δδ)·q of a
    /// roller changes, with f = (1 − K1·c)/S and q = s/S (c, s = cos φi, sin φi; φi moves with
    /// −φ). With S² = (c − K1)² + s²:
    ///   f' = K1²·s·(K1 − c)/S³, and |s·(K1 − c)| ≤ S²/2 (AM–GM), so |f'| ≤ K1²/(2S);
    ///   q' = (c − K1)·(1 − K1·c)/S³, and |c − K1| ≤ S, |1 − K1·c| ≤ S
    ///        ((1 − K1·c)² = S² − K1²·s²), so |q'| ≤ 1/S;
    ///   |∂h/∂β| = e·nc·|q| ≤ e·nc, as |s| ≤ S.
    /// Hence |∂h/∂φ| ≤ (|ΔRp|·K1²/2 + e·nc·|β + Δδ|)/S for S ≥ `least_s`. Each of the three
    /// bounds on f', q' and q is attained somewhere (so none can be lowered as it stands), though
    /// not all at the same φi, and the least S of a window adds slack over the rest of it.
    /// Returns (bound of |∂h/∂φ| at lag β, bound of |∂h/∂β|), mm/rad.
    pub fn closing_rate_bounds(&self, least_s: f64, lag_rad: f64) -> (f64, f64) {
        let lever = self.e_nc_mm * (lag_rad + self.rotation_rad).abs();
        let crank = (self.shift_mm.abs() * self.k1 * self.k1 * 0.5 + lever) / least_s;
        (crank, self.e_nc_mm)
    }
}

/// How far the first-order closed form's linearisation in the lag is carried by a solution.
///
/// The closed form is the first term of the exact gap's expansion in the lag about the ideal
/// pose: g_i − l_i·(β + Δδ), the arm l_i that of the ideal pose whatever the lag. The exact
/// gap of roller i, G_i(β) = D(R(−β)·Q_i) − r' (D the signed distance to the locus C, Q_i the
/// roller centre seen from the disc centre), has the second derivative
///   H_i = ∂²G_i/∂β² = κ_C·(n_i·Q_i)² − n_i·Q_i
/// at the ideal pose (the Hessian of D on C is κ_C·t·tᵀ, and t·(J·Q) = ∓n·Q), with κ_C the
/// locus's curvature at the roller's contact (cos(nc·t_i) = cos φi, `Locus::curvature_at`) and
/// n_i·Q_i = (Rp + K1·e − e·(np + 1)·cos φi)/S_i (n_i = (u_i − K1·e_φ)/S_i, Q_i = Rp·u_i −
/// e·e_φ). Over a lag β the arm of roller i moves by H_i·β, which the closed form leaves out,
/// so the rollers' moment Σ F_i·l_i is off by up to
///   ε = |β + Δδ|·Σ F_i·|H_i| / Σ F_i·|l_i|
/// of itself. The closed form holds while ε < 1; at ε ≥ 1 the left-out term is as large as the
/// moment itself and no digit of the answer is known: the first-order geometry is outside its
/// validity. For the paper's design, over a mesh period in 1° steps, ε is at most 0.025 at
/// 20 N·m (β ≈ 0.0037 rad) and 2.1 at 1e5 N·m (β ≈ 0.18 rad), where the exact geometry's
/// rollers hold at most ~8.5e4 N·m; it reaches 1 at about 4.6e4 N·m. The modifications' own
/// second order (ΔR²/ρ) is left out of ε: it does not grow with the load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LagValidity<'a> {
    design: &'a Design,
    locus: crate::model::design::Locus,
    coefficients: Coefficients,
}

impl<'a> LagValidity<'a> {
    /// The bound's constants for `design` under the modification `m` (the locus of R' = Rp +
    /// ΔRp, the closed form's coefficients).
    pub fn new(design: &'a Design, m: &Modification) -> Self {
        LagValidity {
            design,
            locus: design.locus(m),
            coefficients: Coefficients::new(design, m),
        }
    }

    /// (l_i, H_i) of the roller at (cos φi, sin φi), mm (see the type).
    pub fn arm_and_bend(&self, cos_phi_i: f64, sin_phi_i: f64) -> (f64, f64) {
        let (_, arm, inverse_s) = self.coefficients.with_inverse_s(cos_phi_i, sin_phi_i);
        let (d, k1) = (self.design, self.coefficients.k1);
        let e = d.eccentricity_mm;
        let normal_reach = (d.roller_circle_radius_mm + k1 * e
            - e * (d.rollers as f64 + 1.0) * cos_phi_i)
            * inverse_s;
        let bend = self.locus.curvature_at(cos_phi_i) * normal_reach * normal_reach - normal_reach;
        (arm, bend)
    }

    /// ε at the crank angle `crank_rad` and lag `lag_rad` of rollers carrying `force_n[i]` (N):
    /// the share of the rollers' moment their arms move by over the lag. 0 without a force;
    /// not finite when the forces are not.
    pub fn moment_change(&self, crank_rad: f64, lag_rad: f64, force_n: &[f64]) -> f64 {
        let (mut moved, mut moment) = (0.0, 0.0);
        for (i, &f) in force_n.iter().enumerate().filter(|(_, f)| **f != 0.0) {
            let (s, c) = (self.design.roller_angle(i) - crank_rad).sin_cos();
            let (arm, bend) = self.arm_and_bend(c, s);
            moved += f.abs() * bend.abs();
            moment += f.abs() * arm.abs();
        }
        let lever = (lag_rad + self.coefficients.rotation_rad).abs();
        if moved == 0.0 || lever == 0.0 {
            return 0.0;
        }
        lever * moved / moment
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

#[cfg(test)]
mod tests {
    use super::Coefficients;
    use proptest::prelude::*;

    fn coefficients(k1: f64, e_nc_mm: f64, shift_mm: f64, rotation_rad: f64) -> Coefficients {
        Coefficients {
            one_plus_k1_sq: 1.0 + k1 * k1,
            two_k1: 2.0 * k1,
            k1,
            e_nc_mm,
            equidistant_mm: 0.1,
            shift_mm,
            rotation_rad,
        }
    }

    proptest! {
        /// The closing rate bounds hold against finite differences of the closed form: over a
        /// window of `reach` around φi, the change of h = g − l·β from the window's centre is
        /// within (bound of |∂h/∂φ|)·|Δφ| at the centre's lag, and within (bound of |∂h/∂β|)·|Δβ|
        /// at a fixed angle (the two legs the sweep's screen adds up). The 1e-12 mm slack covers
        /// the round-off of h (a few ulp of terms of ~1 mm).
        #[test]
        fn closing_changes_within_the_rate_bounds(
            k1 in 0.05f64..0.97,
            e_nc in 1.0f64..40.0,
            shift in -0.5f64..0.5,
            rotation in -0.01f64..0.01,
            lag in -0.02f64..0.02,
            centre in -3.2f64..3.2,
            reach in 1e-4f64..0.3,
            dlag in -1e-3f64..1e-3,
        ) {
            let c = coefficients(k1, e_nc, shift, rotation);
            let at = |phi: f64, lag: f64| {
                let (g, l) = c.at(phi.cos(), phi.sin());
                g - l * lag
            };
            let least_s = c.least_s_within((centre.cos(), centre.sin()), reach);
            let (rate_crank, rate_lag) = c.closing_rate_bounds(least_s, lag);
            let h0 = at(centre, lag);
            for k in -20..=20 {
                let phi = centre + reach * k as f64 / 20.0;
                let s = (1.0 + k1 * k1 - 2.0 * k1 * phi.cos()).sqrt();
                prop_assert!(least_s <= s * (1.0 + 1e-12), "S {s} below {least_s}");
                let h = at(phi, lag);
                let dphi = (phi - centre).abs();
                prop_assert!((h - h0).abs() <= rate_crank * dphi + 1e-12, "crank leg at {phi}");
                let moved = at(phi, lag + dlag);
                prop_assert!((moved - h).abs() <= rate_lag * dlag.abs() + 1e-12, "lag leg at {phi}");
            }
        }
    }
}
