//! Checks of single values that more than one section of a spec applies.

use crate::error::{Error, ErrorKind, Result};

/// A value error at `key`.
pub(super) fn invalid(key: &str, message: String) -> Error {
    Error::new(ErrorKind::InvalidValue, message).at_key(key)
}

/// `value` when it is a finite number.
pub(super) fn finite(key: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(invalid(
            key,
            format!("must be a finite number, got {value}"),
        ))
    }
}
