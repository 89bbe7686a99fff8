//! `profile`: the modified disc profile as a polyline within a chordal tolerance.

use crate::error::{Error, Result};
use crate::geometry::disc_mesh::{disc_mesh, TriangleMesh};
use crate::geometry::disc_solid::{self, Circle, DiscSolid};
use crate::geometry::placement::{self, disc_body, Body, Placement};
use crate::geometry::polyline::{polyline, ProfilePoint};
use crate::geometry::profile::Profile;
use crate::geometry::Vec2;
use crate::spec::Spec;

/// Finest chordal tolerance of an exported profile, mm (1 nm): below it the point count
/// explodes (≈ 1/√tolerance) and the chords approach the rounding of f64 coordinates.
pub const MIN_PROFILE_TOLERANCE_MM: f64 = 1e-6;

/// Points of the spec's whole modified profile, every chord within `tolerance_mm` of it.
///
/// ```
/// let spec = cycloid::spec::load("specs/reducer.yaml")?;
/// let points = cycloid::profile(&spec, 0.5e-3)?; // chords within 0.5 µm
/// // Every point lies between the disc's root and tip circles, Rp − Rrp ∓ e, less the
/// // equidistant modification.
/// let r = |p: &cycloid::geometry::polyline::ProfilePoint| p.point.norm();
/// assert!(points.iter().all(|p| r(p) > 30.0 - 3.0 - 2.0 - 0.2 && r(p) < 30.0 - 3.0 + 2.0));
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn profile(spec: &Spec, tolerance_mm: f64) -> Result<Vec<ProfilePoint>> {
    check_tolerance(tolerance_mm)?;
    let profile = Profile::new(&spec.design, &spec.modification);
    Ok(polyline(&profile, tolerance_mm))
}

fn check_tolerance(tolerance_mm: f64) -> Result<()> {
    // NaN fails too.
    if tolerance_mm.is_nan() || tolerance_mm < MIN_PROFILE_TOLERANCE_MM {
        return Err(Error::invalid_value(format!(
            "the profile's chordal tolerance must be at least {MIN_PROFILE_TOLERANCE_MM} mm, \
             got {tolerance_mm} mm"
        )));
    }
    Ok(())
}

/// The disc the solid exports are made of: the profile as `check` meshes it
/// (`Profile::as_ground`; as built, with its identified modification and form error, when the
/// spec has `measured_profile`), the output-pin holes, the bore when the crank bearing's outer
/// diameter is given, and the face width.
pub struct Disc {
    pub profile: Profile,
    pub teeth: usize,
    pub holes: Vec<Circle>,
    pub bore: Option<Circle>,
    pub face_width_mm: f64,
    /// Which disc the profile is.
    pub source: DiscSource,
    /// Each disc of the reducer as a body of the exports (`placement::disc_body`): one disc
    /// in its own frame, several each where the reducer puts it.
    pub bodies: Vec<Body>,
}

/// Which disc the solid exports are of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiscSource {
    /// The drawing's modification.
    Drawing,
    /// The drawing's modification ground with `reducer.deviations`' grinding errors or form
    /// error.
    Ground,
    /// The disc identified from `measured_profile`.
    Measured,
}

/// The disc of `spec` for `profile --step`/`--stl`. A crowned disc is refused: its flanks are
/// not the straight extrusion these exports build.
pub fn disc(spec: &Spec) -> Result<Disc> {
    if crowned(spec) {
        return Err(Error::invalid_value(
            "the disc is crowned (`modification.crowning`): the STEP and STL exports build a \
             straight flank extruded over the face width and would not be this disc; export a \
             section with --csv or --dxf instead",
        ));
    }
    let built = crate::engine::as_built::identify(spec)?.map(|(s, _)| s);
    let (d, m) = match &built {
        Some(b) => (&b.design, &b.modification),
        None => (&spec.design, &spec.modification),
    };
    let profile = Profile::as_ground(d, m);
    let design = &spec.design;
    let holes = disc_solid::pin_holes(&design.pins, design.hole_radius_mm());
    let bore = disc_solid::bore(design);
    Ok(Disc {
        profile,
        teeth: design.teeth,
        holes,
        bore,
        face_width_mm: design.face_width_mm,
        source: match &built {
            Some(_) => DiscSource::Measured,
            None if d.deviations.grinds() => DiscSource::Ground,
            None => DiscSource::Drawing,
        },
        bodies: (0..design.discs).map(|k| disc_body(design, k)).collect(),
    })
}

/// Whether any scene crowns the disc (`modification.crowning`), which `disc` refuses.
pub fn crowned(spec: &Spec) -> bool {
    spec.scenes.iter().any(|s| !s.face.crowning.is_none())
}

impl Disc {
    /// The solid of disc 0 in its frame: the profile as cubic B-spline pieces within
    /// `tolerance_mm`, extruded.
    pub fn solid(&self, tolerance_mm: f64) -> Result<DiscSolid> {
        check_tolerance(tolerance_mm)?;
        Ok(DiscSolid::new(
            &self.profile,
            self.teeth,
            self.holes.clone(),
            self.bore,
            self.face_width_mm,
            tolerance_mm,
        ))
    }

    /// Every disc's solid in its own frame (its holes turned as its body says) and where it
    /// goes: what `--step` writes.
    pub fn solids(&self, tolerance_mm: f64) -> Result<Vec<(DiscSolid, Placement)>> {
        let first = self.solid(tolerance_mm)?;
        Ok((self.bodies.iter())
            .map(|b| {
                let solid = DiscSolid {
                    holes: self.holes_of(b),
                    ..first.clone()
                };
                (solid, b.placement)
            })
            .collect())
    }

    /// The closed triangle mesh of disc 0 in its frame: the profile's polyline and the
    /// circles' polygons within `tolerance_mm`.
    pub fn mesh(&self, tolerance_mm: f64) -> Result<TriangleMesh> {
        self.mesh_with(&self.holes, tolerance_mm)
    }

    /// Every disc's mesh, each moved where it goes: what `--stl` writes.
    pub fn placed_mesh(&self, tolerance_mm: f64) -> Result<TriangleMesh> {
        let mut out = TriangleMesh {
            vertices: Vec::new(),
            triangles: Vec::new(),
        };
        for b in &self.bodies {
            let mesh = self.mesh_with(&self.holes_of(b), tolerance_mm)?;
            placement::append(&mut out, &mesh, &b.placement);
        }
        Ok(out)
    }

    /// The holes of a body's disc: disc 0's turned by its `hole_turn_rad`.
    fn holes_of(&self, body: &Body) -> Vec<Circle> {
        let turn = nalgebra::Rotation2::new(body.hole_turn_rad);
        (self.holes.iter())
            .map(|c| Circle {
                centre: turn * c.centre,
                ..*c
            })
            .collect()
    }

    fn mesh_with(&self, holes: &[Circle], tolerance_mm: f64) -> Result<TriangleMesh> {
        check_tolerance(tolerance_mm)?;
        let outline: Vec<Vec2> = (polyline(&self.profile, tolerance_mm).iter())
            .map(|p| p.point)
            .collect();
        let circles: Vec<Circle> = holes.iter().chain(self.bore.iter()).copied().collect();
        disc_mesh(&outline, &circles, self.face_width_mm, tolerance_mm).ok_or_else(|| {
            Error::computation(
                "the disc's face could not be triangulated (its outline touches itself or a \
                 hole): no STL was written",
            )
        })
    }
}
