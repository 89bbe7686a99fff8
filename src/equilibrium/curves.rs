//! Curves of a loaded sweep: lags, forces, pressures, bearing force, TE and ratio.
//! Arrays are [angle] or [roller|pin][angle]; engine units (rad, N, MPa, mm).

use super::first_order_sweep::{FirstOrderSweep, Row, Scratch, Summary};
use super::solve::SolveFailure;
use super::sweep::{solve_into, AngleSolution, Model, Work};
use crate::geometry::{cross, Vec2};
use rayon::prelude::*;

/// Crank angles solved in sequence by one worker, warm-starting each from the previous. The
/// chunk size is fixed (not derived from the thread count) so results are the same bit for bit
/// however many threads run them.
pub const CHUNK: usize = 64;

/// Roller contact over the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct RollerCurves {
    /// β: lag of the disc behind −φ/nc, rad (positive opposes the motion).
    pub lag_rad: Vec<f64>,
    pub force_n: Vec<Vec<f64>>,
    pub pressure_mpa: Vec<Vec<f64>>,
    pub half_width_mm: Vec<Vec<f64>>,
    pub contacts: Vec<usize>,
}

/// Output pins over the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct PinCurves {
    /// βo: lag of the output behind the disc, rad.
    pub output_lag_rad: Vec<f64>,
    pub force_n: Vec<Vec<f64>>,
}

/// Crank bearing over the sweep: force magnitude, its angle ε from the eccentric direction
/// (counter-clockwise), and the relative residual of the paper's Eqs. 12–14.
#[derive(Debug, Clone, PartialEq)]
pub struct BearingCurves {
    pub force_n: Vec<f64>,
    pub angle_rad: Vec<f64>,
    pub residual: Vec<f64>,
    /// Disc-centre displacement magnitude (compliant bearing; zeros when rigid), mm.
    pub deflection_mm: Vec<f64>,
}

/// Loaded transmission error δ = β + βo (rad; βo = 0 when the pins are not modelled) and the
/// ratio κ = dφ/dφout = 1/(1/nc − dδ/dφ), by central differences (periodic when the sweep
/// covers whole mesh periods, second-order one-sided at the ends otherwise).
#[derive(Debug, Clone, PartialEq)]
pub struct Transmission {
    pub te_rad: Vec<f64>,
    pub ratio: Option<Vec<f64>>,
}

#[derive(Debug, Clone, PartialEq, Default)]
pub struct LoadedSweep {
    pub rollers: Option<RollerCurves>,
    pub pins: Option<PinCurves>,
    pub bearing: Option<BearingCurves>,
    pub transmission: Option<Transmission>,
}

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
    Some(
        (0..n)
            .map(|k| {
                if periodic {
                    (values[(k + 1) % n] - values[(k + n - 1) % n]) / (2.0 * h)
                } else if k == 0 {
                    (-3.0 * values[0] + 4.0 * values[1] - values[2]) / (2.0 * h)
                } else if k == n - 1 {
                    (3.0 * values[n - 1] - 4.0 * values[n - 2] + values[n - 3]) / (2.0 * h)
                } else {
                    (values[k + 1] - values[k - 1]) / (2.0 * h)
                }
            })
            .collect(),
    )
}

/// Per-angle results of one chunk, flat and column-major: [roller][angle] and [pin][angle],
/// allocated for the whole chunk and written in place.
struct Chunk {
    angles: usize,
    rollers: usize,
    pins: usize,
    lag: Vec<f64>,
    output_lag: Vec<f64>,
    roller_force: Vec<f64>,
    pressure: Vec<f64>,
    half_width: Vec<f64>,
    contacts: Vec<usize>,
    pin_force: Vec<f64>,
    bearing: Vec<Vec2>,
    /// Angle of the bearing force from the eccentric direction, rad.
    bearing_angle: Vec<f64>,
    residual: Vec<f64>,
    deflection: Vec<f64>,
}

/// Angle of a force from the eccentric direction e_φ, counter-clockwise, rad.
fn angle_from(e_phi: Vec2, f: Vec2) -> f64 {
    cross(e_phi, f).atan2(e_phi.dot(&f))
}

impl Chunk {
    fn new(model: &Model, angles: usize) -> Self {
        let rollers = model.rollers.as_ref().map_or(0, |r| r.count());
        let pins = model.pins.as_ref().map_or(0, |p| p.count);
        Chunk {
            angles,
            rollers,
            pins,
            lag: vec![0.0; angles],
            output_lag: vec![0.0; angles],
            roller_force: vec![0.0; angles * rollers],
            pressure: vec![0.0; angles * rollers],
            half_width: vec![0.0; angles * rollers],
            contacts: vec![0; angles],
            pin_force: vec![0.0; angles * pins],
            bearing: vec![Vec2::zeros(); angles],
            bearing_angle: vec![0.0; angles],
            residual: vec![0.0; angles],
            deflection: vec![0.0; angles],
        }
    }

    /// Entry k of column i of a column-major [column][angle] array.
    fn at(&self, i: usize, k: usize) -> usize {
        i * self.angles + k
    }

    /// Record angle k of the lean first-order sweep.
    fn record_first_order(&mut self, k: usize, e_phi: Vec2, row: &Row<'_>, s: &Summary) {
        for (i, &f) in row.roller_force_n.iter().enumerate() {
            let at = self.at(i, k);
            self.roller_force[at] = f;
            self.pressure[at] = row.pressure_mpa[i];
            self.half_width[at] = row.half_width_mm[i];
        }
        for (j, &f) in row.pin_force_n.iter().enumerate() {
            let at = self.at(j, k);
            self.pin_force[at] = f;
        }
        self.lag[k] = s.lag_rad;
        self.output_lag[k] = s.output_lag_rad;
        self.contacts[k] = s.contacts;
        self.bearing[k] = s.bearing_n;
        self.bearing_angle[k] = angle_from(e_phi, s.bearing_n);
        self.residual[k] = s.residual;
    }

    /// Record angle k of the general solve.
    fn record(&mut self, k: usize, model: &Model, e_phi: Vec2, sol: &AngleSolution) {
        self.lag[k] = sol.lag_rad.unwrap_or(0.0);
        self.output_lag[k] = sol.output_lag_rad.unwrap_or(0.0);
        if let Some(r) = &model.rollers {
            let mut contacts = 0;
            for (i, s) in sol.rollers.iter().enumerate() {
                let at = self.at(i, k);
                self.roller_force[at] = s.force_n;
                let (p, b) = if s.force_n > 0.0 {
                    contacts += 1;
                    let h = r.hertz(s);
                    (h.peak_pressure_mpa, h.half_width_mm)
                } else {
                    (0.0, 0.0)
                };
                self.pressure[at] = p;
                self.half_width[at] = b;
            }
            self.contacts[k] = contacts;
        }
        for (j, p) in sol.pins.iter().enumerate() {
            let at = self.at(j, k);
            self.pin_force[at] = p.force_n;
        }
        let bearing = sol.bearing_force_n.unwrap_or_default();
        self.bearing[k] = bearing;
        self.bearing_angle[k] = angle_from(e_phi, bearing);
        self.residual[k] = sol.residual.unwrap_or(0.0);
        self.deflection[k] = sol.centre_offset_mm.norm();
    }
}

fn solve_chunk(model: &Model, crank_rad: &[f64]) -> Result<Chunk, SweepFailure> {
    let mut work = Work::default();
    let mut chunk = Chunk::new(model, crank_rad.len());
    let lean = FirstOrderSweep::new(model);
    let mut scratch = Scratch::default();
    let (rollers, pins) = (chunk.rollers, chunk.pins);
    let mut entries = [vec![0.0; rollers], vec![0.0; rollers], vec![0.0; rollers]];
    let mut pin_entries = vec![0.0; pins];
    for (k, &phi) in crank_rad.iter().enumerate() {
        if let Some(lean) = &lean {
            let (sin, cos) = phi.sin_cos();
            let e_phi = Vec2::new(cos, sin);
            let guess = work.guess(phi);
            let [forces, pressures, widths] = &mut entries;
            let mut row = Row {
                roller_force_n: forces,
                pressure_mpa: pressures,
                half_width_mm: widths,
                pin_force_n: &mut pin_entries,
            };
            if let Some(s) = lean.solve(phi, e_phi, guess, &mut scratch, &mut row) {
                work.remember_lags(phi, s.lag_rad, s.output_lag_rad);
                chunk.record_first_order(k, e_phi, &row, &s);
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
    Ok(chunk)
}

/// Solve every crank angle and collect the curves. Chunks of `CHUNK` angles run in parallel;
/// within a chunk each angle is warm-started from the previous ones.
pub fn sweep(
    model: &Model,
    crank_rad: &[f64],
    periodic: bool,
) -> Result<LoadedSweep, SweepFailure> {
    let chunks: Vec<Chunk> = crank_rad
        .par_chunks(CHUNK)
        .map(|c| solve_chunk(model, c))
        .collect::<Result<_, _>>()?;
    Ok(collect(model, crank_rad, &chunks, periodic))
}

/// Column-major chunks → [column][angle].
fn columns(chunks: &[Chunk], width: usize, field: fn(&Chunk) -> &[f64]) -> Vec<Vec<f64>> {
    let rows = chunks.iter().map(|c| c.angles).sum::<usize>();
    (0..width)
        .map(|i| {
            let mut column = Vec::with_capacity(rows);
            for c in chunks {
                column.extend_from_slice(&field(c)[c.at(i, 0)..c.at(i + 1, 0)]);
            }
            column
        })
        .collect()
}

fn concat<T: Copy>(chunks: &[Chunk], field: fn(&Chunk) -> &[T]) -> Vec<T> {
    chunks
        .iter()
        .flat_map(|c| field(c).iter().copied())
        .collect()
}

fn collect(model: &Model, crank_rad: &[f64], chunks: &[Chunk], periodic: bool) -> LoadedSweep {
    let mut out = LoadedSweep::default();
    let lag = concat(chunks, |c| &c.lag);
    let output_lag = concat(chunks, |c| &c.output_lag);
    if let Some(r) = &model.rollers {
        let n = r.count();
        out.rollers = Some(RollerCurves {
            lag_rad: lag.clone(),
            force_n: columns(chunks, n, |c| &c.roller_force),
            pressure_mpa: columns(chunks, n, |c| &c.pressure),
            half_width_mm: columns(chunks, n, |c| &c.half_width),
            contacts: concat(chunks, |c| &c.contacts),
        });
    }
    if let Some(p) = &model.pins {
        out.pins = Some(PinCurves {
            output_lag_rad: output_lag.clone(),
            force_n: columns(chunks, p.count, |c| &c.pin_force),
        });
    }
    if model.bearing {
        let fb = concat(chunks, |c| &c.bearing);
        out.bearing = Some(BearingCurves {
            force_n: fb.iter().map(|f| f.norm()).collect(),
            angle_rad: concat(chunks, |c| &c.bearing_angle),
            residual: concat(chunks, |c| &c.residual),
            deflection_mm: concat(chunks, |c| &c.deflection),
        });
    }
    if model.rollers.is_some() {
        let te_rad: Vec<f64> = lag.iter().zip(&output_lag).map(|(b, o)| b + o).collect();
        let h = match crank_rad {
            [a, b, ..] => b - a,
            _ => 1.0,
        };
        let nc = model.teeth as f64;
        let ratio = derivative(&te_rad, h, periodic)
            .map(|d| d.iter().map(|dd| 1.0 / (1.0 / nc - dd)).collect());
        out.transmission = Some(Transmission { te_rad, ratio });
    }
    out
}

/// Largest entry of a [row][angle] array: (value, row, angle index). Empty gives (0, 0, 0).
pub fn max_entry(rows: &[Vec<f64>]) -> (f64, usize, usize) {
    let mut best = (f64::NEG_INFINITY, 0, 0);
    for (i, row) in rows.iter().enumerate() {
        for (k, &v) in row.iter().enumerate() {
            if v > best.0 {
                best = (v, i, k);
            }
        }
    }
    if best.0.is_finite() {
        best
    } else {
        (0.0, 0, 0)
    }
}

/// (min, max) of a curve with their indices.
pub fn extremes(values: &[f64]) -> ((f64, usize), (f64, usize)) {
    let mut lo = (f64::INFINITY, 0);
    let mut hi = (f64::NEG_INFINITY, 0);
    for (k, &v) in values.iter().enumerate() {
        if v < lo.0 {
            lo = (v, k);
        }
        if v > hi.0 {
            hi = (v, k);
        }
    }
    (lo, hi)
}

/// max − min of a curve.
pub fn fluctuation(values: &[f64]) -> f64 {
    let ((lo, _), (hi, _)) = extremes(values);
    if values.is_empty() {
        0.0
    } else {
        hi - lo
    }
}
