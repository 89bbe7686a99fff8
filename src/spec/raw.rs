//! The spec as written: serde structs that mirror the YAML one to one, no validation.
//! Every struct denies unknown keys so a misspelt key is an error, never silently ignored.
//! Units are in the key names; conversion to engine units happens in `model`.

use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSpec {
    pub name: String,
    pub reducer: RawReducer,
    #[serde(default)]
    pub modification: RawModification,
    pub scenes: Vec<RawScene>,
    #[serde(default)]
    pub limits: RawLimits,
    /// Reviewed reference curves the results must stay close to.
    #[serde(default)]
    pub golden: Vec<RawGolden>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawReducer {
    pub teeth: i64,
    pub rollers: i64,
    pub eccentricity_mm: f64,
    pub roller_circle_radius_mm: f64,
    pub roller_radius_mm: f64,
    pub face_width_mm: f64,
    pub output_pins: RawOutputPins,
    pub material: RawMaterial,
    /// Rollers and output pins, when their material differs from the disc's.
    #[serde(default)]
    pub roller_material: Option<RawMaterial>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawOutputPins {
    pub count: i64,
    pub circle_radius_mm: f64,
    pub pin_radius_mm: f64,
    #[serde(default)]
    pub hole_clearance_mm: f64,
}

#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub struct RawMaterial {
    pub youngs_modulus_gpa: f64,
    pub poisson_ratio: f64,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawModification {
    #[serde(default)]
    pub shift_mm: f64,
    #[serde(default)]
    pub equidistant_mm: f64,
    #[serde(default)]
    pub rotation_deg: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub name: String,
    #[serde(default)]
    pub output_torque_nm: f64,
    pub crank: RawCrank,
    pub effects: Vec<String>,
    #[serde(default)]
    pub contact_law: Option<String>,
    #[serde(default)]
    pub geometry: Option<String>,
    #[serde(default)]
    pub bearing_stiffness_n_per_mm: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCrank {
    pub from_deg: f64,
    pub to_deg: f64,
    pub steps: i64,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct RawLimits {
    pub min_clearance_mm: Option<f64>,
    pub max_roller_force_n: Option<f64>,
    pub max_pin_force_n: Option<f64>,
    pub max_bearing_force_n: Option<f64>,
    pub max_contact_pressure_mpa: Option<f64>,
    pub max_te_fluctuation_arcsec: Option<f64>,
    pub max_ratio_fluctuation: Option<f64>,
    pub min_rollers_in_contact: Option<i64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGolden {
    pub scene: String,
    pub quantity: String,
    /// CSV path, relative to the directory of the spec file.
    pub file: String,
    pub tolerance: RawTolerance,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawTolerance {
    /// Absolute band, in the quantity's unit.
    #[serde(default)]
    pub abs: f64,
    /// Relative band, a fraction of the golden value.
    #[serde(default)]
    pub rel: f64,
}
