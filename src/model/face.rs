//! The contact along the face width (MODEL.md "Along the face width"): the disc's crowning, its
//! tilt against the housing, and how many slices the face is cut into.
//!
//! z is measured along the axis from the middle of the face, mm, z ∈ [−B/2, B/2].

/// Crowning of the disc's flanks along the face width (spec: `modification.crowning`): material
/// removed at z, mm, the same at every point of the profile.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Crowning {
    /// A straight (cylindrical) disc: today's 2-D model.
    #[default]
    None,
    /// Circular crowning of radius Rc, flat over |z| ≤ z0:
    /// crown(z) = (|z| − z0)²/(2·Rc) for |z| > z0 (MODEL.md "Along the face width"; the
    /// parabola of the circle, exact to (|z| − z0)⁴/Rc³).
    Circular {
        /// Rc, mm.
        radius_mm: f64,
        /// z0, the half-length of the flat middle, mm.
        start_mm: f64,
    },
    /// Lundberg's logarithmic profile in the form of Johns & Gohar as generalised by Fujiwara &
    /// Kawase (NTN Technical Review 75, 2007, Eq. 3; Proc. IMechE J 220, 2006), with a flat
    /// middle: with a = B/2 and the crowned length K2·a at each end,
    ///   crown(z) = A·ln(1 / (1 − (1 − e^{−z_m/A})·((|z| − (1 − K2)·a)/(K2·a))²))
    /// for |z| > (1 − K2)·a, 0 inside; A = 2·K1·Q/(π·B·E'), E' = 2·E* (Johns & Gohar's
    /// E', 2/E' = (1−ν1²)/E1 + (1−ν2²)/E2). The drop at the face's ends is z_m, and K2 = 1, z_m →
    /// ∞ gives Johns & Gohar's A·ln(1/(1 − (2z/B)²)). Q is the load the profile is designed for,
    /// N; K1 a load coefficient (1: Lundberg's). Checked against the formula worked by hand
    /// (tests/it/face_width.rs, `the_logarithmic_crown_is_fujiwara_and_kawases_profile_by_hand`).
    Logarithmic {
        /// Q, N.
        design_load_n: f64,
        /// z_m, the drop at the face's ends, mm.
        end_drop_mm: f64,
        /// K1.
        load_coefficient: f64,
        /// K2, the crowned share of each half of the face, (0, 1].
        crowned_fraction: f64,
    },
}

impl Crowning {
    /// A straight disc.
    pub fn is_none(&self) -> bool {
        matches!(self, Crowning::None)
    }
}

/// A small tilt of the disc against the housing, rad (spec: `scenes[].misalignment`, in mrad):
/// θx about the fixed frame's x axis, θy about its y axis (right-hand rule). The disc's section
/// at z is displaced in its plane by u(z) = z·(θy, −θx) (MODEL.md "Along the face width").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Misalignment {
    /// θx, about the fixed x axis, rad.
    pub about_x_rad: f64,
    /// θy, about the fixed y axis, rad.
    pub about_y_rad: f64,
}

impl Misalignment {
    /// No tilt.
    pub fn is_zero(&self) -> bool {
        self.about_x_rad == 0.0 && self.about_y_rad == 0.0
    }

    /// This tilt followed by `other`: θx and θy add, rad. Exact to first order in θ (small
    /// rotations commute and add; the neglected term is of order θ², 1e-6 at 1 mrad), the
    /// order to which the model's u(z) = z·(θy, −θx) holds at all.
    pub fn plus(&self, other: &Misalignment) -> Misalignment {
        Misalignment {
            about_x_rad: self.about_x_rad + other.about_x_rad,
            about_y_rad: self.about_y_rad + other.about_y_rad,
        }
    }

    /// The in-plane displacement of the section at z per unit z, (θy, −θx), rad.
    pub fn slope(&self) -> (f64, f64) {
        (self.about_y_rad, -self.about_x_rad)
    }
}

/// The face of a scene's contacts: the disc's crowning (the design's, `modification.crowning`),
/// the scene's tilt and its slices (`scenes[].face_slices`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Face {
    /// The disc's crowning.
    pub crowning: Crowning,
    /// The scene's tilt of the disc against the housing.
    pub misalignment: Misalignment,
    /// Slices the face width is cut into (≥ 1; 1 with no crowning and no tilt is the 2-D model).
    pub slices: usize,
}

impl Default for Face {
    fn default() -> Self {
        Face {
            crowning: Crowning::None,
            misalignment: Misalignment::default(),
            slices: 1,
        }
    }
}

impl Face {
    /// Straight and aligned: every slice carries the same line load, F/B (whatever `slices`).
    pub fn is_uniform(&self) -> bool {
        self.crowning.is_none() && self.misalignment.is_zero()
    }

    /// Whether the line load along the face is resolved (reported per slice): more than one
    /// slice, or a crown or tilt.
    pub fn is_resolved(&self) -> bool {
        self.slices > 1 || !self.is_uniform()
    }
}
