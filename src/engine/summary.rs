//! The headline results of each scene (`quantity::SUMMARY`): min clearance, lost motion, the
//! largest roller, pin and bearing forces and Hertz pressure, TE and ratio fluctuation, fewest
//! rollers in contact, each with where it occurs. What a reviewer reads first; `check` prints
//! it after the checks table, the results JSON carries it as `summary`, and the design review
//! puts it at the top.

use crate::model::quantity::{Quantity, SUMMARY};
use crate::model::results::SceneResult;

/// One headline result of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Headline {
    pub quantity: &'static Quantity,
    /// In the quantity's unit.
    pub value: f64,
    /// Where it occurs.
    pub at: String,
}

/// The headline results a scene computed (those it did not compute are left out).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneSummary {
    pub scene: String,
    pub headlines: Vec<Headline>,
    /// How many crank angles the scene samples.
    pub angles: usize,
    /// The step between its first two crank angles, rad (0 with one angle).
    pub step_rad: f64,
}

/// The summary of every scene, in spec order.
pub fn summarise(results: &[SceneResult]) -> Vec<SceneSummary> {
    results
        .iter()
        .map(|r| SceneSummary {
            scene: r.name.clone(),
            headlines: SUMMARY
                .iter()
                .filter_map(|&q| {
                    let e = q.scalar(r)?;
                    Some(Headline {
                        quantity: q,
                        value: e.value,
                        at: e.at,
                    })
                })
                .collect(),
            angles: r.crank_rad.len(),
            step_rad: match r.crank_rad.as_slice() {
                [a, b, ..] => b - a,
                _ => 0.0,
            },
        })
        .collect()
}
