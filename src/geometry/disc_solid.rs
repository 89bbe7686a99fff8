//! The disc as a solid: its profile as cubic B-spline pieces within a tolerance of the exact
//! curve, its output-pin holes and its bore, extruded over the face width (what `profile
//! --step` writes and `--stl` meshes).

use super::profile::Profile;
use super::{unit, Vec2};
use crate::model::{Design, OutputPins};
use std::f64::consts::TAU;

/// One cubic Bézier piece of the profile over t in [t0, t1]: the Hermite cubic through Γ(t0)
/// and Γ(t1) with the tangents Γ'(t0) and Γ'(t1) (control points P0, P0 + hΓ'(t0)/3,
/// P3 − hΓ'(t1)/3, P3, h = t1 − t0). Neighbouring pieces share their end point and tangent, so
/// the run of pieces is a C¹ cubic B-spline in t with triple interior knots. Disc frame, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bezier {
    /// The profile parameter at the piece's ends, rad.
    pub t: [f64; 2],
    /// Control points, mm.
    pub control: [Vec2; 4],
}

impl Bezier {
    fn hermite(profile: &Profile, t0: f64, t1: f64) -> Self {
        let h = t1 - t0;
        let (p0, p3) = (profile.point(t0), profile.point(t1));
        let (d0, d3) = (profile.tangent(t0), profile.tangent(t1));
        Bezier {
            t: [t0, t1],
            control: [p0, p0 + d0 * (h / 3.0), p3 - d3 * (h / 3.0), p3],
        }
    }

    /// The point at u in [0, 1] (de Casteljau's Bernstein form), mm.
    pub fn at(&self, u: f64) -> Vec2 {
        let v = 1.0 - u;
        let [a, b, c, d] = self.control;
        a * (v * v * v) + b * (3.0 * v * v * u) + c * (3.0 * v * u * u) + d * (u * u * u)
    }

    /// Largest distance |B(u) − Γ(t0 + u·h)| over 15 interior samples. It bounds the distance
    /// of each point of either curve from the other (each has a point of the other that far).
    fn sampled_error(&self, profile: &Profile) -> f64 {
        let h = self.t[1] - self.t[0];
        (1..16)
            .map(|i| {
                let u = i as f64 / 16.0;
                (self.at(u) - profile.point(self.t[0] + u * h)).norm()
            })
            .fold(0.0, f64::max)
    }
}

/// A circle of the disc's face (a pin hole, the bore), disc frame, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    pub centre: Vec2,
    pub radius_mm: f64,
}

/// The output-pin holes of a disc: hole j at the nominal centre of pin j
/// (`OutputPins::centre_mm`), radius `hole_radius_mm` (pin + e + hole clearance,
/// `Design::hole_radius_mm`).
pub fn pin_holes(pins: &OutputPins, hole_radius_mm: f64) -> Vec<Circle> {
    (0..pins.count)
        .map(|j| Circle {
            centre: Vec2::from(pins.centre_mm(j)),
            radius_mm: hole_radius_mm,
        })
        .collect()
}

/// The bore of the crank bearing, centred on the disc, when its outer diameter is given.
pub fn bore(design: &Design) -> Option<Circle> {
    (design.crank_bearing.and_then(|b| b.outer_diameter_mm)).map(|d| Circle {
        centre: Vec2::zeros(),
        radius_mm: 0.5 * d,
    })
}

/// The disc as a prism: the region inside the profile, less the holes and the bore, from z = 0
/// to z = B. Disc frame (origin at the disc centre, tooth root on +x, z along the axis), mm.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscSolid {
    /// The profile, one run of pieces per tooth from root to root (t from 2πk/nc to
    /// 2π(k+1)/nc), counter-clockwise.
    pub teeth: Vec<Vec<Bezier>>,
    /// The output-pin holes, hole j at angle 2πj/M on the pin circle.
    pub holes: Vec<Circle>,
    /// The bore of the crank bearing, when its outer diameter is given.
    pub bore: Option<Circle>,
    /// B, mm.
    pub face_width_mm: f64,
}

/// Pieces of each tooth to start from before any is split: 8 per tooth keeps the first pieces
/// shorter than a flank, so no piece spans the tip and both flanks.
const START_PIECES: usize = 8;

/// The profile's pieces of one tooth, each within `tolerance_mm` of the exact profile: a piece
/// whose sampled error exceeds half the tolerance is halved. The half covers what the 15
/// samples miss of the error between them: the Hermite error is smooth, ~u²(1 − u)² times the
/// fourth derivative, and its maximum lies within 1/32 of a sample, where it differs from the
/// sample's by well under 1 %.
pub fn tooth_pieces(profile: &Profile, teeth: usize, k: usize, tolerance_mm: f64) -> Vec<Bezier> {
    let (a, b) = (
        TAU * k as f64 / teeth as f64,
        TAU * (k + 1) as f64 / teeth as f64,
    );
    let mut out = Vec::new();
    for i in 0..START_PIECES {
        let t0 = a + (b - a) * i as f64 / START_PIECES as f64;
        let t1 = a + (b - a) * (i + 1) as f64 / START_PIECES as f64;
        split(profile, t0, t1, 0.5 * tolerance_mm, &mut out);
    }
    out
}

/// Push the pieces of [t0, t1] within `bound_mm`, halving; a piece narrower than 1e-9 rad is
/// kept (its error is then round-off of the profile's coordinates).
fn split(profile: &Profile, t0: f64, t1: f64, bound_mm: f64, out: &mut Vec<Bezier>) {
    let piece = Bezier::hermite(profile, t0, t1);
    if t1 - t0 < 1e-9 || piece.sampled_error(profile) <= bound_mm {
        out.push(piece);
        return;
    }
    let mid = 0.5 * (t0 + t1);
    split(profile, t0, mid, bound_mm, out);
    split(profile, mid, t1, bound_mm, out);
}

impl DiscSolid {
    /// The solid of `profile` with `teeth` teeth, within `tolerance_mm`.
    pub fn new(
        profile: &Profile,
        teeth: usize,
        holes: Vec<Circle>,
        bore: Option<Circle>,
        face_width_mm: f64,
        tolerance_mm: f64,
    ) -> Self {
        DiscSolid {
            teeth: (0..teeth)
                .map(|k| tooth_pieces(profile, teeth, k, tolerance_mm))
                .collect(),
            holes,
            bore,
            face_width_mm,
        }
    }

    /// The holes and the bore: every circle cut through the disc.
    pub fn circles(&self) -> impl Iterator<Item = &Circle> {
        self.holes.iter().chain(self.bore.iter())
    }

    /// Pieces of the whole profile.
    pub fn piece_count(&self) -> usize {
        self.teeth.iter().map(Vec::len).sum()
    }
}

/// Vertices of a polygon inscribed in `circle` whose chords stay within `tolerance_mm` of it
/// (sagitta r·(1 − cos(π/n)) ≤ tol), at least 8, the first on +x from the centre, clockwise
/// when `clockwise`.
pub fn circle_polygon(circle: &Circle, tolerance_mm: f64, clockwise: bool) -> Vec<Vec2> {
    let r = circle.radius_mm;
    let half_angle = (1.0 - (tolerance_mm / r).min(1.0)).acos();
    let n = ((std::f64::consts::PI / half_angle).ceil() as usize).max(8);
    let sign = if clockwise { -1.0 } else { 1.0 };
    (0..n)
        .map(|i| {
            let a = sign * TAU * i as f64 / n as f64;
            circle.centre + unit(a) * r
        })
        .collect()
}
