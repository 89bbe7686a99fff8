//! Which effects a scene needs, why, and the plan that runs exactly those.
//!
//! The plan follows the scene: an effect is computed when the scene asks for it or when an
//! effect it asked for cannot be computed without it. Limits never add effects: a limit is
//! checked in the scenes that compute its quantity (`check`), and a limit that no scene can
//! evaluate is an error. A detail of an effect (the closing lags of `clearance`) is computed
//! when a limit, a golden or an output file of the run reads a quantity that needs it (`plan`).

use crate::engine::{bearing_life, duty_cycle, efficiency, strength, torsion};
use crate::equilibrium::coupling::Coupling;
use crate::equilibrium::discs::Discs;
use crate::equilibrium::discs_sweep::{self, DiscSweeps};
use crate::equilibrium::loaded::Model;
use crate::equilibrium::losses::LossModel;
use crate::equilibrium::solve::{Settings, SolveFailure};
use crate::equilibrium::sweep;
use crate::error::{Error, Result};
use crate::geometry::clearance::{self, Mesh};
use crate::geometry::first_order;
use crate::geometry::mesh_minimum::{self, MeshMinimum};
use crate::model::accuracy::LadderTolerances;
use crate::model::quantity::QUANTITIES;
use crate::model::results::{
    BearingLife, ClearanceSweep, DiscResult, DutyBinResult, LoadedSweep, ReducerResult, SceneResult,
};
use crate::model::{
    Design, Detail, Effect, Friction, FrictionModel, GeometryMode, Modification, Plan, Scene,
};
use crate::progress::{Phase, Progress, Silent};
use crate::spec::Spec;
use crate::units;

/// The output files of a run that read every quantity of every scene.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Writes {
    /// The results JSON (`--json`).
    pub json: bool,
    /// The design review (`--report`).
    pub report: bool,
}

/// Progress phases of crank angles below this many are not worth showing (a scene that ends
/// before a display's first redraw).
const SCENES_WORTH_SHOWING: u64 = 200_000;

/// Every scene of `spec`, in parallel; results (and the first error) in spec order.
pub fn run_all(spec: &Spec, writes: Writes, progress: &dyn Progress) -> Result<Vec<SceneResult>> {
    use rayon::prelude::*;
    let plans: Vec<_> = spec.scenes.iter().map(|s| plan(spec, s, writes)).collect();
    // The sweeps of every scene, in crank angles.
    let total: usize = spec
        .scenes
        .iter()
        .zip(&plans)
        .map(|(s, plan)| s.crank_rad.len() * scene_sweeps(s, plan, spec.design.discs))
        .sum();
    let phase = Phase {
        worth_showing: SCENES_WORTH_SHOWING,
        ..Phase::new("solving the scenes", "crank angles", total as u64)
    };
    let heard = progress.phase(&phase);
    let options = RunOptions {
        progress: &*heard,
        ..Default::default()
    };
    let results: Vec<Result<SceneResult>> = spec
        .scenes
        .par_iter()
        .zip(&plans)
        .map(|(s, plan)| run(spec, s, plan, &options))
        .collect();
    results.into_iter().collect()
}

/// The plan of `scene` in a run of `spec` that writes `writes`: the scene's effects, and the
/// details of them that the spec's limits and the scene's goldens read, or every detail when
/// an output file reads every quantity.
pub fn plan(spec: &Spec, scene: &Scene, writes: Writes) -> Plan {
    let mut plan = Plan::for_scene(scene);
    for l in &spec.limits.entries {
        plan.ask(l.def.quantity, &format!("limit {}", l.def.key));
    }
    for g in spec.golden.iter().filter(|g| g.scene == scene.name) {
        plan.ask(g.quantity, &format!("golden {}", g.quantity.key));
    }
    for (file, writes) in [("--json", writes.json), ("--report", writes.report)] {
        if writes {
            for q in QUANTITIES {
                plan.ask(q, file);
            }
        }
    }
    plan
}

/// How a scene runs: the loaded solves' convergence settings (the accuracy ladder varies
/// them), the error bound sought for the smallest gap over the mesh, and who hears of the
/// crank angles done. `Default`: the default settings and the accuracy ladder's default
/// clearance tolerance (0.1 µm), nobody.
#[derive(Clone, Copy)]
pub struct RunOptions<'a> {
    pub settings: Settings,
    /// The error bound sought for the smallest gap over the whole mesh, mm
    /// (`geometry::mesh_minimum`): the spec's `accuracy.tolerance.clearance_um`.
    pub clearance_tolerance_mm: f64,
    /// Hears of the crank angles done by each sweep the plan runs (the caller's phase, whose
    /// count `scene_sweeps` gives).
    pub progress: &'a dyn Progress,
}

impl Default for RunOptions<'_> {
    fn default() -> Self {
        RunOptions {
            settings: Settings::default(),
            clearance_tolerance_mm: units::mm_from_um(LadderTolerances::default().clearance_um),
            progress: &Silent,
        }
    }
}

impl RunOptions<'_> {
    /// The defaults, with the clearance tolerance of `spec`'s `accuracy:` when it has one.
    pub fn for_spec(spec: &Spec) -> Self {
        RunOptions::default().with_spec(spec)
    }

    /// These options with the clearance tolerance of `spec`'s `accuracy:` when it has one.
    fn with_spec(self, spec: &Spec) -> Self {
        let tolerance = spec
            .accuracy
            .as_ref()
            .map_or(self.clearance_tolerance_mm, |a| {
                units::mm_from_um(a.options.tolerances.clearance_um)
            });
        RunOptions {
            clearance_tolerance_mm: tolerance,
            ..self
        }
    }
}

/// Run one scene of the spec, with its design and modification, according to `plan`, the
/// smallest gap over the mesh to the spec's clearance tolerance (`RunOptions::for_spec`); a
/// failure points at the scene's key in the spec (`at_scene`).
pub fn run(spec: &Spec, scene: &Scene, plan: &Plan, options: &RunOptions) -> Result<SceneResult> {
    let options = options.with_spec(spec);
    run_design(&spec.design, &spec.modification, (scene, plan), &options)
        .map_err(|e| at_scene(spec, scene, e))
}

/// A failure of a scene of the spec, with the spec key it points at: the scene's value that
/// `run_design` named (the torque the rollers cannot carry, the bearing too soft for it), else
/// the scene itself, so that an absurd value is found in the spec.
pub fn at_scene(spec: &Spec, scene: &Scene, mut e: Error) -> Error {
    let Some(i) = spec.scenes.iter().position(|s| s.name == scene.name) else {
        return e;
    };
    e.key_path = Some(match e.key_path.take() {
        Some(k) => format!("scenes[{i}].{k}"),
        None => format!("scenes[{i}]"),
    });
    e
}

/// Run one scene of `design` with the modification `m` (an optimisation candidate, a part as
/// drawn by the tolerance study, or the spec's own) according to `plan`.
pub fn run_design(
    design: &Design,
    m: &Modification,
    (scene, plan): (&Scene, &Plan),
    options: &RunOptions,
) -> Result<SceneResult> {
    if let Some(bins) = &scene.duty_cycle {
        return run_duty_cycle(design, m, (scene, plan, bins), options);
    }
    run_one(design, m, (scene, plan), options, None)
}

/// `run_design` of a scene without a duty cycle; `shared`: the clearance of each disc when it
/// is already computed (`run_duty_cycle`: the same for every bin), else computed here.
fn run_one(
    design: &Design,
    m: &Modification,
    (scene, plan): (&Scene, &Plan),
    options: &RunOptions,
    shared: Option<&[ClearanceSweep]>,
) -> Result<SceneResult> {
    let (settings, progress) = (&options.settings, options.progress);
    let mesh = Mesh::new(design, m);
    let target = mesh_minimum::Target::new(design, options.clearance_tolerance_mm);
    let mut whole = MeshMinimum::new(&mesh, target);
    // Disc k's clearance, its crank phase `shift`.
    let mut clearance = |k: usize, shift: f64| -> Result<Option<ClearanceSweep>> {
        if !plan.has(Effect::Clearance) {
            return Ok(None);
        }
        if let Some(c) = shared {
            return Ok(Some(c[k].clone()));
        }
        clearance_sweep(&mut whole, (scene, plan), shift, progress).map(Some)
    };
    let torsion = torsion_loops(design, m, (scene, plan), settings, progress)?;
    let model = runs_loaded(plan).then(|| loaded_model(design, m, scene, plan, settings));
    let sweeps = loaded_sweeps(design, model.as_ref(), (scene, plan), progress)?;
    let swept = sweeps.is_some();
    // Each disc's curves and torque share, moved out of the sweep (not copied).
    let (mut each, transmission) = match sweeps {
        Some(s) => (s.discs.into_iter().zip(s.torque_nmm), s.transmission),
        None => (Vec::new().into_iter().zip(Vec::new()), None),
    };
    let mut discs = Vec::with_capacity(design.discs);
    for k in 0..design.discs {
        let mut loaded = LoadedSweep::default();
        if let Some((curves, torque)) = each.next() {
            loaded = curves;
            // A disc's torque share is a curve of its own only beside other discs.
            loaded.torque_nmm = (design.discs > 1).then_some(torque);
            first_order_valid(design, m, scene, (&loaded, design.disc_phase_rad(k)))?;
            loaded.strength = strength::disc_strength(design, (scene, plan), &loaded);
        }
        discs.push(DiscResult {
            clearance: clearance(k, design.disc_phase_rad(k))?,
            bearing_life: bearing_life(design, scene, plan, &loaded),
            loaded,
            efficiency: None,
        });
    }
    // The reducer's curves, over every disc.
    let mut reducer = ReducerResult {
        transmission,
        torsion,
        ..ReducerResult::default()
    };
    if swept {
        let each: Vec<&LoadedSweep> = discs.iter().map(|d| &d.loaded).collect();
        if plan.computes(Effect::Strength) {
            // The coupled model's friction on the pins bends them too.
            let pin_friction = (model.as_ref().and_then(Model::coupled)).map_or(0.0, |c| c.pin);
            reducer.pin_stress =
                strength::pin_stress(design, &scene.crank_rad, &each, pin_friction);
        }
        if let Some((all, each)) = efficiency::efficiency(design, (scene, plan), &each)? {
            reducer.efficiency = Some(all);
            for (disc, e) in discs.iter_mut().zip(each) {
                disc.efficiency = Some(e);
            }
        }
    }
    Ok(SceneResult {
        name: scene.name.clone(),
        crank_rad: scene.crank_rad.clone(),
        reducer,
        discs,
        duty: None,
    })
}

/// A duty-cycle scene ([`engine::duty_cycle`](crate::engine::duty_cycle)): each bin run as
/// the scene at the bin's torque and speed (in parallel, results in the bins' order whatever
/// the thread count), combined. A bin's failure points at its key (`duty_cycle[j]…`).
///
/// The clearance does not depend on the load: the bins differ in torque and speed alone, so
/// each disc's clearance over the scene's crank angles is the same in every bin. It is
/// computed once, before the bins, and each bin's result carries it (the same bytes as the
/// bin's own). Should it fail, each bin computes its own as a scene alone does, so the error
/// and the key it points at are the ones a bin gives.
fn run_duty_cycle(
    design: &Design,
    m: &Modification,
    (scene, plan, bins): (&Scene, &Plan, &[crate::model::DutyBin]),
    options: &RunOptions,
) -> Result<SceneResult> {
    use rayon::prelude::*;
    let shared = match bins.first() {
        Some(bin) if plan.has(Effect::Clearance) => {
            clearances(design, m, (&bin.scene(scene, 0), plan), options).ok()
        }
        _ => None,
    };
    let runs: Vec<Result<SceneResult>> = bins
        .par_iter()
        .enumerate()
        .map(|(j, bin)| {
            let at = bin.scene(scene, j);
            run_one(design, m, (&at, plan), options, shared.as_deref()).map_err(|mut e| {
                e.key_path = Some(match e.key_path.take().as_deref() {
                    Some("output_torque_nm") => format!("duty_cycle[{j}].output_torque_nm"),
                    None => format!("duty_cycle[{j}]"),
                    Some(k) => k.to_string(),
                });
                e
            })
        })
        .collect();
    let runs = bins
        .iter()
        .zip(runs)
        .map(|(&bin, r)| r.map(|result| DutyBinResult { bin, result }))
        .collect::<Result<Vec<_>>>()?;
    Ok(SceneResult {
        name: scene.name.clone(),
        crank_rad: scene.crank_rad.clone(),
        reducer: ReducerResult::default(),
        discs: Vec::new(),
        duty: Some(Box::new(duty_cycle::combine(design, runs))),
    })
}

/// The clearance of each disc of `design` over the scene's angles, in disc order: `run_one`
/// with the plan's clearance alone (one mesh minimum for all, disc k at its crank phase).
fn clearances(
    design: &Design,
    m: &Modification,
    (scene, plan): (&Scene, &Plan),
    options: &RunOptions,
) -> Result<Vec<ClearanceSweep>> {
    let alone = plan.part(|e| e == Effect::Clearance);
    let discs = run_one(design, m, (scene, &alone), options, None)?.discs;
    Ok(discs.into_iter().filter_map(|d| d.clearance).collect())
}

/// The clearance of a disc at crank phase `shift` over the scene's angles, with the smallest
/// gap over the whole mesh (`MeshMinimum::cover`), its crank angle the scene's.
fn clearance_sweep(
    whole: &mut MeshMinimum,
    (scene, plan): (&Scene, &Plan),
    shift: f64,
    progress: &dyn Progress,
) -> Result<ClearanceSweep> {
    let scope = if plan.has_detail(Detail::Backlash) {
        clearance::Scope::Backlash
    } else {
        clearance::Scope::Gaps
    };
    let crank: Vec<f64> = scene.crank_rad.iter().map(|c| c + shift).collect();
    let failed = |f| Error::computation(format!("scene `{}`: {f}", scene.name));
    let mut c = clearance::sweep(whole.mesh(), &crank, scope, progress).map_err(failed)?;
    let period_deg = units::deg(whole.period_rad());
    whole.cover(&crank, shift, &mut c).map_err(|f| {
        Error::computation(format!(
            "scene `{}`: seeking the smallest gap over the whole period of {}° of crank: {f}",
            scene.name,
            crate::numeric::number(period_deg)
        ))
    })?;
    Ok(c)
}

/// A first-order scene's loaded sweep (of the disc at crank phase `phase_rad`) within the
/// closed form's validity ([`first_order::LagValidity`](crate::geometry::first_order::LagValidity)):
/// at every crank angle the rollers' arms move over the lag by less than their moment; else an
/// error at the scene's `geometry` saying where and how far, never a result.
fn first_order_valid(
    design: &Design,
    m: &Modification,
    scene: &Scene,
    (loaded, phase_rad): (&LoadedSweep, f64),
) -> Result<()> {
    let Some(rollers) = loaded.rollers.as_ref() else {
        return Ok(());
    };
    if scene.geometry != GeometryMode::FirstOrder {
        return Ok(());
    }
    let validity = first_order::LagValidity::new(design, m);
    let mut forces = vec![0.0; design.rollers];
    // The worst angle: (ε, crank, lag); a change that is not a number is the worst of all.
    let mut worst = (0.0, 0.0, 0.0);
    for (k, (&crank, &lag)) in scene.crank_rad.iter().zip(&rollers.lag_rad).enumerate() {
        forces
            .iter_mut()
            .zip(&rollers.force_n)
            .for_each(|(f, curve)| *f = curve[k]);
        let change = validity.moment_change(crank + phase_rad, lag, &forces);
        let change = if change.is_nan() {
            f64::INFINITY
        } else {
            change
        };
        if change > worst.0 {
            worst = (change, crank, lag);
        }
    }
    let (change, crank, lag) = worst;
    if change < 1.0 {
        return Ok(());
    }
    let share = match change.is_finite() {
        true => crate::numeric::percent(change),
        false => "more than any number".to_string(),
    };
    Err(Error::computation(format!(
        "scene `{}`: crank angle {:.4}°: the first-order geometry is outside its validity: \
         its lag β = {} rad moves the rollers' moment arms, which the closed form keeps at \
         those of the ideal pose, by {share} of their moment (|β|·Σ F·|∂²g/∂β²| / Σ F·|l|, from \
         the locus's curvature at each contact; the closed form holds below 100 %); the exact \
         geometry (`geometry: exact`) is the reference",
        scene.name,
        units::deg(crank),
        crate::numeric::number(lag),
    ))
    .at_key("geometry"))
}

/// The torsion loops of a scene with a `torque_sweep` ([`engine::torsion`](crate::engine::torsion)), when planned.
fn torsion_loops(
    design: &Design,
    m: &Modification,
    (scene, plan): (&Scene, &Plan),
    settings: &Settings,
    progress: &dyn Progress,
) -> Result<Option<crate::model::results::TorsionCurves>> {
    let (Some(sweep), true) = (&scene.torque_sweep, plan.has(Effect::Torsion)) else {
        return Ok(None);
    };
    let model = loaded_model(design, m, scene, plan, settings);
    let discs = Discs::new(&model, design.discs);
    let pins = plan.has(Effect::OutputPins);
    let compliances = crate::model::results::TorsionCompliances {
        contact_law: scene.contact_law,
        geometry: scene.geometry,
        pin_contacts: pins,
        bearing_stiffness_n_per_mm: model.bearing_stiffness_n_per_mm,
        pin_bending: design.pins.support.filter(|_| pins),
        structure_rad_per_nmm: design.structure_compliance_rad_per_nmm,
    };
    torsion::run(&discs, sweep, &scene.crank_rad, compliances, progress)
        .map(Some)
        .map_err(|f| {
            Error::computation(format!(
                "scene `{}`: crank angle {:.4}° locked, output torque {} N·m: {}",
                scene.name,
                units::deg(f.crank_rad),
                crate::numeric::number(units::nm(f.torque_nmm)),
                f.failure
            ))
            .at_key("torque_sweep.rated_nm")
        })
}

/// The loaded sweep of the scene's discs (`discs_sweep::sweep_reducer`: one disc, or several
/// coupled through the output, [`equilibrium::discs`](crate::equilibrium::discs)), when the
/// plan runs it.
fn loaded_sweeps(
    design: &Design,
    model: Option<&Model>,
    (scene, plan): (&Scene, &Plan),
    progress: &dyn Progress,
) -> Result<Option<DiscSweeps>> {
    let Some(model) = model else {
        return Ok(None);
    };
    let periodic = scene.spans_loaded_periods(design, plan);
    discs_sweep::sweep_reducer(model, design.discs, &scene.crank_rad, (periodic, progress))
        .map(Some)
        .map_err(|f| sweep_failed(scene, f))
}

/// The error of a loaded sweep that failed, at the scene's value it points at (made a spec
/// key by `at_scene`).
fn sweep_failed(scene: &Scene, f: sweep::SweepFailure) -> Error {
    let e = solve_failed(scene, f.crank_rad, &f.failure);
    match f.failure.cause() {
        SolveFailure::BeyondCapacity { .. } => e.at_key("output_torque_nm"),
        SolveFailure::OutOfMesh { .. } => e.at_key("bearing_stiffness_n_per_mm"),
        _ => e,
    }
}

/// The crank bearing's rating life over the scene ([`engine::bearing_life`](crate::engine::bearing_life)): when the design
/// has a `crank_bearing`, the scene computes the bearing force, and its sweep covers whole
/// loaded periods (the equivalent load is a mean over the load cycle; see `notes` for the
/// scenes left out); the life in hours needs the scene's `input_speed_rpm` too.
fn bearing_life(
    design: &Design,
    scene: &Scene,
    plan: &Plan,
    loaded: &LoadedSweep,
) -> Option<BearingLife> {
    let rating = design.crank_bearing?;
    let force = &loaded.bearing.as_ref()?.force_n;
    if !scene.spans_loaded_periods(design, plan) {
        return None;
    }
    let load = bearing_life::equivalent_load(force, rating.life_exponent);
    let rpm = scene.input_speed_rpm;
    Some(bearing_life::life(load, rating, rpm, design.teeth))
}

/// What a reader of the results must be told besides the numbers ([`report::explain`](crate::report::explain) says
/// it in words).
#[derive(Debug, Clone, PartialEq)]
pub enum Note {
    /// A torsion scene: its hysteresis loss is 0 (its loop is solved without friction), or it
    /// comes from the friction of `reducer.friction` in the loop's balance (`friction`).
    Hysteresis { scene: String, friction: bool },
    /// A scene whose crank-bearing life is not rated: its crank range is not a whole number of
    /// loaded periods (`loaded_period_rad`), and the equivalent load is a mean over whole load
    /// cycles.
    LifeNotRated {
        scene: String,
        loaded_period_rad: f64,
    },
    /// A scene whose crank-bearing life in hours is not rated: it has no `input_speed_rpm`.
    LifeHoursNotRated { scene: String },
    /// A scene that computes `efficiency` without `input_speed_rpm`: its losses have no watts
    /// (losses × ω) and no temperature; η does not depend on the speed.
    LossWattsNotRated { scene: String },
    /// A scene with the output pins whose crank is longer than the holes were bored for by
    /// more than their clearance: every pin is pressed into its hole by `interference_mm`
    /// (de − c) at every crank angle, whatever the torque, and the crank bearing carries that
    /// preload (MODEL.md "Part deviations": the holes keep the nominal e + c). `drawn`: the
    /// depth is the largest a tolerance study draws, in the samples whose crank is that long.
    PinsPreloaded {
        /// The scene's name.
        scene: String,
        /// How deep every pin is pressed into its hole, mm.
        interference_mm: f64,
        /// The depth is the largest a tolerance study draws.
        drawn: bool,
    },
}

/// The note of `scene` (run by `plan`, with the output pins) whose crank is longer than the
/// pin holes allow: it presses every pin into its hole by de − c, mm, for an eccentricity
/// deviation de and hole clearance c (a hole's radius is pin + e + c, the pin's centre sits
/// e + de from the hole's), when positive; `drawn` as `Note::PinsPreloaded` says.
pub fn pins_preloaded(
    design: &Design,
    (scene, plan): (&Scene, &Plan),
    eccentricity_deviation_mm: f64,
    drawn: bool,
) -> Option<Note> {
    let depth = eccentricity_deviation_mm - design.pins.hole_clearance_mm;
    (plan.has(Effect::OutputPins) && depth > 0.0).then(|| Note::PinsPreloaded {
        scene: scene.name.clone(),
        interference_mm: depth,
        drawn,
    })
}

/// The notes of a spec's scenes, in scene order: a torsion scene's zero hysteresis, losses
/// without a speed to give their watts, pins preloaded by a crank longer than their holes
/// allow, a crank bearing whose life a scene could not rate.
pub fn notes(spec: &Spec) -> Vec<Note> {
    let mut notes = Vec::new();
    for scene in &spec.scenes {
        let plan = Plan::for_scene(scene);
        let name = || scene.name.clone();
        if plan.has(Effect::Torsion) {
            notes.push(Note::Hysteresis {
                scene: name(),
                friction: spec
                    .design
                    .friction
                    .is_some_and(|f| Coupling::new(&f, &spec.design).active()),
            });
        }
        if plan.computes(Effect::Efficiency) && !scene.has_speed() {
            notes.push(Note::LossWattsNotRated { scene: name() });
        }
        let de = spec.design.deviations.eccentricity_mm;
        notes.extend(pins_preloaded(&spec.design, (scene, &plan), de, false));
        if spec.design.crank_bearing.is_some() && plan.computes(Effect::Bearing) {
            if !scene.spans_loaded_periods(&spec.design, &plan) {
                notes.push(Note::LifeNotRated {
                    scene: name(),
                    loaded_period_rad: scene.run_period_rad(&spec.design, &plan),
                });
            } else if !scene.has_speed() {
                notes.push(Note::LifeHoursNotRated { scene: name() });
            }
        }
    }
    notes
}

/// How many sweeps over its crank angles `scene`'s `plan` runs for a reducer of `discs` discs:
/// the work a progress display of the scene counts, in crank angles. The clearance once per
/// disc (with a duty cycle too: the bins share it, `run_duty_cycle`), the loaded sweep and the
/// torsion once per bin.
pub fn scene_sweeps(scene: &Scene, plan: &Plan, discs: usize) -> usize {
    // A duty cycle has at least one bin (the spec refuses an empty one).
    let bins = scene.duty_cycle.as_ref().map_or(1, Vec::len);
    let clearance = discs * usize::from(plan.has(Effect::Clearance));
    clearance + bins * (usize::from(runs_loaded(plan)) + usize::from(plan.has(Effect::Torsion)))
}

/// Whether `plan` runs the loaded sweep over the crank angle (roller contact, output pins or
/// the bearing, outside a torsion scene).
fn runs_loaded(plan: &Plan) -> bool {
    Effect::ALL
        .into_iter()
        .any(|e| e.is_loaded() && plan.computes(e))
}

/// The friction a crank sweep of `plan` balances with: the coupled model's, when the scene
/// computes `efficiency` (`loaded_model`; a torsion loop balances with any model's).
pub fn coupled_sweep(design: &Design, plan: &Plan) -> Option<Friction> {
    (design.friction)
        .filter(|f| f.model == FrictionModel::Coupled && plan.computes(Effect::Efficiency))
}

/// The loaded model of a scene (roller contact, output pins, bearing as `plan` says) solved to
/// `settings`: what the sweep of `run_design` solves at every crank angle, and what the design
/// review's drawing solves at its one angle.
pub fn loaded_model(
    design: &Design,
    m: &Modification,
    scene: &Scene,
    plan: &Plan,
    settings: &Settings,
) -> Model {
    let mut model = Model::new(design, m, scene, plan);
    model.settings = *settings;
    // The sweep records the friction losses and input torque of `efficiency` at each angle.
    model.losses = (design.friction)
        .filter(|_| plan.computes(Effect::Efficiency))
        .map(|f| LossModel::new(f, design));
    // The coupled friction model puts friction inside the balance of a crank sweep that asks
    // for `efficiency`: its loaded outputs are then the coupled ones. A torsion loop always
    // balances with its friction, whichever model the efficiency uses (friction that is not
    // in the balance opens no loop); its sliding is the disc's turn under the locked input,
    // the loading branch's until `engine::torsion` sets the branch.
    match design.friction {
        Some(f) if scene.torque_sweep.is_some() && plan.has(Effect::Torsion) => {
            let mut model = model.with_friction(&f, design);
            model.coupling = model.coupling.map(|c| c.in_torsion(1.0));
            model
        }
        _ => match coupled_sweep(design, plan) {
            Some(f) => model.with_friction(&f, design),
            None => model,
        },
    }
}

/// The error of a loaded solve that failed: the scene and the crank angle.
pub fn solve_failed(scene: &Scene, crank_rad: f64, failure: &impl std::fmt::Display) -> Error {
    Error::computation(format!(
        "scene `{}`: crank angle {:.4}°: equilibrium solve failed: {failure}",
        scene.name,
        units::deg(crank_rad),
    ))
}
