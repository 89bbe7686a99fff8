//! Where a scalar occurs, in words (`model::place::Place`): the one place every view (the
//! checks' "where", the headline results, the results JSON's `at`, JUnit, the review's
//! subtitles) says it. Crank angles read in degrees to two decimals ("crank 12.30°"), other
//! figures to `numeric::number`'s four significant digits.

use crate::model::friction::PathLosses;
use crate::model::place::{Bin, Crank, Part, PartAt, Place, Rule, Site, Unbounded};
use crate::model::results::{Driver, MinCoverage};
use crate::numeric::{number, phase};
use crate::units;

/// How a one-angle scene's extreme says where it was sought: its place already names the
/// angle ("crank 0.00°, the scene's only crank angle"), said once.
pub const ONLY_ANGLE: &str = "the scene's only crank angle";

/// A place in words: "bin 2 (40 N·m, 1500 rpm): disc 1: roller 3 at crank 12.30°".
pub fn text(p: &Place) -> String {
    let bin = p.bin.as_ref().map_or(String::new(), bin);
    let disc = p.disc.map_or(String::new(), |k| format!("disc {k}: "));
    format!("{bin}{disc}{}", site(&p.site))
}

/// "bin 2 (40 N·m, 1500 rpm): ".
fn bin(b: &Bin) -> String {
    format!(
        "bin {} ({} N·m, {} rpm): ",
        b.index,
        number(units::nm(b.output_torque_nmm)),
        number(b.input_speed_rpm)
    )
}

/// A crank angle φ, rad, as every place reads it: "crank 12.30°".
pub fn crank(rad: f64) -> String {
    format!("crank {:.2}°", units::deg(rad))
}

/// "roller 3 at crank 12.30°", "pin 0 at crank 1.00°".
fn part_at(a: &PartAt) -> String {
    let part = match a.part {
        Part::Roller => "roller",
        Part::Pin => "pin",
    };
    format!("{part} {} at {}", a.index, crank(a.crank.rad))
}

/// The site on a run, in words.
fn site(s: &Site) -> String {
    let deg = |c: &Crank| format!("{:.2}°", units::deg(c.rad));
    match s {
        Site::Crank(c) => crank(c.rad),
        Site::Part(a) => part_at(a),
        Site::Sampled { crank: c, angles: 1 } => format!("{}, {ONLY_ANGLE}", crank(c.rad)),
        Site::Sampled { crank: c, angles: n } => {
            format!("{}, over the scene's {}", crank(c.rad), angles(*n))
        }
        Site::Locked(c) => format!("{} locked", crank(c.rad)),
        Site::Spread { min, max } => format!("min at {}, max at {}", deg(min), deg(max)),
        Site::Gap {
            roller,
            crank_rad,
            tooth_phase,
            over,
        } => format!(
            "roller {roller} at {}, tooth phase {} (0 root, 0.5 tip), {}",
            crank(*crank_rad),
            phase(*tooth_phase),
            sought_over(over)
        ),
        Site::Slice { at, slice, slices } => format!(
            "{}, slice {slice} of {slices} (slice 0 at z = −B/2)",
            part_at(at)
        ),
        Site::Rule(r) => rule(*r).to_string(),
        Site::Life { load_n } => format!("at P = {} N", number(*load_n)),
        Site::DutyLife {
            load_n,
            mean_speed_rpm,
        } => format!(
            "at P = {} N, mean speed {} rpm",
            number(*load_n),
            number(*mean_speed_rpm)
        ),
        Site::Fatigue {
            part,
            pressure_mpa,
            at,
        } => format!(
            "{part} at {} MPa{}",
            number(*pressure_mpa),
            at.as_ref().map_or(String::new(), |a| format!(", {}", part_at(a)))
        ),
        Site::DutyFatigue { part } => format!("{part} under the cycle (Miner, flanks apart)"),
        Site::StaticSafety { force_n, at } => format!(
            "C0 / {} N{}",
            number(*force_n),
            at.map_or(String::new(), |c| format!(" at {}", crank(c.rad)))
        ),
        Site::PowerLoss(p) => power_loss(p),
        Site::Efficiency {
            driver,
            self_locks,
            locked,
            angles,
        } => efficiency(*driver, *self_locks, *locked, *angles),
        Site::Unbounded(u) => unbounded(u),
    }
}

/// "1 crank angle", "4 crank angles".
fn angles(n: usize) -> String {
    format!("{n} crank angle{}", if n == 1 { "" } else { "s" })
}

/// What the smallest gap was sought over: the whole period of the gaps, its step and the error
/// bound, or the scene's angles alone.
fn sought_over(coverage: &MinCoverage) -> String {
    match coverage {
        MinCoverage::Period(p) => format!(
            "over the whole period of {}° sampled every {}° (error ≤ {} µm)",
            number(units::deg(p.period_rad)),
            number(units::deg(p.step_rad)),
            number(units::um(p.error_bound_mm))
        ),
        MinCoverage::Angles(n) => format!("over the scene's {} only", angles(*n)),
    }
}

/// The formula a figure is.
fn rule(r: Rule) -> &'static str {
    match r {
        Rule::BearingEquivalentLoad => "(mean of Fb^p over the sweep)^(1/p)",
        Rule::DutyEquivalentLoad => "(Σ share·n·P^p / Σ share·n)^(1/p) over the bins",
        Rule::EquivalentTorque => "(Σ share·n·|T|³ / Σ share·n)^(1/3) over the bins",
        Rule::MeanSpeed => "Σ share·n over the bins",
        Rule::DutyMeanEfficiency => {
            "energy delivered / energy entering over the bins, each as its power flows"
        }
        Rule::Temperature => "ambient + mean power loss/(h·A)",
    }
}

/// The mean power lost on each path, W.
fn power_loss(p: &PathLosses) -> String {
    format!(
        "mean over the crank angles: rollers {} W, output pins {} W, crank bearing {} W, \
         no-load {} W",
        number(p.rollers),
        number(p.output_pins),
        number(p.crank_bearing),
        number(p.no_load)
    )
}

/// What a scene's mean efficiency is of, where it is read (the headline, a limit's row, the
/// review): with the input driving P_out/(P_out + mean loss); with the output driving (T < 0)
/// the back-driven (P − mean loss)/P, the crank angles where the input must still push, and,
/// when the mean loss takes all of P, that the scene self-locks (`engine::power_flow`).
fn efficiency(driver: Driver, self_locks: bool, locked: usize, angles: usize) -> String {
    const OVER: &str = "over the scene's crank angles";
    const BACK: &str = "back-driven (the output drives, T < 0)";
    match (driver, self_locks) {
        (Driver::Input, _) => format!("P_out/(P_out + mean loss) {OVER}"),
        (Driver::Output, true) => format!(
            "SELF-LOCKS: {BACK}, the mean loss exceeds the power P = |T|·ω_out entering at the \
             output, (P − mean loss)/P ≤ 0 {OVER}; the input must push at {locked} of {angles} \
             crank angles (self_locking_deg)"
        ),
        (Driver::Output, false) => {
            let at =
                format!("{BACK}: (P − mean loss)/P, P = |T|·ω_out entering at the output, {OVER}");
            match locked {
                0 => at,
                _ => format!(
                    "{at}; self-locks at {locked} of {angles} crank angles (self_locking_deg)"
                ),
            }
        }
    }
}

/// Why a figure has no finite bound, and that it is written as the largest double.
fn unbounded(u: &Unbounded) -> String {
    match u {
        Unbounded::Life { load_n } if *load_n == 0.0 => "unbounded: P = 0 N, no load wears the \
                                                          bearing (written as 1.798e308 h, the \
                                                          largest number)"
            .to_string(),
        Unbounded::Life { load_n } => format!(
            "unbounded: at P = {} N the life is beyond 1.798e308 h, the largest number",
            number(*load_n)
        ),
        Unbounded::PinSafety => {
            "unbounded: no pin is bent (written as 1.798e308, the largest number)".to_string()
        }
        Unbounded::Fatigue { part, pressure_mpa } => format!(
            "unbounded: the {part} take no damage at {} MPa (written as 1.798e308 h, the largest \
             number)",
            number(*pressure_mpa)
        ),
        Unbounded::StaticSafety => "unbounded: the bearing carries no force (written as \
                                    1.798e308, the largest number)"
            .to_string(),
        Unbounded::DutyFatigue { part } => format!(
            "unbounded: no bin wears the {part} (written as 1.798e308 h, the largest number)"
        ),
        Unbounded::DutyLife => "unbounded: no bin loads the bearing enough to wear it (written \
                                as 1.798e308 h, the largest number)"
            .to_string(),
    }
}

/// Whether a place names the scene's only crank angle already (`ONLY_ANGLE`): a headline
/// adds no sampling to it.
pub fn names_only_angle(p: &Place) -> bool {
    matches!(p.site, Site::Sampled { angles: 1, .. })
}

/// Whether a place's words end on the scene's crank angles after a comma (", over the scene's
/// …"), so that a headline adds only their step to it: an extreme sought over the scene's
/// angles, a gap sought over them alone, a back-driven efficiency that does not self-lock.
pub fn counts_scene_angles(p: &Place) -> bool {
    match p.site {
        Site::Sampled { angles, .. } => angles != 1,
        Site::Gap { over, .. } => matches!(over, MinCoverage::Angles(_)),
        Site::Efficiency {
            driver,
            self_locks,
            ..
        } => driver == Driver::Output && !self_locks,
        _ => false,
    }
}
