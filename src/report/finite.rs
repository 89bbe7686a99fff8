//! A number a JSON document can hold, for every typed document the tool writes (the results
//! JSON, `report::json`; the tolerance study's, `report::tolerance`): serialising a non-finite
//! one is an error, never `null`.

use serde::{Serialize, Serializer};

/// A number JSON can hold: serialising a non-finite one is an error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Finite(pub f64);

impl Serialize for Finite {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self.0.is_finite() {
            true => s.serialize_f64(self.0),
            false => Err(not_finite(self.0)),
        }
    }
}

/// The error of a number JSON cannot hold.
pub fn not_finite<E: serde::ser::Error>(value: f64) -> E {
    E::custom(format!(
        "a result is {value}, which JSON cannot hold (a bug: please report it with the spec)"
    ))
}
