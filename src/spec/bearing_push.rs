//! The push of a compliant crank bearing (`scenes[].bearing_stiffness_n_per_mm`): a bearing
//! too soft for a scene's torque lets the disc centre leave its mesh, whatever the solver does.
//!
//! The crank holds each disc through its bearing at the eccentric: the crank's moment balance
//! about the input axis gives the input torque as e times the tangential component of the
//! bearing force, T_in = e·Fb_t. The solves with a compliant bearing are frictionless (the
//! coupled friction model is refused with one, the loss model is computed after them), so the
//! work balance over a period, the elastic energy periodic, gives the input torque's mean as
//! T/nc plus the energy released where the solution path snaps (a fold of the equilibria the
//! sweep jumps across), which is never negative: for a positive torque the mean is at least
//! T/nc. Summed over the N discs the tangential forces then average at least T/(nc·e), so the
//! most loaded disc's averages at least T/(N·nc·e), and its centre's push along the orbit's
//! tangent, Fb_t/kb, at least T/(N·nc·e·kb). Its push at some angle is at least its mean, and
//! a centre moved beyond e has left the mesh (`SolveFailure::OutOfMesh`): a scene with
//! T/(N·nc·e·kb) > e cannot be solved over the reducer's period, and is refused before it is
//! tried, with the stiffness it would need, T/(N·nc·e²). A negative torque is not judged: the
//! released energy lowers its mean (by 4 % on the preloaded disc of
//! `specs/hard/preload-compliant-bearing.yaml` at −1 N·m on 300 N/mm).

use super::rules::rule;
use crate::error::Result;
use crate::model::{Design, Effect, Plan, Scene};
use crate::numeric::{input, number};
use crate::units;

/// Refuse the first scene whose compliant crank bearing the torque must push beyond e on
/// average (module doc). A torque loop (`torque_sweep`) holds the crank still, so the mean over
/// a period does not apply to it; a duty cycle is judged at its largest positive torque.
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
        // The largest positive torque, and the duty-cycle bin that has it.
        let (torque_nmm, bin) = match &s.duty_cycle {
            Some(bins) => (bins.iter().enumerate())
                .map(|(j, b)| (b.output_torque_nmm, Some(j)))
                .fold((0.0, None), |a, b| if b.0 > a.0 { b } else { a }),
            None => (s.output_torque_nmm, None),
        };
        let force_n = torque_nmm / (discs * nc * e);
        let push_mm = force_n / kb;
        if push_mm > e {
            let (held, which, leaves) = match design.discs {
                1 => ("disc", "the disc's", "the disc"),
                _ => ("discs", "the most loaded disc's", "that disc"),
            };
            let at = bin.map_or(String::new(), |j| format!(" (duty-cycle bin {j})"));
            return Err(rule(
                &format!("scenes[{i}].bearing_stiffness_n_per_mm"),
                format!(
                    "scene `{}`: a crank bearing of {} N/mm cannot hold the {held} at {} N·m{at}: \
                     over a period the input torque loads {which} bearing tangentially by at \
                     least T/(N·nc·e) = {} N on average (N = {}, nc = {}, e = {} mm), which \
                     moves its centre by at least {} mm on average, more than e: {leaves} would \
                     leave its mesh; the bearing needs more than T/(N·nc·e²) = {} N/mm",
                    s.name,
                    input(kb),
                    input(units::nm(torque_nmm)),
                    number(force_n),
                    design.discs,
                    design.teeth,
                    input(e),
                    number(push_mm),
                    number(rounded_up(force_n / e)),
                ),
            ));
        }
    }
    Ok(())
}

/// `x` > 0 rounded up at its fourth significant digit, so that `number`'s four digits never
/// understate a bound (277.78 N/mm shows as 277.8, 277.71 as 277.8, not 277.7).
fn rounded_up(x: f64) -> f64 {
    let unit = 10f64.powf(x.log10().floor() - 3.0);
    (x / unit).ceil() * unit
}
