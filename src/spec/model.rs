//! The validated spec: engine units (mm, N, N·mm, rad, MPa), every value checked.
//! Built from `raw` by `spec::load`; nothing downstream re-validates user input.

use crate::scene::Effect;

/// Elastic material of one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    pub youngs_modulus_mpa: f64,
    pub poisson_ratio: f64,
}

impl Material {
    /// Compliance term (1 − ν²)/E in 1/MPa.
    pub fn compliance_per_mpa(&self) -> f64 {
        (1.0 - self.poisson_ratio * self.poisson_ratio) / self.youngs_modulus_mpa
    }
}

/// Output mechanism: pins on the output flange, running in holes of the disc.
/// A hole's radius is `pin_radius_mm + e + hole_clearance_mm` (ideal pin-in-hole plus clearance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutputPins {
    pub count: usize,
    pub circle_radius_mm: f64,
    pub pin_radius_mm: f64,
    pub hole_clearance_mm: f64,
}

/// Reducer geometry (MODEL.md "Paper design"): one disc, `rollers = teeth + 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    pub teeth: usize,
    pub rollers: usize,
    pub eccentricity_mm: f64,
    pub roller_circle_radius_mm: f64,
    pub roller_radius_mm: f64,
    pub face_width_mm: f64,
    pub pins: OutputPins,
    pub disc_material: Material,
    pub roller_material: Material,
}

impl Design {
    /// Short-amplitude coefficient K1 = e·np/Rp (MODEL.md); a disc exists only for K1 < 1.
    pub fn k1(&self) -> f64 {
        self.eccentricity_mm * self.rollers as f64 / self.roller_circle_radius_mm
    }

    /// Contact modulus E* = 1 / ((1−ν1²)/E1 + (1−ν2²)/E2) in MPa (paper Eq. 10).
    pub fn contact_modulus_mpa(&self) -> f64 {
        1.0 / (self.disc_material.compliance_per_mpa() + self.roller_material.compliance_per_mpa())
    }

    /// Angular position of roller i in the fixed frame: 2πi/np.
    pub fn roller_angle(&self, i: usize) -> f64 {
        std::f64::consts::TAU * i as f64 / self.rollers as f64
    }

    /// Mesh period in crank angle: 2π/np.
    pub fn mesh_period_rad(&self) -> f64 {
        std::f64::consts::TAU / self.rollers as f64
    }

    /// Period of the output-pin pattern in crank angle, 2π·nc/(np·M): a pin's arm depends on
    /// γj − φ = 2πj/M − φ·np/nc, and the pattern repeats when that advances by 2π/M.
    pub fn pin_period_rad(&self) -> f64 {
        std::f64::consts::TAU * self.teeth as f64 / (self.rollers * self.pins.count) as f64
    }

    /// Crank period of loaded curves: the mesh period 2π/np, or, with the output pins modelled,
    /// the least common multiple of it and the pin period, (2π/np)·nc/gcd(nc, M) (108° for the
    /// paper's design: TE = β + βo, pin and bearing forces repeat only after it).
    pub fn loaded_period_rad(&self, pins_modelled: bool) -> f64 {
        if !pins_modelled {
            return self.mesh_period_rad();
        }
        let (mut a, mut b) = (self.teeth, self.pins.count);
        while b != 0 {
            (a, b) = (b, a % b);
        }
        self.mesh_period_rad() * (self.teeth / a) as f64
    }

    /// Radius of an output-pin hole in the disc: pin radius + e + hole clearance.
    pub fn hole_radius_mm(&self) -> f64 {
        self.pins.pin_radius_mm + self.eccentricity_mm + self.pins.hole_clearance_mm
    }
}

/// Tooth-profile modification (MODEL.md "Profile").
/// `shift_mm` = ΔRp (+ thicker teeth), `equidistant_mm` = ΔRrp (+ thinner teeth),
/// `rotation_rad` = Δδ, the profile turned counter-clockwise about the disc centre.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Modification {
    pub shift_mm: f64,
    pub equidistant_mm: f64,
    pub rotation_rad: f64,
}

impl Modification {
    /// Normal gap at tooth tip and root, ΔRrp − ΔRp (paper Eq. 8's left side).
    pub fn tip_clearance_mm(&self) -> f64 {
        self.equidistant_mm - self.shift_mm
    }
}

/// Force–approach law of a line contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactLaw {
    /// F = (π/4)·E*·L·d, the paper's Eq. 9.
    PaperLinear,
    /// Johnson's logarithmic line-contact compliance (see `contact::law`).
    HertzNonlinear,
}

/// How gaps and moment arms are evaluated under load.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GeometryMode {
    /// Closest point on the exact profile at the loaded pose.
    Exact,
    /// Closed-form first-order gaps and arms of MODEL.md.
    FirstOrder,
}

/// One load case swept over crank angle.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub name: String,
    /// Torque on the disc, N·mm (spec: `output_torque_nm`).
    pub output_torque_nmm: f64,
    /// Crank angles φ in rad: `from + k·(to − from)/steps`, k = 0..steps (end excluded).
    pub crank_rad: Vec<f64>,
    /// The crank range as written (`crank.from_deg`, `crank.to_deg`), degrees.
    pub crank_from_deg: f64,
    pub crank_to_deg: f64,
    /// Effects as the spec asks for them; `scene::Plan` adds what they need.
    pub effects: Vec<Effect>,
    pub contact_law: ContactLaw,
    pub geometry: GeometryMode,
    /// Radial stiffness of the crank bearing, N/mm; `None` is a rigid bearing.
    pub bearing_stiffness_n_per_mm: Option<f64>,
}

impl Scene {
    /// True when the sweep covers a whole number of mesh periods (so unloaded curves wrap).
    pub fn spans_whole_periods(&self, design: &Design) -> bool {
        self.spans_whole(design.mesh_period_rad())
    }

    /// True when the sweep covers a whole number of `period_rad` (so its curves wrap around).
    pub fn spans_whole(&self, period_rad: f64) -> bool {
        let n = self.crank_rad.len();
        if n < 2 {
            return false;
        }
        let step = self.crank_rad[1] - self.crank_rad[0];
        let span = step * n as f64 / period_rad;
        (span - span.round()).abs() < 1e-9 && span.round() >= 1.0
    }
}

/// Acceptance limits; each applies to every scene that computes its quantity.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Limits {
    pub min_clearance_mm: Option<f64>,
    pub max_roller_force_n: Option<f64>,
    pub max_pin_force_n: Option<f64>,
    pub max_bearing_force_n: Option<f64>,
    pub max_contact_pressure_mpa: Option<f64>,
    pub max_te_fluctuation_arcsec: Option<f64>,
    pub max_ratio_fluctuation: Option<f64>,
    pub min_rollers_in_contact: Option<usize>,
    pub optimum_max_objective: Option<f64>,
}

/// A validated spec, with the text it came from (for error locations and hashing).
#[derive(Debug, Clone)]
pub struct Spec {
    pub name: String,
    pub path: String,
    pub source: String,
    pub design: Design,
    pub modification: Modification,
    pub scenes: Vec<Scene>,
    pub limits: Limits,
    pub studies: Vec<Study>,
    pub golden: Vec<Golden>,
    /// The accuracy ladder the design review shows (`accuracy:`), if asked for.
    pub accuracy: Option<Accuracy>,
}

/// `accuracy:` of a spec: which scene's ladder the design review shows, and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Accuracy {
    /// Index into `Spec::scenes`.
    pub scene: usize,
    pub options: crate::accuracy::Options,
}

/// A quantity an optimisation can minimise. Each is a scalar of one scene's sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Objective {
    /// κmax − κmin (paper Eq. 18), dimensionless.
    RatioFluctuation,
    /// δmax − δmin of the loaded TE (paper Eqs. 22–23), arcsec.
    TeFluctuation,
    /// Largest roller force, N.
    MaxRollerForce,
    /// Largest lost motion over the sweep, arcsec.
    LostMotion,
    /// Largest crank-bearing force, N.
    MaxBearingForce,
}

impl Objective {
    pub const ALL: [Objective; 5] = [
        Objective::RatioFluctuation,
        Objective::TeFluctuation,
        Objective::MaxRollerForce,
        Objective::LostMotion,
        Objective::MaxBearingForce,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Objective::RatioFluctuation => "ratio_fluctuation",
            Objective::TeFluctuation => "te_fluctuation",
            Objective::MaxRollerForce => "max_roller_force",
            Objective::LostMotion => "lost_motion",
            Objective::MaxBearingForce => "max_bearing_force",
        }
    }

    pub fn unit(self) -> &'static str {
        match self {
            Objective::RatioFluctuation => "",
            Objective::TeFluctuation | Objective::LostMotion => "arcsec",
            Objective::MaxRollerForce | Objective::MaxBearingForce => "N",
        }
    }

    pub fn from_name(name: &str) -> Option<Objective> {
        Objective::ALL.into_iter().find(|o| o.name() == name)
    }
}

/// A design variable of a study, bounds in engine units (mm, or rad for the rotation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VariableKind {
    Shift,
    Equidistant,
    Rotation,
}

impl VariableKind {
    pub fn key(self) -> &'static str {
        match self {
            VariableKind::Shift => "shift_mm",
            VariableKind::Equidistant => "equidistant_mm",
            VariableKind::Rotation => "rotation_deg",
        }
    }

    /// The value of this variable in a modification, engine units.
    pub fn get(self, m: &Modification) -> f64 {
        match self {
            VariableKind::Shift => m.shift_mm,
            VariableKind::Equidistant => m.equidistant_mm,
            VariableKind::Rotation => m.rotation_rad,
        }
    }

    pub fn set(self, m: &mut Modification, value: f64) {
        match self {
            VariableKind::Shift => m.shift_mm = value,
            VariableKind::Equidistant => m.equidistant_mm = value,
            VariableKind::Rotation => m.rotation_rad = value,
        }
    }

    /// Engine value to the spec's unit (mm stay mm, rad become degrees).
    pub fn to_spec_unit(self, value: f64) -> f64 {
        match self {
            VariableKind::Rotation => value.to_degrees(),
            _ => value,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Variable {
    pub kind: VariableKind,
    pub lower: f64,
    pub upper: f64,
}

/// One optimisation study (paper §4): minimise a (weighted) objective of one scene over the
/// modification variables, subject to the tip clearance band (paper Eqs. 8, 21) and the
/// whole-mesh minimum clearance, checked on the exact geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    pub name: String,
    /// Index into `Spec::scenes`.
    pub scene: usize,
    /// Weighted terms; a single objective has weight 1.
    pub objective: Vec<(Objective, f64)>,
    pub variables: Vec<Variable>,
    /// The starting modification (variables not optimised keep the spec's values).
    pub start: Modification,
    /// ΔRrp − ΔRp ∈ [lower, upper], mm.
    pub tip_clearance_mm: Option<(f64, f64)>,
    /// Whole-mesh minimum clearance ≥ this, mm.
    pub min_clearance_mm: Option<f64>,
    pub references: Vec<(String, Modification)>,
    pub optimum_max_objective: Option<f64>,
    pub global_samples: usize,
    pub local_evaluations: usize,
}

/// Allowed deviation from a golden value g: |value − g| ≤ abs + rel·|g|.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    pub abs: f64,
    pub rel: f64,
}

impl Tolerance {
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
    pub scene: String,
    /// Key of a per-angle quantity (`crate::quantity::QUANTITIES`).
    pub quantity: &'static str,
    /// The path as written in the spec.
    pub file: String,
    /// The path resolved against the spec file's directory (lexically normalised).
    pub path: std::path::PathBuf,
    pub tolerance: Tolerance,
}
