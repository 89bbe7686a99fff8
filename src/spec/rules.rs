//! Design rules a disc must satisfy before anything is computed. Each failure names the rule,
//! the numbers and the spec key to change.

use crate::error::{Error, ErrorKind, Result};
use crate::model::design::{roller_gap_mm, root_radius_mm, Ligaments};
use crate::model::{Design, Modification};
use crate::units;

/// The refusal of an impossible design by a rule, at the spec key to change.
pub(super) fn rule(key: &str, message: String) -> Error {
    Error::new(ErrorKind::ImpossibleDesign, message).at_key(key)
}

/// Check every geometric rule; the first one broken is the error.
pub fn check(design: &Design, m: &Modification) -> Result<()> {
    let e = design.eccentricity_mm;
    let np = design.rollers as f64;
    let rp = design.roller_circle_radius_mm;
    let k1 = design.k1();
    if k1 >= 1.0 {
        return Err(rule(
            "reducer.eccentricity_mm",
            format!(
                "short-amplitude coefficient K1 = e·np/Rp = {e}·{np}/{rp} = {k1:.4} must be below 1 \
                 (the locus would loop)"
            ),
        ));
    }
    let locus_radius = rp + m.shift_mm;
    let locus_k1 = crate::model::design::k1(e, design.rollers, locus_radius);
    if locus_radius <= 0.0 || locus_k1 >= 1.0 {
        return Err(rule(
            "modification.shift_mm",
            format!(
                "the shifted locus radius Rp + ΔRp = {locus_radius:.4} mm gives K1 = {locus_k1:.4}; \
                 it must stay below 1"
            ),
        ));
    }
    let offset = design.roller_radius_mm + m.equidistant_mm;
    if offset <= 0.0 {
        return Err(rule(
            "modification.equidistant_mm",
            format!("the generating roller radius Rrp + ΔRrp = {offset:.4} mm must be positive"),
        ));
    }
    let convex = design.locus(m).min_convex_radius();
    if offset >= convex.radius_mm {
        return Err(rule(
            "reducer.roller_radius_mm",
            format!(
                "undercut: the generating roller radius Rrp + ΔRrp = {offset:.4} mm is not smaller than \
                 the smallest convex radius of curvature of the roller-centre locus, {:.4} mm \
                 (at t = {:.3}° from the tooth root); the profile would have cusps",
                convex.radius_mm,
                units::deg(convex.t)
            ),
        ));
    }
    let gap = roller_gap_mm(rp, design.roller_radius_mm, design.rollers);
    if gap <= 0.0 {
        return Err(rule(
            "reducer.roller_radius_mm",
            format!(
                "rollers overlap: the distance between neighbouring roller centres, \
                 2·Rp·sin(π/np) = {:.4} mm, must exceed the roller diameter {:.4} mm",
                gap + 2.0 * design.roller_radius_mm,
                2.0 * design.roller_radius_mm
            ),
        ));
    }
    check_holes(design, root_radius_mm(locus_radius, e, offset))
}

fn check_holes(design: &Design, root_radius: f64) -> Result<()> {
    let rw = design.pins.circle_radius_mm;
    let hole = design.hole_radius_mm();
    let ligaments = Ligaments::of(rw, hole, design.pins.count, root_radius);
    if ligaments.to_root_mm <= 0.0 {
        return Err(rule(
            "reducer.output_pins.circle_radius_mm",
            format!(
                "output-pin holes cut into the tooth root: pin circle radius + hole radius \
                 = {rw} + {hole:.4} = {:.4} mm reaches the root radius of the profile, \
                 Rp + ΔRp − e − (Rrp + ΔRrp) = {root_radius:.4} mm \
                 (hole radius = pin radius + e + hole clearance)",
                rw + hole
            ),
        ));
    }
    if ligaments.between_holes_mm <= 0.0 {
        return Err(rule(
            "reducer.output_pins.count",
            format!(
                "output-pin holes overlap: neighbouring hole centres are {:.4} mm apart, \
                 less than the hole diameter {:.4} mm",
                ligaments.between_holes_mm + 2.0 * hole,
                2.0 * hole
            ),
        ));
    }
    if ligaments.to_centre_mm <= 0.0 {
        return Err(rule(
            "reducer.output_pins.circle_radius_mm",
            format!(
                "output-pin holes reach the disc centre: pin circle radius {rw} mm must exceed \
                 the hole radius {hole:.4} mm"
            ),
        ));
    }
    Ok(())
}
