//! The results JSON (schema 1): typed documents (`Document`, `#[derive(Serialize)]`) that
//! borrow the results; no tree of values is built. Arrays are \[roller\]\[angle\] or
//! \[angle\]; a quantity that was not computed is absent, never zero. The keys are documented
//! in the README ("Results JSON"). A scene's document (`SceneDoc`) is the registry's: every
//! quantity a scene computed (`model::quantity::QUANTITIES`) is there under its key with the
//! values, in the units, `Quantity::curves` and `Quantity::scalar` give, in the order `SCENE`
//! lists; what is no registry quantity is typed beside them (`Extra`). What a study's result
//! holds is mapped in one place, `StudyDoc::new`.
//!
//! No number in the file is null, NaN or infinite: serialising a non-finite number is an
//! error and the run stops with it (the engine never produces one: a computation that fails
//! stops the run before).

use crate::engine::golden::{sha256_hex, GoldenResult, Point};
use crate::engine::mass_properties::{MassProperties, Unbalance};
use crate::engine::optimise::StudyResult;
use crate::engine::summary::SceneSummary;
use crate::engine::verdict::{Check, CheckKind};
use crate::model::quantity::{self as q, Extreme, Of, Quantity, QUANTITIES};
use crate::model::results::{
    ClearanceSweep, DiscResult, EfficiencyCurves, LoadedSweep, MinCoverage, SceneResult,
    TorsionCompliances,
};
use crate::model::Study;
use crate::numeric::extremes;
use crate::report::explain::{hysteresis, torsion_compliances, torsion_law_note, CompliancesText};
use crate::report::json_text::{self, Object, Text};
use crate::spec::Spec;
use crate::units::{self, nm_per_arcmin};
use serde::ser::{Error as _, SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};
use std::io::Write;

pub use super::finite::Finite;

/// A curve as the registry or the results hold it, already in its key's unit.
#[derive(Clone, Copy)]
pub struct Curve<'a>(&'a [f64]);

impl Serialize for Curve<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_seq(self.0.iter().map(|&v| Finite(v)))
    }
}

/// A count per crank angle (`q::COUNTS`), written as whole numbers; one that is not (never:
/// the registry's counts are whole) is an error, not rounded.
pub struct Counts<'a>(&'a [f64]);

impl Serialize for Counts<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.0.len()))?;
        for &n in self.0 {
            seq.serialize_element(&json_text::count(n).map_err(S::Error::custom)?)?;
        }
        seq.end()
    }
}

/// Curves \[part\]\[angle\] in the key's unit: a registry quantity's rows (`q::Rows`), or
/// the rows of a flat table (`FaceLoads::angles`).
pub struct Rows<I>(I);

impl<'a, I: Iterator<Item = &'a [f64]> + Clone> Serialize for Rows<I> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_seq(self.0.clone().map(Curve))
    }
}

/// `key: value` pairs written as an object, in their order: a study's variables.
pub struct Pairs(Vec<(&'static str, Finite)>);

impl Serialize for Pairs {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_map(self.0.iter().copied())
    }
}

#[derive(Serialize)]
pub struct MinClearanceAt {
    roller: usize,
    crank_deg: Finite,
    tooth_phase: Finite,
}

/// What the smallest gap was sought over (`MinCoverage`): the whole period of the gaps, its
/// step and the error bound of the sampling, or the scene's own crank angles alone.
#[derive(Serialize)]
#[serde(untagged)]
pub enum MinClearanceOver {
    Period {
        period_deg: Finite,
        step_deg: Finite,
        error_bound_mm: Finite,
    },
    Angles {
        crank_angles: usize,
    },
}

/// One scene's document: the entries of `SCENE` in its order. Every curve of the registry
/// (`QUANTITIES`) that the scene computed is there under its key with the values
/// `Quantity::curves` gives (the registry's units: the document converts nothing of its
/// own), every scalar too; beside them the entries that are no registry quantity (`Extra`).
pub struct SceneDoc<'a> {
    /// Whose results the document writes: the scene's, or one disc's alone (`discs`).
    of: Of<'a>,
    /// Whether it begins with the scene's name and crank angles (not in a duty bin's run, nor
    /// in a disc's document).
    named: bool,
    /// The scene's scalars as its summary computed them (`SceneSummary::scalars`); without
    /// one (a disc's document, a duty bin's run) each is read from the results.
    scalars: Option<&'a [(&'static Quantity, Extreme)]>,
}

/// One entry, or a group of entries, of a scene's document.
#[derive(Clone, Copy)]
enum Field {
    /// A registry curve under its key, as `Quantity::curves` gives it (one curve per roller
    /// or pin: rows; a count: whole numbers).
    Curve(&'static Quantity),
    /// A registry curve, then its largest and smallest value under these two keys.
    CurveAndExtremes(&'static Quantity, &'static str, &'static str),
    /// Every registry scalar the scene computed (`Quantity::scalar`: with several discs the
    /// worst over the discs), in the registry's order.
    Scalars,
    /// Entries that are not registry quantities.
    Extra(Extra),
}

/// The entries of a scene's document that no limit or golden reads, kept typed here: each is
/// either not a curve over the crank angles or not a property of the design.
#[derive(Clone, Copy)]
enum Extra {
    /// `name`, `crank_deg`: the scene and its abscissa (not in a disc's document).
    Name,
    /// `min_clearance_at`, `min_clearance_over`: where `min_clearance_mm` is and what it was
    /// sought over, as numbers (its `at` says it for people).
    MinClearance,
    /// `line_load_n_per_mm` \[roller\]\[crank\]\[slice\], with more than one slice (MODEL.md
    /// "Along the face width"): three indices, no registry shape; `max_line_load_n_per_mm` is
    /// its registry scalar.
    LineLoads,
    /// `residual`: the equilibrium's, solver noise left out of the registry (`QUANTITIES`).
    Residual,
    /// `self_locking_deg` (the crank angles where the input must push while the output
    /// drives: a set of angles, not a curve), `power_loss_w` (each path's mean loss, W, with a
    /// speed) and `power_loss_note` (why they are absent without one).
    Losses,
    /// A torsion scene's loop: `torque_nm` \[m\] and `torsion_arcmin` \[crank\]\[m\].
    TorsionLoop,
    /// A torsion scene's rigidity each way, N·m/arcmin \[crank\] (the registry's is the smaller).
    TorsionDirections,
    /// A torsion scene's texts: `hysteresis` and `compliances` (`CompliancesDoc`).
    TorsionNotes,
    /// `discs`: with several discs, each disc's document (MODEL.md "Several discs").
    Discs,
    /// `duty_cycle`: a duty-cycle scene's bins and each disc's life (`DutyDoc`).
    DutyCycle,
    /// `contact_fatigue_life_h`: the disc's and the rollers' lives, h (`FatigueDoc`).
    Fatigue,
}

/// The scene document's entries in their order (the order of the results JSON's keys, which
/// a reader may rely on; the registry's own order puts the curves apart from the sub-documents
/// written beside them). Every curve of `QUANTITIES` is here once (a unit test holds it).
const SCENE: &[Field] = &[
    Field::Extra(Extra::Name),
    Field::Curve(&q::DISC_TORQUE),
    Field::Curve(&q::CLEARANCE),
    Field::Extra(Extra::MinClearance),
    Field::Curve(&q::BACKLASH),
    Field::Curve(&q::BACKLASH_REVERSE),
    Field::Curve(&q::LOST_MOTION),
    Field::Curve(&q::LAG),
    Field::Curve(&q::ROLLER_FORCE),
    Field::Curve(&q::CONTACT_PRESSURE),
    Field::Curve(&q::CONTACT_HALF_WIDTH),
    Field::Curve(&q::CONTACTS),
    Field::Extra(Extra::LineLoads),
    Field::Curve(&q::FACE_LOAD_FACTOR),
    Field::Curve(&q::OUTPUT_LAG),
    Field::Curve(&q::PIN_FORCE),
    Field::Curve(&q::BEARING_FORCE),
    Field::Curve(&q::BEARING_ANGLE),
    Field::Curve(&q::BEARING_DEFLECTION),
    Field::Extra(Extra::Residual),
    Field::CurveAndExtremes(&q::TE, "te_max_arcsec", "te_min_arcsec"),
    Field::CurveAndExtremes(&q::RATIO, "ratio_max", "ratio_min"),
    Field::Curve(&q::EFFICIENCY),
    Field::Curve(&q::INPUT_TORQUE),
    Field::Extra(Extra::Losses),
    Field::Scalars,
    Field::Extra(Extra::TorsionLoop),
    Field::Curve(&q::TORSION_LOST_MOTION),
    Field::Curve(&q::TORSION_BACKLASH),
    Field::Curve(&q::TORSIONAL_RIGIDITY),
    Field::Extra(Extra::TorsionDirections),
    Field::Curve(&q::HYSTERESIS_LOSS),
    Field::Curve(&q::HYSTERESIS_ENERGY),
    Field::Extra(Extra::TorsionNotes),
    Field::Extra(Extra::Discs),
    Field::Extra(Extra::DutyCycle),
    Field::Curve(&q::PIN_BENDING_STRESS),
    Field::Extra(Extra::Fatigue),
];

/// The disc's and the rollers' contact fatigue lives, h, each when its S–N law is given (a
/// disc's own with several discs; `engine::strength`).
#[derive(Serialize)]
pub struct FatigueDoc {
    #[serde(skip_serializing_if = "Option::is_none")]
    disc: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rollers: Option<Finite>,
}

/// A duty-cycle scene's block (`engine::duty_cycle`): each disc's crank bearing under the
/// cycle and each bin with its run. The cycle's figures (`duty_life_h`,
/// `equivalent_torque_nm`, `mean_speed_rpm`, …) are the scene's scalars.
#[derive(Serialize)]
pub struct DutyDoc<'a> {
    /// Each disc's equivalent load and life under the cycle (rated only).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    discs: Vec<DutyLifeDoc>,
    bins: Vec<DutyBinDoc<'a>>,
    /// Each disc's and its rollers' contact fatigue under the cycle (Miner, flanks apart).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    duty_contact_fatigue_life_h: Vec<DutyFatigueDoc>,
}

/// One disc's contact fatigue under a duty cycle: the lives, h, and each bin's share of the
/// damage of the flank it loads.
#[derive(Serialize)]
pub struct DutyFatigueDoc {
    #[serde(skip_serializing_if = "Option::is_none")]
    disc: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rollers: Option<Finite>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    disc_damage_share: Vec<Finite>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    rollers_damage_share: Vec<Finite>,
}

/// One disc's crank bearing under a duty cycle.
#[derive(Serialize)]
pub struct DutyLifeDoc {
    equivalent_load_n: Finite,
    life_h: Option<Finite>,
}

/// One bin of a duty cycle: as given, its share of the revolutions sᵢ·nᵢ/Σ sⱼ·nⱼ, its own
/// equivalent load of each disc's bearing, peak pressure and mean efficiency, and its whole
/// run (the curves and scalars of a scene).
#[derive(Serialize)]
pub struct DutyBinDoc<'a> {
    output_torque_nm: Finite,
    input_speed_rpm: Finite,
    time_share: Finite,
    revolution_share: Finite,
    #[serde(skip_serializing_if = "Option::is_none")]
    equivalent_load_n: Option<Vec<Finite>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_contact_pressure_mpa: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mean_efficiency: Option<Finite>,
    results: SceneDoc<'a>,
}

impl<'a> DutyDoc<'a> {
    fn new(r: &'a SceneResult) -> Option<Self> {
        let d = r.duty.as_deref()?;
        Some(DutyDoc {
            duty_contact_fatigue_life_h: (d.contact_fatigue.iter())
                .map(|f| DutyFatigueDoc {
                    disc: f.disc_h.map(Finite),
                    rollers: f.rollers_h.map(Finite),
                    disc_damage_share: finite(f.disc_shares.iter().copied()),
                    rollers_damage_share: finite(f.rollers_shares.iter().copied()),
                })
                .collect(),
            discs: (d.life.iter())
                .map(|b| DutyLifeDoc {
                    equivalent_load_n: Finite(b.equivalent_load_n),
                    life_h: b.life_h.map(Finite),
                })
                .collect(),
            bins: (d.bins.iter())
                .map(|b| DutyBinDoc {
                    output_torque_nm: Finite(units::nm(b.bin.output_torque_nmm)),
                    input_speed_rpm: Finite(b.bin.input_speed_rpm),
                    time_share: Finite(b.bin.time_share),
                    revolution_share: Finite(d.revolution_share(b)),
                    equivalent_load_n: crate::engine::duty_cycle::bin_equivalent_loads(&b.result)
                        .map(finite),
                    max_contact_pressure_mpa: q::MAX_CONTACT_PRESSURE
                        .scalar(&b.result)
                        .map(|e| Finite(e.value)),
                    mean_efficiency: q::MEAN_EFFICIENCY
                        .scalar(&b.result)
                        .map(|e| Finite(e.value)),
                    results: SceneDoc::without_summary(Of {
                        r: &b.result,
                        disc: None,
                    }),
                })
                .collect(),
        })
    }
}

/// The contact law and compliances of a torsion curve (`explain::torsion_compliances`).
#[derive(Serialize)]
pub struct CompliancesDoc {
    contact_law: &'static str,
    /// `modelled`, `not_modelled`, `given`.
    #[serde(flatten)]
    lists: CompliancesText,
    /// The rest of the reducer's torsional compliance, arcmin per kN·m (0: none given).
    structure_arcmin_per_knm: Finite,
    /// Where the law puts the rigidity against a catalogue's.
    note: &'static str,
}

fn finite(values: impl IntoIterator<Item = f64>) -> Vec<Finite> {
    values.into_iter().map(Finite).collect()
}

/// The mean power lost on each path, W (`EfficiencyCurves::power_loss_w`).
#[derive(Serialize)]
pub struct PowerLossDoc {
    rollers: Finite,
    output_pins: Finite,
    crank_bearing: Finite,
    no_load: Finite,
    total: Finite,
}

impl PowerLossDoc {
    fn new(e: &EfficiencyCurves) -> Option<PowerLossDoc> {
        let p = e.power_loss_w()?;
        Some(PowerLossDoc {
            rollers: Finite(p.rollers),
            output_pins: Finite(p.output_pins),
            crank_bearing: Finite(p.crank_bearing),
            no_load: Finite(p.no_load),
            total: Finite(p.total()),
        })
    }
}

/// Why a scene's losses have no watts.
pub const NO_SPEED: &str = "no input_speed_rpm: the efficiency does not depend on the speed \
     (Coulomb friction), the losses in watts and the temperature need one";

/// The line load of every roller along the face, N/mm \[roller\]\[crank\]\[slice\], where the
/// scene resolves the face in more than one slice.
fn line_loads(loaded: &LoadedSweep) -> Option<Vec<Rows<std::slice::ChunksExact<'_, f64>>>> {
    let f = loaded.rollers.as_ref()?.face.as_ref()?;
    let loaded = f.slices > 1 && f.line_load_n_per_mm.first().is_some_and(|r| !r.is_empty());
    loaded.then(|| {
        (0..f.line_load_n_per_mm.len())
            .map(|i| Rows(f.angles(i)))
            .collect()
    })
}

/// What a torsion curve's angle is made of (`explain::torsion_compliances`).
fn compliances(c: &TorsionCompliances) -> CompliancesDoc {
    CompliancesDoc {
        contact_law: c.contact_law.name(),
        lists: torsion_compliances(c),
        structure_arcmin_per_knm: Finite(units::arcmin_per_knm(c.structure_rad_per_nmm)),
        note: torsion_law_note(c.contact_law),
    }
}

fn min_clearance_at(c: &ClearanceSweep) -> MinClearanceAt {
    MinClearanceAt {
        roller: c.min.roller,
        crank_deg: Finite(units::deg(c.min.crank_rad)),
        tooth_phase: Finite(c.min.tooth_phase),
    }
}

fn min_clearance_over(c: &ClearanceSweep) -> MinClearanceOver {
    match c.coverage {
        MinCoverage::Period(p) => MinClearanceOver::Period {
            period_deg: Finite(units::deg(p.period_rad)),
            step_deg: Finite(units::deg(p.step_rad)),
            error_bound_mm: Finite(p.error_bound_mm),
        },
        MinCoverage::Angles(n) => MinClearanceOver::Angles { crank_angles: n },
    }
}

/// Writes `key: value` when there is a value.
fn entry<M: SerializeMap, T: Serialize>(
    map: &mut M,
    key: &'static str,
    value: Option<T>,
) -> std::result::Result<(), M::Error> {
    value.map_or(Ok(()), |v| map.serialize_entry(key, &v))
}

/// Crank angles, degrees.
fn degrees(crank_rad: &[f64]) -> Vec<f64> {
    crank_rad.iter().map(|&a| units::deg(a)).collect()
}

impl<'a> SceneDoc<'a> {
    /// The scene's document; `summary` is its summary, when there is one.
    pub fn new(r: &'a SceneResult, summary: Option<&'a SceneSummary>) -> Self {
        SceneDoc {
            of: Of { r, disc: None },
            named: true,
            scalars: summary.map(|s| s.scalars.as_slice()),
        }
    }

    /// A document without a summary, its scalars read from the results: a duty bin's run
    /// (the scene's document without its name and angles) or one disc's.
    fn without_summary(of: Of<'a>) -> Self {
        SceneDoc {
            of,
            named: false,
            scalars: None,
        }
    }

    /// The disc whose curves the document writes: one disc's alone, or the scene's only disc.
    fn disc(&self) -> Option<&'a DiscResult> {
        self.of.disc.or_else(|| self.of.r.only_disc())
    }

    /// The losses the document writes: the reducer's in the scene's, a disc's own in its.
    fn efficiency(&self) -> Option<&'a EfficiencyCurves> {
        match self.of.disc {
            None => self.of.r.reducer.efficiency.as_ref(),
            Some(d) => d.efficiency.as_ref(),
        }
    }

    /// A registry curve under its key, and its extremes under `extremes`' keys.
    fn curve<M: CurveMap>(
        &self,
        map: &mut M,
        quantity: &'static Quantity,
        extremes_keys: Option<(&'static str, &'static str)>,
    ) -> std::result::Result<(), M::Error> {
        let Some(rows) = self.of.rows(quantity) else {
            return Ok(());
        };
        let row = rows.first().map(Vec::as_slice).unwrap_or_default();
        if quantity.shape.per().is_some() {
            map.rows(quantity.key, &rows)?;
        } else if quantity.is_count() {
            map.counts(quantity.key, row)?;
        } else {
            map.curve(quantity.key, row)?;
        }
        if let Some((max_key, min_key)) = extremes_keys {
            let ((lo, _), (hi, _)) = extremes(row);
            map.serialize_entry(max_key, &Finite(hi))?;
            map.serialize_entry(min_key, &Finite(lo))?;
        }
        Ok(())
    }

    fn extra<M: CurveMap>(&self, map: &mut M, extra: Extra) -> std::result::Result<(), M::Error> {
        let (r, scene, named) = (self.of.r, self.of.disc.is_none(), self.named);
        let loaded = self.disc().map(|d| &d.loaded);
        let clearance = self.disc().and_then(|d| d.clearance.as_ref());
        let efficiency = self.efficiency();
        let reducer_eff = efficiency.and_then(|e| e.reducer.as_ref());
        let torsion = r.reducer.torsion.as_ref().filter(|_| scene);
        match extra {
            Extra::Name if named => {
                map.serialize_entry("name", &r.name)?;
                map.curve("crank_deg", &degrees(&r.crank_rad))
            }
            Extra::Name => Ok(()),
            Extra::MinClearance => {
                entry(map, "min_clearance_at", clearance.map(min_clearance_at))?;
                entry(map, "min_clearance_over", clearance.map(min_clearance_over))
            }
            Extra::LineLoads => entry(map, "line_load_n_per_mm", loaded.and_then(line_loads)),
            Extra::Residual => match loaded.and_then(|l| l.bearing.as_ref()) {
                Some(b) => map.curve("residual", &b.residual),
                None => Ok(()),
            },
            Extra::Losses => {
                if let Some(e) = reducer_eff {
                    map.curve("self_locking_deg", &degrees(&e.self_locking_crank_rad))?;
                }
                entry(map, "power_loss_w", efficiency.and_then(PowerLossDoc::new))?;
                entry(
                    map,
                    "power_loss_note",
                    efficiency
                        .filter(|e| e.input_speed_rad_s.is_none())
                        .map(|_| NO_SPEED),
                )
            }
            Extra::TorsionLoop => {
                let Some(t) = torsion else { return Ok(()) };
                let torque_nm: Vec<f64> = t.torque_nmm.iter().map(|&x| units::nm(x)).collect();
                map.curve("torque_nm", &torque_nm)?;
                let arcmin = |row: &Vec<f64>| row.iter().map(|&g| units::arcmin(g)).collect();
                let torsion_arcmin = t.torsion_rad.iter().map(arcmin).collect();
                map.rows("torsion_arcmin", &q::Rows::Owned(torsion_arcmin))
            }
            Extra::TorsionDirections => {
                let Some(t) = torsion else { return Ok(()) };
                let direction = |pick: fn((f64, f64)) -> f64| -> Vec<f64> {
                    (t.figures.iter())
                        .map(|f| nm_per_arcmin(pick(f.rigidity_nmm_per_rad)))
                        .collect()
                };
                map.curve(
                    "torsional_rigidity_forward_nm_per_arcmin",
                    &direction(|d| d.0),
                )?;
                map.curve(
                    "torsional_rigidity_reverse_nm_per_arcmin",
                    &direction(|d| d.1),
                )
            }
            Extra::TorsionNotes => {
                entry(map, "hysteresis", torsion.map(|t| hysteresis(t.friction)))?;
                entry(
                    map,
                    "compliances",
                    torsion.map(|t| compliances(&t.compliances)),
                )
            }
            Extra::Discs => entry(
                map,
                "discs",
                (scene && r.names_discs()).then(|| {
                    (r.discs.iter())
                        .map(|d| SceneDoc::without_summary(Of { r, disc: Some(d) }))
                        .collect::<Vec<_>>()
                }),
            ),
            Extra::DutyCycle => entry(map, "duty_cycle", DutyDoc::new(r).filter(|_| scene)),
            Extra::Fatigue => entry(
                map,
                "contact_fatigue_life_h",
                (loaded.and_then(|l| l.strength?.fatigue)).map(|f| FatigueDoc {
                    disc: f.disc_h.map(Finite),
                    rollers: f.rollers_h.map(Finite),
                }),
            ),
        }
    }
}

impl SceneDoc<'_> {
    /// One field's entries (none when the scene did not compute it).
    fn field<M: CurveMap>(&self, map: &mut M, field: Field) -> std::result::Result<(), M::Error> {
        match field {
            Field::Curve(quantity) => self.curve(map, quantity, None),
            Field::CurveAndExtremes(quantity, max, min) => {
                self.curve(map, quantity, Some((max, min)))
            }
            Field::Scalars => match self.scalars {
                Some(scalars) => (scalars.iter())
                    .try_for_each(|(q, e)| map.serialize_entry(q.key, &Finite(e.value))),
                None => (QUANTITIES.iter()).try_for_each(|q| {
                    entry(map, q.key, self.of.scalar(q).map(|e| Finite(e.value)))
                }),
            },
            Field::Extra(extra) => self.extra(map, extra),
        }
    }

    /// Write the document as `Serialize` would, its curves' numbers by `json_text`. A long
    /// scene's fields are written by two threads from both ends of `SCENE` (`Ends`): this one
    /// from the front into `text`, a second from the back into memory, passed on
    /// after the front's. A field's text is the same whoever writes it, so the file is the
    /// same bytes. Why: the sweep runs on every core, the JSON's formatting on one
    /// (BENCHMARKS.md "The JSON on two threads").
    fn write(&self, text: &mut Text) -> serde_json::Result<()> {
        let mut object = Object::new(text)?;
        if !self.is_long() {
            SCENE.iter().try_for_each(|&f| self.field(&mut object, f))?;
            return object.end();
        }
        // The first field, a named scene's name (`is_long`), is this thread's: every field
        // the other writes follows an entry, after a comma.
        let ends = Ends::new(1..SCENE.len());
        let mut back = None;
        // A thread of its own, not a worker of rayon's pool: a pool's worker asleep since the
        // sweep took from 30 µs to past the end of the front's work to start (a new thread:
        // 0.1–0.16 ms; BENCHMARKS.md "The JSON on two threads"). Where none can be had (a
        // cap on threads), this one takes every field.
        let front = std::thread::scope(|s| {
            let spawned = std::thread::Builder::new()
                .spawn_scoped(s, || back = Some(self.write_from_back(&ends)));
            drop(spawned);
            (std::iter::once(0).chain(ends.front()))
                .try_for_each(|i| self.field(&mut object, SCENE[i]))
        });
        front?;
        pass_back(&mut object, back)?;
        object.end()
    }

    /// The document with fields `..m` written as the front's and the rest as the back's
    /// (`write`'s split, at a given place and on one thread).
    #[cfg(test)]
    fn write_split(&self, text: &mut Text, m: usize) -> serde_json::Result<()> {
        let mut object = Object::new(text)?;
        (SCENE[..m].iter()).try_for_each(|&f| self.field(&mut object, f))?;
        pass_back(
            &mut object,
            Some(self.write_from_back(&Ends::new(m..SCENE.len()))),
        )?;
        object.end()
    }

    /// The fields `ends` gives from the back, each written after a comma into memory: the
    /// text and each field's bytes in it, last field first.
    fn write_from_back(&self, ends: &Ends) -> serde_json::Result<Back> {
        // Room for ten curves' numbers at each angle without growing (25 bytes a number at
        // most): the back half of a scene of ten rollers or pins.
        let mut text = Text::in_memory(250 * self.of.r.crank_rad.len());
        let mut segments = Vec::new();
        for i in ends.back() {
            let start = text.bytes().len();
            self.field(&mut Object::after_first(&mut text), SCENE[i])?;
            segments.push(start..text.bytes().len());
        }
        Ok((text.into_bytes(), segments))
    }

    /// Whether the document is long enough that a second thread pays for waking it: a
    /// named scene (its first field, `Extra::Name`, always written) of `LONG_SCENE` crank
    /// angles or more, where the run may use more than one thread (`RAYON_NUM_THREADS`).
    fn is_long(&self) -> bool {
        self.named && self.of.r.crank_rad.len() >= LONG_SCENE && rayon::current_num_threads() > 1
    }
}

/// The text the back's thread wrote and each field's bytes in it, last field first.
type Back = (Vec<u8>, Vec<std::ops::Range<usize>>);

/// The back's fields (`SceneDoc::write_from_back`), in their order after the front's: none
/// when no second thread was had, whose fields the front then wrote.
fn pass_back(
    object: &mut Object,
    back: Option<serde_json::Result<Back>>,
) -> serde_json::Result<()> {
    let Some(back) = back else {
        return Ok(());
    };
    let (bytes, segments) = back?;
    (segments.into_iter().rev()).try_for_each(|range| object.pass(&bytes[range]))
}

/// Crank angles from which a scene's document is written on two threads (`SceneDoc::write`).
pub const LONG_SCENE: usize = 1024;

/// The indices of a range handed out from both ends, each once: `front` from the first up,
/// `back` from the last down, until they meet.
struct Ends(std::sync::Mutex<std::ops::Range<usize>>);

impl Ends {
    fn new(range: std::ops::Range<usize>) -> Self {
        Ends(std::sync::Mutex::new(range))
    }

    // A poisoned lock (a panic while it was held) still holds a whole range: `next` cannot
    // panic.
    fn front(&self) -> impl Iterator<Item = usize> + '_ {
        std::iter::from_fn(|| self.0.lock().unwrap_or_else(|e| e.into_inner()).next())
    }

    fn back(&self) -> impl Iterator<Item = usize> + '_ {
        std::iter::from_fn(|| (self.0.lock().unwrap_or_else(|e| e.into_inner())).next_back())
    }
}

/// Where a scene document's entries go: an object of serde's (`Serde`, the document inside
/// another, a disc's or a duty bin's), or the text of `json_text`, which writes curves
/// without serde's per-number path (the results file's scenes).
trait CurveMap: SerializeMap {
    /// `key: [x…]`.
    fn curve(&mut self, key: &'static str, row: &[f64]) -> std::result::Result<(), Self::Error>;
    /// `key: [[x…]…]`, a row per roller or pin.
    fn rows(&mut self, key: &'static str, rows: &q::Rows) -> std::result::Result<(), Self::Error>;
    /// `key: [n…]`, whole numbers (`Counts`).
    fn counts(&mut self, key: &'static str, row: &[f64]) -> std::result::Result<(), Self::Error>;
}

/// A serde map as a `CurveMap`.
struct Serde<M>(M);

impl<M: SerializeMap> SerializeMap for Serde<M> {
    type Ok = M::Ok;
    type Error = M::Error;

    fn serialize_key<T: ?Sized + Serialize>(
        &mut self,
        key: &T,
    ) -> std::result::Result<(), M::Error> {
        self.0.serialize_key(key)
    }

    fn serialize_value<T: ?Sized + Serialize>(
        &mut self,
        value: &T,
    ) -> std::result::Result<(), M::Error> {
        self.0.serialize_value(value)
    }

    fn end(self) -> std::result::Result<M::Ok, M::Error> {
        self.0.end()
    }
}

impl<M: SerializeMap> CurveMap for Serde<M> {
    fn curve(&mut self, key: &'static str, row: &[f64]) -> std::result::Result<(), M::Error> {
        self.0.serialize_entry(key, &Curve(row))
    }

    fn rows(&mut self, key: &'static str, rows: &q::Rows) -> std::result::Result<(), M::Error> {
        self.0
            .serialize_entry(key, &Rows(rows.iter().map(Vec::as_slice)))
    }

    fn counts(&mut self, key: &'static str, row: &[f64]) -> std::result::Result<(), M::Error> {
        self.0.serialize_entry(key, &Counts(row))
    }
}

impl CurveMap for Object<'_, '_> {
    fn curve(&mut self, key: &'static str, row: &[f64]) -> serde_json::Result<()> {
        self.raw(key, |text| text.with(|buf| json_text::numbers(buf, row)))
    }

    fn rows(&mut self, key: &'static str, rows: &q::Rows) -> serde_json::Result<()> {
        self.raw(key, |text| {
            json_text::rows(text, rows.iter().map(Vec::as_slice))
        })
    }

    fn counts(&mut self, key: &'static str, row: &[f64]) -> serde_json::Result<()> {
        self.raw(key, |text| text.with(|buf| json_text::counts(buf, row)))
    }
}

impl Serialize for SceneDoc<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut map = Serde(s.serialize_map(None)?);
        SCENE.iter().try_for_each(|&f| self.field(&mut map, f))?;
        map.end()
    }
}

#[derive(Serialize)]
pub struct CheckDoc<'a> {
    id: &'a str,
    kind: &'static str,
    value: Finite,
    limit: Finite,
    unit: &'static str,
    passed: bool,
    at: String,
}

#[derive(Serialize)]
pub struct PointDoc<'a> {
    column: &'a str,
    crank_deg: Finite,
    golden: Finite,
    value: Finite,
    deviation: Finite,
    band: Finite,
}

impl<'a> From<&'a Point> for PointDoc<'a> {
    fn from(p: &'a Point) -> Self {
        PointDoc {
            column: &p.column,
            crank_deg: Finite(p.at.crank_deg),
            golden: Finite(p.golden),
            value: Finite(p.value),
            deviation: Finite(p.deviation),
            band: Finite(p.band),
        }
    }
}

#[derive(Serialize)]
pub struct GoldenToleranceDoc {
    abs: Finite,
    rel: Finite,
}

#[derive(Serialize)]
pub struct GoldenDoc<'a> {
    scene: &'a str,
    quantity: &'static str,
    /// The disc whose curve it is, with several discs.
    #[serde(skip_serializing_if = "Option::is_none")]
    disc: Option<usize>,
    unit: &'static str,
    file: String,
    tolerance: GoldenToleranceDoc,
    passed: bool,
    points_compared: usize,
    worst: PointDoc<'a>,
    largest: PointDoc<'a>,
}

/// One headline result of a scene ([`engine::summary`](crate::engine::summary)).
#[derive(Serialize)]
pub struct HeadlineDoc {
    key: &'static str,
    label: &'static str,
    value: Finite,
    unit: &'static str,
    at: String,
    /// The plausible band's upper end the value lies beyond (`engine::plausibility`), in the
    /// quantity's unit; only on a marked headline.
    #[serde(skip_serializing_if = "Option::is_none")]
    beyond_plausible: Option<Finite>,
}

#[derive(Serialize)]
pub struct SummaryDoc<'a> {
    scene: &'a str,
    headlines: Vec<HeadlineDoc>,
}

/// One term of a study's objective at the optimum, unweighted, in its own unit.
#[derive(Serialize)]
pub struct TermDoc {
    name: &'static str,
    weight: Finite,
    unit: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    value: Option<Finite>,
}

#[derive(Serialize)]
pub struct ConstraintDoc<'a> {
    name: &'a str,
    value: Finite,
    bound: Finite,
    /// ≥ 0 satisfied.
    margin: Finite,
    satisfied: bool,
}

/// What an optimisation study found.
#[derive(Serialize)]
pub struct StudyDoc<'a> {
    name: &'a str,
    scene: &'a str,
    objective: Vec<TermDoc>,
    /// The weighted objective at the optimum; absent when it could not be evaluated.
    #[serde(skip_serializing_if = "Option::is_none")]
    objective_value: Option<Finite>,
    /// The variables at the optimum, in the spec's units, in the study's order.
    variables: Pairs,
    constraints: Vec<ConstraintDoc<'a>>,
    feasible: bool,
    /// Why the optimum could not be evaluated.
    #[serde(skip_serializing_if = "Option::is_none")]
    failure: Option<&'a str>,
    evaluations: usize,
    /// Where the optimum was found and why that search stopped (`optimise::Found`).
    stop_reason: String,
    /// What the objective alone hides: the optimum's smallest clearance over the whole mesh
    /// (mm) and its largest unloaded lost motion (arcsec, negative under interference).
    #[serde(skip_serializing_if = "Option::is_none")]
    min_clearance_mm: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    lost_motion_arcsec: Option<Finite>,
    /// The check of the optimum against the verification grid, when it ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    verification: Option<VerificationDoc>,
}

/// The verification grid of a study (`optimise::Verification`).
#[derive(Serialize)]
pub struct VerificationDoc {
    /// Grid points per variable, and in all.
    steps: usize,
    points: usize,
    feasible: usize,
    /// The best feasible grid point's objective minus the optimum's: ≥ 0 when no grid point
    /// is better. Absent when no grid point is feasible.
    #[serde(skip_serializing_if = "Option::is_none")]
    margin: Option<Finite>,
}

impl<'a> StudyDoc<'a> {
    fn new(spec: &'a Spec, study: &'a Study, r: &'a StudyResult) -> Self {
        let o = &r.optimum;
        let value = |q: &Quantity| {
            o.terms
                .iter()
                .find(|(t, _)| t.quantity == q)
                .map(|(_, v)| Finite(*v))
        };
        StudyDoc {
            name: &r.name,
            scene: &spec.scenes[study.scene].name,
            objective: study
                .objective
                .iter()
                .map(|(term, weight)| TermDoc {
                    name: term.name,
                    weight: Finite(*weight),
                    unit: term.quantity.unit,
                    value: value(term.quantity),
                })
                .collect(),
            objective_value: o.objective.is_finite().then_some(Finite(o.objective)),
            variables: Pairs(
                (study.variables.iter())
                    .map(|v| (v.kind.key(), Finite(v.kind.spec_value(&o.point))))
                    .collect(),
            ),
            constraints: o
                .margins
                .iter()
                .map(|m| ConstraintDoc {
                    name: &m.name,
                    value: Finite(m.value),
                    bound: Finite(m.bound),
                    margin: Finite(m.margin()),
                    satisfied: m.satisfied(),
                })
                .collect(),
            feasible: o.feasible(),
            failure: o.failure.as_deref(),
            evaluations: r.evaluations,
            stop_reason: super::optimisation::found(r.found),
            min_clearance_mm: o.min_clearance.as_ref().map(|c| Finite(c.gap_mm)),
            lost_motion_arcsec: o.lost_motion_arcsec.map(Finite),
            verification: r.verification.as_ref().map(|v| VerificationDoc {
                steps: v.steps,
                points: v.points,
                feasible: v.feasible,
                margin: v.margin.filter(|m| m.is_finite()).map(Finite),
            }),
        }
    }
}

/// The whole results document: its head, the scenes' documents, its tail, in this order.
/// `write_to` writes it; its `Serialize` (the Python bindings' tree) gives the same entries.
#[derive(Serialize)]
pub struct Document<'a> {
    #[serde(flatten)]
    head: Head<'a>,
    scenes: Vec<SceneDoc<'a>>,
    #[serde(flatten)]
    tail: Tail<'a>,
}

/// The results document's entries before its scenes.
#[derive(Serialize)]
struct Head<'a> {
    schema: u32,
    name: &'a str,
    tool_version: &'static str,
    spec_path: &'a str,
    /// SHA-256 of the spec file's text.
    spec_sha256: String,
    passed: bool,
    /// One disc's mass, its inertia about its centre and its centroid's offset from it, and
    /// the reducer's inertia at the input (a check's document; absent from a study's).
    #[serde(skip_serializing_if = "Option::is_none")]
    disc_mass_kg: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    disc_inertia_kgm2: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    disc_centroid_offset_mm: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    input_inertia_kgm2: Option<Finite>,
    /// Per scene that computes `inertia`: the unbalance the discs leave on the crank.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    unbalance: Vec<UnbalanceDoc<'a>>,
    checks: Vec<CheckDoc<'a>>,
    golden: Vec<GoldenDoc<'a>>,
}

/// The results document's entries after its scenes.
#[derive(Serialize)]
struct Tail<'a> {
    summary: Vec<SummaryDoc<'a>>,
    studies: Vec<StudyDoc<'a>>,
}

/// What the results document holds; `summaries` are `engine::summary::summarise(results)`.
pub struct Contents<'a> {
    pub spec: &'a Spec,
    /// Limit, study and golden checks.
    pub checks: &'a [Check],
    pub results: &'a [SceneResult],
    /// The golden checks' detail.
    pub goldens: &'a [GoldenResult],
    pub summaries: &'a [SceneSummary],
    /// The spec's optimisation studies' results, matched to `spec.studies` by name.
    pub studies: &'a [StudyResult],
    /// The discs' mass properties (a check's).
    pub mass: Option<&'a MassProperties>,
    /// The unbalance of each scene that computes `inertia` (a check's).
    pub unbalance: &'a [Unbalance],
}

impl<'a> Contents<'a> {
    /// Everything a check's run computed.
    pub fn of(run: &'a crate::engine::commands::CheckRun) -> Self {
        Contents {
            spec: &run.spec,
            checks: &run.checks,
            results: &run.results,
            goldens: &run.goldens,
            summaries: &run.summaries,
            studies: &run.studies,
            mass: Some(&run.mass),
            unbalance: &run.unbalance,
        }
    }
}

/// The documents of `results`, each matched to its study of `spec` by name: the results
/// document's `studies`, and what the Python `optimise` returns.
pub fn studies<'a>(spec: &'a Spec, results: &'a [StudyResult]) -> Vec<StudyDoc<'a>> {
    (results.iter())
        .filter_map(|r| {
            let study = spec.studies.iter().find(|s| s.name == r.name)?;
            Some(StudyDoc::new(spec, study, r))
        })
        .collect()
}

/// One scene's unbalance at speed (`engine::mass_properties::Unbalance`).
#[derive(Serialize)]
struct UnbalanceDoc<'a> {
    scene: &'a str,
    input_speed_rpm: Finite,
    /// F_c = m·(e + de)·ω² of one disc.
    disc_centripetal_force_n: Finite,
    unbalance_force_n: Finite,
    unbalance_moment_nm: Finite,
}

impl<'a> Document<'a> {
    pub fn new(c: &Contents<'a>) -> Self {
        Document {
            head: Head::new(c),
            scenes: (c.results.iter().enumerate())
                .map(|(k, r)| SceneDoc::new(r, c.summaries.get(k).filter(|s| s.scene == r.name)))
                .collect(),
            tail: Tail {
                summary: c.summaries.iter().map(summary).collect(),
                studies: studies(c.spec, c.studies),
            },
        }
    }

    /// Write the document (compact) to `out`: the head and tail serialised by serde_json,
    /// each scene by `SceneDoc::write`.
    pub fn write_to(&self, out: &mut dyn Write) -> std::io::Result<()> {
        let mut text = Text::new(out);
        let mut object = Object::new(&mut text)?;
        object.flatten(&self.head)?;
        object.raw("scenes", |text| {
            text.push(b"[")?;
            for (i, scene) in self.scenes.iter().enumerate() {
                text.push(if i > 0 { b"," } else { b"" })?;
                scene.write(text)?;
            }
            text.push(b"]")
        })?;
        object.flatten(&self.tail)?;
        object.end()?;
        text.finish()
    }
}

impl<'a> Head<'a> {
    fn new(c: &Contents<'a>) -> Self {
        Head {
            schema: 1,
            name: &c.spec.name,
            tool_version: env!("CARGO_PKG_VERSION"),
            spec_path: &c.spec.path,
            spec_sha256: sha256_hex(&c.spec.source),
            passed: c.checks.iter().all(|k| k.passed),
            disc_mass_kg: c.mass.map(|m| Finite(m.disc.mass_kg)),
            disc_inertia_kgm2: c.mass.map(|m| Finite(units::kgm2(m.disc.inertia_kgmm2))),
            disc_centroid_offset_mm: c.mass.map(|m| Finite(m.disc.centroid_offset_mm)),
            input_inertia_kgm2: c.mass.map(|m| Finite(units::kgm2(m.input_inertia_kgmm2))),
            unbalance: (c.unbalance.iter())
                .map(|u| UnbalanceDoc {
                    scene: &c.spec.scenes[u.scene].name,
                    input_speed_rpm: Finite(u.input_speed_rpm),
                    disc_centripetal_force_n: Finite(u.disc_force_n),
                    unbalance_force_n: Finite(u.force_n),
                    unbalance_moment_nm: Finite(units::nm(u.moment_nmm)),
                })
                .collect(),
            checks: c.checks.iter().map(check).collect(),
            golden: c.goldens.iter().map(golden).collect(),
        }
    }
}

fn check(c: &Check) -> CheckDoc<'_> {
    CheckDoc {
        id: &c.id,
        kind: match c.kind {
            CheckKind::Limit => "limit",
            CheckKind::Golden => "golden",
        },
        value: Finite(c.value),
        limit: Finite(c.limit),
        unit: c.unit,
        passed: c.passed,
        at: super::table::evidence(&c.at),
    }
}

fn golden(g: &GoldenResult) -> GoldenDoc<'_> {
    let c = &g.comparison;
    GoldenDoc {
        scene: &g.golden.scene,
        quantity: g.golden.quantity.key,
        disc: g.golden.disc,
        unit: g.golden.quantity.unit,
        file: g.golden.path.display().to_string(),
        tolerance: GoldenToleranceDoc {
            abs: Finite(g.golden.tolerance.abs),
            rel: Finite(g.golden.tolerance.rel),
        },
        passed: c.passed,
        points_compared: c.points,
        worst: (&c.worst).into(),
        largest: (&c.largest).into(),
    }
}

fn summary(s: &SceneSummary) -> SummaryDoc<'_> {
    SummaryDoc {
        scene: &s.scene,
        headlines: s
            .headlines
            .iter()
            .map(|h| HeadlineDoc {
                key: h.quantity.key,
                label: h.quantity.label,
                value: Finite(h.value),
                unit: h.quantity.unit,
                at: super::place::text(&h.at),
                beyond_plausible: h.beyond.map(|b| Finite(b.band)),
            })
            .collect(),
    }
}

/// The results of scenes alone (no checks, goldens or studies) with their `summaries`
/// (`engine::summary::marked`) as a JSON value: what a test compares with the registry.
pub fn scenes_value(
    spec: &Spec,
    results: &[SceneResult],
    summaries: &[SceneSummary],
) -> serde_json::Result<serde_json::Value> {
    let doc = scenes_document(spec, results, summaries);
    let mut text = Vec::new();
    doc.write_to(&mut text).map_err(serde_json::Error::io)?;
    serde_json::from_slice(&text)
}

/// The document of scenes alone (no checks, goldens, studies or mass properties), with their
/// `summaries` (`engine::summary::marked`).
pub fn scenes_document<'a>(
    spec: &'a Spec,
    results: &'a [SceneResult],
    summaries: &'a [SceneSummary],
) -> Document<'a> {
    Document::new(&Contents {
        spec,
        checks: &[],
        results,
        goldens: &[],
        summaries,
        studies: &[],
        mass: None,
        unbalance: &[],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::results::{MinClearance, SampledPeriod};

    /// `min_clearance_over` is one of the two objects docs/results-json.md gives: the whole
    /// period's three figures, or the scene's crank angles alone, never a mix (the enum that
    /// replaced four optional fields must not tag its variant or write the other's keys).
    #[test]
    fn the_minimum_is_sought_over_a_period_or_over_the_crank_angles_alone() {
        let min = MinClearance {
            gap_mm: 0.01,
            roller: 0,
            crank_rad: 0.0,
            tooth_phase: 0.0,
        };
        let over = |coverage| {
            let c = ClearanceSweep {
                gap_mm: Vec::new(),
                min,
                coverage,
                backlash: None,
            };
            serde_json::to_value(min_clearance_over(&c)).unwrap()
        };
        let angles = over(MinCoverage::Angles(36));
        assert_eq!(angles, serde_json::json!({ "crank_angles": 36 }));
        let period = over(MinCoverage::Period(SampledPeriod {
            period_rad: std::f64::consts::PI,
            step_rad: 0.01,
            error_bound_mm: 1e-6,
        }));
        // serde_json's Value keeps its keys sorted.
        let keys: Vec<&str> = period
            .as_object()
            .unwrap()
            .keys()
            .map(|k| k.as_str())
            .collect();
        assert_eq!(keys, ["error_bound_mm", "period_deg", "step_deg"]);
        assert_eq!(period["error_bound_mm"], 1e-6);
    }

    #[test]
    fn a_non_finite_number_is_an_error_not_null() {
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(serde_json::to_string(&Finite(x)).is_err(), "{x}");
        }
        let curve = [0.0, -0.0, 1.5, f64::NAN];
        assert!(serde_json::to_string(&Curve(&curve)).is_err());
        assert_eq!(
            serde_json::to_string(&Curve(&curve[..3])).unwrap(),
            "[0.0,-0.0,1.5]"
        );
    }

    /// The scene document names every curve of the registry once: none is left out of the
    /// results JSON, none written twice.
    #[test]
    fn the_scene_document_has_every_registry_curve_once() {
        let curves = |f: &Field| match *f {
            Field::Curve(q) | Field::CurveAndExtremes(q, _, _) => Some(q.key),
            _ => None,
        };
        let mut listed: Vec<_> = SCENE.iter().filter_map(curves).collect();
        listed.sort_unstable();
        let mut registry: Vec<_> = (QUANTITIES.iter())
            .filter(|q| !q.is_scalar())
            .map(|q| q.key)
            .collect();
        registry.sort_unstable();
        assert_eq!(listed, registry);
        assert_eq!(
            SCENE.iter().filter(|f| matches!(f, Field::Scalars)).count(),
            1
        );
    }

    /// A long scene's document is the same bytes wherever `SceneDoc::write` splits its fields
    /// between the front's thread and the back's (the split is the threads' race): every
    /// split, for a one-disc scene with line loads, a two-disc scene (each disc's document
    /// inside) and a duty cycle (its bins), against serde_json's text of the document.
    #[test]
    fn a_scene_document_is_the_same_bytes_wherever_its_fields_are_split() {
        use crate::engine::scene::{self, Writes};
        for (path, name) in [
            ("specs/reducer-misaligned.yaml", "designed"),
            ("specs/reducer-two-discs.yaml", "rated"),
            ("specs/reducer-duty-cycle.yaml", "robot-joint"),
        ] {
            let spec = crate::spec::load(path).unwrap();
            let mut s = (spec.scenes.iter().find(|s| s.name == name))
                .unwrap_or_else(|| panic!("{path}: no scene {name}"))
                .clone();
            s.crank_rad.truncate(5);
            let writes = Writes {
                json: true,
                report: false,
            };
            let plan = scene::plan(&spec, &s, writes);
            let r = scene::run(&spec, &s, &plan, &Default::default()).unwrap();
            let doc = SceneDoc::new(&r, None);
            let serialised = serde_json::to_vec(&doc).unwrap();
            for m in 1..=SCENE.len() {
                let mut written = Vec::new();
                let mut text = Text::new(&mut written);
                doc.write_split(&mut text, m).unwrap();
                text.finish().unwrap();
                assert!(written == serialised, "{path}: split at field {m}");
            }
        }
    }

    /// A count is written as a whole number, and one that is not is an error, not rounded.
    #[test]
    fn counts_are_whole_numbers() {
        assert_eq!(
            serde_json::to_string(&Counts(&[0.0, 3.0])).unwrap(),
            "[0,3]"
        );
        for x in [2.5, -1.0, f64::NAN, f64::INFINITY] {
            assert!(serde_json::to_string(&Counts(&[x])).is_err(), "{x}");
        }
    }
}
