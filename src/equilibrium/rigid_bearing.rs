//! The balances at one crank angle with the disc centre held: at e·(cos φ, sin φ) for a rigid
//! bearing, or at a given offset from it (each iterate of the compliant bearing's solve).
//!
//! Moment balance about the disc centre decouples into the roller balance Σ F_i·l_i(β) = T and
//! the pin balance Σ F_j·a_j(βo) = T, each a monotone 1-D root (`solve`). The bearing force is
//! then −(Σ roller forces + Σ pin forces).

use super::balance::{
    closed_form, moment, moment_by, round_off, settle, unload_round_off, Contact,
};
use super::coupling::Coupling;
use super::loaded::{AngleSolution, Model};
use super::pins::{PinState, Pins};
use super::rollers::{AngleTrig, Reach, RollerState, Rollers};
use super::solve::{monotone_root, Balance, Root, SolveFailure};
use super::work::Work;
use crate::geometry::clearance::{GapFailure, Pose};
use crate::geometry::{z_cross, Vec2};
use crate::model::{ContactLaw, GeometryMode};

/// Zero torque with clearance leaves the disc free within its backlash; we report the limit
/// T → 0⁺: the lag at which the nearest contact in the load direction just closes.
/// Newton on the smallest gap, x ← x + min(gap/(−∂gap/∂x)) over contacts that close as x grows,
/// the contacts `states` evaluated at each x by `evaluate`; they hold the evaluation at the
/// lag returned. `gap` is a contact's gap to its first touch: along a tilted or crowned face
/// the 2-D gap less what the face closes beyond it (`Rollers::touch_gap_mm`), else the gap.
fn touching<C: Contact, S>(
    states: &mut Vec<C>,
    mut evaluate: impl FnMut(f64, &mut Vec<C>) -> Result<(), S>,
    gap: impl Fn(&C) -> f64,
    start: f64,
) -> Result<f64, S> {
    let mut x = start;
    for _ in 0..50 {
        evaluate(x, states)?;
        let step = states
            .iter()
            .filter(|s| s.gap_slope_mm() < 0.0)
            .map(|s| gap(s) / -s.gap_slope_mm())
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
        evaluate(x, states)?;
        let overlap = states
            .iter()
            .filter(|s| s.gap_slope_mm() < 0.0 && gap(s) < 0.0)
            .map(|s| gap(s) / s.gap_slope_mm())
            .fold(0.0, f64::max);
        if overlap == 0.0 {
            return Ok(x);
        }
        x -= overlap + f64::EPSILON * x.abs();
    }
    evaluate(x, states)?;
    Ok(x)
}

fn in_contact<C: Contact>(states: &[C]) -> bool {
    states.iter().any(|s| s.force_n() > 0.0)
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
    let pose = |lag| Pose::new(crank, lag, offset);
    // The closed form needs a constant stiffness: not along a crowned or tilted face.
    let linear = r.geometry == GeometryMode::FirstOrder
        && r.law == ContactLaw::PaperLinear
        && r.face().is_none()
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
    let trig = AngleTrig::new(crank, model.teeth);
    let root = rollers_root(
        model,
        r,
        (&trig, offset),
        (model.torque_nmm, guess),
        work,
        moment,
    )
    .map_err(|failure| match failure {
        // Not one lag tried moved the rollers' moment towards the torque: nothing touches on
        // that side, which is no overload.
        SolveFailure::NoBracket {
            nearest: Some((_, value)),
            ..
        } if value == 0.0 && model.torque_nmm != 0.0 => SolveFailure::NoContact {
            torque_nmm: model.torque_nmm,
            range_rad: model.settings.max_range,
        },
        SolveFailure::NoBracket {
            nearest: Some((x, value)),
            ..
        } => beyond_reach(r, &pose(x), value, model.torque_nmm),
        other => other,
    })?;
    let (states, reaches) = (&mut work.sol.rollers, &mut work.reaches);
    let offset_norm = offset.norm();
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
    } else if work.exact_final {
        // Every roller exact at the answer (skipped ones carried only a gap bound).
        r.evaluate_at(&pose(lag), &trig, states, &mut [])?;
    }
    if model.torque_nmm == 0.0 {
        // Free in the backlash: no contact carries force, or none more than round-off. The
        // root search meets a zero torque wherever the moment is round-off, and from a lag
        // beyond the backlash's far side (a warm start at a share against the torque) that is
        // the far side's edge, where a roller's force of round-off still counts as a contact:
        // the limit T → 0⁺ is the near contact in the load direction all the same.
        let free = round_off(states, r.moment_resolution(states, offset_norm));
        if free || !in_contact(states) {
            let evaluate = |l, states: &mut Vec<RollerState>| r.evaluate(&pose(l), states);
            lag = touching(states, evaluate, |s| r.touch_gap_mm(s), lag)?;
            reaches
                .iter_mut()
                .for_each(|x| x.gap_mm = f64::NEG_INFINITY);
        }
        let resolution = r.moment_resolution(states, offset_norm);
        unload_round_off(states, resolution);
    }
    Ok(lag)
}

/// The pins' states at output lag `lag` for the disc at crank direction `e_phi`, turned by
/// `rotation` (sin, cos), its centre moved by `offset` from e·e_φ: first order where the model's
/// geometry asks for it.
fn pins_at(
    model: &Model,
    p: &Pins,
    (e_phi, rotation, offset): (Vec2, (f64, f64), Vec2),
    lag: f64,
    states: &mut Vec<PinState>,
) {
    if model.first_order {
        let centre = e_phi * model.eccentricity_mm + offset;
        p.first_order_at(e_phi, rotation, centre, lag, states);
    } else {
        p.evaluate_at(e_phi, rotation, offset, lag, states);
    }
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
    let first_order = model.first_order;
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
    let root = pins_root(model, p, (e_phi, offset, psi), guess, work, |s| s.arm_mm)?;
    let states = &mut work.sol.pins;
    let rotation = psi.sin_cos();
    let evaluate = |lag: f64, states: &mut Vec<PinState>| {
        pins_at(model, p, (e_phi, rotation, offset), lag, states);
        Ok::<_, SolveFailure>(())
    };
    // `states` holds the evaluation at root.x: the solver's last evaluation is at its answer.
    let mut lag = root.x;
    if let Some(towards) = root.straddle {
        // As for the rollers: forces mixed between two neighbouring output lags.
        lag = settle(lag, towards, model.torque_nmm, states, evaluate)?;
    }
    if model.torque_nmm == 0.0 {
        if !in_contact(states) {
            lag = touching(states, evaluate, |s: &PinState| s.gap_mm, lag)?;
        }
        let resolution = p.moment_resolution(states, offset.norm());
        unload_round_off(states, resolution);
    }
    Ok(lag)
}

pub(super) fn net_force(sol: &AngleSolution) -> Vec2 {
    let r: Vec2 = sol.rollers.iter().map(|s| s.force_vector()).sum();
    let p: Vec2 = sol.pins.iter().map(|s| s.force_vector()).sum();
    r + p
}

/// Solve the rigid-bearing balances at one crank angle and a fixed centre offset, into
/// `work.sol`, warm-started from the work's history.
pub(super) fn solve_rigid(
    model: &Model,
    crank: f64,
    work: &mut Work,
    offset: Vec2,
) -> Result<(), SolveFailure> {
    if let Some(c) = model.coupled() {
        return solve_rigid_coupled(model, c, crank, work, offset);
    }
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

// The coupled friction model (`coupling`): the same balances with every contact's
// friction inside them. Roller and pin friction are linear in their normal forces (kinematic
// sliding directions: adjusted arms l̃, ã); the bearing's friction moment c_b·|Fb| couples the
// rollers to the pins' total force, which depends on the rollers only through the disc's
// rotation ψ = −φ/nc + β (a change of β of 1e-4 rad moves it by ~1e-4 of itself). So: the pins
// at the guessed ψ, the rollers with those pins' totals, the pins again at the solved ψ, until
// the pins' totals move the rollers' balance by no more than its tolerance (a fixed point that
// contracts like μ·∂P/∂β, 2–3 passes; `COUPLED_PASSES` at most, then "did not converge").

/// The most passes of the coupled rollers–pins iteration at one angle before it reports that
/// it did not converge (each pass contracts the error by ~μ·1e-4; 3 passes are the rule).
const COUPLED_PASSES: usize = 30;

/// The pins' totals that the rollers' coupled balance needs: Σ of their forces on the disc
/// (friction included), N, and the pins' friction moment moved from the axis to the disc centre,
/// c_p·(Σ F_j)·(O_d × τ), N·mm.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct PinTotals {
    force: Vec2,
    shift: f64,
}

impl PinTotals {
    fn of(c: &Coupling, e_phi: Vec2, centre: Vec2, pins: &[PinState]) -> Self {
        PinTotals {
            force: c.pin_total(e_phi, centre, pins),
            shift: c.pin_shift(e_phi, centre, pins),
        }
    }
}

/// The rollers' coupled balance at their states: (Σ F·l̃ − c_b·|Fb|, its slope ∂/∂β with the
/// geometry held, its scale), with Fb = −(Σ roller forces + the pins' total).
fn coupled_roller_moment(
    c: &Coupling,
    crank: f64,
    centre: Vec2,
    states: &[RollerState],
    pins: &PinTotals,
) -> (f64, f64, f64) {
    let (mut m, mut dm, mut scale) = (0.0, 0.0, 0.0);
    let (mut force, mut dforce) = (Vec2::zeros(), Vec2::zeros());
    for s in states
        .iter()
        .filter(|s| s.force_n != 0.0 || s.stiffness_n_per_mm != 0.0)
    {
        let arm = c.roller_arm(crank, centre, s);
        m += s.force_n * arm;
        // ∂F/∂β = k·l (∂gap/∂β = −l).
        let df = s.stiffness_n_per_mm * s.arm_mm;
        dm += df * arm;
        scale += (s.force_n * arm).abs();
        let t = z_cross(s.normal);
        let unit = -s.normal - t * (c.roller * c.roller_sign(crank, centre, s));
        force += unit * s.force_n;
        dforce += unit * df;
    }
    let fb = -(force + pins.force);
    let norm = fb.norm();
    let moment = c.bearing_moment(norm);
    if norm > 0.0 {
        // M_b is linear in |Fb|, and ∂|Fb|/∂β = Fb·∂Fb/∂β/|Fb|.
        dm -= c.bearing_moment(fb.dot(&-dforce)) / norm;
    }
    (m - moment, dm, scale + moment.abs())
}

/// The rollers' coupled balance: β with Σ F·l̃ − c_b·|Fb| = T + the pins' shift.
#[allow(clippy::too_many_arguments)]
fn solve_rollers_coupled(
    model: &Model,
    c: &Coupling,
    r: &Rollers,
    (crank, e_phi): (f64, Vec2),
    offset: Vec2,
    guess: f64,
    pins: &PinTotals,
    work: &mut Work,
) -> Result<f64, SolveFailure> {
    let pose = |lag| Pose::new(crank, lag, offset);
    let centre = e_phi * model.eccentricity_mm + offset;
    let target = model.torque_nmm + pins.shift;
    let balance = |states: &[RollerState]| coupled_roller_moment(c, crank, centre, states, pins);
    let trig = AngleTrig::new(crank, model.teeth);
    let root = rollers_root(model, r, (&trig, offset), (target, guess), work, balance).map_err(
        |failure| match failure {
            SolveFailure::NoBracket {
                nearest: Some((x, value)),
                ..
            } if value != 0.0 => {
                let at = (crank, centre, &pose(x));
                // Said in the scene's output torque: the balance's moment less the pins' shift.
                let moment = value - pins.shift;
                self_locking(c, r, at, pins, model.torque_nmm)
                    .unwrap_or_else(|| beyond_reach(r, &pose(x), moment, model.torque_nmm))
            }
            other => other,
        },
    )?;
    // A straddled root (round-off of the gaps) is taken at its end: its balance is within the
    // round-off of the gaps, which the tolerance of the pins' pass below accepts.
    if root.straddle.is_some() || work.exact_final {
        r.evaluate_at(&pose(root.x), &trig, &mut work.sol.rollers, &mut [])?;
    }
    Ok(root.x)
}

/// Whether friction is what kept the coupled rollers' balance from the output torque
/// `torque_nmm` at the pose `pose` (crank angle, disc centre) where the search came nearest:
/// self-locking when the friction moment against the turn, M_f = Σ F·l − (Σ F·l̃ − c_b·|Fb| −
/// the pins' shift) (so that Σ F·l − M_f = T balances), takes all of the normal forces' moment
/// Σ F·l in the torque's direction, or when Σ F·l alone passed the torque there (without
/// friction a smaller lag balances it). None otherwise (an overload of the contacts).
fn self_locking(
    c: &Coupling,
    r: &Rollers,
    (crank, centre, pose): (f64, Vec2, &Pose),
    pins: &PinTotals,
    torque_nmm: f64,
) -> Option<SolveFailure> {
    let mut states = Vec::new();
    r.evaluate(pose, &mut states).ok()?;
    let normal = moment(&states).0;
    let net = coupled_roller_moment(c, crank, centre, &states, pins).0 - pins.shift;
    let friction = normal - net;
    let s = torque_nmm.signum();
    (s * net <= 0.0 || s * normal >= s * torque_nmm).then_some(SolveFailure::SelfLocking {
        torque_nmm,
        friction_moment_nmm: friction,
        normal_moment_nmm: normal,
        lag_rad: pose.lag_rad,
    })
}

/// The root β of the rollers' balance `balance` = `target` at the crank angle of `trig` and the
/// centre offset `offset` (the search of both the frictionless balance Σ F·l and the coupled
/// one Σ F·l̃ − c_b·|Fb|), the rollers' states left at the root and its slope kept in
/// `work.slopes.0`. The caller computes the angle's trigonometry once, for its exact
/// re-evaluations too.
fn rollers_root(
    model: &Model,
    r: &Rollers,
    (trig, offset): (&AngleTrig, Vec2),
    (target, guess): (f64, f64),
    work: &mut Work,
    balance: impl Fn(&[RollerState]) -> (f64, f64, f64),
) -> Result<Root, SolveFailure> {
    let pose = |lag| Pose::new(trig.crank_rad, lag, offset);
    Reach::size(&mut work.reaches, r.count(), pose(guess));
    let (states, reaches) = (&mut work.sol.rollers, &mut work.reaches);
    let offset_norm = offset.norm();
    let root = monotone_root(
        |lag| {
            r.evaluate_at(&pose(lag), trig, states, reaches)?;
            let (value, slope, scale) = balance(states);
            Ok::<_, GapFailure>(Balance {
                value,
                slope,
                scale,
                resolution: r.moment_resolution(states, offset_norm),
            })
        },
        target,
        guess,
        &model.settings,
    )?;
    work.slopes.0 = root.slope;
    Ok(root)
}

/// The root βo of the pins' balance Σ F_j·arm_j = T at the disc rotation ψ (the search of
/// both the frictionless balance, arm = a_j, and the coupled one, arm = ã_j), the pins' states
/// left at the root and its slope kept in `work.slopes.1`.
fn pins_root(
    model: &Model,
    p: &Pins,
    (e_phi, offset, psi): (Vec2, Vec2, f64),
    guess: f64,
    work: &mut Work,
    arm: impl Fn(&PinState) -> f64,
) -> Result<Root, SolveFailure> {
    let states = &mut work.sol.pins;
    // The angle's trigonometry, once for every evaluation of the pin balance.
    let rotation = psi.sin_cos();
    let root = monotone_root(
        |lag| {
            pins_at(model, p, (e_phi, rotation, offset), lag, states);
            let (value, slope, scale) = moment_by(states, &arm);
            Ok::<_, SolveFailure>(Balance {
                value,
                slope,
                scale,
                resolution: p.moment_resolution(states, offset.norm()),
            })
        },
        model.torque_nmm,
        guess,
        &model.settings,
    )?;
    work.slopes.1 = root.slope;
    Ok(root)
}

/// `solve_rigid` with the coupled friction `c` (a torque that is not zero; at zero torque
/// nothing slides under load but a preload, which the frictionless balance answers).
fn solve_rigid_coupled(
    model: &Model,
    c: &Coupling,
    crank: f64,
    work: &mut Work,
    offset: Vec2,
) -> Result<(), SolveFailure> {
    let (mut lag, mut out) = work.guess_at_torque(crank, model);
    work.sol.centre_offset_mm = offset;
    let ideal = -crank / model.teeth as f64;
    let e_phi = work.e_phi;
    let centre = e_phi * model.eccentricity_mm + offset;
    let psi = |lag: f64| ideal + if model.rollers.is_some() { lag } else { 0.0 };
    // The pins' coupled balance at the rollers' lag: βo with Σ F_j·ã_j = T (the flange's
    // torque, friction included), from the guess `out`.
    let solve_pins = |p: &Pins, lag: f64, out: f64, work: &mut Work| {
        let arm = |s: &PinState| c.pin_arm(e_phi, centre, s);
        let out = pins_root(model, p, (e_phi, offset, psi(lag)), out, work, arm)?.x;
        work.sol.output_lag_rad = Some(out);
        Ok::<_, SolveFailure>(out)
    };
    let mut totals = PinTotals::default();
    if let Some(p) = &model.pins {
        out = solve_pins(p, lag, out, work)?;
        totals = PinTotals::of(c, e_phi, centre, &work.sol.pins);
    }
    let Some(r) = &model.rollers else {
        return Ok(());
    };
    let mut relative_change = f64::INFINITY;
    for _ in 0..COUPLED_PASSES {
        lag = solve_rollers_coupled(model, c, r, (crank, e_phi), offset, lag, &totals, work)?;
        work.sol.lag_rad = Some(lag);
        let Some(p) = &model.pins else {
            return Ok(());
        };
        out = solve_pins(p, lag, out, work)?;
        let moved = PinTotals::of(c, e_phi, centre, &work.sol.pins);
        let before = coupled_roller_moment(c, crank, centre, &work.sol.rollers, &totals);
        let after = coupled_roller_moment(c, crank, centre, &work.sol.rollers, &moved);
        // How far the pins' new totals move the rollers' balance from where it was solved.
        let change = ((after.0 - moved.shift) - (before.0 - totals.shift)).abs();
        totals = moved;
        relative_change = change / model.torque_nmm.abs().max(after.2);
        if relative_change <= model.settings.rel_tol {
            return Ok(());
        }
    }
    Err(SolveFailure::NotConverged {
        x: lag,
        residual: relative_change,
    })
}
