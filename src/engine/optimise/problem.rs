//! One optimisation study as a problem: a modification in, objective and constraint margins out.
//!
//! Only the effects the objective needs are simulated: the fluctuation objectives need the
//! roller balance (and the pins when the study's scene models them, since TE = β + βo);
//! `max_bearing_force` needs the bearing; `lost_motion` needs the clearance sweep. The
//! whole-mesh clearance constraint uses the light `clearance::min_gap`.

use crate::equilibrium::curves;
use crate::equilibrium::sweep::Model;
use crate::geometry::clearance::{self, Mesh};
use crate::model::results::MinClearance;
use crate::model::{Effect, Plan};
use crate::model::{Modification, Objective, Scene, Study};
use crate::numeric::{extremes, fluctuation, max_entry};
use crate::spec::rules;
use crate::spec::Spec;
use crate::units;

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

/// A study bound to its spec.
#[derive(Debug, Clone)]
pub struct Problem<'a> {
    pub spec: &'a Spec,
    pub study: &'a Study,
    pub scene: &'a Scene,
    scene_has_pins: bool,
    progress: Option<&'a indicatif::ProgressBar>,
}

impl<'a> Problem<'a> {
    pub fn new(spec: &'a Spec, study: &'a Study) -> Self {
        let scene = &spec.scenes[study.scene];
        Problem {
            spec,
            study,
            scene,
            scene_has_pins: Plan::for_scene(scene).has(Effect::OutputPins),
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

    fn needs(&self, o: Objective) -> bool {
        self.study.objective.iter().any(|(t, _)| *t == o)
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
        let transmission =
            self.needs(Objective::RatioFluctuation) || self.needs(Objective::TeFluctuation);
        let bearing = self.needs(Objective::MaxBearingForce);
        let rollers = transmission || bearing || self.needs(Objective::MaxRollerForce);
        let pins = bearing || (transmission && self.scene_has_pins);
        let loaded = if rollers {
            let model = Model::new(design, m, self.scene, true, pins, bearing);
            let periodic = self.scene.spans_whole(design.loaded_period_rad(pins));
            Some(curves::sweep(&model, crank, periodic).map_err(|f| {
                format!(
                    "crank angle {:.4}°: equilibrium solve failed: {}",
                    units::deg(f.crank_rad),
                    f.failure
                )
            })?)
        } else {
            None
        };
        let lost_motion = if self.needs(Objective::LostMotion) {
            let sweep = clearance::sweep(&mesh, crank).map_err(|f| f.to_string())?;
            Some(units::arcsec(extremes(&sweep.lost_motion_rad).1 .0))
        } else {
            None
        };
        let missing = |what: &str| format!("{what} was not computed");
        self.study
            .objective
            .iter()
            .map(|&(o, _)| {
                let l = loaded.as_ref();
                let value = match o {
                    Objective::RatioFluctuation => l
                        .and_then(|l| l.transmission.as_ref())
                        .and_then(|t| t.ratio.as_deref())
                        .map(fluctuation)
                        .ok_or_else(|| missing("the ratio (needs at least 3 crank angles)"))?,
                    Objective::TeFluctuation => l
                        .and_then(|l| l.transmission.as_ref())
                        .map(|t| units::arcsec(fluctuation(&t.te_rad)))
                        .ok_or_else(|| missing("the loaded TE"))?,
                    Objective::MaxRollerForce => l
                        .and_then(|l| l.rollers.as_ref())
                        .map(|r| max_entry(&r.force_n).0)
                        .ok_or_else(|| missing("the roller forces"))?,
                    Objective::MaxBearingForce => l
                        .and_then(|l| l.bearing.as_ref())
                        .map(|b| extremes(&b.force_n).1 .0)
                        .ok_or_else(|| missing("the bearing force"))?,
                    Objective::LostMotion => lost_motion.ok_or_else(|| missing("lost motion"))?,
                };
                if value.is_finite() {
                    Ok((o, value))
                } else {
                    Err(format!("objective {} is not finite", o.name()))
                }
            })
            .collect()
    }
}
