//! The headline results of each scene (`quantity::SUMMARY`): min clearance, lost motion, the
//! largest roller, pin and bearing forces and Hertz pressure, TE and ratio fluctuation, fewest
//! rollers in contact, each with where it occurs. What a reviewer reads first; `check` prints
//! it after the checks table, the results JSON carries it as `summary`, and the design review
//! puts it at the top.

use crate::engine::plausibility::{self, Beyond};
use crate::model::quantity::{
    Extreme, Quantity, DISC_TORQUE, MAX_HYSTERESIS_LOSS, QUANTITIES, SUMMARY,
};
use crate::model::results::SceneResult;
use crate::spec::Spec;

/// One headline result of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Headline {
    pub quantity: &'static Quantity,
    /// In the quantity's unit.
    pub value: f64,
    /// Where it occurs, as data (`report::place` says it in words).
    pub at: crate::model::place::Place,
    /// Beyond its plausible band, no limit judging it (`engine::plausibility`): a mark for
    /// the reader, not a failed check. `None` from `summarise`; `marked` sets it.
    pub beyond: Option<Beyond>,
    /// The smallest magnitude the computation resolves, in the quantity's unit: a value below
    /// it is not distinguished from 0 (a torsion loop's hysteresis loss: `resolution`); 0
    /// where the value is resolved to its printed digits.
    pub resolution: f64,
}

/// One disc's share Tk of the scene's torque over its crank angles, N·m (with several discs).
#[derive(Debug, Clone, PartialEq)]
pub struct TorqueShare {
    pub disc: usize,
    pub mean_nm: f64,
    pub min_nm: f64,
    pub max_nm: f64,
    /// The scene's torque, the sum of the shares at every angle (MODEL.md "Several discs"),
    /// N·m: the shares' sum at the first angle.
    pub scene_nm: f64,
}

/// The headline results a scene computed (those it did not compute are left out).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSummary {
    pub scene: String,
    pub headlines: Vec<Headline>,
    /// Every registry scalar the scene computed (`Quantity::scalar`), in `QUANTITIES`' order:
    /// computed once here, read by the headlines, the finiteness guard and the results JSON.
    pub scalars: Vec<(&'static Quantity, Extreme)>,
    /// How many crank angles the scene samples.
    pub angles: usize,
    /// The step between its first two crank angles, rad (0 with one angle).
    pub step_rad: f64,
    /// Its first crank angle, rad (its only one, with one angle).
    pub first_rad: f64,
    /// The reducer's discs (1, or `reducer.discs`).
    pub discs: usize,
    /// Each disc's torque share, with several discs that carry load (else empty).
    pub shares: Vec<TorqueShare>,
}

impl SceneSummary {
    /// The scene's scalar of `q`, if it computed it (`scalars`).
    pub fn scalar(&self, q: &Quantity) -> Option<&Extreme> {
        scalar_in(&self.scalars, q)
    }
}

/// `q`'s scalar among `scalars`, matched by key.
fn scalar_in<'a>(scalars: &'a [(&Quantity, Extreme)], q: &Quantity) -> Option<&'a Extreme> {
    scalars.iter().find(|(s, _)| s.key == q.key).map(|(_, e)| e)
}

/// The summary of every scene, in spec order.
pub fn summarise(results: &[SceneResult]) -> Vec<SceneSummary> {
    results
        .iter()
        .map(|r| (r, scalars(r)))
        .map(|(r, scalars)| SceneSummary {
            scene: r.name.clone(),
            headlines: SUMMARY
                .iter()
                .filter_map(|&q| {
                    let e = scalar_in(&scalars, q)?;
                    Some(Headline {
                        quantity: q,
                        value: e.value,
                        at: e.at.clone(),
                        beyond: None,
                        resolution: resolution(q, r),
                    })
                })
                .collect(),
            scalars,
            angles: r.crank_rad.len(),
            step_rad: crate::numeric::step(&r.crank_rad),
            first_rad: r.crank_rad.first().copied().unwrap_or(0.0),
            discs: r.discs.len().max(1),
            shares: shares(r),
        })
        .collect()
}

/// Every registry scalar `r` computed, in `QUANTITIES`' order (`SceneSummary::scalars`).
fn scalars(r: &SceneResult) -> Vec<(&'static Quantity, Extreme)> {
    QUANTITIES
        .iter()
        .filter_map(|&q| Some((q, q.scalar(r)?)))
        .collect()
}

/// What a headline of `q` resolves in `r` (`Headline::resolution`): for the max hysteresis loss
/// of a torsion loop, the finest of its locked angles' resolutions
/// (`TorsionCurves::hysteresis_resolution_rad`), arcmin; else 0.
fn resolution(q: &Quantity, r: &SceneResult) -> f64 {
    match &r.reducer.torsion {
        Some(t) if q.key == MAX_HYSTERESIS_LOSS.key => (0..t.figures.len())
            .map(|k| crate::units::arcmin(t.hysteresis_resolution_rad(k)))
            .reduce(f64::min)
            .unwrap_or(0.0),
        _ => 0.0,
    }
}

/// Each disc's torque share over the crank angles (`DISC_TORQUE`): the mean, the range and the
/// scene's torque; empty for one disc (it has no share curve) or a scene without loaded discs.
fn shares(r: &SceneResult) -> Vec<TorqueShare> {
    let curves: Vec<Vec<f64>> = r
        .discs
        .iter()
        .filter_map(|d| DISC_TORQUE.disc_curves(d)?.values.pop())
        .filter(|c| !c.is_empty())
        .collect();
    if curves.len() != r.discs.len() {
        return Vec::new();
    }
    let scene_nm: f64 = curves.iter().map(|c| c[0]).sum();
    curves
        .iter()
        .enumerate()
        .map(|(disc, c)| TorqueShare {
            disc,
            mean_nm: c.iter().sum::<f64>() / c.len() as f64,
            min_nm: c.iter().copied().fold(f64::INFINITY, f64::min),
            max_nm: c.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            scene_nm,
        })
        .collect()
}

/// `summarise`, each headline marked when it lies beyond its plausible band and no limit of
/// `spec` judges it (`engine::plausibility`). Scenes are matched to `results` by position
/// (results are in spec order).
pub fn marked(spec: &Spec, results: &[SceneResult]) -> Vec<SceneSummary> {
    let mut summaries = summarise(results);
    for (s, scene) in summaries.iter_mut().zip(&spec.scenes) {
        let torque_nmm = match (&scene.torque_sweep, &scene.duty_cycle) {
            (Some(_), _) => 0.0, // a torsion scene has no loaded headline of force or pressure
            // A duty cycle's headlines are the worst over its bins: the largest bin torque.
            (_, Some(bins)) => bins
                .iter()
                .fold(0.0f64, |m, b| m.max(b.output_torque_nmm.abs())),
            _ => scene.output_torque_nmm,
        };
        for h in &mut s.headlines {
            h.beyond =
                plausibility::beyond(&spec.design, &spec.limits, h.quantity, torque_nmm, h.value);
        }
    }
    summaries
}
