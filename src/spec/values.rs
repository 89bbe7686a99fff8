//! Checks of single values that more than one section of a spec applies.

use crate::error::{Error, Result};
use crate::numeric;

/// `value` when it is a finite number.
pub(super) fn finite(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(
            key,
            format!("must be a finite number, got {value}"),
        ))
    }
}

/// A named choice (`contact_law`, `geometry`, `reducer.friction.model`,
/// `tolerances.distribution`), when given.
pub(super) fn named<T: std::str::FromStr<Err = String>>(
    key: &str,
    value: Option<&str>,
) -> Result<Option<T>> {
    value
        .map(|v| v.parse().map_err(|m| Error::invalid(key, m)))
        .transpose()
}

/// Refused at `key` unless `value` holds more than blanks (a name, a file path).
pub(super) fn not_blank(key: &str, value: &str) -> Result<()> {
    if value.trim().is_empty() {
        return Err(Error::invalid(key, "must not be empty".into()));
    }
    Ok(())
}

/// A finite number of at least 0 (a clearance, a tolerance band).
pub(super) fn zero_or_positive(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(
            key,
            format!("must be zero or positive, got {}", numeric::input(value)),
        ))
    }
}

/// A disc's index at `key`: one of the reducer's `discs`, numbered from 0.
pub(super) fn disc_index(key: &str, k: i64, discs: usize) -> Result<usize> {
    if (0..discs as i64).contains(&k) {
        return Ok(k as usize);
    }
    Err(Error::invalid(
        key,
        format!("the reducer has {discs} disc(s), numbered from 0; got {k}"),
    ))
}

/// A positive finite number.
pub(super) fn positive(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(
            key,
            format!("must be a positive number, got {}", numeric::input(value)),
        ))
    }
}

/// Largest length the engine accepts, mm. Beyond 100 m a double's ~1e-16 relative precision
/// no longer resolves the micrometre gaps this tool exists to check.
const MAX_LENGTH_MM: f64 = 1e5;

/// A positive length no larger than `MAX_LENGTH_MM`.
pub(super) fn length(key: &str, value: f64) -> Result<f64> {
    let value = positive(key, value)?;
    if value > MAX_LENGTH_MM {
        return Err(Error::invalid(
            key,
            format!(
                "{} mm is larger than the {MAX_LENGTH_MM} mm (100 m) this tool handles: \
                 beyond it double precision cannot resolve micrometre gaps",
                numeric::input(value)
            ),
        ));
    }
    Ok(value)
}

/// Largest tilt of the disc about either axis, mrad. The face model is first order in the tilt
/// (a point at z along the face moves by θ·z); the dropped term θ²/2 of the radii is 1.25e-5 of
/// them at 5 mrad (0.3 µm on a 25 mm roller circle), below the gaps the tool resolves. Measured
/// misalignments of a reducer's disc are tenths of a milliradian.
pub(super) const MAX_TILT_MRAD: f64 = 5.0;

/// A tilt in mrad, finite and within ±`MAX_TILT_MRAD`; in rad.
pub(super) fn tilt_rad(key: &str, value_mrad: f64) -> Result<f64> {
    let value = finite(key, value_mrad)?;
    if value.abs() > MAX_TILT_MRAD {
        return Err(Error::invalid(
            key,
            format!(
                "{} mrad is beyond the ±{MAX_TILT_MRAD} mrad the first-order face model \
                 represents (a reducer's disc tilts by tenths of a milliradian)",
                numeric::input(value)
            ),
        ));
    }
    Ok(1e-3 * value)
}

/// Largest input speed, rpm: 10⁵ rpm is beyond any cycloidal reducer's input (they run at up
/// to a few thousand rpm), a bound at which speeds, lives and losses stay finite numbers.
pub(super) const MAX_SPEED_RPM: f64 = 1e5;

/// `value` (rpm, already checked finite and not negative) when it is at most `MAX_SPEED_RPM`.
pub(super) fn speed_rpm(key: &str, value: f64) -> Result<f64> {
    if value <= MAX_SPEED_RPM {
        return Ok(value);
    }
    Err(Error::invalid(
        key,
        format!(
            "{} rpm is above the {MAX_SPEED_RPM} rpm this tool takes (a cycloidal reducer's \
             input turns at a few thousand rpm at most)",
            numeric::input(value)
        ),
    ))
}

/// Smallest and largest heat-transfer coefficient h, W/(m²·K): still air with radiation is
/// ~5–25, forced oil or water cooling up to ~10⁴; below 0.1 a housing would be a vacuum flask,
/// and P/(h·A) no temperature at all.
pub(super) const HEAT_TRANSFER_W_PER_M2K: (f64, f64) = (0.1, 1e5);

/// Smallest and largest housing area A, m²: 1 cm² (a housing smaller than a thumbnail) to
/// 100 m² (a reducer larger than this tool's 100 m bound on sizes allows is no housing).
pub(super) const HOUSING_AREA_M2: (f64, f64) = (1e-4, 100.0);

/// `value` of `unit` when finite and within `(low, high)` inclusive; `why` says why there.
pub(super) fn within(
    key: &str,
    value: f64,
    (low, high): (f64, f64),
    unit: &str,
    why: &str,
) -> Result<f64> {
    if value.is_finite() && (low..=high).contains(&value) {
        return Ok(value);
    }
    Err(Error::invalid(
        key,
        format!(
            "must lie in [{}, {}] {unit}, got {}: {why}",
            numeric::input(low),
            numeric::input(high),
            numeric::input(value)
        ),
    ))
}
