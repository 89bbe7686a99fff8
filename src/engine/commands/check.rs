//! `check`: every scene of a spec, its limits and golden curves, its optimisation studies, the
//! accuracy scene's resolution, and on request the tolerance study and what the design review
//! shows. Returns data; the terminal table, JSON, JUnit and the review are built in `report`.

use super::tolerance;
use crate::engine::accuracy::{self, Ladder};
use crate::engine::as_built;
use crate::engine::drawing::{self, Disc};
use crate::engine::golden::{self, GoldenResult};
use crate::engine::mass_properties::{mass_properties, unbalances, MassProperties, Unbalance};
use crate::engine::optimise::{self, problem::Evaluation, StudyResult};
use crate::engine::resolution::{self, Resolution};
use crate::engine::scene::{self, Writes};
use crate::engine::summary::{self, SceneSummary};
use crate::engine::torque_curve;
use crate::engine::verdict::{self, Check};
use crate::error::{Error, Result};
use crate::measure::fit::Identification;
use crate::model::results::{SceneResult, TorqueCurve};
use crate::model::{Modification, Study};
use crate::progress::{Budget, Phase, Progress};
use crate::spec::Spec;

/// Largest grid of an objective map, per variable (101² = 10 201 evaluations per study).
pub const MAX_MAP_STEPS: usize = 101;

/// An objective map of `steps` grid points per variable can be drawn: 2 to `MAX_MAP_STEPS`.
pub fn map_steps_allowed(steps: usize) -> bool {
    (2..=MAX_MAP_STEPS).contains(&steps)
}

/// What a `check` computes besides the scenes' limits and goldens.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CheckOptions {
    /// The output files that read every quantity of every scene (more of each effect is
    /// recorded for them).
    pub writes: Writes,
    /// Also run the Monte Carlo of the spec's `tolerances:`; its failure rate joins the checks.
    pub tolerance: bool,
    /// Compute what the design review shows: the disc drawing, the objective maps, the
    /// accuracy ladder, and each scene as designed beside as built.
    pub review: Option<ReviewOptions>,
}

/// What the design review is drawn from, checked where it is made (`ReviewOptions::new`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReviewOptions {
    /// Crank angle of the disc drawing, rad; `None`: where the smallest gap occurs.
    crank_rad: Option<f64>,
    /// Grid points per variable of each study's objective map: 0 (no map) or 2 to
    /// `MAX_MAP_STEPS`.
    map_steps: usize,
}

impl ReviewOptions {
    /// The disc drawn where the smallest gap occurs, no objective maps.
    pub const PLAIN: ReviewOptions = ReviewOptions {
        crank_rad: None,
        map_steps: 0,
    };

    /// The review's options as `check --report` takes them (`--report-crank-deg`,
    /// `--report-map-steps`): the drawing's crank angle, degrees, finite and within the crank
    /// angles a spec may give; the maps 0 (none) or 2 to `MAX_MAP_STEPS` steps.
    pub fn new(crank_deg: Option<f64>, map_steps: usize) -> Result<Self> {
        let bad = |m: String| Err(Error::invalid_value(m));
        if let Some(deg) = crank_deg.filter(|d| !d.is_finite()) {
            return bad(format!(
                "--report-crank-deg must be a finite angle, got {deg}"
            ));
        }
        let max = crate::spec::MAX_CRANK_DEG;
        if let Some(deg) = crank_deg.filter(|d| d.abs() > max) {
            return bad(format!(
                "--report-crank-deg {} is beyond ±{max}°, the crank angles a spec may give (the \
                 angle's rounding would exceed 1e-9 rad)",
                crate::numeric::input(deg)
            ));
        }
        if map_steps != 0 && !map_steps_allowed(map_steps) {
            return bad(format!(
                "--report-map-steps must be 0 (no map) or 2 to {MAX_MAP_STEPS}, got {map_steps}"
            ));
        }
        Ok(ReviewOptions {
            crank_rad: crank_deg.map(crate::units::rad),
            map_steps,
        })
    }
}

/// Everything one `check` computed.
#[derive(Debug, Clone)]
pub struct CheckRun {
    /// The spec the checks ran on: with `measured_profile`, the disc as built (the identified
    /// modification and form error in place of the drawing's).
    pub spec: Spec,
    /// The identified disc, when the spec has measured points.
    pub as_built: Option<AsBuilt>,
    /// One result per scene, in spec order.
    pub results: Vec<SceneResult>,
    /// Limits, studies, goldens, the resolution and the tolerance study, in that order.
    pub checks: Vec<Check>,
    pub goldens: Vec<GoldenResult>,
    pub summaries: Vec<SceneSummary>,
    /// One result per optimisation study, in spec order.
    pub studies: Vec<StudyResult>,
    /// The accuracy scene's crank resolution, when the spec has `accuracy:`.
    pub resolution: Option<Resolution>,
    /// What the design review shows, when asked for.
    pub review: Option<Review>,
    /// The discs' mass properties and the inertia at the input (of the disc as built, when
    /// measured).
    pub mass: MassProperties,
    /// What the discs' centripetal forces leave on the crank, per scene that computes
    /// `inertia`.
    pub unbalance: Vec<Unbalance>,
}

impl CheckRun {
    /// Every check passed.
    pub fn passed(&self) -> bool {
        self.checks.iter().all(|c| c.passed)
    }
}

/// The disc as built, beside the drawing.
#[derive(Debug, Clone)]
pub struct AsBuilt {
    pub identification: Identification,
    /// The spec's own modification, as designed.
    pub designed_modification: Modification,
    /// Each scene as designed, when the review shows them beside the results as built.
    pub designed: Option<Vec<SceneResult>>,
}

/// What the design review draws besides the results.
#[derive(Debug, Clone)]
pub struct Review {
    /// The disc at the drawing's crank angle.
    pub disc: Disc,
    /// Each study's objective map (empty without a map), in spec order.
    pub maps: Vec<Vec<Evaluation>>,
    /// Grid points per variable of the maps.
    pub map_steps: usize,
    /// The accuracy ladder of the spec's `accuracy:` scene and its wall-clock time, s.
    pub ladder: Option<(Ladder, f64)>,
    /// Each scene's mean efficiency against its output torque (`None`: no efficiency).
    pub efficiency: Vec<Option<TorqueCurve>>,
    /// Each tilted scene's line load along the face, tilted and as designed.
    pub face: Vec<crate::engine::face_profile::FaceProfile>,
    /// The disc as a solid, to picture beside the drawing (`None`: `profile` would not
    /// export it).
    pub solid: Option<super::solid_picture::SolidPicture>,
}

/// Run every scene of `spec`, check its limits and goldens, run its studies, and what
/// `options` asks for besides. Errors about a spec key carry its location in the spec.
///
/// ```
/// use cycloid::{check, CheckOptions};
/// let spec = cycloid::spec::load("specs/reducer.yaml")?;
/// let run = check(&spec, &CheckOptions::default(), &cycloid::progress::Silent)?;
/// // The paper's optimum keeps its 15 µm tip clearance over the whole mesh.
/// let clearance = run.checks.iter().find(|c| c.id.ends_with("min_clearance_mm")).unwrap();
/// assert!(run.passed() && clearance.value >= 0.015);
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn check(spec: &Spec, options: &CheckOptions, progress: &dyn Progress) -> Result<CheckRun> {
    run(spec, options, progress).map_err(|e| spec.locate(e))
}

fn run(drawing: &Spec, options: &CheckOptions, progress: &dyn Progress) -> Result<CheckRun> {
    let identified = as_built::identify(drawing)?;
    let mut as_built = None;
    let spec = match identified {
        Some((built, identification)) => {
            // The design review shows each scene as designed beside as built.
            let designed = match options.review {
                // As designed: without the tilt as built (`reducer.deviations.misalignment`),
                // which the disc as built runs with.
                Some(_) => {
                    let mut designed = drawing.clone();
                    designed.design.deviations.misalignment = Default::default();
                    Some(scene::run_all(&designed, options.writes, progress)?)
                }
                None => None,
            };
            as_built = Some(AsBuilt {
                identification,
                designed_modification: drawing.modification,
                designed,
            });
            built
        }
        None => drawing.clone(),
    };
    // Read the golden files before computing anything: a missing one fails fast.
    let golden_curves = golden::load_all(&spec)?;
    let results = scene::run_all(&spec, options.writes, progress)?;
    let summaries = summary::marked(&spec, &results);
    all_finite(&summaries)?;
    let mut checks = verdict::evaluate(&spec, &summaries)?;
    let studies = studies(&spec, spec.studies.iter().collect(), progress);
    checks.extend(verdict::optimisation(&spec, &studies));
    let goldens = golden::evaluate(&spec, &results, &golden_curves)?;
    checks.extend(goldens.iter().map(Check::from_golden));
    // The full accuracy ladder runs only for the design review; `check` alone runs the steps
    // rungs it needs to judge the accuracy scene's resolution (`engine::resolution`).
    let ladder = match (&spec.accuracy, options.review) {
        (Some(a), Some(_)) => Some(ladder(&spec, a, progress)?),
        _ => None,
    };
    let resolution = match (&spec.accuracy, &ladder) {
        (Some(_), Some((l, _))) => Some(resolution::of_ladder(l)),
        (Some(a), None) => Some(resolution::run(&spec, a.scene, &a.options)?),
        _ => None,
    };
    if let (true, Some(r)) = (spec.limits.accuracy_resolved, &resolution) {
        checks.push(verdict::resolution(r));
    }
    if options.tolerance {
        // The study draws from the drawing, whatever disc the other checks run on.
        checks.push(tolerance::failure_rate_check(drawing, progress)?);
    }
    let review = match options.review {
        Some(r) => Some(Review {
            disc: drawing::disc(
                &spec,
                r.crank_rad
                    .unwrap_or_else(|| drawing::default_crank_rad(&results)),
            )?,
            maps: maps(&spec, &studies, r.map_steps, progress),
            map_steps: r.map_steps,
            ladder,
            efficiency: spec
                .scenes
                .iter()
                .map(|s| torque_curve::torque_curve(&spec, s))
                .collect::<Result<_>>()?,
            face: crate::engine::face_profile::face_profiles(&spec, &results)?,
            solid: super::solid_picture::solid_picture(drawing)?,
        }),
        None => None,
    };
    let mass = mass_properties(&spec);
    Ok(CheckRun {
        unbalance: unbalances(&spec, &mass.disc),
        mass,
        spec,
        as_built,
        results,
        checks,
        goldens,
        summaries,
        studies,
        resolution,
        review,
    })
}

/// The last guard against a false pass: a scalar of the registry that is not a finite number
/// (an input the spec's bounds let through, a computation that overflowed) is an error naming
/// the scene and the quantity, never a figure a limit compares or a page shows. (A life with
/// no finite bound is `UNBOUNDED_LIFE_H`, the largest double: a finite number.)
fn all_finite(summaries: &[SceneSummary]) -> Result<()> {
    for s in summaries {
        let beyond = (s.scalars.iter()).find(|(_, x)| !x.value.is_finite());
        if let Some((q, x)) = beyond {
            return Err(Error::computation(format!(
                "scene `{}`: {} is {}, not a finite number: the inputs are beyond what the \
                 model computes; nothing is judged",
                s.scene, q.key, x.value
            )));
        }
    }
    Ok(())
}

/// Studies in parallel, in the order given, their evaluations counted.
pub fn studies(spec: &Spec, studies: Vec<&Study>, progress: &dyn Progress) -> Vec<StudyResult> {
    use rayon::prelude::*;
    if studies.is_empty() {
        return Vec::new();
    }
    // At most this many evaluations: local runs often stop before their budget, so each
    // study's unused budget counts as done when it ends, and the count ends full.
    let most: usize = studies.iter().map(|s| optimise::most_evaluations(s)).sum();
    let what = format!(
        "optimising {} stud{}",
        studies.len(),
        if studies.len() == 1 { "y" } else { "ies" }
    );
    let heard = progress.phase(&Phase::new(what, "evaluations at most", most as u64));
    studies
        .par_iter()
        .map(|s| {
            let budget = Budget::new(&*heard, optimise::most_evaluations(s) as u64);
            let result = optimise::run_study(spec, s, &budget);
            budget.close();
            result
        })
        .collect()
}

/// Each study's map around its optimum (none below 2 steps).
fn maps(
    spec: &Spec,
    studies: &[StudyResult],
    steps: usize,
    progress: &dyn Progress,
) -> Vec<Vec<Evaluation>> {
    spec.studies
        .iter()
        .zip(studies)
        .map(|(s, r)| match steps >= 2 {
            true => optimise::map(spec, s, steps, &r.optimum.point, progress),
            false => Vec::new(),
        })
        .collect()
}

/// The accuracy ladder of the design review and its wall-clock time, s.
fn ladder(
    spec: &Spec,
    a: &crate::spec::Accuracy,
    progress: &dyn Progress,
) -> Result<(Ladder, f64)> {
    let start = std::time::Instant::now();
    // Steps rungs 12 … finest, and at most four settings rungs.
    let rungs = (a.options.finest / accuracy::COARSEST).trailing_zeros() as u64 + 1 + 4;
    let heard = progress.phase(&Phase::new("accuracy ladder", "rungs", rungs));
    let ladder = accuracy::run(spec, a.scene, &a.options, &mut |event| {
        if let accuracy::Event::Rung(..) = event {
            heard.advance(1);
        }
    })?;
    Ok((ladder, start.elapsed().as_secs_f64()))
}
