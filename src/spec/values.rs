//! Checks of single values that more than one section of a spec applies.

use crate::error::{Error, Result};

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
