//! How fast the housing's rollers spin when they turn on their pins and roll on the disc
//! (`reducer.friction.rollers.mode: rotating`), for their share of the inertia at the input.
//!
//! The disc's centre O₁ = e·u(φ) moves at e·ω·u⊥ while the disc turns at ψ̇ = −ω/nc (MODEL.md
//! "Conventions"), so the disc's motion is, at each instant, a turn at ψ̇ about the point I
//! where its velocity vanishes: v(P) = ψ̇·k × (P − I) with v(O₁) = e·ω·u⊥ gives
//! I = O₁ + e·nc·u = e·np·u, the pitch point (the disc's pitch circle e·nc rolls inside the
//! housing's e·np). By the law of gearing the contact normal of roller i passes through I and
//! through the roller's centre Cᵢ = Rp·(cos θᵢ, sin θᵢ), so its contact point Pᵢ lies on CᵢI, Rrp
//! from Cᵢ: |Pᵢ − I| = dᵢ − Rrp with dᵢ = |Cᵢ − I|. The disc's point Pᵢ moves at
//! (ω/nc)·(dᵢ − Rrp) along the tangent; a roller rolling on it without slip turns at
//!   Ωᵢ = (ω/nc)·(dᵢ − Rrp)/Rrp,
//! the speed the fixed roller's sliding has (`equilibrium::friction::sliding`) over its radius.
//! Every roller is taken to roll (those a modified profile leaves out of contact too: their
//! pins' drag keeps them near that speed); a roller of inertia J_r about its axis has the
//! kinetic energy ½·J_r·Ωᵢ².

use crate::model::Design;
use std::f64::consts::TAU;

/// Points of the trapezoid rule over a turn of the crank: the integrand is periodic and
/// analytic (dᵢ ≥ Rp·(1 − K1) > 0), so the rule converges geometrically, as (K1)^N; 4,096 points
/// leave round-off for every K1 < 0.99.
const POINTS: usize = 4096;

/// ⟨Σᵢ (Ωᵢ/ω)²⟩, the rollers' spin energy per ½·J_r·ω², averaged over a turn of the crank
/// (dimensionless): (1/(nc·Rrp)²)·np·⟨(d − Rrp)²⟩ with d² = Rp² + (e·np)² − 2·Rp·e·np·cos α and α
/// uniform over a turn (the np rollers are evenly spaced, so the sum over them averages as np
/// times one roller's mean over α). Closed form, for the tests: ⟨d⟩ = (2(a + b)/π)·E(k),
/// k = 2√(ab)/(a + b), a = Rp, b = e·np, E the complete elliptic integral of the second kind.
pub fn mean_square_spin_ratio(design: &Design) -> f64 {
    let (a, b) = (
        design.roller_circle_radius_mm,
        design.eccentricity_mm * design.rollers as f64,
    );
    let r = design.roller_radius_mm;
    let mean = (0..POINTS)
        .map(|k| {
            let alpha = TAU * k as f64 / POINTS as f64;
            let d = (a * a + b * b - 2.0 * a * b * alpha.cos()).sqrt();
            (d - r) * (d - r)
        })
        .sum::<f64>()
        / POINTS as f64;
    let nc_r = design.teeth as f64 * r;
    design.rollers as f64 * mean / (nc_r * nc_r)
}
