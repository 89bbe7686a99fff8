//! Local refinement of a front design: a pattern search in the unit cube of the continuous
//! variables that moves only to a feasible design dominating the current one, each variable in
//! turn up and down by a step that halves when no move is taken, until the step falls below
//! `MIN_STEP` or the budget of evaluations is spent.

use super::candidate::Candidate;
use super::evaluate::{evaluate, Evaluation};
use super::pareto::dominates;
use crate::error::Result;
use crate::model::requirements::Requirements;
use crate::model::requirements::Variables;
use crate::progress::Progress;

/// First step, a fraction of each variable's range.
const FIRST_STEP: f64 = 0.125;
/// Smallest step: 1/1024 of a range (0.03 mm of a 30 mm range).
const MIN_STEP: f64 = 1.0 / 1024.0;

/// Every evaluation of the pattern search from `start` (a feasible design), in order.
pub fn refine(
    req: &Requirements,
    start: &Evaluation,
    progress: &dyn Progress,
) -> Result<Vec<Evaluation>> {
    let ranges = req.search.continuous.to_array();
    let free: Vec<usize> = (0..8).filter(|&k| !ranges[k].fixed()).collect();
    let to_unit = |c: &Candidate| -> [f64; 8] {
        let x = c.x.to_array();
        let mut u = [0.0; 8];
        for &k in &free {
            u[k] = (x[k] - ranges[k].lower) / (ranges[k].upper - ranges[k].lower);
        }
        u
    };
    let mut current = start.clone();
    let mut u = to_unit(&current.candidate);
    let mut step = FIRST_STEP;
    let mut out = Vec::new();
    let budget = req.search.refine_budget;
    'search: while step >= MIN_STEP {
        for &k in &free {
            for dir in [1.0, -1.0] {
                if out.len() >= budget {
                    break 'search;
                }
                let mut v = u;
                v[k] = (u[k] + dir * step).clamp(0.0, 1.0);
                if v[k] == u[k] {
                    continue;
                }
                let mut c = Candidate::at(current.candidate.choice, &req.search.continuous, &v);
                // Fixed variables keep their value exactly.
                let (mut x, kept) = (c.x.to_array(), current.candidate.x.to_array());
                for j in (0..8).filter(|j| !free.contains(j)) {
                    x[j] = kept[j];
                }
                c.x = Variables::from_array(x);
                let e = evaluate(req, &c)?;
                progress.advance(1);
                let better = e.feasible() && dominates(&e.minimised(req), &current.minimised(req));
                out.push(e.clone());
                if better {
                    current = e;
                    u = v;
                    continue 'search;
                }
            }
        }
        step /= 2.0;
    }
    Ok(out)
}
