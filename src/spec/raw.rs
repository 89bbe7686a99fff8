//! The spec as written: serde structs that mirror the YAML one to one, no validation.
//! Every struct denies unknown keys so a misspelt key is an error, never silently ignored.
//! Units are in the key names; conversion to engine units happens in `model`.

use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a spec: a mapping with the keys name, reducer, scenes (and optionally modification, limits)"
)]
pub struct RawSpec {
    pub name: String,
    pub reducer: RawReducer,
    #[serde(default)]
    pub modification: RawModification,
    pub scenes: Vec<RawScene>,
    #[serde(default)]
    pub limits: RawLimits,
}

#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping of the reducer keys (teeth, rollers, eccentricity_mm, ...)"
)]
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
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys count, circle_radius_mm, pin_radius_mm (and optionally hole_clearance_mm)"
)]
pub struct RawOutputPins {
    pub count: i64,
    pub circle_radius_mm: f64,
    pub pin_radius_mm: f64,
    #[serde(default)]
    pub hole_clearance_mm: f64,
}

#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys youngs_modulus_gpa, poisson_ratio"
)]
pub struct RawMaterial {
    pub youngs_modulus_gpa: f64,
    pub poisson_ratio: f64,
}

#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys shift_mm, equidistant_mm, rotation_deg"
)]
pub struct RawModification {
    #[serde(default)]
    pub shift_mm: f64,
    #[serde(default)]
    pub equidistant_mm: f64,
    #[serde(default)]
    pub rotation_deg: f64,
}

#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a scene: a mapping with the keys name, crank, effects (and optionally output_torque_nm, ...)"
)]
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
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys from_deg, to_deg, steps"
)]
pub struct RawCrank {
    pub from_deg: f64,
    pub to_deg: f64,
    pub steps: i64,
}

#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping of limit keys (min_clearance_mm, ...)"
)]
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
