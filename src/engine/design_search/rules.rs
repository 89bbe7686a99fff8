//! The requirements' constraints on a candidate that need no physics: the envelope, the
//! requirements' design rules (K1, roller gap, pin-hole ligaments) and a circular crown's flat
//! middle inside the candidate's face. The spec's own rules
//! (`spec::rules`: K1 < 1, undercut, rollers overlapping, holes) run when its spec is parsed.

use super::candidate::*;
use super::failure::{Failure, Requirement};
use crate::model::requirements::Requirements;
use crate::model::Crowning;
use std::f64::consts::PI;

/// Every requirement that `c` breaks before any physics, each with its value and limit.
pub fn failures(req: &Requirements, c: &Candidate) -> Vec<Failure> {
    let x = &c.x;
    let np = c.rollers() as f64;
    let m = c.choice.pins as f64;
    let mut out = Vec::new();
    let mut max = |requirement: Requirement, value: f64, limit: f64| {
        if value > limit {
            out.push(Failure::bound(requirement, value, limit));
        }
    };
    max(
        Requirement::OuterDiameter,
        c.outer_diameter_mm(req),
        req.envelope.max_outer_diameter_mm,
    );
    max(
        Requirement::AxialLength,
        c.axial_length_mm(req),
        req.envelope.max_axial_length_mm,
    );
    // K1 = e·np/Rp (the spec refuses K1 ≥ 1 whatever the requirements say).
    let k1 = x[E] * np / x[RP];
    if k1 > req.rules.max_k1 || (req.rules.max_k1 >= 1.0 && k1 >= 1.0) {
        out.push(Failure::bound(Requirement::MaxK1, k1, req.rules.max_k1));
    }
    let mut min = |requirement: Requirement, value: f64, limit: f64| {
        if value < limit {
            out.push(Failure::bound(requirement, value, limit));
        }
    };
    // Gap between neighbouring rollers: 2·Rp·sin(π/np) − 2·Rrp.
    let gap = 2.0 * x[RP] * (PI / np).sin() - 2.0 * x[RRP];
    min(Requirement::MinRollerGap, gap, req.rules.min_roller_gap_mm);
    // Pin-hole ligaments (rh = rpin + e + hole clearance): hole to hole
    // 2·rw·sin(π/M) − 2·rh, hole to tooth root Rp + ΔRp − e − (Rrp + ΔRrp) − rw − rh, hole
    // to the disc centre rw − rh; the smallest of the three.
    let hole = x[RPIN] + x[E] + req.search.hole_clearance_mm;
    let root = x[RP] + x[SHIFT] - x[E] - (x[RRP] + x[EQUIDISTANT]);
    let ligament = (2.0 * x[RW] * (PI / m).sin() - 2.0 * hole)
        .min(root - x[RW] - hole)
        .min(x[RW] - hole);
    min(
        Requirement::MinLigament,
        ligament,
        req.rules.min_ligament_mm,
    );
    // A circular crown's flat middle inside the face: start z0 < B/2 (the spec refuses
    // z0 ≥ B/2 at `modification.crowning.start_mm`); recorded as z0 against B/2.
    if let Crowning::Circular { start_mm, .. } = req.crowning {
        if start_mm >= 0.5 * x[B] {
            out.push(Failure::bound(
                Requirement::CrownStart,
                start_mm,
                0.5 * x[B],
            ));
        }
    }
    out
}
