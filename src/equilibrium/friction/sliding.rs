//! Rigid-body kinematics at the nominal ratio and the sliding speed of each contact
//! (MODEL.md "Friction, efficiency and heat"). Every speed here is per unit input speed
//! (ω = 1 rad/s): multiply by ω for mm/s. Fixed frame at the input axis.
//!
//! Disc and output flange turn at ωd = −ω/nc; the crank turns at Ω = ω(1 + 1/nc) relative
//! to the disc. The disc's velocity field is v(X) = v_c + ωd ẑ × (X − O_d) with its centre
//! O_d = e(cos φ, sin φ) moving at v_c = e·ω(−sin φ, cos φ); its instantaneous centre is the
//! pitch point I = e·np(cos φ, sin φ).

use crate::geometry::{cross, z_cross, Vec2};

/// ωd / ω = −1/nc: the disc's (and output's) speed per unit input speed.
pub fn disc_speed_ratio(teeth: usize) -> f64 {
    -1.0 / teeth as f64
}

/// Ω / ω = 1 + 1/nc: the crank's speed relative to the disc per unit input speed.
pub fn relative_crank_speed_ratio(teeth: usize) -> f64 {
    1.0 + 1.0 / teeth as f64
}

/// The velocity of the disc's material point at `point_mm` per unit input speed, mm/rad,
/// for a disc whose centre sits at crank angle `crank_rad` (its own phase included) on a
/// crank of eccentricity `eccentricity_mm`.
pub fn disc_velocity(crank_rad: f64, eccentricity_mm: f64, teeth: usize, point_mm: Vec2) -> Vec2 {
    let (s, c) = crank_rad.sin_cos();
    let centre = Vec2::new(c, s) * eccentricity_mm;
    let centre_velocity = Vec2::new(-s, c) * eccentricity_mm;
    let r = point_mm - centre;
    // ẑ × r = (−r_y, r_x)
    centre_velocity + z_cross(r) * disc_speed_ratio(teeth)
}

/// The disc's sliding speed over a fixed roller at contact point `point_mm`, along the
/// contact's tangent t = ẑ × n (n the unit normal from the disc towards the roller), per unit
/// input speed, mm/rad; signed: positive when the disc's material moves along +t. For the
/// unmodified profile |this| = (|P_i − I| − Rrp)/nc.
pub fn roller_sliding(
    crank_rad: f64,
    eccentricity_mm: f64,
    teeth: usize,
    point_mm: Vec2,
    normal: Vec2,
) -> f64 {
    let v = disc_velocity(crank_rad, eccentricity_mm, teeth, point_mm);
    // v·(ẑ × n) = n × v … written with `cross` (a × b = a_x b_y − a_y b_x): v·t = cross(n, v).
    cross(normal, v)
}

/// The speed at which a hole slides over a fixed output pin, per unit input speed, mm/rad:
/// the hole orbits the pin on a circle of radius e at Ω, without turning relative to it.
pub fn pin_sliding(eccentricity_mm: f64, teeth: usize) -> f64 {
    eccentricity_mm * relative_crank_speed_ratio(teeth)
}

/// Torsion under a locked input: the sliding of the disc over a fixed roller at `point_mm`
/// along t = ẑ × n per unit turn dβ of the disc about its centre `centre_mm`, mm/rad:
/// (ẑ × (C − O_d))·(ẑ × n) = (C − O_d)·n.
pub fn torsion_roller_sliding(centre_mm: Vec2, point_mm: Vec2, normal: Vec2) -> f64 {
    (point_mm - centre_mm).dot(&normal)
}

/// Torsion under a locked input: the sliding of a hole over its pin at the contact point
/// `point_mm` (X) along ẑ × u (u the unit contact direction `direction`) per unit turn dβ of
/// the disc about its centre `centre_mm` (O_d), the flange turning about the axis by
/// dβ + ρ·dβ (ρ = `pin_ratio`), mm/rad. The disc's material at X moves by dβ·ẑ × (X − O_d),
/// the pin's by (1 + ρ)·dβ·ẑ × X; their difference along ẑ × u is −O_d·u − ρ·X·u.
pub fn torsion_pin_sliding(
    centre_mm: Vec2,
    point_mm: Vec2,
    direction: Vec2,
    pin_ratio: f64,
) -> f64 {
    -centre_mm.dot(&direction) - pin_ratio * point_mm.dot(&direction)
}
