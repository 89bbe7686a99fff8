//! Local stage: COBYLA (Powell's derivative-free constrained method; the `cobyla` crate's
//! port of NLopt's) in normalised coordinates z ∈ [0, 1]^n, with explicit stop tolerances.
//!
//! The objective (max − min of a sampled curve) is non-smooth; COBYLA needs no gradients and
//! handles the constraints (tip clearance band, whole-mesh clearance, lost motion) as
//! g(z) ≥ 0, each relative to its bound so that constraints of different units weigh alike.
//! Objective and constraints at one point share one evaluation through a cache.

use super::problem::{point_at_unit, Evaluation, Problem};
use crate::progress::Progress;
use cobyla::{minimize, Func, RhoBeg, StopTols, SuccessStatus};
use std::cell::RefCell;

/// Stop when a step changes every normalised variable by less than this (1e-6 of the range:
/// 0.5 nm on the paper's 0.5 mm box, far below grinding accuracy).
pub const X_TOL: f64 = 1e-6;
/// ... or the objective by less than this, relatively.
pub const F_TOL_REL: f64 = 1e-9;
/// Objective returned for a candidate that cannot be evaluated.
const PENALTY: f64 = 1e9;

/// Why a local run stopped (after argmin's termination status): the one place a stop is named.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// A step moved every normalised variable by less than `X_TOL`.
    StepBelowTolerance,
    /// The objective changed by less than `F_TOL_REL`, relatively.
    ObjectiveChangeBelowTolerance,
    /// The run used its evaluation budget (`local_evaluations`).
    BudgetUsedUp,
    /// COBYLA ended on a status of its own (success without a tolerance met).
    Ended,
    /// COBYLA gave up: round-off limited its progress.
    RoundoffLimited,
    /// COBYLA failed (invalid arguments, out of memory, an unexpected error).
    Failed,
}

impl StopReason {
    fn of(status: Result<SuccessStatus, cobyla::FailStatus>) -> Self {
        use cobyla::FailStatus;
        match status {
            Ok(SuccessStatus::XtolReached) => StopReason::StepBelowTolerance,
            Ok(SuccessStatus::FtolReached) => StopReason::ObjectiveChangeBelowTolerance,
            Ok(SuccessStatus::MaxEvalReached) => StopReason::BudgetUsedUp,
            Ok(_) => StopReason::Ended,
            Err(FailStatus::RoundoffLimited) => StopReason::RoundoffLimited,
            Err(_) => StopReason::Failed,
        }
    }
}

/// One local run.
#[derive(Debug, Clone)]
pub struct LocalRun {
    /// Where it started.
    pub start: Evaluation,
    /// The best point it evaluated (its start when it found nothing better).
    pub best: Evaluation,
    /// Every point evaluated, in order.
    pub path: Vec<Evaluation>,
    pub stop: StopReason,
}

/// Run COBYLA from `start`, with initial steps of `rho_begin` of each variable's range and at
/// most the study's `local_evaluations`, telling `progress` of every evaluation.
pub fn run(
    problem: &Problem,
    start: &Evaluation,
    rho_begin: f64,
    progress: &dyn Progress,
) -> LocalRun {
    let dims = problem.study.variables.len();
    let z0: Vec<f64> = problem.unit_of(&start.point);
    let path: RefCell<Vec<Evaluation>> = RefCell::new(Vec::new());
    let eval = |z: &[f64]| -> Evaluation {
        let p = point_at_unit(problem.study, z);
        if let Some(e) = path.borrow().iter().rev().find(|e| e.point == p) {
            return e.clone();
        }
        progress.advance(1);
        let e = problem.evaluate_point(&p);
        path.borrow_mut().push(e.clone());
        e
    };
    let objective = |z: &[f64], _: &mut ()| {
        let e = eval(z);
        if e.failure.is_some() {
            PENALTY
        } else {
            e.objective
        }
    };
    let n_margins = start.margins.len();
    let constraints: Vec<Box<dyn Func<()> + '_>> = (0..n_margins)
        .map(|k| {
            let eval = &eval;
            Box::new(move |z: &[f64], _: &mut ()| {
                let e = eval(z);
                e.margins.get(k).map_or(-PENALTY, |m| m.relative())
            }) as Box<dyn Func<()> + '_>
        })
        .collect();
    let cons: Vec<&dyn Func<()>> = constraints.iter().map(|c| c.as_ref()).collect();
    let bounds = vec![(0.0, 1.0); dims];
    let stop = StopTols {
        ftol_rel: F_TOL_REL,
        xtol_abs: vec![X_TOL; dims],
        ..StopTols::default()
    };
    let status = minimize(
        objective,
        &z0,
        &bounds,
        &cons,
        (),
        problem.study.local_evaluations,
        RhoBeg::All(rho_begin),
        Some(stop),
    );
    drop(cons);
    drop(constraints);
    let path = path.take();
    let best = super::problem::best(std::iter::once(start).chain(&path))
        .cloned()
        .unwrap_or_else(|| start.clone());
    LocalRun {
        start: start.clone(),
        best,
        path,
        stop: StopReason::of(status.map(|s| s.0).map_err(|f| f.0)),
    }
}
