//! The loaded sweep over the crank angles of a scene (one angle's solve is `angle`), and its
//! curves: lags, forces, pressures, bearing force, TE and ratio.
//! Arrays are [angle] or [roller|pin][angle]; engine units (rad, N, MPa, mm).

use super::angle::solve_into;
use super::discs::{common_lag, converged, solve_coupled, CoupledWork, Discs, Share};
use super::first_order_sweep::{FirstOrderSweep, Row, Scratch, Summary};
use super::loaded::{AngleSolution, Model};
use super::solve::SolveFailure;
use super::work::Work;
use crate::geometry::{cross, NearbyAtan2, NearbySinCos, Vec2};
use crate::model::results::{BearingCurves, LoadedSweep, PinCurves, RollerCurves, Transmission};
use crate::progress::{Progress, Silent};
use rayon::prelude::*;

/// Crank angles solved in sequence by one worker, warm-starting each from the previous. The
/// chunk size is fixed (not derived from the thread count) so results are the same bit for bit
/// however many threads run them.
pub const CHUNK: usize = 64;

/// A solve that failed, with the crank angle it failed at.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepFailure {
    pub crank_rad: f64,
    pub failure: SolveFailure,
}

fn all_finite(sol: &AngleSolution) -> bool {
    let r = sol
        .rollers
        .iter()
        .all(|s| s.force_n.is_finite() && s.gap_mm.is_finite());
    let p = sol
        .pins
        .iter()
        .all(|s| s.force_n.is_finite() && s.gap_mm.is_finite());
    let b = sol
        .bearing_force_n
        .is_none_or(|f| f.x.is_finite() && f.y.is_finite());
    r && p
        && b
        && sol.lag_rad.is_none_or(f64::is_finite)
        && sol.output_lag_rad.is_none_or(f64::is_finite)
}

/// dδ/dφ at every sample (uniform spacing h).
pub fn derivative(values: &[f64], h: f64, periodic: bool) -> Option<Vec<f64>> {
    let n = values.len();
    if n < 3 {
        return None;
    }
    let (first, last) = if periodic {
        (
            (values[1] - values[n - 1]) / (2.0 * h),
            (values[0] - values[n - 2]) / (2.0 * h),
        )
    } else {
        (
            (-3.0 * values[0] + 4.0 * values[1] - values[2]) / (2.0 * h),
            (3.0 * values[n - 1] - 4.0 * values[n - 2] + values[n - 3]) / (2.0 * h),
        )
    };
    let mut d = Vec::with_capacity(n);
    d.push(first);
    d.extend(values.windows(3).map(|w| (w[2] - w[0]) / (2.0 * h)));
    d.push(last);
    Some(d)
}

/// The curves of a sweep as columns [angle] and [roller|pin][angle], allocated once and
/// written in place by the chunks (`Columns::chunks`).
struct Columns {
    lag: Vec<f64>,
    output_lag: Vec<f64>,
    roller_force: Vec<Vec<f64>>,
    pressure: Vec<Vec<f64>>,
    half_width: Vec<Vec<f64>>,
    contacts: Vec<usize>,
    pin_force: Vec<Vec<f64>>,
    bearing_force: Vec<f64>,
    /// Angle of the bearing force from the eccentric direction, rad.
    bearing_angle: Vec<f64>,
    residual: Vec<f64>,
    deflection: Vec<f64>,
}

/// One chunk's rows of every column: `Columns` cut at the same angles.
struct Chunk<'a> {
    lag: &'a mut [f64],
    output_lag: &'a mut [f64],
    roller_force: Vec<&'a mut [f64]>,
    pressure: Vec<&'a mut [f64]>,
    half_width: Vec<&'a mut [f64]>,
    contacts: &'a mut [usize],
    pin_force: Vec<&'a mut [f64]>,
    bearing_force: &'a mut [f64],
    bearing_angle: &'a mut [f64],
    residual: &'a mut [f64],
    deflection: &'a mut [f64],
}

/// Angle of a force from the eccentric direction e_φ, counter-clockwise, rad.
fn angle_from(e_phi: Vec2, f: Vec2) -> f64 {
    cross(e_phi, f).atan2(e_phi.dot(&f))
}

/// `column` cut into pieces of `CHUNK` angles.
fn pieces<T>(column: &mut [T]) -> std::slice::ChunksMut<'_, T> {
    column.chunks_mut(CHUNK)
}

/// [column][angle] cut into [chunk][column] pieces of `CHUNK` angles (`chunks` of them).
fn piece_rows(columns: &mut [Vec<f64>], chunks: usize) -> Vec<Vec<&mut [f64]>> {
    let width = columns.len();
    let mut rows: Vec<Vec<&mut [f64]>> = (0..chunks).map(|_| Vec::with_capacity(width)).collect();
    for column in columns {
        for (row, piece) in rows.iter_mut().zip(pieces(column)) {
            row.push(piece);
        }
    }
    rows
}

impl Columns {
    fn new(model: &Model, angles: usize) -> Self {
        let rollers = model.rollers.as_ref().map_or(0, |r| r.count());
        let pins = model.pins.as_ref().map_or(0, |p| p.count);
        let column = || vec![0.0; angles];
        Columns {
            lag: column(),
            output_lag: column(),
            roller_force: (0..rollers).map(|_| column()).collect(),
            pressure: (0..rollers).map(|_| column()).collect(),
            half_width: (0..rollers).map(|_| column()).collect(),
            contacts: vec![0; angles],
            pin_force: (0..pins).map(|_| column()).collect(),
            bearing_force: column(),
            bearing_angle: column(),
            residual: column(),
            deflection: column(),
        }
    }

    /// The chunks of `CHUNK` angles, in order.
    fn chunks(&mut self) -> Vec<Chunk<'_>> {
        let n = self.lag.len().div_ceil(CHUNK);
        let mut roller_force = piece_rows(&mut self.roller_force, n).into_iter();
        let mut pressure = piece_rows(&mut self.pressure, n).into_iter();
        let mut half_width = piece_rows(&mut self.half_width, n).into_iter();
        let mut pin_force = piece_rows(&mut self.pin_force, n).into_iter();
        let scalars = pieces(&mut self.lag)
            .zip(pieces(&mut self.output_lag))
            .zip(pieces(&mut self.contacts))
            .zip(pieces(&mut self.bearing_force))
            .zip(pieces(&mut self.bearing_angle))
            .zip(pieces(&mut self.residual))
            .zip(pieces(&mut self.deflection));
        scalars
            .map(
                |(
                    (((((lag, output_lag), contacts), bearing_force), bearing_angle), residual),
                    deflection,
                )| Chunk {
                    lag,
                    output_lag,
                    roller_force: roller_force.next().unwrap_or_default(),
                    pressure: pressure.next().unwrap_or_default(),
                    half_width: half_width.next().unwrap_or_default(),
                    contacts,
                    pin_force: pin_force.next().unwrap_or_default(),
                    bearing_force,
                    bearing_angle,
                    residual,
                    deflection,
                },
            )
            .collect()
    }
}

impl<'a> Chunk<'a> {
    /// Zero the per-roller and per-pin entries of angle k (a lean solve writes only those in
    /// contact, into entries that must start at zero).
    fn clear(&mut self, k: usize) {
        let columns = [
            &mut self.roller_force,
            &mut self.pressure,
            &mut self.half_width,
            &mut self.pin_force,
        ];
        for column in columns {
            column.iter_mut().for_each(|c| c[k] = 0.0);
        }
    }

    /// The per-roller and per-pin entries of angle k, for the lean sweep to write in place.
    fn row(&mut self, k: usize) -> Row<'_, 'a> {
        Row {
            k,
            roller_force_n: &mut self.roller_force,
            pressure_mpa: &mut self.pressure,
            half_width_mm: &mut self.half_width,
            pin_force_n: &mut self.pin_force,
        }
    }

    /// Record the bearing force at angle k, its angle from e_φ and the residual.
    fn record_bearing(&mut self, k: usize, bearing: Vec2, angle: f64, residual: f64) {
        self.bearing_force[k] = bearing.norm();
        self.bearing_angle[k] = angle;
        self.residual[k] = residual;
    }

    /// Record the rest of angle k of the lean first-order sweep (its row is written), with
    /// the bearing force's angle from `bearing_angle`, which follows the force along the chunk.
    fn record_first_order(
        &mut self,
        k: usize,
        e_phi: Vec2,
        s: &Summary,
        bearing_angle: &mut NearbyAtan2,
    ) {
        self.lag[k] = s.lag_rad;
        self.output_lag[k] = s.output_lag_rad;
        self.contacts[k] = s.contacts;
        let f = s.bearing_n;
        let angle = bearing_angle.atan2(cross(e_phi, f), e_phi.dot(&f));
        self.record_bearing(k, f, angle, s.residual);
    }

    /// Record angle k of the general solve.
    fn record(&mut self, k: usize, model: &Model, e_phi: Vec2, sol: &AngleSolution) {
        self.lag[k] = sol.lag_rad.unwrap_or(0.0);
        self.output_lag[k] = sol.output_lag_rad.unwrap_or(0.0);
        if let Some(r) = &model.rollers {
            let mut contacts = 0;
            for (i, s) in sol.rollers.iter().enumerate() {
                self.roller_force[i][k] = s.force_n;
                let (p, b) = if s.force_n > 0.0 {
                    contacts += 1;
                    let h = r.hertz(s);
                    (h.peak_pressure_mpa, h.half_width_mm)
                } else {
                    (0.0, 0.0)
                };
                self.pressure[i][k] = p;
                self.half_width[i][k] = b;
            }
            self.contacts[k] = contacts;
        }
        for (j, p) in sol.pins.iter().enumerate() {
            self.pin_force[j][k] = p.force_n;
        }
        let bearing = sol.bearing_force_n.unwrap_or_default();
        let angle = angle_from(e_phi, bearing);
        self.record_bearing(k, bearing, angle, sol.residual.unwrap_or(0.0));
        self.deflection[k] = sol.centre_offset_mm.norm();
    }
}

fn solve_chunk(
    model: &Model,
    lean: Option<&FirstOrderSweep<'_>>,
    crank_rad: &[f64],
    chunk: &mut Chunk<'_>,
    scratch: &mut Scratch,
) -> Result<(), SweepFailure> {
    let mut work = Work::default();
    scratch.restart();
    let mut crank_direction = NearbySinCos::default();
    let mut bearing_angle = NearbyAtan2::default();
    for (k, &phi) in crank_rad.iter().enumerate() {
        if let Some(lean) = lean {
            let (sin, cos) = crank_direction.sin_cos(phi);
            let e_phi = Vec2::new(cos, sin);
            let guess = || work.guess(phi, model);
            if let Some(s) = lean.solve(phi, (cos, sin), guess, scratch, &mut chunk.row(k)) {
                chunk.record_first_order(k, e_phi, &s, &mut bearing_angle);
                if !scratch.screened() {
                    lean.screen(&crank_rad[k + 1..], s.lag_rad, scratch);
                }
                // The lags from the recorded entries: loading them from `s` as a pair stalls
                // on the two separate stores that wrote them.
                work.remember_lags(phi, (chunk.lag[k], chunk.output_lag[k]), model.torque_nmm);
                continue;
            }
        }
        let fail = |failure| SweepFailure {
            crank_rad: phi,
            failure,
        };
        solve_into(model, phi, &mut work).map_err(fail)?;
        if !all_finite(&work.sol) {
            return Err(fail(SolveFailure::NonFinite {
                x: work.sol.lag_rad.unwrap_or(0.0),
            }));
        }
        chunk.record(k, model, work.e_phi, &work.sol);
    }
    Ok(())
}

/// Solve every crank angle and collect the curves. Chunks of `CHUNK` angles run in parallel;
/// within a chunk each angle is warm-started from the previous ones, and from nothing before
/// the chunk, so results do not depend on how chunks are shared out (scratch space is reused
/// across chunks, its state restarted). A failure is reported at the first crank angle that
/// fails.
pub fn sweep(
    model: &Model,
    crank_rad: &[f64],
    periodic: bool,
) -> Result<LoadedSweep, SweepFailure> {
    sweep_observed(model, crank_rad, periodic, &Silent)
}

/// `sweep`, telling `progress` of every chunk of crank angles done.
pub fn sweep_observed(
    model: &Model,
    crank_rad: &[f64],
    periodic: bool,
    progress: &dyn Progress,
) -> Result<LoadedSweep, SweepFailure> {
    let mut columns = Columns::new(model, crank_rad.len());
    let lean = FirstOrderSweep::new(model);
    let outcomes: Vec<Result<(), SweepFailure>> = crank_rad
        .par_chunks(CHUNK)
        .zip(columns.chunks())
        .map_init(Scratch::default, |scratch, (c, mut chunk)| {
            let done = solve_chunk(model, lean.as_ref(), c, &mut chunk, scratch);
            progress.advance(c.len() as u64);
            done
        })
        .collect();
    outcomes.into_iter().collect::<Result<(), _>>()?;
    Ok(collect(model, crank_rad, columns, periodic))
}

/// The transmission of a sweep from its TE (rad) at `crank_rad`: κ = 1/(1/nc − dδ/dφ).
fn transmission(te_rad: Vec<f64>, crank_rad: &[f64], teeth: usize, periodic: bool) -> Transmission {
    let h = match crank_rad {
        [a, b, ..] => b - a,
        _ => 1.0,
    };
    let nc = teeth as f64;
    let ratio = derivative(&te_rad, h, periodic)
        .map(|d| d.iter().map(|dd| 1.0 / (1.0 / nc - dd)).collect());
    Transmission { te_rad, ratio }
}

fn collect(model: &Model, crank_rad: &[f64], columns: Columns, periodic: bool) -> LoadedSweep {
    let te_rad = model.rollers.is_some().then(|| {
        let c = &columns;
        c.lag
            .iter()
            .zip(&c.output_lag)
            .map(|(b, o)| b + o)
            .collect()
    });
    LoadedSweep {
        transmission: te_rad.map(|te| transmission(te, crank_rad, model.teeth, periodic)),
        ..disc_curves(model, columns)
    }
}

/// A disc's own curves from its columns: lags, forces, bearing (no transmission: with several
/// discs that is the reducer's, from the common output lag).
fn disc_curves(model: &Model, c: Columns) -> LoadedSweep {
    LoadedSweep {
        rollers: model.rollers.as_ref().map(|_| RollerCurves {
            lag_rad: c.lag,
            force_n: c.roller_force,
            pressure_mpa: c.pressure,
            half_width_mm: c.half_width,
            contacts: c.contacts,
        }),
        pins: model.pins.as_ref().map(|_| PinCurves {
            output_lag_rad: c.output_lag,
            force_n: c.pin_force,
        }),
        bearing: model.bearing.then_some(BearingCurves {
            force_n: c.bearing_force,
            angle_rad: c.bearing_angle,
            residual: c.residual,
            deflection_mm: c.deflection,
        }),
        ..LoadedSweep::default()
    }
}

/// A sweep of several discs (`discs::solve_coupled` at every crank angle): each disc's curves
/// (its lags, forces, bearing; no transmission of its own) and torque share, and the
/// reducer's transmission from the common output lag γ.
#[derive(Debug, Clone)]
pub struct DiscSweeps {
    pub discs: Vec<LoadedSweep>,
    /// Disc k's share of the output torque, N·mm, [disc][angle].
    pub torque_nmm: Vec<Vec<f64>>,
    pub transmission: Option<Transmission>,
}

/// One chunk of a several-disc sweep: each disc's rows, its torque share and γ.
struct DiscChunk<'a> {
    discs: Vec<Chunk<'a>>,
    torque: Vec<&'a mut [f64]>,
    output_lag: &'a mut [f64],
}

fn solve_disc_chunk(
    discs: &Discs,
    crank_rad: &[f64],
    chunk: &mut DiscChunk<'_>,
    lean: &mut Lean<'_>,
) -> Result<(), SweepFailure> {
    let mut work = CoupledWork::new(discs);
    lean.restart(discs, crank_rad);
    for (k, &phi) in crank_rad.iter().enumerate() {
        if let Some(gamma) = lean.solve(discs, phi, k, &mut work, chunk) {
            chunk.output_lag[k] = gamma;
            continue;
        }
        record_coupled(discs, (k, phi), &mut work, chunk)?;
    }
    Ok(())
}

/// Angle k (crank `phi`) by the general coupled solve (`discs::solve_coupled`), recorded in
/// `chunk`.
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
    chunk.output_lag[k] = solve_coupled(discs, phi, work).map_err(fail)?;
    for (d, rows) in chunk.discs.iter_mut().enumerate() {
        let (model, w) = (&work.models[d], &work.works[d]);
        if !all_finite(&w.sol) {
            return Err(fail(SolveFailure::NonFinite {
                x: w.sol.lag_rad.unwrap_or(0.0),
            }));
        }
        rows.record(k, model, w.e_phi, &w.sol);
        chunk.torque[d][k] = model.torque_nmm;
    }
    Ok(())
}

/// A chunk of angles of several discs by the general coupled solve alone, its split guessed
/// at the first angles from `before` (the chunk before it) where given: its work, whose
/// split the next chunk continues from.
fn solve_coupled_chunk(
    discs: &Discs,
    crank_rad: &[f64],
    chunk: &mut DiscChunk<'_>,
    before: Option<&CoupledWork>,
) -> Result<CoupledWork, SweepFailure> {
    let mut work = CoupledWork::new(discs);
    if let Some(before) = before {
        work.continue_from(before);
    }
    for (k, &phi) in crank_rad.iter().enumerate() {
        record_coupled(discs, (k, phi), &mut work, chunk)?;
    }
    Ok(work)
}

/// The lean first-order kernel of each disc (`FirstOrderSweep`), where it applies to every
/// disc (first-order geometry, the linear law, a rigid bearing): each disc is solved at the
/// shares extrapolated from the last angles, and the Newton on the shares, weighted by each
/// kernel's own compliance at its solution, corrects them until the split settles
/// (`discs::converged`); an angle it does not settle goes to the coupled solve. One per
/// worker, restarted at every chunk (`Lean::restart`): its kernels and scratch space are
/// built once per sweep.
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
    /// share's output lag γk (rad) and stiffness 1/ck (N·mm/rad) set. `None` where the kernel
    /// leaves the angle to the general solve, or the disc has no contact (no compliance of its
    /// own).
    fn solve(
        &mut self,
        (model, work): (&Model, &Work),
        k: usize,
        rows: &mut Chunk<'_>,
    ) -> Option<()> {
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
        c.is_finite().then_some(())
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
    /// leaves the angle to the coupled solve.
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
            disc.solve(solver, k, rows)?;
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
    /// angle to the coupled solve.
    fn solve(
        &mut self,
        discs: &Discs,
        phi: f64,
        k: usize,
        work: &mut CoupledWork,
        chunk: &mut DiscChunk<'_>,
    ) -> Option<f64> {
        let n = self.discs.len();
        if n == 0 {
            return None;
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
}

/// The chunks of a sweep the general coupled solve takes (no lean kernels) in two waves: the
/// even chunks from no history, then each odd chunk continuing the split of the even chunk
/// before it. A chunk's first angles otherwise guess the split from fewer than the four
/// angles the Newton on the shares needs to settle in one step (at the first, an equal
/// split), and each further step there is a disc solve over every roller: on 11 rollers in
/// exact geometry the chunk starts held 85 % of the sweep's second steps. The waves are fixed
/// by the chunks' order, so results do not depend on the thread count. (The lean kernels'
/// extra steps at chunk starts cost about what a second wave's bookkeeping does; they run in
/// one wave.)
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
                let done = solve_coupled_chunk(discs, c, &mut chunk, from);
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

/// `sweep_observed` of several discs: chunks of `CHUNK` angles in parallel, each angle
/// warm-started from the previous ones of its chunk (split and lags), so results do not
/// depend on the thread count.
pub fn sweep_discs_observed(
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
    let mut per_chunk: Vec<DiscChunk<'_>> = piece_rows(&mut torque, chunks)
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
    if discs.models.iter().all(FirstOrderSweep::applies) {
        let outcomes: Vec<Result<(), SweepFailure>> = crank_rad
            .par_chunks(CHUNK)
            .zip(per_chunk)
            .map_init(
                || Lean::new(discs),
                |lean, (c, mut chunk)| {
                    let done = solve_disc_chunk(discs, c, &mut chunk, lean);
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
