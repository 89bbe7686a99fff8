//! Optimisation of the tooth-profile modification (paper §4), done more carefully than a single
//! local search: the objectives are max − min of sampled curves, non-smooth with long flat
//! valleys, so a deterministic global stage (Halton sample of the box, in parallel) seeds
//! several local COBYLA runs (also in parallel), and the reported optimum is the best feasible
//! point evaluated anywhere, with every constraint re-checked on the exact geometry.

pub mod global;
pub mod local;
pub mod problem;
pub mod write;

use crate::model::Study;
use crate::spec::Spec;
use local::LocalRun;
use problem::{Evaluation, Problem};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// How many of the best feasible global samples seed a local run (besides the start).
pub const LOCAL_SEEDS: usize = 3;

/// The outcome of one study.
#[derive(Debug, Clone)]
pub struct StudyResult {
    pub name: String,
    pub start: Evaluation,
    pub references: Vec<(String, Evaluation)>,
    pub optimum: Evaluation,
    pub global: Vec<Evaluation>,
    pub local_runs: Vec<LocalRun>,
    /// Index into `local_runs` of the run that found the optimum, if a local run did.
    pub winner: Option<usize>,
    pub evaluations: usize,
    pub elapsed: Duration,
    pub stop_reason: String,
}

impl StudyResult {
    /// How the search went: evaluations, time and why it stopped.
    pub fn outcome(&self) -> String {
        format!(
            "{} evaluations ({} global, {} local runs) in {:.2} s; {}",
            self.evaluations,
            self.global.len(),
            self.local_runs.len(),
            self.elapsed.as_secs_f64(),
            self.stop_reason
        )
    }
}

fn best<'a>(candidates: impl IntoIterator<Item = &'a Evaluation>) -> Option<&'a Evaluation> {
    candidates
        .into_iter()
        .fold(None, |best: Option<&Evaluation>, e| match best {
            Some(b) if !e.better_than(b) => Some(b),
            _ => Some(e),
        })
}

/// Seeds of the local stage: the start, then the best distinct feasible global samples.
fn seeds(start: &Evaluation, global: &[Evaluation]) -> Vec<Evaluation> {
    let mut ranked: Vec<&Evaluation> = global.iter().filter(|e| e.feasible()).collect();
    ranked.sort_by(|a, b| a.objective.total_cmp(&b.objective));
    let mut out = vec![start.clone()];
    out.extend(ranked.into_iter().take(LOCAL_SEEDS).cloned());
    out
}

/// Run one study: global sample, local runs, best feasible point.
pub fn run_study(spec: &Spec, study: &Study) -> StudyResult {
    run_study_with(spec, study, None)
}

/// `run_study`, counting evaluations on a progress bar.
pub fn run_study_with(
    spec: &Spec,
    study: &Study,
    progress: Option<&indicatif::ProgressBar>,
) -> StudyResult {
    let clock = Instant::now();
    let problem = Problem::new(spec, study).with_progress(progress);
    let start = problem.evaluate(&study.start);
    let references: Vec<(String, Evaluation)> = study
        .references
        .iter()
        .map(|(label, m)| (label.clone(), problem.evaluate(m)))
        .collect();
    let global = global::sample(&problem);
    let local_runs: Vec<LocalRun> = seeds(&start, &global)
        .par_iter()
        .map(|s| local::run(&problem, s, study.local_evaluations))
        .collect();
    let all = std::iter::once(&start)
        .chain(&global)
        .chain(local_runs.iter().flat_map(|r| &r.path));
    let optimum = best(all).cloned().unwrap_or_else(|| start.clone());
    let winner = local_runs.iter().position(|r| r.path.contains(&optimum));
    let stop_reason = match winner {
        Some(k) => format!("local run {} {}", k + 1, local_runs[k].stop_reason),
        None => "the best point came from the global sample; every local run ended higher".into(),
    };
    StudyResult {
        name: study.name.clone(),
        evaluations: 1
            + references.len()
            + global.len()
            + local_runs.iter().map(|r| r.path.len()).sum::<usize>(),
        start,
        references,
        optimum,
        global,
        local_runs,
        winner,
        elapsed: clock.elapsed(),
        stop_reason,
    }
}

/// The objective over a `steps` × `steps` grid of the study's first two variables (the others
/// held at `around`), evaluated in parallel; rows in grid order.
pub fn map(
    spec: &Spec,
    study: &Study,
    steps: usize,
    around: &crate::model::Modification,
) -> Vec<Evaluation> {
    let problem = Problem::new(spec, study);
    let vars = &study.variables;
    let axis = |k: usize, i: usize| {
        let v = &vars[k];
        v.lower + (v.upper - v.lower) * i as f64 / (steps - 1).max(1) as f64
    };
    let cells: Vec<(usize, usize)> = (0..steps)
        .flat_map(|i| (0..if vars.len() > 1 { steps } else { 1 }).map(move |j| (i, j)))
        .collect();
    cells
        .par_iter()
        .map(|&(i, j)| {
            let mut m = *around;
            vars[0].kind.set(&mut m, axis(0, i));
            if vars.len() > 1 {
                vars[1].kind.set(&mut m, axis(1, j));
            }
            problem.evaluate(&m)
        })
        .collect()
}
