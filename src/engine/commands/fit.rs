//! `fit`: identify the disc that a spec's measured points lie on.

use crate::engine::as_built;
use crate::error::{Error, ErrorKind, Result};
use crate::measure::fit::Identification;
use crate::spec::Spec;

/// The disc of the spec's `measured_profile` points: centre, orientation, modifications and
/// form error, with standard uncertainties. A spec without measured points is refused.
pub fn fit(spec: &Spec) -> Result<Identification> {
    let measured = spec.measured.as_ref().ok_or_else(|| {
        Error::new(
            ErrorKind::InvalidValue,
            format!(
                "{}: the spec has no `measured_profile:` section; add \
                 `measured_profile: {{file: points.csv, format: csv, harmonics: 0, fit: \
                 [shift_mm, equidistant_mm]}}`",
                spec.path
            ),
        )
    })?;
    as_built::fit(spec, measured)
}
