//! Optimisation of the tooth-profile modification (paper §4), done as a global search: the
//! objectives are max − min of sampled curves, non-smooth, with many narrow valleys (along
//! ΔRrp − ΔRp ≈ const near the tip-clearance bound on the paper's design), where a plain local
//! method stops in the first valley it meets. So:
//!
//! 1. a dense, deterministic space-filling sample of the box (`global`, `global_samples`
//!    points, in parallel; infeasible points are screened out before their loaded sweep);
//! 2. COBYLA runs (`local`, in parallel) from the start and from the samples that are the best
//!    of their neighbourhood (`seeds`), each in its own valley, with initial steps of the
//!    sample's spacing;
//! 3. a verification grid (`verify`, `verify_grid` points per variable): when a grid point
//!    beats the search's optimum, local runs refine from there; the result says by how much
//!    the best grid point is above the final optimum.
//!
//! The optimum is the best feasible point evaluated anywhere, with every constraint checked on
//! the exact geometry. Everything is collected in a fixed order, so the optimum is the same bit
//! for bit whatever the number of threads.

pub mod global;
pub mod local;
pub mod problem;
pub mod seeds;
pub mod verify;

use crate::model::Study;
use crate::progress::{Phase, Progress};
use crate::spec::Spec;
use local::{LocalRun, StopReason};
use problem::{best, Evaluation, Problem};
use rayon::prelude::*;
use std::time::{Duration, Instant};
use verify::Verification;

/// Where the optimum was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Found {
    /// The study's start is the best point evaluated.
    Start,
    /// A point of the global sample (index into `StudyResult::global`), better than every
    /// local run.
    GlobalSample(usize),
    /// A local run of the search (index into `StudyResult::local_runs`) and why it stopped.
    LocalRun(usize, StopReason),
    /// A point of the verification grid, better than the search and its refinements.
    GridPoint,
    /// A local run from a grid point that beat the search (index into
    /// `Verification::refinements`) and why it stopped.
    Refinement(usize, StopReason),
}

/// The outcome of one study. Every evaluation keeps its modification, objective terms and
/// constraint margins, so the result can be written out (JSON) as it is.
#[derive(Debug, Clone)]
pub struct StudyResult {
    /// The study's name.
    pub name: String,
    /// The study's start, with its min clearance and lost motion.
    pub start: Evaluation,
    /// Each reference (label, evaluation), with its min clearance and lost motion.
    pub references: Vec<(String, Evaluation)>,
    /// The best feasible point evaluated anywhere (the least infeasible one when none is
    /// feasible), with its min clearance and lost motion.
    pub optimum: Evaluation,
    /// Where the optimum was found.
    pub found: Found,
    /// The global sample, in sample order (infeasible points carry no objective).
    pub global: Vec<Evaluation>,
    /// The local runs of the search: from the start, then from the seeds, best seed first.
    pub local_runs: Vec<LocalRun>,
    /// The verification grid and its refinements (None when `verify_grid` is 0).
    pub verification: Option<Verification>,
    /// Every evaluation of the study (start, references, global, local, verification).
    pub evaluations: usize,
    /// Wall-clock time of the study.
    pub elapsed: Duration,
}

impl StudyResult {
    /// Index of the local run of the search that found the optimum, if one did.
    pub fn winner(&self) -> Option<usize> {
        match self.found {
            Found::LocalRun(k, _) => Some(k),
            _ => None,
        }
    }
}

/// Most evaluations a study can take (for a progress bar): the start and references, the
/// global sample, every local run at its budget, the verification grid and as many
/// refinements as local seeds. Local runs often stop early.
pub fn most_evaluations(study: &Study) -> usize {
    let dims = study.variables.len() as u32;
    let grid = if study.verify_grid >= 2 {
        study.verify_grid.pow(dims)
    } else {
        0
    };
    let runs = 1 + 2 * seeds::LOCAL_SEEDS;
    1 + study.references.len() + global::points(study).len() + grid + runs * study.local_evaluations
}

/// Run one study: global sample, local runs, verification grid, best feasible point;
/// `progress` hears of every evaluation.
pub fn run_study(spec: &Spec, study: &Study, progress: &dyn Progress) -> StudyResult {
    let clock = Instant::now();
    let problem = Problem::new(spec, study);
    let dims = study.variables.len();
    progress.advance(1 + study.references.len() as u64);
    let start = problem.evaluate_point(&study.start_point());
    let references: Vec<(String, Evaluation)> = study
        .references
        .iter()
        .map(|(label, m)| (label.clone(), problem.evaluate(m)))
        .collect();
    let zs = global::points(study);
    let global = global::sample(&problem, &zs, progress);
    let h = global::spacing(study);
    let seeds = seeds::local_minima(&zs, &global, Evaluation::feasible, seeds::radius(h, dims));
    let starts: Vec<&Evaluation> = std::iter::once(&start).chain(seeds).collect();
    let local_runs: Vec<LocalRun> = starts
        .par_iter()
        .map(|s| local::run(&problem, s, h, progress))
        .collect();
    let searched = best(
        std::iter::once(&start)
            .chain(&global)
            .chain(local_runs.iter().map(|r| &r.best)),
    )
    .cloned()
    .unwrap_or_else(|| start.clone());
    let mut verification =
        (study.verify_grid >= 2).then(|| verify::run(&problem, &searched, progress));
    let refined = verification
        .iter()
        .flat_map(|v| v.best.iter().chain(v.refinements.iter().map(|r| &r.best)));
    let optimum = best(std::iter::once(&searched).chain(refined))
        .cloned()
        .unwrap_or(searched);
    let found = found(
        &optimum,
        &start,
        &global,
        &local_runs,
        verification.as_ref(),
    );
    if let Some(v) = verification.as_mut() {
        v.margin = match (&v.best, optimum.feasible()) {
            (Some(b), true) => Some(b.objective - optimum.objective),
            _ => None,
        };
    }
    let evaluations = 1
        + references.len()
        + global.len()
        + local_runs.iter().map(|r| r.path.len()).sum::<usize>()
        + verification.as_ref().map_or(0, |v| {
            v.points + v.refinements.iter().map(|r| r.path.len()).sum::<usize>()
        });
    StudyResult {
        name: study.name.clone(),
        start: problem.describe(start),
        references: references
            .into_iter()
            .map(|(l, e)| (l, problem.describe(e)))
            .collect(),
        optimum: problem.describe(optimum),
        found,
        global,
        local_runs,
        verification,
        evaluations,
        elapsed: clock.elapsed(),
    }
}

/// Where `optimum` came from: a local run whose path holds it first (a run evaluates its own
/// start again, so an optimum that is the start or a global sample is usually reported as the
/// run from it), else the start, a global sample, a refinement of the verification grid, or a
/// grid point.
fn found(
    optimum: &Evaluation,
    start: &Evaluation,
    global: &[Evaluation],
    local_runs: &[LocalRun],
    verification: Option<&Verification>,
) -> Found {
    let holds = |run: &LocalRun| run.path.contains(optimum);
    if let Some(k) = local_runs.iter().position(holds) {
        return Found::LocalRun(k, local_runs[k].stop);
    }
    if optimum == start {
        return Found::Start;
    }
    if let Some(i) = global.iter().position(|g| g == optimum) {
        return Found::GlobalSample(i);
    }
    match verification.and_then(|v| v.refinements.iter().position(holds).map(|k| (v, k))) {
        Some((v, k)) => Found::Refinement(k, v.refinements[k].stop),
        None => Found::GridPoint,
    }
}

/// The objective over a `steps` × `steps` grid of the study's first two variables (the others
/// held at `around`), evaluated in parallel, its cells counted in a phase of `progress`; rows
/// in grid order.
pub fn map(
    spec: &Spec,
    study: &Study,
    steps: usize,
    around: &crate::model::Point,
    progress: &dyn Progress,
) -> Vec<Evaluation> {
    let problem = Problem::new(spec, study);
    let vars = &study.variables;
    let axis = |k: usize, i: usize| {
        let v = &vars[k];
        if v.logarithmic() {
            v.at_unit(i as f64 / (steps - 1).max(1) as f64)
        } else {
            v.lower + (v.upper - v.lower) * i as f64 / (steps - 1).max(1) as f64
        }
    };
    let cells: Vec<(usize, usize)> = (0..steps)
        .flat_map(|i| (0..if vars.len() > 1 { steps } else { 1 }).map(move |j| (i, j)))
        .collect();
    let what = format!("objective map of `{}`", study.name);
    let heard = progress.phase(&Phase::new(what, "cells", cells.len() as u64));
    cells
        .par_iter()
        .map(|&(i, j)| {
            let mut m = *around;
            vars[0].kind.set(&mut m, axis(0, i));
            if vars.len() > 1 {
                vars[1].kind.set(&mut m, axis(1, j));
            }
            heard.advance(1);
            problem.evaluate_point(&m)
        })
        .collect()
}
