//! `profile`: the modified disc profile as a polyline within a chordal tolerance.

use crate::error::{Error, ErrorKind, Result};
use crate::geometry::polyline::{polyline, ProfilePoint};
use crate::geometry::profile::Profile;
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
    // NaN fails too.
    if tolerance_mm.is_nan() || tolerance_mm < MIN_PROFILE_TOLERANCE_MM {
        return Err(Error::new(
            ErrorKind::InvalidValue,
            format!(
                "the profile's chordal tolerance must be at least {MIN_PROFILE_TOLERANCE_MM} mm, \
                 got {tolerance_mm} mm"
            ),
        ));
    }
    let profile = Profile::new(&spec.design, &spec.modification);
    Ok(polyline(&profile, tolerance_mm))
}
