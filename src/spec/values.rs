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
