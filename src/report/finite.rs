//! A number a JSON document can hold, for every typed document the tool writes (the results
//! JSON, `report::json`; the tolerance study's, `report::tolerance`): serialising a non-finite
//! one is an error, never `null`.

use serde::ser::Error as _;
use serde::{Serialize, Serializer};

/// A number JSON can hold: serialising a non-finite one is an error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Finite(pub f64);

impl Serialize for Finite {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        if self.0.is_finite() {
            s.serialize_f64(self.0)
        } else {
            Err(S::Error::custom(format!(
                "a result is {}, which JSON cannot hold (a bug: please report it with the spec)",
                self.0
            )))
        }
    }
}
