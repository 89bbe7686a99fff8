//! One contact along the face width (MODEL.md "Along the face width"): the force and stiffness
//! of a roller's (or pin's) line contact whose approach varies along z, and its line load.
//!
//! At z (mm from the middle of the face, |z| ≤ B/2) the contact's approach is
//!   a(z) = d − crown(z) + t·z,
//! d the 2-D approach (−gap, mm), crown(z) ≥ 0 the material removed (`model::face::Crowning`) and
//! t the tilt's slope (rad, `Misalignment::approach_slope`). The face is a Winkler bed: no
//! coupling between its sections, each carrying the contact law per unit length.
//!
//! - The paper's linear law, straight or circularly crowned: the closed form
//!   F = (k/B)·∫ max(0, a(z)) dz over [−B/2, B/2], ∂F/∂d = (k/B)·(loaded length),
//!   k = (π/4)·E*·B (paper Eq. 9). a(z) is linear over the flat middle and a concave parabola
//!   over each crowned end, so its positive part on each piece is one interval whose ends are
//!   the roots of a linear or quadratic, and the integral a polynomial's.
//! - Otherwise (Johnson's law, or the logarithmic crown): n slices of width B/n at their centres
//!   z_s = −B/2 + (s + ½)·B/n, each the law with length B/n at its approach a(z_s).
//!
//! The line load at z is the force per unit length there, N/mm: (k/B)·max(0, a(z)) for the
//! linear law, a slice's force/(B/n) otherwise. Units: mm, N, N/mm.

use super::law::{self, ContactForce, LineContact};
use crate::model::face::{Crowning, Face};
use crate::model::ContactLaw;
use std::f64::consts::PI;

/// The face of one kind of contact (the rollers', the pins'), ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceWidth {
    width_mm: f64,
    slices: usize,
    crown: Crown,
    /// The largest closing a tilt can add to the 2-D approach anywhere on the face,
    /// |θ|·B/2, mm (|t| ≤ |θ| for every contact; the crown only opens).
    pub reach_mm: f64,
    /// The tilt (θy, −θx), rad.
    slope: (f64, f64),
    /// Sum the slices even where the closed form holds (`by_slices`).
    by_slices: bool,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Crown {
    None,
    Circular {
        /// 1/(2·Rc), 1/mm.
        curvature: f64,
        start_mm: f64,
    },
    Logarithmic {
        /// A = 2·K1·Q/(π·B·E'), mm.
        scale_mm: f64,
        /// 1 − e^{−z_m/A}.
        depth: f64,
        /// (1 − K2)·B/2, mm.
        start_mm: f64,
        /// K2·B/2, mm.
        length_mm: f64,
    },
}

impl FaceWidth {
    /// The face `face` of contacts of width B = `width_mm` between bodies of contact modulus
    /// E* (MPa; for the logarithmic crown's A, E' = 2·E*). `crowned`: the disc's crown applies
    /// (the rollers; the pins' holes are not crowned).
    pub fn new(face: &Face, width_mm: f64, contact_modulus_mpa: f64, crowned: bool) -> Self {
        let half = 0.5 * width_mm;
        let crown = match face.crowning {
            _ if !crowned => Crown::None,
            Crowning::None => Crown::None,
            Crowning::Circular {
                radius_mm,
                start_mm,
            } => Crown::Circular {
                curvature: 0.5 / radius_mm,
                start_mm,
            },
            Crowning::Logarithmic {
                design_load_n,
                end_drop_mm,
                load_coefficient,
                crowned_fraction,
            } => {
                let e_prime = 2.0 * contact_modulus_mpa;
                let scale_mm = 2.0 * load_coefficient * design_load_n / (PI * width_mm * e_prime);
                Crown::Logarithmic {
                    scale_mm,
                    depth: -(-end_drop_mm / scale_mm).exp_m1(),
                    start_mm: (1.0 - crowned_fraction) * half,
                    length_mm: crowned_fraction * half,
                }
            }
        };
        let (ux, uy) = face.misalignment.slope();
        FaceWidth {
            width_mm,
            slices: face.slices.max(1),
            crown,
            reach_mm: ux.hypot(uy) * half,
            slope: (ux, uy),
            by_slices: false,
        }
    }

    /// This face summed over its slices whatever the law: the Winkler model of n slices the
    /// closed form is the limit of (n → ∞), to check it against and to time it.
    pub fn by_slices(mut self) -> Self {
        self.by_slices = true;
        self
    }

    /// Whether every section of the face sees the same approach (no crown, no tilt).
    pub fn is_uniform(&self) -> bool {
        self.crown == Crown::None && self.slope == (0.0, 0.0)
    }

    pub fn slices(&self) -> usize {
        self.slices
    }

    /// The slope t of a contact's approach along z, rad, for a contact whose force on the disc
    /// is along the unit vector `force_direction`: t = −f·(θy, −θx) (`Misalignment`).
    #[inline]
    pub fn approach_slope(&self, force_direction: (f64, f64)) -> f64 {
        -(force_direction.0 * self.slope.0 + force_direction.1 * self.slope.1)
    }

    /// Material removed by the crown at z, mm (0 over the flat middle).
    pub fn crown_mm(&self, z: f64) -> f64 {
        let z = z.abs();
        match self.crown {
            Crown::None => 0.0,
            Crown::Circular {
                curvature,
                start_mm,
            } => {
                let w = (z - start_mm).max(0.0);
                curvature * w * w
            }
            Crown::Logarithmic {
                scale_mm,
                depth,
                start_mm,
                length_mm,
            } => {
                let r = ((z - start_mm).max(0.0) / length_mm).min(1.0);
                -scale_mm * (-depth * r * r).ln_1p()
            }
        }
    }

    /// Centre of slice s, mm from the middle of the face.
    pub fn slice_centre_mm(&self, s: usize) -> f64 {
        let h = self.width_mm / self.slices as f64;
        -0.5 * self.width_mm + (s as f64 + 0.5) * h
    }

    /// Whether the closed form holds: the linear law over a straight or circularly crowned face.
    fn closed_form(&self, law: ContactLaw) -> bool {
        law == ContactLaw::PaperLinear
            && !self.by_slices
            && !matches!(self.crown, Crown::Logarithmic { .. })
    }

    /// Force and stiffness ∂F/∂d of the contact `c` (its length B) at 2-D approach d (mm)
    /// with slope t (rad) along the face.
    pub fn force(&self, law: ContactLaw, c: &LineContact, d: f64, t: f64) -> ContactForce {
        if d + t.abs() * 0.5 * self.width_mm <= 0.0 {
            // The crown only opens: no section reaches.
            return ContactForce::NONE;
        }
        if self.closed_form(law) {
            let per_mm = law::paper_linear_stiffness(c) / self.width_mm;
            let (integral, length) = self.linear_integral(d, t);
            return ContactForce {
                force_n: per_mm * integral,
                stiffness_n_per_mm: per_mm * length,
            };
        }
        let slice = self.slice_contact(c);
        let mut total = ContactForce::NONE;
        for s in 0..self.slices {
            let z = self.slice_centre_mm(s);
            let f = law::force(law, &slice, d - self.crown_mm(z) + t * z);
            total.force_n += f.force_n;
            total.stiffness_n_per_mm += f.stiffness_n_per_mm;
        }
        total
    }

    /// Line load at each slice centre (N/mm) of the contact at approach d with slope t, into
    /// `out` (`slices` entries).
    pub fn line_loads(&self, law: ContactLaw, c: &LineContact, d: f64, t: f64, out: &mut [f64]) {
        let slice = self.slice_contact(c);
        let per_mm = law::paper_linear_stiffness(c) / self.width_mm;
        for (s, q) in out.iter_mut().enumerate().take(self.slices) {
            let z = self.slice_centre_mm(s);
            let a = d - self.crown_mm(z) + t * z;
            *q = match law {
                ContactLaw::PaperLinear => per_mm * a.max(0.0),
                ContactLaw::HertzNonlinear => law::force(law, &slice, a).force_n / slice.length_mm,
            };
        }
    }

    /// The largest line load at the slice centres (N/mm), as `line_loads` gives them, without
    /// storing them.
    pub fn peak_line_load(&self, law: ContactLaw, c: &LineContact, d: f64, t: f64) -> f64 {
        let slice = self.slice_contact(c);
        let per_mm = law::paper_linear_stiffness(c) / self.width_mm;
        let approach = |s: usize| {
            let z = self.slice_centre_mm(s);
            d - self.crown_mm(z) + t * z
        };
        let deepest = (0..self.slices)
            .map(approach)
            .fold(f64::NEG_INFINITY, f64::max);
        // Every law's line load grows with the approach: the deepest slice carries the peak.
        match law {
            ContactLaw::PaperLinear => per_mm * deepest.max(0.0),
            ContactLaw::HertzNonlinear => {
                law::force(law, &slice, deepest).force_n / slice.length_mm
            }
        }
    }

    /// The contact of one slice: length B/n.
    fn slice_contact(&self, c: &LineContact) -> LineContact {
        LineContact {
            length_mm: c.length_mm / self.slices as f64,
            ..*c
        }
    }

    /// ∫ max(0, a(z)) dz over the face (mm²) and the length where a > 0 (mm), for the
    /// straight or circularly crowned face.
    fn linear_integral(&self, d: f64, t: f64) -> (f64, f64) {
        let half = 0.5 * self.width_mm;
        let (curvature, start) = match self.crown {
            Crown::Circular {
                curvature,
                start_mm,
            } => (curvature, start_mm.min(half)),
            _ => (0.0, half),
        };
        // Flat middle: a = d + t·z over [−z0, z0].
        let (mut integral, mut length) = clipped_quadratic(d, t, 0.0, -start, start);
        if start < half {
            // Crowned ends, in w = |z| − z0 ∈ [0, B/2 − z0]: a = (d ± t·z0) ± t·w − w²/(2Rc).
            for sign in [1.0, -1.0] {
                let (i, l) =
                    clipped_quadratic(d + sign * t * start, sign * t, curvature, 0.0, half - start);
                integral += i;
                length += l;
            }
        }
        (integral, length)
    }
}

/// ∫ max(0, h) over [lo, hi] and the length where h > 0, for h(w) = a + b·w − c·w², c ≥ 0
/// (concave: its positive part is one interval, between the roots of h).
fn clipped_quadratic(a: f64, b: f64, c: f64, lo: f64, hi: f64) -> (f64, f64) {
    if hi <= lo {
        return (0.0, 0.0);
    }
    let (p, q) = if c == 0.0 {
        if b == 0.0 {
            if a > 0.0 {
                (lo, hi)
            } else {
                return (0.0, 0.0);
            }
        } else {
            let root = -a / b;
            if b > 0.0 {
                (root.max(lo), hi)
            } else {
                (lo, root.min(hi))
            }
        }
    } else {
        // c·w² − b·w − a = 0, the stable form of the roots.
        let disc = b * b + 4.0 * a * c;
        if disc <= 0.0 {
            return (0.0, 0.0);
        }
        let root = disc.sqrt();
        let qq = 0.5 * (b + b.signum() * root);
        let (r1, r2) = if qq == 0.0 {
            (-root / (2.0 * c), root / (2.0 * c))
        } else {
            let (x, y) = (qq / c, -a / qq);
            (x.min(y), x.max(y))
        };
        (r1.max(lo), r2.min(hi))
    };
    if q <= p {
        return (0.0, 0.0);
    }
    let mean = a + 0.5 * b * (p + q) - c * (p * p + p * q + q * q) / 3.0;
    ((q - p) * mean.max(0.0), q - p)
}

#[cfg(test)]
mod tests {
    use super::clipped_quadratic;

    /// The clipped integral against a fine midpoint sum, for a parabola crossing zero inside
    /// the interval on both sides, one side, and a straight line.
    #[test]
    fn clipped_integral_matches_a_fine_sum() {
        for &(a, b, c, lo, hi) in &[
            (1.0, 0.5, 2.0, -2.0, 2.0),
            (0.2, -1.0, 0.0, -1.0, 1.0),
            (-0.1, 0.3, 0.05, 0.0, 3.0),
            (0.5, 0.0, 0.0, -1.0, 1.0),
        ] {
            let n = 200_000;
            let h = (hi - lo) / n as f64;
            let (mut sum, mut len) = (0.0, 0.0);
            for k in 0..n {
                let w = lo + (k as f64 + 0.5) * h;
                let v: f64 = a + b * w - c * w * w;
                if v > 0.0 {
                    sum += v * h;
                    len += h;
                }
            }
            let (i, l) = clipped_quadratic(a, b, c, lo, hi);
            // Midpoint rule: O(h²) on the smooth part, O(h) at the clip's corner.
            assert!((i - sum).abs() < 1e-6, "{i} {sum}");
            assert!((l - len).abs() < 2.0 * h, "{l} {len}");
        }
    }
}
