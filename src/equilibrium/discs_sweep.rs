//! The loaded sweep of a reducer's discs on one crank, one or several (several by
//! `discs::solve_coupled` at every crank angle): each disc's curves and torque share, and the
//! reducer's transmission from the common output lag. One disc is N = 1 on the same path: it carries the whole torque,
//! so it skips what only a split needs (the Newton on the shares, their history, the second
//! wave) and solves alone (`angle::solve_into`, or its lean kernel at the whole torque), its
//! output lag γ = β + βo its own. The columns, chunks and curves are `sweep`'s.

use super::angle::solve_into;
use super::discs::{common_lag, converged, output_lag, solve_coupled, CoupledWork, Discs, Share};
use super::first_order_sweep::{FirstOrderSweep, Scratch};
use super::loaded::Model;
use super::solve::SolveFailure;
use super::sweep::{
    all_finite, disc_curves, piece_rows, pieces, transmission, Chunk, Columns, SweepFailure, CHUNK,
};
use super::work::Work;
use crate::geometry::{NearbyAtan2, NearbySinCos, Vec2};
use crate::model::results::{LoadedSweep, Transmission};
use crate::progress::Progress;
use rayon::prelude::*;

/// A sweep of a reducer's discs (`sweep_discs`): each disc's curves (its lags, forces,
/// bearing; no transmission of its own) and torque share, and the reducer's transmission from
/// the common output lag γ.
#[derive(Debug, Clone)]
pub struct DiscSweeps {
    pub discs: Vec<LoadedSweep>,
    /// Disc k's share of the output torque, N·mm, \[disc\]\[angle\].
    pub torque_nmm: Vec<Vec<f64>>,
    pub transmission: Option<Transmission>,
}

/// One chunk of a sweep: each disc's rows, its torque share and γ.
struct DiscChunk<'a> {
    discs: Vec<Chunk<'a>>,
    torque: Vec<&'a mut [f64]>,
    output_lag: &'a mut [f64],
}

/// A chunk of angles, each by the lean kernels (`Lean`; none where they do not apply) or else
/// by the general solve, its split guessed at the first angles from `before` (the chunk before
/// it) where given: its work, whose split the next chunk continues from.
fn solve_chunk(
    discs: &Discs,
    crank_rad: &[f64],
    chunk: &mut DiscChunk<'_>,
    (lean, before): (&mut Lean<'_>, Option<&CoupledWork>),
) -> Result<CoupledWork, SweepFailure> {
    let mut work = CoupledWork::new(discs);
    if let Some(before) = before {
        work.continue_from(before);
    }
    lean.restart(discs, crank_rad);
    for (k, &phi) in crank_rad.iter().enumerate() {
        if let Some(gamma) = lean.solve(discs, phi, k, &mut work, chunk) {
            chunk.output_lag[k] = gamma;
            continue;
        }
        record_coupled(discs, (k, phi), &mut work, chunk)?;
    }
    Ok(work)
}

/// Angle k (crank `phi`) by the general solve (`solve_general`), recorded in `chunk`.
fn record_coupled(
    discs: &Discs,
    (k, phi): (usize, f64),
    work: &mut CoupledWork,
    chunk: &mut DiscChunk<'_>,
) -> Result<(), SweepFailure> {
    let fail = |failure| SweepFailure {
        crank_rad: phi,
        failure,
    };
    chunk.output_lag[k] = solve_general(discs, phi, work).map_err(fail)?;
    // Several discs are solved at their shares (`work.models`), one at the scene's model.
    let models = match discs.count() {
        1 => &discs.models,
        _ => &work.models,
    };
    for (d, rows) in chunk.discs.iter_mut().enumerate() {
        let (model, w) = (&models[d], &work.works[d]);
        if !all_finite(&w.sol) {
            return Err(fail(SolveFailure::NonFinite {
                x: w.sol.lag_rad.unwrap_or(0.0),
            }));
        }
        rows.record(k, model, (phi + discs.phases[d], w.e_phi), &w.sol);
        chunk.torque[d][k] = model.torque_nmm;
    }
    Ok(())
}

/// The discs at crank `phi` by the general solve: several by the coupled solve
/// (`discs::solve_coupled`); one carries the whole torque and solves alone
/// (`angle::solve_into` at the model's torque), its output lag γ = β + βo its own. (The coupled
/// solve of one disc would take the Newton's bookkeeping at every angle, and at zero torque
/// hold a compliant bearing rigid, as for a disc let float, `discs::solve_disc`.) Returns γ,
/// rad; each disc's solution is in `work`, and with several discs its model at its share.
fn solve_general(discs: &Discs, phi: f64, work: &mut CoupledWork) -> Result<f64, SolveFailure> {
    if discs.count() > 1 {
        // The shares, beam gaps and lags extrapolated from the angles before can start a disc's
        // own solve where it runs away (two tilted discs on bending pins: a lag of 3e3 rad).
        // Such an angle is solved again from nothing before it is said to fail.
        return solve_coupled(discs, phi, work).or_else(|failure| {
            let mut cold = CoupledWork::new(discs);
            let gamma = solve_coupled(discs, phi, &mut cold).map_err(|_| failure)?;
            *work = cold;
            Ok(gamma)
        });
    }
    solve_into(&discs.models[0], phi + discs.phases[0], &mut work.works[0])?;
    Ok(output_lag(&work.works[0]))
}

/// The lean first-order kernel of each disc (`FirstOrderSweep`), where it applies to every
/// disc (first-order geometry, the linear law, a rigid bearing): each disc is solved at the
/// shares extrapolated from the last angles, and the Newton on the shares, weighted by each
/// kernel's own compliance at its solution, corrects them until the split settles
/// (`discs::converged`); an angle it does not settle goes to the coupled solve. One per
/// worker's run of chunks (rayon's `map_init`), restarted at every chunk (`Lean::restart`):
/// its kernels and scratch space are built once for the chunks a worker takes in a row.
struct Lean<'a> {
    /// Every disc's kernel and state, or none: the lean path needs them all.
    discs: Vec<LeanDisc<'a>>,
    /// The crank distance over which the shares' history extrapolates (`Model::warm_reach`).
    reach: f64,
    /// The Newton's tolerance on a share's correction, N·mm: a quarter of the coupled solve's,
    /// as the compliances are exact on each disc's contact set only (a contact that opens or
    /// closes within the step changes a disc's slope by ±50 %).
    tol: f64,
}

/// One disc's lean kernel and what it carries along a chunk.
struct LeanDisc<'a> {
    kernel: FirstOrderSweep<'a>,
    scratch: Scratch,
    bearing_angle: NearbyAtan2,
    crank_direction: NearbySinCos,
    /// The disc's own crank angles over the chunk (φ + its phase), for its screen of the
    /// rollers that may touch over the angles ahead (`FirstOrderSweep::screen`).
    cranks: Vec<f64>,
    /// The disc's torque, output lag and stiffness there, for the Newton on the shares.
    share: Share,
}

/// Newton steps on the shares that the lean kernels take at one angle before the coupled
/// solve takes over: one when the extrapolated split holds, two when the shares move and no
/// contact changes (the first-order balance is linear on a contact set, and the kernels'
/// compliances are its slopes), three when one contact changes on the way.
const LEAN_STEPS: usize = 3;

impl LeanDisc<'_> {
    /// Angle k by the kernel at its share's torque, its screen renewed when it lapsed: the
    /// angle recorded in `rows` (a later Newton step at the angle records it again), and the
    /// share's output lag γk = βk + βo,k (rad) and stiffness 1/ck (N·mm/rad) set. `None` where
    /// the kernel leaves the angle to the general solve; else whether the disc has a contact
    /// (a compliance of its own).
    fn solve(
        &mut self,
        (model, work): (&Model, &Work),
        k: usize,
        rows: &mut Chunk<'_>,
    ) -> Option<bool> {
        let phi = self.cranks[k];
        let (sin, cos) = self.crank_direction.sin_cos(phi);
        let guess = || work.guess(phi, model);
        self.kernel.set_torque(self.share.torque);
        let s = self
            .kernel
            .solve(phi, (cos, sin), guess, &mut self.scratch, &mut rows.row(k))?;
        if !self.scratch.screened() {
            let ahead = &self.cranks[k + 1..];
            self.kernel.screen(ahead, s.lag_rad, &mut self.scratch);
        }
        rows.record_first_order(k, Vec2::new(cos, sin), &s, &mut self.bearing_angle);
        // The kernel's own compliance on its contact set: exact until a contact changes.
        let c = s.compliance_rad_per_nmm;
        (self.share.lag, self.share.weight) = (s.lag_rad + s.output_lag_rad, 1.0 / c);
        Some(c.is_finite())
    }
}

impl<'a> Lean<'a> {
    fn new(discs: &'a Discs) -> Self {
        let kernels: Option<Vec<FirstOrderSweep<'a>>> =
            discs.models.iter().map(FirstOrderSweep::new).collect();
        let disc = |kernel| LeanDisc {
            kernel,
            scratch: Scratch::default(),
            bearing_angle: NearbyAtan2::default(),
            crank_direction: NearbySinCos::default(),
            cranks: Vec::with_capacity(CHUNK),
            share: Share::default(),
        };
        Lean {
            discs: kernels.unwrap_or_default().into_iter().map(disc).collect(),
            reach: discs.models[0].warm_reach(),
            tol: 2.5 * discs.models[0].settings.rel_tol * discs.torque_nmm.abs(),
        }
    }

    /// Start the chunk of crank angles `crank_rad`: each disc's angles, and every state a
    /// previous chunk left (active sets, screens, the rotations followed) forgotten, so that
    /// a chunk's results do not depend on which chunks its worker solved before.
    fn restart(&mut self, discs: &Discs, crank_rad: &[f64]) {
        for (disc, phase) in self.discs.iter_mut().zip(&discs.phases) {
            disc.cranks.clear();
            disc.cranks.extend(crank_rad.iter().map(|c| c + phase));
            disc.scratch.restart();
            disc.bearing_angle = NearbyAtan2::default();
            disc.crank_direction = NearbySinCos::default();
        }
    }

    /// Every disc at angle k at its share's torque (`LeanDisc::solve`), or `None` when one
    /// leaves the angle to the coupled solve or has no contact (no compliance of its own).
    fn solve_discs(
        &mut self,
        discs: &Discs,
        k: usize,
        work: &CoupledWork,
        chunk: &mut DiscChunk<'_>,
    ) -> Option<()> {
        let per_disc = self
            .discs
            .iter_mut()
            .zip(discs.models.iter().zip(&work.works))
            .zip(&mut chunk.discs);
        for ((disc, solver), rows) in per_disc {
            disc.solve(solver, k, rows)?.then_some(())?;
        }
        Some(())
    }

    /// The discs' shares in the Newton.
    fn shares(&self) -> impl Iterator<Item = Share> + '_ {
        self.discs.iter().map(|d| d.share)
    }

    /// Angle k (crank `phi`) by the kernels at the shares extrapolated from the last angles,
    /// corrected by the Newton on the shares until the split settles: γ, each disc recorded in
    /// `chunk` and remembered in `work`. `None` (the chunk's entries at k cleared) leaves the
    /// angle to the coupled solve. One disc has no split to settle (`solve_alone`).
    fn solve(
        &mut self,
        discs: &Discs,
        phi: f64,
        k: usize,
        work: &mut CoupledWork,
        chunk: &mut DiscChunk<'_>,
    ) -> Option<f64> {
        let n = self.discs.len();
        if n < 2 {
            return self.solve_alone(discs, k, work, chunk);
        }
        let (total, tol) = (discs.torque_nmm, self.tol);
        let weights = work.extrapolation(phi, self.reach);
        for (d, disc) in self.discs.iter_mut().enumerate() {
            disc.share.torque = work.share_guess(d, weights, n, total);
        }
        let mut common = None;
        for step_number in 0..LEAN_STEPS {
            if step_number > 0 {
                chunk.discs.iter_mut().for_each(|c| c.clear(k));
            }
            if self.solve_discs(discs, k, work, chunk).is_none() {
                break;
            }
            let c = common_lag(self.shares(), total);
            if converged(self.shares(), c, tol) {
                common = Some(c);
                break;
            }
            for disc in &mut self.discs {
                disc.share.torque += disc.share.step(c);
            }
            // A share against the torque sends its disc across its backlash: the coupled
            // solve handles that.
            if self.shares().any(|s| s.torque * total < 0.0) {
                break;
            }
        }
        let Some(common) = common else {
            chunk.discs.iter_mut().for_each(|c| c.clear(k));
            return None;
        };
        let per_disc = self
            .discs
            .iter_mut()
            .zip(&mut chunk.discs)
            .zip(&mut chunk.torque)
            .zip(&mut work.works);
        for (((disc, rows), shares), w) in per_disc {
            shares[k] = disc.share.torque;
            w.remember_lags(
                disc.cranks[k],
                (rows.lag[k], rows.output_lag[k]),
                disc.share.torque,
            );
        }
        // The Newton's next split (`CoupledWork::remember_split` says why).
        let next = self.shares().map(|s| s.torque + s.step(common));
        work.remember_split(phi, next, total);
        Some(common)
    }

    /// Angle k of one disc (none: no kernel), which carries the whole torque: its kernel at
    /// that torque, with no Newton on the shares and no split to remember; γ is the disc's own
    /// β + βo (a disc without contact has no compliance, and needs none). `None` (its entries
    /// at k cleared) leaves the angle to the general solve.
    fn solve_alone(
        &mut self,
        discs: &Discs,
        k: usize,
        work: &mut CoupledWork,
        chunk: &mut DiscChunk<'_>,
    ) -> Option<f64> {
        let (disc, rows) = (self.discs.first_mut()?, &mut chunk.discs[0]);
        let total = discs.torque_nmm;
        disc.share.torque = total;
        if disc
            .solve((&discs.models[0], &work.works[0]), k, rows)
            .is_none()
        {
            rows.clear(k);
            return None;
        }
        chunk.torque[0][k] = total;
        let lags = (rows.lag[k], rows.output_lag[k]);
        work.works[0].remember_lags(disc.cranks[k], lags, total);
        Some(disc.share.lag)
    }
}

/// The chunks of a sweep of several discs the general coupled solve takes (no lean kernels) in
/// two waves: the even chunks from no history, then each odd chunk continuing the split of the
/// even chunk before it. A chunk's first angles otherwise guess the split from fewer than the
/// four angles the Newton on the shares needs to settle in one step (at the first, an equal
/// split), and each further step there is a disc solve over every roller. The waves are fixed
/// by the chunks' order, so results do not depend on the thread count. The lean kernels run
/// in one wave: their extra steps at chunk starts are no dearer than a second wave's
/// bookkeeping; so does one disc, which has no split to carry.
fn solve_in_two_waves(
    discs: &Discs,
    crank_rad: &[f64],
    per_chunk: Vec<DiscChunk<'_>>,
    progress: &dyn Progress,
) -> Result<(), SweepFailure> {
    let (even, odd): (Vec<_>, Vec<_>) = crank_rad
        .chunks(CHUNK)
        .zip(per_chunk)
        .enumerate()
        .partition(|(i, _)| i % 2 == 0);
    // Chunk i continues from before[i / 2] where given: the even chunk before an odd one.
    let wave = |jobs: Vec<(usize, (&[f64], DiscChunk<'_>))>,
                before: &[Result<CoupledWork, SweepFailure>]| {
        let done: Vec<Result<CoupledWork, SweepFailure>> = jobs
            .into_par_iter()
            .map(|(i, (c, mut chunk))| {
                let from = before.get(i / 2).and_then(|b| b.as_ref().ok());
                // No kernels: a disc's model needs the general solve (`sweep_discs`).
                let done = solve_chunk(discs, c, &mut chunk, (&mut Lean::new(discs), from));
                progress.advance(c.len() as u64);
                done
            })
            .collect();
        done
    };
    let first = wave(even, &[]);
    let second = wave(odd, &first);
    // The first failure in crank order: chunk i is first[i / 2] or second[i / 2].
    let mut second = second.into_iter();
    for done in first {
        done?;
        second.next().transpose()?;
    }
    Ok(())
}

/// The loaded sweep of a reducer of `count` discs (each disc as `model`, the scene's model of
/// the disc at phase 0, at its crank phase 2πk/N): the one entry of a scene's loaded run,
/// whatever N ≥ 1 (`sweep_discs`; the spec refuses no disc). One disc carries the whole torque
/// at every angle: its torque share is T and its output lag γ = β + βo is the reducer's.
pub fn sweep_reducer(
    model: &Model,
    count: usize,
    crank_rad: &[f64],
    (periodic, progress): (bool, &dyn Progress),
) -> Result<DiscSweeps, SweepFailure> {
    sweep_discs(&Discs::new(model, count), crank_rad, periodic, progress)
}

/// Solve the discs at every crank angle and collect their curves. Chunks of `CHUNK` angles run
/// in parallel; within a chunk each angle is warm-started from the previous ones (split and
/// lags), and from nothing before the chunk but, with several discs on the general solve, the
/// split of the chunk before it (`solve_in_two_waves`): results do not depend on how chunks
/// are shared out, nor on the thread count (scratch space is reused across chunks, its state
/// restarted). A failure is reported at the first crank angle that fails; `progress` hears of
/// every chunk of crank angles done.
pub fn sweep_discs(
    discs: &Discs,
    crank_rad: &[f64],
    periodic: bool,
    progress: &dyn Progress,
) -> Result<DiscSweeps, SweepFailure> {
    let n = crank_rad.len();
    let chunks = n.div_ceil(CHUNK);
    let mut columns: Vec<Columns> = discs.models.iter().map(|m| Columns::new(m, n)).collect();
    let mut torque = vec![vec![0.0; n]; discs.count()];
    let mut output_lag = vec![0.0; n];
    let mut per_chunk: Vec<DiscChunk<'_>> = piece_rows(&mut torque, chunks, 1)
        .into_iter()
        .zip(pieces(&mut output_lag))
        .map(|(torque, output_lag)| DiscChunk {
            discs: Vec::new(),
            torque,
            output_lag,
        })
        .collect();
    for disc_columns in &mut columns {
        for (chunk, rows) in per_chunk.iter_mut().zip(disc_columns.chunks()) {
            chunk.discs.push(rows);
        }
    }
    if discs.count() == 1 || discs.models.iter().all(FirstOrderSweep::applies) {
        let outcomes: Vec<Result<(), SweepFailure>> = crank_rad
            .par_chunks(CHUNK)
            .zip(per_chunk)
            .map_init(
                || Lean::new(discs),
                |lean, (c, mut chunk)| {
                    let done = solve_chunk(discs, c, &mut chunk, (lean, None)).map(drop);
                    progress.advance(c.len() as u64);
                    done
                },
            )
            .collect();
        outcomes.into_iter().collect::<Result<(), _>>()?;
    } else {
        solve_in_two_waves(discs, crank_rad, per_chunk, progress)?;
    }
    let model = &discs.models[0];
    let transmission = model
        .rollers
        .is_some()
        .then(|| transmission(output_lag, crank_rad, model.teeth, periodic));
    let discs = discs
        .models
        .iter()
        .zip(columns)
        .map(|(m, c)| disc_curves(m, c))
        .collect();
    Ok(DiscSweeps {
        discs,
        torque_nmm: torque,
        transmission,
    })
}
