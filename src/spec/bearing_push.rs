//! The push of a compliant crank bearing (`scenes[].bearing_stiffness_n_per_mm`): a bearing
//! too soft for a scene's torque lets the disc centre leave its mesh, whatever the solver does.
//!
//! The crank holds each disc through its bearing at the eccentric: the crank's moment balance
//! about the input axis gives the input torque as e times the tangential component of the
//! bearing force, T_in = e·Fb_t. The solves with a compliant bearing are frictionless (the
//! coupled friction model is refused with one, the loss model is computed after them), so the
//! work balance over a period, with the elastic energy periodic, gives the mean of T_in as the
//! disc's torque over the mean ratio nc: the tangential force averages T_k/(nc·e), and the
//! centre's push along the orbit's tangent, Fb_t/kb, averages T_k/(nc·e·kb). The discs' shares
//! T_k sum to T, so the most loaded averages at least T/N. Its push at some angle is at least
//! its mean, and a centre moved beyond e has left the mesh (`SolveFailure::OutOfMesh`): a
//! scene with T/(N·nc·e·kb) > e cannot be solved over the reducer's period, and is refused
//! before it is tried, with the stiffness it would need, T/(N·nc·e²).

use super::rules::rule;
use crate::error::Result;
use crate::model::{Design, Effect, Plan, Scene};
use crate::numeric::input;
use crate::units;

/// Refuse the first scene whose compliant crank bearing the torque must push beyond e on
/// average (module doc). A torque loop (`torque_sweep`) holds the crank still, so the mean over
/// a period does not apply to it; a duty cycle is judged at its largest torque.
pub(super) fn check(design: &Design, scenes: &[Scene]) -> Result<()> {
    let e = design.built_eccentricity_mm();
    let (discs, nc) = (design.discs as f64, design.teeth as f64);
    for (i, s) in scenes.iter().enumerate() {
        let Some(kb) = s.bearing_stiffness_n_per_mm else {
            continue;
        };
        if s.torque_sweep.is_some() || !Plan::for_scene(s).has(Effect::Bearing) {
            continue;
        }
        let torque_nmm = match &s.duty_cycle {
            Some(bins) => bins
                .iter()
                .map(|b| b.output_torque_nmm.abs())
                .fold(0.0, f64::max),
            None => s.output_torque_nmm.abs(),
        };
        let force_n = torque_nmm / (discs * nc * e);
        let push_mm = force_n / kb;
        if push_mm > e {
            return Err(rule(
                &format!("scenes[{i}].bearing_stiffness_n_per_mm"),
                format!(
                    "scene `{}`: the crank bearing of {} N/mm cannot hold the disc at {} N·m: \
                     over a period the input torque loads each disc's bearing tangentially by \
                     T/(N·nc·e) = {force_n:.1} N on average (N = {} {}, nc = {}, e = {} mm), \
                     which moves its centre by {push_mm:.3} mm on average, more than e: the disc \
                     would leave its mesh; the bearing needs more than T/(N·nc·e²) = {:.1} N/mm",
                    s.name,
                    input(kb),
                    input(units::nm(torque_nmm)),
                    design.discs,
                    if design.discs == 1 { "disc" } else { "discs" },
                    design.teeth,
                    input(e),
                    force_n / e,
                ),
            ));
        }
    }
    Ok(())
}
