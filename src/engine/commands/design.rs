//! `design`: search a requirements file's design space for its Pareto front and return the
//! front with the spec of each of its designs; `design_shard` computes one shard of the
//! global stage, `merge_design_shards` and `design_from_shards` finish the search from them.

use super::check::{check, CheckOptions, CheckRun, ReviewOptions};
use crate::engine::design_search::{self, candidate, shard, Evaluation, SearchRun};
use crate::engine::scene::Writes;
use crate::error::{Error, Result};
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

/// The name of front design `k` (0-based): `design-01`, …; its review page is
/// `design-01/index.html`.
pub fn design_name(k: usize) -> String {
    format!("design-{:02}", k + 1)
}

/// The file name of front design `k` (0-based): `design-01.yaml`, …
pub fn design_file(k: usize) -> String {
    format!("{}.yaml", design_name(k))
}

/// The spec of front design `k` as written: the full check's scenes and limits, named after
/// the requirements, with a header saying where it comes from and its objectives.
pub fn front_spec(req: &Requirements, requirements_path: &str, k: usize, e: &Evaluation) -> String {
    let objectives: Vec<String> = req
        .objectives
        .iter()
        .zip(&e.objectives)
        .map(|(o, v)| format!("{} = {v}", o.name()))
        .collect();
    let header = format!(
        "Written by `cycloid design {requirements_path}`: design {} of the Pareto front of `{}`.\n\
         Objectives: {}.\n\
         It meets every requirement; `cycloid check` on this file passes.",
        k + 1,
        req.name,
        objectives.join(", ")
    );
    let name = format!("{}-{}", req.name, design_name(k));
    let raw = candidate::raw_spec(req, &e.candidate, &name, req.search.steps_per_mesh_period);
    super::spec_text::spec_text(&raw, &header)
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
    Ok(with_specs(req, requirements_path, search))
}

/// A search with the spec text of each front design.
fn with_specs(req: &Requirements, requirements_path: &str, search: SearchRun) -> DesignRun {
    let specs = search
        .front
        .iter()
        .enumerate()
        .map(|(k, e)| (design_file(k), front_spec(req, requirements_path, k, e)))
        .collect();
    DesignRun { search, specs }
}

/// The check of each front design's spec, in the front's order, as `check SPEC --report DIR`
/// runs it (the disc drawn where its smallest gap occurs, no objective maps): what each
/// design's own review page shows. The spec is read as `design_file(k)`.
pub fn front_checks(run: &DesignRun, progress: &dyn Progress) -> Result<Vec<CheckRun>> {
    let options = CheckOptions {
        writes: Writes {
            json: false,
            report: true,
        },
        tolerance: false,
        review: Some(ReviewOptions::PLAIN),
    };
    (run.specs.iter())
        .map(|(file, text)| check(&crate::spec::parse(file, text)?, &options, progress))
        .collect()
}

/// Shard `(i, n)` of the search of `req` (read as `text` from `requirements_path`): the
/// global stage's evaluations of the candidates j ≡ i (mod n), encoded as the shard file
/// that `merge_design_shards` reads.
///
/// ```
/// use cycloid::engine::commands::{design, design_from_shards, design_shard, merge_design_shards};
/// use cycloid::progress::Silent;
/// let path = "specs/requirements-robot-joint.yaml";
/// let text = std::fs::read_to_string(path).unwrap()
///     .replace("samples: 128", "samples: 2")
///     .replace("refine_budget: 20", "refine_budget: 0");
/// let req = cycloid::spec::requirements::parse(path, &text)?;
/// let shards: Vec<(String, Vec<u8>)> = (0..2)
///     .map(|i| Ok((format!("shard{i}"), design_shard(&req, path, &text, (i, 2), &Silent)?)))
///     .collect::<cycloid::Result<_>>()?;
/// // The merged shards give the unsharded run's front, bit for bit.
/// let merged = design_from_shards(merge_design_shards(&shards)?, &Silent)?;
/// let whole = design(&req, path, &Silent)?;
/// assert_eq!(merged.specs, whole.specs);
/// assert_eq!(merged.search.global, whole.search.global);
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn design_shard(
    req: &Requirements,
    requirements_path: &str,
    text: &str,
    (i, n): (u64, u64),
    progress: &dyn Progress,
) -> Result<Vec<u8>> {
    let all = design_search::global_candidates(req);
    let mine = shard::share(&all, (i, n));
    let what = format!("global stage, shard {i}/{n}: rules, screen, full check");
    let evaluations = design_search::global_stage(req, &mine, &what, progress)?;
    let header = shard::Header {
        text_sha256: shard::requirements_hash(text),
        seed: u64::from(req.search.seed),
        items: all.len() as u64,
        index: i,
        count: n,
        text_path: requirements_path.to_string(),
        text: text.to_string(),
    };
    Ok(shard::encode(&header, &evaluations))
}

/// The shards of one search joined: the requirements they carry and the global stage's
/// evaluations of every candidate, in the unsharded run's order.
#[derive(Debug, Clone)]
pub struct MergedDesign {
    pub requirements: Requirements,
    /// The requirements file's path as the shards were given it (the front's specs name it).
    pub requirements_path: String,
    /// SHA-256 of the requirements text the shards hold: the file they were made from, found
    /// by its content wherever it is (its recorded path is relative to an unknown directory).
    pub requirements_sha256: [u8; 32],
    pub evaluations: Vec<Evaluation>,
    /// Shards merged.
    pub shards: u64,
}

/// Check and join the shard files `(name, bytes)` of one search.
pub fn merge_design_shards(files: &[(String, Vec<u8>)]) -> Result<MergedDesign> {
    let shards = files
        .iter()
        .map(|(name, bytes)| shard::decode(name, bytes))
        .collect::<Result<Vec<_>>>()?;
    let names: Vec<String> = files.iter().map(|(name, _)| name.clone()).collect();
    let order = shard::check_set(&names, &shards)?;
    let h = shards[0].header.clone();
    let requirements = crate::spec::requirements::parse(&h.text_path, &h.text).map_err(|e| {
        Error::invalid_value(format!(
            "{}: the requirements the shards hold do not load in this cycloid: {}",
            names[0], e.message
        ))
    })?;
    // The shards in index order, moved (their evaluations move on into the search).
    let mut given: Vec<Option<(&str, shard::Shard)>> = names
        .iter()
        .map(String::as_str)
        .zip(shards)
        .map(Some)
        .collect();
    let ordered = order
        .iter()
        .map(|&i| given[i].take().expect("check_set places each shard once"))
        .collect();
    let evaluations = shard::merge(&requirements, ordered)?;
    Ok(MergedDesign {
        requirements_path: h.text_path,
        requirements_sha256: h.text_sha256,
        shards: h.count,
        requirements,
        evaluations,
    })
}

/// The search finished from merged shards: the local refinement of the front (it starts from
/// the front of every shard's evaluations, so it runs here, after the merge) and the front,
/// as the unsharded `design` gives it from the same evaluations (moved into the search, not
/// copied).
pub fn design_from_shards(merged: MergedDesign, progress: &dyn Progress) -> Result<DesignRun> {
    let search = design_search::finish(&merged.requirements, merged.evaluations, progress)?;
    Ok(with_specs(
        &merged.requirements,
        &merged.requirements_path,
        search,
    ))
}
