//! Output pins as beams (issue 29, `reducer.output_pins.support`): the pin's bending at each
//! disc's mid-plane, in series with its contact in the hole.
//!
//! A pin is an Euler–Bernoulli beam of bending stiffness EI, E the pins' modulus (the rollers'
//! material, `reducer.roller_material`, which the pins' contacts take too) and
//! I = π·d⁴/64 with d = 2·r the diameter of the pin that bends: the pin itself, radius
//! `output_pins.pin_radius_mm`, or with free sleeves (`reducer.friction.output_pins.mode:
//! sleeve`) the pin inside the sleeve, radius `bore_radius_mm` (the sleeve turns on it and
//! carries no bending). Disc k loads it at its mid-plane z = a_k (mm from the flange) with a
//! point force; the deflection at disc j's plane per unit force at disc k's is the influence
//! coefficient c_jk (mm/N), the same in x and y (a round pin):
//!
//! - `cantilever` (clamped in the flange at z = 0, free at z = L): for a ≤ b,
//!   c(a, b) = a²·(3b − a)/(6EI) (Gere & Goodno, *Mechanics of Materials*, Table G-1 case 5;
//!   Roark's *Formulas for Stress and Strain*, Table 8.1 case 1a), symmetric (Maxwell);
//!   at the load c(a, a) = a³/(3EI).
//! - `both_ends` (clamped in the flange at z = 0, simply supported at z = L: a propped
//!   cantilever): the cantilever's coefficients less the prop's reaction R = P·c0(L, b)/c0(L, L)
//!   (superposition, the deflection at L held at zero):
//!   c(a, b) = c0(a, b) − c0(a, L)·c0(L, b)/c0(L, L), c0 the cantilever's. At the load this is
//!   the propped cantilever's y/P = a³·(L − a)²·(4L − a)/(12·EI·L³) (Roark, Table 8.1 case
//!   1c; AISC *Steel Construction Manual*, beam diagrams case 14, with a from the flange).
//!
//! Shear deflection is ignored: a pin's shear compliance over its bending one is of order
//! (d/a)²·(E/G)·(10/9)/16 ≈ 0.18·(d/a)² for steel, a few percent for a pin whose disc sits
//! two diameters or more from the flange, and less than the uncertainty of the clamping.
//!
//! In the balance: disc k's pin j pushes the hole wall with F_kj along û_kj (fixed frame); the
//! hole pushes the pin back, so the pin's centre at disc j's plane moves by
//! −Σ_k c_jk·F_kj·û_kj, and disc j's gap e + c − |Q − H| opens by its projection on û_j:
//!   gap_j = gap_rigid,j + c_jj·F_j + Σ_{k≠j} c_jk·F_k·(û_j·û_k)
//! (to first order in the deflection, tiny next to e). The own term is a spring in series with
//! the contact (`series_force`); the others' terms are an extra gap per pin that couples the
//! discs (`Pins::set_beam_gaps`, solved by `discs::solve_coupled`).

use crate::contact::law::{self, ContactForce, LineContact};
use crate::model::{ContactLaw, Design, PinMode, PinSupportKind, MAX_DISCS};
use std::f64::consts::PI;

/// The influence coefficients of one output pin, every pin alike.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinBeam {
    /// c_jk, mm/N: deflection at disc j's mid-plane per unit force at disc k's.
    pub coefficients_mm_per_n: [[f64; MAX_DISCS]; MAX_DISCS],
    /// The discs along the pin (the first `discs` rows and columns are used).
    pub discs: usize,
    /// Radius of the pin that bends, mm (the pin, or the pin inside a sleeve).
    pub bending_radius_mm: f64,
}

/// I = π·d⁴/64 of a round section of diameter `diameter_mm`, mm⁴.
pub fn second_moment_mm4(diameter_mm: f64) -> f64 {
    PI * diameter_mm.powi(4) / 64.0
}

/// A cantilever clamped at z = 0 (free end beyond both points): the deflection at z = a per
/// unit force at z = b, a²(3b − a)/(6EI) for a ≤ b and symmetric, mm/N.
pub fn cantilever_influence(a_mm: f64, b_mm: f64, ei_nmm2: f64) -> f64 {
    let (x, y) = (a_mm.min(b_mm), a_mm.max(b_mm));
    x * x * (3.0 * y - x) / (6.0 * ei_nmm2)
}

/// The share of a force at z = `load_mm` that the prop of a propped cantilever of length
/// `length_mm` carries: the cantilever's deflection at L under the load over its deflection
/// at L under the prop's own unit force, c0(L, a)/c0(L, L) = a²·(3L − a)/(2L³) (Roark, Table
/// 8.1 case 1c).
pub fn prop_share(load_mm: f64, length_mm: f64) -> f64 {
    cantilever_influence(length_mm, load_mm, 1.0) / cantilever_influence(length_mm, length_mm, 1.0)
}

/// A beam clamped at z = 0 and simply supported at z = `length_mm`: the cantilever's
/// coefficient less the prop's, c0(a, b) − c0(a, L)·c0(L, b)/c0(L, L), mm/N.
pub fn propped_influence(a_mm: f64, b_mm: f64, length_mm: f64, ei_nmm2: f64) -> f64 {
    let c0 = |x, y| cantilever_influence(x, y, ei_nmm2);
    let l = length_mm;
    c0(a_mm, b_mm) - c0(a_mm, l) * c0(l, b_mm) / c0(l, l)
}

impl PinBeam {
    /// The pins of `design` as beams, or none when its pins are rigid (no `support`).
    pub fn of(design: &Design) -> Option<PinBeam> {
        let support = design.pins.support?;
        let sleeve = design
            .friction
            .and_then(|f| f.output_pins)
            .and_then(|p| match p.mode {
                PinMode::Sleeve { bore_radius_mm } => Some(bore_radius_mm),
                PinMode::Fixed => None,
            });
        let r = sleeve.unwrap_or(design.pins.pin_radius_mm);
        let ei = design.roller_material.youngs_modulus_mpa * second_moment_mm4(2.0 * r);
        let a = support.disc_positions_mm;
        let mut c = [[0.0; MAX_DISCS]; MAX_DISCS];
        for j in 0..design.discs {
            for k in 0..design.discs {
                c[j][k] = match support.kind {
                    PinSupportKind::Cantilever => cantilever_influence(a[j], a[k], ei),
                    PinSupportKind::BothEnds => {
                        propped_influence(a[j], a[k], support.length_mm, ei)
                    }
                };
            }
        }
        Some(PinBeam {
            coefficients_mm_per_n: c,
            discs: design.discs,
            bending_radius_mm: r,
        })
    }

    /// c_kk, mm/N: the pin's own compliance at disc k's plane, in series with its contact.
    pub fn own_compliance_mm_per_n(&self, disc: usize) -> f64 {
        self.coefficients_mm_per_n[disc][disc]
    }

    /// Whether the pins couple several discs (more than one disc along them).
    pub fn couples(&self) -> bool {
        self.discs > 1
    }
}

/// The contact of `law` in series with a spring of compliance `compliance_mm_per_n` (the
/// pin's bending at the disc): the force F with approach_total = d_contact(F) + c·F, and the
/// series stiffness dF/d(approach_total) = 1/(1/k_contact + c), k_contact = dF/dd of the
/// contact at F. With the paper's linear law F = approach/(1/k + c) exactly; with Johnson's
/// law d_contact is strictly increasing (`law::johnson_approach_mm`), so is the sum, and a
/// safeguarded Newton in ln F (`law::johnson_force_in_series`) finds its one root. c = 0 is
/// the contact alone, bit for bit.
// Inlined into `Pins::evaluate_at`: where the compiler chose otherwise (a build whose only
// changes were in report and numeric, 66d9331) a two-disc `check` took 1.0 % more
// instructions (91.56 M against 90.64 M, callgrind, one thread), 0.65 M of it the call.
#[inline]
pub fn series_force(
    contact_law: ContactLaw,
    contact: &LineContact,
    compliance_mm_per_n: f64,
    approach_mm: f64,
) -> ContactForce {
    if compliance_mm_per_n == 0.0 || approach_mm <= 0.0 {
        return law::force(contact_law, contact, approach_mm);
    }
    let c = compliance_mm_per_n;
    let k = series_linear_stiffness(contact, c);
    match contact_law {
        ContactLaw::PaperLinear => ContactForce::linear(k, approach_mm),
        // Started from the linear law in series: Johnson's law is softer than it at these
        // loads, so the answer lies below.
        ContactLaw::HertzNonlinear => law::johnson_force_in_series(contact, (c, k), approach_mm),
    }
}

/// The paper's linear law of `contact` in series with a spring of compliance
/// `compliance_mm_per_n`: 1/(1/k + c), N/mm; c = 0 is the contact's k itself, bit for bit.
#[inline]
pub fn series_linear_stiffness(contact: &LineContact, compliance_mm_per_n: f64) -> f64 {
    let k = law::paper_linear_stiffness(contact);
    if compliance_mm_per_n == 0.0 {
        return k;
    }
    1.0 / (1.0 / k + compliance_mm_per_n)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The propped cantilever's coefficient at the load point equals Roark's closed form
    /// P·a³·(L − a)²·(4L − a)/(12·EI·L³) (Table 8.1 case 1c), and the coefficients are
    /// symmetric (Maxwell–Betti); both to round-off.
    #[test]
    fn the_propped_cantilever_matches_roark() {
        let (l, ei): (f64, f64) = (30.0, 2.06e5 * second_moment_mm4(10.0));
        for a in [3.0f64, 10.0, 17.5, 29.0] {
            let roark = a.powi(3) * (l - a).powi(2) * (4.0 * l - a) / (12.0 * ei * l.powi(3));
            let c = propped_influence(a, a, l, ei);
            assert!((c - roark).abs() <= 1e-12 * roark, "a {a}: {c} vs {roark}");
            let other = propped_influence(a, 20.0, l, ei);
            assert!(
                (other - propped_influence(20.0, a, l, ei)).abs() <= 1e-15 * c.abs().max(1e-12)
            );
        }
    }
}
