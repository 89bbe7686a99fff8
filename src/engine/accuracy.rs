//! What accuracy costs in time: one scene run on a ladder of settings, each rung's headline
//! outputs compared with the finest rung (the reference), and the wall-clock time of each run.
//!
//! The ladder:
//! - **steps rungs**: 12, 24, 48, … crank steps per mesh period up to the finest (3072 by
//!   default), over the scene's own crank range and in its own geometry, contact law and solver
//!   tolerance. The number of crank angles scales with the range, so a 108° range (three mesh
//!   periods) runs 36, 72, … angles. Every grid is nested in the finest: angle k of a rung with
//!   N steps per period is, bit for bit, angle k·(finest/N) of the reference.
//! - **settings rungs**, one setting changed at a time at the settings resolution (by default the
//!   cheapest steps rung that meets every tolerance, else the finest): the other geometry mode
//!   (`first_order` ↔ `exact`), the other contact law (`paper_linear` ↔ `hertz_nonlinear`) and
//!   the solver tolerances rel_tol 1e-6 and 1e-9 (the default 1e-11 is the steps rung itself).
//!
//! A different contact law is a different model: its "error" is a model difference, not an
//! approximation of the reference, so it is never chosen as the cheapest rung. The same holds
//! for the `exact` rung of a scene that asks for `first_order`: the reference is always the
//! scene's own model, at the finest resolution, with the default tolerance.
//!
//! The errors, each in its quantity's unit:
//! - **TE curve**: max |δ_ref(φ) − δ_rung(φ)| over the reference's angles, the rung's curve
//!   linearly interpolated between its samples (wrapping around when the sweep covers whole
//!   loaded periods, else only between its first and last angle). At its own angles a rung
//!   agrees with the reference to the solver tolerance, since every angle is solved on its own:
//!   the discretisation error of a sampled curve lies between its samples
//!   (`Rung::te_at_nodes_arcsec` keeps the agreement at the samples).
//! - **TE fluctuation** δmax − δmin (arcsec), **ratio fluctuation** κmax − κmin, **max roller
//!   force** (N), **max bearing force** (N), **min clearance** (µm): |rung − reference|.
//!
//! Only the quantities the scene computes are compared (a scene without `bearing` has no
//! bearing column). Times are wall-clock measurements of `scene::run` for the rung, the
//! same work `check` does for the scene; they are printed, never asserted.

use crate::engine::scene;
use crate::equilibrium::solve::Settings;
use crate::error::{Error, Result};
pub use crate::model::accuracy::{
    base_angles, check, ladder_steps, tolerance, LadderTolerances, Options, Setting, COARSEST,
    DEFAULT_FINEST, FACE_SLICES, MAX_FINEST,
};
use crate::model::quantity::{self, TE};
use crate::model::results::SceneResult;
use crate::model::{ContactLaw, GeometryMode, Scene};
use crate::model::{Effect, Plan};
use crate::spec::{self, Spec};
use crate::units;
use std::time::Instant;

/// Runs shorter than this (s) are repeated, and the fastest of `REPEATS` runs is the time.
pub const REPEAT_BELOW_S: f64 = 0.05;
pub const REPEATS: usize = 5;
/// Solver tolerances of the tolerance rungs (the default, `Settings::default().rel_tol`, is the
/// steps rung at the same resolution).
pub const LOOSE_REL_TOL: [f64; 2] = [1e-6, 1e-9];

/// A headline output of a scene, compared rung by rung.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum LadderQuantity {
    TeCurve,
    TeFluctuation,
    RatioFluctuation,
    MaxRollerForce,
    MaxBearingForce,
    MinClearance,
    /// The largest face load factor (peak line load over its roller's mean F/B): only for a
    /// resolved face (crowned or tilted).
    MaxFaceLoadFactor,
    /// The largest line load along the face, N/mm: only for a resolved face.
    MaxLineLoad,
}

/// How many quantities the ladder watches (the length of its per-quantity arrays).
pub const QUANTITIES: usize = 8;

impl LadderQuantity {
    pub const ALL: [LadderQuantity; QUANTITIES] = [
        LadderQuantity::TeCurve,
        LadderQuantity::TeFluctuation,
        LadderQuantity::RatioFluctuation,
        LadderQuantity::MaxRollerForce,
        LadderQuantity::MaxBearingForce,
        LadderQuantity::MinClearance,
        LadderQuantity::MaxFaceLoadFactor,
        LadderQuantity::MaxLineLoad,
    ];

    /// A quantity along the face width: watched only where the scene's face is crowned or
    /// tilted (a 2-D scene has none, and its ladder names none of them).
    pub fn is_face(self) -> bool {
        matches!(
            self,
            LadderQuantity::MaxFaceLoadFactor | LadderQuantity::MaxLineLoad
        )
    }

    /// Short column heading.
    pub fn label(self) -> &'static str {
        match self {
            LadderQuantity::TeCurve => "TE curve",
            LadderQuantity::TeFluctuation => "TE fluct.",
            LadderQuantity::RatioFluctuation => "ratio fluct.",
            LadderQuantity::MaxRollerForce => "max roller F",
            LadderQuantity::MaxBearingForce => "max bearing F",
            LadderQuantity::MinClearance => "min clearance",
            LadderQuantity::MaxFaceLoadFactor => "face factor",
            LadderQuantity::MaxLineLoad => "max line load",
        }
    }

    /// The quantity of the registry it is (the TE curve's is the loaded TE).
    pub fn registry(self) -> &'static quantity::Quantity {
        match self {
            LadderQuantity::TeCurve => &quantity::TE,
            LadderQuantity::TeFluctuation => &quantity::TE_FLUCTUATION,
            LadderQuantity::RatioFluctuation => &quantity::RATIO_FLUCTUATION,
            LadderQuantity::MaxRollerForce => &quantity::MAX_ROLLER_FORCE,
            LadderQuantity::MaxBearingForce => &quantity::MAX_BEARING_FORCE,
            LadderQuantity::MinClearance => &quantity::MIN_CLEARANCE,
            LadderQuantity::MaxFaceLoadFactor => &quantity::MAX_FACE_LOAD_FACTOR,
            LadderQuantity::MaxLineLoad => &quantity::MAX_LINE_LOAD,
        }
    }

    /// The unit of the errors: the registry's, but µm for the clearance (its tolerance is a
    /// fraction of a micrometre).
    pub fn unit(self) -> &'static str {
        match self {
            LadderQuantity::MinClearance => "µm",
            q => q.registry().unit,
        }
    }

    /// The registry's value in `unit`.
    fn scale(self) -> f64 {
        match self {
            LadderQuantity::MinClearance => units::um(1.0),
            _ => 1.0,
        }
    }

    pub fn tolerance(self, t: &LadderTolerances) -> f64 {
        match self {
            LadderQuantity::TeCurve | LadderQuantity::TeFluctuation => t.te_arcsec,
            LadderQuantity::RatioFluctuation => t.ratio,
            LadderQuantity::MaxRollerForce | LadderQuantity::MaxBearingForce => t.force_n,
            LadderQuantity::MinClearance => t.clearance_um,
            LadderQuantity::MaxFaceLoadFactor => t.face_load_factor,
            LadderQuantity::MaxLineLoad => t.line_load_n_per_mm,
        }
    }

    /// Does an error meet this quantity's tolerance? (A NaN error does not.)
    pub fn within(self, error: f64, t: &LadderTolerances) -> bool {
        error <= self.tolerance(t)
    }

    fn index(self) -> usize {
        self as usize
    }
}

/// The headline outputs of one run, in the ladder's units (arcsec, N, µm).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Outputs {
    pub crank_rad: Vec<f64>,
    /// Loaded TE δ at every crank angle, arcsec.
    pub te_arcsec: Option<Vec<f64>>,
    /// Transmission ratio κ at every crank angle (central differences of δ).
    pub ratio: Option<Vec<f64>>,
    /// Rollers carrying load at every crank angle.
    pub contacts: Option<Vec<usize>>,
    /// The scalar quantities (index: `LadderQuantity as usize`; the TE curve's is its largest |δ|).
    pub scalars: [Option<f64>; QUANTITIES],
}

impl Outputs {
    /// The ladder's outputs of a run; the face quantities only when `face` (the ladder watches
    /// them: the scene's face is crowned or tilted, `Layout::face`).
    pub fn of(r: &SceneResult, face: bool) -> Outputs {
        let curve = |q: &quantity::Quantity| q.curves(r).and_then(|c| c.values.into_iter().next());
        let te_arcsec = curve(&TE);
        let mut scalars = [None; QUANTITIES];
        for q in LadderQuantity::ALL {
            scalars[q.index()] = match q {
                q if q.is_face() && !face => None,
                LadderQuantity::TeCurve => te_arcsec
                    .as_ref()
                    .map(|v| v.iter().fold(0.0, |m: f64, x| m.max(x.abs()))),
                q => q.registry().scalar(r).map(|e| e.value * q.scale()),
            };
        }
        Outputs {
            crank_rad: r.crank_rad.clone(),
            te_arcsec,
            ratio: curve(&quantity::RATIO),
            contacts: (r.only_disc())
                .and_then(|d| d.loaded.rollers.as_ref())
                .map(|c| c.contacts.clone()),
            scalars,
        }
    }

    /// The scalar value of a quantity (the TE curve's is its largest |δ|).
    pub fn value(&self, q: LadderQuantity) -> Option<f64> {
        self.scalars[q.index()]
    }
}

/// Which setting a rung changes from the reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variation {
    /// Crank steps per mesh period (the reference is the finest of these).
    Steps,
    /// The other geometry mode.
    Geometry,
    /// The other contact law: a different model.
    ContactLaw,
    /// A looser solver tolerance.
    SolverTolerance,
    /// Another number of face slices (`FACE_SLICES`), at the scene's own crank angles; compared
    /// with the finest slice count, their own reference (only for a crowned or tilted face).
    FaceSlices,
}

/// One run of the ladder.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    pub label: String,
    pub variation: Variation,
    /// Crank steps per mesh period (12·2^k; not an integer for a range of partial periods).
    pub steps_per_period: f64,
    /// Crank angles solved.
    pub angles: usize,
    pub geometry: GeometryMode,
    pub law: ContactLaw,
    pub rel_tol: f64,
    /// Slices the face is cut into (the scene's own but for a face-slices rung).
    pub slices: usize,
    /// Wall-clock time of the run, s: loaded effects plus clearance.
    pub seconds: f64,
    /// The part of `seconds` spent on the clearance (unloaded) sweep; a settings rung reuses
    /// the clearance of the steps rung at its resolution, and its time.
    pub clearance_seconds: f64,
    pub outputs: Outputs,
    /// |rung − reference| per quantity (index: `LadderQuantity as usize`); `None` when not
    /// computed. A face-slices rung's reference is the finest slice count.
    pub errors: [Option<f64>; QUANTITIES],
    /// max |δ_ref − δ_rung| at the rung's own crank angles, arcsec (solver round-off only).
    pub te_at_nodes_arcsec: Option<f64>,
    /// This rung is the reference: of the ladder (the finest steps rung), or of the
    /// face-slices rungs (the finest slice count).
    pub is_reference: bool,
    /// The rung is another model, not an approximation of the reference (its error is a model
    /// difference): never chosen as the cheapest.
    pub model_difference: bool,
}

impl Rung {
    /// The rung's work, as an order (smaller is cheaper): its crank angles first (each angle is
    /// one solve of the scene's model, so the work grows with them), then at equal angles its
    /// settings, coarsest first: first-order geometry (closed-form gaps and arms, no
    /// closest-point search per roller) before exact, then the looser solver tolerance (fewer
    /// Newton iterations per angle) before the tighter. Known before anything runs, so that the
    /// cheapest rung never depends on the scheduler; the measured `seconds` are information.
    pub fn work(&self) -> (usize, u8, std::cmp::Reverse<u64>) {
        let geometry = match self.geometry {
            GeometryMode::FirstOrder => 0,
            GeometryMode::Exact => 1,
        };
        // A positive double's bits order as the double does.
        (
            self.angles,
            geometry,
            std::cmp::Reverse(self.rel_tol.to_bits()),
        )
    }

    pub fn error(&self, q: LadderQuantity) -> Option<f64> {
        self.errors[q.index()]
    }

    pub fn meets(&self, t: &LadderTolerances) -> bool {
        misses(&self.errors, t).is_empty()
    }
}

/// The quantities whose error (index: `LadderQuantity as usize`) exceeds its tolerance, each
/// with its error in its unit.
pub fn misses(
    errors: &[Option<f64>; QUANTITIES],
    t: &LadderTolerances,
) -> Vec<(LadderQuantity, f64)> {
    LadderQuantity::ALL
        .into_iter()
        .filter_map(|q| {
            errors[q.index()]
                .filter(|&e| !q.within(e, t))
                .map(|e| (q, e))
        })
        .collect()
}

/// The cheapest of `rungs` that meets every tolerance: the least work (`Rung::work`) among
/// those that meet `tolerances`, model differences excluded (another model is no
/// approximation of the reference); the reference meets them by definition (its own error is
/// unmeasured) and is the answer when nothing cheaper does. Earlier rows win ties. Decided by
/// work alone, never by the measured times, so that `cycloid accuracy` and the report's ladder
/// name the same rung for the same spec; the one choice both use.
///
/// The face-slices rungs have their own reference (`cheapest_slices`) and take no part.
pub fn cheapest(rungs: &[Rung], tolerances: &LadderTolerances) -> Option<usize> {
    rungs
        .iter()
        .enumerate()
        .filter(|(_, r)| r.variation != Variation::FaceSlices)
        .filter(|(_, r)| r.is_reference || (!r.model_difference && r.meets(tolerances)))
        .min_by(|(i, a), (j, b)| a.work().cmp(&b.work()).then(i.cmp(j)))
        .map(|(i, _)| i)
}

/// The fewest face slices that meet every tolerance against the finest slice count: among the
/// face-slices rungs, the one with the fewest slices that meets `tolerances` (each slice is one
/// more evaluation of the contact law per contact and angle, so the work grows with them), the
/// finest when none does; `None` without face-slices rungs.
pub fn cheapest_slices(rungs: &[Rung], tolerances: &LadderTolerances) -> Option<usize> {
    rungs
        .iter()
        .enumerate()
        .filter(|(_, r)| r.variation == Variation::FaceSlices)
        .filter(|(_, r)| r.is_reference || r.meets(tolerances))
        .min_by_key(|(_, r)| r.slices)
        .map(|(i, _)| i)
}

/// A solver tolerance as rungs are named: "1e-6", else in exponent form.
pub fn tol_text(x: f64) -> String {
    let e = x.log10().round();
    if (10f64.powf(e) - x).abs() <= 1e-6 * x {
        format!("1e{}", e as i32)
    } else {
        format!("{x:e}")
    }
}

/// What is known before anything runs: the scene, its range, the quantities compared.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    pub spec_name: String,
    pub scene: String,
    pub from_deg: f64,
    pub to_deg: f64,
    /// Mesh periods covered by the range.
    pub periods: f64,
    /// Crank angles per 12 steps per mesh period (the coarsest rung's angle count).
    pub base_angles: usize,
    /// The quantities the scene computes, in column order.
    pub quantities: Vec<LadderQuantity>,
    pub finest: usize,
    pub tolerances: LadderTolerances,
    pub geometry: GeometryMode,
    pub law: ContactLaw,
    /// The TE and ratio curves wrap around (the range covers whole loaded periods).
    pub periodic: bool,
    /// The scene computes roller contact, so the loaded outputs exist and the settings rungs
    /// run (output pins alone give none of the ladder's quantities).
    pub loaded: bool,
    /// The scene loads a crowned or tilted face: the face quantities are watched and the
    /// face-slices rungs run, at the scene's own `angles_own` crank angles.
    pub face: bool,
    /// The scene's own crank angles (the face-slices rungs run them; the resolution verdict
    /// judges the scene's steps per mesh period from them).
    pub angles_own: usize,
}

impl Layout {
    pub(crate) fn angles(&self, steps_per_period: usize) -> usize {
        self.base_angles * (steps_per_period / COARSEST)
    }

    /// The crank angles of a steps rung of `steps_per_period`, rad: nested in the finest's.
    pub(crate) fn crank_rad(&self, steps_per_period: usize) -> Vec<f64> {
        spec::crank_angles(self.from_deg, self.to_deg, self.angles(steps_per_period))
    }

    pub(crate) fn steps_per_period(&self, angles: usize) -> f64 {
        angles as f64 / self.periods
    }
}

/// The whole ladder.
#[derive(Debug, Clone, PartialEq)]
pub struct Ladder {
    pub layout: Layout,
    /// Steps rungs from coarse to fine (the reference last), then the settings rungs.
    pub rungs: Vec<Rung>,
    /// Steps per mesh period of the settings rungs.
    pub settings_steps: usize,
    /// Index of the cheapest rung that meets every tolerance (`cheapest`: by work, not by the
    /// measured times), model differences excluded; the reference when nothing cheaper does.
    pub cheapest: Option<usize>,
    /// Index of the fewest face slices that meet every tolerance (`cheapest_slices`); `None`
    /// without face-slices rungs.
    pub cheapest_slices: Option<usize>,
    /// Settings rungs left out (each says why).
    pub skipped: Vec<Skipped>,
}

impl Ladder {
    pub fn reference(&self) -> &Rung {
        self.rungs
            .iter()
            .find(|r| r.is_reference && r.variation == Variation::Steps)
            .expect("a ladder has a reference")
    }

    /// The steps rungs, coarse to fine, the reference last.
    pub fn steps_rungs(&self) -> impl Iterator<Item = &Rung> {
        self.rungs
            .iter()
            .filter(|r| r.variation == Variation::Steps)
    }

    /// Errors at or below this are round-off, not discretisation: 1e-8 of the quantity's
    /// magnitude in the reference (the largest |δ| for the TE quantities, the largest κ for the
    /// ratio fluctuation). The solves converge to 1e-11 relative; central differences divide
    /// their round-off by the step.
    pub fn noise_floor(&self, q: LadderQuantity) -> f64 {
        let o = &self.reference().outputs;
        let scale = match q {
            LadderQuantity::RatioFluctuation => o
                .ratio
                .as_ref()
                .map_or(0.0, |r| r.iter().fold(0.0, |m: f64, x| m.max(x.abs()))),
            LadderQuantity::TeFluctuation => o.value(LadderQuantity::TeCurve).unwrap_or(0.0),
            _ => o.value(q).map_or(0.0, f64::abs),
        };
        1e-8 * scale
    }

    /// An error above the noise floor, else `None`.
    fn resolved(&self, r: &Rung, q: LadderQuantity) -> Option<f64> {
        r.error(q).filter(|&e| e > self.noise_floor(q))
    }

    /// Observed order of convergence of a quantity between successive steps rungs below the
    /// reference: p = log2(e(N)/e(2N)), one value per pair (N, 2N) with 2N below the finest;
    /// `None` where an error is at round-off (`noise_floor`), e.g. an extreme that falls on a
    /// crank angle every grid shares.
    pub fn orders(&self, q: LadderQuantity) -> Vec<(usize, Option<f64>)> {
        let steps: Vec<&Rung> = self.steps_rungs().filter(|r| !r.is_reference).collect();
        steps
            .windows(2)
            .map(|w| {
                let n = w[0].steps_per_period.round() as usize;
                let p = match (self.resolved(w[0], q), self.resolved(w[1], q)) {
                    (Some(a), Some(b)) => Some((a / b).log2()),
                    _ => None,
                };
                (n, p)
            })
            .collect()
    }

    /// Least-squares slope of log e against log N over the steps rungs below the reference,
    /// without the one just below it (its error against the reference is inflated by the
    /// reference's own error: e(N/2)/e(N) = 2^p + 1 instead of 2^p). `None` with fewer than two
    /// errors above the noise floor.
    pub fn fitted_order(&self, q: LadderQuantity) -> Option<f64> {
        let steps: Vec<&Rung> = self.steps_rungs().filter(|r| !r.is_reference).collect();
        let points: Vec<(f64, f64)> = steps[..steps.len().saturating_sub(1)]
            .iter()
            .filter_map(|r| {
                let e = self.resolved(r, q)?;
                Some((r.steps_per_period.log2(), e.log2()))
            })
            .collect();
        if points.len() < 2 {
            return None;
        }
        let n = points.len() as f64;
        let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
        let my = points.iter().map(|p| p.1).sum::<f64>() / n;
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let sxx: f64 = points.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
        (sxx > 0.0).then(|| -sxy / sxx)
    }
}

/// Rungs of the ladder that were not run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Skipped {
    /// The solver tolerance rungs: first-order geometry with the linear law is solved in
    /// closed form, without a tolerance.
    ToleranceRungs,
    /// The settings rungs: the scene computes no roller contact, and the clearance depends on
    /// the crank steps only.
    SettingsRungs,
}

/// What the ladder reports while it runs.
pub enum Event<'a> {
    /// Before the first run.
    Started(&'a Layout),
    /// A rung finished (in table order: steps rungs coarse to fine, then settings rungs, then
    /// face-slices rungs coarse to fine).
    Rung(&'a Layout, &'a Rung),
}

/// The scene a ladder runs by default: the first that computes roller contact (not a duty
/// cycle's, which runs once per bin), else the first.
pub fn default_scene(spec: &Spec) -> usize {
    spec.scenes.iter().position(Scene::loaded_once).unwrap_or(0)
}

pub(crate) fn layout(spec: &Spec, scene: &Scene, options: &Options) -> Layout {
    let plan = Plan::for_scene(scene);
    let (from_deg, to_deg) = (scene.crank_from_deg, scene.crank_to_deg);
    let periods = units::rad(to_deg - from_deg) / spec.design.mesh_period_rad();
    let base = base_angles(periods);
    let face =
        plan.has(Effect::RollerContact) && !spec.design.deviations.face(&scene.face).is_uniform();
    let mut probe = scene.clone();
    probe.crank_rad = spec::crank_angles(from_deg, to_deg, base);
    Layout {
        spec_name: spec.name.clone(),
        scene: scene.name.clone(),
        from_deg,
        to_deg,
        periods,
        base_angles: base,
        quantities: LadderQuantity::ALL
            .into_iter()
            .filter(|q| plan.has(q.registry().effect) && (face || !q.is_face()))
            .collect(),
        finest: options.finest,
        tolerances: options.tolerances,
        geometry: scene.geometry,
        law: scene.contact_law,
        periodic: probe.spans_loaded_periods(&spec.design, &plan),
        loaded: plan.has(Effect::RollerContact),
        face,
        angles_own: scene.crank_rad.len(),
    }
}

/// The errors of `rung` against `reference`; the rung's grid is nested in the reference's
/// (`ratio` reference angles per rung angle).
pub(crate) fn errors(
    reference: &Outputs,
    rung: &Outputs,
    ratio: usize,
    periodic: bool,
) -> ([Option<f64>; QUANTITIES], Option<f64>) {
    let mut e = [None; QUANTITIES];
    let mut at_nodes = None;
    if let (Some(f), Some(c)) = (&reference.te_arcsec, &rung.te_arcsec) {
        let (curve, nodes) = curve_error(f, c, ratio, periodic);
        e[LadderQuantity::TeCurve.index()] = Some(curve);
        at_nodes = Some(nodes);
    }
    for q in LadderQuantity::ALL.into_iter().skip(1) {
        if let (Some(a), Some(b)) = (reference.value(q), rung.value(q)) {
            e[q.index()] = Some((a - b).abs());
        }
    }
    (e, at_nodes)
}

/// max |fine − interpolated coarse| over the fine samples, and max |fine − coarse| at the
/// coarse samples. Coarse sample k sits at fine sample k·ratio; between samples the coarse
/// curve is linear, wrapping from the last sample to the first when `periodic` (fine samples
/// past the last coarse one are skipped otherwise).
pub fn curve_error(fine: &[f64], coarse: &[f64], ratio: usize, periodic: bool) -> (f64, f64) {
    let (mut curve, mut nodes) = (0.0f64, 0.0f64);
    let n = coarse.len();
    for (j, &f) in fine.iter().enumerate() {
        let (k, i) = (j / ratio, j % ratio);
        if k >= n {
            break;
        }
        let value = if i == 0 {
            nodes = nodes.max((f - coarse[k]).abs());
            coarse[k]
        } else if k + 1 < n || periodic {
            let w = i as f64 / ratio as f64;
            coarse[k] * (1.0 - w) + coarse[(k + 1) % n] * w
        } else {
            continue;
        };
        curve = curve.max((f - value).abs());
    }
    (curve, nodes)
}

/// The model a rung solves: its geometry, contact law and solver tolerance (rel_tol).
type Model = (GeometryMode, ContactLaw, f64);

/// A rung's run: its outputs and the measured times of its loaded effects and its clearance.
#[derive(Clone)]
struct Run {
    outputs: Outputs,
    loaded_seconds: f64,
    clearance_seconds: f64,
}

/// Run `plan` for `scene` with `settings`, timed. A short run is timed again (up to `REPEATS`
/// runs in all) and the fastest time kept: milliseconds are at the mercy of the scheduler (the
/// cheapest rung is chosen by work, `cheapest`; the times are information).
fn timed(
    spec: &Spec,
    scene: &Scene,
    plan: &Plan,
    settings: &Settings,
) -> Result<(SceneResult, f64)> {
    let mut best = f64::INFINITY;
    let mut first = None;
    for _ in 0..REPEATS {
        let start = Instant::now();
        let result = scene::run(spec, scene, plan, &run_options(settings))?;
        let seconds = start.elapsed().as_secs_f64();
        best = best.min(seconds);
        let done = seconds >= REPEAT_BELOW_S;
        first.get_or_insert(result);
        if done {
            break;
        }
    }
    Ok((first.expect("at least one run"), best))
}

/// A scene's run to `settings`, heard by nobody.
fn run_options(settings: &Settings) -> scene::RunOptions<'static> {
    scene::RunOptions {
        settings: *settings,
        ..Default::default()
    }
}

/// Run the ladder of one scene. `progress` hears of every finished rung as it finishes.
///
/// The clearance (unloaded, exact geometry) and the loaded effects are run and timed apart:
/// the clearance depends on the crank steps only, so the settings rungs reuse the clearance of
/// the steps rung at their resolution, its result and its measured time.
pub fn run(
    spec: &Spec,
    scene_index: usize,
    options: &Options,
    progress: &mut dyn FnMut(Event),
) -> Result<Ladder> {
    let scene = &spec.scenes[scene_index];
    check(&spec.design, scene, options).map_err(|(_, m)| Error::invalid_value(m))?;
    let layout = layout(spec, scene, options);
    progress(Event::Started(&layout));
    let plan = Plan::for_scene(scene);
    let clearance_plan = plan.part(|e| e == Effect::Clearance);
    let loaded_plan = plan.part(|e| e != Effect::Clearance);
    let default_tol = Settings::default().rel_tol;
    // One run of `s` at `rel_tol`, its loaded effects and (with `clearance`) its clearance
    // timed apart.
    let run_scene = |s: &Scene, rel_tol: f64, clearance: bool| -> Result<Run> {
        let settings = Settings {
            rel_tol,
            ..Settings::default()
        };
        let (mut result, loaded_seconds) = if loaded_plan.effects.is_empty() {
            (
                scene::run(spec, s, &loaded_plan, &run_options(&settings))?,
                0.0,
            )
        } else {
            timed(spec, s, &loaded_plan, &settings)?
        };
        let mut clearance_seconds = 0.0;
        if clearance && !clearance_plan.effects.is_empty() {
            let (c, seconds) = timed(spec, s, &clearance_plan, &settings)?;
            for (disc, timed) in result.discs.iter_mut().zip(c.discs) {
                disc.clearance = timed.clearance;
            }
            clearance_seconds = seconds;
        }
        Ok(Run {
            outputs: Outputs::of(&result, layout.face),
            loaded_seconds,
            clearance_seconds,
        })
    };
    let run_once = |steps_per_period: usize,
                    (geometry, law, rel_tol): Model,
                    clearance: bool|
     -> Result<Run> {
        let mut s = scene.clone();
        s.crank_rad = layout.crank_rad(steps_per_period);
        s.geometry = geometry;
        s.contact_law = law;
        run_scene(&s, rel_tol, clearance)
    };
    let (geometry, law) = (scene.geometry, scene.contact_law);
    let own = (geometry, law, default_tol);
    // Warm-up, untimed: the first run of a process starts the thread pool and touches fresh
    // memory, which would be charged to the reference otherwise.
    run_once(COARSEST, own, true)?;
    let reference_run = run_once(options.finest, own, true)?;
    let reference = reference_run.outputs.clone();
    // A rung from its run, compared with `against` where given (a face-slices rung: the same
    // angles as its reference), else with the reference in a grid nested in the finest.
    let make = |label: String,
                variation: Variation,
                (geometry, law, rel_tol): Model,
                run: Run,
                against: Option<&Outputs>| {
        let n = run.outputs.crank_rad.len();
        let (reference, ratio) = match against {
            Some(outputs) => (outputs, 1),
            None => (&reference, layout.angles(options.finest) / n),
        };
        let (errors, te_at_nodes_arcsec) = errors(reference, &run.outputs, ratio, layout.periodic);
        Rung {
            label,
            variation,
            steps_per_period: layout.steps_per_period(n),
            angles: n,
            geometry,
            law,
            rel_tol,
            slices: scene.face.slices,
            seconds: run.loaded_seconds + run.clearance_seconds,
            clearance_seconds: run.clearance_seconds,
            outputs: run.outputs,
            errors,
            te_at_nodes_arcsec,
            is_reference: false,
            model_difference: variation == Variation::ContactLaw
                || (variation == Variation::Geometry && geometry == GeometryMode::Exact),
        }
    };
    let mut rungs = Vec::new();
    let mut n = COARSEST;
    while n < options.finest {
        let run = run_once(n, own, true)?;
        let rung = make(format!("steps {n}"), Variation::Steps, own, run, None);
        progress(Event::Rung(&layout, &rung));
        rungs.push(rung);
        n *= 2;
    }
    let label = format!("steps {} (reference)", options.finest);
    let mut top = make(label, Variation::Steps, own, reference_run, None);
    top.is_reference = true;
    progress(Event::Rung(&layout, &top));
    rungs.push(top);

    let settings_steps = options.settings_steps.unwrap_or_else(|| {
        rungs
            .iter()
            .find(|r| !r.is_reference && r.meets(&options.tolerances))
            .map_or(options.finest, |r| {
                (r.angles / layout.base_angles) * COARSEST
            })
    });
    // The steps rung at the settings resolution: its clearance is every settings rung's.
    let base = rungs
        .iter()
        .find(|r| r.angles == layout.angles(settings_steps))
        .cloned()
        .expect("the settings resolution is a steps rung");
    let mut skipped = Vec::new();
    if layout.loaded {
        let other_geometry = match geometry {
            GeometryMode::Exact => GeometryMode::FirstOrder,
            GeometryMode::FirstOrder => GeometryMode::Exact,
        };
        let other_law = match law {
            ContactLaw::PaperLinear => ContactLaw::HertzNonlinear,
            ContactLaw::HertzNonlinear => ContactLaw::PaperLinear,
        };
        let mut variants = vec![
            (
                format!("{} geometry", other_geometry.name()),
                Variation::Geometry,
                (other_geometry, law, default_tol),
            ),
            (
                format!("{} law", other_law.name()),
                Variation::ContactLaw,
                (geometry, other_law, default_tol),
            ),
        ];
        if geometry == GeometryMode::FirstOrder && law == ContactLaw::PaperLinear {
            skipped.push(Skipped::ToleranceRungs);
        } else {
            for tol in LOOSE_REL_TOL {
                variants.push((
                    format!("rel_tol {}", tol_text(tol)),
                    Variation::SolverTolerance,
                    (geometry, law, tol),
                ));
            }
        }
        for (label, variation, model) in variants {
            let mut run = run_once(settings_steps, model, false)?;
            let clearance = LadderQuantity::MinClearance.index();
            run.outputs.scalars[clearance] = base.outputs.scalars[clearance];
            run.clearance_seconds = base.clearance_seconds;
            let rung = make(label, variation, model, run, None);
            progress(Event::Rung(&layout, &rung));
            rungs.push(rung);
        }
    } else {
        skipped.push(Skipped::SettingsRungs);
    }
    if layout.face {
        // The face-slices rungs: the scene as it is (its crank angles, geometry, law), cut into
        // each of `FACE_SLICES`, compared with the finest (run first, shown last). Every angle
        // is the same in every rung (`ratio` 1): the TE curve's error needs no interpolation.
        let run_slices = |n: usize| -> Result<Run> {
            let mut s = scene.clone();
            s.face.slices = n;
            run_scene(&s, default_tol, true)
        };
        let finest_slices = FACE_SLICES[FACE_SLICES.len() - 1];
        let slices_reference = run_slices(finest_slices)?;
        let slice_rung = |n: usize, run: Run| {
            let label = if n == finest_slices {
                format!("face slices {n} (reference)")
            } else {
                format!("face slices {n}")
            };
            let against = Some(&slices_reference.outputs);
            let variation = Variation::FaceSlices;
            let mut rung = make(label, variation, own, run, against);
            rung.slices = n;
            rung.is_reference = n == finest_slices;
            rung
        };
        for &n in &FACE_SLICES[..FACE_SLICES.len() - 1] {
            let rung = slice_rung(n, run_slices(n)?);
            progress(Event::Rung(&layout, &rung));
            rungs.push(rung);
        }
        let top = slice_rung(finest_slices, slices_reference.clone());
        progress(Event::Rung(&layout, &top));
        rungs.push(top);
    }
    let cheapest_slices = cheapest_slices(&rungs, &options.tolerances);
    let cheapest = cheapest(&rungs, &options.tolerances);
    Ok(Ladder {
        layout,
        rungs,
        settings_steps,
        cheapest,
        cheapest_slices,
        skipped,
    })
}
