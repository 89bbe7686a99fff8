//! `design`: search a requirements file's design space for its Pareto front and return the
//! front with the spec of each of its designs.

use crate::engine::design_search::{self, candidate, Evaluation, SearchRun};
use crate::error::Result;
use crate::model::requirements::Requirements;
use crate::progress::Progress;

/// A search and the spec text of each front design.
#[derive(Debug, Clone)]
pub struct DesignRun {
    pub search: SearchRun,
    /// (file name, spec text) per front design, in the front's order.
    pub specs: Vec<(String, String)>,
}

impl DesignRun {
    /// Some design met every requirement.
    pub fn feasible(&self) -> bool {
        !self.search.front.is_empty()
    }
}

/// The file name of front design `k` (0-based): `design-01.yaml`, …
pub fn design_file(k: usize) -> String {
    format!("design-{:02}.yaml", k + 1)
}

/// The spec of front design `k` as written: the full check's scenes and limits, named after
/// the requirements, with a header saying where it comes from and its objectives.
pub fn front_spec(req: &Requirements, requirements_path: &str, k: usize, e: &Evaluation) -> String {
    let objectives: Vec<String> = req
        .objectives
        .iter()
        .zip(&e.objectives)
        .map(|(o, v)| format!("{} = {v}", o.key()))
        .collect();
    let header = format!(
        "Written by `cycloid design {requirements_path}`: design {} of the Pareto front of `{}`.\n\
         Objectives: {}.\n\
         It meets every requirement; `cycloid check` on this file passes.",
        k + 1,
        req.name,
        objectives.join(", ")
    );
    candidate::spec_text(
        req,
        &e.candidate,
        &format!("{}-design-{:02}", req.name, k + 1),
        req.search.steps_per_mesh_period,
        &header,
    )
}

/// Search `req`'s design space (read from `requirements_path`, named in the specs' headers).
///
/// ```no_run
/// let req = cycloid::spec::requirements::load("specs/requirements-robot-joint.yaml")?;
/// let run = cycloid::engine::commands::design(&req, "specs/requirements-robot-joint.yaml",
///     &cycloid::progress::Silent)?;
/// assert!(run.feasible());
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn design(
    req: &Requirements,
    requirements_path: &str,
    progress: &dyn Progress,
) -> Result<DesignRun> {
    let search = design_search::search(req, progress)?;
    let specs = search
        .front
        .iter()
        .enumerate()
        .map(|(k, e)| (design_file(k), front_spec(req, requirements_path, k, e)))
        .collect();
    Ok(DesignRun { search, specs })
}
