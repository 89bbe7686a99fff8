//! `optimise`: the spec's optimisation studies, and the first one's objective map.

use super::check::{map_steps_allowed, studies, MAX_MAP_STEPS};
use crate::engine::optimise::{map, problem::Evaluation, StudyResult};
use crate::error::{Error, Result};
use crate::model::Study;
use crate::progress::Progress;
use crate::spec::Spec;

/// The studies run, in spec order (or the one asked for), with their results.
pub struct OptimiseRun<'a> {
    pub studies: Vec<(&'a Study, StudyResult)>,
    /// The first study's objective over a grid around its optimum, when asked for.
    pub map: Option<Vec<Evaluation>>,
}

impl OptimiseRun<'_> {
    /// Every optimum meets the constraints.
    pub fn feasible(&self) -> bool {
        self.studies.iter().all(|(_, r)| r.optimum.feasible())
    }
}

/// Run the study named `only` (else every study) of `spec`; with `map_steps`, the first
/// study's objective over that many grid points per variable around its optimum.
///
/// ```
/// let spec = cycloid::spec::load("specs/paper.yaml")?;
/// let name = spec.studies[0].name.clone();
/// let run = cycloid::optimise(&spec, Some(&name), Some(3), &cycloid::progress::Silent)?;
/// assert_eq!(run.studies.len(), 1);
/// assert!(run.feasible());
/// assert_eq!(run.map.map(|cells| cells.len()), Some(9)); // 3 × 3 grid of two variables
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn optimise<'a>(
    spec: &'a Spec,
    only: Option<&str>,
    map_steps: Option<usize>,
    progress: &dyn Progress,
) -> Result<OptimiseRun<'a>> {
    let chosen = chosen(spec, only)?;
    if let Some(steps) = map_steps.filter(|&s| !map_steps_allowed(s)) {
        return Err(Error::invalid_value(format!(
            "an objective map has 2 to {MAX_MAP_STEPS} steps per variable, got {steps}"
        )));
    }
    let results = studies(spec, chosen.clone(), progress);
    let map = match (map_steps, results.first()) {
        (Some(steps), Some(r)) => Some(map(spec, chosen[0], steps, &r.optimum.point, progress)),
        _ => None,
    };
    Ok(OptimiseRun {
        studies: chosen.into_iter().zip(results).collect(),
        map,
    })
}

/// The studies to run: the one named `only`, else all; a spec without studies is refused.
fn chosen<'a>(spec: &'a Spec, only: Option<&str>) -> Result<Vec<&'a Study>> {
    if spec.studies.is_empty() {
        return Err(Error::invalid_value(format!(
            "{}: the spec has no `optimise` section",
            spec.path
        )));
    }
    let Some(name) = only else {
        return Ok(spec.studies.iter().collect());
    };
    let study = spec
        .studies
        .iter()
        .find(|s| s.name == name)
        .ok_or_else(|| {
            Error::invalid_value(format!(
                "no study named `{name}`; studies: {}",
                spec.studies
                    .iter()
                    .map(|s| s.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })?;
    Ok(vec![study])
}
