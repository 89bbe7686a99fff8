//! The tooth-profile modification of a design (MODEL.md "Profile"): shift, equidistant and
//! rotation.

/// Tooth-profile modification (MODEL.md "Profile").
/// `shift_mm` = ΔRp (+ thicker teeth), `equidistant_mm` = ΔRrp (+ thinner teeth),
/// `rotation_rad` = Δδ, the profile turned counter-clockwise about the disc centre.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Modification {
    /// ΔRp, the shift modification, mm: + thicker teeth (interference), − thinner.
    pub shift_mm: f64,
    /// ΔRrp, the equidistant modification, mm: + thinner teeth, − thicker.
    pub equidistant_mm: f64,
    /// Δδ, the rotation modification, rad: the profile turned counter-clockwise about the disc
    /// centre (spec: `rotation_deg`).
    pub rotation_rad: f64,
}

impl Modification {
    /// The profile rotation Δδ reduced to the tooth pitch, into (−π/nc, π/nc]: the profile has
    /// nc-fold symmetry (R(−2π/nc)·C(t) = C(t − 2π/nc), MODEL.md "Profile"), so a rotation by
    /// a whole number of pitches is the same disc. Reduced, a rotation is never more than half
    /// a pitch from the unrotated profile, which the closest-point search can follow.
    pub fn rotation_within_pitch(&self, teeth: usize) -> f64 {
        let pitch = std::f64::consts::TAU / teeth as f64;
        let turns = (self.rotation_rad / pitch).round();
        if turns == 0.0 {
            self.rotation_rad
        } else {
            self.rotation_rad - turns * pitch
        }
    }

    /// Normal gap at tooth tip and root, ΔRrp − ΔRp (paper Eq. 8's left side).
    pub fn tip_clearance_mm(&self) -> f64 {
        self.equidistant_mm - self.shift_mm
    }
}
