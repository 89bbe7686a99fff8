//! Which effects a scene needs, why, and the plan that runs exactly those.
//!
//! The plan follows the scene: an effect is computed when the scene asks for it or when an
//! effect it asked for cannot be computed without it. Limits never add work: a limit is checked
//! in the scenes that compute its quantity (`check`), and a limit that no scene can evaluate is
//! an error.

use crate::equilibrium::curves::{self, LoadedSweep};
use crate::equilibrium::solve::Settings;
use crate::equilibrium::sweep::Model;
use crate::error::{Error, Result};
use crate::geometry::clearance::{self, ClearanceSweep, Mesh};
use crate::spec::{ContactLaw, GeometryMode, Scene, Spec};

/// A physical effect a scene can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Effect {
    /// Unloaded gaps, backlash, unloaded TE, lost motion, minimum clearance.
    Clearance,
    /// Loaded lag, roller forces, contacts, Hertz pressure.
    RollerContact,
    /// Output-pin forces and pin deflection.
    OutputPins,
    /// Crank-bearing force from the force balance, equilibrium residuals.
    Bearing,
}

impl Effect {
    pub const ALL: [Effect; 4] = [
        Effect::Clearance,
        Effect::RollerContact,
        Effect::OutputPins,
        Effect::Bearing,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Effect::Clearance => "clearance",
            Effect::RollerContact => "roller_contact",
            Effect::OutputPins => "output_pins",
            Effect::Bearing => "bearing",
        }
    }

    pub fn from_name(name: &str) -> Option<Effect> {
        Effect::ALL.into_iter().find(|e| e.name() == name)
    }

    /// Effects this one cannot be computed without.
    pub fn needs(self) -> &'static [Effect] {
        match self {
            Effect::Bearing => &[Effect::RollerContact, Effect::OutputPins],
            _ => &[],
        }
    }
}

/// One effect in a plan, with the reason it is there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlannedEffect {
    pub effect: Effect,
    pub reason: String,
}

/// What will be computed for one scene.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Plan {
    pub scene: String,
    pub effects: Vec<PlannedEffect>,
}

impl Plan {
    pub fn for_scene(scene: &Scene) -> Plan {
        let mut effects: Vec<PlannedEffect> = Vec::new();
        for &asked in &scene.effects {
            add(&mut effects, asked, "asked for by the scene".to_string());
        }
        effects.sort_by_key(|p| p.effect);
        Plan {
            scene: scene.name.clone(),
            effects,
        }
    }

    pub fn has(&self, effect: Effect) -> bool {
        self.effects.iter().any(|p| p.effect == effect)
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

/// Everything computed for one scene. A quantity that was not computed is `None`.
#[derive(Debug, Clone)]
pub struct SceneResult {
    pub name: String,
    pub crank_rad: Vec<f64>,
    pub clearance: Option<ClearanceSweep>,
    pub loaded: LoadedSweep,
}

/// Run one scene according to its plan.
pub fn run(spec: &Spec, scene: &Scene, plan: &Plan) -> Result<SceneResult> {
    run_with(spec, scene, plan, &Settings::default())
}

/// Run one scene according to its plan, with the loaded solves converged to `settings`
/// (`run` uses the default settings; the accuracy ladder varies them).
pub fn run_with(
    spec: &Spec,
    scene: &Scene,
    plan: &Plan,
    settings: &Settings,
) -> Result<SceneResult> {
    let mesh = Mesh::new(&spec.design, &spec.modification);
    let clearance = if plan.has(Effect::Clearance) {
        Some(
            clearance::sweep(&mesh, &scene.crank_rad)
                .map_err(|f| Error::computation(format!("scene `{}`: {f}", scene.name)))?,
        )
    } else {
        None
    };
    let (rollers, pins, bearing) = (
        plan.has(Effect::RollerContact),
        plan.has(Effect::OutputPins),
        plan.has(Effect::Bearing),
    );
    let loaded = if rollers || pins || bearing {
        let mut model = Model::new(
            &spec.design,
            &spec.modification,
            scene,
            rollers,
            pins,
            bearing,
        );
        model.settings = *settings;
        let periodic = scene.spans_whole(spec.design.loaded_period_rad(pins || bearing));
        curves::sweep(&model, &scene.crank_rad, periodic).map_err(|f| {
            Error::computation(format!(
                "scene `{}`: crank angle {:.4}°: equilibrium solve failed: {}",
                scene.name,
                f.crank_rad.to_degrees(),
                f.failure
            ))
        })?
    } else {
        LoadedSweep::default()
    };
    Ok(SceneResult {
        name: scene.name.clone(),
        crank_rad: scene.crank_rad.clone(),
        clearance,
        loaded,
    })
}

/// Human-readable plan of a spec: what runs, in which scene, and why.
pub fn explain(spec: &Spec) -> String {
    let mut out = format!("spec `{}`: {} scene(s)\n", spec.name, spec.scenes.len());
    for scene in &spec.scenes {
        let plan = Plan::for_scene(scene);
        let first = scene.crank_rad.first().copied().unwrap_or(0.0).to_degrees();
        let step = match scene.crank_rad.as_slice() {
            [a, b, ..] => (b - a).to_degrees(),
            _ => 0.0,
        };
        out += &format!(
            "\nscene `{}`: output torque {} N·m, {} crank angles from {:.4}° in steps of {:.4}°, \
             {} geometry\n",
            scene.name,
            scene.output_torque_nmm / 1000.0,
            scene.crank_rad.len(),
            first,
            step,
            match scene.geometry {
                GeometryMode::Exact => "exact",
                GeometryMode::FirstOrder => "first-order",
            }
        );
        if plan.has(Effect::RollerContact) || plan.has(Effect::OutputPins) {
            out += &format!(
                "  contact law {}, crank bearing {}\n",
                match scene.contact_law {
                    ContactLaw::PaperLinear => "paper_linear",
                    ContactLaw::HertzNonlinear => "hertz_nonlinear",
                },
                match scene.bearing_stiffness_n_per_mm {
                    Some(k) => format!("compliant ({k} N/mm)"),
                    None => "rigid".to_string(),
                }
            );
        }
        if plan.has(Effect::RollerContact) && !plan.has(Effect::OutputPins) {
            out +=
                "  note    output pins not modelled: loaded TE is the disc lag β alone (βo = 0)\n";
        }
        for p in &plan.effects {
            out += &format!("  compute {:<15} {}\n", p.effect.name(), p.reason);
        }
        let skipped: Vec<&str> = Effect::ALL
            .iter()
            .filter(|e| !plan.has(**e))
            .map(|e| e.name())
            .collect();
        if !skipped.is_empty() {
            out += &format!("  skip    {} (not asked for)\n", skipped.join(", "));
        }
        let limits = crate::check::limits_for(&spec.limits, &plan);
        if !limits.is_empty() {
            out += &format!("  limits  {}\n", limits.join(", "));
        }
    }
    out
}
