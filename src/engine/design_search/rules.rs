//! The requirements' constraints on a candidate that need no physics: the envelope, the
//! requirements' design rules (K1, roller gap, pin-hole ligaments) and a circular crown's flat
//! middle inside the candidate's face. The spec's own rules
//! (`spec::rules`: K1 < 1, undercut, rollers overlapping, holes) run when its spec is parsed.

use super::candidate::Candidate;
use super::failure::{Failure, Requirement};
use crate::model::design::{k1, roller_gap_mm, root_radius_mm, Ligaments};
use crate::model::requirements::Requirements;
use crate::model::Crowning;

/// Every requirement that `c` breaks before any physics, each with its value and limit.
pub fn failures(req: &Requirements, c: &Candidate) -> Vec<Failure> {
    let x = &c.x;
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
    let k1 = k1(x.eccentricity_mm, c.rollers(), x.roller_circle_radius_mm);
    if k1 > req.rules.max_k1 || (req.rules.max_k1 >= 1.0 && k1 >= 1.0) {
        out.push(Failure::bound(Requirement::MaxK1, k1, req.rules.max_k1));
    }
    let mut min = |requirement: Requirement, value: f64, limit: f64| {
        if value < limit {
            out.push(Failure::bound(requirement, value, limit));
        }
    };
    // The spec's own formulas (`model::design`), bounded by the requirements' rules.
    min(
        Requirement::MinRollerGap,
        roller_gap_mm(x.roller_circle_radius_mm, x.roller_radius_mm, c.rollers()),
        req.rules.min_roller_gap_mm,
    );
    let root = root_radius_mm(
        x.roller_circle_radius_mm + x.shift_mm,
        x.eccentricity_mm,
        x.roller_radius_mm + x.equidistant_mm,
    );
    let ligaments = Ligaments::of(
        x.pin_circle_radius_mm,
        c.hole_radius_mm(req),
        c.choice.pins,
        root,
    );
    min(
        Requirement::MinLigament,
        ligaments.smallest_mm(),
        req.rules.min_ligament_mm,
    );
    // A circular crown's flat middle inside the face: start z0 < B/2 (the spec refuses
    // z0 ≥ B/2 at `modification.crowning.start_mm`); recorded as z0 against B/2.
    if let Crowning::Circular { start_mm, .. } = req.crowning {
        if start_mm >= 0.5 * x.face_width_mm {
            out.push(Failure::bound(
                Requirement::CrownStart,
                start_mm,
                0.5 * x.face_width_mm,
            ));
        }
    }
    out
}
