//! The curves of the loaded sweep over the crank angles of a scene: lags, forces, pressures,
//! bearing force, TE and ratio, as columns written in place chunk by chunk. The sweep that
//! fills them, of one disc or several, is `discs_sweep` (one angle's solve is `angle`).
//! Arrays are \[angle\] or \[roller|pin\]\[angle\]; engine units (rad, N, MPa, mm).

use super::first_order_sweep::{Row, Summary};
use super::friction::loss::disc_losses;
use super::loaded::{AngleSolution, Model};
use super::rollers::Rollers;
use super::solve::SolveFailure;
use crate::geometry::{angle_from, cross, NearbyAtan2, Vec2};
use crate::model::friction::PathLosses;
use crate::model::results::{
    BearingCurves, FaceLoads, LoadedSweep, PinCurves, RollerCurves, Transmission,
};

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

pub(super) fn all_finite(sol: &AngleSolution) -> bool {
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

/// The curves of a sweep as columns \[angle\] and \[roller|pin\]\[angle\], allocated once and
/// written in place by the chunks (`Columns::chunks`).
pub(super) struct Columns {
    lag: Vec<f64>,
    output_lag: Vec<f64>,
    roller_force: Vec<Vec<f64>>,
    pressure: Vec<Vec<f64>>,
    half_width: Vec<Vec<f64>>,
    contacts: Vec<usize>,
    pin_force: Vec<Vec<f64>>,
    /// Angle of each pin's force on the pin from e_φ (`PinCurves::direction_rad`), rad.
    pin_direction: Vec<Vec<f64>>,
    bearing_force: Vec<f64>,
    /// Angle of the bearing force from the eccentric direction, rad.
    bearing_angle: Vec<f64>,
    residual: Vec<f64>,
    deflection: Vec<f64>,
    /// Each angle's friction losses, one column with `Model::losses`, else none.
    loss: Vec<Vec<PathLosses>>,
    /// Each angle's input torque, one column with `Model::losses` of the coupled model, else
    /// none.
    input_torque: Vec<Vec<f64>>,
    /// Each roller's line loads, \[angle·slices + slice\], N/mm, when the face is resolved
    /// (`Face::is_resolved`; else no columns).
    line_load: Vec<Vec<f64>>,
    /// Slices per angle of `line_load`.
    slices: usize,
    /// The face load factor of each angle, one column when the face is not uniform (the
    /// general solve's `record` writes it from the line loads it has at hand), else none.
    face_factor: Vec<Vec<f64>>,
}

/// One chunk's rows of every column: `Columns` cut at the same angles.
pub(super) struct Chunk<'a> {
    pub(super) lag: &'a mut [f64],
    pub(super) output_lag: &'a mut [f64],
    roller_force: Vec<&'a mut [f64]>,
    pressure: Vec<&'a mut [f64]>,
    half_width: Vec<&'a mut [f64]>,
    contacts: &'a mut [usize],
    pin_force: Vec<&'a mut [f64]>,
    pin_direction: Vec<&'a mut [f64]>,
    bearing_force: &'a mut [f64],
    bearing_angle: &'a mut [f64],
    residual: &'a mut [f64],
    deflection: &'a mut [f64],
    loss: Vec<&'a mut [PathLosses]>,
    input_torque: Vec<&'a mut [f64]>,
    line_load: Vec<&'a mut [f64]>,
    slices: usize,
    face_factor: Vec<&'a mut [f64]>,
}

/// `column` cut into pieces of `CHUNK` angles.
pub(super) fn pieces<T>(column: &mut [T]) -> std::slice::ChunksMut<'_, T> {
    column.chunks_mut(CHUNK)
}

/// \[column\]\[angle·width\] cut into \[chunk\]\[column\] pieces of `CHUNK` angles (`chunks` of
/// them; `width` entries an angle).
pub(super) fn piece_rows<T>(
    columns: &mut [Vec<T>],
    chunks: usize,
    width: usize,
) -> Vec<Vec<&mut [T]>> {
    let mut rows: Vec<Vec<&mut [T]>> = (0..chunks)
        .map(|_| Vec::with_capacity(columns.len()))
        .collect();
    for column in columns {
        for (row, piece) in rows.iter_mut().zip(column.chunks_mut(CHUNK * width)) {
            row.push(piece);
        }
    }
    rows
}

impl Columns {
    pub(super) fn new(model: &Model, angles: usize) -> Self {
        let rollers = model.rollers.as_ref().map_or(0, |r| r.count());
        let slices = model.rollers.as_ref().map_or(1, |r| r.slices());
        let resolved = model
            .rollers
            .as_ref()
            .is_some_and(|r| r.slices() > 1 || r.face().is_some());
        let pins = model.pins.as_ref().map_or(0, |p| p.count);
        let column = || vec![0.0; angles];
        // A column that only some models record: one, or none.
        let optional = |recorded: bool| Vec::from_iter(recorded.then(column));
        Columns {
            lag: column(),
            output_lag: column(),
            roller_force: (0..rollers).map(|_| column()).collect(),
            pressure: (0..rollers).map(|_| column()).collect(),
            half_width: (0..rollers).map(|_| column()).collect(),
            contacts: vec![0; angles],
            pin_force: (0..pins).map(|_| column()).collect(),
            pin_direction: (0..pins).map(|_| column()).collect(),
            bearing_force: column(),
            bearing_angle: column(),
            residual: column(),
            deflection: column(),
            loss: Vec::from_iter(
                (model.losses.is_some()).then(|| vec![PathLosses::default(); angles]),
            ),
            input_torque: optional(model.losses.as_ref().is_some_and(|l| l.input.is_some())),
            line_load: (0..if resolved { rollers } else { 0 })
                .map(|_| vec![0.0; angles * slices])
                .collect(),
            slices,
            face_factor: optional(model.rollers.as_ref().is_some_and(|r| r.face().is_some())),
        }
    }

    /// The chunks of `CHUNK` angles, in order.
    pub(super) fn chunks(&mut self) -> Vec<Chunk<'_>> {
        let n = self.lag.len().div_ceil(CHUNK);
        let mut roller_force = piece_rows(&mut self.roller_force, n, 1).into_iter();
        let mut pressure = piece_rows(&mut self.pressure, n, 1).into_iter();
        let mut half_width = piece_rows(&mut self.half_width, n, 1).into_iter();
        let mut pin_force = piece_rows(&mut self.pin_force, n, 1).into_iter();
        let mut pin_direction = piece_rows(&mut self.pin_direction, n, 1).into_iter();
        let mut loss = piece_rows(&mut self.loss, n, 1).into_iter();
        let mut input_torque = piece_rows(&mut self.input_torque, n, 1).into_iter();
        let slices = self.slices;
        let mut line_load = piece_rows(&mut self.line_load, n, slices).into_iter();
        let mut face_factor = piece_rows(&mut self.face_factor, n, 1).into_iter();
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
                    pin_direction: pin_direction.next().unwrap_or_default(),
                    bearing_force,
                    bearing_angle,
                    residual,
                    deflection,
                    loss: loss.next().unwrap_or_default(),
                    input_torque: input_torque.next().unwrap_or_default(),
                    line_load: line_load.next().unwrap_or_default(),
                    slices,
                    face_factor: face_factor.next().unwrap_or_default(),
                },
            )
            .collect()
    }
}

impl<'a> Chunk<'a> {
    /// Zero the per-roller and per-pin entries of angle k (a lean solve writes only those in
    /// contact, into entries that must start at zero).
    pub(super) fn clear(&mut self, k: usize) {
        let columns = [
            &mut self.roller_force,
            &mut self.pressure,
            &mut self.half_width,
            &mut self.pin_force,
            &mut self.pin_direction,
        ];
        for column in columns {
            column.iter_mut().for_each(|c| c[k] = 0.0);
        }
    }

    /// The per-roller and per-pin entries of angle k, for the lean sweep to write in place.
    pub(super) fn row(&mut self, k: usize) -> Row<'_, 'a> {
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
    pub(super) fn record_first_order(
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

    /// Record angle k of the general solve, at the disc's crank angle `crank_rad` (its phase
    /// included) with its direction e_φ.
    pub(super) fn record(
        &mut self,
        k: usize,
        model: &Model,
        (crank_rad, e_phi): (f64, Vec2),
        sol: &AngleSolution,
    ) {
        self.lag[k] = sol.lag_rad.unwrap_or(0.0);
        self.output_lag[k] = sol.output_lag_rad.unwrap_or(0.0);
        if let Some(r) = &model.rollers {
            let mut contacts = 0;
            let n = self.slices;
            // The face load factor's peak line load and the force of its roller.
            let mut peak = (0.0, 0.0);
            for (i, s) in sol.rollers.iter().enumerate() {
                self.roller_force[i][k] = s.force_n;
                // The line loads once the angle is solved; the peak slice's Hertz from them.
                let q = self
                    .line_load
                    .get_mut(i)
                    .map(|q| &mut q[k * n..(k + 1) * n]);
                let (p, b) = if s.force_n > 0.0 {
                    contacts += 1;
                    let h = match q {
                        Some(q) => {
                            let (h, top) = r.hertz_and_line_loads(s, q);
                            if top > peak.0 {
                                peak = (top, s.force_n);
                            }
                            h
                        }
                        None => r.hertz(s),
                    };
                    (h.peak_pressure_mpa, h.half_width_mm)
                } else {
                    // Out of contact: its line loads stay the column's zeros (`Columns::new`;
                    // an angle is recorded once).
                    (0.0, 0.0)
                };
                self.pressure[i][k] = p;
                self.half_width[i][k] = b;
            }
            self.contacts[k] = contacts;
            if let Some(f) = self.face_factor.first_mut() {
                f[k] = face_load_factor(peak, r.face_width_mm());
            }
        }
        for (j, p) in sol.pins.iter().enumerate() {
            self.pin_force[j][k] = p.force_n;
            // The force on the pin is −F·û; in the first-order geometry û = −e_φ exactly and
            // this is 0 (a lean angle's entry stays the column's zero).
            self.pin_direction[j][k] = if p.force_n != 0.0 {
                angle_from(e_phi, -p.direction)
            } else {
                0.0
            };
        }
        let bearing = sol.bearing_force_n.unwrap_or_default();
        let angle = angle_from(e_phi, bearing);
        self.record_bearing(k, bearing, angle, sol.residual.unwrap_or(0.0));
        self.deflection[k] = sol.centre_offset_mm.norm();
        self.record_friction(k, model, crank_rad, sol);
    }

    /// Record angle k's friction losses and input torque (`Model::losses`), from its solution
    /// and the bearing force just recorded.
    fn record_friction(&mut self, k: usize, model: &Model, crank_rad: f64, sol: &AngleSolution) {
        let Some(losses) = &model.losses else {
            return;
        };
        if let Some(l) = self.loss.first_mut() {
            // The disc's contact losses at its crank angle (its phase included), N·mm/rad.
            l[k] = disc_losses(&losses.friction, &losses.design, crank_rad, sol);
        }
        if let (Some(t), Some(c)) = (self.input_torque.first_mut(), &losses.input) {
            t[k] = c.input_torque(self.bearing_force[k], self.bearing_angle[k]);
        }
    }
}

/// The transmission of a sweep from its TE (rad) at `crank_rad`: κ = 1/(1/nc − dδ/dφ).
pub(super) fn transmission(
    te_rad: Vec<f64>,
    crank_rad: &[f64],
    teeth: usize,
    periodic: bool,
) -> Transmission {
    let nc = teeth as f64;
    // The step is read only where there are three angles or more (`derivative`).
    let ratio = derivative(&te_rad, crate::numeric::step(crank_rad), periodic)
        .map(|d| d.iter().map(|dd| 1.0 / (1.0 / nc - dd)).collect());
    Transmission { te_rad, ratio }
}

/// A disc's own curves from its columns: lags, forces, bearing (no transmission: that is the
/// reducer's, from the common output lag).
pub(super) fn disc_curves(model: &Model, c: Columns) -> LoadedSweep {
    let face = model
        .rollers
        .as_ref()
        .filter(|_| !c.line_load.is_empty())
        .map(|r| face_loads(r, &c.roller_force, c.line_load, c.slices, c.face_factor));
    LoadedSweep {
        rollers: model.rollers.as_ref().map(|_| RollerCurves {
            lag_rad: c.lag,
            force_n: c.roller_force,
            pressure_mpa: c.pressure,
            half_width_mm: c.half_width,
            contacts: c.contacts,
            face,
        }),
        pins: model.pins.as_ref().map(|_| PinCurves {
            output_lag_rad: c.output_lag,
            force_n: c.pin_force,
            direction_rad: c.pin_direction,
        }),
        bearing: model.bearing.then_some(BearingCurves {
            force_n: c.bearing_force,
            angle_rad: c.bearing_angle,
            residual: c.residual,
            deflection_mm: c.deflection,
        }),
        losses: c.loss.into_iter().next(),
        input_torque_nmm: c.input_torque.into_iter().next(),
        ..LoadedSweep::default()
    }
}

/// The face load factor of an angle from the peak line load (N/mm) and the force (N) of the
/// roller that carries it: peak/(F/B), 0 where no roller carries a force.
fn face_load_factor((peak, force_n): (f64, f64), width_mm: f64) -> f64 {
    if force_n > 0.0 {
        peak / (force_n / width_mm)
    } else {
        0.0
    }
}

/// The line loads of every roller `[roller][angle·slices + slice]` and the face load factor of
/// every angle (MODEL.md "Along the face width": the peak line load over the rollers and slices
/// divided by the mean line load F_i/B of the roller that carries it; 0 where no roller
/// carries a force). On a uniform face (no crown, no tilt; the lean first-order sweep writes
/// no line loads) every slice carries F_i/B.
fn face_loads(
    r: &Rollers,
    force_n: &[Vec<f64>],
    mut line_load: Vec<Vec<f64>>,
    slices: usize,
    face_factor: Vec<Vec<f64>>,
) -> FaceLoads {
    let width = r.face_width_mm();
    let angles = force_n.first().map_or(0, Vec::len);
    if r.face().is_none() {
        for (q, f) in line_load.iter_mut().zip(force_n) {
            for (row, &f) in q.chunks_exact_mut(slices).zip(f) {
                row.fill(f / width);
            }
        }
    }
    // Written by `Chunk::record` on a face that is not uniform; on a uniform one every slice
    // carries its roller's mean F/B, a factor of 1 wherever a roller carries a force.
    let face_load_factor = face_factor.into_iter().next().unwrap_or_else(|| {
        (0..angles)
            .map(|k| match force_n.iter().any(|f| f[k] > 0.0) {
                true => 1.0,
                false => 0.0,
            })
            .collect()
    });
    FaceLoads {
        line_load_n_per_mm: line_load,
        slices,
        face_load_factor,
    }
}
