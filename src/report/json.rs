//! The results JSON (schema 1): typed documents (`Document`, `#[derive(Serialize)]`) that
//! borrow the results and convert them to the units named in their keys as they are
//! serialised; no tree of values is built. Arrays are \[roller\]\[angle\] or \[angle\]; a quantity
//! that was not computed is absent, never zero. The keys are documented in the README
//! ("Results JSON"); every registry quantity a scene computed is there under its key. What a
//! study's result holds is mapped in one place, `StudyDoc::new`.
//!
//! No number in the file is null, NaN or infinite: serialising a non-finite number is an
//! error and the run stops with it (the engine never produces one: a computation that fails
//! stops the run before).

use crate::engine::golden::{sha256_hex, GoldenResult, Point};
use crate::engine::mass_properties::{MassProperties, Unbalance};
use crate::engine::optimise::StudyResult;
use crate::engine::summary::SceneSummary;
use crate::engine::verdict::{Check, CheckKind};
use crate::error::Result;
use crate::model::quantity::{self as q, Quantity, QUANTITIES};
use crate::model::results::{ClearanceSweep, EfficiencyCurves, MinCoverage, SceneResult};
use crate::model::Study;
use crate::numeric::extremes;
use crate::report::explain::{hysteresis, torsion_compliances, torsion_law_note};
use crate::spec::Spec;
use crate::units::{self, nm_per_arcmin};
use serde::ser::{Error as _, SerializeMap, SerializeSeq};
use serde::{Serialize, Serializer};
use std::io::{BufWriter, Write};
use std::path::Path;

/// A number JSON can hold: serialising a non-finite one is an error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Finite(pub f64);

impl Serialize for Finite {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        if self.0.is_finite() {
            s.serialize_f64(self.0)
        } else {
            Err(S::Error::custom(format!(
                "a result is {}, which JSON cannot hold (a bug: please report it with the spec)",
                self.0
            )))
        }
    }
}

/// The unit a curve is written in, from the engine's (mm, N, MPa, rad).
#[derive(Clone, Copy)]
pub enum To {
    /// The engine's own unit (mm, N, MPa, a ratio).
    Same,
    Deg,
    Arcsec,
    /// N·mm to N·m.
    Nm,
}

impl To {
    /// A match rather than a function pointer: the conversion inlines into the loop that
    /// writes a curve, which is most of the file's cost.
    #[inline]
    fn convert(self, x: f64) -> f64 {
        match self {
            To::Same => x,
            To::Deg => units::deg(x),
            To::Arcsec => units::arcsec(x),
            To::Nm => units::nm(x),
        }
    }
}

/// A curve in engine units, converted to the key's unit as it is written.
#[derive(Clone, Copy)]
pub struct Curve<'a> {
    values: &'a [f64],
    to: To,
}

impl<'a> Curve<'a> {
    fn new(values: &'a [f64], to: To) -> Self {
        Curve { values, to }
    }

    fn plain(values: &'a [f64]) -> Self {
        Curve::new(values, To::Same)
    }
}

impl Serialize for Curve<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(self.values.len()))?;
        for &v in self.values {
            seq.serialize_element(&Finite(self.to.convert(v)))?;
        }
        seq.end()
    }
}

/// Curves \[part\]\[angle\] in the key's unit.
#[derive(Clone, Copy)]
pub struct Rows<'a>(&'a [Vec<f64>]);

impl Serialize for Rows<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_seq(self.0.iter().map(|row| Curve::plain(row)))
    }
}

/// Rows of a flat table (`FaceLoads::angles`), written as `Rows` writes its rows.
pub struct FlatRows<'a>(std::slice::ChunksExact<'a, f64>);

impl Serialize for FlatRows<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_seq(self.0.clone().map(Curve::plain))
    }
}

/// `key: value` pairs written as an object, in their order: the registry's scalars of a scene,
/// a study's variables.
pub struct Pairs(Vec<(&'static str, Finite)>);

impl Serialize for Pairs {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (key, value) in &self.0 {
            map.serialize_entry(key, value)?;
        }
        map.end()
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
pub struct MinClearanceOver {
    #[serde(skip_serializing_if = "Option::is_none")]
    period_deg: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    step_deg: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error_bound_mm: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    crank_angles: Option<usize>,
}

/// One scene: its curves, the registry's scalars and a few extremes.
#[derive(Serialize)]
pub struct SceneDoc<'a> {
    /// The scene's name and crank angles; absent in a disc's document (`discs`).
    #[serde(skip_serializing_if = "Option::is_none")]
    name: Option<&'a str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    crank_deg: Option<Curve<'a>>,
    /// A disc's share of the output torque (in a disc's document).
    #[serde(skip_serializing_if = "Option::is_none")]
    torque_nm: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    clearance_mm: Option<Rows<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    min_clearance_at: Option<MinClearanceAt>,
    #[serde(skip_serializing_if = "Option::is_none")]
    min_clearance_over: Option<MinClearanceOver>,
    #[serde(skip_serializing_if = "Option::is_none")]
    backlash_arcsec: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    backlash_reverse_arcsec: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    lost_motion_arcsec: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    lag_arcsec: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    roller_force_n: Option<Rows<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    contact_pressure_mpa: Option<Rows<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    contact_half_width_mm: Option<Rows<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    contacts: Option<&'a [usize]>,
    /// The line load of every roller along the face, N/mm \[roller\]\[crank\]\[slice\], with
    /// more than one slice (MODEL.md "Along the face width").
    #[serde(skip_serializing_if = "Option::is_none")]
    line_load_n_per_mm: Option<Vec<FlatRows<'a>>>,
    /// The face load factor at each crank angle, where the scene resolves the face.
    #[serde(skip_serializing_if = "Option::is_none")]
    face_load_factor: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    output_lag_arcsec: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pin_force_n: Option<Rows<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bearing_force_n: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bearing_angle_deg: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bearing_deflection_mm: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    residual: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    te_arcsec: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    te_max_arcsec: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    te_min_arcsec: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ratio: Option<Curve<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ratio_max: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    ratio_min: Option<Finite>,
    /// η at each crank angle (`efficiency`).
    #[serde(skip_serializing_if = "Option::is_none")]
    efficiency: Option<Curve<'a>>,
    /// The input torque at each crank angle, N·m.
    #[serde(skip_serializing_if = "Option::is_none")]
    input_torque_nm: Option<Curve<'a>>,
    /// The crank angles where the reducer self-locks (the output drives, T < 0, and the input
    /// must still push), degrees; empty when it back-drives everywhere or T ≥ 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    self_locking_deg: Option<Curve<'a>>,
    /// The mean power lost on each path, W (with a speed; a disc's: its contacts').
    #[serde(skip_serializing_if = "Option::is_none")]
    power_loss_w: Option<PowerLossDoc>,
    /// Why the losses in watts are absent (no speed), with `efficiency`.
    #[serde(skip_serializing_if = "Option::is_none")]
    power_loss_note: Option<&'static str>,
    /// The registry's scalars the scene computed (`QUANTITIES`): min_clearance_mm,
    /// max_roller_force_n, ... (with several discs, the worst over the discs).
    #[serde(flatten)]
    scalars: Pairs,
    /// A torsion scene's curves and figures (`TorsionDoc`).
    #[serde(flatten)]
    torsion: Option<TorsionDoc>,
    /// With several discs, each disc's curves and scalars (MODEL.md "Several discs").
    #[serde(skip_serializing_if = "Vec::is_empty")]
    discs: Vec<SceneDoc<'a>>,
    /// A duty-cycle scene's bins and each disc's life under the cycle (`DutyDoc`).
    #[serde(skip_serializing_if = "Option::is_none")]
    duty_cycle: Option<DutyDoc<'a>>,
    /// The `strength` effect's pin stresses and contact fatigue lives (`StrengthDoc`).
    #[serde(flatten)]
    strength: StrengthDoc<'a>,
}

/// The `strength` effect's curves and lives beside the registry's scalars (`engine::strength`).
#[derive(Serialize)]
pub struct StrengthDoc<'a> {
    /// σ_b of each output pin, MPa \[pin\]\[crank\] (the reducer's, every disc's force summed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pin_bending_stress_mpa: Option<Rows<'a>>,
    /// The disc's and the rollers' contact fatigue lives, h (a disc's own with several).
    #[serde(skip_serializing_if = "Option::is_none")]
    contact_fatigue_life_h: Option<FatigueDoc>,
}

/// The two lives of `StrengthDoc`, each when its S–N law is given.
#[derive(Serialize)]
pub struct FatigueDoc {
    #[serde(skip_serializing_if = "Option::is_none")]
    disc: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rollers: Option<Finite>,
}

impl<'a> StrengthDoc<'a> {
    fn new(r: &'a SceneResult) -> Self {
        let fatigue = r.loaded.strength.and_then(|s| s.fatigue);
        StrengthDoc {
            pin_bending_stress_mpa: (r.loaded.pin_stress.as_ref())
                .map(|p| Rows(&p.bending_stress_mpa)),
            contact_fatigue_life_h: fatigue.map(|f| FatigueDoc {
                disc: f.disc_h.map(Finite),
                rollers: f.rollers_h.map(Finite),
            }),
        }
    }
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
                    revolution_share: Finite(
                        b.bin.time_share * b.bin.input_speed_rpm / d.mean_speed_rpm,
                    ),
                    equivalent_load_n: crate::engine::duty_cycle::bin_equivalent_loads(&b.result)
                        .map(finite),
                    max_contact_pressure_mpa: q::MAX_CONTACT_PRESSURE
                        .scalar(&b.result)
                        .map(|e| Finite(e.value)),
                    mean_efficiency: q::MEAN_EFFICIENCY
                        .scalar(&b.result)
                        .map(|e| Finite(e.value)),
                    results: SceneDoc::disc(&b.result),
                })
                .collect(),
        })
    }
}

/// A torsion scene's block in the results JSON (flattened into the scene object): its loop,
/// torsion angles and catalogue figures.
#[derive(Serialize)]
pub struct TorsionDoc {
    /// The loop's torques, N·m \[m\].
    torque_nm: Vec<Finite>,
    /// γ \[crank\]\[m\], arcmin.
    torsion_arcmin: Vec<Vec<Finite>>,
    lost_motion_arcmin: Vec<Finite>,
    backlash_arcmin: Vec<Finite>,
    /// The smaller direction \[crank\].
    torsional_rigidity_nm_per_arcmin: Vec<Finite>,
    torsional_rigidity_forward_nm_per_arcmin: Vec<Finite>,
    torsional_rigidity_reverse_nm_per_arcmin: Vec<Finite>,
    /// With friction in the loop: γ_unloading − γ_loading at T = 0 \[crank\], arcmin.
    #[serde(skip_serializing_if = "Option::is_none")]
    hysteresis_loss_arcmin: Option<Vec<Finite>>,
    /// With friction in the loop: its area, the energy per cycle \[crank\], J.
    #[serde(skip_serializing_if = "Option::is_none")]
    hysteresis_energy_j: Option<Vec<Finite>>,
    /// Where the hysteresis loss comes from (0 without friction), and how it is read.
    hysteresis: &'static str,
    /// What the torsion angle is made of.
    compliances: CompliancesDoc,
}

/// The contact law and compliances of a torsion curve (`explain::torsion_compliances`).
#[derive(Serialize)]
pub struct CompliancesDoc {
    contact_law: &'static str,
    /// Computed by the loaded model.
    modelled: Vec<String>,
    /// Held rigid by the model (a rigid crank bearing, rigid pins): no twist of theirs.
    not_modelled: Vec<String>,
    /// Given in the spec and added (the structure's c·T).
    given: Vec<String>,
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

/// A per-crank curve of the registry, as written.
fn registry(r: &SceneResult, quantity: &Quantity) -> Vec<Finite> {
    let values = quantity.curves(r).and_then(|mut c| c.values.pop());
    finite(values.unwrap_or_default())
}

impl TorsionDoc {
    pub fn new(r: &SceneResult) -> Option<TorsionDoc> {
        let t = r.torsion.as_ref()?;
        let direction = |pick: fn((f64, f64)) -> f64| {
            finite(
                t.figures
                    .iter()
                    .map(|f| nm_per_arcmin(pick(f.rigidity_nmm_per_rad))),
            )
        };
        Some(TorsionDoc {
            torque_nm: finite(t.torque_nmm.iter().map(|&x| units::nm(x))),
            torsion_arcmin: t
                .torsion_rad
                .iter()
                .map(|row| finite(row.iter().map(|&g| units::arcmin(g))))
                .collect(),
            lost_motion_arcmin: registry(r, &q::TORSION_LOST_MOTION),
            backlash_arcmin: registry(r, &q::TORSION_BACKLASH),
            torsional_rigidity_nm_per_arcmin: registry(r, &q::TORSIONAL_RIGIDITY),
            torsional_rigidity_forward_nm_per_arcmin: direction(|d| d.0),
            torsional_rigidity_reverse_nm_per_arcmin: direction(|d| d.1),
            hysteresis_loss_arcmin: t.friction.then(|| registry(r, &q::HYSTERESIS_LOSS)),
            hysteresis_energy_j: t.friction.then(|| registry(r, &q::HYSTERESIS_ENERGY)),
            hysteresis: hysteresis(t.friction),
            compliances: {
                let c = &t.compliances;
                let text = torsion_compliances(c);
                CompliancesDoc {
                    contact_law: c.contact_law.name(),
                    modelled: text.modelled,
                    not_modelled: text.not_modelled,
                    given: text.given,
                    structure_arcmin_per_knm: Finite(units::arcmin_per_knm(
                        c.structure_rad_per_nmm,
                    )),
                    note: torsion_law_note(c.contact_law),
                }
            },
        })
    }
}

/// (max, min) of a curve.
fn max_min(values: &[f64], to: To) -> (Option<Finite>, Option<Finite>) {
    let ((lo, _), (hi, _)) = extremes(values);
    (Some(Finite(to.convert(hi))), Some(Finite(to.convert(lo))))
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
        MinCoverage::Period(p) => MinClearanceOver {
            period_deg: Some(Finite(units::deg(p.period_rad))),
            step_deg: Some(Finite(units::deg(p.step_rad))),
            error_bound_mm: Some(Finite(p.error_bound_mm)),
            crank_angles: None,
        },
        MinCoverage::Angles(n) => MinClearanceOver {
            period_deg: None,
            step_deg: None,
            error_bound_mm: None,
            crank_angles: Some(n),
        },
    }
}

impl<'a> SceneDoc<'a> {
    pub fn new(r: &'a SceneResult) -> Self {
        let c = r.clearance.as_ref();
        let backlash = c.and_then(|c| c.backlash.as_ref());
        let l = &r.loaded;
        let (rollers, pins, bearing) = (l.rollers.as_ref(), l.pins.as_ref(), l.bearing.as_ref());
        let te = l.transmission.as_ref();
        let ratio = te.and_then(|t| t.ratio.as_deref());
        let arcsec = |v: &'a [f64]| Curve::new(v, To::Arcsec);
        let (te_max_arcsec, te_min_arcsec) =
            te.map_or((None, None), |t| max_min(&t.te_rad, To::Arcsec));
        let (ratio_max, ratio_min) = ratio.map_or((None, None), |v| max_min(v, To::Same));
        let reducer_eff = r.efficiency.as_ref().and_then(|e| e.reducer.as_ref());
        SceneDoc {
            name: Some(&r.name),
            crank_deg: Some(Curve::new(&r.crank_rad, To::Deg)),
            torque_nm: l.torque_nmm.as_deref().map(|t| Curve::new(t, To::Nm)),
            clearance_mm: c.map(|c| Rows(&c.gap_mm)),
            min_clearance_at: c.map(min_clearance_at),
            min_clearance_over: c.map(min_clearance_over),
            backlash_arcsec: backlash.map(|b| arcsec(&b.forward_rad)),
            backlash_reverse_arcsec: backlash.map(|b| arcsec(&b.reverse_rad)),
            lost_motion_arcsec: backlash.map(|b| arcsec(&b.lost_motion_rad)),
            lag_arcsec: rollers.map(|c| arcsec(&c.lag_rad)),
            roller_force_n: rollers.map(|c| Rows(&c.force_n)),
            contact_pressure_mpa: rollers.map(|c| Rows(&c.pressure_mpa)),
            contact_half_width_mm: rollers.map(|c| Rows(&c.half_width_mm)),
            contacts: rollers.map(|c| c.contacts.as_slice()),
            line_load_n_per_mm: rollers
                .and_then(|c| c.face.as_ref())
                .filter(|f| {
                    f.slices > 1 && f.line_load_n_per_mm.first().is_some_and(|r| !r.is_empty())
                })
                .map(|f| {
                    (0..f.line_load_n_per_mm.len())
                        .map(|i| FlatRows(f.angles(i)))
                        .collect()
                }),
            face_load_factor: rollers
                .and_then(|c| c.face.as_ref())
                .map(|f| Curve::plain(&f.face_load_factor)),
            output_lag_arcsec: pins.map(|p| arcsec(&p.output_lag_rad)),
            pin_force_n: pins.map(|p| Rows(&p.force_n)),
            bearing_force_n: bearing.map(|b| Curve::plain(&b.force_n)),
            bearing_angle_deg: bearing.map(|b| Curve::new(&b.angle_rad, To::Deg)),
            bearing_deflection_mm: bearing.map(|b| Curve::plain(&b.deflection_mm)),
            residual: bearing.map(|b| Curve::plain(&b.residual)),
            te_arcsec: te.map(|t| arcsec(&t.te_rad)),
            te_max_arcsec,
            te_min_arcsec,
            ratio: ratio.map(Curve::plain),
            ratio_max,
            ratio_min,
            efficiency: reducer_eff.map(|e| Curve::plain(&e.efficiency)),
            input_torque_nm: reducer_eff.map(|e| Curve::new(&e.input_torque_nmm, To::Nm)),
            self_locking_deg: reducer_eff.map(|e| Curve::new(&e.self_locking_crank_rad, To::Deg)),
            power_loss_w: r.efficiency.as_ref().and_then(PowerLossDoc::new),
            power_loss_note: r
                .efficiency
                .as_ref()
                .filter(|e| e.input_speed_rad_s.is_none())
                .map(|_| NO_SPEED),
            scalars: Pairs(
                QUANTITIES
                    .iter()
                    .filter_map(|q| Some((q.key, Finite(q.scalar(r)?.value))))
                    .collect(),
            ),
            torsion: TorsionDoc::new(r),
            discs: r.discs.iter().map(SceneDoc::disc).collect(),
            duty_cycle: DutyDoc::new(r),
            strength: StrengthDoc::new(r),
        }
    }

    /// A disc's document: its curves and scalars, without the scene's name and angles.
    fn disc(r: &'a SceneResult) -> Self {
        SceneDoc {
            name: None,
            crank_deg: None,
            ..SceneDoc::new(r)
        }
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
            crank_deg: Finite(p.crank_deg),
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
                study
                    .variables
                    .iter()
                    .map(|v| {
                        (
                            v.kind.key(),
                            Finite(v.kind.to_spec_unit(v.kind.get(&o.point()))),
                        )
                    })
                    .collect(),
            ),
            constraints: o
                .margins
                .iter()
                .map(|m| ConstraintDoc {
                    name: &m.name,
                    value: Finite(m.value),
                    bound: Finite(m.bound),
                    margin: Finite(m.margin),
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

/// The whole results document.
#[derive(Serialize)]
pub struct Document<'a> {
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
    scenes: Vec<SceneDoc<'a>>,
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
            scenes: c.results.iter().map(SceneDoc::new).collect(),
            summary: c.summaries.iter().map(summary).collect(),
            studies: c
                .studies
                .iter()
                .filter_map(|r| {
                    let study = c.spec.studies.iter().find(|s| s.name == r.name)?;
                    Some(StudyDoc::new(c.spec, study, r))
                })
                .collect(),
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
        unit: g.unit,
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

/// The results of scenes alone (no checks, goldens or studies) as a JSON value: what a test
/// compares with the registry.
pub fn scenes_value(spec: &Spec, results: &[SceneResult]) -> serde_json::Result<serde_json::Value> {
    let summaries = crate::engine::summary::marked(spec, results);
    serde_json::to_value(Document::new(&Contents {
        spec,
        checks: &[],
        results,
        goldens: &[],
        summaries: &summaries,
        studies: &[],
        mass: None,
        unbalance: &[],
    }))
}

/// serde_json's compact format, with zeros (most of the forces and pressures: a roller out of
/// contact) written without the float formatter, which costs as much for 0.0 as for any
/// number.
struct Compact;

impl serde_json::ser::Formatter for Compact {
    fn write_f64<W: ?Sized + Write>(&mut self, out: &mut W, value: f64) -> std::io::Result<()> {
        if value == 0.0 {
            out.write_all(if value.is_sign_negative() {
                b"-0.0"
            } else {
                b"0.0"
            })
        } else {
            serde_json::ser::CompactFormatter.write_f64(out, value)
        }
    }
}

/// Write the document to `path` atomically ([`files::write_atomic_with`](crate::files::write_atomic_with)), compact, through a
/// buffer of 64 KiB: it stays in cache, and the writes of a few bytes per number into it
/// inline (through the `dyn Write` below it they would be calls).
pub fn write(path: &Path, doc: &Document) -> Result<()> {
    crate::files::write_atomic_with(path, |out| {
        let mut out = BufWriter::with_capacity(64 << 10, out);
        doc.serialize(&mut serde_json::Serializer::with_formatter(
            &mut out, Compact,
        ))?;
        out.flush()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_non_finite_number_is_an_error_not_null() {
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(serde_json::to_string(&Finite(x)).is_err(), "{x}");
        }
        let curve = [0.0, -0.0, 1.5, f64::NAN];
        assert!(serde_json::to_string(&Curve::plain(&curve)).is_err());
        assert_eq!(
            serde_json::to_string(&Curve::plain(&curve[..3])).unwrap(),
            "[0.0,-0.0,1.5]"
        );
    }

    /// The compact formatter's zeros are serde_json's (the value read back is the same).
    #[test]
    fn zeros_are_written_as_serde_json_writes_them() {
        for x in [0.0, -0.0] {
            let mut ours = Vec::new();
            Finite(x)
                .serialize(&mut serde_json::Serializer::with_formatter(
                    &mut ours, Compact,
                ))
                .unwrap();
            assert_eq!(
                String::from_utf8(ours).unwrap(),
                serde_json::to_string(&x).unwrap()
            );
        }
    }
}
