//! One optimisation study as a problem: a modification in, objective and constraint margins out.
//!
//! Only the effects the objective needs are simulated (`candidate_plan`): each objective is a
//! scalar quantity of the registry, read from the candidate's scene run exactly as `check`
//! reads it. The whole-mesh clearance constraint uses the light `clearance::min_gap`.

use crate::engine::scene;
use crate::equilibrium::solve::Settings;
use crate::geometry::clearance::{self, Mesh};
use crate::model::quantity::{RATIO_FLUCTUATION, TE_FLUCTUATION};
use crate::model::results::MinClearance;
use crate::model::{Effect, Modification, Objective, Plan, Scene, Study};
use crate::spec::rules;
use crate::spec::Spec;

/// A constraint's value, its bound and the margin (≥ 0 satisfied).
#[derive(Debug, Clone, PartialEq)]
pub struct Margin {
    pub name: String,
    pub value: f64,
    pub bound: f64,
    pub margin: f64,
}

impl Margin {
    /// Satisfied within the checker's comparison tolerance (`check::tolerance`).
    pub fn satisfied(&self) -> bool {
        self.margin >= -crate::engine::check::tolerance(self.bound)
    }
}

/// Everything known about one candidate modification.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    pub modification: Modification,
    /// Weighted objective; +∞ when the candidate could not be evaluated.
    pub objective: f64,
    /// Each objective term, unweighted, in its own unit.
    pub terms: Vec<(Objective, f64)>,
    pub margins: Vec<Margin>,
    /// Where the whole-mesh minimum clearance occurs, when computed.
    pub min_clearance: Option<MinClearance>,
    /// Why the candidate could not be evaluated (a design rule or a solver failure).
    pub failure: Option<String>,
}

impl Evaluation {
    /// Satisfies every constraint (margins ≥ 0) and was evaluated.
    pub fn feasible(&self) -> bool {
        self.failure.is_none() && self.margins.iter().all(Margin::satisfied)
    }

    /// The smallest margin (negative: the worst violation).
    pub fn worst_margin(&self) -> f64 {
        self.margins
            .iter()
            .map(|m| m.margin)
            .fold(f64::INFINITY, f64::min)
    }

    /// Order for "better": feasible first, then lower objective, then larger margin.
    pub fn better_than(&self, other: &Evaluation) -> bool {
        match (self.feasible(), other.feasible()) {
            (true, false) => true,
            (false, true) => false,
            (true, true) => self.objective < other.objective,
            (false, false) => self.worst_margin() > other.worst_margin(),
        }
    }
}

/// The effects a candidate of a study simulates: those of its objectives' quantities, and the
/// output pins when the scene models them and an objective is of the transmission (TE and
/// ratio are β + βo: with the pins in the scene its TE includes their deflection).
fn candidate_plan(scene: &Scene, objectives: &[(Objective, f64)]) -> Plan {
    let mut effects: Vec<Effect> = objectives.iter().map(|(o, _)| o.quantity.effect).collect();
    let transmission = objectives
        .iter()
        .any(|(o, _)| [TE_FLUCTUATION.key, RATIO_FLUCTUATION.key].contains(&o.quantity.key));
    if transmission && Plan::for_scene(scene).has(Effect::OutputPins) {
        effects.push(Effect::OutputPins);
    }
    let mut plan = Plan::of(&scene.name, &effects);
    for (o, _) in objectives {
        plan.ask(o.quantity, &format!("objective {}", o.name));
    }
    plan
}

/// A study bound to its spec.
#[derive(Debug, Clone)]
pub struct Problem<'a> {
    pub spec: &'a Spec,
    pub study: &'a Study,
    pub scene: &'a Scene,
    /// What a candidate simulates: only the effects its objectives need.
    plan: Plan,
    progress: Option<&'a indicatif::ProgressBar>,
}

impl<'a> Problem<'a> {
    pub fn new(spec: &'a Spec, study: &'a Study) -> Self {
        let scene = &spec.scenes[study.scene];
        Problem {
            spec,
            study,
            scene,
            plan: candidate_plan(scene, &study.objective),
            progress: None,
        }
    }

    /// Count every evaluation on `progress`.
    pub fn with_progress(mut self, progress: Option<&'a indicatif::ProgressBar>) -> Self {
        self.progress = progress;
        self
    }

    /// The modification at variable values x (engine units, in `study.variables` order).
    pub fn modification_at(&self, x: &[f64]) -> Modification {
        let mut m = self.study.start;
        for (v, &value) in self.study.variables.iter().zip(x) {
            v.kind.set(&mut m, value);
        }
        m
    }

    /// Variable values of a modification.
    pub fn variables_of(&self, m: &Modification) -> Vec<f64> {
        self.study.variables.iter().map(|v| v.kind.get(m)).collect()
    }

    /// Evaluate a candidate: design rules, constraints, then the objective terms.
    pub fn evaluate(&self, m: &Modification) -> Evaluation {
        self.evaluate_screened(m, false)
    }

    /// `evaluate`, but with `screen` a candidate that violates a constraint gets no objective
    /// (+∞): the global stage only seeds local runs from feasible points, so the loaded sweep
    /// of an infeasible one would be wasted.
    pub fn evaluate_screened(&self, m: &Modification, screen: bool) -> Evaluation {
        if let Some(bar) = self.progress {
            bar.inc(1);
        }
        let mut e = Evaluation {
            modification: *m,
            objective: f64::INFINITY,
            terms: Vec::new(),
            margins: Vec::new(),
            min_clearance: None,
            failure: None,
        };
        if let Some((lo, hi)) = self.study.tip_clearance_mm {
            let tip = m.tip_clearance_mm();
            e.margins.push(Margin {
                name: "tip_clearance_mm (lower, paper Eq. 8)".into(),
                value: tip,
                bound: lo,
                margin: tip - lo,
            });
            e.margins.push(Margin {
                name: "tip_clearance_mm (upper, paper Eq. 21)".into(),
                value: tip,
                bound: hi,
                margin: hi - tip,
            });
        }
        if let Err(err) = rules::check(&self.spec.design, m) {
            e.failure = Some(err.message);
            return e;
        }
        if screen && !e.margins.iter().all(Margin::satisfied) {
            return e;
        }
        match self.terms(m, &mut e, screen) {
            Ok(terms) if terms.is_empty() => {}
            Ok(terms) => {
                e.objective = terms
                    .iter()
                    .zip(&self.study.objective)
                    .map(|((_, value), (_, w))| w * value)
                    .sum();
                e.terms = terms;
            }
            Err(msg) => e.failure = Some(msg),
        }
        e
    }

    fn terms(
        &self,
        m: &Modification,
        e: &mut Evaluation,
        screen: bool,
    ) -> Result<Vec<(Objective, f64)>, String> {
        let design = &self.spec.design;
        let crank = &self.scene.crank_rad;
        let mesh = Mesh::new(design, m);
        if let Some(dt) = self.study.min_clearance_mm {
            let min = clearance::min_gap(&mesh, crank).map_err(|f| f.to_string())?;
            e.margins.push(Margin {
                name: "min_clearance_mm (whole mesh)".into(),
                value: min.gap_mm,
                bound: dt,
                margin: min.gap_mm - dt,
            });
            e.min_clearance = Some(min);
        }
        if screen && !e.margins.iter().all(Margin::satisfied) {
            return Ok(Vec::new());
        }
        let r = scene::run_design(design, m, self.scene, &self.plan, &Settings::default())
            .map_err(|err| err.message)?;
        self.study
            .objective
            .iter()
            .map(|&(o, _)| {
                let value = o.quantity.scalar(&r).map(|x| x.value).ok_or_else(|| {
                    format!(
                        "{} was not computed (a ratio needs at least 3 crank angles)",
                        o.quantity.label
                    )
                })?;
                if value.is_finite() {
                    Ok((o, value))
                } else {
                    Err(format!("objective {} is not finite", o.name))
                }
            })
            .collect()
    }
}
