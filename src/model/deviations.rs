//! Deviations of the built parts from the drawing (MODEL.md "Part deviations"): one as-built
//! state, given (`reducer.deviations`) or drawn from the tolerances (`cycloid tolerance`).
//! Engine units (mm); every field zero is the nominal reducer.

use super::face::{Face, Misalignment};
use super::modification::Modification;

/// Offset of a part's centre from its nominal place on its circle, mm: `radial_mm` outward,
/// `tangential_mm` a length along the circle, counter-clockwise.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CentreDeviation {
    /// dr, outward along the circle's radius, mm.
    pub radial_mm: f64,
    /// dt, along the circle, counter-clockwise, mm: a length, the angle is dt/R.
    pub tangential_mm: f64,
}

impl CentreDeviation {
    /// Whether the centre is on its nominal place.
    pub fn is_zero(&self) -> bool {
        self.radial_mm == 0.0 && self.tangential_mm == 0.0
    }

    /// How far the centre moves, √(dr² + dt²), mm (dt taken as a length).
    pub fn size_mm(&self) -> f64 {
        self.radial_mm.hypot(self.tangential_mm)
    }

    /// The centre's displacement in the frame of its circle, (x, y) mm, for a part whose
    /// nominal centre is at `radius_mm` on the direction (cos a, sin a) = `unit`: the moved
    /// centre is (R + dr)·(cos(a + dt/R), sin(a + dt/R)), formed so that no term of size R is
    /// subtracted from another (the displacement is micrometres, R tens of millimetres).
    pub fn displacement_mm(&self, radius_mm: f64, unit: (f64, f64)) -> (f64, f64) {
        let turn = self.tangential_mm / radius_mm;
        // (R + dr)·e^{i·turn} − R = dr·e^{i·turn} + R·(e^{i·turn} − 1), with
        // e^{i·turn} − 1 = (−2·sin²(turn/2), sin turn).
        let half = (0.5 * turn).sin();
        let (s, c) = turn.sin_cos();
        let along = self.radial_mm * c - 2.0 * radius_mm * half * half;
        let across = (radius_mm + self.radial_mm) * s;
        let (ux, uy) = unit;
        (along * ux - across * uy, along * uy + across * ux)
    }
}

/// Highest order of a form-error harmonic (`reducer.deviations.form[].order`): 1,000. A wave
/// of order k is about 2π·Rp/k long along the disc, 0.19 mm at order 1,000 on the paper's
/// disc (Rp = 30 mm), already the width of a roller's Hertz contact at its rated load (2b ≈ 0.1
/// mm): a contact flattens a shorter wave, and the model, one contact point per roller on a
/// profile that is the series, does not resolve it (it is roughness, not form). A fit
/// identifies orders up to 200 (`measured_profile.harmonics`). The bound also bounds the work
/// of every order: the profile's table of w (`geometry::form_error`) evaluates the series at
/// each of its nodes, the regularity check samples 64 points per wave of the highest order.
pub const MAX_FORM_ORDER: usize = 1000;

/// One harmonic of a disc's form error (MODEL.md "Measured profiles"): w(t) ∋
/// cos_mm·cos(order·t) + sin_mm·sin(order·t), t the locus parameter, w along the profile's
/// normal (positive: material missing, like a positive ΔRrp).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FormTerm {
    /// The harmonic's order k, of cos(k·t) and sin(k·t).
    pub order: usize,
    /// The coefficient of cos(order·t), mm.
    pub cos_mm: f64,
    /// The coefficient of sin(order·t), mm.
    pub sin_mm: f64,
}

impl FormTerm {
    /// Amplitude sqrt(a² + b²), mm.
    pub fn amplitude_mm(&self) -> f64 {
        self.cos_mm.hypot(self.sin_mm)
    }
}

/// Roller i as built: its centre's offset and its radius's deviation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RollerDeviation {
    /// Its centre's offset from its nominal place, angle 2πi/np on the circle of radius Rp.
    pub centre: CentreDeviation,
    /// Roller radius minus the design's, mm.
    pub radius_mm: f64,
}

impl RollerDeviation {
    /// Whether the roller is as drawn: on its place, of the design's radius.
    pub fn is_zero(&self) -> bool {
        self.centre.is_zero() && self.radius_mm == 0.0
    }
}

/// Every deviation of one reducer as built.
///
/// `rollers`, `pins` and each disc's `holes` are either empty (all nominal) or one entry per
/// part, indexed as the design numbers them (roller i at 2πi/np, pin and hole j at 2πj/M).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Deviations {
    /// de: the crank's eccentricity minus the design's, mm. The disc keeps the profile it was
    /// ground with (the design's e); only its centre's orbit changes.
    pub eccentricity_mm: f64,
    /// The rollers in the housing, `rollers[i]` for roller i.
    pub rollers: Vec<RollerDeviation>,
    /// Output pins on the flange.
    pub pins: Vec<CentreDeviation>,
    /// `holes[k][j]`: pin hole j of disc k (empty: every hole of every disc nominal).
    pub holes: Vec<Vec<CentreDeviation>>,
    /// Grinding error of the shift modification ΔRp, mm (added to the spec's).
    pub shift_mm: f64,
    /// Grinding error of the equidistant modification ΔRrp, mm (added to the spec's).
    pub equidistant_mm: f64,
    /// The disc's form error (every disc alike; empty: none), orders ≥ 2 and not multiples of
    /// the tooth count (those are the modification itself).
    pub form: Vec<FormTerm>,
    /// The disc's tilt against the housing as built (spec: `reducer.deviations.misalignment`,
    /// mrad), added to every scene's own tilt (`Deviations::face`). Not a part off its place:
    /// `is_nominal` does not look at it (a scene's tilt is allowed wherever this is).
    pub misalignment: Misalignment,
}

impl Deviations {
    /// No deviation at all: the nominal reducer, whose symmetries the engine may use.
    pub fn is_nominal(&self) -> bool {
        self.eccentricity_mm == 0.0
            && self.shift_mm == 0.0
            && self.equidistant_mm == 0.0
            && !self.moves_rollers()
            && !self.moves_pins()
            && self.form.is_empty()
    }

    /// The face a scene's contacts see on this reducer as built: the scene's face `scene`
    /// with its tilt plus this tilt, θ = θ_scene + θ_dev for each axis, rad (MODEL.md "Along
    /// the face width": the section at z moves by u(z) = z·(θy, −θx), linear in θ, so two
    /// small tilts add). With no deviation tilt the scene's face itself, bit for bit.
    pub fn face(&self, scene: &Face) -> Face {
        if self.misalignment.is_zero() {
            return *scene;
        }
        Face {
            misalignment: scene.misalignment.plus(&self.misalignment),
            ..*scene
        }
    }

    /// The form error w(t), mm (positive: material missing).
    pub fn form_mm(&self, t: f64) -> f64 {
        self.form
            .iter()
            .map(|f| {
                let (s, c) = (f.order as f64 * t).sin_cos();
                f.cos_mm * c + f.sin_mm * s
            })
            .sum()
    }

    /// The largest |w| the form error can reach, mm: the sum of its amplitudes.
    pub fn form_bound_mm(&self) -> f64 {
        // A fold from +0.0: an empty sum of f64 is −0.0, which prints as "-0.000".
        self.form.iter().fold(0.0, |sum, f| sum + f.amplitude_mm())
    }

    /// Some roller is off its nominal place or size: gaps repeat only after a full crank turn.
    pub fn moves_rollers(&self) -> bool {
        self.rollers.iter().any(|r| !r.is_zero())
    }

    /// Some pin or hole is off its place: the pin pattern repeats only after a full turn of
    /// the disc (nc crank turns).
    pub fn moves_pins(&self) -> bool {
        self.pins.iter().any(|p| !p.is_zero()) || self.holes.iter().flatten().any(|h| !h.is_zero())
    }

    /// Whether the disc is ground off the drawing: a grinding error (`ground`) or a form error.
    pub fn grinds(&self) -> bool {
        self.shift_mm != 0.0 || self.equidistant_mm != 0.0 || !self.form.is_empty()
    }

    /// The modification as ground: the spec's plus the grinding errors.
    pub fn ground(&self, m: &Modification) -> Modification {
        Modification {
            shift_mm: m.shift_mm + self.shift_mm,
            equidistant_mm: m.equidistant_mm + self.equidistant_mm,
            ..*m
        }
    }

    /// Roller i's deviation (zero when none is given).
    pub fn roller(&self, i: usize) -> RollerDeviation {
        self.rollers.get(i).copied().unwrap_or_default()
    }

    /// Pin j's deviation (zero when none is given).
    pub fn pin(&self, j: usize) -> CentreDeviation {
        self.pins.get(j).copied().unwrap_or_default()
    }

    /// Hole j of disc k (zero when none is given).
    pub fn hole(&self, disc: usize, j: usize) -> CentreDeviation {
        self.holes
            .get(disc)
            .and_then(|h| h.get(j))
            .copied()
            .unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::CentreDeviation;

    /// The displacement is the moved centre minus the nominal one, formed without
    /// cancellation: compare with the direct difference at a size (R = 1 mm) where that
    /// difference loses nothing that matters (error ~1e-16 mm next to µm displacements).
    #[test]
    fn displacement_is_the_moved_centre_minus_the_nominal() {
        let a: f64 = 0.7;
        let unit = (a.cos(), a.sin());
        let d = CentreDeviation {
            radial_mm: 2e-3,
            tangential_mm: -5e-3,
        };
        let r = 1.0;
        let moved = (r + d.radial_mm) * (a + d.tangential_mm / r).cos() - r * a.cos();
        let moved_y = (r + d.radial_mm) * (a + d.tangential_mm / r).sin() - r * a.sin();
        let (x, y) = d.displacement_mm(r, unit);
        assert!((x - moved).abs() < 1e-15 && (y - moved_y).abs() < 1e-15);
    }
}
