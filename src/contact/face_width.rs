//! One contact along the face width (MODEL.md "Along the face width"): the force and stiffness
//! of a roller's (or pin's) line contact whose approach varies along z, and its line load.
//!
//! At z (mm from the middle of the face, |z| ≤ B/2) the contact's approach is
//!   a(z) = d − crown(z) + t·z,
//! d the 2-D approach (−gap, mm), crown(z) ≥ 0 the material removed (`model::face::Crowning`) and
//! t the tilt's slope (rad, `FaceWidth::approach_slope`). The face is a Winkler bed: no
//! coupling between its sections, each carrying the contact law per unit length.
//!
//! - The paper's linear law, straight or circularly crowned: the closed form
//!   F = (k/B)·∫ max(0, a(z)) dz over [−B/2, B/2], ∂F/∂d = (k/B)·(loaded length),
//!   k = (π/4)·E*·B (paper Eq. 9). a(z) is linear over the flat middle and a concave parabola
//!   over each crowned end, concave over the whole face: its positive part is one interval
//!   [p, q] whose ends are roots of a linear or quadratic (`loaded`), and
//!   ∫ a dz over [p, q] = (q − p)·(d + t·(p + q)/2) − ∫ crown dz, the crown's integral
//!   sign(z)·c·(|z| − z0)₊³/3 (`integral`).
//! - Otherwise (Johnson's law, or the logarithmic crown): n slices of width B/n at their centres
//!   z_s = −B/2 + (s + ½)·B/n, each the law with length B/n at its approach a(z_s).
//!
//! The line load of slice s is its force/(B/n), N/mm, whatever the law: with the closed form
//! the slice's force is (k/B)·∫ max(0, a(z)) dz over the slice (its mean line load), so the
//! slices' line loads times B/n sum to the contact's force and the largest is at least the mean
//! F/B. Units: mm, N, N/mm.

use super::law::{self, ContactForce, LineContact};
use crate::model::face::{Crowning, Face};
use crate::model::ContactLaw;
use std::f64::consts::PI;

/// Centre of slice s of a face of width B = `width_mm` cut into n = `slices`, mm from the
/// middle of the face: z_s = −B/2 + (s + ½)·B/n. The one formula the slices' forces are
/// evaluated at and the review draws their line loads at.
pub fn slice_centre_mm(width_mm: f64, slices: usize, s: usize) -> f64 {
    let h = width_mm / slices as f64;
    -0.5 * width_mm + (s as f64 + 0.5) * h
}

/// The face of one kind of contact (the rollers', the pins'), ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceWidth {
    width_mm: f64,
    slices: usize,
    crown: Crown,
    /// The largest closing a tilt can add to the 2-D approach anywhere on the face, mm:
    /// max over z of |θ|·|z| − crown(z) (|t| ≤ |θ| for every contact; `reach`).
    pub reach_mm: f64,
    /// The tilt (θy, −θx), rad.
    slope: (f64, f64),
    /// Sum the slices even where the closed form holds (`by_slices`).
    by_slices: bool,
    /// The closed form's pieces: the flat middle |z| ≤ z0 (`flat_mm`, z0 clamped to B/2) and
    /// the crowned ends, where a = d ± t·z − c·(|z| − z0)² (`curvature` c = 1/(2·Rc), 1/mm;
    /// 0 without a circular crown).
    flat_mm: f64,
    curvature: f64,
    /// The crown's depth at the face's ends, c·(B/2 − z0)², mm.
    end_drop_mm: f64,
    /// ∫ crown dz over the face, 2·c·(B/2 − z0)³/3, mm².
    crown_area_mm2: f64,
    /// The circular crown's mean depth over each slice, (∫ crown dz over it)/(B/n), mm (0
    /// without a circular crown): a slice loaded whole carries the mean of a over it,
    /// d + t·z_s − this, without the crown's integral at its edges each time.
    slice_crown_mm: Vec<f64>,
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
    /// E* (MPa; for the logarithmic crown's A, E' = 2·E*).
    pub fn new(face: &Face, width_mm: f64, contact_modulus_mpa: f64) -> Self {
        let half = 0.5 * width_mm;
        let crown = match face.crowning {
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
        let (curvature, flat_mm) = match crown {
            Crown::Circular {
                curvature,
                start_mm,
            } => (curvature, start_mm.min(half)),
            _ => (0.0, half),
        };
        let mut f = FaceWidth {
            width_mm,
            slices: face.slices.max(1),
            crown,
            reach_mm: 0.0,
            slope: (ux, uy),
            by_slices: false,
            flat_mm,
            curvature,
            end_drop_mm: curvature * (half - flat_mm).powi(2),
            crown_area_mm2: 2.0 * curvature * (half - flat_mm).powi(3) / 3.0,
            slice_crown_mm: Vec::new(),
        };
        f.reach_mm = f.reach(ux.hypot(uy));
        let h = width_mm / f.slices as f64;
        f.slice_crown_mm = (0..f.slices)
            .map(|s| {
                (f.crown_integral(f.slice_edge_mm(s + 1)) - f.crown_integral(f.slice_edge_mm(s)))
                    / h
            })
            .collect();
        f
    }

    /// The largest of θ·z − crown(z) over 0 ≤ z ≤ B/2 (θ ≥ 0, mm): with a circular crown,
    /// θ·z* − c·(z* − z0)² at z* = min(z0 + θ/(2c), B/2), where its slope θ − 2c·(z − z0)
    /// vanishes or the face ends; otherwise θ·B/2 (the crown ≥ 0 only lowers it).
    fn reach(&self, theta: f64) -> f64 {
        let half = 0.5 * self.width_mm;
        if self.curvature == 0.0 {
            return theta * half;
        }
        let z = (self.flat_mm + theta / (2.0 * self.curvature)).min(half);
        theta * z - self.curvature * (z - self.flat_mm).powi(2)
    }

    /// How far beyond its 2-D approach d a contact with slope t (rad) along the face must close
    /// before it carries force, mm: the largest t·z − crown(z) where the force is read. The
    /// closed form integrates over the whole face (`reach` of |t|: the crown is symmetric);
    /// summed slices read the law at their centres. The contact carries force exactly when
    /// d + this > 0, so a gap less this is the gap to its first touch (the zero-torque pose).
    pub fn closing_mm(&self, law: ContactLaw, t: f64) -> f64 {
        if self.closed_form(law) {
            return self.reach(t.abs());
        }
        (0..self.slices)
            .map(|s| {
                let z = self.slice_centre_mm(s);
                t * z - self.crown_mm(z)
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// This face summed over its slices whatever the law: the Winkler model of n slices the
    /// closed form is the limit of (n → ∞), to check it against and to time it.
    pub fn by_slices(mut self) -> Self {
        self.by_slices = true;
        self
    }

    /// The tilt's slope t of a contact's approach along z, rad, for a contact whose force on the
    /// disc is along the unit vector f (`force_direction`): t = −f·(θy, −θx). The section at z
    /// moves by u(z) = z·(θy, −θx) (`Misalignment::slope`), which closes a contact pushing the
    /// disc along f by −f·u(z), so its approach there is d + t·z. For a roller f = −n_i (n_i
    /// from the disc towards roller i): t = n_i·(θy, −θx); for a pin, f its push on the disc.
    /// The one place rollers and pins take t from.
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

    /// Centre of slice s, mm from the middle of the face (`slice_centre_mm`).
    fn slice_centre_mm(&self, s: usize) -> f64 {
        slice_centre_mm(self.width_mm, self.slices, s)
    }

    /// Edge s of the slices (s = 0..=n), mm from the middle of the face: −B/2 + s·B/n, the
    /// last exactly B/2.
    fn slice_edge_mm(&self, s: usize) -> f64 {
        let half = 0.5 * self.width_mm;
        if s == self.slices {
            half
        } else {
            -half + s as f64 * (self.width_mm / self.slices as f64)
        }
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
        // The most the tilt closes a section, at the end it closes.
        let reach = t.abs() * 0.5 * self.width_mm;
        if d + reach <= 0.0 {
            // The crown only opens: no section reaches.
            return ContactForce::NONE;
        }
        if self.closed_form(law) {
            let per_mm = law::paper_linear_stiffness(c) / self.width_mm;
            if d - self.end_drop_mm - reach > 0.0 {
                // Positive at both ends, so everywhere (a is concave): ∫ a dz = d·B − ∫ crown dz
                // (t·z integrates to 0 over the face).
                return ContactForce {
                    force_n: per_mm * (d * self.width_mm - self.crown_area_mm2),
                    stiffness_n_per_mm: per_mm * self.width_mm,
                };
            }
            if self.curvature == 0.0 {
                // Straight, |d| < |t|·B/2: a = d + t·z is positive over L = B/2 + d/|t| from
                // the end it closes at, rising to |t|·L there: ∫ a dz = |t|·L²/2.
                let length = 0.5 * self.width_mm + d / t.abs();
                return ContactForce {
                    force_n: per_mm * 0.5 * t.abs() * length * length,
                    stiffness_n_per_mm: per_mm * length,
                };
            }
            let Some((p, q)) = self.loaded(d, t) else {
                return ContactForce::NONE;
            };
            return ContactForce {
                force_n: per_mm * self.integral(d, t, p, q),
                stiffness_n_per_mm: per_mm * (q - p),
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

    /// The line load of each slice (N/mm), its force/(B/n), of the contact at approach d with
    /// slope t, into `out` (`slices` entries), and the largest of them. With the closed form
    /// the slice's force is the face's integral over the slice, (k/B)·∫ max(0, a) dz over
    /// [z_s − B/2n, z_s + B/2n], so the line loads times B/n sum to `force` (to round-off);
    /// summed slices: the law with length B/n at the slice centre's approach.
    pub fn line_loads(
        &self,
        law: ContactLaw,
        c: &LineContact,
        d: f64,
        t: f64,
        out: &mut [f64],
    ) -> f64 {
        let out = &mut out[..self.slices];
        let mut peak = 0.0_f64;
        // Slice s's line load q_s.
        let mut f = |s: usize, q: f64| {
            out[s] = q;
            peak = peak.max(q);
        };
        let n = self.slices;
        let h = self.width_mm / n as f64;
        let per_mm = law::paper_linear_stiffness(c) / self.width_mm;
        if self.closed_form(law) {
            let Some((p, q)) = self.loaded(d, t) else {
                (0..n).for_each(|s| f(s, 0.0));
                return peak;
            };
            let half = 0.5 * self.width_mm;
            // The slices that meet (p, q): those holding p and q carry
            // (∫ a dz over their loaded part)·(k/B)/h; those between, loaded whole, the mean
            // of a over the slice, d + t·z_s − (the crown's mean depth over it).
            let first = (((p + half) / h) as usize).min(n - 1);
            let last = ((((q + half) / h) as usize) + 1).clamp(first + 1, n);
            (0..first).for_each(|s| f(s, 0.0));
            let end = |s: usize| {
                let (lo, hi) = (self.slice_edge_mm(s), self.slice_edge_mm(s + 1));
                (per_mm / h * self.integral(d, t, lo.max(p), hi.min(q))).max(0.0)
            };
            f(first, end(first));
            if last > first + 1 {
                let whole = first + 1..last - 1;
                for (s, crown) in whole.clone().zip(&self.slice_crown_mm[whole]) {
                    let z = self.slice_centre_mm(s);
                    f(s, (per_mm * (d + t * z - crown)).max(0.0));
                }
                f(last - 1, end(last - 1));
            }
            (last..n).for_each(|s| f(s, 0.0));
            return peak;
        }
        let slice = self.slice_contact(c);
        for s in 0..n {
            let z = self.slice_centre_mm(s);
            let a = d - self.crown_mm(z) + t * z;
            f(
                s,
                match law {
                    ContactLaw::PaperLinear => per_mm * a.max(0.0),
                    ContactLaw::HertzNonlinear => {
                        law::force(law, &slice, a).force_n / slice.length_mm
                    }
                },
            );
        }
        peak
    }

    /// The contact of one slice: length B/n.
    fn slice_contact(&self, c: &LineContact) -> LineContact {
        LineContact {
            length_mm: c.length_mm / self.slices as f64,
            ..*c
        }
    }

    /// The approach at z on a straight or circularly crowned face, a(z) = d + t·z − crown(z),
    /// mm: concave (crown is convex), linear over the flat middle |z| ≤ z0 and a parabola over
    /// each crowned end.
    #[inline]
    fn approach(&self, d: f64, t: f64, z: f64) -> f64 {
        let w = (z.abs() - self.flat_mm).max(0.0);
        d + t * z - self.curvature * w * w
    }

    /// ∫ crown dz from 0 to z, mm²: sign(z)·c·(|z| − z0)₊³/3.
    #[inline]
    fn crown_integral(&self, z: f64) -> f64 {
        let w = (z.abs() - self.flat_mm).max(0.0);
        (self.curvature * w * w * w / 3.0).copysign(z)
    }

    /// ∫ a dz over [lo, hi] where a > 0 throughout (a part of `loaded`), mm²:
    /// (hi − lo)·(d + t·(lo + hi)/2) − (∫ crown from lo to hi), never below 0 (round-off).
    #[inline]
    fn integral(&self, d: f64, t: f64, lo: f64, hi: f64) -> f64 {
        let linear = (hi - lo) * (d + 0.5 * t * (lo + hi));
        (linear - (self.crown_integral(hi) - self.crown_integral(lo))).max(0.0)
    }

    /// The loaded interval [p, q] of the face, where a(z) > 0 (one interval: a is concave),
    /// mm; `None` where a ≤ 0 everywhere. For the straight or circularly crowned face.
    #[inline(always)]
    fn loaded(&self, d: f64, t: f64) -> Option<(f64, f64)> {
        let half = 0.5 * self.width_mm;
        // Where a peaks: a' = t − crown'(z), crown'(z) = ±2c·(|z| − z0) over the ends.
        let peak = if t == 0.0 {
            0.0
        } else if self.curvature > 0.0 {
            (t.signum() * self.flat_mm + t / (2.0 * self.curvature)).clamp(-half, half)
        } else {
            t.signum() * half
        };
        if self.approach(d, t, peak) <= 0.0 {
            return None;
        }
        // The left root is the right root of the face mirrored, a(−z) with slope −t.
        Some((
            -self.root_beyond(d, -t, -peak),
            self.root_beyond(d, t, peak),
        ))
    }

    /// The end of the loaded interval on the +z side of `from` (where a > 0): B/2 if a > 0
    /// there, else the root of a in (from, B/2), in the first piece whose far end is not
    /// loaded: the −z crowned end (a = A + t·w − c·w² in w = −z − z0 ≥ 0, A = d − t·z0, the
    /// smaller root in w: z grows as w shrinks), the flat middle (a linear) or the +z crowned
    /// end (a = A + t·w − c·w², w = z − z0, A = d + t·z0, the larger root). Roots of
    /// c·w² − b·w − A in the stable form.
    #[inline(always)]
    fn root_beyond(&self, d: f64, t: f64, from: f64) -> f64 {
        let half = 0.5 * self.width_mm;
        let (z0, c) = (self.flat_mm, self.curvature);
        if self.approach(d, t, half) > 0.0 {
            return half;
        }
        let root = if from < -z0 && d - t * z0 <= 0.0 {
            // a(from) > 0 ≥ a(−z0): the root is on the −z crowned end, where b = −t.
            let (a, b) = (d - t * z0, -t);
            let disc = (b * b + 4.0 * c * a).max(0.0).sqrt();
            let w = if b <= 0.0 {
                (b - disc) / (2.0 * c)
            } else {
                -2.0 * a / (b + disc)
            };
            -z0 - w
        } else if from < z0 && d + t * z0 <= 0.0 {
            // a > 0 before the flat middle's +z end, ≤ 0 there, on a line: t < 0.
            -d / t
        } else {
            let (a, b) = (d + t * z0, t);
            let disc = (b * b + 4.0 * c * a).max(0.0).sqrt();
            let w = if b >= 0.0 {
                (b + disc) / (2.0 * c)
            } else {
                2.0 * a / (disc - b)
            };
            z0 + w
        };
        root.clamp(from, half)
    }
}
