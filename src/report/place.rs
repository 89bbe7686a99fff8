//! Where a scalar occurs, in words (`model::place::Place`): the one place every view (the
//! checks' "where", the headline results, the results JSON's `at`, JUnit, the review's
//! subtitles) says it. Crank angles read in degrees to two decimals ("crank 12.30°"), other
//! figures to `numeric::number`'s four significant digits.

use crate::model::friction::PathLosses;
use crate::model::place::{Bin, Crank, GoldenAt, PartAt, Place, Rule, Site, Unbounded};
use crate::model::power_flow::Driver;
use crate::model::results::MinCoverage;
use crate::numeric::{number, phase};
use crate::units;
use std::borrow::Borrow;

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
    crank_deg(units::deg(rad))
}

/// A crank angle held in degrees (a golden's): "crank 12.30°".
fn crank_deg(deg: f64) -> String {
    format!("crank {deg:.2}°")
}

/// "roller 3 at crank 12.30°", "pin 0 at crank 1.00°".
fn part_at(a: &PartAt) -> String {
    format!("{} {} at {}", a.part.name(), a.index, crank(a.crank.rad))
}

/// A golden point: "roller 3 at crank 12.30°", or "crank 12.30°" on a curve of its own.
fn golden_at(g: &GoldenAt) -> String {
    match g.part {
        Some((part, index)) => format!("{} {index} at {}", part.name(), crank_deg(g.crank_deg)),
        None => crank_deg(g.crank_deg),
    }
}

/// The site on a run, in words.
fn site(s: &Site) -> String {
    let deg = |c: &Crank| format!("{:.2}°", units::deg(c.rad));
    match s {
        Site::Crank(c) => crank(c.rad),
        Site::Part(a) => part_at(a),
        Site::Sampled {
            crank: c,
            angles: 1,
        } => format!("{}, {ONLY_ANGLE}", crank(c.rad)),
        Site::Sampled {
            crank: c,
            angles: n,
        } => format!(
            "{}, over the scene's {}",
            crank(c.rad),
            counted(*n, "crank angle")
        ),
        Site::Locked(c) => format!("{} locked", crank(c.rad)),
        Site::Spread { min, max } => format!("min at {}, max at {}", deg(min), deg(max)),
        Site::Gap { min, over } => format!(
            "roller {} at {}, tooth phase {} (0 root, 0.5 tip), {}",
            min.roller,
            crank(min.crank_rad),
            phase(min.tooth_phase),
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
            at.as_ref()
                .map_or(String::new(), |a| format!(", {}", part_at(a)))
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
        Site::Golden(g) => golden_at(g),
    }
}

/// `n` of `noun`, its plural an added "s": "1 crank angle", "4 crank angles".
pub fn counted(n: usize, noun: &str) -> String {
    format!("{n} {noun}{}", if n == 1 { "" } else { "s" })
}

/// "a", "a and b", "a, b and c" (`word` "and" or "or").
pub fn listed<S: Borrow<str>>(items: &[S], word: &str) -> String {
    match items {
        [] => String::new(),
        [one] => one.borrow().to_string(),
        [rest @ .., last] => format!("{} {word} {}", rest.join(", "), last.borrow()),
    }
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
        MinCoverage::Angles(n) => format!("over the scene's {} only", counted(*n, "crank angle")),
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
/// when the mean loss takes all of P, that the scene self-locks (`model::power_flow`).
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

/// A value that may be the engine's "no bound" (`UNBOUNDED_LIFE_H`, the largest double: a life
/// or safety without load or damage, a study with no constraint) as a person reads it:
/// "unbounded", else `show(x)`.
pub fn or_unbounded(x: f64, show: impl FnOnce(f64) -> String) -> String {
    match crate::model::results::is_unbounded(x) {
        true => "unbounded".to_string(),
        false => show(x),
    }
}

/// Why a figure has no finite bound, and that it is written as the largest double (a life in
/// hours, a safety as a number).
fn unbounded(u: &Unbounded) -> String {
    let (why, unit) = match u {
        Unbounded::Life { load_n } if *load_n == 0.0 => {
            ("P = 0 N, no load wears the bearing".to_string(), " h")
        }
        Unbounded::Life { load_n } => {
            return format!(
                "unbounded: at P = {} N the life is beyond 1.798e308 h, the largest number",
                number(*load_n)
            )
        }
        Unbounded::PinSafety => ("no pin is bent".to_string(), ""),
        Unbounded::Fatigue { part, pressure_mpa } => (
            format!("the {part} take no damage at {} MPa", number(*pressure_mpa)),
            " h",
        ),
        Unbounded::StaticSafety => ("the bearing carries no force".to_string(), ""),
        Unbounded::DutyFatigue { part } => (format!("no bin wears the {part}"), " h"),
        Unbounded::DutyLife => (
            "no bin loads the bearing enough to wear it".to_string(),
            " h",
        ),
    };
    format!("unbounded: {why} (written as 1.798e308{unit}, the largest number)")
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
            driver, self_locks, ..
        } => driver == Driver::Output && !self_locks,
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::place::Part;
    use crate::model::results::{MinClearance, SampledPeriod};

    fn at_deg(index: usize, deg: f64) -> Crank {
        Crank {
            index,
            rad: deg.to_radians(),
        }
    }

    fn gap(roller: usize, crank_rad: f64, tooth_phase: f64) -> MinClearance {
        MinClearance {
            gap_mm: 0.0,
            roller,
            crank_rad,
            tooth_phase,
        }
    }

    fn roller(index: usize, deg: f64) -> PartAt {
        PartAt {
            part: Part::Roller,
            index,
            crank: at_deg(7, deg),
        }
    }

    /// Constructed places and the words each must read as, written by hand from the wording
    /// every output has carried ("roller 3 at crank 12.30°": angles to two decimals in degrees,
    /// figures to four significant digits; bin, then disc, then the site).
    fn cases() -> Vec<(Place, &'static str)> {
        let of = Place::of;
        let bin = Bin {
            index: 2,
            output_torque_nmm: 40_000.0,
            input_speed_rpm: 1500.0,
        };
        let period = SampledPeriod {
            period_rad: 36f64.to_radians(),
            step_rad: 0.01f64.to_radians(),
            error_bound_mm: 1.234e-4,
        };
        let efficiency = |driver, self_locks, locked| {
            of(Site::Efficiency {
                driver,
                self_locks,
                locked,
                angles: 360,
            })
        };
        vec![
            (of(Site::Crank(at_deg(0, 12.3))), "crank 12.30°"),
            (of(Site::Part(roller(3, 12.3))), "roller 3 at crank 12.30°"),
            (
                of(Site::Part(PartAt {
                    part: Part::Pin,
                    index: 0,
                    crank: at_deg(1, -1.0),
                })),
                "pin 0 at crank -1.00°",
            ),
            (
                of(Site::Spread {
                    min: at_deg(1, 1.0),
                    max: at_deg(2, 2.0),
                }),
                "min at 1.00°, max at 2.00°",
            ),
            (of(Site::Locked(at_deg(5, 5.0))), "crank 5.00° locked"),
            (
                Place {
                    bin: None,
                    disc: Some(1),
                    site: Site::Part(roller(3, 12.3)),
                },
                "disc 1: roller 3 at crank 12.30°",
            ),
            (
                Place {
                    bin: Some(bin),
                    disc: None,
                    site: Site::Part(roller(3, 12.3)),
                },
                "bin 2 (40.00 N·m, 1500 rpm): roller 3 at crank 12.30°",
            ),
            (
                Place {
                    bin: Some(bin),
                    disc: Some(0),
                    site: Site::Crank(at_deg(0, 0.0)),
                },
                "bin 2 (40.00 N·m, 1500 rpm): disc 0: crank 0.00°",
            ),
            (
                of(Site::Sampled {
                    crank: at_deg(828, 82.8),
                    angles: 3600,
                }),
                "crank 82.80°, over the scene's 3600 crank angles",
            ),
            (
                of(Site::Sampled {
                    crank: at_deg(0, 0.0),
                    angles: 1,
                }),
                "crank 0.00°, the scene's only crank angle",
            ),
            (
                of(Site::Gap {
                    min: gap(4, 0.0, 0.25),
                    over: MinCoverage::Angles(1),
                }),
                "roller 4 at crank 0.00°, tooth phase 0.250 (0 root, 0.5 tip), over the scene's \
                 1 crank angle only",
            ),
            (
                of(Site::Gap {
                    min: gap(0, 3f64.to_radians(), 0.5),
                    over: MinCoverage::Period(period),
                }),
                "roller 0 at crank 3.00°, tooth phase 0.500 (0 root, 0.5 tip), over the whole \
                 period of 36.00° sampled every 0.01000° (error ≤ 0.1234 µm)",
            ),
            (
                of(Site::Slice {
                    at: roller(2, 16.2),
                    slice: 5,
                    slices: 11,
                }),
                "roller 2 at crank 16.20°, slice 5 of 11 (slice 0 at z = −B/2)",
            ),
            (
                of(Site::Rule(Rule::BearingEquivalentLoad)),
                "(mean of Fb^p over the sweep)^(1/p)",
            ),
            (
                Place {
                    bin: None,
                    disc: Some(1),
                    site: Site::Rule(Rule::DutyEquivalentLoad),
                },
                "disc 1: (Σ share·n·P^p / Σ share·n)^(1/p) over the bins",
            ),
            (
                of(Site::Rule(Rule::EquivalentTorque)),
                "(Σ share·n·|T|³ / Σ share·n)^(1/3) over the bins",
            ),
            (of(Site::Rule(Rule::MeanSpeed)), "Σ share·n over the bins"),
            (
                of(Site::Rule(Rule::DutyMeanEfficiency)),
                "energy delivered / energy entering over the bins, each as its power flows",
            ),
            (
                of(Site::Rule(Rule::Temperature)),
                "ambient + mean power loss/(h·A)",
            ),
            (of(Site::Life { load_n: 1949.0 }), "at P = 1949 N"),
            (
                Place {
                    bin: None,
                    disc: Some(1),
                    site: Site::DutyLife {
                        load_n: 1234.4,
                        mean_speed_rpm: 750.0,
                    },
                },
                "disc 1: at P = 1234 N, mean speed 750.0 rpm",
            ),
            (
                of(Site::Fatigue {
                    part: "disc",
                    pressure_mpa: 1278.0,
                    at: Some(roller(2, 16.2)),
                }),
                "disc at 1278 MPa, roller 2 at crank 16.20°",
            ),
            (
                of(Site::Fatigue {
                    part: "rollers",
                    pressure_mpa: 1278.0,
                    at: None,
                }),
                "rollers at 1278 MPa",
            ),
            (
                of(Site::DutyFatigue { part: "rollers" }),
                "rollers under the cycle (Miner, flanks apart)",
            ),
            (
                of(Site::StaticSafety {
                    force_n: 1949.0,
                    at: Some(at_deg(828, 82.8)),
                }),
                "C0 / 1949 N at crank 82.80°",
            ),
            (
                of(Site::StaticSafety {
                    force_n: 1949.0,
                    at: None,
                }),
                "C0 / 1949 N",
            ),
            (
                of(Site::PowerLoss(PathLosses {
                    rollers: 12.5,
                    output_pins: 3.25,
                    crank_bearing: 1.0,
                    no_load: 0.0,
                })),
                "mean over the crank angles: rollers 12.50 W, output pins 3.250 W, crank bearing \
                 1.000 W, no-load 0 W",
            ),
            (
                efficiency(Driver::Input, false, 0),
                "P_out/(P_out + mean loss) over the scene's crank angles",
            ),
            (
                efficiency(Driver::Output, true, 7),
                "SELF-LOCKS: back-driven (the output drives, T < 0), the mean loss exceeds the \
                 power P = |T|·ω_out entering at the output, (P − mean loss)/P ≤ 0 over the \
                 scene's crank angles; the input must push at 7 of 360 crank angles \
                 (self_locking_deg)",
            ),
            (
                efficiency(Driver::Output, false, 0),
                "back-driven (the output drives, T < 0): (P − mean loss)/P, P = |T|·ω_out \
                 entering at the output, over the scene's crank angles",
            ),
            (
                efficiency(Driver::Output, false, 7),
                "back-driven (the output drives, T < 0): (P − mean loss)/P, P = |T|·ω_out \
                 entering at the output, over the scene's crank angles; self-locks at 7 of 360 \
                 crank angles (self_locking_deg)",
            ),
            (
                of(Site::Unbounded(Unbounded::Life { load_n: 0.0 })),
                "unbounded: P = 0 N, no load wears the bearing (written as 1.798e308 h, the \
                 largest number)",
            ),
            (
                of(Site::Unbounded(Unbounded::Life { load_n: 2500.0 })),
                "unbounded: at P = 2500 N the life is beyond 1.798e308 h, the largest number",
            ),
            (
                of(Site::Unbounded(Unbounded::PinSafety)),
                "unbounded: no pin is bent (written as 1.798e308, the largest number)",
            ),
            (
                of(Site::Unbounded(Unbounded::Fatigue {
                    part: "rollers",
                    pressure_mpa: 0.0,
                })),
                "unbounded: the rollers take no damage at 0 MPa (written as 1.798e308 h, the \
                 largest number)",
            ),
            (
                of(Site::Unbounded(Unbounded::StaticSafety)),
                "unbounded: the bearing carries no force (written as 1.798e308, the largest \
                 number)",
            ),
            (
                of(Site::Unbounded(Unbounded::DutyFatigue { part: "disc" })),
                "unbounded: no bin wears the disc (written as 1.798e308 h, the largest number)",
            ),
            (
                Place {
                    bin: None,
                    disc: Some(0),
                    site: Site::Unbounded(Unbounded::DutyLife),
                },
                "disc 0: unbounded: no bin loads the bearing enough to wear it (written as \
                 1.798e308 h, the largest number)",
            ),
            (
                of(Site::Golden(GoldenAt {
                    part: Some((Part::Roller, 3)),
                    crank_deg: 12.3,
                })),
                "roller 3 at crank 12.30°",
            ),
            (
                of(Site::Golden(GoldenAt {
                    part: Some((Part::Pin, 2)),
                    crank_deg: -1.0,
                })),
                "pin 2 at crank -1.00°",
            ),
            (
                Place {
                    bin: None,
                    disc: Some(1),
                    site: Site::Golden(GoldenAt {
                        part: None,
                        crank_deg: 66.7,
                    }),
                },
                "disc 1: crank 66.70°",
            ),
        ]
    }

    #[test]
    fn a_place_reads_as_every_output_has_worded_it() {
        for (place, words) in cases() {
            assert_eq!(text(&place), words, "{place:?}");
        }
    }

    /// A golden point's angle reads as the comparison had it, in degrees: 1.875° and 0.575° (a
    /// golden sampled every 0.025°) to two decimals, as `{:.2}` rounds their exact binary
    /// values (1.875 is a tie, to even; 0.575 is 0.57499…). Through radians and back they
    /// would read 1.87° and 0.58°, which the second half shows of the words of a rad angle.
    #[test]
    fn a_golden_point_reads_its_angle_in_the_degrees_it_was_compared_at() {
        let at = |part, crank_deg| text(&Place::of(Site::Golden(GoldenAt { part, crank_deg })));
        assert_eq!(
            at(Some((Part::Roller, 0)), 1.875),
            "roller 0 at crank 1.88°"
        );
        assert_eq!(at(None, 0.575), "crank 0.57°");
        assert_eq!(crank(units::rad(1.875)), "crank 1.87°");
        assert_eq!(crank(units::rad(0.575)), "crank 0.58°");
    }

    /// The typed tests a headline makes of a place say what its words say: whether they name
    /// the scene's only angle, and whether they end on the scene's angles after a comma (what
    /// the headline's sampling used to be chosen by, searching the words).
    #[test]
    fn what_a_headline_asks_of_a_place_agrees_with_its_words() {
        for (place, words) in cases() {
            assert_eq!(
                names_only_angle(&place),
                words.contains(ONLY_ANGLE),
                "{words}"
            );
            let counted = words.contains(", over the scene's ");
            assert_eq!(counts_scene_angles(&place), counted, "{words}");
        }
    }
}
