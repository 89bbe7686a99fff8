//! How good the answer is: after the search, a dense grid of the variables (`verify_grid`
//! points per variable) is evaluated; when a grid point beats the search's optimum, local runs
//! refine from the grid points that do. The result says by how much the best grid point is
//! above the final optimum, so a reader knows what the optimum is worth.

use super::local::{self, LocalRun};
use super::problem::{best, Evaluation, Problem};
use super::seeds;
use crate::progress::Progress;
use rayon::prelude::*;

/// The verification of one study's optimum.
#[derive(Debug, Clone)]
pub struct Verification {
    /// Grid points per variable (bounds included).
    pub steps: usize,
    /// Grid points evaluated: steps^variables.
    pub points: usize,
    /// Grid points that satisfy every constraint.
    pub feasible: usize,
    /// The best feasible grid point (None: no grid point is feasible).
    pub best: Option<Evaluation>,
    /// The objective of the search's optimum, before the grid was seen.
    pub searched_objective: f64,
    /// Local runs from the grid points that beat the search's optimum (empty when none did).
    pub refinements: Vec<LocalRun>,
    /// The best feasible grid point's objective minus the final optimum's: ≥ 0 means no grid
    /// point is better than the optimum. None when no grid point is feasible, or the optimum
    /// is not.
    pub margin: Option<f64>,
}

impl Verification {
    /// By how much the grid's best point beat the search's optimum (None: it did not).
    pub fn beat_search_by(&self) -> Option<f64> {
        let b = self.best.as_ref()?;
        (b.objective < self.searched_objective).then_some(self.searched_objective - b.objective)
    }
}

/// The grid's points in the unit cube, `h` apart, the first variable varying slowest.
pub fn points(steps: usize, dims: usize, h: f64) -> Vec<Vec<f64>> {
    let total = steps.pow(dims as u32);
    (0..total)
        .map(|mut k| {
            let mut z = vec![0.0; dims];
            for zi in z.iter_mut().rev() {
                *zi = (k % steps) as f64 * h;
                k /= steps;
            }
            z
        })
        .collect()
}

/// Evaluate the grid and refine from its points that beat `searched` (the search's optimum),
/// telling `progress` of every evaluation.
pub fn run(problem: &Problem, searched: &Evaluation, progress: &dyn Progress) -> Verification {
    let dims = problem.study.variables.len();
    let steps = problem.study.verify_grid;
    let h = 1.0 / (steps - 1).max(1) as f64;
    let zs = points(steps, dims, h);
    let grid = super::global::sample(problem, &zs, progress);
    let feasible = grid.iter().filter(|e| e.feasible()).count();
    let best_point = best(grid.iter().filter(|e| e.feasible())).cloned();
    let searched_objective = if searched.feasible() {
        searched.objective
    } else {
        f64::INFINITY
    };
    // Grid points that beat the search and are the best of their neighbourhood.
    let better = |e: &Evaluation| e.feasible() && e.objective < searched_objective;
    let starts = seeds::local_minima(&zs, &grid, better, seeds::radius(h, dims));
    let refinements: Vec<LocalRun> = starts
        .par_iter()
        .map(|s| local::run(problem, s, h, progress))
        .collect();
    Verification {
        steps,
        points: grid.len(),
        feasible,
        best: best_point,
        searched_objective,
        refinements,
        margin: None,
    }
}
