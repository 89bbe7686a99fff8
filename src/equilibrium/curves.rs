//! Curves of a loaded sweep: lags, forces, pressures, bearing force, TE and ratio.
//! Arrays are [angle] or [roller|pin][angle]; engine units (rad, N, MPa, mm).

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

/// Per-angle results of one chunk, flat: [angle][roller] and [angle][pin].
#[derive(Default)]
struct Chunk {
    lag: Vec<f64>,
    output_lag: Vec<f64>,
    roller_force: Vec<f64>,
    pressure: Vec<f64>,
    half_width: Vec<f64>,
    contacts: Vec<usize>,
    pin_force: Vec<f64>,
    bearing: Vec<Vec2>,
    residual: Vec<f64>,
    deflection: Vec<f64>,
}

impl Chunk {
    fn record(&mut self, model: &Model, sol: &AngleSolution) {
        self.lag.push(sol.lag_rad.unwrap_or(0.0));
        self.output_lag.push(sol.output_lag_rad.unwrap_or(0.0));
        if let Some(r) = &model.rollers {
            let mut contacts = 0;
            for s in &sol.rollers {
                self.roller_force.push(s.force_n);
                let (p, b) = if s.force_n > 0.0 {
                    contacts += 1;
                    let h = r.hertz(s);
                    (h.peak_pressure_mpa, h.half_width_mm)
                } else {
                    (0.0, 0.0)
                };
                self.pressure.push(p);
                self.half_width.push(b);
            }
            self.contacts.push(contacts);
        }
        self.pin_force.extend(sol.pins.iter().map(|p| p.force_n));
        self.bearing.push(sol.bearing_force_n.unwrap_or_default());
        self.residual.push(sol.residual.unwrap_or(0.0));
        self.deflection.push(sol.centre_offset_mm.norm());
    }
}

fn solve_chunk(model: &Model, crank_rad: &[f64]) -> Result<Chunk, SweepFailure> {
    let mut work = Work::default();
    let n = crank_rad.len();
    let rollers = model.rollers.as_ref().map_or(0, |r| r.count()) * n;
    let pins = model.pins.as_ref().map_or(0, |p| p.count) * n;
    let mut chunk = Chunk {
        lag: Vec::with_capacity(n),
        output_lag: Vec::with_capacity(n),
        roller_force: Vec::with_capacity(rollers),
        pressure: Vec::with_capacity(rollers),
        half_width: Vec::with_capacity(rollers),
        contacts: Vec::with_capacity(n),
        pin_force: Vec::with_capacity(pins),
        bearing: Vec::with_capacity(n),
        residual: Vec::with_capacity(n),
        deflection: Vec::with_capacity(n),
    };
    for &phi in crank_rad {
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
        chunk.record(model, &work.sol);
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

/// [angle][column] flat chunks → [column][angle].
fn columns(chunks: &[Chunk], width: usize, field: fn(&Chunk) -> &[f64]) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::new(); width];
    for c in chunks {
        for row in field(c).chunks(width.max(1)) {
            for (column, v) in out.iter_mut().zip(row) {
                column.push(*v);
            }
        }
    }
    out
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
            angle_rad: fb
                .iter()
                .zip(crank_rad)
                .map(|(f, &phi)| {
                    let e = Vec2::new(phi.cos(), phi.sin());
                    cross(e, *f).atan2(e.dot(f))
                })
                .collect(),
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
