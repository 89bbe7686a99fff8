//! Where local runs start: the sampled points that are the best of their neighbourhood, best
//! first (the start rule of multi-level single linkage, Rinnooy Kan and Timmer 1987: a local
//! run from a point with a better sample nearby would most likely end where that one's does).
//! Distinct valleys of the objective each get a run, instead of several runs in one valley.

use super::problem::Evaluation;

/// Most local runs started from one sample (besides the start of the study).
pub const LOCAL_SEEDS: usize = 4;

/// The neighbourhood radius, in the unit cube, for a sample of spacing `h`: a little more than
/// the diagonal of one cell, so that a point's nearest neighbours in every direction count.
pub fn radius(h: f64, dims: usize) -> f64 {
    1.01 * h * (dims.max(1) as f64).sqrt()
}

/// Of the evaluations `evals` at `zs` that `candidate` admits (feasible points), the best
/// first, those with no better candidate within `radius`: at most `LOCAL_SEEDS`. Equal
/// objectives rank by index, so the choice does not depend on evaluation order.
pub fn local_minima<'a>(
    zs: &[Vec<f64>],
    evals: &'a [Evaluation],
    candidate: impl Fn(&Evaluation) -> bool,
    radius: f64,
) -> Vec<&'a Evaluation> {
    let mut ranked: Vec<usize> = (0..evals.len()).filter(|&k| candidate(&evals[k])).collect();
    ranked.sort_by(|&a, &b| evals[a].objective.total_cmp(&evals[b].objective));
    let near = |a: usize, b: usize| {
        let d2: f64 = zs[a]
            .iter()
            .zip(&zs[b])
            .map(|(x, y)| (x - y) * (x - y))
            .sum();
        d2 <= radius * radius
    };
    let mut out = Vec::new();
    for (rank, &k) in ranked.iter().enumerate() {
        if out.len() == LOCAL_SEEDS {
            break;
        }
        if !ranked[..rank].iter().any(|&better| near(better, k)) {
            out.push(&evals[k]);
        }
    }
    out
}
