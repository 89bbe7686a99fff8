//! The one registry of quantities: every output the tool names, its key (as in the results
//! JSON), unit, label, the effect that computes it, and how to read it from a scene's results.
//! Limits, goldens, the accuracy ladder, optimisation objectives, summaries and plots all look
//! their quantities up here; a new quantity is one entry.
//!
//! A quantity is either per crank angle (`Shape::Curve`, or one curve per roller or pin) or a
//! scalar of the whole sweep (`Shape::Scalar`: an extreme with where it occurs, as data:
//! `model::place`). Values are in the unit named by the key (arcsec, N, mm, MPa, deg).

use super::effect::{Detail, Effect};
use super::place::{Bin, Crank, Part, PartAt, Place, Rule, Site, Unbounded};
use super::results::{
    BacklashCurves, DiscResult, DutyCycle, EfficiencyCurves, ReducerEfficiency, ReducerResult,
    RollerCurves, SceneResult, TorsionFigures,
};
use crate::numeric::{extremes, fluctuation, max_entry};
use crate::units;

/// Rows `[column][angle]` in output units, as a curve's reader gives them: borrowed, the
/// results' own where they hold them in the key's unit (no copy: the results JSON writes them
/// as they are; one row: `one`), else owned, computed from them (a unit conversion, a count as
/// a number).
pub type Rows<'a> = std::borrow::Cow<'a, [Vec<f64>]>;

/// How a quantity is laid out over a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// One value per crank angle.
    Curve,
    /// One curve per roller.
    PerRoller,
    /// One curve per output pin.
    PerPin,
    /// One value for the whole sweep (an extreme, with where it occurs).
    Scalar,
}

impl Shape {
    /// What one column is ("roller", "pin") when there is one curve per part.
    pub fn per(self) -> Option<&'static str> {
        self.part().map(Part::name)
    }

    /// The part one column is a curve of, when there is one curve per part.
    pub fn part(self) -> Option<Part> {
        match self {
            Shape::PerRoller => Some(Part::Roller),
            Shape::PerPin => Some(Part::Pin),
            _ => None,
        }
    }
}

/// A scalar of a sweep and where it occurs (roller 3 at crank 0.2147 rad).
#[derive(Debug, Clone, PartialEq)]
pub struct Extreme {
    /// The value, in the unit of the quantity's key.
    pub value: f64,
    /// Where it occurs, or what it rests on, as data (`report::place` says it in words).
    pub at: Place,
}

/// Whose results a quantity is read from: a scene's, or one disc's of it.
#[derive(Clone, Copy)]
pub struct Of<'a> {
    /// The scene's results: its crank angles, and with `disc` None the reducer's curves and
    /// scalars and its only disc's (`SceneResult::only_disc`).
    pub r: &'a SceneResult,
    /// One disc of the scene, read alone.
    pub disc: Option<&'a DiscResult>,
}

impl<'a> Of<'a> {
    /// `q`'s rows in these results (`Quantity::rows`, `Quantity::disc_rows`).
    pub fn rows(&self, q: &Quantity) -> Option<Rows<'a>> {
        match self.disc {
            None => q.rows(self.r),
            Some(d) => q.disc_rows(d),
        }
    }

    /// `q`'s curves in these results (`Quantity::curves`, `Quantity::disc_curves`): `rows`
    /// under their names.
    pub fn curves(&self, q: &Quantity) -> Option<Curves> {
        q.named(self.rows(q)?)
    }

    /// `q`'s scalar in these results (`Quantity::scalar`, `Quantity::disc_scalar`).
    pub fn scalar(&self, q: &Quantity) -> Option<Extreme> {
        match self.disc {
            None => q.scalar(self.r),
            Some(d) => q.disc_scalar(d, &self.r.crank_rad),
        }
    }
}

/// Where a quantity is read from, which makes it a disc's or the reducer's
/// (`Quantity::of_reducer`). A scalar's reader takes the run's crank angles beside the results,
/// to say where its extreme occurs.
#[derive(Clone, Copy)]
enum Read {
    /// Each disc's curves.
    DiscCurves(fn(&DiscResult) -> Option<Rows<'_>>),
    /// The reducer's curves, over all its discs.
    ReducerCurves(fn(&ReducerResult) -> Option<Rows<'_>>),
    /// Each disc's scalar: the scene's is the worst over its discs.
    DiscScalar(fn(&DiscResult, &[f64]) -> Option<Extreme>),
    /// The reducer's scalar.
    ReducerScalar(fn(&ReducerResult, &[f64]) -> Option<Extreme>),
    /// A scalar of friction losses: the scene's is the reducer's (every disc's contacts and
    /// the drag), a disc's document gives the disc's own contacts' (`DiscResult::efficiency`).
    Losses(fn(&EfficiencyCurves) -> Option<Extreme>),
    /// A duty cycle's own figure (`DUTY`).
    CycleScalar(fn(&DutyCycle) -> Option<Extreme>),
    /// Each disc's scalar, which a duty cycle gives of its own when it computes it (else the
    /// worst over its bins).
    DiscOrCycle(
        fn(&DiscResult, &[f64]) -> Option<Extreme>,
        fn(&DutyCycle) -> Option<Extreme>,
    ),
}

/// One quantity of the registry.
#[derive(Clone, Copy)]
pub struct Quantity {
    /// Key in the results JSON (and in `golden[].quantity`, limits, summaries).
    pub key: &'static str,
    /// Unit for axis labels and messages ("" when dimensionless).
    pub unit: &'static str,
    /// What a person calls it.
    pub label: &'static str,
    /// The effect that computes it.
    pub effect: Effect,
    /// How it is laid out over a scene.
    pub shape: Shape,
    /// For a scalar, the curve it is an extreme of (where a limit on it is drawn).
    pub of: Option<&'static str>,
    read: Read,
}

impl std::fmt::Debug for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Quantity({})", self.key)
    }
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.key)
    }
}

impl PartialEq for Quantity {
    fn eq(&self, other: &Self) -> bool {
        self.key == other.key
    }
}

/// Named curves of one quantity over the crank angles of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Curves {
    /// Column names: the quantity key, or `roller_0`, `roller_1`, ... / `pin_0`, ...
    pub columns: Vec<String>,
    /// `[column][angle]`, output units.
    pub values: Vec<Vec<f64>>,
}

impl Quantity {
    /// The quantity's curves in a scene's results: the reducer's, or a disc's curves of a
    /// one-disc scene (`SceneResult::only_disc`; with several discs each disc's are
    /// `disc_curves`); `None` when the scene did not compute it, or for a scalar.
    pub fn curves(&self, r: &SceneResult) -> Option<Curves> {
        self.named(self.rows(r)?)
    }

    /// `curves`' rows, without their names, borrowed where the results hold them.
    pub fn rows<'r>(&self, r: &'r SceneResult) -> Option<Rows<'r>> {
        match self.read {
            Read::ReducerCurves(read) => read(&r.reducer),
            Read::DiscCurves(read) => read(r.only_disc()?),
            _ => None,
        }
    }

    /// The quantity's curves in one disc's results; `None` for the reducer's quantities, when
    /// not computed, or for a scalar.
    pub fn disc_curves(&self, d: &DiscResult) -> Option<Curves> {
        self.named(self.disc_rows(d)?)
    }

    /// `disc_curves`' rows, without their names, borrowed where the results hold them.
    pub fn disc_rows<'d>(&self, d: &'d DiscResult) -> Option<Rows<'d>> {
        match self.read {
            Read::DiscCurves(read) => read(d),
            _ => None,
        }
    }

    /// Rows under their column names.
    fn named(&self, rows: Rows) -> Option<Curves> {
        let values = rows.into_owned();
        let columns = match self.shape.per() {
            Some(what) => (0..values.len()).map(|i| format!("{what}_{i}")).collect(),
            None => vec![self.key.to_string()],
        };
        Some(Curves { columns, values })
    }

    /// The scalar's value and where it occurs; `None` when not computed, or for a curve. A
    /// quantity of each disc (a force, a clearance) is the worst over the discs, and where it
    /// occurs names the disc with several (`Place::disc`); in a duty-cycle scene the cycle's
    /// own figure or the worst over the bins (`worst_bin`).
    pub fn scalar(&self, r: &SceneResult) -> Option<Extreme> {
        if let Some(duty) = r.duty.as_deref() {
            if self.for_duty() == Some(false) {
                return None;
            }
            let own = match self.read {
                Read::CycleScalar(read) | Read::DiscOrCycle(_, read) => read(duty),
                _ => None,
            };
            return own.or_else(|| self.worst_bin(duty));
        }
        let c = r.crank_rad.as_slice();
        match self.read {
            Read::ReducerScalar(read) => read(&r.reducer, c),
            Read::Losses(read) => read(r.reducer.efficiency.as_ref()?),
            Read::DiscScalar(read) | Read::DiscOrCycle(read, _) => {
                let named = r.names_discs();
                (r.discs.iter().enumerate())
                    .filter_map(|(k, disc)| {
                        let mut e = read(disc, c)?;
                        e.at.disc = named.then_some(k);
                        Some(e)
                    })
                    .reduce(|a, b| if self.worse(b.value, a.value) { b } else { a })
            }
            _ => None,
        }
    }

    /// The scalar of one disc alone over the crank angles `crank_rad` (a disc's document); a
    /// friction loss is the disc's own contacts' (`Read::Losses`); `None` for the reducer's
    /// quantities, when not computed, or for a curve.
    pub fn disc_scalar(&self, d: &DiscResult, crank_rad: &[f64]) -> Option<Extreme> {
        match self.read {
            Read::DiscScalar(read) | Read::DiscOrCycle(read, _) => read(d, crank_rad),
            Read::Losses(read) => read(d.efficiency.as_ref()?),
            _ => None,
        }
    }

    /// In a duty-cycle scene (`SceneResult::duty`), the worst value over its bins' runs, named
    /// by its bin, its torque and speed (`Place::bin`).
    fn worst_bin(&self, duty: &DutyCycle) -> Option<Extreme> {
        duty.bins
            .iter()
            .enumerate()
            .filter_map(|(j, b)| {
                let mut e = self.scalar(&b.result)?;
                e.at.bin = Some(Bin {
                    index: j,
                    output_torque_nmm: b.bin.output_torque_nmm,
                    input_speed_rpm: b.bin.input_speed_rpm,
                });
                Some(e)
            })
            .reduce(|a, b| if self.worse(b.value, a.value) { b } else { a })
    }

    /// Which scenes have this quantity: `Some(true)` a duty cycle's figure (`DUTY`), only in
    /// a duty-cycle scene; `Some(false)` one run's figure at one speed (`SINGLE_RUN`: a bin's
    /// bearing life and efficiency, in its own run), not a duty-cycle scene's; `None` every
    /// scene (in a duty-cycle scene the worst over its bins).
    pub fn for_duty(&self) -> Option<bool> {
        if DUTY.contains(&self) {
            Some(true)
        } else if SINGLE_RUN.contains(&self) {
            Some(false)
        } else {
            None
        }
    }

    /// Whether `a` is worse than `b` for this quantity: lower when its limit bounds it from
    /// below (`LIMITS`; a `min_` quantity without a limit too), higher for every other.
    fn worse(&self, a: f64, b: f64) -> bool {
        let from_below = LIMITS
            .iter()
            .find(|l| l.quantity.key == self.key)
            .map_or(self.key.starts_with("min_"), |l| l.bound == Bound::Min);
        if from_below {
            a < b
        } else {
            a > b
        }
    }

    /// Whether the reducer as a whole has this quantity (the output's TE and ratio, the
    /// torsion under a locked input, the efficiency, the pins' stresses, a duty cycle's
    /// figures) rather than each disc (MODEL.md "Several discs"): where its reader reads it.
    pub fn of_reducer(&self) -> bool {
        !matches!(
            self.read,
            Read::DiscCurves(_) | Read::DiscScalar(_) | Read::DiscOrCycle(..)
        )
    }

    /// Whether it is one value for the whole sweep (`Shape::Scalar`) rather than curves.
    pub fn is_scalar(&self) -> bool {
        self.shape == Shape::Scalar
    }

    /// The detail of its effect this quantity needs beyond the effect itself (`NEEDS_BACKLASH`).
    pub fn detail(&self) -> Option<Detail> {
        NEEDS_BACKLASH.contains(&self).then_some(Detail::Backlash)
    }

    /// Whether its values count rollers (`COUNTS`): whole numbers, and a limit on it too.
    pub fn is_count(&self) -> bool {
        COUNTS.contains(&self)
    }

    /// For an angle that wraps (±180°), its period: deviations are taken modulo it (`WRAPS`).
    pub fn period(&self) -> Option<f64> {
        WRAPS.iter().find(|(q, _)| *q == self).map(|&(_, p)| p)
    }

    /// "label (unit)" for an axis.
    pub fn axis_label(&self) -> String {
        if self.unit.is_empty() {
            self.label.to_string()
        } else {
            format!("{} ({})", self.label, self.unit)
        }
    }
}

/// The rollers' curves of a disc's loaded sweep, when computed.
fn rollers(d: &DiscResult) -> Option<&RollerCurves> {
    d.loaded.rollers.as_ref()
}

/// The backlash curves of a disc, when computed.
fn backlash(d: &DiscResult) -> Option<&BacklashCurves> {
    d.clearance.as_ref()?.backlash.as_ref()
}

/// One curve of `v` converted by `unit` (`units`: rad to arcsec, N·mm to N·m, …).
fn converted(v: &[f64], unit: fn(f64) -> f64) -> Rows<'static> {
    Rows::Owned(vec![v.iter().map(|&x| unit(x)).collect()])
}

fn arcsec(v: &[f64]) -> Rows<'static> {
    converted(v, units::arcsec)
}

/// One row of the results.
fn one(v: &Vec<f64>) -> Rows<'_> {
    Rows::Borrowed(std::slice::from_ref(v))
}

/// Crank angle `k` of the run's angles `c` (φ = 0 past its end: an extreme of an empty curve).
fn crank(c: &[f64], k: usize) -> Crank {
    Crank {
        index: k,
        rad: c.get(k).copied().unwrap_or(0.0),
    }
}

/// An extreme at a place of the scene's own run.
fn at(value: f64, site: Site) -> Extreme {
    Extreme {
        value,
        at: Place::of(site),
    }
}

/// Part `i` of `part` at the run's crank angle `k` (of the angles `c`).
fn part_at(c: &[f64], part: Part, i: usize, k: usize) -> PartAt {
    PartAt {
        part,
        index: i,
        crank: crank(c, k),
    }
}

/// The largest entry of per-part curves and where: roller 3 at crank angle 12.
fn largest(c: &[f64], rows: &[Vec<f64>], part: Part) -> Extreme {
    let (value, i, k) = max_entry(rows);
    at(value, Site::Part(part_at(c, part, i, k)))
}

/// The largest value of a curve and where.
fn highest(c: &[f64], curve: &[f64]) -> Extreme {
    let (_, (value, k)) = extremes(curve);
    at(value, Site::Crank(crank(c, k)))
}

/// max − min of a curve (scaled), with where each occurs.
fn spread(c: &[f64], curve: &[f64], scale: f64) -> Extreme {
    let ((_, lo), (_, hi)) = extremes(curve);
    let site = Site::Spread {
        min: crank(c, lo),
        max: crank(c, hi),
    };
    at(fluctuation(curve) * scale, site)
}

/// Gap of each roller at the ideal pose (β = 0), mm, one curve per roller
/// (`ClearanceSweep::gap_mm`); negative: interference.
pub const CLEARANCE: Quantity = Quantity {
    key: "clearance_mm",
    unit: "mm",
    label: "clearance",
    effect: Effect::Clearance,
    shape: Shape::PerRoller,
    of: None,
    read: Read::DiscCurves(|d| d.clearance.as_ref().map(|c| Rows::Borrowed(&c.gap_mm))),
};

/// Unloaded TE: the smallest closing lag of the rollers that a positive torque closes, arcsec
/// (`BacklashCurves::forward_rad`); negative under interference (preload).
pub const BACKLASH: Quantity = Quantity {
    key: "backlash_arcsec",
    unit: "arcsec",
    label: "backlash (unloaded TE)",
    effect: Effect::Clearance,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| backlash(d).map(|b| arcsec(&b.forward_rad))),
};

/// The closing lag the other way, as a magnitude, arcsec (`BacklashCurves::reverse_rad`).
pub const BACKLASH_REVERSE: Quantity = Quantity {
    key: "backlash_reverse_arcsec",
    unit: "arcsec",
    label: "reverse backlash",
    effect: Effect::Clearance,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| backlash(d).map(|b| arcsec(&b.reverse_rad))),
};

/// Unloaded lost motion: backlash + reverse backlash, arcsec (`BacklashCurves::lost_motion_rad`).
pub const LOST_MOTION: Quantity = Quantity {
    key: "lost_motion_arcsec",
    unit: "arcsec",
    label: "lost motion",
    effect: Effect::Clearance,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| backlash(d).map(|b| arcsec(&b.lost_motion_rad))),
};

/// β, the lag of the disc behind its ideal angle −φ/nc under load, arcsec
/// (`RollerCurves::lag_rad`); positive opposes the motion.
pub const LAG: Quantity = Quantity {
    key: "lag_arcsec",
    unit: "arcsec",
    label: "disc lag β",
    effect: Effect::RollerContact,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| rollers(d).map(|c| arcsec(&c.lag_rad))),
};

/// Loaded TE δ = β + βo (with several discs the common output lag γ), arcsec
/// (`Transmission::te_rad`).
pub const TE: Quantity = Quantity {
    key: "te_arcsec",
    unit: "arcsec",
    label: "loaded TE δ = β + βo",
    effect: Effect::RollerContact,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| r.transmission.as_ref().map(|t| arcsec(&t.te_rad))),
};

/// Transmission ratio κ = dφ/dφout = 1/(1/nc − dδ/dφ), dimensionless (`Transmission::ratio`);
/// its mean over a period is nc.
pub const RATIO: Quantity = Quantity {
    key: "ratio",
    unit: "",
    label: "transmission ratio κ = dφ/dφout",
    effect: Effect::RollerContact,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| {
        r.transmission
            .as_ref()
            .and_then(|t| t.ratio.as_ref().map(one))
    }),
};

/// Contact force of each roller on the disc, N, one curve per roller (`RollerCurves::force_n`).
pub const ROLLER_FORCE: Quantity = Quantity {
    key: "roller_force_n",
    unit: "N",
    label: "roller force",
    effect: Effect::RollerContact,
    shape: Shape::PerRoller,
    of: None,
    read: Read::DiscCurves(|d| rollers(d).map(|c| Rows::Borrowed(&c.force_n))),
};

/// Hertz peak pressure p0 of each roller's contact, MPa, one curve per roller
/// (`RollerCurves::pressure_mpa`).
pub const CONTACT_PRESSURE: Quantity = Quantity {
    key: "contact_pressure_mpa",
    unit: "MPa",
    label: "Hertz peak pressure",
    effect: Effect::RollerContact,
    shape: Shape::PerRoller,
    of: None,
    read: Read::DiscCurves(|d| rollers(d).map(|c| Rows::Borrowed(&c.pressure_mpa))),
};

/// Hertz half-width b of each roller's contact, mm, one curve per roller
/// (`RollerCurves::half_width_mm`).
pub const CONTACT_HALF_WIDTH: Quantity = Quantity {
    key: "contact_half_width_mm",
    unit: "mm",
    label: "contact half-width",
    effect: Effect::RollerContact,
    shape: Shape::PerRoller,
    of: None,
    read: Read::DiscCurves(|d| rollers(d).map(|c| Rows::Borrowed(&c.half_width_mm))),
};

/// How many rollers carry a force at each crank angle (`RollerCurves::contacts`).
pub const CONTACTS: Quantity = Quantity {
    key: "contacts",
    unit: "",
    label: "rollers in contact",
    effect: Effect::RollerContact,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| {
        rollers(d).map(|c| Rows::Owned(vec![c.contacts.iter().map(|&n| n as f64).collect()]))
    }),
};

/// The face load factor at each crank angle (`FaceLoads::face_load_factor`): the peak line
/// load along the face over the rollers divided by the mean line load F_i/B of the roller that
/// carries it (MODEL.md "Along the face width"); only where the scene resolves the face.
pub const FACE_LOAD_FACTOR: Quantity = Quantity {
    key: "face_load_factor",
    unit: "",
    label: "face load factor",
    effect: Effect::RollerContact,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| Some(one(&rollers(d)?.face.as_ref()?.face_load_factor))),
};

/// A disc's share Tk of the torque, N·m (`LoadedSweep::torque_nmm`): with several discs only.
pub const DISC_TORQUE: Quantity = Quantity {
    key: "torque_nm",
    unit: "N·m",
    label: "disc torque share Tk",
    effect: Effect::RollerContact,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| Some(converted(d.loaded.torque_nmm.as_ref()?, units::nm))),
};

/// βo, the lag of the output behind the disc from the pins' deflection, arcsec
/// (`PinCurves::output_lag_rad`).
pub const OUTPUT_LAG: Quantity = Quantity {
    key: "output_lag_arcsec",
    unit: "arcsec",
    label: "output lag βo",
    effect: Effect::OutputPins,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| d.loaded.pins.as_ref().map(|p| arcsec(&p.output_lag_rad))),
};

/// Contact force of each output pin on the disc, N, one curve per pin (`PinCurves::force_n`).
pub const PIN_FORCE: Quantity = Quantity {
    key: "pin_force_n",
    unit: "N",
    label: "output-pin force",
    effect: Effect::OutputPins,
    shape: Shape::PerPin,
    of: None,
    read: Read::DiscCurves(|d| d.loaded.pins.as_ref().map(|p| Rows::Borrowed(&p.force_n))),
};

/// |Fb|, the magnitude of the crank bearing's force on the disc, N (`BearingCurves::force_n`).
pub const BEARING_FORCE: Quantity = Quantity {
    key: "bearing_force_n",
    unit: "N",
    label: "crank-bearing force |Fb|",
    effect: Effect::Bearing,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| d.loaded.bearing.as_ref().map(|b| one(&b.force_n))),
};

/// ε, the angle of the bearing force from the eccentric direction, counter-clockwise, degrees in
/// [−180, 180] (`BearingCurves::angle_rad`).
pub const BEARING_ANGLE: Quantity = Quantity {
    key: "bearing_angle_deg",
    unit: "deg",
    label: "crank-bearing force angle ε",
    effect: Effect::Bearing,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| {
        (d.loaded.bearing.as_ref()).map(|b| converted(&b.angle_rad, units::deg))
    }),
};

/// Displacement of the disc centre in a compliant crank bearing, mm; zero when rigid
/// (`BearingCurves::deflection_mm`).
pub const BEARING_DEFLECTION: Quantity = Quantity {
    key: "bearing_deflection_mm",
    unit: "mm",
    label: "crank-bearing deflection",
    effect: Effect::Bearing,
    shape: Shape::Curve,
    of: None,
    read: Read::DiscCurves(|d| d.loaded.bearing.as_ref().map(|b| one(&b.deflection_mm))),
};

/// The smallest gap over the rollers and the whole mesh (the whole crank period of the gaps,
/// whatever angles the scene samples: `ClearanceSweep::coverage`), mm, with the roller, the
/// crank angle, the place on the tooth, the period, its step and the error bound
/// (`ClearanceSweep::min`).
pub const MIN_CLEARANCE: Quantity = Quantity {
    key: "min_clearance_mm",
    unit: "mm",
    label: "min clearance over the mesh",
    effect: Effect::Clearance,
    shape: Shape::Scalar,
    of: Some("clearance_mm"),
    read: Read::DiscScalar(|d, _| {
        d.clearance.as_ref().map(|gaps| {
            let site = Site::Gap {
                min: gaps.min,
                over: gaps.coverage,
            };
            at(gaps.min.gap_mm, site)
        })
    }),
};

/// The largest unloaded lost motion over the scene's crank angles (only those: its closing lags
/// are not sought over the whole mesh), arcsec.
pub const MAX_LOST_MOTION: Quantity = Quantity {
    key: "max_lost_motion_arcsec",
    unit: "arcsec",
    label: "max lost motion (unloaded)",
    effect: Effect::Clearance,
    shape: Shape::Scalar,
    of: Some("lost_motion_arcsec"),
    read: Read::DiscScalar(|d, c| {
        let (_, (value, k)) = extremes(&backlash(d)?.lost_motion_rad);
        let site = Site::Sampled {
            crank: crank(c, k),
            angles: c.len(),
        };
        Some(at(units::arcsec(value), site))
    }),
};

/// The largest roller force, N, with the roller and the crank angle.
pub const MAX_ROLLER_FORCE: Quantity = Quantity {
    key: "max_roller_force_n",
    unit: "N",
    label: "max roller force",
    effect: Effect::RollerContact,
    shape: Shape::Scalar,
    of: Some("roller_force_n"),
    read: Read::DiscScalar(|d, c| Some(largest(c, &rollers(d)?.force_n, Part::Roller))),
};

/// The largest Hertz peak pressure of the rollers' contacts, MPa, with the roller and the crank
/// angle.
pub const MAX_CONTACT_PRESSURE: Quantity = Quantity {
    key: "max_contact_pressure_mpa",
    unit: "MPa",
    label: "max Hertz pressure",
    effect: Effect::RollerContact,
    shape: Shape::Scalar,
    of: Some("contact_pressure_mpa"),
    read: Read::DiscScalar(|d, c| Some(largest(c, &rollers(d)?.pressure_mpa, Part::Roller))),
};

/// The largest face load factor over the crank angles, with the angle (`FACE_LOAD_FACTOR`).
pub const MAX_FACE_LOAD_FACTOR: Quantity = Quantity {
    key: "max_face_load_factor",
    unit: "",
    label: "max face load factor",
    effect: Effect::RollerContact,
    shape: Shape::Scalar,
    of: Some("face_load_factor"),
    read: Read::DiscScalar(|d, c| {
        let face = rollers(d)?.face.as_ref()?;
        Some(highest(c, &face.face_load_factor))
    }),
};

/// The largest line load along the face, N/mm, with the roller, the crank angle and the slice
/// (`FaceLoads::line_load_n_per_mm`).
pub const MAX_LINE_LOAD: Quantity = Quantity {
    key: "max_line_load_n_per_mm",
    unit: "N/mm",
    label: "max line load",
    effect: Effect::RollerContact,
    shape: Shape::Scalar,
    of: None,
    read: Read::DiscScalar(|d, c| {
        let face = rollers(d)?.face.as_ref()?;
        let (value, i, k, s) = face.peak_line_load();
        face.line_load_n_per_mm.first()?.first()?;
        let site = Site::Slice {
            at: part_at(c, Part::Roller, i, k),
            slice: s,
            slices: face.slices,
        };
        Some(at(value, site))
    }),
};

/// The fewest rollers in contact at any crank angle.
pub const MIN_ROLLERS_IN_CONTACT: Quantity = Quantity {
    key: "min_rollers_in_contact",
    unit: "",
    label: "fewest rollers in contact",
    effect: Effect::RollerContact,
    shape: Shape::Scalar,
    of: Some("contacts"),
    read: Read::DiscScalar(|d, c| {
        let counts: Vec<f64> = rollers(d)?.contacts.iter().map(|&n| n as f64).collect();
        let ((value, k), _) = extremes(&counts);
        Some(at(value, Site::Crank(crank(c, k))))
    }),
};

/// δmax − δmin over the crank angles, arcsec: the paper's objective fΔδ (Eqs. 22–23).
pub const TE_FLUCTUATION: Quantity = Quantity {
    key: "te_fluctuation_arcsec",
    unit: "arcsec",
    label: "TE fluctuation δmax − δmin",
    effect: Effect::RollerContact,
    shape: Shape::Scalar,
    of: Some("te_arcsec"),
    read: Read::ReducerScalar(|r, c| {
        let t = r.transmission.as_ref()?;
        Some(spread(c, &t.te_rad, units::arcsec(1.0)))
    }),
};

/// κmax − κmin over the crank angles, dimensionless: the paper's objective fκ (Eq. 18).
pub const RATIO_FLUCTUATION: Quantity = Quantity {
    key: "ratio_fluctuation",
    unit: "",
    label: "ratio fluctuation κmax − κmin",
    effect: Effect::RollerContact,
    shape: Shape::Scalar,
    of: Some("ratio"),
    read: Read::ReducerScalar(|r, c| {
        let ratio = r.transmission.as_ref()?.ratio.as_ref()?;
        Some(spread(c, ratio, 1.0))
    }),
};

/// The largest output-pin force, N, with the pin and the crank angle.
pub const MAX_PIN_FORCE: Quantity = Quantity {
    key: "max_pin_force_n",
    unit: "N",
    label: "max pin force",
    effect: Effect::OutputPins,
    shape: Shape::Scalar,
    of: Some("pin_force_n"),
    read: Read::DiscScalar(|d, c| Some(largest(c, &d.loaded.pins.as_ref()?.force_n, Part::Pin))),
};

/// The largest crank-bearing force |Fb|, N, with the crank angle.
pub const MAX_BEARING_FORCE: Quantity = Quantity {
    key: "max_bearing_force_n",
    unit: "N",
    label: "max crank-bearing force",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: Some("bearing_force_n"),
    read: Read::DiscScalar(|d, c| Some(highest(c, &d.loaded.bearing.as_ref()?.force_n))),
};

/// The largest relative residual of the balances (the paper's Eqs. 12–14) over the crank angles,
/// dimensionless (`BearingCurves::residual`).
pub const MAX_RESIDUAL: Quantity = Quantity {
    key: "max_residual",
    unit: "",
    label: "largest residual of Eqs. 12–14",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: None,
    read: Read::DiscScalar(|d, c| Some(highest(c, &d.loaded.bearing.as_ref()?.residual))),
};

/// The catalogue figures of a torsion scene, `[crank]`, read by `figure`.
fn torsion_figures(r: &ReducerResult, figure: impl Fn(&TorsionFigures) -> f64) -> Option<Rows<'_>> {
    let t = r.torsion.as_ref()?;
    Some(Rows::Owned(vec![t.figures.iter().map(figure).collect()]))
}

/// Torsion lost motion γ(+3 %) − γ(−3 %) of the rated torque, arcmin, at each locked crank angle
/// (`TorsionFigures::lost_motion_rad`).
pub const TORSION_LOST_MOTION: Quantity = Quantity {
    key: "lost_motion_arcmin",
    unit: "arcmin",
    label: "lost motion at ±3 % rated torque",
    effect: Effect::Torsion,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| torsion_figures(r, |f| units::arcmin(f.lost_motion_rad))),
};

/// Torsion backlash γ(0⁺) − γ(0⁻), the dead band at zero torque, arcmin, at each locked crank
/// angle (`TorsionFigures::backlash_rad`).
pub const TORSION_BACKLASH: Quantity = Quantity {
    key: "backlash_arcmin",
    unit: "arcmin",
    label: "backlash (dead band at zero torque)",
    effect: Effect::Torsion,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| torsion_figures(r, |f| units::arcmin(f.backlash_rad))),
};

/// Torsional rigidity, the secant stiffness between 50 % and 100 % of the rated torque in the
/// smaller direction, N·m/arcmin, at each locked crank angle (`TorsionFigures::rigidity`).
pub const TORSIONAL_RIGIDITY: Quantity = Quantity {
    key: "torsional_rigidity_nm_per_arcmin",
    unit: "N·m/arcmin",
    label: "torsional rigidity (50–100 % rated, smaller direction)",
    effect: Effect::Torsion,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| torsion_figures(r, |f| units::nm_per_arcmin(f.rigidity()))),
};

/// The figures of a torsion scene whose loop carries friction, `[crank]`, read by `figure`
/// (none without friction: the frictionless loop has no hysteresis to read).
fn friction_figures(
    r: &ReducerResult,
    figure: impl Fn(&TorsionFigures) -> f64,
) -> Option<Rows<'_>> {
    r.torsion.as_ref().filter(|t| t.friction)?;
    torsion_figures(r, figure)
}

/// Hysteresis loss of a torsion loop with friction, the traversed loop's width at T = 0, arcmin,
/// at each locked crank angle (`TorsionFigures::hysteresis_rad`).
pub const HYSTERESIS_LOSS: Quantity = Quantity {
    key: "hysteresis_loss_arcmin",
    unit: "arcmin",
    label: "hysteresis loss (friction, at zero torque)",
    effect: Effect::Torsion,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| friction_figures(r, |f| units::arcmin(f.hysteresis_rad))),
};

/// The energy friction takes per cycle of a torsion loop, its area ∮ T dγ, J, at each locked
/// crank angle (`TorsionFigures::loop_energy_nmm`).
pub const HYSTERESIS_ENERGY: Quantity = Quantity {
    key: "hysteresis_energy_j",
    unit: "J",
    label: "energy per cycle of the torsion loop",
    effect: Effect::Torsion,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| friction_figures(r, |f| 1e-3 * f.loop_energy_nmm)),
};

/// The largest (`largest` true) or smallest value of a per-crank curve of the registry, with
/// the crank angle where it occurs.
fn curve_extreme((r, c): (&ReducerResult, &[f64]), q: &Quantity, largest: bool) -> Option<Extreme> {
    let Read::ReducerCurves(read) = q.read else {
        return None;
    };
    let rows = read(r)?;
    let ((lo, klo), (hi, khi)) = extremes(rows.iter().last()?);
    let (value, k) = if largest { (hi, khi) } else { (lo, klo) };
    Some(at(value, Site::Locked(crank(c, k))))
}

/// The largest torsion lost motion over the locked crank angles, arcmin.
pub const MAX_TORSION_LOST_MOTION: Quantity = Quantity {
    key: "max_lost_motion_arcmin",
    unit: "arcmin",
    label: "max lost motion of the reducer (±3 % of rated torque)",
    effect: Effect::Torsion,
    shape: Shape::Scalar,
    of: Some("lost_motion_arcmin"),
    read: Read::ReducerScalar(|r, c| curve_extreme((r, c), &TORSION_LOST_MOTION, true)),
};

/// The largest torsion backlash over the locked crank angles, arcmin.
pub const MAX_TORSION_BACKLASH: Quantity = Quantity {
    key: "max_backlash_arcmin",
    unit: "arcmin",
    label: "max backlash of the reducer (torsion dead band)",
    effect: Effect::Torsion,
    shape: Shape::Scalar,
    of: Some("backlash_arcmin"),
    read: Read::ReducerScalar(|r, c| curve_extreme((r, c), &TORSION_BACKLASH, true)),
};

/// The smallest torsional rigidity over the locked crank angles, N·m/arcmin.
pub const MIN_TORSIONAL_RIGIDITY: Quantity = Quantity {
    key: "min_torsional_rigidity_nm_per_arcmin",
    unit: "N·m/arcmin",
    label: "min torsional rigidity",
    effect: Effect::Torsion,
    shape: Shape::Scalar,
    of: Some("torsional_rigidity_nm_per_arcmin"),
    read: Read::ReducerScalar(|r, c| curve_extreme((r, c), &TORSIONAL_RIGIDITY, false)),
};

/// The largest hysteresis loss over the locked crank angles, arcmin.
pub const MAX_HYSTERESIS_LOSS: Quantity = Quantity {
    key: "max_hysteresis_loss_arcmin",
    unit: "arcmin",
    label: "max hysteresis loss of the reducer (friction)",
    effect: Effect::Torsion,
    shape: Shape::Scalar,
    of: Some("hysteresis_loss_arcmin"),
    read: Read::ReducerScalar(|r, c| curve_extreme((r, c), &HYSTERESIS_LOSS, true)),
};

/// The crank bearing's equivalent dynamic load P = (mean of Fb^p over the sweep)^(1/p), N
/// (`BearingLife::equivalent_load_n`).
pub const BEARING_EQUIVALENT_LOAD: Quantity = Quantity {
    key: "bearing_equivalent_load_n",
    unit: "N",
    label: "crank-bearing equivalent load P",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: None,
    read: Read::DiscScalar(|d, _| {
        (d.bearing_life).map(|b| at(b.equivalent_load_n, Site::Rule(Rule::BearingEquivalentLoad)))
    }),
};

/// The crank bearing's rating life L10h = (C/P)^p·10⁶/(60·n·(1 + 1/nc)), hours, n the input
/// speed (`BearingLife::life_h`); `results::UNBOUNDED_LIFE_H` when it has no finite bound,
/// its place saying so.
pub const BEARING_LIFE: Quantity = Quantity {
    key: "bearing_life_h",
    unit: "h",
    label: "crank-bearing rating life L10h",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: None,
    read: Read::DiscScalar(|d, _| {
        let b = d.bearing_life?;
        let load_n = b.equivalent_load_n;
        let site = match b.is_unbounded() {
            false => Site::Life { load_n },
            true => Site::Unbounded(Unbounded::Life { load_n }),
        };
        Some(at(b.life_h?, site))
    }),
};

/// The output pins' stresses, when the scene computes them (`Effect::Strength`).
fn pin_stress(r: &ReducerResult) -> Option<&super::strength::PinStress> {
    r.pin_stress.as_ref()
}

/// σ_b = 32·M/(π·d³) of each output pin at its most loaded section, MPa, one curve per pin
/// (`PinStress::bending_stress_mpa`; `equilibrium::pin_stress`): every disc's force on the pin
/// summed as vectors, on the pin that bends (the pin, or the pin inside a free sleeve).
pub const PIN_BENDING_STRESS: Quantity = Quantity {
    key: "pin_bending_stress_mpa",
    unit: "MPa",
    label: "output-pin bending stress",
    effect: Effect::Strength,
    shape: Shape::PerPin,
    of: None,
    read: Read::ReducerCurves(|r| Some(Rows::Borrowed(&pin_stress(r)?.bending_stress_mpa))),
};

/// The largest output-pin bending stress, MPa, with the pin and the crank angle.
pub const MAX_PIN_BENDING_STRESS: Quantity = Quantity {
    key: "max_pin_bending_stress_mpa",
    unit: "MPa",
    label: "max pin bending stress",
    effect: Effect::Strength,
    shape: Shape::Scalar,
    of: Some("pin_bending_stress_mpa"),
    read: Read::ReducerScalar(|r, c| {
        Some(largest(c, &pin_stress(r)?.bending_stress_mpa, Part::Pin))
    }),
};

/// The largest peak shear stress 4·V/(3·A) of an output pin, MPa, with the pin and the crank
/// angle (`PinStress::shear_stress_mpa`).
pub const MAX_PIN_SHEAR_STRESS: Quantity = Quantity {
    key: "max_pin_shear_stress_mpa",
    unit: "MPa",
    label: "max pin shear stress",
    effect: Effect::Strength,
    shape: Shape::Scalar,
    of: None,
    read: Read::ReducerScalar(|r, c| Some(largest(c, &pin_stress(r)?.shear_stress_mpa, Part::Pin))),
};

/// The pins' safety against yield in bending: yield strength / the largest bending stress,
/// with the pins' yield strength (`roller_material.yield_strength_mpa`); the largest double,
/// said "unbounded", when no pin is loaded.
pub const PIN_BENDING_SAFETY: Quantity = Quantity {
    key: "pin_bending_safety",
    unit: "",
    label: "pin bending safety (yield / stress)",
    effect: Effect::Strength,
    shape: Shape::Scalar,
    of: None,
    read: Read::ReducerScalar(|r, c| {
        let p = pin_stress(r)?;
        let yield_mpa = p.yield_strength_mpa?;
        let most = largest(c, &p.bending_stress_mpa, Part::Pin);
        let safety = yield_mpa / most.value;
        Some(match safety.is_finite() {
            true => Extreme {
                value: safety,
                at: most.at,
            },
            false => at(f64::MAX, Site::Unbounded(Unbounded::PinSafety)),
        })
    }),
};

/// The shorter of the disc's and the rollers' rolling-contact fatigue lives, hours
/// (`FatigueLives::shorter`, `contact::fatigue`), naming the part and the pressure;
/// `results::UNBOUNDED_LIFE_H` when neither takes damage.
pub const MIN_CONTACT_FATIGUE_LIFE: Quantity = Quantity {
    key: "min_contact_fatigue_life_h",
    unit: "h",
    label: "contact fatigue life (shorter of disc and rollers)",
    effect: Effect::Strength,
    shape: Shape::Scalar,
    of: None,
    read: Read::DiscOrCycle(
        |d, c| {
            let f = d.loaded.strength?.fatigue?;
            let (value, part) = f.shorter()?;
            let pressure_mpa = f.pressure_mpa;
            // Where the largest pressure is (the one the life is at), when the curves hold it.
            let place = rollers(d)
                .map(|r| max_entry(&r.pressure_mpa))
                .filter(|&(p, _, _)| p == pressure_mpa)
                .map(|(_, i, k)| part_at(c, Part::Roller, i, k));
            let site = match super::results::is_unbounded(value) {
                false => Site::Fatigue {
                    part,
                    pressure_mpa,
                    at: place,
                },
                true => Site::Unbounded(Unbounded::Fatigue { part, pressure_mpa }),
            };
            Some(at(value, site))
        },
        duty_fatigue,
    ),
};

/// The crank bearing's static safety s0 = C0 / the largest bearing force (ISO 76), with
/// `crank_bearing.static_load_rating_n`; the largest double, said "unbounded", when the
/// bearing carries nothing.
pub const STATIC_SAFETY: Quantity = Quantity {
    key: "static_safety",
    unit: "",
    label: "crank-bearing static safety s0",
    effect: Effect::Strength,
    shape: Shape::Scalar,
    of: None,
    read: Read::DiscScalar(|d, c| {
        let s = d.loaded.strength?.static_safety?;
        // Where the largest bearing force is, when the curve holds it.
        let place = (d.loaded.bearing.as_ref())
            .map(|b| extremes(&b.force_n).1)
            .filter(|&(f, _)| f == s.largest_force_n)
            .map(|(_, k)| crank(c, k));
        let site = match super::results::is_unbounded(s.safety) {
            false => Site::StaticSafety {
                force_n: s.largest_force_n,
                at: place,
            },
            true => Site::Unbounded(Unbounded::StaticSafety),
        };
        Some(at(s.safety, site))
    }),
};

/// The shortest contact fatigue life under a duty cycle (Palmgren–Miner, the flanks apart,
/// `engine::duty_fatigue`) over its discs and parts, naming them; `None` when not computed.
fn duty_fatigue(d: &DutyCycle) -> Option<Extreme> {
    let several = d.contact_fatigue.len() > 1;
    (d.contact_fatigue.iter().enumerate())
        .flat_map(|(k, f)| [(f.disc_h, "disc", k), (f.rollers_h, "rollers", k)])
        .filter_map(|(h, part, k)| Some((h?, part, k)))
        .reduce(|a, b| if b.0 < a.0 { b } else { a })
        .map(|(value, part, k)| {
            let unbounded = super::results::is_unbounded(value);
            let site = match unbounded {
                false => Site::DutyFatigue { part },
                true => Site::Unbounded(Unbounded::DutyFatigue { part }),
            };
            let mut e = at(value, site);
            e.at.disc = (several && !unbounded).then_some(k);
            e
        })
}

/// A duty cycle's figure of disc `k` at `site`, naming the disc with several discs.
fn of_disc(d: &DutyCycle, k: usize, value: f64, site: Site) -> Extreme {
    let mut e = at(value, site);
    e.at.disc = (d.life.len() > 1).then_some(k);
    e
}

/// The crank bearing's rating life under a duty cycle, hours (ISO 281 with Palmgren–Miner,
/// `engine::duty_cycle`): L10h = (C/P)^p·10⁶ / (60·Σ sᵢ·nᵢ·(1 + 1/nc)) with
/// P = (Σ sᵢ·nᵢ·Pᵢ^p / Σ sᵢ·nᵢ)^(1/p); with several discs the shortest disc's
/// (`DutyCycle::shortest_life`); `results::UNBOUNDED_LIFE_H` when it has no finite bound.
pub const DUTY_LIFE: Quantity = Quantity {
    key: "duty_life_h",
    unit: "h",
    label: "crank-bearing life under the duty cycle L10h",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: None,
    read: Read::CycleScalar(|d| {
        let (k, b) = d.shortest_life()?;
        let site = match b.is_unbounded() {
            true => Site::Unbounded(Unbounded::DutyLife),
            false => Site::DutyLife {
                load_n: b.equivalent_load_n,
                mean_speed_rpm: d.mean_speed_rpm,
            },
        };
        Some(of_disc(d, k, b.life_h?, site))
    }),
};

/// The crank bearing's equivalent load under a duty cycle, P = (Σ sᵢ·nᵢ·Pᵢ^p / Σ sᵢ·nᵢ)^(1/p),
/// N; with several discs the largest disc's.
pub const DUTY_EQUIVALENT_LOAD: Quantity = Quantity {
    key: "duty_equivalent_load_n",
    unit: "N",
    label: "crank-bearing equivalent load under the duty cycle P",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: None,
    read: Read::CycleScalar(|d| {
        let (k, b) = d.life.iter().enumerate().reduce(|a, b| {
            if b.1.equivalent_load_n > a.1.equivalent_load_n {
                b
            } else {
                a
            }
        })?;
        let site = Site::Rule(Rule::DutyEquivalentLoad);
        Some(of_disc(d, k, b.equivalent_load_n, site))
    }),
};

/// The root-mean-cube output torque of a duty cycle weighted by revolutions,
/// T_eq = (Σ sᵢ·nᵢ·|Tᵢ|³ / Σ sᵢ·nᵢ)^(1/3), N·m (`DutyCycle::equivalent_torque_nmm`).
pub const EQUIVALENT_TORQUE: Quantity = Quantity {
    key: "equivalent_torque_nm",
    unit: "N·m",
    label: "equivalent output torque (root-mean-cube)",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: None,
    read: Read::CycleScalar(|d| {
        let site = Site::Rule(Rule::EquivalentTorque);
        Some(at(units::nm(d.equivalent_torque_nmm), site))
    }),
};

/// The time-weighted mean input speed of a duty cycle, n_m = Σ sᵢ·nᵢ, rpm.
pub const MEAN_SPEED: Quantity = Quantity {
    key: "mean_speed_rpm",
    unit: "rpm",
    label: "mean input speed",
    effect: Effect::Bearing,
    shape: Shape::Scalar,
    of: None,
    read: Read::CycleScalar(|d| Some(at(d.mean_speed_rpm, Site::Rule(Rule::MeanSpeed)))),
};

/// The mean efficiency of a duty cycle weighted by energy, Σ sᵢ·Dᵢ / Σ sᵢ·Eᵢ (each bin's
/// energy delivered and entering, `engine::duty_cycle`), dimensionless
/// (`DutyCycle::mean_efficiency`).
pub const DUTY_MEAN_EFFICIENCY: Quantity = Quantity {
    key: "duty_mean_efficiency",
    unit: "",
    label: "mean efficiency over the duty cycle (by energy)",
    effect: Effect::Efficiency,
    shape: Shape::Scalar,
    of: None,
    read: Read::CycleScalar(|d| {
        let site = Site::Rule(Rule::DutyMeanEfficiency);
        Some(at(d.mean_efficiency?, site))
    }),
};

/// The reducer's efficiency figures of a scene, when computed.
fn reducer_efficiency(r: &ReducerResult) -> Option<&ReducerEfficiency> {
    r.efficiency.as_ref()?.reducer.as_ref()
}

/// η(φ) = P_out/(P_out + loss(φ)), dimensionless, at each crank angle
/// (`ReducerEfficiency::efficiency`, MODEL.md "Friction, efficiency and heat").
pub const EFFICIENCY: Quantity = Quantity {
    key: "efficiency",
    unit: "",
    label: "efficiency η",
    effect: Effect::Efficiency,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| reducer_efficiency(r).map(|e| one(&e.efficiency))),
};

/// The input torque at each crank angle, N·m (`ReducerEfficiency::input_torque_nmm`).
pub const INPUT_TORQUE: Quantity = Quantity {
    key: "input_torque_nm",
    unit: "N·m",
    label: "input torque",
    effect: Effect::Efficiency,
    shape: Shape::Curve,
    of: None,
    read: Read::ReducerCurves(|r| {
        reducer_efficiency(r).map(|e| converted(&e.input_torque_nmm, units::nm))
    }),
};

/// The mean efficiency of the power that flows, dimensionless (`ReducerEfficiency::
/// mean_efficiency`): P_out/(P_out + mean loss), back-driven (P − mean loss)/P.
pub const MEAN_EFFICIENCY: Quantity = Quantity {
    key: "mean_efficiency",
    unit: "",
    label: "mean efficiency",
    effect: Effect::Efficiency,
    shape: Shape::Scalar,
    of: Some("efficiency"),
    read: Read::ReducerScalar(|r, c| {
        reducer_efficiency(r).map(|e| {
            let site = Site::Efficiency {
                driver: e.flow.driver,
                self_locks: e.self_locks,
                locked: e.self_locking_crank_rad.len(),
                angles: c.len(),
            };
            at(e.mean_efficiency, site)
        })
    }),
};

/// The mean power lost to friction on every path, W, with a speed (`EfficiencyCurves::
/// power_loss_w`; a disc's: its contacts').
pub const TOTAL_POWER_LOSS: Quantity = Quantity {
    key: "total_power_loss_w",
    unit: "W",
    label: "power loss",
    effect: Effect::Efficiency,
    shape: Shape::Scalar,
    of: None,
    read: Read::Losses(|e| {
        let p = e.power_loss_w()?;
        Some(at(p.total(), Site::PowerLoss(p)))
    }),
};

/// The steady temperature ambient + P/(h·A), °C (`ReducerEfficiency::temperature_c`).
pub const TEMPERATURE: Quantity = Quantity {
    key: "temperature_c",
    unit: "°C",
    label: "steady temperature",
    effect: Effect::Efficiency,
    shape: Shape::Scalar,
    of: None,
    read: Read::ReducerScalar(|r, _| {
        let t = reducer_efficiency(r)?.temperature_c?;
        Some(at(t, Site::Rule(Rule::Temperature)))
    }),
};

/// Every quantity, curves first, in the order of the results JSON.
///
/// The equilibrium `residual` per angle is left out of the curves on purpose: it is solver
/// noise, not a property of the design, and a golden of noise can only flake.
pub const QUANTITIES: &[&Quantity] = &[
    &CLEARANCE,
    &BACKLASH,
    &BACKLASH_REVERSE,
    &LOST_MOTION,
    &LAG,
    &TE,
    &RATIO,
    &ROLLER_FORCE,
    &CONTACT_PRESSURE,
    &CONTACT_HALF_WIDTH,
    &CONTACTS,
    &FACE_LOAD_FACTOR,
    &DISC_TORQUE,
    &OUTPUT_LAG,
    &PIN_FORCE,
    &BEARING_FORCE,
    &BEARING_ANGLE,
    &BEARING_DEFLECTION,
    &TORSION_LOST_MOTION,
    &TORSION_BACKLASH,
    &TORSIONAL_RIGIDITY,
    &HYSTERESIS_LOSS,
    &HYSTERESIS_ENERGY,
    &EFFICIENCY,
    &INPUT_TORQUE,
    &MIN_CLEARANCE,
    &MAX_LOST_MOTION,
    &MAX_ROLLER_FORCE,
    &MAX_CONTACT_PRESSURE,
    &MIN_ROLLERS_IN_CONTACT,
    &TE_FLUCTUATION,
    &RATIO_FLUCTUATION,
    &MAX_PIN_FORCE,
    &MAX_BEARING_FORCE,
    &MAX_RESIDUAL,
    &MAX_FACE_LOAD_FACTOR,
    &MAX_LINE_LOAD,
    &MAX_TORSION_LOST_MOTION,
    &MAX_TORSION_BACKLASH,
    &MIN_TORSIONAL_RIGIDITY,
    &MAX_HYSTERESIS_LOSS,
    &BEARING_EQUIVALENT_LOAD,
    &BEARING_LIFE,
    &MEAN_EFFICIENCY,
    &TOTAL_POWER_LOSS,
    &TEMPERATURE,
    &EQUIVALENT_TORQUE,
    &MEAN_SPEED,
    &DUTY_EQUIVALENT_LOAD,
    &DUTY_LIFE,
    &DUTY_MEAN_EFFICIENCY,
    &PIN_BENDING_STRESS,
    &MAX_PIN_BENDING_STRESS,
    &MAX_PIN_SHEAR_STRESS,
    &PIN_BENDING_SAFETY,
    &MIN_CONTACT_FATIGUE_LIFE,
    &STATIC_SAFETY,
];

/// A duty cycle's own figures: only a duty-cycle scene has them (`Quantity::for_duty`).
pub const DUTY: &[&Quantity] = &[
    &EQUIVALENT_TORQUE,
    &MEAN_SPEED,
    &DUTY_EQUIVALENT_LOAD,
    &DUTY_LIFE,
    &DUTY_MEAN_EFFICIENCY,
];

/// The figures of one run at one speed and torque that a duty cycle replaces by its own
/// (`DUTY`): a duty-cycle scene has them in each bin's run only, never as the worst bin's (a
/// bin's life or efficiency is not the cycle's).
pub const SINGLE_RUN: &[&Quantity] = &[
    &BEARING_EQUIVALENT_LOAD,
    &BEARING_LIFE,
    &MEAN_EFFICIENCY,
    &TOTAL_POWER_LOSS,
    &TEMPERATURE,
];

/// The quantities along the face width: read only from a scene that resolves the face
/// (`Face::is_resolved`); a limit on one needs such a scene.
pub const NEEDS_FACE: &[&Quantity] = &[&FACE_LOAD_FACTOR, &MAX_FACE_LOAD_FACTOR, &MAX_LINE_LOAD];

/// The quantities read from the closing lags of the rollers (`Detail::Backlash`): computed only
/// when one of them is read.
pub const NEEDS_BACKLASH: &[&Quantity] =
    &[&BACKLASH, &BACKLASH_REVERSE, &LOST_MOTION, &MAX_LOST_MOTION];

/// The angles that wrap (±180°), each with its period in the key's unit (`Quantity::period`).
pub const WRAPS: &[(&Quantity, f64)] = &[(&BEARING_ANGLE, 360.0)];

/// The headline results of a scene, in the order a summary shows them.
pub const SUMMARY: &[&Quantity] = &[
    &MIN_CLEARANCE,
    &MAX_LOST_MOTION,
    &MAX_ROLLER_FORCE,
    &MAX_CONTACT_PRESSURE,
    &MAX_FACE_LOAD_FACTOR,
    &MAX_LINE_LOAD,
    &MAX_PIN_FORCE,
    &MAX_BEARING_FORCE,
    &TE_FLUCTUATION,
    &RATIO_FLUCTUATION,
    &MIN_ROLLERS_IN_CONTACT,
    &MAX_TORSION_LOST_MOTION,
    &MAX_TORSION_BACKLASH,
    &MIN_TORSIONAL_RIGIDITY,
    &MAX_HYSTERESIS_LOSS,
    &BEARING_EQUIVALENT_LOAD,
    &BEARING_LIFE,
    &MEAN_EFFICIENCY,
    &TOTAL_POWER_LOSS,
    &TEMPERATURE,
    &DUTY_LIFE,
    &EQUIVALENT_TORQUE,
    &MEAN_SPEED,
    &DUTY_EQUIVALENT_LOAD,
    &DUTY_MEAN_EFFICIENCY,
    &MAX_PIN_BENDING_STRESS,
    &PIN_BENDING_SAFETY,
    &MIN_CONTACT_FATIGUE_LIFE,
    &STATIC_SAFETY,
];

/// The scalars that are max − min of their curve (`of`) rather than a value on it: a limit on
/// one is the width of a band the curve must fit in, not a level.
pub const SPREADS: &[&Quantity] = &[&TE_FLUCTUATION, &RATIO_FLUCTUATION];

/// The quantities whose values count rollers: every output prints them as whole numbers, any
/// other quantity to four significant digits (`report::table::figure`), and a limit on one
/// must be a whole number (`spec::validate`).
pub const COUNTS: &[&Quantity] = &[&CONTACTS, &MIN_ROLLERS_IN_CONTACT];

/// The quantity with this key.
pub fn find(key: &str) -> Option<&'static Quantity> {
    QUANTITIES.iter().copied().find(|q| q.key == key)
}

/// The per-angle quantity (a curve) with this key: what a golden can compare.
pub fn find_curve(key: &str) -> Option<&'static Quantity> {
    find(key).filter(|q| !q.is_scalar())
}

/// The keys of the per-angle quantities, comma-separated, for messages.
pub fn curve_keys() -> String {
    QUANTITIES
        .iter()
        .filter(|q| !q.is_scalar())
        .map(|q| q.key)
        .collect::<Vec<_>>()
        .join(", ")
}

/// Which side of its limit a value must stay on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// value ≤ limit passes.
    Max,
    /// value ≥ limit passes.
    Min,
}

impl Bound {
    /// The bound as a sign for tables and messages: "≤" or "≥".
    pub fn symbol(self) -> &'static str {
        match self {
            Bound::Max => "≤",
            Bound::Min => "≥",
        }
    }
}

/// A limit a spec can set (`limits.<key>`): a bound on a scalar quantity of every scene that
/// computes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitDef {
    /// Its key under `limits:` (not always the quantity's: `max_te_fluctuation_arcsec` bounds
    /// `te_fluctuation_arcsec`).
    pub key: &'static str,
    /// The scalar quantity it bounds.
    pub quantity: &'static Quantity,
    /// Which side of the limit passes.
    pub bound: Bound,
    /// The values the bounded quantity can physically take, (lowest, highest) in the
    /// limit's unit: a limit outside them is refused at its key (it could never be met, or
    /// never fail). Unbounded (−∞, ∞) where the registry states no range.
    pub range: (f64, f64),
}

/// The range of a quantity the registry states nothing about.
const ANY: (f64, f64) = (f64::NEG_INFINITY, f64::INFINITY);

/// Every limit, in the order the checks table lists them.
pub const LIMITS: &[LimitDef] = &[
    LimitDef {
        key: "min_clearance_mm",
        quantity: &MIN_CLEARANCE,
        bound: Bound::Min,
        range: ANY,
    },
    LimitDef {
        key: "max_roller_force_n",
        quantity: &MAX_ROLLER_FORCE,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "max_contact_pressure_mpa",
        quantity: &MAX_CONTACT_PRESSURE,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "max_face_load_factor",
        quantity: &MAX_FACE_LOAD_FACTOR,
        bound: Bound::Max,
        // The peak line load is at least the mean of its roller's (a limit below 1 could
        // never pass).
        range: (1.0, f64::INFINITY),
    },
    LimitDef {
        key: "max_line_load_n_per_mm",
        quantity: &MAX_LINE_LOAD,
        bound: Bound::Max,
        range: (0.0, f64::INFINITY),
    },
    LimitDef {
        key: "min_rollers_in_contact",
        quantity: &MIN_ROLLERS_IN_CONTACT,
        bound: Bound::Min,
        range: ANY,
    },
    LimitDef {
        key: "max_te_fluctuation_arcsec",
        quantity: &TE_FLUCTUATION,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "max_ratio_fluctuation",
        quantity: &RATIO_FLUCTUATION,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "max_pin_force_n",
        quantity: &MAX_PIN_FORCE,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "max_bearing_force_n",
        quantity: &MAX_BEARING_FORCE,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "max_lost_motion_arcsec",
        quantity: &MAX_LOST_MOTION,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "max_lost_motion_arcmin",
        quantity: &MAX_TORSION_LOST_MOTION,
        bound: Bound::Max,
        range: ANY,
    },
    LimitDef {
        key: "min_torsional_rigidity_nm_per_arcmin",
        quantity: &MIN_TORSIONAL_RIGIDITY,
        bound: Bound::Min,
        range: ANY,
    },
    LimitDef {
        key: "max_hysteresis_loss_arcmin",
        quantity: &MAX_HYSTERESIS_LOSS,
        bound: Bound::Max,
        range: (0.0, f64::INFINITY),
    },
    LimitDef {
        key: "min_bearing_life_h",
        quantity: &BEARING_LIFE,
        bound: Bound::Min,
        range: ANY,
    },
    LimitDef {
        key: "min_duty_life_h",
        quantity: &DUTY_LIFE,
        bound: Bound::Min,
        range: ANY,
    },
    LimitDef {
        key: "min_mean_efficiency",
        quantity: &MEAN_EFFICIENCY,
        bound: Bound::Min,
        range: (0.0, 1.0),
    },
    LimitDef {
        key: "max_power_loss_w",
        quantity: &TOTAL_POWER_LOSS,
        bound: Bound::Max,
        range: (0.0, f64::INFINITY),
    },
    LimitDef {
        key: "max_temperature_c",
        quantity: &TEMPERATURE,
        bound: Bound::Max,
        range: (-273.15, f64::INFINITY),
    },
    LimitDef {
        key: "max_pin_bending_stress_mpa",
        quantity: &MAX_PIN_BENDING_STRESS,
        bound: Bound::Max,
        range: (0.0, f64::INFINITY),
    },
    LimitDef {
        key: "min_pin_bending_safety",
        quantity: &PIN_BENDING_SAFETY,
        bound: Bound::Min,
        range: (0.0, f64::INFINITY),
    },
    LimitDef {
        key: "min_contact_fatigue_life_h",
        quantity: &MIN_CONTACT_FATIGUE_LIFE,
        bound: Bound::Min,
        range: (0.0, f64::INFINITY),
    },
    LimitDef {
        key: "min_static_safety",
        quantity: &STATIC_SAFETY,
        bound: Bound::Min,
        range: (0.0, f64::INFINITY),
    },
];

/// The limit with this key.
pub fn find_limit(key: &str) -> Option<&'static LimitDef> {
    LIMITS.iter().find(|l| l.key == key)
}

/// An optimisation objective (`optimise.objective`): a scalar quantity to minimise.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectiveDef {
    /// Its name in a spec.
    pub name: &'static str,
    /// The scalar quantity it minimises.
    pub quantity: &'static Quantity,
    /// Axis label of a map of it.
    pub label: &'static str,
}

/// Every objective.
pub const OBJECTIVES: &[ObjectiveDef] = &[
    ObjectiveDef {
        name: "ratio_fluctuation",
        quantity: &RATIO_FLUCTUATION,
        label: "ratio fluctuation κmax − κmin",
    },
    ObjectiveDef {
        name: "te_fluctuation",
        quantity: &TE_FLUCTUATION,
        label: "TE fluctuation δmax − δmin (arcsec)",
    },
    ObjectiveDef {
        name: "max_roller_force",
        quantity: &MAX_ROLLER_FORCE,
        label: "largest roller force (N)",
    },
    ObjectiveDef {
        name: "lost_motion",
        quantity: &MAX_LOST_MOTION,
        label: "largest lost motion (arcsec)",
    },
    ObjectiveDef {
        name: "max_bearing_force",
        quantity: &MAX_BEARING_FORCE,
        label: "largest bearing force (N)",
    },
    ObjectiveDef {
        name: "max_face_load_factor",
        quantity: &MAX_FACE_LOAD_FACTOR,
        label: "largest face load factor (peak / mean line load)",
    },
    ObjectiveDef {
        name: "max_contact_pressure",
        quantity: &MAX_CONTACT_PRESSURE,
        label: "largest Hertz pressure (MPa)",
    },
];

/// The objective with this name.
pub fn find_objective(name: &str) -> Option<&'static ObjectiveDef> {
    OBJECTIVES.iter().find(|o| o.name == name)
}

/// Every objective name, comma-separated, for messages.
pub fn objective_names() -> String {
    OBJECTIVES
        .iter()
        .map(|o| o.name)
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Keys are unique across the registry, limits and objectives; every limit and objective
    /// bounds a scalar; every scalar that is an extreme of a curve names a curve that exists.
    #[test]
    fn the_registry_is_consistent() {
        for (i, a) in QUANTITIES.iter().enumerate() {
            assert!(
                QUANTITIES[i + 1..].iter().all(|b| b.key != a.key),
                "{} twice",
                a.key
            );
            if let Some(curve) = a.of {
                assert!(find_curve(curve).is_some(), "{} is of {curve}", a.key);
                assert_eq!(find(curve).unwrap().effect, a.effect, "{}", a.key);
            }
        }
        for l in LIMITS {
            assert!(l.quantity.is_scalar(), "{}", l.key);
            assert!(find(l.quantity.key).is_some(), "{}", l.key);
        }
        for o in OBJECTIVES {
            assert!(o.quantity.is_scalar(), "{}", o.name);
        }
        for q in SUMMARY {
            assert!(q.is_scalar(), "{}", q.key);
        }
    }
}
