//! Global stage: a Halton low-discrepancy sample of the variable box, evaluated in parallel.
//! The sample is deterministic (no random numbers), and results are collected in sample order,
//! so the outcome does not depend on the number of threads.

use super::problem::{Evaluation, Problem};
use rayon::prelude::*;

const PRIMES: [u32; 3] = [2, 3, 5];

/// k-th element (k ≥ 1) of the van der Corput sequence in `base`, in (0, 1).
pub fn radical_inverse(mut k: u64, base: u32) -> f64 {
    let b = base as u64;
    let (mut value, mut scale) = (0.0, 1.0 / base as f64);
    while k > 0 {
        value += (k % b) as f64 * scale;
        k /= b;
        scale /= base as f64;
    }
    value
}

/// `n` Halton points in the unit cube of `dims` (≤ 3) dimensions, skipping the origin.
pub fn halton(n: usize, dims: usize) -> Vec<Vec<f64>> {
    (1..=n as u64)
        .map(|k| {
            PRIMES[..dims]
                .iter()
                .map(|&p| radical_inverse(k, p))
                .collect()
        })
        .collect()
}

/// Map a unit-cube point to variable values.
pub fn scale(problem: &Problem, z: &[f64]) -> Vec<f64> {
    problem
        .study
        .variables
        .iter()
        .zip(z)
        .map(|(v, &zi)| v.lower + zi * (v.upper - v.lower))
        .collect()
}

/// Evaluate the study's global sample (infeasible points get no objective: they never seed a
/// local run).
pub fn sample(problem: &Problem) -> Vec<Evaluation> {
    let dims = problem.study.variables.len();
    halton(problem.study.global_samples, dims)
        .par_iter()
        .map(|z| problem.evaluate_screened(&problem.modification_at(&scale(problem, z)), true))
        .collect()
}
