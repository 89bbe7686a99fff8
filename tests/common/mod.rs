//! Helpers shared by the geometry and export tests: designs built directly, the paper's spec,
//! a closed form of the locus curvature, and the proptest strategy of valid designs.
//!
//! Nothing here calls the code under test to produce an expected value: the closed forms are
//! derived below from the definition of the locus in MODEL.md.
#![allow(dead_code)] // each test crate uses a different subset

use cycloid::model::{Design, Material, Modification, OutputPins};
use cycloid::spec::{self, Spec};
use proptest::prelude::*;
use std::f64::consts::PI;

pub const STEEL: Material = Material {
    youngs_modulus_mpa: 206_000.0,
    poisson_ratio: 0.3,
};

/// A design with np rollers (nc = np − 1 teeth). Pins and materials do not enter the geometry.
pub fn design(rollers: usize, eccentricity_mm: f64, rp_mm: f64, rrp_mm: f64) -> Design {
    Design {
        teeth: rollers - 1,
        rollers,
        eccentricity_mm,
        roller_circle_radius_mm: rp_mm,
        roller_radius_mm: rrp_mm,
        face_width_mm: 8.0,
        pins: OutputPins {
            count: 6,
            circle_radius_mm: 0.5 * rp_mm,
            pin_radius_mm: 0.05 * rp_mm,
            hole_clearance_mm: 0.0,
        },
        disc_material: STEEL,
        roller_material: STEEL,
    }
}

pub fn modification(shift_mm: f64, equidistant_mm: f64, rotation_rad: f64) -> Modification {
    Modification {
        shift_mm,
        equidistant_mm,
        rotation_rad,
    }
}

/// The paper's design (Table 1): nc 9, np 10, e 2, Rp 30, Rrp 3.
pub fn paper_design() -> Design {
    design(10, 2.0, 30.0, 3.0)
}

/// specs/reducer.yaml with its modification replaced, parsed and validated by `spec::parse`.
pub fn paper_spec(shift_mm: f64, equidistant_mm: f64) -> Spec {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/specs/reducer.yaml");
    let text = std::fs::read_to_string(path).expect("specs/reducer.yaml is readable");
    let mut replaced = 0;
    let text: String = text
        .lines()
        .map(|line| {
            let key = line.trim_start();
            if key.starts_with("shift_mm:") {
                replaced += 1;
                format!("  shift_mm: {shift_mm}")
            } else if key.starts_with("equidistant_mm:") {
                replaced += 1;
                format!("  equidistant_mm: {equidistant_mm}")
            } else {
                line.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    assert_eq!(
        replaced, 2,
        "reducer.yaml has one shift_mm and one equidistant_mm"
    );
    spec::parse(path, &text).unwrap_or_else(|e| panic!("paper spec is valid: {e}"))
}

/// Curvature of the locus C(t) = R(cos t, sin t) − e(cos nt, sin nt) (n = np) as a function of
/// x = cos(nc·t), derived by hand from C' and C'':
///   C'×C'' = R² + e²n³ − R·e·n(n+1)·x,   |C'|² = R² + e²n² − 2R·e·n·x,
///   κ_C = (C'×C'')/|C'|³.
pub fn locus_curvature_closed(rollers: usize, e: f64, r: f64, x: f64) -> f64 {
    let n = rollers as f64;
    (r * r + e * e * n.powi(3) - r * e * n * (n + 1.0) * x)
        / (r * r + e * e * n * n - 2.0 * r * e * n * x).powf(1.5)
}

/// Smallest convex radius of curvature of the locus and the parameter t ∈ [0, π/nc] (from the
/// root) where it occurs, in closed form. κ_C(x) = (A − Bx)/(D − Ex)^{3/2} has a single
/// stationary point x* = (3AE − 2BD)/(BE) = (3(1 + K²n) − (n + 1)(1 + K²))/(K(n + 1)),
/// K = e·n/R; the maximum curvature on [−1, 1] is at x* (if inside) or at an end.
pub fn min_convex_radius_closed(rollers: usize, e: f64, r: f64) -> (f64, f64) {
    let n = rollers as f64;
    let k = e * n / r;
    let x_star = (3.0 * (1.0 + k * k * n) - (n + 1.0) * (1.0 + k * k)) / (k * (n + 1.0));
    let (x, kappa) = [x_star.clamp(-1.0, 1.0), -1.0, 1.0]
        .into_iter()
        .map(|x| (x, locus_curvature_closed(rollers, e, r, x)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    (1.0 / kappa, x.acos() / (n - 1.0))
}

/// A valid design and a modification that keeps it valid.
#[derive(Debug, Clone)]
pub struct Case {
    pub design: Design,
    pub m: Modification,
}

impl Case {
    pub fn k1(&self) -> f64 {
        self.design.k1()
    }
}

/// Largest modification a case may carry: 0.3 mm, but small against the tooth depth (2e) and
/// the roller, so that the gaps stay a small-modification question.
fn modification_cap(e: f64, rrp: f64) -> f64 {
    0.3f64.min(0.15 * e).min(0.5 * rrp)
}

/// Build a case from unit parameters; `None` if the modification cannot be kept valid.
/// - np rollers, Rp, K1 = e·np/Rp in (0.1, 0.9);
/// - Rrp = u·0.8·min(ρmin, Rp·sin(π/np)): below 0.8 of the smallest convex radius of curvature
///   of the locus (no undercut) and of half the roller pitch (rollers do not overlap);
/// - ΔRp = a·cap, ΔRrp in [−cap, min(cap, 0.9·ρmin(Rp + ΔRp) − Rrp)] (still undercut-free).
#[allow(clippy::too_many_arguments)]
pub fn build_case(
    rollers: usize,
    rp: f64,
    k1: f64,
    u: f64,
    a: f64,
    b: f64,
    rotation_rad: f64,
) -> Option<Case> {
    let n = rollers as f64;
    let e = k1 * rp / n;
    let (rho, _) = min_convex_radius_closed(rollers, e, rp);
    let rrp = u * 0.8 * rho.min(rp * (PI / n).sin());
    let cap = modification_cap(e, rrp);
    let shift = a * cap;
    let (rho_shifted, _) = min_convex_radius_closed(rollers, e, rp + shift);
    let hi = cap.min(0.9 * rho_shifted - rrp);
    let lo = -cap;
    if hi <= lo || e * n / (rp + shift) >= 0.95 {
        return None;
    }
    Some(Case {
        design: design(rollers, e, rp, rrp),
        m: modification(shift, lo + b * (hi - lo), rotation_rad),
    })
}

/// Random valid designs with random modifications (no profile rotation).
pub fn cases() -> impl Strategy<Value = Case> {
    (
        4usize..=40,
        20.0f64..120.0,
        0.1f64..0.9,
        0.1f64..1.0,
        -1.0f64..1.0,
        0.0f64..1.0,
    )
        .prop_filter_map("modification must keep the design valid", |p| {
            build_case(p.0, p.1, p.2, p.3, p.4, p.5, 0.0)
        })
}

/// As `cases`, with a profile rotation Δδ of up to ±0.2 mrad.
pub fn rotated_cases() -> impl Strategy<Value = Case> {
    (cases(), -2e-4f64..2e-4).prop_map(|(mut c, d)| {
        c.m.rotation_rad = d;
        c
    })
}

/// Random valid designs with the profile unmodified.
pub fn unmodified_cases() -> impl Strategy<Value = Case> {
    cases().prop_map(|mut c| {
        c.m = Modification::default();
        c
    })
}
