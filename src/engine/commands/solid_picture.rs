//! The solid the design review pictures beside the disc drawing: the triangle mesh that
//! `profile --stl` writes (`commands::profile::Disc::mesh`), built at a coarser chordal
//! tolerance so that the picture stays small. Disc frame, mm.

use super::profile::{crowned, disc, DiscSource};
use crate::error::Result;
use crate::geometry::disc_mesh::TriangleMesh;
use crate::spec::Spec;

/// The picture's chordal tolerance as a share of the roller circle's outer radius Rp + Rrp:
/// 1/1000 is 0.3 pixel on a disc drawn 600 pixels across (the review's picture), and keeps the
/// mesh to a couple of thousand triangles (the export's 0.5 µm gives the paper's disc 12,320).
pub const PICTURE_TOLERANCE_SHARE: f64 = 1e-3;

/// The mesh to picture and what its caption names.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidPicture {
    pub mesh: TriangleMesh,
    /// The chordal tolerance the mesh was built at, mm.
    pub tolerance_mm: f64,
    /// B, mm.
    pub face_width_mm: f64,
    /// The crank bearing's bore, mm (`None`: no bore).
    pub bore_diameter_mm: Option<f64>,
    /// Which disc the mesh is.
    pub source: DiscSource,
}

/// The solid of `spec` (the drawing's spec, as `profile` reads it) to picture; `None` when
/// `profile` would not export it: a crowned disc, or a face that does not triangulate.
pub fn solid_picture(spec: &Spec) -> Result<Option<SolidPicture>> {
    if crowned(spec) {
        return Ok(None);
    }
    let d = &spec.design;
    let tolerance_mm = PICTURE_TOLERANCE_SHARE * (d.roller_circle_radius_mm + d.roller_radius_mm);
    let disc = disc(spec)?;
    let Ok(mesh) = disc.mesh(tolerance_mm) else {
        return Ok(None);
    };
    Ok(Some(SolidPicture {
        mesh,
        tolerance_mm,
        face_width_mm: disc.face_width_mm,
        bore_diameter_mm: disc.bore.map(|b| 2.0 * b.radius_mm),
        source: disc.source,
    }))
}
