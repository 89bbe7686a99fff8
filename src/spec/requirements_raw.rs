//! A requirements file as written (serde), kept apart from the validated
//! [`Requirements`](crate::model::requirements::Requirements); `spec::requirements` checks it.

use super::raw::{
    RawCrowning, RawDutyBin, RawFriction, RawLimits, RawMaterial, RawMisalignment, RawPinSupport,
    RawThermal,
};
use serde::Deserialize;

/// Top-level keys every requirements file has and no spec has: a document with one of them and
/// no `reducer` is a requirements file given where a spec is read.
pub(crate) const REQUIREMENTS_KEYS: [&str; 5] = [
    "ratio",
    "rated_torque_nm",
    "envelope",
    "objectives",
    "search",
];

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRequirements {
    pub name: String,
    /// One ratio or a list of acceptable ratios (integers: the disc's teeth).
    pub ratio: serde_yaml::Value,
    pub rated_torque_nm: f64,
    #[serde(default)]
    pub peak_torque_nm: Option<f64>,
    #[serde(default)]
    pub input_speed_rpm: Option<f64>,
    /// Bins `{output_torque_nm, input_speed_rpm, time_share}` in place of `input_speed_rpm`.
    #[serde(default)]
    pub duty_cycle: Option<Vec<RawDutyBin>>,
    pub envelope: RawEnvelope,
    pub material: RawMaterial,
    /// The rollers' and the output pins' material: the keys of a spec's
    /// `reducer.roller_material`.
    #[serde(default)]
    pub roller_material: Option<RawMaterial>,
    /// The output pins as beams: the keys of a spec's `reducer.output_pins` that no search
    /// varies (its `support`).
    #[serde(default)]
    pub output_pins: Option<RawRequirementsPins>,
    #[serde(default)]
    pub crank_bearing: Option<RawBearing>,
    /// The keys of a spec's `reducer.friction`.
    #[serde(default)]
    pub friction: Option<RawFriction>,
    /// The keys of a spec's `reducer.thermal`.
    #[serde(default)]
    pub thermal: Option<RawThermal>,
    /// The keys of a spec's `modification.crowning`.
    #[serde(default)]
    pub crowning: Option<RawCrowning>,
    /// The disc's tilt in the loaded running scenes, mrad.
    #[serde(default)]
    pub misalignment: Option<RawMisalignment>,
    /// Slices of the face width of every loaded scene.
    #[serde(default)]
    pub face_slices: Option<i64>,
    #[serde(default)]
    pub rules: RawRules,
    #[serde(default)]
    pub limits: RawLimits,
    pub objectives: Vec<String>,
    pub search: RawSearch,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawEnvelope {
    pub max_outer_diameter_mm: f64,
    pub max_axial_length_mm: f64,
    #[serde(default)]
    pub housing_wall_mm: Option<f64>,
    #[serde(default)]
    pub axial_allowance_mm: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRequirementsPins {
    pub support: RawPinSupport,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawBearing {
    pub dynamic_load_rating_n: f64,
    #[serde(default)]
    pub life_exponent: Option<f64>,
    #[serde(default)]
    pub static_load_rating_n: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRules {
    #[serde(default)]
    pub max_k1: Option<f64>,
    #[serde(default)]
    pub min_ligament_mm: Option<f64>,
    #[serde(default)]
    pub min_roller_gap_mm: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSearch {
    pub eccentricity_mm: Vec<f64>,
    pub roller_circle_radius_mm: Vec<f64>,
    pub roller_radius_mm: Vec<f64>,
    pub face_width_mm: Vec<f64>,
    pub pin_circle_radius_mm: Vec<f64>,
    pub pin_radius_mm: Vec<f64>,
    #[serde(default)]
    pub shift_mm: Option<Vec<f64>>,
    #[serde(default)]
    pub equidistant_mm: Option<Vec<f64>>,
    pub pin_counts: Vec<i64>,
    #[serde(default)]
    pub discs: Option<Vec<i64>>,
    #[serde(default)]
    pub hole_clearance_mm: Option<f64>,
    #[serde(default)]
    pub samples: Option<i64>,
    #[serde(default)]
    pub seed: Option<i64>,
    #[serde(default)]
    pub refine_budget: Option<i64>,
    #[serde(default)]
    pub steps_per_mesh_period: Option<i64>,
}
