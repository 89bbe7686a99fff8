//! Where a disc sits in the reducer: the rigid motion from the disc frame (origin at the
//! disc's centre, tooth root on +x, z along the axis from the face z = 0) to the reducer's
//! frame (origin on the input axis, roller 0 on +x), used to place each disc of several in an
//! exported assembly (`profile --step`, `--stl`).

use super::disc_mesh::TriangleMesh;
use super::{wrap_pi, Vec2};
use crate::model::Design;
use std::f64::consts::TAU;

/// The rigid motion p ↦ R(turn)·p + centre in the plane, and z ↦ z + z_mm along the axis.
/// Angles counter-clockwise seen from +z, rad; lengths mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The disc's rotation about its own centre, rad.
    pub turn_rad: f64,
    /// The disc centre in the reducer's frame, mm.
    pub centre: Vec2,
    /// Where the disc's face z = 0 sits along the axis, mm.
    pub z_mm: f64,
}

/// One disc of a reducer as a body of the exported assembly: its placement, and how far its
/// output-pin holes are turned about its centre from disc 0's (in the disc frame, counter-
/// clockwise), rad: 0 when the disc is disc 0's part, turned.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    pub placement: Placement,
    pub hole_turn_rad: f64,
}

/// Where disc k of `design` sits at crank angle 0 (MODEL.md "Several discs"): its centre at
/// (e + de)·(cos φk, sin φk), φk = 2πk/N its crank phase; its face from a_k − B/2 (a_k its
/// mid-plane along the pins, `output_pins.support`) or, without a support, from k·B (the discs
/// side by side, disc 0 nearest the flange). Its turn τ meshes its teeth with the rollers,
/// τ ≡ −φk/nc (mod 2π/nc), and sets its holes around the pins at 2πj/M, τ + δ ≡ 0 (mod 2π/M),
/// δ the holes' turn from disc 0's. Of the nc turns the teeth allow, the one that leaves the
/// holes where disc 0 has them (δ = 0: the same part) is taken when there is one (the nearest
/// to 0 of those, counter-clockwise of two), else the one whose holes are turned least; a disc
/// whose holes are turned is a part of its own. One disc: the disc frame itself.
pub fn disc_body(design: &Design, k: usize) -> Body {
    if design.discs == 1 {
        return Body {
            placement: Placement::IDENTITY,
            hole_turn_rad: 0.0,
        };
    }
    let (nc, m) = (design.teeth as f64, design.pins.count as f64);
    let phase = design.disc_phase_rad(k);
    let hole_step = TAU / m;
    let turns = (0..design.teeth).map(|i| wrap_pi(-phase / nc + TAU * i as f64 / nc));
    // δ in (−step/2, step/2]: the holes' least turn that puts them on the pins.
    let hole_turn = |tau: f64| {
        let d = (-tau).rem_euclid(hole_step);
        let d = if d > 0.5 * hole_step {
            d - hole_step
        } else {
            d
        };
        // Round-off of the sums above (≤ 1e-15 rad) is no turn of the holes.
        if d.abs() < 1e-12 {
            0.0
        } else {
            d
        }
    };
    // Least hole turn, then least turn, then the counter-clockwise of a ±τ pair; compared in
    // nrad so that round-off does not pick between equals.
    let nrad = |x: f64| (x * 1e9).round() as i64;
    let key = |tau: f64| (nrad(hole_turn(tau).abs()), nrad(tau.abs()), -nrad(tau));
    let turn_rad = turns.min_by_key(|&tau| key(tau)).expect("a disc has teeth");
    let e = design.built_eccentricity_mm();
    let b = design.face_width_mm;
    let z_mm = match &design.pins.support {
        Some(s) => s.disc_positions_mm[k] - 0.5 * b,
        None => k as f64 * b,
    };
    Body {
        placement: Placement {
            turn_rad,
            centre: Vec2::new(e * phase.cos(), e * phase.sin()),
            z_mm,
        },
        hole_turn_rad: hole_turn(turn_rad),
    }
}

impl Placement {
    /// The disc frame itself (one disc exports in its own frame).
    pub const IDENTITY: Placement = Placement {
        turn_rad: 0.0,
        centre: Vec2::new(0.0, 0.0),
        z_mm: 0.0,
    };

    /// A point of the disc frame in the reducer's frame.
    pub fn point(&self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        let [dx, dy, dz] = self.direction([x, y, z]);
        [dx + self.centre.x, dy + self.centre.y, dz + self.z_mm]
    }

    /// A direction of the disc frame in the reducer's frame (turned, not moved).
    pub fn direction(&self, [x, y, z]: [f64; 3]) -> [f64; 3] {
        let (s, c) = self.turn_rad.sin_cos();
        [c * x - s * y, s * x + c * y, z]
    }
}

/// Appends `mesh` moved by `at` to `out` (its triangles after those already there; each
/// mesh appended stays closed on its own).
pub fn append(out: &mut TriangleMesh, mesh: &TriangleMesh, at: &Placement) {
    let n = out.vertices.len();
    out.vertices
        .extend(mesh.vertices.iter().map(|&v| at.point(v)));
    (out.triangles).extend(mesh.triangles.iter().map(|t| t.map(|i| i + n)));
}
