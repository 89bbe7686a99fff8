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
    /// Effects as the spec asks for them; `scene::Plan` adds what they need.
    pub effects: Vec<Effect>,
    pub contact_law: ContactLaw,
    pub geometry: GeometryMode,
    /// Radial stiffness of the crank bearing, N/mm; `None` is a rigid bearing.
    pub bearing_stiffness_n_per_mm: Option<f64>,
}

impl Scene {
    /// True when the sweep covers a whole number of mesh periods (so curves wrap around).
    pub fn spans_whole_periods(&self, design: &Design) -> bool {
        let n = self.crank_rad.len();
        if n < 2 {
            return false;
        }
        let step = self.crank_rad[1] - self.crank_rad[0];
        let span = step * n as f64 / design.mesh_period_rad();
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
    pub golden: Vec<Golden>,
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
