//! A golden curve entry of a spec: the reviewed file a scene's curve is compared with.

use super::quantity::Quantity;

/// Allowed deviation from a golden value g: |value − g| ≤ abs + rel·|g|.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GoldenTolerance {
    /// The absolute part, in the unit of the quantity's key (≥ 0).
    pub abs: f64,
    /// The relative part, a fraction of |g| (≥ 0; not both zero).
    pub rel: f64,
}

impl GoldenTolerance {
    /// The band around a golden value.
    pub fn band(&self, golden: f64) -> f64 {
        self.abs + self.rel * golden.abs()
    }
}

/// A reviewed reference curve (`golden[]`) that a scene's results are compared with.
#[derive(Debug, Clone, PartialEq)]
pub struct Golden {
    /// Key path of this entry in the spec (`golden[2]`), for error locations.
    pub key: String,
    /// The name of the scene whose curve is compared.
    pub scene: String,
    /// A per-angle quantity of the registry.
    pub quantity: &'static Quantity,
    /// With several discs, the disc whose curve it is (a disc's quantity: forces, lags).
    pub disc: Option<usize>,
    /// The path as written in the spec.
    pub file: String,
    /// The path resolved against the spec file's directory (lexically normalised).
    pub path: std::path::PathBuf,
    /// The band every compared point must stay in (`tolerance`).
    pub tolerance: GoldenTolerance,
}

impl Golden {
    /// "[disc k]" after a name when the golden holds a disc's curve, else nothing.
    pub fn disc_suffix(&self) -> String {
        self.disc.map_or(String::new(), |k| format!("[disc {k}]"))
    }
}
