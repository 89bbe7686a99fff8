//! Curves of a loaded sweep: lags, forces, pressures, bearing force, TE and ratio.
//! Arrays are [angle] or [roller|pin][angle]; engine units (rad, N, MPa, mm).

use super::solve::SolveFailure;
use super::sweep::{solve_angle, AngleSolution, Model};
use crate::geometry::{cross, Vec2};

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

/// Solve every crank angle (warm-started from the previous one) and collect the curves.
pub fn sweep(
    model: &Model,
    crank_rad: &[f64],
    periodic: bool,
) -> Result<LoadedSweep, SweepFailure> {
    let mut previous = AngleSolution::default();
    let mut solutions = Vec::with_capacity(crank_rad.len());
    for &phi in crank_rad {
        let fail = |failure| SweepFailure {
            crank_rad: phi,
            failure,
        };
        let sol = solve_angle(model, phi, &previous).map_err(fail)?;
        if !all_finite(&sol) {
            return Err(fail(SolveFailure::NonFinite {
                x: sol.lag_rad.unwrap_or(0.0),
            }));
        }
        previous = sol.clone();
        solutions.push(sol);
    }
    Ok(collect(model, crank_rad, &solutions, periodic))
}

fn transpose(rows: impl Iterator<Item = Vec<f64>>, width: usize) -> Vec<Vec<f64>> {
    let mut out = vec![Vec::new(); width];
    for row in rows {
        for (column, v) in out.iter_mut().zip(row) {
            column.push(v);
        }
    }
    out
}

fn collect(
    model: &Model,
    crank_rad: &[f64],
    sols: &[AngleSolution],
    periodic: bool,
) -> LoadedSweep {
    let mut out = LoadedSweep::default();
    if let Some(r) = &model.rollers {
        let n = r.count();
        let hertz = |s: &AngleSolution| -> Vec<(f64, f64)> {
            s.rollers
                .iter()
                .map(|st| {
                    let h = r.hertz(st);
                    (h.peak_pressure_mpa, h.half_width_mm)
                })
                .collect()
        };
        out.rollers = Some(RollerCurves {
            lag_rad: sols.iter().map(|s| s.lag_rad.unwrap_or(0.0)).collect(),
            force_n: transpose(
                sols.iter()
                    .map(|s| s.rollers.iter().map(|r| r.force_n).collect()),
                n,
            ),
            pressure_mpa: transpose(
                sols.iter().map(|s| hertz(s).iter().map(|h| h.0).collect()),
                n,
            ),
            half_width_mm: transpose(
                sols.iter().map(|s| hertz(s).iter().map(|h| h.1).collect()),
                n,
            ),
            contacts: sols
                .iter()
                .map(|s| s.rollers.iter().filter(|r| r.force_n > 0.0).count())
                .collect(),
        });
    }
    if let Some(p) = &model.pins {
        out.pins = Some(PinCurves {
            output_lag_rad: sols
                .iter()
                .map(|s| s.output_lag_rad.unwrap_or(0.0))
                .collect(),
            force_n: transpose(
                sols.iter()
                    .map(|s| s.pins.iter().map(|p| p.force_n).collect()),
                p.count,
            ),
        });
    }
    if model.bearing {
        let fb: Vec<Vec2> = sols
            .iter()
            .map(|s| s.bearing_force_n.unwrap_or_default())
            .collect();
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
            residual: sols.iter().map(|s| s.residual.unwrap_or(0.0)).collect(),
            deflection_mm: sols.iter().map(|s| s.centre_offset_mm.norm()).collect(),
        });
    }
    if model.rollers.is_some() {
        let te_rad: Vec<f64> = sols
            .iter()
            .map(|s| s.lag_rad.unwrap_or(0.0) + s.output_lag_rad.unwrap_or(0.0))
            .collect();
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
