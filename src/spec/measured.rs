//! `measured_profile:` of a spec, validated.

use super::raw::RawMeasuredProfile;
use crate::error::{Error, Result};
use crate::model::measured::{Fitted, MeasuredProfile, PointsFormat, FITTED_NAMES};

/// Highest form-error harmonic a spec may ask for: 2·200 coefficients already need thousands of
/// points around the whole disc.
pub(crate) const MAX_HARMONICS: i64 = 200;

fn invalid(key: &str, message: String) -> Error {
    Error::invalid(format!("measured_profile.{key}"), message)
}

pub(crate) fn build(spec_path: &str, raw: RawMeasuredProfile) -> Result<MeasuredProfile> {
    super::values::not_blank("measured_profile.file", &raw.file)?;
    let format: PointsFormat = raw.format.parse().map_err(|m| invalid("format", m))?;
    if !(0..=MAX_HARMONICS).contains(&raw.harmonics) {
        return Err(invalid(
            "harmonics",
            format!("must be 0 to {MAX_HARMONICS}, got {}", raw.harmonics),
        ));
    }
    let mut fit = Fitted::default();
    for (i, name) in raw.fit.iter().enumerate() {
        let flags = [&mut fit.shift, &mut fit.equidistant, &mut fit.rotation];
        let Some((_, flag)) = FITTED_NAMES.iter().zip(flags).find(|(n, _)| *n == name) else {
            return Err(invalid(
                &format!("fit[{i}]"),
                format!(
                    "unknown modification `{name}`; known: {}",
                    FITTED_NAMES.join(", ")
                ),
            ));
        };
        if *flag {
            return Err(invalid(
                &format!("fit[{i}]"),
                format!("`{name}` is listed twice"),
            ));
        }
        *flag = true;
    }
    Ok(MeasuredProfile {
        path: super::paths::resolve(spec_path, &raw.file)
            .display()
            .to_string(),
        format,
        harmonics: raw.harmonics as usize,
        fit,
    })
}
