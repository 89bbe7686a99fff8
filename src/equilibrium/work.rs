//! What a run over neighbouring crank angles carries from one solve to the next (`Work`): the
//! last solution and its buffers, where each roller was last evaluated, and the history that
//! the next angle's lags are guessed from.

use super::loaded::{AngleSolution, Model};
use super::rollers::Reach;
use crate::geometry::Vec2;

/// Reusable state of a sequential run over neighbouring crank angles: the last solution (its
/// buffers and warm starts), where each roller was last evaluated, and the lags of the last
/// three solved angles for extrapolating the next guess.
#[derive(Debug, Clone, Default)]
pub struct Work {
    pub sol: AngleSolution,
    /// Evaluate every roller exactly at the answer. Off in sweeps, where a roller proven out
    /// of reach keeps the geometry of its last exact evaluation and a lower bound as its gap
    /// (its force is exactly zero either way).
    pub exact_final: bool,
    /// (cos φ, sin φ) of the angle being solved.
    pub(super) e_phi: Vec2,
    pub(super) reaches: Vec<Reach>,
    /// The last (up to three) solved angles, oldest first, in the last `filled` entries.
    history: [Solved; 3],
    filled: usize,
    pub(super) terms: Vec<(f64, f64)>,
    pub(super) events: Vec<(f64, f64, f64)>,
    /// ∂M/∂β of the rollers' balance and ∂M/∂βo of the pins' at the last solution, N·mm/rad,
    /// as the root search last evaluated them (0 where a closed form solved the balance).
    pub(super) slopes: (f64, f64),
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
    /// The work of a lone solve from `sol` (its lags and contact points the warm start), with
    /// every roller evaluated exactly at the answer.
    pub(super) fn exact_from(sol: AngleSolution) -> Self {
        Work {
            sol,
            exact_final: true,
            ..Work::default()
        }
    }

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
    /// contact set, where the lags' trend alone misses by that departure over the slope and
    /// the balance takes another evaluation.
    /// With a rigid bearing only: a compliant one's lags move with the centre too.
    pub(super) fn guess_at_torque(&self, crank: f64, model: &Model) -> (f64, f64) {
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
    pub(super) fn near(&self, crank: f64, model: &Model) -> bool {
        self.filled > 0 && (self.history[2].crank - crank).abs() <= model.warm_reach()
    }

    /// Forget the last angle's states when it is too far from `crank` to warm-start it (a
    /// sweep of two steps over a turn): the closest points then start from each roller's own
    /// foot guess, and every roller is evaluated, so that each angle solves on its own.
    pub(super) fn forget_if_far(&mut self, crank: f64, model: &Model) {
        if self.filled > 0 && !self.near(crank, model) {
            self.filled = 0;
            self.sol.rollers.clear();
            self.sol.pins.clear();
            self.reaches.clear();
        }
    }

    /// Whether `crank` is the angle solved last.
    pub(super) fn solved_at(&self, crank: f64) -> bool {
        self.filled > 0 && self.history[2].crank == crank
    }

    pub(super) fn remember(&mut self, crank: f64, torque: f64) {
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
        if self.solved_at(crank) {
            self.history[2] = solved;
            return;
        }
        self.history = [self.history[1], self.history[2], solved];
        self.filled = (self.filled + 1).min(3);
    }
}
