//! The effect `efficiency` of a scene (MODEL.md "Friction, efficiency and heat"): the loss of
//! every friction path at every crank angle, the efficiency, the input torque and the steady
//! temperature, from the contact forces of the scene's friction model.
//!
//! The friction model is chosen where the sweep is solved (`scene::loaded_model`): the loss
//! model's sweep is the frictionless balance, the coupled model's has friction inside every
//! balance; both record each angle's losses where its solution is at hand
//! (`LoadedSweep::losses`, measured by `equilibrium::friction::loss`), and the coupled model
//! each disc's share of the input torque from the crank's balance (`Coupling::input_torque`);
//! here they are summed over the discs. The loss model's input torque is the reducer's energy
//! balance (`reducer_figures`), and so is the coupled model's at zero torque, whose balance is
//! the frictionless one (a preload's friction is in its losses, not in that balance).
//!
//! Powers per unit input speed (N·mm/rad, the power at ω = 1 rad/s in N·mm/s):
//! P = |T|/nc with T the scene's output torque (all discs); η(φ) is the efficiency of the power
//! that flows at loss(φ) (`model::power_flow`: P/(P + loss) with the input driving, (P −
//! loss)/P with the output driving, T < 0), mean η the same at the mean loss (the mean of the
//! losses, not of η). With no output torque η is 0 where anything is lost and 1 where nothing
//! is (no NaN). Coulomb friction
//! makes every loss proportional to ω, so η does not depend on the speed; the watts are the
//! losses × ω × 1e-3 and exist only with `input_speed_rpm`, the temperature ambient +
//! P/(h·A) only with `reducer.thermal` too.

use crate::equilibrium::friction::loss::{reducer_losses, PathLosses};
use crate::error::{Error, Result};
use crate::model::power_flow::PowerFlow;
use crate::model::results::{EfficiencyCurves, LoadedSweep, ReducerEfficiency};
use crate::model::{Design, Effect, Friction, FrictionModel, Plan, Scene};
use crate::units;

/// The efficiency of a scene whose loaded sweep is done (`discs`: each disc's curves, one for
/// a one-disc reducer, each with the losses and input torque its sweep recorded,
/// `LoadedSweep::losses`): the reducer's curves and each disc's (empty for one disc). `None`
/// when the plan does not compute it.
pub fn efficiency(
    design: &Design,
    (scene, plan): (&Scene, &Plan),
    discs: &[&LoadedSweep],
) -> Result<Option<(EfficiencyCurves, Vec<EfficiencyCurves>)>> {
    let Some(friction) = design
        .friction
        .filter(|_| plan.computes(Effect::Efficiency))
    else {
        return Ok(None);
    };
    let per_disc = recorded(discs, |d| d.losses.as_ref(), "losses")?;
    let speed = scene.input_speed_rpm.map(units::rad_per_s);
    let curves = |loss_nmm: Vec<PathLosses>, reducer| EfficiencyCurves {
        model: friction.model,
        mean_loss_nmm: mean(&loss_nmm),
        loss_nmm,
        input_speed_rad_s: speed,
        reducer,
    };
    let n = scene.crank_rad.len();
    let total: Vec<PathLosses> = (0..n)
        .map(|i| {
            let discs = per_disc.iter().map(|d| &d[i]);
            reducer_losses(&friction, scene.input_speed_rpm, discs)
        })
        .collect();
    // At zero torque the coupled model's balance is the frictionless one
    // (`loaded::Model::coupled`): its crank's balance holds no contact friction, yet a
    // preload's contacts slide and lose. Its input torque is then the loss model's energy
    // balance, T_in·ω = the losses.
    let input = match friction.model {
        FrictionModel::Coupled if scene.output_torque_nmm != 0.0 => {
            Some(crank_input_torque(&friction, scene, discs)?)
        }
        FrictionModel::Loss | FrictionModel::Coupled => None,
    };
    let reducer = reducer_figures(design, scene, &total, speed, input);
    let disc_curves = if per_disc.len() > 1 {
        per_disc
            .into_iter()
            .map(|d| curves(d.clone(), None))
            .collect()
    } else {
        Vec::new()
    };
    Ok(Some((curves(total, Some(reducer)), disc_curves)))
}

/// What each disc's sweep recorded for the efficiency (`field`, named `what`); an error when a
/// sweep did not record it (`Model::losses` not set by the scene's loaded model): a fault of
/// the engine, not of the spec.
fn recorded<'a, T>(
    discs: &[&'a LoadedSweep],
    field: impl Fn(&'a LoadedSweep) -> Option<&'a T>,
    what: &str,
) -> Result<Vec<&'a T>> {
    (discs.iter().map(|d| field(d)).collect::<Option<_>>()).ok_or_else(|| {
        Error::computation(format!(
            "the efficiency: the loaded sweep recorded no {what} (the scene's loaded model did \
             not ask for them)"
        ))
    })
}

/// The reducer's efficiency, input torque and temperature from its losses `[angle]`.
fn reducer_figures(
    design: &Design,
    scene: &Scene,
    loss: &[PathLosses],
    speed_rad_s: Option<f64>,
    coupled_input_nmm: Option<Vec<f64>>,
) -> ReducerEfficiency {
    let nc = design.teeth as f64;
    let torque = scene.output_torque_nmm;
    let flow = PowerFlow::new(torque, design.teeth);
    let mean_loss = mean(loss).total();
    let temperature_c = design
        .thermal
        .zip(speed_rad_s)
        .map(|(t, w)| t.temperature_c(units::w(mean_loss * w)));
    let input_torque_nmm: Vec<f64> = coupled_input_nmm.unwrap_or_else(|| {
        // The loss model's input torque from the energy balance P_in = P_out + Σ losses per
        // unit input speed: T/nc + loss(φ).
        loss.iter().map(|l| torque / nc + l.total()).collect()
    });
    ReducerEfficiency {
        flow,
        efficiency: loss.iter().map(|l| flow.efficiency(l.total())).collect(),
        mean_efficiency: flow.efficiency(mean_loss),
        self_locks: flow.self_locks(mean_loss),
        self_locking_crank_rad: self_locking(scene, &input_torque_nmm),
        input_torque_nmm,
        temperature_c,
    }
}

/// Where the output drives (T < 0 at the forward kinematics: back-driving) and the input must
/// still push (T_in ≥ 0): the friction holds more than the output's torque can drive, the
/// reducer self-locks at those crank angles (rad). Empty for a driving output torque.
fn self_locking(scene: &Scene, input_torque_nmm: &[f64]) -> Vec<f64> {
    if scene.output_torque_nmm >= 0.0 {
        return Vec::new();
    }
    scene
        .crank_rad
        .iter()
        .zip(input_torque_nmm)
        .filter(|(_, t)| **t >= 0.0)
        .map(|(phi, _)| *phi)
        .collect()
}

/// The coupled model's input torque at each crank angle, N·mm, from the crank's balance about
/// the axis: T_in = Σ_k T_in,k + T0 (at the scene's speed), T_in,k disc k's share that its
/// sweep recorded (`Coupling::input_torque`).
fn crank_input_torque(
    friction: &Friction,
    scene: &Scene,
    discs: &[&LoadedSweep],
) -> Result<Vec<f64>> {
    let shares = recorded(discs, |d| d.input_torque_nmm.as_ref(), "input torque")?;
    let drag = friction.no_load_torque_nmm.at_rpm(scene.input_speed_rpm);
    Ok((0..scene.crank_rad.len())
        .map(|i| {
            let discs: f64 = shares.iter().map(|t| t[i]).sum();
            discs + drag
        })
        .collect())
}

/// The mean of each path over the angles.
fn mean(loss: &[PathLosses]) -> PathLosses {
    let sum = loss.iter().fold(PathLosses::default(), |a, b| a.plus(b));
    sum.scaled(1.0 / loss.len().max(1) as f64)
}
