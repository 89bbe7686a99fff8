//! Global stage: a dense, space-filling sample of the variable box and of the faces of the
//! feasible region, evaluated in parallel.
//!
//! Interior points are an Owen-scrambled Sobol sequence (the `sobol_burley` crate, Burley's
//! hash-based scrambling) with a fixed seed: evenly spread in every projection, without a
//! grid's alignment with the verification grid, and the same on every run.
//!
//! An interior sample never lands on a constraint, yet the objectives of these studies improve
//! towards the tip clearance (the positive-combination optima of the paper's design lie on
//! ΔRrp − ΔRp = 15 µm, in V-shaped valleys a few µm wide that a local method does not follow
//! from the interior). So each face of the box and each bound of the tip-clearance band (a
//! plane in the variables when shift or equidistant is one) gets its own Sobol sample of one
//! dimension less: a local run from the best face points then only has to move along the face.
//!
//! Results are collected in a fixed order (interior, then face by face), so the outcome does not
//! depend on the number of threads.

use super::problem::{point_at_unit, Evaluation, Problem};
use crate::model::study::MAX_GLOBAL_SAMPLES;
use crate::model::{Study, VariableKind};
use crate::progress::Progress;
use rayon::prelude::*;

/// The fixed scrambling seed of the interior sample (any value would do; this one is the
/// sequence's identity). Face k uses `SEED + 1 + k`.
const SEED: u32 = 12;

/// `n` Sobol points (at most `MAX_GLOBAL_SAMPLES`, the sequence's length) of the unit cube of
/// `dims` dimensions, in [0, 1), scrambled with `seed`.
fn sobol(n: usize, dims: usize, seed: u32) -> Vec<Vec<f64>> {
    (0..n.min(MAX_GLOBAL_SAMPLES) as u32)
        .map(|k| {
            (0..dims as u32)
                .map(|d| f64::from(sobol_burley::sample(k, d, seed)))
                .collect()
        })
        .collect()
}

/// A face of the feasible region: one coordinate of the unit cube set by the others.
#[derive(Debug, Clone, Copy)]
enum Face {
    /// Variable `index` at its lower (`upper` false) or upper bound.
    Box { index: usize, upper: bool },
    /// ΔRrp − ΔRp = `tip_mm`, solved for variable `index` (equidistant, else shift).
    Tip { index: usize, tip_mm: f64 },
}

/// The faces of a study's feasible region that are planes in its variables.
fn faces(study: &Study) -> Vec<Face> {
    let vars = &study.variables;
    let mut out: Vec<Face> = (0..vars.len())
        .flat_map(|index| [false, true].map(|upper| Face::Box { index, upper }))
        .collect();
    let solved = [VariableKind::Equidistant, VariableKind::Shift]
        .iter()
        .find_map(|&kind| vars.iter().position(|v| v.kind == kind));
    if let (Some(index), Some((lo, hi))) = (solved, study.tip_clearance_mm) {
        out.extend([lo, hi].map(|tip_mm| Face::Tip { index, tip_mm }));
    }
    out
}

/// The point of `face` at `u` (the other coordinates, in order), or None when the face's
/// plane leaves the box there.
fn on_face(study: &Study, face: Face, u: &[f64]) -> Option<Vec<f64>> {
    let index = match face {
        Face::Box { index, .. } | Face::Tip { index, .. } => index,
    };
    let mut z = u.to_vec();
    z.insert(index, 0.0);
    z[index] = match face {
        Face::Box { upper, .. } => f64::from(u8::from(upper)),
        Face::Tip { tip_mm, .. } => {
            let m = point_at_unit(study, &z).modification;
            let v = &study.variables[index];
            let value = match v.kind {
                VariableKind::Equidistant => m.shift_mm + tip_mm,
                _ => m.equidistant_mm - tip_mm,
            };
            let zi = v.unit_of(value);
            (0.0..=1.0).contains(&zi).then_some(zi)?
        }
    };
    Some(z)
}

/// The global sample in the unit cube: `global_samples` interior points, then
/// `boundary_samples` points on each face (one point per face for a single variable).
pub fn points(study: &Study) -> Vec<Vec<f64>> {
    let dims = study.variables.len();
    let mut out = sobol(study.global_samples, dims, SEED);
    let per_face = if dims == 1 { 1 } else { study.boundary_samples };
    for (k, &face) in faces(study).iter().enumerate() {
        let us = sobol(per_face, dims - 1, SEED + 1 + k as u32);
        out.extend(us.iter().filter_map(|u| on_face(study, face, u)));
    }
    out
}

/// Spacing of the interior sample in the unit cube: the side of a cell holding one point.
pub fn spacing(study: &Study) -> f64 {
    let dims = study.variables.len().max(1) as f64;
    (study.global_samples.max(1) as f64).powf(-1.0 / dims)
}

/// Evaluate the global sample at `zs` (infeasible points get no objective: they never seed a
/// local run), each told to `progress`; the verification grid's points are evaluated the same
/// way (`verify::run`).
pub fn sample(problem: &Problem, zs: &[Vec<f64>], progress: &dyn Progress) -> Vec<Evaluation> {
    zs.par_iter()
        .map(|z| {
            progress.advance(1);
            problem.evaluate_screened(&point_at_unit(problem.study, z), true)
        })
        .collect()
}
