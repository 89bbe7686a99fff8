//! Where a scalar of a sweep occurs, or what it rests on, as data (`quantity::Extreme::at`):
//! which bin of a duty cycle, which disc of several, which part and index, which crank angle.
//! Built by the registry (`model::quantity`) where it finds the extreme, and by
//! `engine::golden::compare` for a golden comparison's points; said in words only by
//! `report::place`, for every view (terminal, results JSON, JUnit, the review, explain, bless).
//!
//! Units and frames: a crank angle is the input crank's φ, rad, counter-clockwise positive,
//! the disc centre at (e, 0) at φ = 0 (MODEL.md "Conventions"), as `SceneResult::crank_rad`
//! holds it; roller i sits at 2πi/np, pin j at 2πj/M, both counted from 0; forces N, pressures
//! MPa, speeds rpm, powers W, torques N·mm.

use super::friction::PathLosses;
use super::power_flow::Driver;
use super::results::{MinClearance, MinCoverage};

/// Where a scalar occurs: the bin and disc whose run holds it (outermost first), and the site
/// on that run.
#[derive(Debug, Clone, PartialEq)]
pub struct Place {
    /// In a duty-cycle scene, the bin whose run holds the worst value (`Quantity::scalar`).
    pub bin: Option<Bin>,
    /// With several discs, the disc whose value it is (0-based, disc k at φ + 2πk/N).
    pub disc: Option<usize>,
    /// Where on that run, or what the value rests on.
    pub site: Site,
}

impl Place {
    /// A site of the scene's own run (no bin, no disc).
    pub fn of(site: Site) -> Place {
        Place {
            bin: None,
            disc: None,
            site,
        }
    }
}

/// A bin of a duty cycle, with what a reader needs beside its index: its torque and speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bin {
    /// Its index in `scenes[].duty_cycle`, from 0.
    pub index: usize,
    /// Its output torque, N·mm (signed: negative back-drives).
    pub output_torque_nmm: f64,
    /// Its input speed, rpm.
    pub input_speed_rpm: f64,
}

/// One of a run's crank angles.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crank {
    /// Its index in the run's `crank_rad`.
    pub index: usize,
    /// φ there, rad.
    pub rad: f64,
}

/// A part of which a scene has one curve each.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// A ring roller, i at 2πi/np.
    Roller,
    /// An output pin, j at 2πj/M.
    Pin,
}

impl Part {
    /// Its name, in a column's name and in a place: "roller", "pin".
    pub fn name(self) -> &'static str {
        match self {
            Part::Roller => "roller",
            Part::Pin => "pin",
        }
    }
}

/// One part's curve at one crank angle: roller or pin `index` at `crank`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartAt {
    /// Which kind of part.
    pub part: Part,
    /// Which one, from 0.
    pub index: usize,
    /// At which of the run's crank angles.
    pub crank: Crank,
}

/// Where on a run a scalar occurs, or what it rests on.
#[derive(Debug, Clone, PartialEq)]
pub enum Site {
    /// The crank angle of a curve's extreme.
    Crank(Crank),
    /// The part and crank angle of the extreme of per-part curves.
    Part(PartAt),
    /// An extreme sought over the scene's own angles only (the unloaded lost motion).
    Sampled {
        /// Where it is.
        crank: Crank,
        /// How many crank angles the scene has.
        angles: usize,
    },
    /// The locked crank angle of a torsion figure's extreme.
    Locked(Crank),
    /// max − min of a curve.
    Spread {
        /// Where its min is.
        min: Crank,
        /// Where its max is.
        max: Crank,
    },
    /// The smallest gap.
    Gap {
        /// Its roller, crank angle (over the whole mesh a sample of the period, not one of the
        /// run's angles) and place on the tooth.
        min: MinClearance,
        /// What it was sought over.
        over: MinCoverage,
    },
    /// The largest line load along the face.
    Slice {
        /// Its roller and crank angle.
        at: PartAt,
        /// Its slice, 0 at z = −B/2.
        slice: usize,
        /// Of how many slices.
        slices: usize,
    },
    /// The formula a figure is, with no place of its own.
    Rule(Rule),
    /// A bearing's rating life.
    Life {
        /// At its equivalent load P, N.
        load_n: f64,
    },
    /// A bearing's life under a duty cycle.
    DutyLife {
        /// At its equivalent load P, N.
        load_n: f64,
        /// The cycle's mean input speed, rpm.
        mean_speed_rpm: f64,
    },
    /// The shorter contact fatigue life.
    Fatigue {
        /// Its part (`FatigueLives::shorter`: "disc", "rollers").
        part: &'static str,
        /// The Hertz pressure it is at, MPa.
        pressure_mpa: f64,
        /// The roller and angle of that pressure, when the curves hold it.
        at: Option<PartAt>,
    },
    /// The shorter contact fatigue life under a duty cycle (Miner, the flanks apart).
    DutyFatigue {
        /// Its part ("disc", "rollers").
        part: &'static str,
    },
    /// The static safety C0 / the largest bearing force.
    StaticSafety {
        /// The largest bearing force, N.
        force_n: f64,
        /// Its angle, when the curve holds it.
        at: Option<Crank>,
    },
    /// The mean power lost on each path, W.
    PowerLoss(PathLosses),
    /// What a mean efficiency is of (`model::power_flow`).
    Efficiency {
        /// Whose power enters.
        driver: Driver,
        /// Whether the mean loss takes all of the power entering at the output.
        self_locks: bool,
        /// At how many crank angles the input must push (back-driven).
        locked: usize,
        /// Of how many crank angles.
        angles: usize,
    },
    /// A figure with no finite bound, and why.
    Unbounded(Unbounded),
    /// A point of a golden curve's comparison (`engine::golden::Point`).
    Golden(GoldenAt),
}

/// A point of a golden comparison: a column of the curves at one of the angles compared.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GoldenAt {
    /// The roller or pin whose column it is (`roller_3`: roller 3); `None` for a quantity of
    /// one curve (`te_arcsec`).
    pub part: Option<(Part, usize)>,
    /// The crank angle, degrees, as compared: the golden file's (as read from it) or the run's
    /// (`units::deg` of `crank_rad`), whichever sets the angles (`engine::golden::compare`).
    /// In degrees, not rad, because a golden's angles are degrees and a round trip through
    /// radians can move the printed hundredth (1.875° reads 1.87° after it).
    pub crank_deg: f64,
}

/// The formula of a figure that is no extreme (a mean, an equivalent).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// P = (mean of Fb^p over the sweep)^(1/p).
    BearingEquivalentLoad,
    /// P = (Σ share·n·P^p / Σ share·n)^(1/p) over a duty cycle's bins.
    DutyEquivalentLoad,
    /// T_eq = (Σ share·n·|T|³ / Σ share·n)^(1/3) over the bins.
    EquivalentTorque,
    /// n_m = Σ share·n over the bins.
    MeanSpeed,
    /// Σ energy delivered / Σ energy entering over the bins.
    DutyMeanEfficiency,
    /// ambient + mean power loss/(h·A).
    Temperature,
}

/// Why a figure has no finite bound (written as the largest double).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Unbounded {
    /// A rating life.
    Life {
        /// Its equivalent load P, N: 0 when nothing loads the bearing, else the life is beyond
        /// every double.
        load_n: f64,
    },
    /// The pins' bending safety: no pin is bent.
    PinSafety,
    /// A contact fatigue life: the part takes no damage.
    Fatigue {
        /// The part ("disc", "rollers").
        part: &'static str,
        /// At this Hertz pressure, MPa.
        pressure_mpa: f64,
    },
    /// The static safety: the bearing carries no force.
    StaticSafety,
    /// A contact fatigue life under a duty cycle: no bin wears the part.
    DutyFatigue {
        /// The part ("disc", "rollers").
        part: &'static str,
    },
    /// A bearing life under a duty cycle: no bin loads the bearing enough to wear it.
    DutyLife,
}
