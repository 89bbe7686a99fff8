//! The spec as written: serde structs that mirror the YAML one to one, no validation.
//! Every struct denies unknown keys so a misspelt key is an error, never silently ignored.
//! Units are in the key names; conversion to engine units happens in `model`.

use serde::Deserialize;
use std::collections::BTreeMap;

/// The whole spec, generic over the form of `optimise` so that a failed untagged match can be
/// parsed again as the form the YAML has, for a precise error (see [`spec::yaml::parse_raw`](crate::spec::yaml::parse_raw)).
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a spec: a mapping with the keys name, reducer, scenes (and optionally modification, limits, optimise)"
)]
pub(crate) struct RawSpecOf<O> {
    pub name: String,
    pub reducer: RawReducer,
    #[serde(default)]
    pub modification: RawModification,
    pub scenes: Vec<RawScene>,
    #[serde(default)]
    pub limits: RawLimits,
    #[serde(default = "Option::default")]
    pub optimise: Option<O>,
    /// Reviewed reference curves the results must stay close to.
    #[serde(default)]
    pub golden: Vec<RawGolden>,
    /// A directory, relative to the spec's, where `bless` may write goldens besides the spec's
    /// own directory tree (`../golden` for a spec in `specs/`).
    #[serde(default)]
    pub golden_root: Option<String>,
    /// The accuracy ladder of one scene, shown in the design review (`check --report`).
    #[serde(default)]
    pub accuracy: Option<RawAccuracy>,
    /// Points measured on the disc, to identify it (`cycloid fit`).
    #[serde(default)]
    pub measured_profile: Option<RawMeasuredProfile>,
    /// Tolerance bands of the parts, for the Monte Carlo study (`cycloid tolerance`).
    #[serde(default)]
    pub tolerances: Option<RawTolerances>,
}

/// `tolerances:`: a band ±b per deviation kind (0 or absent: not toleranced), how deviations
/// are distributed in it, and the study (scene, samples, seed, allowed failure rate).
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys scene, max_failure_rate and the bands (eccentricity_mm, roller_radial_mm, ...)"
)]
pub(crate) struct RawTolerances {
    #[serde(default)]
    pub eccentricity_mm: f64,
    #[serde(default)]
    pub roller_radial_mm: f64,
    #[serde(default)]
    pub roller_tangential_mm: f64,
    #[serde(default)]
    pub roller_radius_mm: f64,
    #[serde(default)]
    pub pin_radial_mm: f64,
    #[serde(default)]
    pub pin_tangential_mm: f64,
    #[serde(default)]
    pub hole_radial_mm: f64,
    #[serde(default)]
    pub hole_tangential_mm: f64,
    #[serde(default)]
    pub shift_mm: f64,
    #[serde(default)]
    pub equidistant_mm: f64,
    /// `normal` (band = 3σ) or `uniform`; default normal.
    #[serde(default)]
    pub distribution: Option<String>,
    pub scene: String,
    #[serde(default)]
    pub samples: Option<i64>,
    #[serde(default)]
    pub seed: Option<i64>,
    pub max_failure_rate: f64,
}

impl RawTolerances {
    /// The bands in the order of [`model::tolerances::Kind::ALL`](crate::model::tolerances::Kind::ALL).
    pub(crate) fn bands(&self) -> [f64; 10] {
        [
            self.eccentricity_mm,
            self.roller_radial_mm,
            self.roller_tangential_mm,
            self.roller_radius_mm,
            self.pin_radial_mm,
            self.pin_tangential_mm,
            self.hole_radial_mm,
            self.hole_tangential_mm,
            self.shift_mm,
            self.equidistant_mm,
        ]
    }
}

/// `measured_profile:`: a points file and what to identify from it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMeasuredProfile {
    /// Relative to the directory of the spec file.
    pub file: String,
    pub format: String,
    /// Highest harmonic of the form-error series.
    #[serde(default)]
    pub harmonics: i64,
    /// Among shift_mm, equidistant_mm, rotation_deg.
    #[serde(default)]
    pub fit: Vec<String>,
}

pub(crate) type RawSpec = RawSpecOf<RawOptimise>;

/// `optimise:` is one study (a mapping) or a list of studies.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum RawOptimise {
    One(Box<RawStudy>),
    Many(Vec<RawStudy>),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStudy {
    #[serde(default)]
    pub name: Option<String>,
    pub scene: String,
    pub objective: RawObjective,
    pub variables: RawVariables,
    #[serde(default)]
    pub start: Option<RawPoint>,
    #[serde(default)]
    pub constraints: RawConstraints,
    /// Modifications to evaluate and compare with the optimum (e.g. a published optimum).
    #[serde(default)]
    pub references: Vec<RawReference>,
    #[serde(default)]
    pub optimum_max_objective: Option<f64>,
    /// Interior points of the global (space-filling) stage.
    #[serde(default)]
    pub global_samples: Option<i64>,
    /// Points of the global stage on each face of the feasible region.
    #[serde(default)]
    pub boundary_samples: Option<i64>,
    /// Evaluations allowed to each local (COBYLA) run.
    #[serde(default)]
    pub local_evaluations: Option<i64>,
    /// Points per variable of the verification grid (0: none).
    #[serde(default)]
    pub verify_grid: Option<i64>,
}

/// An objective name, or a map of objective names to weights (a weighted sum).
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub(crate) enum RawObjective {
    Name(String),
    Weighted(BTreeMap<String, f64>),
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawVariables {
    pub shift_mm: Option<[f64; 2]>,
    pub equidistant_mm: Option<[f64; 2]>,
    pub rotation_deg: Option<[f64; 2]>,
    /// The circular crown's radius, mm.
    pub crown_radius_mm: Option<[f64; 2]>,
    /// The circular crown's flat half-length, mm.
    pub crown_start_mm: Option<[f64; 2]>,
}

#[derive(Debug, Deserialize, Default, Clone, Copy)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawPoint {
    pub shift_mm: Option<f64>,
    pub equidistant_mm: Option<f64>,
    pub rotation_deg: Option<f64>,
    pub crown_radius_mm: Option<f64>,
    pub crown_start_mm: Option<f64>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawConstraints {
    pub tip_clearance_mm: Option<[f64; 2]>,
    pub min_clearance_mm: Option<f64>,
    pub max_lost_motion_arcsec: Option<f64>,
    /// Upper bounds on objectives of the study's scene, by objective name.
    #[serde(default)]
    pub objectives: BTreeMap<String, f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawReference {
    pub label: String,
    #[serde(default)]
    pub shift_mm: f64,
    #[serde(default)]
    pub equidistant_mm: f64,
    #[serde(default)]
    pub rotation_deg: f64,
}

#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping of the reducer keys (teeth, rollers, eccentricity_mm, ...)"
)]
pub(crate) struct RawReducer {
    pub teeth: i64,
    pub rollers: i64,
    /// Identical discs at crank phases 2πk/discs (default 1).
    #[serde(default = "one_disc")]
    pub discs: i64,
    pub eccentricity_mm: f64,
    pub roller_circle_radius_mm: f64,
    pub roller_radius_mm: f64,
    pub face_width_mm: f64,
    pub output_pins: RawOutputPins,
    pub material: RawMaterial,
    /// Rollers and output pins, when their material differs from the disc's.
    #[serde(default)]
    pub roller_material: Option<RawMaterial>,
    /// The crank bearing's rating, for its rating life.
    #[serde(default)]
    pub crank_bearing: Option<RawCrankBearing>,
    /// Deviations of the built parts from the drawing (one as-built state).
    #[serde(default)]
    pub deviations: Option<RawDeviations>,
    /// Friction at every contact (absent: the frictionless model).
    #[serde(default)]
    pub friction: Option<RawFriction>,
    /// The housing's heat path, for a steady temperature.
    #[serde(default)]
    pub thermal: Option<RawThermal>,
    /// The torsional compliance of the rest of the reducer, in series (absent: 0).
    #[serde(default)]
    pub structure_compliance_arcmin_per_knm: Option<f64>,
    /// The inertia of the output (flange, pins, load) about its axis, kg·m², for the inertia at
    /// the input (absent: 0).
    #[serde(default)]
    pub output_inertia_kgm2: Option<f64>,
    /// Each roller's inertia about its own axis, kg·m², for the rollers' spin in the inertia
    /// at the input when they turn (absent: not counted).
    #[serde(default)]
    pub roller_inertia_kgm2: Option<f64>,
}

/// `reducer.friction` (MODEL.md "Friction, efficiency and heat"): a path not given has no
/// friction.
#[derive(Debug, Deserialize, Clone)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping of the friction keys (model, rollers, output_pins, crank_bearing, no_load_torque_nmm)"
)]
pub(crate) struct RawFriction {
    /// `loss` or `coupled` (the default).
    #[serde(default)]
    pub model: Option<String>,
    #[serde(default)]
    pub rollers: Option<RawRollerFriction>,
    #[serde(default)]
    pub output_pins: Option<RawPinFriction>,
    #[serde(default)]
    pub crank_bearing: Option<RawBearingFriction>,
    /// A drag at the input, N·mm: a number, or a table of [input_rpm, N·mm] pairs.
    #[serde(default)]
    pub no_load_torque_nmm: Option<RawNoLoad>,
}

/// `reducer.friction.no_load_torque_nmm`: one number, or a catalogue's no-load running torque
/// curve as [input_rpm, N·mm] pairs.
#[derive(Debug, Deserialize, Clone)]
#[serde(
    untagged,
    expecting = "a number (N·mm) or a list of [input_rpm, N·mm] pairs"
)]
pub(crate) enum RawNoLoad {
    Constant(f64),
    Table(Vec<[f64; 2]>),
}

/// `reducer.friction.rollers`: `fixed` or `rotating` (on a pin of `bore_radius_mm`).
#[derive(Debug, Deserialize, Clone)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys mode, mu (and bore_radius_mm with mode rotating)"
)]
pub(crate) struct RawRollerFriction {
    pub mode: String,
    pub mu: f64,
    #[serde(default)]
    pub bore_radius_mm: Option<f64>,
}

/// `reducer.friction.output_pins`: `fixed` or `sleeve` (a free sleeve on a pin of
/// `bore_radius_mm`).
#[derive(Debug, Deserialize, Clone)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys mode, mu (and bore_radius_mm with mode sleeve)"
)]
pub(crate) struct RawPinFriction {
    pub mode: String,
    pub mu: f64,
    #[serde(default)]
    pub bore_radius_mm: Option<f64>,
}

/// `reducer.friction.crank_bearing`: friction torque μ·Fb·d/2.
#[derive(Debug, Deserialize, Clone)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys mu, bore_diameter_mm"
)]
pub(crate) struct RawBearingFriction {
    pub mu: f64,
    pub bore_diameter_mm: f64,
}

/// `reducer.thermal`: the steady temperature ambient + P/(h·A).
#[derive(Debug, Deserialize, Clone)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys housing_area_m2, heat_transfer_w_per_m2k, ambient_c"
)]
pub(crate) struct RawThermal {
    pub housing_area_m2: f64,
    pub heat_transfer_w_per_m2k: f64,
    pub ambient_c: f64,
}

/// `reducer.deviations`: every key optional (MODEL.md "Part deviations").
#[derive(Debug, Deserialize, Default, Clone)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping of the deviation keys (eccentricity_mm, rollers, pins, holes, shift_mm, equidistant_mm, form, misalignment)"
)]
pub(crate) struct RawDeviations {
    #[serde(default)]
    pub eccentricity_mm: f64,
    #[serde(default)]
    pub rollers: Vec<RawRollerDeviation>,
    #[serde(default)]
    pub pins: Vec<RawCentreDeviation>,
    #[serde(default)]
    pub holes: Vec<RawCentreDeviation>,
    #[serde(default)]
    pub shift_mm: f64,
    #[serde(default)]
    pub equidistant_mm: f64,
    /// The disc's form error as harmonics in the locus parameter (what `cycloid fit --write`
    /// writes).
    #[serde(default)]
    pub form: Vec<RawFormTerm>,
    /// The disc's tilt against the housing as built, added to every scene's.
    #[serde(default)]
    pub misalignment: Option<RawMisalignment>,
}

/// One harmonic of the form error: w(t) ∋ cos_mm·cos(order·t) + sin_mm·sin(order·t).
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the key order (and optionally cos_mm, sin_mm)"
)]
pub(crate) struct RawFormTerm {
    pub order: i64,
    #[serde(default)]
    pub cos_mm: f64,
    #[serde(default)]
    pub sin_mm: f64,
}

/// One roller's deviation: centre outward and counter-clockwise along its circle, radius.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the key index (and optionally radial_mm, tangential_mm, radius_mm)"
)]
pub(crate) struct RawRollerDeviation {
    pub index: i64,
    #[serde(default)]
    pub radial_mm: f64,
    #[serde(default)]
    pub tangential_mm: f64,
    #[serde(default)]
    pub radius_mm: f64,
}

/// One pin's or hole's centre deviation; a hole names its disc when there are several.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the key index (and optionally disc, radial_mm, tangential_mm)"
)]
pub(crate) struct RawCentreDeviation {
    pub index: i64,
    #[serde(default)]
    pub disc: Option<i64>,
    #[serde(default)]
    pub radial_mm: f64,
    #[serde(default)]
    pub tangential_mm: f64,
}

#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the key dynamic_load_rating_n (and optionally life_exponent, outer_diameter_mm, static_load_rating_n)"
)]
pub(crate) struct RawCrankBearing {
    pub dynamic_load_rating_n: f64,
    #[serde(default)]
    pub life_exponent: Option<f64>,
    #[serde(default)]
    pub outer_diameter_mm: Option<f64>,
    #[serde(default)]
    pub static_load_rating_n: Option<f64>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys count, circle_radius_mm, pin_radius_mm (and optionally hole_clearance_mm, support)"
)]
pub(crate) struct RawOutputPins {
    pub count: i64,
    pub circle_radius_mm: f64,
    pub pin_radius_mm: f64,
    #[serde(default)]
    pub hole_clearance_mm: f64,
    /// The pins as beams (absent: rigid pins).
    #[serde(default)]
    pub support: Option<RawPinSupport>,
}

/// `reducer.output_pins.support`: how the pins are held, for their bending.
#[derive(Debug, Deserialize, Clone)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys kind, length_mm, disc_positions_mm"
)]
pub(crate) struct RawPinSupport {
    pub kind: String,
    pub length_mm: f64,
    pub disc_positions_mm: Vec<f64>,
}

#[derive(Debug, Deserialize, Clone, Copy, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys youngs_modulus_gpa, poisson_ratio (and optionally yield_strength_mpa, contact_fatigue, density_kg_per_m3)"
)]
pub(crate) struct RawMaterial {
    pub youngs_modulus_gpa: f64,
    pub poisson_ratio: f64,
    /// The disc's density, kg/m³ (default steel's), for its mass and inertia.
    #[serde(default)]
    pub density_kg_per_m3: Option<f64>,
    /// The yield strength, for the output pins' bending safety.
    #[serde(default)]
    pub yield_strength_mpa: Option<f64>,
    /// The running surface's S–N law of rolling-contact fatigue.
    #[serde(default)]
    pub contact_fatigue: Option<RawContactFatigue>,
}

/// `contact_fatigue` of a material: N(p) = cycles·(pressure_mpa/p)^exponent.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys pressure_mpa, cycles, exponent (and optionally endurance_pressure_mpa)"
)]
pub(crate) struct RawContactFatigue {
    pub pressure_mpa: f64,
    pub cycles: f64,
    pub exponent: f64,
    #[serde(default)]
    pub endurance_pressure_mpa: Option<f64>,
}

#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys shift_mm, equidistant_mm, rotation_deg, crowning"
)]
pub(crate) struct RawModification {
    #[serde(default)]
    pub shift_mm: f64,
    #[serde(default)]
    pub equidistant_mm: f64,
    #[serde(default)]
    pub rotation_deg: f64,
    /// The disc's crowning along the face width.
    #[serde(default)]
    pub crowning: Option<RawCrowning>,
}

/// `modification.crowning`: `kind` and the keys of its profile (checked against the kind in
/// `spec::validate`).
#[derive(Debug, Deserialize, Clone, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys kind (circular: radius_mm, start_mm; logarithmic: design_load_n, end_drop_mm, load_coefficient, crowned_fraction)"
)]
pub(crate) struct RawCrowning {
    pub kind: String,
    #[serde(default)]
    pub radius_mm: Option<f64>,
    #[serde(default)]
    pub start_mm: Option<f64>,
    #[serde(default)]
    pub design_load_n: Option<f64>,
    #[serde(default)]
    pub end_drop_mm: Option<f64>,
    #[serde(default)]
    pub load_coefficient: Option<f64>,
    #[serde(default)]
    pub crowned_fraction: Option<f64>,
}

/// `scenes[].misalignment`: the disc's tilt against the housing, mrad.
#[derive(Debug, Deserialize, Clone, Copy)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys about_x_mrad, about_y_mrad"
)]
pub(crate) struct RawMisalignment {
    #[serde(default)]
    pub about_x_mrad: f64,
    #[serde(default)]
    pub about_y_mrad: f64,
}

#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a scene: a mapping with the keys name, crank, effects (and optionally output_torque_nm, ...)"
)]
pub(crate) struct RawScene {
    pub name: String,
    #[serde(default)]
    pub output_torque_nm: Option<f64>,
    /// Torsion under a locked input: the torque loop at each crank angle.
    #[serde(default)]
    pub torque_sweep: Option<RawTorqueSweep>,
    #[serde(default)]
    pub input_speed_rpm: Option<f64>,
    pub crank: RawCrank,
    pub effects: Vec<String>,
    #[serde(default)]
    pub contact_law: Option<String>,
    #[serde(default)]
    pub geometry: Option<String>,
    #[serde(default)]
    pub bearing_stiffness_n_per_mm: Option<f64>,
    #[serde(default)]
    pub misalignment: Option<RawMisalignment>,
    #[serde(default)]
    pub face_slices: Option<i64>,
    /// A duty cycle in place of the scene's own torque and speed.
    #[serde(default)]
    pub duty_cycle: Option<Vec<RawDutyBin>>,
}

/// One bin of `scenes[].duty_cycle`.
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a duty-cycle bin: a mapping with the keys output_torque_nm, input_speed_rpm, time_share"
)]
pub(crate) struct RawDutyBin {
    pub output_torque_nm: f64,
    pub input_speed_rpm: f64,
    pub time_share: f64,
}

#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys rated_nm, steps"
)]
pub(crate) struct RawTorqueSweep {
    pub rated_nm: f64,
    pub steps: i64,
}

#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys from_deg, to_deg, steps"
)]
pub(crate) struct RawCrank {
    pub from_deg: f64,
    pub to_deg: f64,
    pub steps: i64,
}

/// `limits:`, a mapping of limit keys (`min_clearance_mm`, ...; the registry's
/// `quantity::LIMITS`, `optimum_max_objective` and the flag `accuracy_resolved`) to values;
/// unknown keys are refused when the spec is validated, with the closest known key.
pub(crate) type RawLimits = std::collections::BTreeMap<String, RawLimit>;

/// A limit's value: a bound, or a flag (`accuracy_resolved: true`).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(untagged)]
pub(crate) enum RawLimit {
    Bound(f64),
    Flag(bool),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGolden {
    pub scene: String,
    pub quantity: String,
    /// With several discs, the disc whose curve this is (0-based).
    #[serde(default)]
    pub disc: Option<i64>,
    /// CSV path, relative to the directory of the spec file.
    pub file: String,
    pub tolerance: RawTolerance,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawTolerance {
    /// Absolute band, in the quantity's unit.
    #[serde(default)]
    pub abs: f64,
    /// Relative band, a fraction of the golden value.
    #[serde(default)]
    pub rel: f64,
}

/// `accuracy:`: run one scene on a ladder of settings (see `crate::engine::accuracy`).
#[derive(Debug, Deserialize)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the key scene (and optionally finest_steps_per_period, settings_steps_per_period, tolerance)"
)]
pub(crate) struct RawAccuracy {
    pub scene: String,
    /// Crank steps per mesh period of the reference run (12·2^k).
    #[serde(default)]
    pub finest_steps_per_period: Option<i64>,
    /// Steps per mesh period of the rungs that vary one setting.
    #[serde(default)]
    pub settings_steps_per_period: Option<i64>,
    #[serde(default)]
    pub tolerance: RawAccuracyTolerance,
}

/// Tolerances a rung must meet against the reference, in the units of the key names.
#[derive(Debug, Deserialize, Default)]
#[serde(
    deny_unknown_fields,
    expecting = "a mapping with the keys te_arcsec, force_n, ratio, clearance_um, \
                 face_load_factor, line_load_n_per_mm"
)]
pub(crate) struct RawAccuracyTolerance {
    pub te_arcsec: Option<f64>,
    pub force_n: Option<f64>,
    pub ratio: Option<f64>,
    pub clearance_um: Option<f64>,
    pub face_load_factor: Option<f64>,
    pub line_load_n_per_mm: Option<f64>,
}

fn one_disc() -> i64 {
    1
}
