//! The mean efficiency of a scene against its output torque (the design review's curve,
//! issue 28): the scene run again at fractions of its torque with its friction model
//! ([`engine::efficiency`](crate::engine::efficiency)).

use crate::engine::scene;
use crate::error::Result;
use crate::model::results::TorqueCurve;
use crate::model::{Effect, Plan, Scene};
use crate::spec::Spec;
use rayon::prelude::*;

/// Output torques of the review's efficiency curve, as fractions of the scene's: 5 % to 150 %,
/// denser at light load where the drag and any preload make the efficiency fall.
pub const CURVE_FRACTIONS: [f64; 12] = [
    0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.65, 0.8, 1.0, 1.25, 1.5,
];

/// The mean efficiency of `scene` of `spec` at each torque of `CURVE_FRACTIONS` × its own, with
/// its sign (its loaded model and friction solved again at each), rising, for the review; `None` when the scene
/// does not compute the efficiency or has no torque.
pub fn torque_curve(spec: &Spec, at_scene: &Scene) -> Result<Option<TorqueCurve>> {
    let plan = Plan::for_scene(at_scene);
    if !plan.computes(Effect::Efficiency) || at_scene.output_torque_nmm == 0.0 {
        return Ok(None);
    }
    let points: Result<Vec<(f64, f64)>> = CURVE_FRACTIONS
        .par_iter()
        .map(|f| {
            // The scene's own sign: a back-driven scene's curve is back-driven too, each
            // point's efficiency that of its power flow (`model::power_flow`).
            let at = Scene {
                output_torque_nmm: at_scene.output_torque_nmm * f,
                ..at_scene.clone()
            };
            let r = scene::run(spec, &at, &plan, &Default::default())?;
            let mean = (r.reducer)
                .efficiency
                .and_then(|e| e.reducer)
                .map_or(1.0, |e| e.mean_efficiency);
            Ok((at.output_torque_nmm, mean))
        })
        .collect();
    let mut points = points?;
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (torque_nmm, mean_efficiency) = points.into_iter().unzip();
    Ok(Some(TorqueCurve {
        torque_nmm,
        mean_efficiency,
    }))
}
