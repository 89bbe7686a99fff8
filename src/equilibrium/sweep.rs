//! The loaded solve at every crank angle of a scene, and the curves it produces.
//!
//! Rigid bearing: the disc centre sits at e·(cos φ, sin φ); moment balance about it decouples
//! into the roller balance Σ F_i·l_i(β) = T and the pin balance Σ F_j·a_j(βo) = T, each a
//! monotone 1-D root (`solve`). The bearing force is then −(Σ roller forces + Σ pin forces).
//! Compliant bearing (stiffness kb): the disc centre moves by u and all of x = (ux, uy, β, βo)
//! are solved together by Newton with an analytic Jacobian (nalgebra), with a bracketed
//! fixed-point fallback.

use super::pins::{self, PinState, Pins};
use super::rollers::{self, AngleTrig, Reach, RollerState, Rollers};
use super::solve::{
    monotone_root, piecewise_linear_root_near, settle_straddle, Balance, Settings, SolveFailure,
};
use crate::geometry::clearance::Pose;
use crate::geometry::{cross, Vec2};
use crate::model::{ContactLaw, Design, Effect, GeometryMode, Modification, Plan, Scene};
use crate::units;
use nalgebra::{Matrix2, Matrix4, Vector4};

/// What the loaded model of a scene includes.
#[derive(Debug, Clone)]
pub struct Model {
    pub rollers: Option<Rollers>,
    pub pins: Option<Pins>,
    pub bearing: bool,
    pub bearing_stiffness_n_per_mm: Option<f64>,
    pub torque_nmm: f64,
    pub teeth: usize,
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
            eccentricity_mm: design.eccentricity_mm,
            settings: Settings::default(),
            first_order: scene.geometry == GeometryMode::FirstOrder,
        }
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
    /// The last (up to three) solved angles (φ, β, βo), oldest first, in the last `filled`
    /// entries.
    history: [(f64, f64, f64); 3],
    filled: usize,
    terms: Vec<(f64, f64)>,
    events: Vec<(f64, f64, f64)>,
}

impl Work {
    /// Guesses for (β, βo) at `crank`: quadratic (Lagrange) extrapolation of the last three
    /// angles, linear from two, the last value from one.
    pub(super) fn guess(&self, crank: f64) -> (f64, f64) {
        match &self.history[3 - self.filled..] {
            [(p0, b0, o0), (p1, b1, o1), (p2, b2, o2)] if p0 != p1 && p1 != p2 && p0 != p2 => {
                let l0 = (crank - p1) * (crank - p2) / ((p0 - p1) * (p0 - p2));
                let l1 = (crank - p0) * (crank - p2) / ((p1 - p0) * (p1 - p2));
                let l2 = (crank - p0) * (crank - p1) / ((p2 - p0) * (p2 - p1));
                (l0 * b0 + l1 * b1 + l2 * b2, l0 * o0 + l1 * o1 + l2 * o2)
            }
            [.., (p0, b0, o0), (p1, b1, o1)] if p1 != p0 => {
                let w = (crank - p1) / (p1 - p0);
                (b1 + w * (b1 - b0), o1 + w * (o1 - o0))
            }
            [.., (_, b, o)] => (*b, *o),
            [] => (0.0, 0.0),
        }
    }

    fn remember(&mut self, crank: f64) {
        let lag = self.sol.lag_rad.unwrap_or(0.0);
        self.remember_lags(crank, lag, self.sol.output_lag_rad.unwrap_or(0.0));
    }

    /// Remember the lags (β, βo) solved at `crank` for the next angle's guess.
    pub(super) fn remember_lags(&mut self, crank: f64, lag: f64, output_lag: f64) {
        self.history = [self.history[1], self.history[2], (crank, lag, output_lag)];
        self.filled = (self.filled + 1).min(3);
    }
}

fn roller_balance(
    r: &Rollers,
    pose: &Pose,
    states: &mut Vec<RollerState>,
) -> Result<Balance, String> {
    r.evaluate(pose, states).map_err(|f| f.to_string())?;
    let (value, slope, scale) = rollers::moment(states);
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
    let deepest = match r.evaluate(pose, &mut states) {
        Ok(()) => states
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.gap_mm.total_cmp(&b.1.gap_mm))
            .map(|(i, s)| {
                format!(
                    "; there roller {i} is pressed {:.3} mm into the disc (roller radius {} mm)",
                    -s.gap_mm, r.mesh.roller_radius_mm
                )
            })
            .unwrap_or_default(),
        Err(_) => String::new(),
    };
    SolveFailure::Evaluation(format!(
        "the rollers cannot balance an output torque of {} N·m: the largest moment found is \
         {:.4} N·m, at a lag of {:.4} rad{deepest}; the load is beyond what this disc can hold \
         in the contact model",
        crate::numeric::input(units::nm(torque_nmm)),
        units::nm(moment_nmm),
        pose.lag_rad
    ))
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
    let closed_form = r.geometry == GeometryMode::FirstOrder
        && r.law == ContactLaw::PaperLinear
        && offset == Vec2::zeros();
    if closed_form {
        r.first_order_terms(e_phi, &mut work.terms);
        let (k, t) = (r.linear_stiffness(), model.torque_nmm);
        let lag = piecewise_linear_root_near(k, &work.terms, t, guess, &mut work.events).ok_or(
            SolveFailure::NoBracket {
                lo: f64::NEG_INFINITY,
                hi: f64::INFINITY,
                nearest: None,
            },
        )?;
        let states = &mut work.sol.rollers;
        let terms = &work.terms;
        let evaluate = |lag: f64, states: &mut Vec<RollerState>| {
            r.first_order_states(&pose(lag), e_phi, terms, states);
            rollers::moment(states)
        };
        let (m, _, scale) = evaluate(lag, states);
        if t == 0.0 {
            // The closed form's answer is the touching pose (T → 0⁺, or a preload's balance).
            // The touching contact's gap g − l·x is round-off (±1e-17 mm), and so is its force
            // (~5e-12 N, whose unbalanced moment made the residual 1): zero, as in the
            // iterative solve.
            if scale <= r.moment_resolution(states, 0.0) {
                for s in states.iter_mut() {
                    (s.force_n, s.stiffness_n_per_mm) = (0.0, 0.0);
                }
            }
            return Ok(lag);
        }
        if (m - t).abs() <= model.settings.rel_tol * t.abs().max(scale) {
            return Ok(lag);
        }
        // The root is exact, but the gaps at the double nearest to it, g − l·x, carry the
        // round-off of l·x: at a tiny torque (1e-6 N·m) that is more than the tolerance.
        // Mix the states of two neighbouring lags as the iterative solve does.
        let mut other = states.clone();
        let (at, weight) = settle_straddle(lag, lag, m, t, |y| Ok(evaluate(y, &mut other).0))?;
        rollers::blend(states, &other, 1.0 - weight);
        return Ok(if weight > 0.5 { at } else { lag });
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
            r.evaluate_at(&pose(lag), &trig, states, reaches)
                .map_err(|f| f.to_string())?;
            let (value, slope, scale) = rollers::moment(states);
            Ok::<_, String>(Balance {
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
    let mut lag = root.x;
    if let Some(towards) = root.straddle {
        // The balance steps over the torque between two adjacent lags (round-off of the
        // gaps): every roller exact at both ends, forces mixed so that Σ F·l = T.
        let exact = |lag: f64, states: &mut Vec<RollerState>| {
            r.evaluate_at(&pose(lag), &trig, states, &mut [])
                .map_err(|f| SolveFailure::Evaluation(f.to_string()))
        };
        exact(lag, states)?;
        let mut other = states.clone();
        let (at, weight) = settle_straddle(
            lag,
            towards,
            rollers::moment(states).0,
            model.torque_nmm,
            |y| {
                exact(y, &mut other)?;
                Ok(rollers::moment(&other).0)
            },
        )?;
        rollers::blend(states, &other, 1.0 - weight);
        if weight > 0.5 {
            lag = at;
        }
    } else if exact_final {
        // Every roller exact at the answer (skipped ones carried only a gap bound).
        r.evaluate_at(&pose(lag), &trig, states, &mut [])
            .map_err(|f| SolveFailure::Evaluation(f.to_string()))?;
    }
    if model.torque_nmm == 0.0 {
        if !in_contact(states.iter().map(|s| &s.force_n)) {
            lag = touching(
                |l| {
                    roller_balance(r, &pose(l), states)
                        .map(|_| states.iter().map(|s| (s.gap_mm, -s.arm_mm)).collect())
                },
                lag,
            )
            .map_err(SolveFailure::Evaluation)?;
            roller_balance(r, &pose(lag), states).map_err(SolveFailure::Evaluation)?;
            reaches
                .iter_mut()
                .for_each(|x| x.gap_mm = f64::NEG_INFINITY);
        }
        // Forces whose moments are round-off (an unmodified profile touches every roller at
        // zero torque, with gaps of ±1e-17 mm) are zero: the limit T → 0⁺ of no load.
        let (_, _, scale) = rollers::moment(states);
        if scale <= r.moment_resolution(states, offset_norm) {
            for s in states.iter_mut() {
                (s.force_n, s.stiffness_n_per_mm) = (0.0, 0.0);
            }
        }
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
    if first_order {
        if let (Some(k), true) = (p.linear_stiffness(), offset == Vec2::zeros()) {
            let centre = e_phi * model.eccentricity_mm;
            p.first_order_at(e_phi, psi.sin_cos(), centre, 0.0, &mut work.sol.pins);
            work.terms.clear();
            work.terms
                .extend(work.sol.pins.iter().map(|s| (s.gap_mm, s.arm_mm)));
            let lag = piecewise_linear_root_near(
                k,
                &work.terms,
                model.torque_nmm,
                guess,
                &mut work.events,
            )
            .ok_or(SolveFailure::NoBracket {
                lo: f64::NEG_INFINITY,
                hi: f64::INFINITY,
                nearest: None,
            })?;
            let states = &mut work.sol.pins;
            p.first_order_lagged(lag, states);
            let (m, _, scale) = pins::moment(states);
            let t = model.torque_nmm;
            if t == 0.0 || (m - t).abs() <= model.settings.rel_tol * t.abs().max(scale) {
                return Ok(lag);
            }
            // Round-off of the gaps at the root's double, as for the rollers. The gaps are
            // linear in the lag: those at y are the ones at the root moved by y − lag.
            let mut other = states.clone();
            let (at, weight) = settle_straddle(lag, lag, m, t, |y| {
                other.copy_from_slice(states);
                p.first_order_lagged(y - lag, &mut other);
                Ok(pins::moment(&other).0)
            })?;
            pins::blend(states, &other, 1.0 - weight);
            return Ok(if weight > 0.5 { at } else { lag });
        }
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
        let (value, slope, scale) = pins::moment(states);
        Balance {
            value,
            slope,
            scale,
            resolution: p.moment_resolution(states, offset.norm()),
        }
    };
    let root = monotone_root(
        |lag| Ok::<_, String>(evaluate(lag, states)),
        model.torque_nmm,
        guess,
        &model.settings,
    )?;
    // `states` holds the evaluation at root.x: the solver's last evaluation is at its answer.
    let mut lag = root.x;
    if let Some(towards) = root.straddle {
        // As for the rollers: forces mixed between two neighbouring output lags.
        let mut other = states.clone();
        let (at, weight) = settle_straddle(
            lag,
            towards,
            pins::moment(states).0,
            model.torque_nmm,
            |y| {
                evaluate(y, &mut other);
                Ok(pins::moment(&other).0)
            },
        )?;
        pins::blend(states, &other, 1.0 - weight);
        if weight > 0.5 {
            lag = at;
        }
    }
    if model.torque_nmm == 0.0 && !in_contact(states.iter().map(|s| &s.force_n)) {
        lag = touching(
            |l| {
                evaluate(l, states);
                Ok::<_, String>(states.iter().map(|s| (s.gap_mm, s.gap_slope_mm)).collect())
            },
            lag,
        )
        .map_err(SolveFailure::Evaluation)?;
        evaluate(lag, states);
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
    let (guess_lag, guess_out) = work.guess(crank);
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
    let (mr, _, sr) = rollers::moment(&sol.rollers);
    let (mp, _, sp) = pins::moment(&sol.pins);
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

/// Evaluate rollers and pins at x = (ux, uy, β, βo).
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
        .map_err(|f| SolveFailure::Evaluation(f.to_string()))?;
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

fn merit(r: &Vector4<f64>, s: &Vector4<f64>) -> f64 {
    r.component_div(s).amax()
}

/// Compliant bearing: Newton on x = (ux, uy, β, βo) from the rigid solution, with backtracking.
fn solve_compliant(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
) -> Result<AngleSolution, SolveFailure> {
    solve_rigid(model, crank, work, Vec2::zeros())?;
    let rigid = work.sol.clone();
    let u0 = net_force(&rigid) / kb;
    let mut x = Vector4::new(
        u0.x,
        u0.y,
        rigid.lag_rad.unwrap_or(0.0),
        rigid.output_lag_rad.unwrap_or(0.0),
    );
    let mut sol = rigid.clone();
    if evaluate_at(model, crank, &x, &mut sol).is_err() {
        // The first centre estimate already pushes a roller out of its closest-point reach:
        // the fallback approaches it from the rigid pose.
        work.sol = rigid;
        return fixed_point(model, kb, crank, work);
    }
    let (mut r, mut s) = compliant_residual(model, kb, &sol);
    let tol = model.settings.rel_tol * 100.0;
    'newton: for _ in 0..60 {
        if merit(&r, &s) <= tol {
            return Ok(sol);
        }
        let Some(dx) = compliant_jacobian(kb, &sol).lu().solve(&(-r)) else {
            break;
        };
        let mut step = 1.0;
        let current = merit(&r, &s);
        loop {
            let trial_x = x + dx * step;
            let mut trial = sol.clone();
            // A step that cannot be evaluated (a nearly singular Jacobian, e.g. pins without
            // load at zero torque, sends a roller out of its reach) is too long: shorten it.
            let evaluated = dx.iter().all(|d| d.is_finite())
                && evaluate_at(model, crank, &trial_x, &mut trial).is_ok();
            if !evaluated {
                if step < 1e-6 {
                    break 'newton;
                }
                step *= 0.5;
                continue;
            }
            let (tr, ts) = compliant_residual(model, kb, &trial);
            if merit(&tr, &ts) < current || step < 1e-6 {
                (x, sol, r, s) = (trial_x, trial, tr, ts);
                break;
            }
            step *= 0.5;
        }
    }
    work.sol = sol;
    fixed_point(model, kb, crank, work)
}

/// Fallback: alternate bracketed 1-D solves for β and βo at a fixed centre with a damped
/// update of the centre from the bearing balance u = Σf/kb.
fn fixed_point(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
) -> Result<AngleSolution, SolveFailure> {
    let mut residual = f64::INFINITY;
    let mut offset = work.sol.centre_offset_mm;
    for _ in 0..500 {
        solve_rigid(model, crank, work, offset)?;
        let target = net_force(&work.sol) / kb;
        let (r, s) = compliant_residual(model, kb, &work.sol);
        residual = merit(&r, &s);
        if residual <= 1e-10 {
            return Ok(work.sol.clone());
        }
        // Newton on the centre alone, β and βo re-solved at each centre: the force residual
        // f(u) − kb·u has the Jacobian −(kb·I + K), K = Σ k·n·nᵀ of the contacts. A fixed
        // damping (u += ½(f/kb − u)) diverges once the contacts are stiffer than the bearing
        // (a preloaded disc on a soft bearing: K ≈ 7·kb).
        let mut stiffness = Matrix2::identity() * kb;
        let directions = work
            .sol
            .rollers
            .iter()
            .map(|s| (s.stiffness_n_per_mm, s.normal))
            .chain(
                work.sol
                    .pins
                    .iter()
                    .map(|p| (p.stiffness_n_per_mm, p.direction)),
            );
        for (k, n) in directions {
            stiffness += k * n * n.transpose();
        }
        let force = kb * (target - offset);
        offset += stiffness
            .lu()
            .solve(&force)
            .unwrap_or(0.5 * (target - offset));
    }
    Err(SolveFailure::NotConverged {
        x: work.sol.lag_rad.unwrap_or(0.0),
        residual,
    })
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
        work.remember(crank);
    }
    solve_into(model, crank, &mut work)?;
    Ok(work.sol)
}

/// Solve one crank angle into `work.sol`, then remember it for the next angle's guess.
pub fn solve_into(model: &Model, crank: f64, work: &mut Work) -> Result<(), SolveFailure> {
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
    work.remember(crank);
    Ok(())
}
