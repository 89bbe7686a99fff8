//! Local stage: COBYLA (Powell's derivative-free constrained method; the `cobyla` crate's
//! port of NLopt's) in normalised coordinates z ∈ [0, 1]^n, with explicit stop tolerances.
//!
//! The objective (max − min of a sampled curve) is non-smooth; COBYLA needs no gradients and
//! handles the constraints (tip clearance band, whole-mesh clearance) as g(z) ≥ 0. Objective
//! and constraints at one point share one evaluation through a cache.

use super::global::scale;
use super::problem::{Evaluation, Problem};
use cobyla::{minimize, Func, RhoBeg, StopTols, SuccessStatus};
use std::cell::RefCell;

/// Initial trust-region radius: a tenth of each variable's range.
pub const RHO_BEGIN: f64 = 0.1;
/// Stop when a step changes every normalised variable by less than this (1e-6 of the range:
/// 0.5 nm on the paper's 0.5 mm box, far below grinding accuracy).
pub const X_TOL: f64 = 1e-6;
/// ... or the objective by less than this, relatively.
pub const F_TOL_REL: f64 = 1e-9;
/// Objective returned for a candidate that cannot be evaluated.
const PENALTY: f64 = 1e9;

/// One local run.
#[derive(Debug, Clone)]
pub struct LocalRun {
    pub start: Evaluation,
    pub best: Evaluation,
    /// Every point evaluated, in order.
    pub path: Vec<Evaluation>,
    pub stop_reason: String,
}

fn reason(status: Result<SuccessStatus, cobyla::FailStatus>) -> String {
    match status {
        Ok(SuccessStatus::XtolReached) => "converged: step below the variable tolerance".into(),
        Ok(SuccessStatus::FtolReached) => "converged: objective change below the tolerance".into(),
        Ok(SuccessStatus::MaxEvalReached) => "stopped: evaluation budget used up".into(),
        Ok(other) => format!("stopped: {other:?}"),
        Err(fail) => format!("COBYLA failed: {fail:?}"),
    }
}

/// Run COBYLA from `start`.
pub fn run(problem: &Problem, start: &Evaluation, max_evaluations: usize) -> LocalRun {
    let vars = &problem.study.variables;
    let z0: Vec<f64> = problem
        .variables_of(&start.modification)
        .iter()
        .zip(vars)
        .map(|(x, v)| (x - v.lower) / (v.upper - v.lower))
        .collect();
    let path: RefCell<Vec<Evaluation>> = RefCell::new(Vec::new());
    let eval = |z: &[f64]| -> Evaluation {
        let m = problem.modification_at(&scale(problem, z));
        if let Some(e) = path.borrow().iter().rev().find(|e| e.modification == m) {
            return e.clone();
        }
        let e = problem.evaluate(&m);
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
                e.margins.get(k).map_or(-PENALTY, |m| m.margin)
            }) as Box<dyn Func<()> + '_>
        })
        .collect();
    let cons: Vec<&dyn Func<()>> = constraints.iter().map(|c| c.as_ref()).collect();
    let bounds = vec![(0.0, 1.0); vars.len()];
    let stop = StopTols {
        ftol_rel: F_TOL_REL,
        xtol_abs: vec![X_TOL; vars.len()],
        ..StopTols::default()
    };
    let status = minimize(
        objective,
        &z0,
        &bounds,
        &cons,
        (),
        max_evaluations,
        RhoBeg::All(RHO_BEGIN),
        Some(stop),
    );
    drop(cons);
    drop(constraints);
    let path = path.take();
    let best = path.iter().fold(start.clone(), |best, e| {
        if e.better_than(&best) {
            e.clone()
        } else {
            best
        }
    });
    LocalRun {
        start: start.clone(),
        best,
        path,
        stop_reason: reason(status.map(|s| s.0).map_err(|f| f.0)),
    }
}
