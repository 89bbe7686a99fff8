//! What a reducer must do, for `cycloid design`: the ratio, torques and speed, the envelope, the
//! materials, the design rules, the limits of a spec, the objectives to trade and the space the
//! search covers. Plain data in engine units (mm, N, N·mm); `spec::requirements` builds it.

use super::design::{CrankBearing, Material, PinSupport};
use super::limits::Limits;
use super::strength::Strength;
use super::{Crowning, DutyBin, Effect, Friction, Misalignment, Thermal};

/// Crank period of the loaded curves of a search's design with `teeth` nc, np = nc + 1 rollers
/// and `pins` M, in mesh periods of 2π/np (M units of `design::pinned_period_units`):
/// nc/gcd(nc, M), the least common multiple of the mesh and pin periods as
/// `Design::loaded_period_rad` has it (M ≥ 1); `tilted` (the requirements' `misalignment`),
/// np times that (the mesh then repeats only after a whole crank turn, `model::period`).
pub fn loaded_mesh_periods(teeth: usize, pins: usize, tilted: bool) -> usize {
    let rollers = teeth + 1;
    let per_turn = if tilted { 1 } else { rollers };
    super::design::pinned_period_units(rollers, pins, teeth, per_turn) / pins
}

/// A continuous variable of the search: its spec key and its closed range, mm (lower = upper
/// fixes it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Lower end, in the variable's unit.
    pub lower: f64,
    /// Upper end, in the variable's unit.
    pub upper: f64,
}

impl Range {
    /// The value at `u` in [0, 1]: lower + u·(upper − lower).
    pub fn at(&self, u: f64) -> f64 {
        self.lower + u * (self.upper - self.lower)
    }

    /// The range is a single value.
    pub fn fixed(&self) -> bool {
        self.lower == self.upper
    }
}

/// The eight continuous variables of the search, in this order (`KEYS`): a design's values
/// (`Variables<f64>`, mm) or the search's ranges of them (`Continuous`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variables<T> {
    /// e, mm.
    pub eccentricity_mm: T,
    /// Rp, mm.
    pub roller_circle_radius_mm: T,
    /// Rrp, mm.
    pub roller_radius_mm: T,
    /// B, mm.
    pub face_width_mm: T,
    /// rw, mm.
    pub pin_circle_radius_mm: T,
    /// The output pins' radius, mm.
    pub pin_radius_mm: T,
    /// ΔRp, mm.
    pub shift_mm: T,
    /// ΔRrp, mm.
    pub equidistant_mm: T,
}

/// The ranges of the search's continuous variables (`search:`).
pub type Continuous = Variables<Range>;

impl<T: Copy> Variables<T> {
    /// The keys under `search:`, in the order of `to_array`.
    pub const KEYS: [&'static str; 8] = [
        "eccentricity_mm",
        "roller_circle_radius_mm",
        "roller_radius_mm",
        "face_width_mm",
        "pin_circle_radius_mm",
        "pin_radius_mm",
        "shift_mm",
        "equidistant_mm",
    ];

    /// From a vector in the order of `KEYS` (the Sobol points, the pattern search and the
    /// shard files see the variables as one vector, through this and `to_array` only).
    pub fn from_array(x: [T; 8]) -> Self {
        let [eccentricity_mm, roller_circle_radius_mm, roller_radius_mm, face_width_mm, pin_circle_radius_mm, pin_radius_mm, shift_mm, equidistant_mm] =
            x;
        Variables {
            eccentricity_mm,
            roller_circle_radius_mm,
            roller_radius_mm,
            face_width_mm,
            pin_circle_radius_mm,
            pin_radius_mm,
            shift_mm,
            equidistant_mm,
        }
    }

    /// The vector in the order of `KEYS`.
    pub fn to_array(&self) -> [T; 8] {
        [
            self.eccentricity_mm,
            self.roller_circle_radius_mm,
            self.roller_radius_mm,
            self.face_width_mm,
            self.pin_circle_radius_mm,
            self.pin_radius_mm,
            self.shift_mm,
            self.equidistant_mm,
        ]
    }
}

/// The design space and how it is searched.
#[derive(Debug, Clone, PartialEq)]
pub struct Search {
    /// The continuous variables' ranges.
    pub continuous: Continuous,
    /// Output-pin counts M tried.
    pub pin_counts: Vec<usize>,
    /// Numbers of discs tried.
    pub discs: Vec<usize>,
    /// Hole clearance of every design, mm.
    pub hole_clearance_mm: f64,
    /// Scrambled-Sobol points per discrete choice (ratio × pin count × discs).
    pub samples: usize,
    /// Scrambling seed: the same seed gives the same front.
    pub seed: u32,
    /// Full checks each front design may spend on its local refinement.
    pub refine_budget: usize,
    /// Crank angles per mesh period (360°/np) of the scenes of a full check; the screen uses a
    /// quarter of them (a subset).
    pub steps_per_mesh_period: usize,
}

/// Design rules beyond the spec's own (`spec::rules`), checked before any physics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignRules {
    /// K1 = e·np/Rp must not exceed this (the spec's rule: below 1).
    pub max_k1: f64,
    /// Smallest ligament, mm: between neighbouring pin holes (2·rw·sin(π/M) − 2·rh), between a
    /// hole and the tooth root (Rp + ΔRp − e − (Rrp + ΔRrp) − rw − rh) and between a hole and the
    /// disc centre (rw − rh); rh = pin radius + e + hole clearance.
    pub min_ligament_mm: f64,
    /// Smallest gap between neighbouring rollers, mm: 2·Rp·sin(π/np) − 2·Rrp.
    pub min_roller_gap_mm: f64,
}

/// The envelope: what the reducer may occupy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Envelope {
    /// Largest outer diameter, mm: 2·(Rp + Rrp + housing wall).
    pub max_outer_diameter_mm: f64,
    /// Largest axial length, mm: discs·B + axial allowance.
    pub max_axial_length_mm: f64,
    /// The housing's wall beyond the rollers, mm.
    pub housing_wall_mm: f64,
    /// Axial length besides the discs (bearings, covers), mm.
    pub axial_allowance_mm: f64,
}

/// An objective to trade: what it measures and which way is better.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObjectiveKind {
    /// 2·(Rp + Rrp + housing wall), mm (smaller).
    OuterDiameter,
    /// discs·B + axial allowance, mm (smaller).
    AxialLength,
    /// The mass estimate, kg (smaller): see `engine::design_search::figures::mass_kg`.
    Mass,
    /// The largest Hertz pressure over the rated and peak scenes, MPa (smaller).
    ContactPressure,
    /// The TE fluctuation of the rated scene, arcsec (smaller).
    TeFluctuation,
    /// The unloaded lost motion of the mesh scene, arcsec (smaller).
    LostMotion,
    /// The crank-bearing rating life at rated torque and speed, or with a duty cycle the
    /// cycle's (Palmgren–Miner, `engine::duty_cycle`), h (larger).
    BearingLife,
    /// The torsional rigidity of the torsion scene, N·m/arcmin (larger).
    Rigidity,
    /// The mean efficiency P_out/(P_out + mean loss) of the rated scene, or with a duty cycle
    /// the cycle's, weighted by energy Σ sᵢ·P_out,i / Σ sᵢ·(P_out,i + lossᵢ) (larger; needs
    /// `friction`).
    Efficiency,
}

named!(ObjectiveKind "objective" {
    OuterDiameter => "outer_diameter_mm",
    AxialLength => "axial_length_mm",
    Mass => "mass_kg",
    ContactPressure => "max_contact_pressure_mpa",
    TeFluctuation => "te_fluctuation_arcsec",
    LostMotion => "max_lost_motion_arcsec",
    BearingLife => "bearing_life_h",
    Rigidity => "torsional_rigidity_nm_per_arcmin",
    Efficiency => "efficiency",
});

impl ObjectiveKind {
    /// Larger is better.
    pub fn maximise(self) -> bool {
        matches!(
            self,
            ObjectiveKind::BearingLife | ObjectiveKind::Rigidity | ObjectiveKind::Efficiency
        )
    }
}

/// A requirements file, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct Requirements {
    /// Name of the requirements, the front's specs are named after it.
    pub name: String,
    /// Acceptable ratios: the disc's teeth nc (rollers nc + 1, output from the disc's pins).
    pub ratios: Vec<usize>,
    /// Rated output torque, N·mm.
    pub rated_torque_nmm: f64,
    /// Peak output torque, N·mm (≥ rated).
    pub peak_torque_nmm: f64,
    /// Input speed of the rated scene, rpm.
    pub input_speed_rpm: Option<f64>,
    /// A duty cycle in place of the input speed: the bins of the candidates' `duty` scene
    /// (torques N·mm, speeds rpm, shares summing to 1).
    pub duty_cycle: Option<Vec<DutyBin>>,
    /// Friction of every candidate (the keys of a spec's `reducer.friction`): its rated scene
    /// (and duty scene) computes the efficiency.
    pub friction: Option<Friction>,
    /// The housing's heat path of every candidate (the keys of a spec's `reducer.thermal`):
    /// with `friction` and `input_speed_rpm` its rated scene computes the steady temperature
    /// ambient + P_loss/(h·A), °C.
    pub thermal: Option<Thermal>,
    /// The crowning of every candidate's discs (the keys of a spec's `modification.crowning`;
    /// `Crowning::None` when not given). A circular crown's flat middle must lie inside each
    /// candidate's face, start < B/2: a design rule (`design_search::rules`).
    pub crowning: Crowning,
    /// The disc's tilt against the housing in the loaded running scenes (rated, peak, duty),
    /// rad (`misalignment`, mrad; zero when not given).
    pub misalignment: Misalignment,
    /// Slices of the face width of every loaded scene (`face_slices`; 1, the 2-D model, when not
    /// given).
    pub face_slices: usize,
    /// What the reducer may occupy.
    pub envelope: Envelope,
    /// Disc, rollers and pins.
    pub material: Material,
    /// Density of every part, kg/mm³.
    pub density_kg_per_mm3: f64,
    /// The rollers' and pins' material (`roller_material`), when not the disc's.
    pub roller_material: Option<Material>,
    /// What the disc's and the rollers' materials bear (`material`, `roller_material`: yield
    /// strength, contact fatigue), for the strength limits.
    pub strength: Strength,
    /// The output pins as beams of every candidate (`output_pins.support`), for their bending
    /// and its stress; none: rigid pins.
    pub pin_support: Option<PinSupport>,
    /// The crank bearing, when its life or static safety is asked for.
    pub crank_bearing: Option<CrankBearing>,
    /// Rules checked before any physics.
    pub rules: DesignRules,
    /// The acceptance limits of a spec.
    pub limits: Limits,
    /// Two or three objectives.
    pub objectives: Vec<ObjectiveKind>,
    /// The design space and how it is searched.
    pub search: Search,
}

impl Requirements {
    /// A strength limit is set: the running scenes compute `strength` (issue 41).
    pub fn needs_strength(&self) -> bool {
        self.limits_effect(Effect::Strength)
    }

    /// The torsion scene is needed (a rigidity objective, or a limit on a torsion figure).
    pub fn needs_torsion(&self) -> bool {
        self.objectives.contains(&ObjectiveKind::Rigidity) || self.limits_effect(Effect::Torsion)
    }

    /// A limit bounds a quantity of `effect`.
    fn limits_effect(&self, effect: Effect) -> bool {
        (self.limits.entries.iter()).any(|l| l.def.quantity.effect == effect)
    }
}
