//! Several identical discs on one crank, driving one output flange (MODEL.md "Several
//! discs, torsion, bearing life").
//!
//! Disc k of N runs at the crank phase φk = φ + 2πk/N and meshes with the same rollers; its
//! holes are bored so that the pins sit centred at its ideal pose (`Pins::for_disc`). Each disc
//! balances its own share Tk of the output torque through its rollers and its pins, with its
//! own crank bearing, exactly as one disc does (`angle::solve_into`); what couples them is the
//! output flange: the output lag γ = βk + βo,k is the same for every disc, and Σ Tk = T.
//! Without the pins in a scene the discs are rigidly coupled: γ = βk.
//!
//! The split of the torque is found by Newton on the shares: disc k's lag γk(Tk) is
//! increasing in Tk with compliance ck = dγk/dTk; the update that makes every γk equal to
//! one γ* while keeping Σ Tk = T is Tk ← Tk + (γ* − γk)/ck, γ* = (T − ΣTk + Σ γk/ck)/Σ 1/ck.
//! The compliance is the secant of the last two solves of the disc at this angle, or, at the
//! first solve, the tangent of its balances (1/Σk·l² of the rollers plus that of the pins).

use super::angle::solve_into;
use super::balance::moment;
use super::loaded::Model;
use super::solve::SolveFailure;
use super::work::Work;
use crate::model::design::disc_phase_rad;
use crate::model::MAX_DISCS;

/// Newton steps of the torque split before the coupled solve gives up: from the split of the
/// previous angle it takes two or three; a contact that opens or closes between two steps
/// costs a few more.
const MAX_STEPS: usize = 60;

/// The loaded models of the discs of a scene, each at its crank phase.
#[derive(Debug, Clone)]
pub struct Discs {
    /// Disc k's model: its pins turned by 2πk/(N·nc); its torque is set by the split.
    pub models: Vec<Model>,
    /// Crank phase of disc k, rad.
    pub phases: Vec<f64>,
    /// The output torque T shared by the discs, N·mm.
    pub torque_nmm: f64,
}

impl Discs {
    /// `count` discs of the one-disc model `model` (a scene's model of the disc at phase 0).
    pub fn new(model: &Model, count: usize) -> Self {
        let teeth = model.teeth as f64;
        let phases: Vec<f64> = (0..count).map(|k| disc_phase_rad(k, count)).collect();
        let models = phases
            .iter()
            .enumerate()
            .map(|(k, &phase)| {
                let mut m = model.clone();
                m.pins = m.pins.map(|p| p.for_disc(k, phase / teeth));
                m
            })
            .collect();
        Discs {
            models,
            phases,
            torque_nmm: model.torque_nmm,
        }
    }

    pub fn count(&self) -> usize {
        self.models.len()
    }
}

/// Reusable state of a sequence of coupled solves over neighbouring crank angles: each disc's
/// model (its torque share) and work, and the last angles' split for the next guess.
#[derive(Debug, Clone)]
pub struct CoupledWork {
    pub models: Vec<Model>,
    pub works: Vec<Work>,
    /// The crank angles of the last (up to `HISTORY`) splits solved, oldest first, in the last
    /// `filled` entries.
    cranks: [f64; HISTORY],
    /// Disc k's departure from the equal split at those angles, Tk − T/N (N·mm; the departures
    /// sum to 0). Kept per disc as scalars, so that the lean sweep reads and writes each share
    /// alone (`remember_split`). A torque, not a fraction of T: preloaded discs that mesh out of
    /// phase (np odd) hold each other with a torque that stays as T → 0, so Tk/T grows without
    /// bound there (−2.7e6 at T = 1e-6 N·m on an 11-roller pair), and a fraction remembered at
    /// a tiny T and applied to the next torque of a torsion loop guessed shares of 1e5 N·m.
    shares: [[f64; HISTORY]; MAX_DISCS],
    filled: usize,
    /// The converged beam gaps (`solve_coupled`, pins that bend shared by the discs; disc by
    /// disc, pin by pin, mm) at those angles, empty where none was solved: extrapolated like
    /// the shares, they start an angle's fixed point within ~1e-9 mm of its answer, where the
    /// last angle's gaps (1e-6 mm off at 3,600 angles a mesh period) took seven passes.
    beam_gaps: [Vec<f64>; HISTORY],
}

/// The splits a `CoupledWork` remembers: four, for a cubic extrapolation. The Newton on the
/// shares settles an angle in one step only when the guess is within its tolerance (~1e-9 of
/// T); a quadratic's truncation error (the third differences of the shares) can exceed that
/// even at fine crank steps, and every angle would then take a second step.
const HISTORY: usize = 4;

impl CoupledWork {
    /// Empty: the discs' models are copied at the first coupled solve (`solve_coupled`), which
    /// sets their torques; the lean sweep of the first-order geometry never needs them.
    pub fn new(discs: &Discs) -> Self {
        CoupledWork {
            models: Vec::new(),
            works: vec![Work::default(); discs.count()],
            cranks: [0.0; HISTORY],
            shares: [[0.0; HISTORY]; MAX_DISCS],
            filled: 0,
            beam_gaps: Default::default(),
        }
    }

    /// Guess the next angles' splits from those `before` remembered: the last angles of the
    /// chunk of angles before this one (`discs_sweep::sweep_discs`).
    pub fn continue_from(&mut self, before: &CoupledWork) {
        (self.cranks, self.shares, self.filled) = (before.cranks, before.shares, before.filled);
        self.beam_gaps.clone_from(&before.beam_gaps);
    }

    /// The beam gaps extrapolated to an angle by `weights` (`extrapolation`), or `None` when
    /// an angle they weigh has none remembered.
    fn beam_gaps_guess(&self, weights: Option<[f64; HISTORY]>, len: usize) -> Option<Vec<f64>> {
        let weights = weights?;
        let held = |(w, g): (&f64, &Vec<f64>)| *w == 0.0 || g.len() == len;
        if len == 0 || !weights.iter().zip(&self.beam_gaps).all(held) {
            return None;
        }
        let mut out = vec![0.0; len];
        for (w, g) in weights
            .iter()
            .zip(&self.beam_gaps)
            .filter(|(w, _)| **w != 0.0)
        {
            for (o, x) in out.iter_mut().zip(g) {
                *o += w * x;
            }
        }
        Some(out)
    }

    /// The Lagrange weights that extrapolate the remembered shares to `crank`, through as
    /// many of the last angles as are held (cubic from four; an entry not yet filled has
    /// weight zero), or `None` with no history or one too far away (`Model::warm_reach`).
    pub fn extrapolation(&self, crank: f64, reach: f64) -> Option<[f64; HISTORY]> {
        let [p0, p1, p2, p3] = self.cranks;
        if self.filled == 0 || (p3 - crank).abs() > reach {
            return None;
        }
        // (crank − pj) and each weight's denominator Π (pi − pj), written out per count held so
        // that the guess costs a few dozen operations an angle, not a loop's bookkeeping.
        let (d0, d1, d2, d3) = (crank - p0, crank - p1, crank - p2, crank - p3);
        Some(match self.filled {
            1 => [0.0, 0.0, 0.0, 1.0],
            2 => [0.0, 0.0, d3 / (p2 - p3), d2 / (p3 - p2)],
            3 => [
                0.0,
                d2 * d3 / ((p1 - p2) * (p1 - p3)),
                d1 * d3 / ((p2 - p1) * (p2 - p3)),
                d1 * d2 / ((p3 - p1) * (p3 - p2)),
            ],
            _ => [
                d1 * d2 * d3 / ((p0 - p1) * (p0 - p2) * (p0 - p3)),
                d0 * d2 * d3 / ((p1 - p0) * (p1 - p2) * (p1 - p3)),
                d0 * d1 * d3 / ((p2 - p0) * (p2 - p1) * (p2 - p3)),
                d0 * d1 * d2 / ((p3 - p0) * (p3 - p1) * (p3 - p2)),
            ],
        })
    }

    /// Disc k's torque (N·mm) of the `n` discs sharing `total`, by the weights `extrapolation`
    /// gave: the equal share T/N plus its remembered departures from it extrapolated (at the
    /// torque of the last solve, for a torsion loop's next torque), or the equal share without
    /// them. The guesses sum to `total` up to round-off; the Newton steps keep the sum.
    pub fn share_guess(
        &self,
        k: usize,
        weights: Option<[f64; HISTORY]>,
        n: usize,
        total: f64,
    ) -> f64 {
        if n == 1 {
            // The whole torque, exactly: one disc solves as `angle::solve_into` alone does.
            return total;
        }
        let equal = total / n as f64;
        match weights {
            Some(w) => {
                let s = &self.shares[k];
                equal + (w[0] * s[0] + w[1] * s[1] + w[2] * s[2] + w[3] * s[3])
            }
            None => equal,
        }
    }

    /// Remember the split `torque` (N·mm, disc by disc) of the output torque `total` at
    /// `crank`, for the guess at the next angle. A second solve of the angle remembered last
    /// replaces it. Where a Newton on the shares settled the angle, the split to remember is
    /// its next one (each share plus `Share::step`), not the one the angle settled on: that
    /// is only within the Newton's tolerance of the answer, and the extrapolation magnifies
    /// the history's error (fifteenfold for a cubic on a uniform grid, weights −1, 4, −6, 4)
    /// past that tolerance, which would take a second Newton step.
    pub fn remember_split(&mut self, crank: f64, torque: impl Iterator<Item = f64>, total: f64) {
        let n = self.works.len().max(1) as f64;
        let new_angle = self.filled == 0 || self.cranks[HISTORY - 1] != crank;
        // The shifts are written out: `rotate_left` is a call the compiler need not inline.
        let shift = |[_, a, b, c]: [f64; HISTORY], last: f64| [a, b, c, last];
        if new_angle {
            self.cranks = shift(self.cranks, crank);
            self.filled = (self.filled + 1).min(HISTORY);
            self.beam_gaps.rotate_left(1);
            self.beam_gaps[HISTORY - 1].clear();
        }
        for (s, t) in self.shares.iter_mut().zip(torque) {
            let share = t - total / n;
            if new_angle {
                *s = shift(*s, share);
            } else {
                s[HISTORY - 1] = share;
            }
        }
    }
}

/// Disc k's output lag γk = βk + βo,k (βo,k = 0 without pins: rigid coupling), rad.
pub(super) fn output_lag(work: &Work) -> f64 {
    work.sol.lag_rad.unwrap_or(0.0) + work.sol.output_lag_rad.unwrap_or(0.0)
}

/// dγk/dTk from the balances at the disc's solution, rad/(N·mm): 1/(∂M/∂β) of the rollers
/// plus 1/(∂M/∂βo) of the pins (geometry held fixed); `None` when a balance has no
/// stiffness (no contact).
fn tangent_compliance(work: &Work) -> Option<f64> {
    let sol = &work.sol;
    let slopes = [
        sol.lag_rad.map(|_| moment(&sol.rollers).1),
        sol.output_lag_rad.map(|_| moment(&sol.pins).1),
    ];
    let mut c = 0.0;
    for slope in slopes.into_iter().flatten() {
        (slope > 0.0).then_some(())?;
        c += 1.0 / slope;
    }
    (c > 0.0 && c.is_finite()).then_some(c)
}

/// Solve the discs at crank `crank` (disc k at crank + its phase) so that every disc has the
/// same output lag and the shares sum to T. Returns the output lag γ (rad); each disc's
/// solution and torque are in `work`.
///
/// With bending pins shared by several discs (`pin_beam`), each disc's pin gaps also open by
/// the other discs' pin forces, Σ_{k≠j} c_jk·F_k·(û_j·û_k): a fixed point over those gaps
/// (block Jacobi, a disc a block), each pass a full solve of the shares (`solve_shares`) at
/// the gaps of the last pass, until no gap moves by more than 1e-9 of the largest plus the
/// pins' gap round-off. Why it converges: at a fixed split the pin forces minimise the
/// complementary energy ½·Fᵀ(K⁻¹ + C)F − F·δ_rigid of each pin, K⁻¹ + C symmetric positive
/// definite (contacts in series with a beam, C its flexibility, Maxwell), and block Jacobi on
/// a positive definite system of two blocks converges (its iteration matrix has the spectral
/// radius |c12|/sqrt((1/k1 + c11)(1/k2 + c22)) < 1); two discs in opposite phases moreover
/// load opposite halves of the pin circle, so a pin carries one disc at a time but near the
/// arms' zero crossings and the coupling is weak. The passes are accelerated by a secant
/// (Anderson) step (`secant_step`) and start from the gaps of the last angles extrapolated
/// (`CoupledWork::beam_gaps_guess`); a disc the split lets float is checked against its dead
/// band once, at the last pass. On the paper's design with two discs on 20 mm cantilever
/// pins (6 and 16 mm from the flange, 10 N·m, 3,600 angles a mesh period) an angle takes 4.4
/// passes of 3.8 disc solves on average, where the last angle's gaps and a solve in γ
/// (`by_lag`) at every pass for the floating disc took 7.1 passes of 7.1. With three or four discs block Jacobi is not proven, and
/// `MAX_BEAM_PASSES` without convergence is "did not converge", a status (exit 2 at the scene
/// and angle), never a result.
pub fn solve_coupled(
    discs: &Discs,
    crank: f64,
    work: &mut CoupledWork,
) -> Result<f64, SolveFailure> {
    let n = discs.count();
    if work.models.len() != n {
        work.models = discs.models.clone();
    }
    let Some(first) = discs.models[0].pins.as_ref().filter(|p| p.couples_discs()) else {
        return solve_shares(discs, crank, work, Verify::Floating).map(|(g, _)| g);
    };
    let c = &first
        .beam()
        .expect("coupled pins are beams")
        .coefficients_mm_per_n;
    let pins = first.count;
    let mut last = (0.0, f64::INFINITY);
    // The last pass's gaps x and their image G(x), for the secant (Anderson) step.
    let mut previous: Option<(Vec<f64>, Vec<f64>)> = None;
    let guess = work.extrapolation(crank, discs.models[0].warm_reach());
    if let Some(gaps) = work.beam_gaps_guess(guess, n * pins) {
        set_beam_gaps(&mut work.models, &gaps, pins);
    }
    // The passes leave a floating disc's dead band unprobed until the gaps have settled: only
    // the last pass's split is the answer.
    let mut verify = Verify::Deferred;
    for _ in 0..MAX_BEAM_PASSES {
        let (gamma, floating) = solve_shares(discs, crank, work, verify)?;
        let mut x = Vec::with_capacity(n * pins);
        let mut image = Vec::with_capacity(n * pins);
        for (j, row) in c.iter().enumerate().take(n) {
            x.extend_from_slice(
                work.models[j]
                    .pins
                    .as_ref()
                    .map_or(&[][..], |p| p.beam_gaps_mm()),
            );
            for p in 0..pins {
                let own = &work.works[j].sol.pins[p];
                let mut sum = 0.0;
                for k in (0..n).filter(|&k| k != j) {
                    let other = &work.works[k].sol.pins[p];
                    sum += row[k] * other.force_n * own.direction.dot(&other.direction);
                }
                image.push(sum);
            }
        }
        let change = x
            .iter()
            .zip(&image)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let largest = image.iter().map(|g| g.abs()).fold(0.0, f64::max);
        if change <= 1e-9 * largest + BEAM_GAP_FLOOR_MM {
            if verify == Verify::Floating
                || all_float_at(discs, work, crank, &floating[..n], gamma)?
            {
                work.beam_gaps[HISTORY - 1] = x;
                return Ok(gamma);
            }
            // A disc let float whose dead band misses the others' lag: the passes go on with
            // every split checked (`by_lag` where it floats wrongly).
            verify = Verify::Floating;
            continue;
        }
        last = (gamma, change);
        let next = secant_step(previous.as_ref(), &x, &image);
        set_beam_gaps(&mut work.models, &next, pins);
        previous = Some((x, image));
    }
    Err(SolveFailure::NotConverged {
        x: last.0,
        residual: last.1,
    })
}

/// Give each disc's pins their beam gaps, `pins` of them a disc in `gaps` (mm).
fn set_beam_gaps(models: &mut [Model], gaps: &[f64], pins: usize) {
    for (model, row) in models.iter_mut().zip(gaps.chunks(pins)) {
        if let Some(p) = model.pins.as_mut() {
            p.set_beam_gaps(row);
        }
    }
}

/// The next gaps of the fixed point x = G(x) after the pass (x, G(x)): Anderson's step of
/// depth one, G(x) − θ·(G(x) − G(x′)) with θ = f·(f − f′)/|f − f′|², f = G(x) − x and the
/// primes the pass before (Walker & Ni, SIAM J. Numer. Anal. 49 (2011)); the plain step G(x)
/// at the first pass or where θ is not finite. On a linear map whose slowest mode dominates
/// (two discs: the Jacobi ratio |c12|/sqrt((1/k1 + c11)(1/k2 + c22)), 0.7 for discs 6 and
/// 16 mm along a 6 mm cantilever pin), the secant removes that mode, where the plain step
/// takes ~70 passes to 1e-9.
fn secant_step(previous: Option<&(Vec<f64>, Vec<f64>)>, x: &[f64], image: &[f64]) -> Vec<f64> {
    let Some((xp, gp)) = previous else {
        return image.to_vec();
    };
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..x.len() {
        let df = (image[i] - x[i]) - (gp[i] - xp[i]);
        num += (image[i] - x[i]) * df;
        den += df * df;
    }
    let theta = num / den;
    if !theta.is_finite() {
        return image.to_vec();
    }
    (0..x.len())
        .map(|i| image[i] - theta * (image[i] - gp[i]))
        .collect()
}

/// Passes of the fixed point over the gaps bending pins couple the discs by: two or three
/// from the last angle's gaps, a few more where a pin changes discs.
const MAX_BEAM_PASSES: usize = 100;

/// The absolute floor of the beam gaps' convergence, mm: a few ulp of the pin circle's
/// lengths (a gap is resolved to 16·ε·(c + e + rw), ~7e-14 mm on the paper's design).
const BEAM_GAP_FLOOR_MM: f64 = 1e-13;

/// Whether `solve_shares` checks that a disc it let float holds the others' lag in its dead
/// band (`all_float_at`) before it returns the split.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Verify {
    /// Checked: the split is the answer.
    Floating,
    /// Left to the caller, who has the floating discs in the result.
    Deferred,
}

/// Newton on the shares first: converged when the next
/// correction of every share is within 10·rel_tol of max(|T|, Σ|F·l| of the discs), ten times
/// the round-off of each disc's own balance (which is what a disc's lag is known to; a
/// preloaded disc's Σ|F·l| is far above T). When that has not converged in `NEWTON_STEPS`
/// (a disc floating in its backlash: its lag jumps across the answer as its share changes
/// sign), the balance is solved as a root in γ (`by_lag`).
fn solve_shares(
    discs: &Discs,
    crank: f64,
    work: &mut CoupledWork,
    verify: Verify,
) -> Result<(f64, [bool; MAX_DISCS]), SolveFailure> {
    let n = discs.count();
    let total = discs.torque_nmm;
    let reach = discs.models[0].warm_reach();
    let weights = work.extrapolation(crank, reach);
    // Fixed arrays of `MAX_DISCS` (the first n used): an angle allocates nothing.
    let mut torque = [0.0; MAX_DISCS];
    for (k, t) in torque[..n].iter_mut().enumerate() {
        *t = work.share_guess(k, weights, n, total);
    }
    let mut lag = [0.0; MAX_DISCS];
    let mut last: [Option<(f64, f64)>; MAX_DISCS] = [None; MAX_DISCS];
    // Discs the Newton has let float (share zero, no weight): a share sent against the torque
    // crosses its disc's backlash, where no compliance describes it; the others settle
    // without it, and the disc's dead band must then hold their common lag (`floats_at`).
    let mut floating = [false; MAX_DISCS];
    let rel_tol = discs.models[0].settings.rel_tol;
    for _ in 0..NEWTON_STEPS {
        let mut weights = [0.0; MAX_DISCS];
        let mut scale = total.abs();
        for k in 0..n {
            if floating[k] && last[k].is_some_and(|(t, _)| t == 0.0) {
                // Solved at zero already, and the beam gaps do not move within a split.
                scale += moment(&work.works[k].sol.rollers).2;
                continue;
            }
            lag[k] =
                solve_disc(discs, work, k, crank, torque[k]).map_err(of_disc(discs, k, crank))?;
            scale += moment(&work.works[k].sol.rollers).2;
            let secant = last[k]
                .filter(|&(t, _)| t != torque[k])
                .map(|(t, g)| (lag[k] - g) / (torque[k] - t))
                .filter(|c| *c > 0.0 && c.is_finite());
            if let Some(c) = secant.or_else(|| tangent_compliance(&work.works[k])) {
                weights[k] = 1.0 / c;
            }
            last[k] = Some((torque[k], lag[k]));
        }
        let (lag_n, weights) = (&lag[..n], &mut weights[..n]);
        // A disc without contact has no compliance of its own; the discs are identical, so
        // the mean of the others' stands in: the Newton then loads it when γ has passed its
        // nearest contact (or `by_lag` finds it floating).
        let loaded = weights.iter().filter(|w| **w > 0.0).count();
        if loaded > 0 && loaded < n {
            let mean = weights.iter().sum::<f64>() / loaded as f64;
            weights
                .iter_mut()
                .filter(|w| **w == 0.0)
                .for_each(|w| *w = mean);
        }
        for (w, _) in weights.iter_mut().zip(floating).filter(|(_, f)| *f) {
            *w = 0.0;
        }
        let torque_n = &mut torque[..n];
        let w: f64 = weights.iter().sum();
        if total == 0.0 || w == 0.0 {
            // No torque (or no contact anywhere): every share is zero and the discs rest at
            // their own lags; the reducer's is their mean.
            return Ok((finish(work, crank, torque_n, total, lag_n), floating));
        }
        let shares = || Share::of(torque_n, lag_n, weights);
        let common = common_lag(shares(), total);
        if converged(shares(), common, 10.0 * rel_tol * scale) {
            if verify == Verify::Floating
                && !all_float_at(discs, work, crank, &floating[..n], common)?
            {
                break;
            }
            // γ is the common lag of the discs that carry a share (a disc without contact has
            // no weight, and its own lag is that of its nearest contact).
            work.remember_split(crank, shares().map(|s| s.torque + s.step(common)), total);
            return Ok((if n == 1 { lag[0] } else { common }, floating));
        }
        if !step_shares(torque_n, lag_n, weights, &mut floating[..n], total) {
            break;
        }
    }
    by_lag(discs, crank, work, &torque[..n], &lag[..n]).map(|g| (g, [false; MAX_DISCS]))
}

/// The Newton's step of the shares `torque` towards their common lag. A share the step would
/// send against the torque `total` crosses its disc's backlash, where its lag jumps and no
/// compliance describes it: the disc floats (zero share and weight, `floating`) and the step
/// is taken again for the others, who carry T. False when every disc would float (the solve
/// in γ, `by_lag`, then handles it); a floating disc's dead band must hold the others' lag in
/// the end (`all_float_at`).
fn step_shares(
    torque: &mut [f64],
    lag: &[f64],
    weights: &mut [f64],
    floating: &mut [bool],
    total: f64,
) -> bool {
    loop {
        let common = common_lag(Share::of(torque, lag, weights), total);
        let mut floated = false;
        for k in 0..torque.len() {
            let next = torque[k] + weights[k] * (common - lag[k]);
            if next * total < 0.0 {
                (torque[k], weights[k], floating[k], floated) = (0.0, 0.0, true, true);
            }
        }
        if floating.iter().all(|f| *f) {
            return false;
        }
        if !floated {
            for k in 0..torque.len() {
                torque[k] += weights[k] * (common - lag[k]);
            }
            if floating.iter().any(|f| *f) {
                // At a tiny torque γ* = (T − ΣTk + Σwk·γk)/Σwk cancels: Σwk·γk is ~1e8 times
                // T near zero torque (an 11-roller pair at 1e-6 N·m left ΣTk off T by 1.6e-8 of
                // T). What it leaves goes to the loaded discs by weight, as `by_lag` does.
                let off = total - torque.iter().sum::<f64>();
                let w: f64 = weights.iter().sum();
                for k in 0..torque.len() {
                    torque[k] += off * weights[k] / w;
                }
            }
            return true;
        }
    }
}

/// The share, as a fraction of T, at which a disc's dead band is probed (`torque_at_lag`).
const PROBE: f64 = 1e-6;

/// One disc in the Newton on the shares: its torque Tk (N·mm), its output lag γk there (rad)
/// and its stiffness wk = 1/ck (N·mm/rad).
#[derive(Debug, Clone, Copy, Default)]
pub struct Share {
    pub torque: f64,
    pub lag: f64,
    pub weight: f64,
}

impl Share {
    /// The discs' shares from columns of torques, lags and stiffnesses.
    fn of<'s>(
        torque: &'s [f64],
        lag: &'s [f64],
        weight: &'s [f64],
    ) -> impl Iterator<Item = Share> + Clone + 's {
        let columns = torque.iter().zip(lag).zip(weight);
        columns.map(|((&torque, &lag), &weight)| Share {
            torque,
            lag,
            weight,
        })
    }

    /// The Newton's correction of this share towards the common lag γ*: wk·(γ* − γk), which
    /// keeps Σ Tk = T.
    pub fn step(&self, common: f64) -> f64 {
        self.weight * (common - self.lag)
    }
}

/// The Newton's common lag γ* = (T − ΣTk + Σ wk·γk)/Σ wk of the discs `shares` sharing `total`
/// (N·mm), rad.
pub fn common_lag(shares: impl Iterator<Item = Share>, total: f64) -> f64 {
    let (mut w, mut t, mut wg) = (0.0, 0.0, 0.0);
    for s in shares {
        (w, t, wg) = (w + s.weight, t + s.torque, wg + s.weight * s.lag);
    }
    (total - t + wg) / w
}

/// Whether the discs `shares` are settled on the common lag `common`: every correction
/// (`Share::step`) within `tol` (N·mm), or every lag equal to γ to round-off (at a tiny
/// torque, one ulp of lag times the stiffness outweighs the balance's whole tolerance); and, in
/// either case, every disc that carries a share at the common lag (the steps alone can look
/// converged across a dead band, where a secant over a disc's jump of lag is a huge
/// compliance, so a tiny weight).
pub fn converged(shares: impl Iterator<Item = Share>, common: f64, tol: f64) -> bool {
    let near = 1e-7 * common.abs().max(1e-300);
    let (mut agree, mut to_ulps, mut small) = (true, true, true);
    for s in shares {
        let off = (s.lag - common).abs();
        agree &= s.torque == 0.0 || off <= near;
        to_ulps &= off <= 8.0 * f64::EPSILON * s.lag.abs();
        small &= s.step(common).abs() <= tol;
    }
    agree && (to_ulps || small)
}

/// Newton steps on the shares before `by_lag` takes over: from the split of the previous
/// angle the Newton converges in one or two.
const NEWTON_STEPS: usize = 8;

/// A failure of disc k's own solve at the reducer's crank angle `crank`, named by the disc
/// when there are several (with one, the failure is the reducer's and reads as before).
fn of_disc(discs: &Discs, k: usize, crank: f64) -> impl Fn(SolveFailure) -> SolveFailure + '_ {
    move |failure| match discs.count() {
        1 => failure,
        n => SolveFailure::Disc {
            disc: k,
            discs: n,
            crank_rad: crank + discs.phases[k],
            failure: Box::new(failure),
        },
    }
}

/// Solve disc k alone at the torque `t` (N·mm): its output lag γk.
fn solve_disc(
    discs: &Discs,
    work: &mut CoupledWork,
    k: usize,
    crank: f64,
    t: f64,
) -> Result<f64, SolveFailure> {
    // A share within the inner root's resolution of zero is zero: the disc floats, and the
    // solve at exactly zero torque finds its nearest contact (`angle::solve_into`) where one
    // at 1e-16 N·m would search for a balance the size of round-off.
    let t = if t.abs() <= 1e-12 * discs.torque_nmm.abs() {
        0.0
    } else {
        t
    };
    work.models[k].torque_nmm = t;
    let phi = crank + discs.phases[k];
    // Another solve of the angle the disc was solved at last (a share corrected, a torsion
    // loop's next torque): every roller evaluated. The bounds that let a sweep skip a roller
    // as out of reach (`rollers::Reach`) are only as good as the gap they start from, and a
    // warm-started closest point can settle on a foot that is not the nearest; a re-solve,
    // whose lag may jump far (across the backlash), would carry such a bound past a contact,
    // so it does not use them.
    if work.works[k].solved_at(phi) {
        work.works[k].reaches.clear();
    }
    // A disc without a share does not load its bearing: its centre sits where a rigid one
    // holds it (and the compliant solve need not find a balance of round-off).
    // So does one whose share only probes where its dead band ends (`torque_at_lag`, at
    // `PROBE`·T): its centre moves by that share over the bearing's stiffness, far below the
    // probe's own resolution, and at such a share the compliant solve does not converge on
    // every design (first-order pins at 1e-6·T).
    let stiffness = work.models[k].bearing_stiffness_n_per_mm;
    if t.abs() <= PROBE * discs.torque_nmm.abs() {
        work.models[k].bearing_stiffness_n_per_mm = None;
    }
    let solved = solve_unloaded_or(discs, work, k, phi, t);
    work.models[k].bearing_stiffness_n_per_mm = stiffness;
    solved?;
    Ok(output_lag(&work.works[k]))
}

/// `solve_into` of disc k at `t`, or at zero when the first-order geometry cannot put the
/// disc on the flank against the output torque (`solve_disc`).
fn solve_unloaded_or(
    discs: &Discs,
    work: &mut CoupledWork,
    k: usize,
    phi: f64,
    t: f64,
) -> Result<(), SolveFailure> {
    match solve_into(&work.models[k], phi, &mut work.works[k]) {
        // The first-order geometry models the loaded flanks alone: a disc cannot take a share
        // against the output torque, it floats in its backlash instead (zero share).
        Err(SolveFailure::NoBracket { .. }) if t * discs.torque_nmm < 0.0 => {
            work.models[k].torque_nmm = 0.0;
            work.models[k].bearing_stiffness_n_per_mm = None;
            solve_into(&work.models[k], phi, &mut work.works[k])
        }
        other => other,
    }
}

/// (x, f(x)) of a one-dimensional root search.
type Point = (f64, f64);

/// Regula falsi (Illinois) on a non-decreasing f between `lo` = (x, f(x)) below `target` and
/// `hi` above it, until |f − target| ≤ `tol` or the bracket is within `width`.
fn illinois(
    mut lo: (f64, f64),
    mut hi: (f64, f64),
    target: f64,
    (tol, width): (f64, f64),
    mut f: impl FnMut(f64) -> Result<f64, SolveFailure>,
) -> Result<f64, SolveFailure> {
    let mut side = 0i8;
    for step in 0..4 * MAX_STEPS {
        if hi.0 - lo.0 <= width {
            break;
        }
        // Every third step bisects: the coupled balance in γ is flat across a dead band and
        // steep beside it, where the secant alone creeps; with the bisections the bracket
        // halves at least every three steps, to round-off within the steps allowed.
        let x = lo.0 + (target - lo.1) * (hi.0 - lo.0) / (hi.1 - lo.1);
        let x = if x > lo.0 && x < hi.0 && step % 3 != 2 {
            x
        } else {
            0.5 * (lo.0 + hi.0)
        };
        let y = f(x)?;
        if (y - target).abs() <= tol {
            return Ok(x);
        }
        if y < target {
            lo = (x, y);
            if side == -1 {
                hi.1 = target + 0.5 * (hi.1 - target);
            }
            side = -1;
        } else {
            hi = (x, y);
            if side == 1 {
                lo.1 = target - 0.5 * (target - lo.1);
            }
            side = 1;
        }
    }
    Ok(if (lo.1 - target).abs() <= (hi.1 - target).abs() {
        lo.0
    } else {
        hi.0
    })
}

/// Expand from `from` = (x, f(x)) in steps of `step` (doubling, away from the target's side)
/// until f passes `target`: the bracket (below, above) of the target.
fn bracket(
    from: (f64, f64),
    mut step: f64,
    target: f64,
    mut f: impl FnMut(f64) -> Result<f64, SolveFailure>,
) -> Result<(Point, Point), SolveFailure> {
    let up = from.1 < target;
    let mut near = from;
    for _ in 0..MAX_STEPS {
        let x = if up { near.0 + step } else { near.0 - step };
        let far = (x, f(x)?);
        if (far.1 >= target) == up {
            return Ok(if up { (near, far) } else { (far, near) });
        }
        near = far;
        step *= 2.0;
    }
    Err(SolveFailure::NoBracket {
        lo: near.0.min(from.0),
        hi: near.0.max(from.0),
        nearest: Some(near),
    })
}

/// The coupled balance as a root in the output lag γ: Σ Tk(γ) = T, where Tk(γ) is the torque
/// at which disc k's own output lag is γ (zero while γ lies in the disc's dead band). Both
/// are non-decreasing, so a bracket holds: at the smallest of the discs' lags of the last
/// Newton step each disc carries at most its share of that step, at the largest at least.
/// Slower than the Newton (an inner root per disc for every γ tried), and it cannot cycle.
/// Each disc's torque to 1e-12 of T, the balance to 1e-10·T.
fn by_lag(
    discs: &Discs,
    crank: f64,
    work: &mut CoupledWork,
    torque: &[f64],
    lag: &[f64],
) -> Result<f64, SolveFailure> {
    let total = discs.torque_nmm;
    let mut shares = torque.to_vec();
    let mut sum_at = |g: f64, work: &mut CoupledWork| -> Result<f64, SolveFailure> {
        for (k, t) in shares.iter_mut().enumerate() {
            *t = torque_at_lag(discs, work, (k, crank), total, g)
                .map_err(of_disc(discs, k, crank))?;
        }
        Ok(shares.iter().sum())
    };
    let (lo, hi) = crate::numeric::extent(lag.iter().copied());
    let below = (lo, sum_at(lo, work)?);
    let above = (hi, sum_at(hi, work)?);
    let width = 4.0 * f64::EPSILON * hi.abs().max(lo.abs());
    let tol = 1e-10 * total.abs();
    let near = |p: Point| (p.1 - total).abs() <= tol;
    let g = if near(below) {
        lo
    } else if near(above) {
        hi
    } else {
        // The Newton's lags need not enclose the answer (at a tiny torque every disc can
        // float between them): widen from the side that misses it.
        let step = (hi - lo)
            .max(1e-9 * hi.abs().max(lo.abs()))
            .max(f64::MIN_POSITIVE);
        let (below, above) = if below.1 > total {
            bracket(below, step, total, |g| sum_at(g, work))?
        } else if above.1 < total {
            bracket(above, step, total, |g| sum_at(g, work))?
        } else {
            (below, above)
        };
        illinois(below, above, total, (tol, width), |g| sum_at(g, work))?
    };
    // The discs hold the solves of the last γ tried; solve them at the answer's. A disc that
    // floats in its backlash (no share) keeps the lag of its nearest contact, not γ.
    let sum = sum_at(g, work)?;
    // What the root in γ leaves of T − Σ Tk goes to the loaded discs by their stiffness, so
    // that the shares sum to T to round-off; it moves their lags by that over Σ 1/ck.
    let loaded: Vec<(usize, f64)> = (0..discs.count())
        .filter(|&k| work.models[k].torque_nmm != 0.0)
        .filter_map(|k| tangent_compliance(&work.works[k]).map(|c| (k, 1.0 / c)))
        .collect();
    let stiffness: f64 = loaded.iter().map(|(_, w)| w).sum();
    if sum != total && stiffness > 0.0 {
        for &(k, w) in &loaded {
            let t = work.models[k].torque_nmm + (total - sum) * w / stiffness;
            solve_disc(discs, work, k, crank, t).map_err(of_disc(discs, k, crank))?;
        }
    }
    let lags: Vec<f64> = work.works.iter().map(output_lag).collect();
    let t: Vec<f64> = work.models.iter().map(|m| m.torque_nmm).collect();
    // A guard, not the criterion: a loaded disc off γ, or shares off T, is a failure to
    // report at the angle, never a result.
    let off = t
        .iter()
        .zip(&lags)
        .filter(|(tk, _)| tk.abs() > 1e-12 * total.abs())
        .map(|(_, l)| (l - g).abs() / g.abs().max(f64::MIN_POSITIVE))
        .fold(0.0, f64::max);
    let unbalanced = (t.iter().sum::<f64>() - total).abs() / total.abs();
    if off > 1e-7 || unbalanced > 1e-9 {
        return Err(SolveFailure::NotConverged {
            x: g,
            residual: off.max(unbalanced),
        });
    }
    finish(work, crank, &t, total, &lags);
    Ok(g)
}

/// Whether every disc the Newton let float (`floating`) holds the common lag `g` inside its
/// dead band (`dead_band_side`); each is left solved at zero torque.
fn all_float_at(
    discs: &Discs,
    work: &mut CoupledWork,
    crank: f64,
    floating: &[bool],
    g: f64,
) -> Result<bool, SolveFailure> {
    for k in (0..floating.len()).filter(|&k| floating[k]) {
        let side = dead_band_side(discs, work, (k, crank), discs.torque_nmm, g)
            .map_err(of_disc(discs, k, crank))?;
        if side.is_some() {
            return Ok(false);
        }
    }
    Ok(true)
}

/// Where the lag `g` lies against disc k's dead band, the lags at ±h (h = `PROBE`·|scale|):
/// the probe (torque, lag) beyond which a share must be sought, or `None` when `g` lies in the
/// band and the disc floats (then left solved at zero torque).
fn dead_band_side(
    discs: &Discs,
    work: &mut CoupledWork,
    (k, crank): (usize, f64),
    scale: f64,
    g: f64,
) -> Result<Option<Point>, SolveFailure> {
    let solve = |t: f64, work: &mut CoupledWork| solve_disc(discs, work, k, crank, t);
    let h = PROBE * scale.abs();
    // Each probe, and whether the disc took it: a disc that cannot take a share against the
    // output torque (first-order geometry, `solve_unloaded_or`) is solved at zero instead.
    let probe = |t: f64, work: &mut CoupledWork| -> Result<(Point, bool), SolveFailure> {
        let lag = solve(t, work)?;
        Ok(((t, lag), work.models[k].torque_nmm != 0.0))
    };
    let (up, up_taken) = probe(h, work)?;
    let (down, down_taken) = probe(-h, work)?;
    // Beyond a probe the disc did not take, it floats: its lag there is that of its nearest
    // contact, and a search on that side would only meet the first-order formula's other,
    // unmodelled flank (an 11-roller disc at 1e-6 N·m reported a share of −1e-9 N·mm at lag
    // −3.655e-3 rad against the others' +3.623e-3).
    if g > up.1 && up_taken {
        Ok(Some(up))
    } else if g < down.1 && down_taken {
        Ok(Some(down))
    } else {
        solve(0.0, work)?;
        Ok(None)
    }
}

/// The torque at which disc k's output lag is `g`: zero when `g` lies in the disc's dead
/// band, between its lags at ±h (h = 1e-6·|T|, `scale` = T: the smallest share a disc is
/// told apart from floating by; a compliant bearing's solve does not converge at 1e-9·T on
/// every design); else a root of γk(Tk) = g by regula falsi, bracketed from that side in
/// steps of |T|/4.
fn torque_at_lag(
    discs: &Discs,
    work: &mut CoupledWork,
    (k, crank): (usize, f64),
    scale: f64,
    g: f64,
) -> Result<f64, SolveFailure> {
    let solve = |t: f64, work: &mut CoupledWork| solve_disc(discs, work, k, crank, t);
    let Some(start) = dead_band_side(discs, work, (k, crank), scale, g)? else {
        return Ok(0.0);
    };
    let (lo, hi) = match bracket(start, 0.25 * scale.abs(), g, |t| solve(t, work)) {
        Ok(b) => b,
        // Below the lag of a disc that cannot take a share against the torque
        // (`solve_disc`): it floats.
        Err(SolveFailure::NoBracket { .. }) if start.1 > g => {
            solve(0.0, work)?;
            return Ok(0.0);
        }
        Err(e) => return Err(e),
    };
    let width = 1e-12 * scale.abs();
    let tol = 1e-13 * g.abs();
    let t = illinois(lo, hi, g, (tol, width), |t| solve(t, work))?;
    solve(t, work)?;
    Ok(work.models[k].torque_nmm)
}

/// Remember the converged split for the next angle; the reducer's output lag is the mean of
/// the discs' (equal to within the tolerance).
pub fn finish(work: &mut CoupledWork, crank: f64, torque: &[f64], total: f64, lag: &[f64]) -> f64 {
    work.remember_split(crank, torque.iter().copied(), total);
    lag.iter().sum::<f64>() / lag.len() as f64
}

#[cfg(test)]
mod tests {
    use super::Discs;
    use crate::equilibrium::loaded::Model;
    use crate::geometry::unit;
    use crate::model::{Effect, Plan};
    use std::f64::consts::TAU;

    /// The pins of disc k as its own solve sees them (`Pins::for_disc`) have the ideal arms of
    /// MODEL.md "Several discs": rw·sin(2πj/M − φ/nc + βk − φk), φk = φ + 2πk/N, for the disc
    /// at its own crank φk turned by ψk = −φk/nc + βk. Only rounding separates the two forms
    /// (a few ulp of rw = 18 mm).
    #[test]
    fn a_disc_sees_the_pins_at_the_arms_of_the_model() {
        let s = crate::spec::load("specs/paper.yaml").unwrap();
        let scene = &s.scenes[0];
        let plan = Plan::of("rated", &[Effect::Bearing]);
        let model = Model::new(&s.design, &s.modification, scene, &plan);
        let (nc, rw, m) = (9.0, 18.0, 6);
        for count in 2..=4 {
            let discs = Discs::new(&model, count);
            for (k, disc) in discs.models.iter().enumerate() {
                let pins = disc.pins.as_ref().unwrap();
                for (phi, lag) in [(0.3, 1e-3), (2.0, -4e-4), (5.5, 0.0)] {
                    let phi_k: f64 = phi + TAU * k as f64 / count as f64;
                    let e_phi = unit(phi_k);
                    let psi = -phi_k / nc + lag;
                    let mut states = Vec::new();
                    pins.first_order_at(e_phi, psi.sin_cos(), e_phi * 2.0, 0.0, &mut states);
                    for (j, st) in states.iter().enumerate() {
                        let arm = rw * (TAU * j as f64 / m as f64 - phi / nc + lag - phi_k).sin();
                        assert!(
                            (st.arm_mm - arm).abs() < 1e-12,
                            "disc {k} of {count}, pin {j}, crank {phi}: {} vs {arm}",
                            st.arm_mm
                        );
                    }
                }
            }
        }
    }
}
