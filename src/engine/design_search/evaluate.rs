//! A candidate through the three stages: the rules (no physics), the screen (the spec's scenes
//! at a quarter of the crank angles, judged only on the limits that sampling cannot make
//! easier) and the full check of the spec a front design is written as.

use super::candidate::{self, Candidate};
pub use super::failure::{Failure, Miss, Requirement};
use crate::engine::scene::{self, Writes};
use crate::engine::summary::{self, SceneSummary};
use crate::engine::verdict::Check;
use crate::error::{ErrorKind, Result};
use crate::model::quantity::{self, LimitDef, Quantity};
use crate::model::requirements::{ObjectiveKind, Requirements};
use crate::progress::Silent;
use crate::spec::Spec;

/// The summaries of a candidate's scenes and the checks of its limits: what `check` computes
/// for a spec without goldens, studies, an accuracy scene or measured points (the only specs a
/// search writes; `tests/it/design_search.rs` runs `check` itself on the front's specs).
fn check(spec: &Spec) -> Result<(Vec<SceneSummary>, Vec<Check>)> {
    let results = scene::run_all(spec, Writes::default(), &Silent)?;
    let summaries = summary::summarise(&results);
    let checks = crate::engine::verdict::evaluate(spec, &summaries)?;
    Ok((summaries, checks))
}

/// The stage a candidate reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Stage {
    /// Stopped by a rule or the envelope.
    Rules,
    /// Stopped by the screen.
    Screen,
    /// Fully checked (feasible when it has no failure).
    Full,
}

/// A candidate and what became of it.
#[derive(Debug, Clone)]
pub struct Evaluation {
    pub candidate: Candidate,
    pub stage: Stage,
    /// Every requirement it did not meet at its last stage (empty: feasible).
    pub failures: Vec<Failure>,
    /// The objectives' values in the requirements' order and units, after a full check.
    pub objectives: Vec<f64>,
}

impl Evaluation {
    /// Fully checked and meets every requirement.
    pub fn feasible(&self) -> bool {
        self.stage == Stage::Full && self.failures.is_empty()
    }

    /// The objectives to minimise (a maximised one negated).
    pub fn minimised(&self, req: &Requirements) -> Vec<f64> {
        req.objectives
            .iter()
            .zip(&self.objectives)
            .map(|(k, &v)| if k.maximise() { -v } else { v })
            .collect()
    }
}

/// Limits whose scene extreme over a subset of the crank angles can only be less extreme than
/// over all of them (a minimum or maximum over angles, a range): a screen that breaks one
/// breaks it in the full check too, so it rejects no design the full check would accept.
const SCREEN_LIMITS: [&str; 11] = [
    "min_clearance_mm",
    "max_roller_force_n",
    "max_contact_pressure_mpa",
    "min_rollers_in_contact",
    "max_te_fluctuation_arcsec",
    "max_ratio_fluctuation",
    "max_pin_force_n",
    "max_bearing_force_n",
    "max_lost_motion_arcsec",
    "max_face_load_factor",
    "max_line_load_n_per_mm",
];

/// The screen judges this limit (one of `SCREEN_LIMITS`).
pub fn screened(def: &LimitDef) -> bool {
    SCREEN_LIMITS.contains(&def.key)
}

/// Counts of what the stages did, for the report.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tally {
    pub generated: u64,
    pub rule_rejected: u64,
    pub screened: u64,
    pub screen_rejected: u64,
    pub fully_checked: u64,
    pub feasible: u64,
}

impl Tally {
    /// Count one evaluation.
    pub fn add(&mut self, e: &Evaluation) {
        self.generated += 1;
        match e.stage {
            Stage::Rules => self.rule_rejected += 1,
            Stage::Screen => {
                self.screened += 1;
                self.screen_rejected += 1;
            }
            Stage::Full => {
                self.screened += 1;
                self.fully_checked += 1;
                self.feasible += u64::from(e.failures.is_empty());
            }
        }
    }
}

/// Take `c` through the rules, the screen and the full check, as far as it goes.
pub fn evaluate(req: &Requirements, c: &Candidate) -> Result<Evaluation> {
    match screen(req, c)? {
        Some(stopped) => Ok(stopped),
        None => full(req, c),
    }
}

/// The rules and the screen of `c`: where it stopped, or `None` when it passed both.
pub fn screen(req: &Requirements, c: &Candidate) -> Result<Option<Evaluation>> {
    let stop = |stage, failures| {
        Ok(Some(Evaluation {
            candidate: *c,
            stage,
            failures,
            objectives: Vec::new(),
        }))
    };
    let failures = super::rules::failures(req, c);
    if !failures.is_empty() {
        return stop(Stage::Rules, failures);
    }
    let steps = req.search.steps_per_mesh_period;
    let spec = match candidate::spec(req, c, "candidate", steps / 4) {
        Ok(s) => s,
        Err(e) if e.kind == ErrorKind::ImpossibleDesign => {
            return stop(
                Stage::Rules,
                vec![Failure {
                    requirement: Requirement::SpecRule(e.key_path.unwrap_or_default()),
                    miss: Miss::Said(e.message),
                }],
            )
        }
        Err(e) => return Err(e),
    };
    let (_, checks) = match check(&spec) {
        Ok(r) => r,
        Err(e) if e.kind == ErrorKind::Computation => return stop(Stage::Screen, vec![torque(e)]),
        Err(e) => return Err(e),
    };
    let failures: Vec<_> = failed(&checks)?
        .into_iter()
        .filter(|f| matches!(f.requirement, Requirement::Limit(d) if screened(d)))
        .collect();
    if !failures.is_empty() {
        return stop(Stage::Screen, failures);
    }
    Ok(None)
}

/// The full check of `c` (its rules already passed).
pub fn full(req: &Requirements, c: &Candidate) -> Result<Evaluation> {
    let spec = candidate::spec(req, c, "candidate", req.search.steps_per_mesh_period)?;
    let (failures, objectives) = match check(&spec) {
        Ok((summaries, checks)) => {
            let failures = failed(&checks)?;
            // Objectives only of a candidate that meets every requirement.
            let objectives = if failures.is_empty() {
                objectives(req, c, &summaries)?
            } else {
                Vec::new()
            };
            (failures, objectives)
        }
        Err(e) if e.kind == ErrorKind::Computation => (vec![torque(e)], Vec::new()),
        Err(e) => return Err(e),
    };
    Ok(Evaluation {
        candidate: *c,
        stage: Stage::Full,
        failures,
        objectives,
    })
}

/// A torque the contact model cannot hold (a computation error of the check).
fn torque(e: crate::error::Error) -> Failure {
    Failure {
        requirement: Requirement::Torque,
        miss: Miss::Said(e.message),
    }
}

/// The failed checks as failures, the worst per limit key (over the scenes).
fn failed(checks: &[Check]) -> Result<Vec<Failure>> {
    let mut out: Vec<Failure> = Vec::new();
    for c in checks.iter().filter(|c| !c.passed) {
        let requirement = Requirement::limit(c.name()).ok_or_else(|| {
            crate::error::Error::computation(format!(
                "the candidate's check `{}` bounds no limit of the requirements",
                c.id
            ))
        })?;
        let f = Failure::bound(requirement, c.value, c.limit);
        match out.iter_mut().find(|o| o.requirement == f.requirement) {
            Some(o) if f.excess() > o.excess() => *o = f,
            Some(_) => {}
            None => out.push(f),
        }
    }
    Ok(out)
}

/// The objectives of a fully checked candidate, in the requirements' order.
fn objectives(req: &Requirements, c: &Candidate, summaries: &[SceneSummary]) -> Result<Vec<f64>> {
    // The worst over the scenes that compute the quantity, by the way it is better.
    let worst = |q: &Quantity, maximise: bool| -> Result<f64> {
        let values: Vec<f64> = summaries
            .iter()
            .filter_map(|s| s.scalar(q).map(|e| e.value))
            .collect();
        let ((lowest, _), (highest, _)) = crate::numeric::extremes(&values);
        let v = if maximise { lowest } else { highest };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(crate::error::Error::computation(format!(
                "no scene of the candidate's spec gave a finite {} for its objective",
                q.label
            )))
        }
    };
    req.objectives
        .iter()
        .map(|k| match k {
            ObjectiveKind::OuterDiameter => Ok(c.outer_diameter_mm(req)),
            ObjectiveKind::AxialLength => Ok(c.axial_length_mm(req)),
            ObjectiveKind::Mass => Ok(c.mass_kg(req)),
            ObjectiveKind::ContactPressure => worst(&quantity::MAX_CONTACT_PRESSURE, false),
            ObjectiveKind::TeFluctuation => worst(&quantity::TE_FLUCTUATION, false),
            ObjectiveKind::LostMotion => worst(&quantity::MAX_LOST_MOTION, false),
            ObjectiveKind::BearingLife if req.duty_cycle.is_some() => {
                worst(&quantity::DUTY_LIFE, true)
            }
            ObjectiveKind::BearingLife => worst(&quantity::BEARING_LIFE, true),
            ObjectiveKind::Efficiency if req.duty_cycle.is_some() => {
                worst(&quantity::DUTY_MEAN_EFFICIENCY, true)
            }
            ObjectiveKind::Efficiency => worst(&quantity::MEAN_EFFICIENCY, true),
            ObjectiveKind::Rigidity => worst(&quantity::MIN_TORSIONAL_RIGIDITY, true),
        })
        .collect()
}
