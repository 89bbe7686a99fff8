//! One optimisation study as a problem: a modification in, objective and constraint margins out.
//!
//! Only the effects the objective needs are simulated (`candidate_plan`): each objective is a
//! scalar quantity of the registry, read from the candidate's scene run exactly as `check`
//! reads it, and so is each objective bounded by `constraints.objectives`. A candidate is a
//! `Point`: the modification and the disc's crowning, which the scene runs with. The whole-mesh clearance constraint uses the light `clearance::min_gap`; the lost
//! motion (a constraint, and a column of the study tables) the full clearance sweep over one
//! mesh period of the scene's crank angles.

use crate::engine::scene;
use crate::geometry::clearance::{self, Mesh};
use crate::model::quantity::{Bound, RATIO_FLUCTUATION, TE_FLUCTUATION};
use crate::model::results::MinClearance;
use crate::model::{Effect, Modification, Objective, Plan, Point, Scene, Study};
use crate::spec::deviations;
use crate::spec::Spec;
use crate::units;

/// A constraint's value and its bound, in the constraint's unit, and which side the bound
/// limits (`margin`: ≥ 0 satisfied).
#[derive(Debug, Clone, PartialEq)]
pub struct Margin {
    /// What is constrained and where the bound comes from, e.g. "min_clearance_mm (whole mesh)".
    pub name: String,
    /// Unit of `value`, `bound` and the margin ("mm", "arcsec").
    pub unit: &'static str,
    pub value: f64,
    pub bound: f64,
    /// Which side `bound` limits: `Min` a lower bound, `Max` an upper one.
    pub side: Bound,
}

impl Margin {
    fn lower(name: &str, unit: &'static str, value: f64, bound: f64) -> Self {
        Margin {
            name: name.into(),
            unit,
            value,
            bound,
            side: Bound::Min,
        }
    }

    fn upper(name: &str, unit: &'static str, value: f64, bound: f64) -> Self {
        Margin {
            side: Bound::Max,
            ..Margin::lower(name, unit, value, bound)
        }
    }

    /// The margin, in the constraint's unit (≥ 0 satisfied): value − bound for a lower bound,
    /// bound − value for an upper one.
    pub fn margin(&self) -> f64 {
        match self.side {
            Bound::Min => self.value - self.bound,
            Bound::Max => self.bound - self.value,
        }
    }

    /// Satisfied within the checker's comparison tolerance (`limit::tolerance`).
    pub fn satisfied(&self) -> bool {
        self.margin() >= -crate::engine::limit::tolerance(self.bound)
    }

    /// The margin relative to the bound, at least 1 of its unit (`limit::Scale::LimitOrUnit`):
    /// constraints of different units compare by this.
    pub fn relative(&self) -> f64 {
        use crate::engine::limit::{relative, Scale};
        relative(self.margin(), self.bound, Scale::LimitOrUnit)
    }
}

/// Everything known about one candidate modification.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// The candidate: its modification and crowning (the spec's unless the study varies the
    /// crown).
    pub point: Point,
    /// Weighted objective; +∞ when the candidate could not be evaluated, or was not because a
    /// constraint already failed (a screened evaluation).
    pub objective: f64,
    /// Each objective term, unweighted, in its own unit.
    pub terms: Vec<(Objective, f64)>,
    /// Every constraint evaluated, in the order tip band, whole-mesh clearance, lost motion,
    /// bounded objectives.
    pub margins: Vec<Margin>,
    /// Where the whole-mesh minimum clearance occurs, when computed.
    pub min_clearance: Option<MinClearance>,
    /// Largest unloaded lost motion over the scene's crank angles, arcsec, when computed.
    pub lost_motion_arcsec: Option<f64>,
    /// Why the candidate could not be evaluated (a design rule or a solver failure).
    pub failure: Option<String>,
}

impl Evaluation {
    fn new(p: &Point) -> Self {
        Evaluation {
            point: *p,
            objective: f64::INFINITY,
            terms: Vec::new(),
            margins: Vec::new(),
            min_clearance: None,
            lost_motion_arcsec: None,
            failure: None,
        }
    }

    /// Satisfies every constraint (margins ≥ 0) and was evaluated.
    pub fn feasible(&self) -> bool {
        self.failure.is_none() && self.margins.iter().all(Margin::satisfied)
    }

    /// The smallest margin relative to its bound (negative: the worst violation).
    pub fn worst_margin(&self) -> f64 {
        self.margins
            .iter()
            .map(Margin::relative)
            .fold(f64::INFINITY, f64::min)
    }

    /// The constraint with the smallest relative margin.
    pub fn tightest(&self) -> Option<&Margin> {
        self.margins
            .iter()
            .min_by(|a, b| a.relative().total_cmp(&b.relative()))
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

/// The best of `candidates` by `Evaluation::better_than`; the first of equals.
pub fn best<'a>(candidates: impl IntoIterator<Item = &'a Evaluation>) -> Option<&'a Evaluation> {
    (candidates.into_iter()).reduce(|b, e| if e.better_than(b) { e } else { b })
}

/// The point of `study` at z of the unit cube of its variables (z = 0 lower bounds, 1 upper
/// bounds; `Variable::at_unit`, logarithmic for the crown radius), the others at its start.
pub fn point_at_unit(study: &Study, z: &[f64]) -> Point {
    let mut p = study.start_point();
    for (v, &zi) in study.variables.iter().zip(z) {
        v.kind.set(&mut p, v.at_unit(zi));
    }
    p
}

/// The effects a candidate of a study simulates: those of its objectives' quantities (the
/// minimised and the bounded ones), and the output pins when the scene models them and an
/// objective is of the transmission (TE and ratio are β + βo: with the pins in the scene its
/// TE includes their deflection).
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
}

impl<'a> Problem<'a> {
    pub fn new(spec: &'a Spec, study: &'a Study) -> Self {
        let scene = &spec.scenes[study.scene];
        Problem {
            spec,
            study,
            scene,
            plan: candidate_plan(
                scene,
                &[&study.objective[..], &study.objective_limits[..]].concat(),
            ),
        }
    }

    /// A point's place in the unit cube of the variables.
    pub fn unit_of(&self, p: &Point) -> Vec<f64> {
        self.study
            .variables
            .iter()
            .map(|v| v.unit_of(v.kind.get(p)))
            .collect()
    }

    /// Evaluate the modification `m` with the spec's crowning (`evaluate_point`).
    pub fn evaluate(&self, m: &Modification) -> Evaluation {
        self.evaluate_point(&Point {
            modification: *m,
            crowning: self.scene.face.crowning,
        })
    }

    /// Evaluate a candidate: design rules, constraints, then the objective terms and the
    /// bounded objectives.
    pub fn evaluate_point(&self, p: &Point) -> Evaluation {
        self.evaluate_screened(p, false)
    }

    /// `evaluate_point`, but with `screen` a candidate that violates a constraint gets no
    /// objective (+∞) and no further constraints: the sampling stages only need the objective
    /// of feasible points, so the loaded sweep of an infeasible one would be wasted.
    pub fn evaluate_screened(&self, p: &Point, screen: bool) -> Evaluation {
        let m = &p.modification;
        let mut e = Evaluation::new(p);
        if let Some((lo, hi)) = self.study.tip_clearance_mm {
            let tip = m.tip_clearance_mm();
            e.margins.push(Margin::lower(
                "tip_clearance_mm (lower, paper Eq. 8)",
                "mm",
                tip,
                lo,
            ));
            e.margins.push(Margin::upper(
                "tip_clearance_mm (upper, paper Eq. 21)",
                "mm",
                tip,
                hi,
            ));
        }
        if let Err(err) = deviations::check(&self.spec.design, m) {
            e.failure = Some(err.message);
            return e;
        }
        let stop = |e: &Evaluation| screen && !e.margins.iter().all(Margin::satisfied);
        if stop(&e) {
            return e;
        }
        let mesh = Mesh::new(&self.spec.design, m);
        if let Err(msg) = self.constraints(&mesh, &mut e, screen) {
            e.failure = Some(msg);
            return e;
        }
        if stop(&e) {
            return e;
        }
        match self.terms(p) {
            Ok((terms, bounded)) => {
                e.objective = terms
                    .iter()
                    .zip(&self.study.objective)
                    .map(|((_, value), (_, w))| w * value)
                    .sum();
                e.terms = terms;
                for ((o, value), (_, bound)) in
                    bounded.into_iter().zip(&self.study.objective_limits)
                {
                    e.margins.push(Margin::upper(
                        &format!("{} (at most)", o.name),
                        o.quantity.unit,
                        value,
                        *bound,
                    ));
                }
            }
            Err(msg) => e.failure = Some(msg),
        }
        e
    }

    /// The constraints on the exact geometry: whole-mesh clearance, then lost motion (the
    /// dearer one, skipped when screening and the clearance already fails).
    fn constraints(&self, mesh: &Mesh, e: &mut Evaluation, screen: bool) -> Result<(), String> {
        if let Some(dt) = self.study.min_clearance_mm {
            let min = self.min_clearance(mesh)?;
            e.margins.push(Margin::lower(
                "min_clearance_mm (whole mesh)",
                "mm",
                min.gap_mm,
                dt,
            ));
            e.min_clearance = Some(min);
        }
        if screen && !e.margins.iter().all(Margin::satisfied) {
            return Ok(());
        }
        if let Some(limit) = self.study.max_lost_motion_arcsec {
            let lost = self.lost_motion_arcsec(mesh)?;
            e.margins.push(Margin::upper(
                "max_lost_motion_arcsec (unloaded)",
                "arcsec",
                lost,
                limit,
            ));
            e.lost_motion_arcsec = Some(lost);
        }
        Ok(())
    }

    fn min_clearance(&self, mesh: &Mesh) -> Result<MinClearance, String> {
        clearance::min_gap(mesh, &self.scene.crank_rad).map_err(|f| f.to_string())
    }

    /// Largest lost motion (forward plus reverse backlash, unloaded) over the scene's crank
    /// angles, arcsec. It repeats with the mesh period, so one period of a whole-period sweep
    /// is enough (`clearance::first_period`).
    fn lost_motion_arcsec(&self, mesh: &Mesh) -> Result<f64, String> {
        let crank = clearance::first_period(mesh, &self.scene.crank_rad);
        let sweep = clearance::sweep(
            mesh,
            crank,
            clearance::Scope::Backlash,
            &crate::progress::Silent,
        )
        .map_err(|f| f.to_string())?;
        let lost = sweep
            .backlash
            .as_ref()
            .map_or(&[][..], |b| &b.lost_motion_rad);
        let (_, (max, _)) = crate::numeric::extremes(lost);
        if max.is_finite() {
            Ok(units::arcsec(max))
        } else {
            Err("the lost motion is unbounded: no roller closes in one direction".into())
        }
    }

    /// `e` with the min clearance and the lost motion filled in when its evaluation did not
    /// need them (the study tables show both for the start, the references and the optimum).
    pub fn describe(&self, mut e: Evaluation) -> Evaluation {
        if e.failure.is_some() || (e.min_clearance.is_some() && e.lost_motion_arcsec.is_some()) {
            return e;
        }
        let mesh = Mesh::new(&self.spec.design, &e.point.modification);
        if e.min_clearance.is_none() {
            e.min_clearance = self.min_clearance(&mesh).ok();
        }
        if e.lost_motion_arcsec.is_none() {
            e.lost_motion_arcsec = self.lost_motion_arcsec(&mesh).ok();
        }
        e
    }

    /// The objective terms and the bounded objectives' values of the candidate's scene run
    /// (the scene with the candidate's crowning).
    #[allow(clippy::type_complexity)]
    fn terms(&self, p: &Point) -> Result<(Vec<(Objective, f64)>, Vec<(Objective, f64)>), String> {
        let crowned;
        let scene = if p.crowning == self.scene.face.crowning {
            self.scene
        } else {
            let mut s = self.scene.clone();
            s.face.crowning = p.crowning;
            crowned = s;
            &crowned
        };
        let r = scene::run_design(
            &self.spec.design,
            &p.modification,
            (scene, &self.plan),
            &scene::RunOptions::default(),
        )
        .map_err(|err| err.message)?;
        let read = |list: &[(Objective, f64)]| -> Result<Vec<(Objective, f64)>, String> {
            list.iter().map(|&(o, _)| read_objective(o, &r)).collect()
        };
        Ok((
            read(&self.study.objective)?,
            read(&self.study.objective_limits)?,
        ))
    }
}

/// The value of objective `o` in a scene's results.
fn read_objective(
    o: Objective,
    r: &crate::model::results::SceneResult,
) -> Result<(Objective, f64), String> {
    let value = (o.quantity.scalar(r).map(|x| x.value))
        .ok_or_else(|| crate::engine::missing::not_computed(o.quantity, r))?;
    if value.is_finite() {
        Ok((o, value))
    } else {
        Err(format!("objective {} is not finite", o.name))
    }
}
