//! The loaded solve at one crank angle of a scene.
//!
//! Rigid bearing: the disc centre sits at e·(cos φ, sin φ); moment balance about it decouples
//! into the roller balance Σ F_i·l_i(β) = T and the pin balance Σ F_j·a_j(βo) = T, each a
//! monotone 1-D root (`solve`). The bearing force is then −(Σ roller forces + Σ pin forces).
//! Compliant bearing (stiffness kb): the disc centre moves by u and all of x = (ux, uy, β, βo)
//! are solved together by Newton with an analytic Jacobian (nalgebra), with a bracketed
//! fixed-point fallback.

use super::balance::{closed_form, moment, round_off, settle, unload_round_off, Contact};
use super::pins::{PinState, Pins};
use super::rollers::{AngleTrig, Reach, RollerState, Rollers};
use super::solve::{monotone_root, Balance, Settings, SolveFailure};
use crate::geometry::clearance::{GapFailure, Pose};
use crate::geometry::{cross, Vec2};
use crate::model::{ContactLaw, Design, Effect, GeometryMode, Modification, Plan, Scene};
use nalgebra::{Matrix4, Vector4};

/// What the loaded model of a scene includes.
#[derive(Debug, Clone)]
pub struct Model {
    pub rollers: Option<Rollers>,
    pub pins: Option<Pins>,
    pub bearing: bool,
    pub bearing_stiffness_n_per_mm: Option<f64>,
    pub torque_nmm: f64,
    pub teeth: usize,
    /// The crank's eccentricity as built, e + de, mm: the disc centre's orbit.
    pub eccentricity_mm: f64,
    pub settings: Settings,
    /// First-order geometry (also for pins when rollers are not modelled).
    pub first_order: bool,
}

impl Model {
    /// The loaded model of `scene` with the loaded effects of `plan` (roller contact, output
    /// pins, bearing); the crank bearing's compliance applies only with the bearing modelled.
    pub fn new(design: &Design, m: &Modification, scene: &Scene, plan: &Plan) -> Self {
        let (rollers, pins, bearing) = (
            plan.has(Effect::RollerContact),
            plan.has(Effect::OutputPins),
            plan.has(Effect::Bearing),
        );
        Model {
            rollers: rollers.then(|| Rollers::new(design, m, scene.contact_law, scene.geometry)),
            pins: pins.then(|| Pins::new(design, scene.contact_law)),
            bearing,
            bearing_stiffness_n_per_mm: scene.bearing_stiffness_n_per_mm.filter(|_| bearing),
            torque_nmm: scene.output_torque_nmm,
            teeth: design.teeth,
            eccentricity_mm: design.eccentricity_mm + design.deviations.eccentricity_mm,
            settings: Settings::default(),
            first_order: scene.geometry == GeometryMode::FirstOrder,
        }
    }

    /// The lag at which the rollers sit in their mesh without load, to first order: a profile
    /// turned by Δδ (reduced to the tooth pitch) is a disc turned by Δδ, which the lag −Δδ
    /// undoes. The first guess of a sweep, so that a large rotation starts at its mesh.
    pub fn rest_lag(&self) -> f64 {
        self.rollers
            .as_ref()
            .map_or(0.0, |r| -r.mesh.profile.rotation_rad)
    }

    /// How far (crank angle, rad) the last solved angle may be for its lags and contact
    /// points to warm-start the next: a quarter of a mesh period, over which a foot moves by a
    /// fortieth of a tooth; a sweep's steps are far finer, a sweep of a few steps per turn is
    /// not warm-started.
    pub fn warm_reach(&self) -> f64 {
        std::f64::consts::FRAC_PI_2 / (self.teeth + 1) as f64
    }

    /// Pins follow the rollers' geometry mode (first order: ideal directions, linear gaps).
    fn first_order_pins(&self) -> bool {
        self.rollers
            .as_ref()
            .is_some_and(|r| r.geometry == GeometryMode::FirstOrder)
            || self.first_order
    }
}

/// The equilibrium at one crank angle. Fixed frame; lags in rad (positive opposes the motion).
/// From `solve_angle` every roller state is exact; inside a sweep a roller proven out of reach
/// has zero force, a lower bound as its gap and the geometry of its last exact evaluation.
#[derive(Debug, Clone, Default)]
pub struct AngleSolution {
    /// β, when the rollers are modelled.
    pub lag_rad: Option<f64>,
    pub rollers: Vec<RollerState>,
    /// βo, when the pins are modelled.
    pub output_lag_rad: Option<f64>,
    pub pins: Vec<PinState>,
    /// Disc-centre displacement from e·(cos φ, sin φ) (compliant bearing), mm.
    pub centre_offset_mm: Vec2,
    /// Crank-bearing force on the disc, N, when `bearing` is modelled.
    pub bearing_force_n: Option<Vec2>,
    /// Largest relative residual of the force and moment balance (paper Eqs. 12–14).
    pub residual: Option<f64>,
}

/// Reusable state of a sequential run over neighbouring crank angles: the last solution (its
/// buffers and warm starts), where each roller was last evaluated, and the last two lags for
/// extrapolating the next guess.
#[derive(Debug, Clone, Default)]
pub struct Work {
    pub sol: AngleSolution,
    /// Evaluate every roller exactly at the answer. Off in sweeps, where a roller proven out
    /// of reach keeps the geometry of its last exact evaluation and a lower bound as its gap
    /// (its force is exactly zero either way).
    pub exact_final: bool,
    /// (cos φ, sin φ) of the angle being solved.
    pub(super) e_phi: Vec2,
    reaches: Vec<Reach>,
    /// The last (up to three) solved angles, oldest first, in the last `filled` entries.
    history: [Solved; 3],
    filled: usize,
    terms: Vec<(f64, f64)>,
    events: Vec<(f64, f64, f64)>,
    /// ∂M/∂β of the rollers' balance and ∂M/∂βo of the pins' at the last solution, N·mm/rad,
    /// as the root search last evaluated them (0 where a closed form solved the balance).
    slopes: (f64, f64),
}

/// A solved angle as the next angle's guess sees it.
#[derive(Debug, Clone, Copy, Default)]
struct Solved {
    crank: f64,
    /// β and βo, rad.
    lag: f64,
    output_lag: f64,
    /// The torque it was solved at, N·mm.
    torque: f64,
}

/// How the history extrapolates to an angle: quadratic (Lagrange weights of the last three
/// angles), linear from the last two (the step ratio), or the last value.
#[derive(Debug, Clone, Copy)]
enum Fit {
    Quadratic([f64; 3]),
    Linear(f64),
    Last,
}

impl Fit {
    fn of(history: &[Solved], crank: f64) -> Option<Fit> {
        match history {
            [h0, h1, h2]
                if h0.crank != h1.crank && h1.crank != h2.crank && h0.crank != h2.crank =>
            {
                let (p0, p1, p2) = (h0.crank, h1.crank, h2.crank);
                let l0 = (crank - p1) * (crank - p2) / ((p0 - p1) * (p0 - p2));
                let l1 = (crank - p0) * (crank - p2) / ((p1 - p0) * (p1 - p2));
                let l2 = (crank - p0) * (crank - p1) / ((p2 - p0) * (p2 - p1));
                Some(Fit::Quadratic([l0, l1, l2]))
            }
            [.., h0, h1] if h1.crank != h0.crank => {
                Some(Fit::Linear((crank - h1.crank) / (h1.crank - h0.crank)))
            }
            [.., _] => Some(Fit::Last),
            [] => None,
        }
    }

    /// The extrapolated value of `value` of the history `Fit::of` was made from.
    fn apply(self, history: &[Solved], value: impl Fn(&Solved) -> f64) -> f64 {
        match (self, history) {
            (Fit::Quadratic([l0, l1, l2]), [h0, h1, h2]) => {
                l0 * value(h0) + l1 * value(h1) + l2 * value(h2)
            }
            (Fit::Linear(w), [.., h0, h1]) => value(h1) + w * (value(h1) - value(h0)),
            (_, [.., h]) => value(h),
            (_, []) => 0.0,
        }
    }
}

/// The change of a balance's lag (rad) for a change `dt` (N·mm) of its torque, by the slope
/// of its moment (N·mm/rad); none where that is no slope.
fn lag_for_torque(slope: f64, dt: f64) -> f64 {
    if slope > 0.0 && slope.is_finite() {
        dt / slope
    } else {
        0.0
    }
}

impl Work {
    /// Guesses for (β, βo) at `crank`: quadratic (Lagrange) extrapolation of the last three
    /// angles, linear from two, the last value from one; with no history, or a history too far
    /// away to say anything (`Model::warm_reach`), the lag at which the disc sits without load
    /// (`Model::rest_lag`) and 0.
    pub(super) fn guess(&self, crank: f64, model: &Model) -> (f64, f64) {
        self.extrapolate(crank, model, false)
    }

    /// `guess` at the model's torque, where that is not the history's (a disc's share of
    /// several, which moves with the crank and, within an angle, with each correction of the
    /// split): each lag moves further by the torque's departure from its own extrapolation
    /// over the slope of its balance at the last solution. Exact for a balance linear on its
    /// contact set, where the lags' trend alone misses by that departure over the slope (on a
    /// disc of 11 rollers that left the pins' balance a second evaluation at most angles).
    /// With a rigid bearing only: a compliant one's lags move with the centre too.
    fn guess_at_torque(&self, crank: f64, model: &Model) -> (f64, f64) {
        self.extrapolate(crank, model, model.bearing_stiffness_n_per_mm.is_none())
    }

    fn extrapolate(&self, crank: f64, model: &Model, follow_torque: bool) -> (f64, f64) {
        let history = &self.history[3 - self.filled..];
        let fit = self.near(crank, model).then(|| Fit::of(history, crank));
        let Some(fit) = fit.flatten() else {
            return (model.rest_lag(), 0.0);
        };
        let lag = fit.apply(history, |h| h.lag);
        let output_lag = fit.apply(history, |h| h.output_lag);
        let t = model.torque_nmm;
        if !follow_torque || history.iter().all(|h| h.torque == t) {
            return (lag, output_lag);
        }
        let dt = t - fit.apply(history, |h| h.torque);
        (
            lag + lag_for_torque(self.slopes.0, dt),
            output_lag + lag_for_torque(self.slopes.1, dt),
        )
    }

    /// Whether the last angle solved is near enough to `crank` to warm-start it.
    fn near(&self, crank: f64, model: &Model) -> bool {
        self.filled > 0 && (self.history[2].crank - crank).abs() <= model.warm_reach()
    }

    /// Forget the last angle's states when it is too far from `crank` to warm-start it (a
    /// sweep of two steps over a turn): the closest points then start from each roller's own
    /// foot guess, and every roller is evaluated, so that each angle solves on its own.
    fn forget_if_far(&mut self, crank: f64, model: &Model) {
        if self.filled > 0 && !self.near(crank, model) {
            self.filled = 0;
            self.sol.rollers.clear();
            self.sol.pins.clear();
            self.reaches.clear();
        }
    }

    /// Evaluate every roller at the next solve: the bounds that let a sweep skip a roller out
    /// of reach are kept from the last solve; a solve of the same angle at another torque (a
    /// disc's share, `discs`) starts without them.
    pub(super) fn reach_all(&mut self) {
        self.reaches.clear();
    }

    /// Whether `crank` is the angle solved last.
    pub(super) fn solved_at(&self, crank: f64) -> bool {
        self.filled > 0 && self.history[2].crank == crank
    }

    fn remember(&mut self, crank: f64, torque: f64) {
        let lag = self.sol.lag_rad.unwrap_or(0.0);
        let output_lag = self.sol.output_lag_rad.unwrap_or(0.0);
        self.remember_lags(crank, (lag, output_lag), torque);
    }

    /// Remember the lags (β, βo) solved at `crank` for the next angle's guess. A solve of the
    /// angle last remembered again (the several-disc balance re-solves a disc at a corrected
    /// torque) replaces it: its lags are then the guess at that angle, and the angles before
    /// it stay for the extrapolation to the next.
    pub(super) fn remember_lags(&mut self, crank: f64, (lag, output_lag): (f64, f64), torque: f64) {
        let solved = Solved {
            crank,
            lag,
            output_lag,
            torque,
        };
        if self.filled > 0 && self.history[2].crank == crank {
            self.history[2] = solved;
            return;
        }
        self.history = [self.history[1], self.history[2], solved];
        self.filled = (self.filled + 1).min(3);
    }
}

fn roller_balance(
    r: &Rollers,
    pose: &Pose,
    states: &mut Vec<RollerState>,
) -> Result<Balance, GapFailure> {
    r.evaluate(pose, states)?;
    let (value, slope, scale) = moment(states);
    Ok(Balance {
        value,
        slope,
        scale,
        resolution: r.moment_resolution(states, pose.centre_offset_mm.norm()),
    })
}

/// Zero torque with clearance leaves the disc free within its backlash; we report the limit
/// T → 0⁺: the lag at which the nearest contact in the load direction just closes.
/// Newton on the smallest gap, x ← x + min(gap/(−∂gap/∂x)) over contacts that close as x grows.
fn touching<S>(
    mut eval: impl FnMut(f64) -> Result<Vec<(f64, f64)>, S>,
    start: f64,
) -> Result<f64, S> {
    let mut x = start;
    for _ in 0..50 {
        let step = eval(x)?
            .into_iter()
            .filter(|&(_, slope)| slope < 0.0)
            .map(|(gap, slope)| gap / -slope)
            .fold(f64::INFINITY, f64::min);
        if !step.is_finite() {
            break;
        }
        x += step;
        if step.abs() <= 1e-16 + 1e-13 * x.abs() {
            break;
        }
    }
    // Land on the open side: in the limit the first contact just touches and carries no force.
    // Newton may stop a rounding error past the touch (a gap of −1e-18 mm, a force of 1e-12 N),
    // which would make the contact count at zero torque depend on rounding.
    for _ in 0..8 {
        let overlap = eval(x)?
            .into_iter()
            .filter(|&(gap, slope)| slope < 0.0 && gap < 0.0)
            .map(|(gap, slope)| gap / slope)
            .fold(0.0, f64::max);
        if overlap == 0.0 {
            break;
        }
        x -= overlap + f64::EPSILON * x.abs();
    }
    Ok(x)
}

fn in_contact<'a>(forces: impl IntoIterator<Item = &'a f64>) -> bool {
    forces.into_iter().any(|&f| f > 0.0)
}

/// The rollers' moment never reached the torque within the lags searched: say how far it got
/// and how deep the contacts were there. Far beyond the rated load the moment stops growing
/// with the lag (rollers pressed millimetres into the flanks slide towards the tips, their arms
/// shrink), so the torque is more than the disc can hold in this contact model.
fn beyond_reach(r: &Rollers, pose: &Pose, moment_nmm: f64, torque_nmm: f64) -> SolveFailure {
    let mut states = Vec::new();
    let deepest = r.evaluate(pose, &mut states).ok().and_then(|()| {
        states
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.gap_mm.total_cmp(&b.1.gap_mm))
            .map(|(i, s)| (i, -s.gap_mm, r.mesh.roller_radius_mm))
    });
    SolveFailure::BeyondCapacity {
        torque_nmm,
        moment_nmm,
        lag_rad: pose.lag_rad,
        deepest,
    }
}

/// Solve the rollers at a fixed centre offset: β with Σ F·l = T. `e_phi` = (cos φ, sin φ).
fn solve_rollers(
    model: &Model,
    r: &Rollers,
    (crank, e_phi): (f64, Vec2),
    offset: Vec2,
    guess: f64,
    work: &mut Work,
) -> Result<f64, SolveFailure> {
    let pose = |lag| Pose {
        crank_rad: crank,
        lag_rad: lag,
        centre_offset_mm: offset,
    };
    let linear = r.geometry == GeometryMode::FirstOrder
        && r.law == ContactLaw::PaperLinear
        && offset == Vec2::zeros();
    if linear {
        r.first_order_terms(e_phi, &mut work.terms);
        let (k, t) = (r.linear_stiffness(), model.torque_nmm);
        let terms = &work.terms;
        let states = &mut work.sol.rollers;
        let (lag, scale) = closed_form(
            (k, terms, t, model.settings.rel_tol),
            guess,
            &mut work.events,
            states,
            |lag, states| r.first_order_states(&pose(lag), e_phi, terms, states),
        )?;
        // The closed form's answer at zero torque is the touching pose (T → 0⁺, or a
        // preload's balance). The touching contact's gap g − l·x is round-off (±1e-17 mm), and
        // so is its force (~5e-12 N, whose unbalanced moment made the residual 1): zero, as in
        // the iterative solve.
        if t == 0.0 && scale <= r.moment_resolution(states, 0.0) {
            states.iter_mut().for_each(RollerState::unload);
        }
        work.slopes.0 = 0.0;
        return Ok(lag);
    }
    if work.reaches.len() != r.count() {
        work.reaches = vec![
            Reach {
                crank_rad: crank,
                lag_rad: guess,
                offset_mm: offset,
                gap_mm: f64::NEG_INFINITY,
            };
            r.count()
        ];
    }
    let exact_final = work.exact_final;
    let (states, reaches) = (&mut work.sol.rollers, &mut work.reaches);
    let trig = AngleTrig::new(crank, model.teeth);
    let offset_norm = offset.norm();
    let root = monotone_root(
        |lag| {
            r.evaluate_at(&pose(lag), &trig, states, reaches)?;
            let (value, slope, scale) = moment(states);
            Ok::<_, GapFailure>(Balance {
                value,
                slope,
                scale,
                resolution: r.moment_resolution(states, offset_norm),
            })
        },
        model.torque_nmm,
        guess,
        &model.settings,
    )
    .map_err(|failure| match failure {
        SolveFailure::NoBracket {
            nearest: Some((x, value)),
            ..
        } => beyond_reach(r, &pose(x), value, model.torque_nmm),
        other => other,
    })?;
    work.slopes.0 = root.slope;
    let mut lag = root.x;
    if let Some(towards) = root.straddle {
        // The balance steps over the torque between two adjacent lags (round-off of the
        // gaps): every roller exact at both ends, forces mixed so that Σ F·l = T.
        let exact = |lag: f64, states: &mut Vec<RollerState>| {
            r.evaluate_at(&pose(lag), &trig, states, &mut [])
                .map_err(SolveFailure::Gap)
        };
        exact(lag, states)?;
        lag = settle(lag, towards, model.torque_nmm, states, exact)?;
    } else if exact_final {
        // Every roller exact at the answer (skipped ones carried only a gap bound).
        r.evaluate_at(&pose(lag), &trig, states, &mut [])
            .map_err(SolveFailure::Gap)?;
    }
    if model.torque_nmm == 0.0 {
        // Free in the backlash: no contact carries force, or none more than round-off. The
        // root search meets a zero torque wherever the moment is round-off, and from a lag
        // beyond the backlash's far side (a warm start at a share against the torque) that is
        // the far side's edge, where a roller's force of round-off still counts as a contact:
        // the limit T → 0⁺ is the near contact in the load direction all the same.
        let free = round_off(states, r.moment_resolution(states, offset_norm));
        if free || !in_contact(states.iter().map(|s| &s.force_n)) {
            lag = touching(
                |l| {
                    roller_balance(r, &pose(l), states)
                        .map(|_| states.iter().map(|s| (s.gap_mm, -s.arm_mm)).collect())
                },
                lag,
            )
            .map_err(SolveFailure::Gap)?;
            roller_balance(r, &pose(lag), states).map_err(SolveFailure::Gap)?;
            reaches
                .iter_mut()
                .for_each(|x| x.gap_mm = f64::NEG_INFINITY);
        }
        let resolution = r.moment_resolution(states, offset_norm);
        unload_round_off(states, resolution);
    }
    Ok(lag)
}

/// Solve the pins at a fixed disc pose: βo with Σ F·a = T.
fn solve_pins(
    model: &Model,
    p: &Pins,
    e_phi: Vec2,
    offset: Vec2,
    psi: f64,
    guess: f64,
    work: &mut Work,
) -> Result<f64, SolveFailure> {
    let first_order = model.first_order_pins();
    if let (true, Some(k), true) = (first_order, p.linear_stiffness(), offset == Vec2::zeros()) {
        let centre = e_phi * model.eccentricity_mm;
        p.first_order_at(e_phi, psi.sin_cos(), centre, 0.0, &mut work.sol.pins);
        work.terms.clear();
        work.terms
            .extend(work.sol.pins.iter().map(|s| (s.gap_mm, s.arm_mm)));
        // The gaps are linear in the lag: those at any lag are the ones at 0 moved by it.
        let at_zero = work.sol.pins.clone();
        let (lag, _) = closed_form(
            (k, &work.terms, model.torque_nmm, model.settings.rel_tol),
            guess,
            &mut work.events,
            &mut work.sol.pins,
            |lag, states| {
                states.clone_from(&at_zero);
                p.first_order_lagged(lag, states);
            },
        )?;
        work.slopes.1 = 0.0;
        return Ok(lag);
    }
    let states = &mut work.sol.pins;
    // The angle's trigonometry, once for every evaluation of the pin balance.
    let ecc = e_phi;
    let rotation = psi.sin_cos();
    let evaluate = |lag: f64, states: &mut Vec<PinState>| {
        if first_order {
            let centre = ecc * model.eccentricity_mm + offset;
            p.first_order_at(ecc, rotation, centre, lag, states);
        } else {
            p.evaluate_at(ecc, rotation, offset, lag, states);
        }
        let (value, slope, scale) = moment(states);
        Balance {
            value,
            slope,
            scale,
            resolution: p.moment_resolution(states, offset.norm()),
        }
    };
    let root = monotone_root(
        |lag| Ok::<_, SolveFailure>(evaluate(lag, states)),
        model.torque_nmm,
        guess,
        &model.settings,
    )?;
    work.slopes.1 = root.slope;
    // `states` holds the evaluation at root.x: the solver's last evaluation is at its answer.
    let mut lag = root.x;
    if let Some(towards) = root.straddle {
        // As for the rollers: forces mixed between two neighbouring output lags.
        lag = settle(lag, towards, model.torque_nmm, states, |y, other| {
            evaluate(y, other);
            Ok(())
        })?;
    }
    if model.torque_nmm == 0.0 && !in_contact(states.iter().map(|s| &s.force_n)) {
        lag = touching(
            |l| {
                evaluate(l, states);
                Ok::<_, SolveFailure>(states.iter().map(|s| (s.gap_mm, s.gap_slope_mm)).collect())
            },
            lag,
        )?;
        evaluate(lag, states);
    }
    if model.torque_nmm == 0.0 {
        let resolution = p.moment_resolution(states, offset.norm());
        unload_round_off(states, resolution);
    }
    Ok(lag)
}

fn net_force(sol: &AngleSolution) -> Vec2 {
    let r: Vec2 = sol.rollers.iter().map(|s| s.force_vector()).sum();
    let p: Vec2 = sol.pins.iter().map(|s| s.force_vector()).sum();
    r + p
}

/// Solve the rigid-bearing balances at one crank angle and a fixed centre offset, into
/// `work.sol`, warm-started from the work's history.
fn solve_rigid(
    model: &Model,
    crank: f64,
    work: &mut Work,
    offset: Vec2,
) -> Result<(), SolveFailure> {
    let (guess_lag, guess_out) = work.guess_at_torque(crank, model);
    work.sol.centre_offset_mm = offset;
    let mut psi = -crank / model.teeth as f64;
    let e_phi = work.e_phi;
    if let Some(r) = &model.rollers {
        let lag = solve_rollers(model, r, (crank, e_phi), offset, guess_lag, work)?;
        psi += lag;
        work.sol.lag_rad = Some(lag);
    }
    if let Some(p) = &model.pins {
        work.sol.output_lag_rad = Some(solve_pins(model, p, e_phi, offset, psi, guess_out, work)?);
    }
    Ok(())
}

/// Residual vector of the compliant problem and the per-row scales.
fn compliant_residual(model: &Model, kb: f64, sol: &AngleSolution) -> (Vector4<f64>, Vector4<f64>) {
    let f = net_force(sol);
    let u = sol.centre_offset_mm;
    let (mr, _, sr) = moment(&sol.rollers);
    let (mp, _, sp) = moment(&sol.pins);
    let force_scale: f64 = sol.rollers.iter().map(|s| s.force_n).sum::<f64>()
        + sol.pins.iter().map(|s| s.force_n).sum::<f64>()
        + kb * u.norm();
    let t = model.torque_nmm.abs();
    (
        Vector4::new(
            f.x - kb * u.x,
            f.y - kb * u.y,
            mr - model.torque_nmm,
            mp - model.torque_nmm,
        ),
        Vector4::new(force_scale, force_scale, t.max(sr), t.max(sp)).map(|s| s.max(1e-300)),
    )
}

/// Evaluate rollers and pins at x = (ux, uy, β, βo) (the finite-difference check of
/// `compliant_jacobian`).
#[cfg(test)]
fn evaluate_at(
    model: &Model,
    crank: f64,
    x: &Vector4<f64>,
    sol: &mut AngleSolution,
) -> Result<(), SolveFailure> {
    let (r, p) = (model.rollers.as_ref(), model.pins.as_ref());
    let (Some(r), Some(p)) = (r, p) else {
        return Err(SolveFailure::Evaluation(
            "a compliant bearing needs rollers and pins".into(),
        ));
    };
    sol.centre_offset_mm = Vec2::new(x[0], x[1]);
    sol.lag_rad = Some(x[2]);
    sol.output_lag_rad = Some(x[3]);
    let pose = Pose {
        crank_rad: crank,
        lag_rad: x[2],
        centre_offset_mm: sol.centre_offset_mm,
    };
    r.evaluate(&pose, &mut sol.rollers)
        .map_err(SolveFailure::Gap)?;
    p.evaluate(
        crank,
        sol.centre_offset_mm,
        -crank / model.teeth as f64 + x[2],
        x[3],
        &mut sol.pins,
    );
    Ok(())
}

/// Jacobian of `compliant_residual` (contact normals and arms held fixed over a step).
fn compliant_jacobian(kb: f64, sol: &AngleSolution) -> Matrix4<f64> {
    let mut j = Matrix4::zeros();
    j[(0, 0)] = -kb;
    j[(1, 1)] = -kb;
    for s in &sol.rollers {
        let (k, n, l) = (s.stiffness_n_per_mm, s.normal, s.arm_mm);
        // f = −F·n, F = F(−gap), ∂gap/∂u = −n, ∂gap/∂β = −l.
        for a in 0..2 {
            for b in 0..2 {
                j[(a, b)] -= k * n[a] * n[b];
            }
            j[(a, 2)] -= k * l * n[a];
            j[(2, a)] += k * l * n[a];
        }
        j[(2, 2)] += k * l * l;
    }
    for s in &sol.pins {
        let (k, d, a, g) = (s.stiffness_n_per_mm, s.direction, s.arm_mm, s.gap_slope_mm);
        // f = F·û, ∂gap/∂u = û, ∂gap/∂βo = g.
        for r in 0..2 {
            for c in 0..2 {
                j[(r, c)] -= k * d[r] * d[c];
            }
            j[(r, 3)] -= k * g * d[r];
            j[(3, r)] -= k * a * d[r];
        }
        j[(3, 3)] -= k * a * g;
    }
    j
}

/// Compliant bearing: the disc centre moves by u until the bearing's force on the disc, −kb·u,
/// balances the contacts' net force f(u): R(u) = f(u) − kb·u = 0, with β and βo balancing the
/// torque at every u (`solve_rigid` at the offset u: bracketed, robust 1-D solves).
///
/// Newton on u alone, with the Jacobian of R reduced from the full 4×4 one
/// (`compliant_jacobian`) by eliminating the lags λ = (β, βo), whose balances hold at every
/// iterate: ∂R/∂u = J_uu − J_uλ·J_λλ⁻¹·J_λu (a Schur complement). ∂R/∂u ≈ −(kb·I + K_eff)
/// with K_eff the contacts' stiffness left after the lags follow, so a step is never longer
/// than the force over the contacts' stiffness, however soft the bearing (1e3 N/mm under
/// contacts of 1e6 N/mm, where a fixed-point iteration converges by 1e-3 per step). Steps are
/// halved until the force residual shrinks (a contact opening or closing makes R kinked; a
/// step that pushes a roller out of its closest-point reach cannot be evaluated).
fn solve_compliant(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
) -> Result<AngleSolution, SolveFailure> {
    let start = if work.near(crank, model) {
        work.sol.centre_offset_mm
    } else {
        Vec2::zeros()
    };
    match centre_newton(model, kb, crank, work, start) {
        Ok(sol) => Ok(sol),
        Err(direct) => stiffness_continuation(model, kb, crank, work).map_err(|_| direct),
    }
}

/// The compliant solve by continuation in the bearing's stiffness: from 10⁴·kb (the disc
/// centre nearly fixed) down to kb by factors of 10, each stage started from the last. The
/// centre moves continuously with the stiffness, so every stage starts near its answer, where
/// the direct Newton from rest can meet kinks of the residual (contacts that open and close)
/// between rest and an answer half a millimetre away (a 1000 N/mm bearing at 10 N·m).
fn stiffness_continuation(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
) -> Result<AngleSolution, SolveFailure> {
    let mut u = Vec2::zeros();
    let mut sol = None;
    for stage in (0..=4).rev() {
        let s = centre_newton(model, kb * 10f64.powi(stage), crank, work, u)?;
        u = s.centre_offset_mm;
        sol = Some(s);
    }
    sol.ok_or(SolveFailure::NotConverged {
        x: 0.0,
        residual: f64::INFINITY,
    })
}

/// Newton on the centre offset from `start` (see `solve_compliant`).
fn centre_newton(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    start: Vec2,
) -> Result<AngleSolution, SolveFailure> {
    let mut u = start;
    let tol = compliant_tolerance(model);
    solve_rigid(model, crank, work, u)?;
    let mut best = work.sol.clone();
    let mut force = force_residual(model, kb, &best);
    let mut exact_jacobian = false;
    for _ in 0..MAX_CENTRE_STEPS {
        if force_merit(model, kb, &best) <= tol {
            return Ok(best);
        }
        let step = if exact_jacobian {
            centre_step_by_differences(model, kb, crank, work, u, &best)?
        } else {
            centre_step(kb, &best, force)
        };
        let mut length = 1.0;
        let before = force.norm();
        loop {
            let trial = u + step * length;
            let trial_force = (trial.iter().all(|x| x.is_finite())
                && solve_rigid(model, crank, work, trial).is_ok())
            .then(|| force_residual(model, kb, &work.sol));
            // Sufficient decrease of |f − kb·u|, for which the Newton direction is a descent
            // direction (a residual relative to Σ|F| + kb·|u| is not: its scale grows with u).
            if trial_force.is_some_and(|f| f.norm() < (1.0 - 1e-4 * length) * force.norm()) {
                (u, force) = (trial, trial_force.unwrap_or(force));
                best = work.sol.clone();
                if u.norm() > model.eccentricity_mm {
                    return Err(out_of_mesh(kb, u, force, model));
                }
                break;
            }
            length *= 0.5;
            if length < 1e-12 {
                // Newton cycles at a kink of R (a contact just closing at the answer, where the
                // stiffness in its direction jumps from ~kb to the contact's).
                work.sol = best.clone();
                return directional_roots(model, kb, crank, work, u, best);
            }
        }
        // A step shortened more than twice, or one that did not halve the residual: the
        // approximate Jacobian (contact normals and arms held fixed) misses the geometric
        // stiffness F·∂n/∂u, which matters when the bearing is as soft as F/ρ, and errs most
        // in the soft direction where the lags take up the motion; the next steps take the
        // reduced Jacobian by finite differences.
        exact_jacobian |= length < 0.25 || force.norm() > 0.5 * before;
    }
    work.sol = best.clone();
    let merit = force_merit(model, kb, &best);
    settled(best, merit)
}

/// Finish a compliant solve that Newton cannot: R is strongly monotone (its symmetric part of
/// ∂R/∂u is ≤ −kb: the bearing's own stiffness plus the contacts', which only resist), so along
/// any unit direction e the component e·R(u + s·e) decreases strictly in s, and its root is a
/// monotone 1-D problem that `monotone_root` brackets and solves whatever the kinks. Alternate
/// such roots along the principal directions of the reduced Jacobian (by differences), which
/// are nearly decoupled near the answer, until the force residual meets the tolerance.
fn directional_roots(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    mut u: Vec2,
    mut best: AngleSolution,
) -> Result<AngleSolution, SolveFailure> {
    let tol = compliant_tolerance(model);
    for _ in 0..MAX_DIRECTIONAL_ROUNDS {
        if force_merit(model, kb, &best) <= tol {
            return Ok(best);
        }
        let h = 1e-6 * u.norm().max(1e-3);
        let mut jacobian = nalgebra::Matrix2::zeros();
        for axis in 0..2 {
            let mut d = Vec2::zeros();
            d[axis] = h;
            let plus = centre_residual(model, kb, crank, work, u + d)?;
            let minus = centre_residual(model, kb, crank, work, u - d)?;
            jacobian.set_column(axis, &((plus - minus) / (2.0 * h)));
        }
        let symmetric = (jacobian + jacobian.transpose()) * 0.5;
        let directions = symmetric.symmetric_eigen().eigenvectors;
        for e in directions.column_iter() {
            let e = Vec2::new(e[0], e[1]);
            let slope = -(e.dot(&(jacobian * e))).min(-kb);
            let scale = force_scale(kb, &best);
            let root = monotone_root(
                |s: f64| {
                    centre_residual(model, kb, crank, work, u + e * s).map(|r| Balance {
                        value: -e.dot(&r),
                        slope,
                        scale,
                        resolution: 0.0,
                    })
                },
                0.0,
                0.0,
                &Settings {
                    rel_tol: 0.1 * tol,
                    initial_step: 1e-6,
                    max_range: model.eccentricity_mm,
                    ..model.settings
                },
            )?;
            u += e * root.x;
            solve_rigid(model, crank, work, u)?;
            best = work.sol.clone();
        }
    }
    work.sol = best.clone();
    let merit = force_merit(model, kb, &best);
    settled(best, merit)
}

/// Rounds of `directional_roots`.
const MAX_DIRECTIONAL_ROUNDS: usize = 20;

/// R(u) = f(u) − kb·u with the lags solved at the offset u.
fn centre_residual(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    u: Vec2,
) -> Result<Vec2, SolveFailure> {
    solve_rigid(model, crank, work, u)?;
    Ok(force_residual(model, kb, &work.sol))
}

/// The scale of the force residual: Σ|F| + kb·|u|.
fn force_scale(kb: f64, sol: &AngleSolution) -> f64 {
    sol.rollers.iter().map(|s| s.force_n).sum::<f64>()
        + sol.pins.iter().map(|s| s.force_n).sum::<f64>()
        + kb * sol.centre_offset_mm.norm()
}

/// The force residual f(u) − kb·u of a solution, N.
fn force_residual(model: &Model, kb: f64, sol: &AngleSolution) -> Vec2 {
    let (r, _) = compliant_residual(model, kb, sol);
    Vec2::new(r[0], r[1])
}

/// A bearing so soft under the load that the disc centre leaves the mesh: once it has moved by
/// more than the eccentricity (the scale of the whole mesh: the disc centre orbits the input
/// axis at e), the rollers no longer hold the disc in its tooth spaces.
fn out_of_mesh(kb: f64, u: Vec2, force: Vec2, model: &Model) -> SolveFailure {
    SolveFailure::OutOfMesh {
        bearing_n_per_mm: kb,
        torque_nmm: model.torque_nmm,
        offset_mm: u.norm(),
        unbalanced_n: force.norm(),
        eccentricity_mm: model.eccentricity_mm,
    }
}

/// The end of a compliant solve that ran out of steps: accepted within the documented 1e-9.
fn settled(sol: AngleSolution, merit: f64) -> Result<AngleSolution, SolveFailure> {
    if merit <= 1e-9 {
        Ok(sol)
    } else {
        Err(SolveFailure::NotConverged {
            x: sol.lag_rad.unwrap_or(0.0),
            residual: merit,
        })
    }
}

/// The force merit a compliant solve converges to: 10× the solver's relative tolerance
/// (1e-10), a decade inside the documented 1e-9 of the reported residual (Eqs. 12–14), whose
/// moment rows about the fixed origin weigh the same force misses by other lever arms.
fn compliant_tolerance(model: &Model) -> f64 {
    model.settings.rel_tol * 10.0
}

/// Newton steps of the centre a compliant solve may take.
const MAX_CENTRE_STEPS: usize = 100;

/// The largest relative residual of the compliant problem: the force rows relative to
/// Σ|F| + kb·|u|, the moment rows (held by the lags' own solves) relative to the torque.
fn force_merit(model: &Model, kb: f64, sol: &AngleSolution) -> f64 {
    let (r, s) = compliant_residual(model, kb, sol);
    r.component_div(&s).amax()
}

/// The Newton step of the centre offset with ∂R/∂u by central differences of R(u), the lags
/// re-solved at each offset: exact to the differences' error, geometric stiffness included.
/// The step h is 1e-6 of the larger of |u| and the gap resolution's scale (1e-3 mm): far above
/// the round-off of R, far below the distance over which the contact set changes.
fn centre_step_by_differences(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    u: Vec2,
    at: &AngleSolution,
) -> Result<Vec2, SolveFailure> {
    let residual = |work: &mut Work, x: Vec2| centre_residual(model, kb, crank, work, x);
    let h = 1e-6 * u.norm().max(1e-3);
    let mut jacobian = nalgebra::Matrix2::zeros();
    for axis in 0..2 {
        let mut d = Vec2::zeros();
        d[axis] = h;
        let column = (residual(work, u + d)? - residual(work, u - d)?) / (2.0 * h);
        jacobian.set_column(axis, &column);
    }
    work.sol = at.clone();
    let force = force_residual(model, kb, at);
    Ok(jacobian.lu().solve(&(-force)).unwrap_or_else(|| force / kb))
}

/// The Newton step of the centre offset: −(∂R/∂u)⁻¹·R with the lags eliminated from the 4×4
/// Jacobian (Schur complement; a lag whose balance has no slope, no contact on its side, is not
/// eliminated).
fn centre_step(kb: f64, sol: &AngleSolution, force: Vec2) -> Vec2 {
    let j = compliant_jacobian(kb, sol);
    let mut reduced = j.fixed_view::<2, 2>(0, 0).into_owned();
    for l in 2..4 {
        let pivot = j[(l, l)];
        if pivot != 0.0 {
            let (column, row) = (j.fixed_view::<2, 1>(0, l), j.fixed_view::<1, 2>(l, 0));
            reduced -= column * row / pivot;
        }
    }
    reduced.lu().solve(&(-force)).unwrap_or_else(|| force / kb)
}

/// Relative residual of the paper's Eqs. 12–14, evaluated independently of how the solution
/// was found: force balance (Eqs. 12–13), moment balance about the fixed origin with every
/// force at its contact point and the bearing force at the disc centre, and the pin/roller
/// moment equality about the disc centre (Eq. 14).
pub fn residual(model: &Model, crank: f64, sol: &AngleSolution, bearing: Vec2) -> f64 {
    let (sin, cos) = crank.sin_cos();
    residual_at(model, Vec2::new(cos, sin), sol, bearing)
}

/// `residual` with the eccentric direction e_φ = (cos φ, sin φ) given, in one pass over the
/// forces in contact.
pub(super) fn residual_at(model: &Model, e_phi: Vec2, sol: &AngleSolution, bearing: Vec2) -> f64 {
    let mut sums = BalanceSums::default();
    for r in sol.rollers.iter().filter(|r| r.force_n != 0.0) {
        sums.roller(r.point, r.force_n, r.force_vector(), r.force_n * r.arm_mm);
    }
    for p in sol.pins.iter().filter(|p| p.force_n != 0.0) {
        sums.pin(p.point, p.force_n, p.force_vector(), p.force_n * p.arm_mm);
    }
    sums.relative(
        model,
        e_phi * model.eccentricity_mm + sol.centre_offset_mm,
        bearing,
    )
}

/// Sums of the forces on the disc for the residual of Eqs. 12–14: Σf, Σ|f|, Σ p×f and Σ|p×f|
/// about the origin, and the moments Σ F·l (rollers) and Σ F·a (pins) about the disc centre
/// with their scales.
#[derive(Debug, Default)]
pub(super) struct BalanceSums {
    force: Vec2,
    force_scale: f64,
    moment: f64,
    moment_scale: f64,
    rollers: (f64, f64),
    pins: (f64, f64),
}

impl BalanceSums {
    /// A force f of magnitude |`magnitude`| at p (the forces are a magnitude times a unit
    /// direction, so |f| is known without a square root).
    fn add(&mut self, p: Vec2, magnitude: f64, f: Vec2) {
        let m = cross(p, f);
        self.force += f;
        self.force_scale += magnitude.abs();
        self.moment += m;
        self.moment_scale += m.abs();
    }

    /// A roller force f = F·(unit direction) at p, with moment F·l about the disc centre.
    pub(super) fn roller(&mut self, p: Vec2, force_n: f64, f: Vec2, moment: f64) {
        self.add(p, force_n, f);
        self.rollers.0 += moment;
        self.rollers.1 += moment.abs();
    }

    /// A pin force f = F·(unit direction) at p, with moment F·a about the disc centre.
    pub(super) fn pin(&mut self, p: Vec2, force_n: f64, f: Vec2, moment: f64) {
        self.add(p, force_n, f);
        self.pins.0 += moment;
        self.pins.1 += moment.abs();
    }

    /// Σf of the forces added so far.
    pub(super) fn net_force(&self) -> Vec2 {
        self.force
    }

    /// With the bearing force at the disc centre: the largest relative residual.
    pub(super) fn relative(mut self, model: &Model, centre: Vec2, bearing: Vec2) -> f64 {
        if bearing != Vec2::zeros() {
            self.add(centre, bearing.norm(), bearing);
        }
        let rel = |x: f64, scale: f64| {
            if scale > 0.0 {
                x.abs() / scale
            } else {
                x.abs()
            }
        };
        let ((mr, sr), (mp, sp)) = (self.rollers, self.pins);
        rel(self.force.norm(), self.force_scale)
            .max(rel(self.moment, self.moment_scale))
            .max(rel(mp - mr, sr.max(sp).max(model.torque_nmm.abs())))
    }
}

/// Solve one crank angle with the model's bearing, warm-started from `previous`.
pub fn solve_angle(
    model: &Model,
    crank: f64,
    previous: &AngleSolution,
) -> Result<AngleSolution, SolveFailure> {
    let mut work = Work {
        sol: previous.clone(),
        exact_final: true,
        ..Work::default()
    };
    if previous.lag_rad.is_some() || previous.output_lag_rad.is_some() {
        // One history entry at this very angle: the guess is the previous solution's lags.
        work.remember(crank, model.torque_nmm);
    }
    solve_into(model, crank, &mut work)?;
    Ok(work.sol)
}

/// Solve one crank angle into `work.sol`, then remember it for the next angle's guess.
pub fn solve_into(model: &Model, crank: f64, work: &mut Work) -> Result<(), SolveFailure> {
    work.forget_if_far(crank, model);
    let (sin, cos) = crank.sin_cos();
    work.e_phi = Vec2::new(cos, sin);
    match model.bearing_stiffness_n_per_mm {
        Some(kb) => work.sol = solve_compliant(model, kb, crank, work)?,
        None => solve_rigid(model, crank, work, Vec2::zeros())?,
    }
    if model.bearing {
        let fb = match model.bearing_stiffness_n_per_mm {
            Some(kb) => -kb * work.sol.centre_offset_mm,
            None => -net_force(&work.sol),
        };
        work.sol.bearing_force_n = Some(fb);
        work.sol.residual = Some(residual_at(model, work.e_phi, &work.sol, fb));
    }
    work.remember(crank, model.torque_nmm);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{compliant_jacobian, compliant_residual, evaluate_at, solve_angle};
    use super::{AngleSolution, Model};
    use crate::model::{Effect, Plan};
    use nalgebra::Vector4;
    use proptest::prelude::*;

    proptest! {
        /// The analytic 4×4 Jacobian of the compliant problem (rows: force x, y, roller moment,
        /// pin moment; columns: ux, uy, β, βo) against central differences of the residual, at
        /// lightly loaded states of the paper's design on bearings of 1e3–1e9 N/mm.
        ///
        /// The Jacobian holds contact normals and arms fixed over a step; what it leaves out is
        /// the geometric stiffness, each force times the turn of its normal and arm, bounded by
        /// ΣF·(κ + 1/e)·(1 + R)² for a unit change (κ the largest locus curvature, 1/e that of
        /// a pin's direction, R = Rp + e the lever), times R more on a moment row and on a lag
        /// column. At 1e-3 N·m the forces are ~0.05 N, so that bound is ~1e-4 of the contact
        /// stiffness terms it sits beside: a wrong sign or a missing term (~k·l, ~k·l²) cannot
        /// hide in it. The differences step 1e-10 mm (1e-10/R rad), inside every contact's
        /// approach or opening (states with a gap within 1e-8 mm of closing are drawn again),
        /// so no contact opens or closes; their round-off, 1e-14 mm of gap times 7e5 N/mm over
        /// 2e-10 mm, is ~40 N/mm, inside the 1e-4 relative part.
        #[test]
        fn compliant_jacobian_matches_finite_differences(
            stiffness_exp in 3.0f64..9.0,
            crank in 0.0f64..std::f64::consts::TAU,
            offset in (-1.0f64..1.0, -1.0f64..1.0),
        ) {
            let s = crate::spec::load("specs/paper.yaml").unwrap();
            let mut scene = s.scenes.iter().find(|c| c.name == "rated").unwrap().clone();
            scene.output_torque_nmm = 1.0;
            let kb = 10f64.powf(stiffness_exp);
            let plan = Plan::of("rated", &[Effect::Bearing]);
            // The lags of the rigid equilibrium (independent of the compliant solver, which
            // uses the Jacobian under test), at a centre offset of a few nanometres.
            let rigid = Model::new(&s.design, &s.modification, &scene, &plan);
            let sol = solve_angle(&rigid, crank, &AngleSolution::default()).unwrap();
            scene.bearing_stiffness_n_per_mm = Some(kb);
            let model = Model::new(&s.design, &s.modification, &scene, &plan);
            let (ux, uy) = (offset.0 * 1e-8, offset.1 * 1e-8);
            let x = Vector4::new(ux, uy, sol.lag_rad.unwrap(), sol.output_lag_rad.unwrap());
            let mut at = sol.clone();
            evaluate_at(&model, crank, &x, &mut at).unwrap();
            // A contact at its threshold within the differences' reach (a pin whose arm nearly
            // vanishes has a gap of ~1e-12 mm) makes the residual kinked there: the two sides
            // differ by its whole stiffness, and no derivative exists to compare.
            let gaps = at.rollers.iter().map(|r| r.gap_mm).chain(at.pins.iter().map(|p| p.gap_mm));
            prop_assume!(gaps.into_iter().all(|g| g.abs() > 1e-8));
            let analytic = compliant_jacobian(kb, &at);
            let d = &s.design;
            let lever = d.roller_circle_radius_mm + d.eccentricity_mm;
            let h = [1e-10, 1e-10, 1e-10 / lever, 1e-10 / lever];
            let residual = |x: Vector4<f64>| {
                let mut e = sol.clone();
                evaluate_at(&model, crank, &x, &mut e).unwrap();
                compliant_residual(&model, kb, &e).0
            };
            let forces: f64 = at.rollers.iter().map(|r| r.force_n).sum::<f64>()
                + at.pins.iter().map(|p| p.force_n).sum::<f64>();
            let profile = &model.rollers.as_ref().unwrap().mesh.profile;
            let kappa = (0..=200)
                .map(|k| profile.locus_curvature_at(-1.0 + 0.01 * k as f64).abs())
                .fold(0.0, f64::max);
            let geometric = forces * (kappa + 1.0 / d.eccentricity_mm) * (1.0 + lever).powi(2);
            let factor = [1.0, 1.0, 1.0 + lever, 1.0 + lever];
            for j in 0..4 {
                let mut step = Vector4::zeros();
                step[j] = h[j];
                let column = (residual(x + step) - residual(x - step)) / (2.0 * h[j]);
                for i in 0..4 {
                    let (a, b) = (analytic[(i, j)], column[i]);
                    let tol = 1e-4 * a.abs().max(b.abs()) + geometric * factor[i] * factor[j];
                    prop_assert!((a - b).abs() <= tol, "J[{i}][{j}]: analytic {a:e}, differences {b:e}, tol {tol:e}");
                }
            }
        }
    }
}
