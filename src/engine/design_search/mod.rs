//! `cycloid design`: the search of a requirements file's design space for its Pareto front.
//!
//! Stages, cheapest first (`evaluate`): the envelope and design rules (no physics, `rules`, and
//! the spec's own `spec::rules` when the candidate's spec is parsed), a screen (the scenes at
//! every fourth crank angle, judged on the limits that fewer angles can only make easier) and
//! the full check of the spec a front design is written as (`candidate::raw_spec`, validated
//! as any spec by `spec::from_raw`: no text is written or parsed while searching).
//!
//! Global stage: per discrete choice (ratio × pin count × discs) an Owen-scrambled Sobol
//! sample (`sobol_burley`) of the continuous box, the seed and the choice's index making its
//! scrambling. Local stage (`refine`): from each front design a pattern search that accepts
//! a move only to a feasible design dominating it, then the front of everything feasible again
//! (two rounds). Everything runs in parallel and is collected in a fixed order, so a seed gives
//! the same front on any number of threads, and on any number of processes (`shard`: each
//! computes a share of the global stage, a merge the rest from their evaluations). With no
//! feasible design, `missed` counts per requirement what the designs met and names the cause
//! from every requirement each design missed (`failure`).

pub mod candidate;
pub mod evaluate;
pub mod failure;
pub mod missed;
pub mod pareto;
pub mod refine;
pub mod rules;
pub mod shard;

pub use crate::model::requirements::Variables;
pub use candidate::{Candidate, Choice};
pub use evaluate::{Evaluation, Failure, Stage, Tally};
pub use missed::Infeasible;

use crate::error::Result;
use crate::model::requirements::Requirements;
use crate::progress::{Phase, Progress};
use rayon::prelude::*;

/// Rounds of local refinement (each refines the front designs not refined yet).
const REFINE_ROUNDS: usize = 2;

/// The outcome of a search.
#[derive(Debug, Clone)]
pub struct SearchRun {
    /// The front, sorted by the first objective: non-dominated feasible designs.
    pub front: Vec<Evaluation>,
    /// What the global stage did.
    pub global: Tally,
    /// What the local refinement did.
    pub local: Tally,
    /// When no design is feasible: what was closest.
    pub infeasible: Option<Infeasible>,
}

/// The discrete choices in a fixed order: ratio, then pin count, then discs.
pub fn choices(req: &Requirements) -> Vec<Choice> {
    let s = &req.search;
    let mut out = Vec::new();
    for &teeth in &req.ratios {
        for &pins in &s.pin_counts {
            for &discs in &s.discs {
                out.push(Choice { teeth, pins, discs });
            }
        }
    }
    out
}

/// How many candidates `global_candidates` gives: choices × samples, without building them
/// (`--shard I/N` takes N at most this).
pub fn global_candidate_count(req: &Requirements) -> u64 {
    choices(req).len() as u64 * req.search.samples as u64
}

/// The global stage's candidates: `samples` scrambled Sobol points of the box per choice.
pub fn global_candidates(req: &Requirements) -> Vec<Candidate> {
    let space = &req.search.continuous;
    let mut out = Vec::new();
    for (i, choice) in choices(req).into_iter().enumerate() {
        let seed = req
            .search
            .seed
            .wrapping_mul(0x9E37_79B9)
            .wrapping_add(i as u32);
        for k in 0..req.search.samples as u32 {
            let u = std::array::from_fn(|d| f64::from(sobol_burley::sample(k, d as u32, seed)));
            out.push(Candidate::at(choice, space, &u));
        }
    }
    out
}

/// The front of the feasible evaluations of `all`, in `all`'s order.
pub fn front_of(req: &Requirements, all: &[Evaluation]) -> Vec<Evaluation> {
    let feasible: Vec<&Evaluation> = all.iter().filter(|e| e.feasible()).collect();
    let points: Vec<Vec<f64>> = feasible.iter().map(|e| e.minimised(req)).collect();
    let refs: Vec<&[f64]> = points.iter().map(Vec::as_slice).collect();
    pareto::front(&refs)
        .into_iter()
        .map(|k| feasible[k].clone())
        .collect()
}

/// Search the requirements' design space for its Pareto front.
pub fn search(req: &Requirements, progress: &dyn Progress) -> Result<SearchRun> {
    let candidates = global_candidates(req);
    let all = global_stage(
        req,
        &candidates,
        "global stage: rules, screen, full check",
        progress,
    )?;
    finish(req, all, progress)
}

/// The global stage's evaluations of `candidates`, in parallel, in their order, heard as
/// `what` (a unit per candidate).
pub fn global_stage(
    req: &Requirements,
    candidates: &[Candidate],
    what: &str,
    progress: &dyn Progress,
) -> Result<Vec<Evaluation>> {
    let phase = progress.phase(&Phase::slow(what, "designs", candidates.len() as u64));
    candidates
        .par_iter()
        .map(|c| {
            let e = evaluate::evaluate(req, c);
            phase.advance(1);
            e
        })
        .collect()
}

/// The search from the global stage's evaluations of every candidate (`all`, in the order of
/// `global_candidates`): the local refinement of the front, the front of everything feasible,
/// and what no design met when nothing is feasible. An unsharded search and a merge of shards
/// both end here, so from the same evaluations they give the same run.
pub fn finish(
    req: &Requirements,
    mut all: Vec<Evaluation>,
    progress: &dyn Progress,
) -> Result<SearchRun> {
    let mut global = Tally::default();
    all.iter().for_each(|e| global.add(e));
    let mut local = Tally::default();
    let mut refined: Vec<Candidate> = Vec::new();
    for _ in 0..REFINE_ROUNDS {
        let starts: Vec<Evaluation> = front_of(req, &all)
            .into_iter()
            .filter(|e| !refined.contains(&e.candidate))
            .collect();
        if starts.is_empty() || req.search.refine_budget == 0 {
            break;
        }
        refined.extend(starts.iter().map(|e| e.candidate));
        let phase = progress.phase(&Phase::slow(
            "local refinement of the front",
            "designs",
            (starts.len() * req.search.refine_budget) as u64,
        ));
        let runs: Vec<Vec<Evaluation>> = starts
            .par_iter()
            .map(|s| refine::refine(req, s, &*phase))
            .collect::<Result<_>>()?;
        for e in runs.into_iter().flatten() {
            local.add(&e);
            all.push(e);
        }
    }
    let mut front = front_of(req, &all);
    front.sort_by(|a, b| {
        a.minimised(req)
            .partial_cmp(&b.minimised(req))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let infeasible = front.is_empty().then(|| missed::diagnose(req, &all));
    Ok(SearchRun {
        front,
        global,
        local,
        infeasible,
    })
}
