//! The loaded model of a scene (`Model`: the rollers, pins and bearing it includes, the torque,
//! the solver's settings) and its equilibrium at one crank angle (`AngleSolution`).

pub use super::angle_solution::AngleSolution;
use super::coupling::Coupling;
use super::losses::LossModel;
use super::pins::Pins;
use super::rollers::Rollers;
use super::solve::Settings;
use crate::geometry::mass_properties::disc_mass;
use crate::geometry::Vec2;
use crate::model::{Design, Effect, Friction, GeometryMode, Modification, Plan, Scene};

/// What the loaded model of a scene includes.
#[derive(Debug, Clone)]
pub struct Model {
    pub rollers: Option<Rollers>,
    pub pins: Option<Pins>,
    pub bearing: bool,
    pub bearing_stiffness_n_per_mm: Option<f64>,
    pub torque_nmm: f64,
    pub teeth: usize,
    /// The crank's eccentricity as built, e + de, mm: the disc centre's orbit.
    pub eccentricity_mm: f64,
    pub settings: Settings,
    /// First-order geometry: the rollers' (`Rollers::geometry`, the scene's too) and the
    /// pins', which follow it (ideal directions, linear gaps), also without the rollers.
    pub first_order: bool,
    /// Friction inside the balance (the coupled model), when active; none: frictionless.
    pub coupling: Option<Coupling>,
    /// F_c = m·(e + de)·ω², N: the disc's centripetal force at the scene's speed
    /// (`Effect::Inertia`), which the crank bearing supplies along −e_φ on top of the
    /// contacts' (its centrifugal reaction, +F_c·e_φ, acts at the disc centre, so it moves no
    /// moment about it); 0 without the effect.
    pub centripetal_n: f64,
    /// Record each angle's friction losses and input torque (`LoadedSweep::losses`) for the
    /// effect `efficiency`; none: other scenes pay nothing.
    pub losses: Option<LossModel>,
}

impl Model {
    /// The loaded model of `scene` with the loaded effects of `plan` (roller contact, output
    /// pins, bearing); the crank bearing's compliance applies only with the bearing modelled.
    pub fn new(design: &Design, m: &Modification, scene: &Scene, plan: &Plan) -> Self {
        let (rollers, pins, bearing) = (
            plan.has(Effect::RollerContact),
            plan.has(Effect::OutputPins),
            plan.has(Effect::Bearing),
        );
        // The scene's face with the tilt as built (`reducer.deviations.misalignment`) added.
        let face = design.deviations.face(&scene.face);
        Model {
            rollers: rollers.then(|| {
                Rollers::new(design, m, scene.contact_law, scene.geometry).with_face(&face)
            }),
            pins: pins.then(|| Pins::new(design, scene.contact_law)),
            bearing,
            bearing_stiffness_n_per_mm: scene.bearing_stiffness_n_per_mm.filter(|_| bearing),
            torque_nmm: scene.output_torque_nmm,
            teeth: design.teeth,
            eccentricity_mm: design.built_eccentricity_mm(),
            settings: Settings::default(),
            first_order: scene.geometry == GeometryMode::FirstOrder,
            coupling: None,
            centripetal_n: centripetal_n(design, m, scene, plan),
            losses: None,
        }
    }

    /// The force the disc's inertia asks of its crank bearing at `e_phi`, N: the centrifugal
    /// reaction +F_c·e_φ, which the bearing's force balances with −F_c·e_φ.
    pub fn centrifugal_n(&self, e_phi: Vec2) -> Vec2 {
        e_phi * self.centripetal_n
    }

    /// This model with `friction` inside its balance (the coupled model,
    /// `coupling`); a friction whose every coefficient is zero leaves it frictionless.
    pub fn with_friction(mut self, friction: &Friction, design: &Design) -> Self {
        self.coupling = Some(Coupling::new(friction, design)).filter(Coupling::active);
        self
    }

    /// The lag at which the rollers sit in their mesh without load, to first order: a profile
    /// turned by Δδ (reduced to the tooth pitch) is a disc turned by Δδ, which the lag −Δδ
    /// undoes. The first guess of a sweep, so that a large rotation starts at its mesh.
    pub fn rest_lag(&self) -> f64 {
        self.rollers
            .as_ref()
            .map_or(0.0, |r| -r.mesh.profile.rotation_rad)
    }

    /// How far (crank angle, rad) the last solved angle may be for its lags and contact
    /// points to warm-start the next: a quarter of a mesh period, over which a foot moves by a
    /// fortieth of a tooth; a sweep's steps are far finer, a sweep of a few steps per turn is
    /// not warm-started.
    pub fn warm_reach(&self) -> f64 {
        std::f64::consts::FRAC_PI_2 / (self.teeth + 1) as f64
    }

    /// The friction inside the balance at this model's torque: none without friction, and none
    /// at zero torque in a running reducer, where only a preload loads the contacts and the
    /// frictionless balance answers (an efficiency scene at zero torque transmits nothing). A
    /// torsion loop's branch keeps its friction at every torque: a preload's contacts hold the
    /// disc there too.
    pub fn coupled(&self) -> Option<&Coupling> {
        self.coupling
            .as_ref()
            .filter(|c| self.torque_nmm != 0.0 || c.is_torsion())
    }
}

/// F_c of `Effect::Inertia` for `scene` (`DiscMass::centripetal_force_n` of the exact disc at
/// the crank's e + de and the scene's speed); 0 without the effect or without a speed (the
/// spec refuses `inertia` without one).
fn centripetal_n(design: &Design, m: &Modification, scene: &Scene, plan: &Plan) -> f64 {
    match scene.input_speed_rpm {
        Some(n) if plan.has(Effect::Inertia) => disc_mass(design, m)
            .centripetal_force_n(design.built_eccentricity_mm(), crate::units::rad_per_s(n)),
        _ => 0.0,
    }
}
