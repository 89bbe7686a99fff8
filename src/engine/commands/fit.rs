//! `fit`: identify the disc that a spec's measured points lie on.

use crate::engine::as_built;
use crate::error::{Error, Result};
use crate::measure::fit::Identification;
use crate::spec::Spec;

/// The disc of the spec's `measured_profile` points: centre, orientation, modifications and
/// form error, with standard uncertainties. A spec without measured points is refused.
///
/// ```
/// // "Measure" the shipped disc: its exported profile as the points of a spec.
/// let dir = std::env::temp_dir().join(format!("cycloid-doc-fit-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let drawing = cycloid::spec::load("specs/reducer.yaml")?;
/// let points = cycloid::profile(&drawing, 1e-4)?;
/// let csv = cycloid::report::export::csv(&drawing, &points, 1e-4);
/// std::fs::write(dir.join("points.csv"), csv).unwrap();
/// let text = std::fs::read_to_string("specs/reducer.yaml").unwrap()
///     + "measured_profile: {file: points.csv, format: csv, harmonics: 0, \
///        fit: [shift_mm, equidistant_mm]}\n";
/// let path = dir.join("measured.yaml");
/// std::fs::write(&path, text).unwrap();
/// let id = cycloid::fit(&cycloid::spec::load(path.to_str().unwrap())?)?;
/// // The modification it was drawn with comes back (ΔRp 0.125 mm, ΔRrp 0.1593 mm).
/// assert!((id.modification.shift_mm - 0.125).abs() < 1e-5);
/// assert!((id.modification.equidistant_mm - 0.1593).abs() < 1e-5);
/// std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn fit(spec: &Spec) -> Result<Identification> {
    let measured = spec.measured.as_ref().ok_or_else(|| {
        Error::invalid_value(format!(
            "{}: the spec has no `measured_profile:` section; add \
             `measured_profile: {{file: points.csv, format: csv, harmonics: 0, fit: \
             [shift_mm, equidistant_mm]}}`",
            spec.path
        ))
    })?;
    as_built::fit(spec, measured)
}
