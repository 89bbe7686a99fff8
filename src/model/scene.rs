//! A load scene: the crank range, the torque, the effects it asks for and how they are
//! computed; and the plan of the effects that run for it.
//!
//! The plan follows the scene: an effect is computed when the scene asks for it or when an
//! effect it asked for cannot be computed without it. Limits never add effects: a limit is
//! checked in the scenes that compute its quantity, and a limit that no scene can evaluate is an
//! error. Within a planned effect, a costly detail that only some of its quantities need (the
//! closing lags of `clearance`) is computed only when a limit, golden, objective or output reads
//! one of those quantities (`Plan::ask`).

use super::design::Design;
use super::effect::{Detail, Effect};
use super::quantity::Quantity;

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

named!(ContactLaw "contact law" {
    PaperLinear => "paper_linear",
    HertzNonlinear => "hertz_nonlinear",
});

named!(GeometryMode "geometry mode" {
    Exact => "exact",
    FirstOrder => "first_order",
});

/// Largest rollers × crank angles of one scene: every per-roller, per-angle array of the results
/// must fit in memory (10⁷ f64 are 80 MB).
pub const MAX_ROLLER_ANGLES: i64 = 10_000_000;

/// One load case swept over crank angle.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The scene's name (`scenes[].name`), unique in its spec.
    pub name: String,
    /// Output torque T, N·mm (spec: `output_torque_nm`; 0 when not given): the torque on the
    /// disc, or shared by the discs when there are several (Σ Tk = T).
    pub output_torque_nmm: f64,
    /// Crank angles φ in rad: `from + k·(to − from)/steps`, k = 0..steps (end excluded).
    pub crank_rad: Vec<f64>,
    /// The start of the crank range as written (`crank.from_deg`), degrees.
    pub crank_from_deg: f64,
    /// The end of the crank range as written (`crank.to_deg`, excluded), degrees.
    pub crank_to_deg: f64,
    /// Effects as the spec asks for them; `Plan` adds what they need.
    pub effects: Vec<Effect>,
    /// The force–approach law of the contacts (`contact_law`; `paper_linear` by default).
    pub contact_law: ContactLaw,
    /// How gaps and arms are evaluated under load (`geometry`; `exact` by default).
    pub geometry: GeometryMode,
    /// Radial stiffness of the crank bearing, N/mm; `None` is a rigid bearing.
    pub bearing_stiffness_n_per_mm: Option<f64>,
    /// Torsion under a locked input at each crank angle (spec: `torque_sweep`); such a scene
    /// has no output torque of its own and no loaded curves over the crank angle.
    pub torque_sweep: Option<TorqueSweep>,
    /// Input (crank) speed, rpm (spec: `input_speed_rpm`): the speed of the crank-bearing
    /// rating life.
    pub input_speed_rpm: Option<f64>,
    /// The contacts along the face width: the disc's crowning (the design's
    /// `modification.crowning`), this scene's tilt (`misalignment`) and slices
    /// (`face_slices`); the default is the 2-D model.
    pub face: super::face::Face,
    /// A duty cycle (spec: `duty_cycle`) in place of the scene's own torque and speed: each
    /// bin runs as this scene loaded at its torque and speed (`engine::duty_cycle`); `None`
    /// for an ordinary scene.
    pub duty_cycle: Option<Vec<DutyBin>>,
}

/// One bin of a duty cycle (spec: `scenes[].duty_cycle[]`): the reducer runs at this output
/// torque and input speed for this share of the time. The shares of a cycle sum to 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DutyBin {
    /// Output torque T_i, N·mm (spec: `output_torque_nm`), as a scene's `output_torque_nmm`.
    pub output_torque_nmm: f64,
    /// Input (crank) speed n_i, rpm (spec: `input_speed_rpm`), ≥ 0; 0 is a standstill,
    /// which turns nothing and wears the bearing by no revolution.
    pub input_speed_rpm: f64,
    /// The share of the time spent in this bin, in [0, 1] (spec: `time_share`).
    pub time_share: f64,
}

impl DutyBin {
    /// sᵢ·nᵢ, rpm: the bin's weight in the cycle's revolutions (its time share times its input
    /// speed; 0 at a standstill).
    pub fn revolution_weight_rpm(&self) -> f64 {
        self.time_share * self.input_speed_rpm
    }

    /// The scene bin `j` runs as: `scene` at the bin's torque and speed (no speed at a
    /// standstill: no life in hours, no watts), without the cycle, named `<scene> bin j`.
    pub fn scene(&self, scene: &Scene, j: usize) -> Scene {
        Scene {
            name: format!("{} bin {j}", scene.name),
            output_torque_nmm: self.output_torque_nmm,
            input_speed_rpm: (self.input_speed_rpm > 0.0).then_some(self.input_speed_rpm),
            duty_cycle: None,
            ..scene.clone()
        }
    }
}

/// The torque loop of a torsion scene (spec: `torque_sweep: {rated_nm, steps}`): at each
/// locked crank angle the output torque goes −rated → +rated → −rated in `steps` intervals
/// per quarter of the loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorqueSweep {
    /// Rated torque, N·mm (spec: `rated_nm`).
    pub rated_nmm: f64,
    /// Intervals per quarter of the loop (≥ 1).
    pub steps: usize,
}

impl TorqueSweep {
    /// The loop's torques, N·mm: T_m for m = 0 ..= 4·steps, from −rated up to +rated (2·steps
    /// intervals) and back down to −rated. T_steps and T_3·steps are exactly 0.
    pub fn torques_nmm(&self) -> Vec<f64> {
        let s = self.steps as i64;
        (0..=4 * s)
            .map(|m| {
                // Distance from the loop's top, in steps: the torque is linear in it.
                let up = if m <= 2 * s { m - s } else { 3 * s - m };
                self.rated_nmm * up as f64 / s as f64
            })
            .collect()
    }
}

impl Scene {
    /// Why `what` (a study, the accuracy ladder) cannot run this scene when it is a torsion
    /// scene: it has no loaded curves over the crank angle.
    pub fn torsion_refusal(&self, what: &str) -> Option<String> {
        self.torque_sweep.is_some().then(|| {
            format!(
                "scene `{}` is a torsion scene (`torque_sweep`): {what} needs a scene loaded \
                 over the crank angle (`output_torque_nm`)",
                self.name
            )
        })
    }

    /// Runs at a speed: its own `input_speed_rpm`, or a duty cycle's bins, each with theirs.
    /// A figure in hours or a centripetal force needs it.
    pub fn has_speed(&self) -> bool {
        self.input_speed_rpm.is_some() || self.duty_cycle.is_some()
    }

    /// Computes roller contact in one run at one torque (a duty cycle's runs once per bin):
    /// the scene the accuracy ladder runs and the disc drawing solves by default.
    pub fn loaded_once(&self) -> bool {
        Plan::for_scene(self).computes(Effect::RollerContact) && self.duty_cycle.is_none()
    }

    /// True when the sweep covers a whole number of the periods of the reducer as run
    /// (`Scene::run_period_rad`, this scene's tilt included): its loaded curves wrap, and a
    /// mean or an extreme over it is one over whole load cycles.
    pub fn spans_loaded_periods(&self, design: &Design, plan: &Plan) -> bool {
        self.spans_whole(self.run_period_rad(design, plan))
    }

    /// The crank period of this scene's loaded curves under `plan` on the reducer `design` as
    /// built, rad (`Design::loaded_period_rad`, with the pins when the plan models them, tilted
    /// when `period::tilted`): the one period of the reducer as run that every consumer reads.
    pub fn run_period_rad(&self, design: &Design, plan: &Plan) -> f64 {
        let tilted = super::period::tilted(design, &self.face);
        design.loaded_period_rad(plan.has(Effect::OutputPins), tilted)
    }

    /// True when the sweep covers a whole number of `period_rad` (so its curves wrap around);
    /// never with fewer than two angles (no step, `numeric::step`: no span).
    pub fn spans_whole(&self, period_rad: f64) -> bool {
        let n = self.crank_rad.len();
        let span = crate::numeric::step(&self.crank_rad) * n as f64 / period_rad;
        (span - span.round()).abs() < 1e-9 && span.round() >= 1.0
    }
}

/// One effect in a plan, with the reason it is there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlannedEffect {
    /// The effect.
    pub effect: Effect,
    /// Why it is planned ("asked for by the scene", "needed by bearing", ...).
    pub reason: String,
}

/// A detail in a plan, with what reads it ("limit max_lost_motion_arcsec", "--json").
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlannedDetail {
    /// The detail.
    pub detail: Detail,
    /// What reads it, each named once, in the order they asked.
    pub read_by: Vec<String>,
}

/// What will be computed for one scene.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Plan {
    /// The name of the scene it is for.
    pub scene: String,
    /// The effects computed, each once, in `Effect`'s order.
    pub effects: Vec<PlannedEffect>,
    /// The details of planned effects that something reads (none unless asked: `Plan::ask`).
    pub details: Vec<PlannedDetail>,
    /// The scene runs a duty cycle (`Scene::duty_cycle`): its quantities are the cycle's
    /// (`Quantity::for_duty`), each bin's in its own result.
    pub duty: bool,
}

impl Plan {
    /// The plan of `scene`: the effects it asks for (and `torsion` for a `torque_sweep`) and
    /// what they need; no details until something asks (`Plan::ask`).
    pub fn for_scene(scene: &Scene) -> Plan {
        let sweep =
            (scene.torque_sweep.as_ref()).map(|_| (Effect::Torsion, "asked for by torque_sweep"));
        let asked = scene.effects.iter().map(|&e| (e, "asked for by the scene"));
        Plan {
            duty: scene.duty_cycle.is_some(),
            ..Plan::asked(&scene.name, sweep.into_iter().chain(asked))
        }
    }

    /// The plan of `effects` and what they need, for the scene named `scene` (an
    /// optimisation candidate, a test).
    pub fn of(scene: &str, effects: &[Effect]) -> Plan {
        Plan::asked(scene, effects.iter().map(|&e| (e, "asked for")))
    }

    /// The plan with only the effects `keep` accepts (and their details).
    pub fn part(&self, keep: impl Fn(Effect) -> bool) -> Plan {
        Plan {
            duty: self.duty,
            scene: self.scene.clone(),
            effects: (self.effects.iter())
                .filter(|p| keep(p.effect))
                .cloned()
                .collect(),
            details: (self.details.iter())
                .filter(|p| keep(p.detail.effect()))
                .cloned()
                .collect(),
        }
    }

    /// The plan of the effects `asked`, each with why, and what they need, for the scene named
    /// `scene`: each effect once, in `Effect`'s order; no details, no duty cycle.
    fn asked(scene: &str, asked: impl Iterator<Item = (Effect, &'static str)>) -> Plan {
        let mut effects: Vec<PlannedEffect> = Vec::new();
        for (effect, why) in asked {
            add(&mut effects, effect, why.to_string());
        }
        effects.sort_by_key(|p| p.effect);
        Plan {
            scene: scene.to_string(),
            effects,
            details: Vec::new(),
            duty: false,
        }
    }

    /// Whether `effect` is planned (see `computes` for whether its quantities are computed).
    pub fn has(&self, effect: Effect) -> bool {
        self.effects.iter().any(|p| p.effect == effect)
    }

    /// Whether the quantities of `effect` are computed: it is planned, and it is not a loaded
    /// effect of a torsion scene (which solves the loaded model at each locked crank angle
    /// under its torque loop, not over the crank angle).
    pub fn computes(&self, effect: Effect) -> bool {
        self.has(effect) && !(effect.is_loaded() && self.has(Effect::Torsion))
    }

    /// Whether this plan computes `quantity`: its effect is computed, and the quantity is one
    /// that a scene of its kind has (a duty cycle's figures only in a duty-cycle scene, a
    /// single run's bearing life only outside one: `Quantity::for_duty`).
    pub fn computes_quantity(&self, quantity: &Quantity) -> bool {
        self.computes(quantity.effect) && quantity.for_duty().is_none_or(|d| d == self.duty)
    }

    /// `quantity` is read by `by` (a limit, a golden, an objective, an output): plan the detail
    /// it needs, if any, when the plan computes its effect. Never adds an effect.
    pub fn ask(&mut self, quantity: &Quantity, by: &str) {
        let Some(detail) = quantity.detail() else {
            return;
        };
        if !self.has(detail.effect()) {
            return;
        }
        match self.details.iter_mut().find(|p| p.detail == detail) {
            Some(p) if p.read_by.iter().any(|b| b == by) => {}
            Some(p) => p.read_by.push(by.to_string()),
            None => {
                self.details.push(PlannedDetail {
                    detail,
                    read_by: vec![by.to_string()],
                });
                self.details.sort_by_key(|p| p.detail);
            }
        }
    }

    /// Whether `detail` is planned: something reads a quantity that needs it.
    pub fn has_detail(&self, detail: Detail) -> bool {
        self.details.iter().any(|p| p.detail == detail)
    }
}

fn add(effects: &mut Vec<PlannedEffect>, effect: Effect, reason: String) {
    if effects.iter().any(|p| p.effect == effect) {
        return;
    }
    effects.push(PlannedEffect { effect, reason });
    for &need in effect.needs() {
        add(effects, need, format!("needed by {}", effect.name()));
    }
}
