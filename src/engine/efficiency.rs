//! The effect `efficiency` of a scene (MODEL.md "Friction, efficiency and heat"): the loss of
//! every friction path at every crank angle, the efficiency, the input torque and the steady
//! temperature, from the contact forces of the scene's friction model.
//!
//! The friction model is chosen where the sweep is solved (`scene::loaded_model`): the loss
//! model's sweep is the frictionless balance, the coupled model's has friction inside every
//! balance; here both measure the losses from their sweep with `equilibrium::friction::loss`. The input torque is the loss model's energy balance or the
//! coupled model's crank balance (`crank_input_torque`).
//!
//! Powers per unit input speed (N·mm/rad, the power at ω = 1 rad/s in N·mm/s):
//! P = |T|/nc with T the scene's output torque (all discs); η(φ) is the efficiency of the power
//! that flows at loss(φ) (`engine::power_flow`: P/(P + loss) with the input driving, (P −
//! loss)/P with the output driving, T < 0), mean η the same at the mean loss (the mean of the
//! losses, not of η). With no output torque η is 0 where anything is lost and 1 where nothing
//! is (no NaN). Coulomb friction
//! makes every loss proportional to ω, so η does not depend on the speed; the watts are the
//! losses × ω × 1e-3 and exist only with `input_speed_rpm`, the temperature ambient +
//! P/(h·A) only with `reducer.thermal` too.

use crate::engine::power_flow::PowerFlow;
use crate::equilibrium::coupling::Coupling;
use crate::equilibrium::friction::loss::{
    disc_losses as contact_losses, reducer_losses, PathLosses,
};
use crate::equilibrium::loaded::{AngleSolution, Model};
use crate::equilibrium::pins::PinState;
use crate::equilibrium::rollers::{Reach, RollerState};
use crate::error::{Error, Result};
use crate::geometry::clearance::Pose;
use crate::geometry::Vec2;
use crate::model::results::{EfficiencyCurves, LoadedSweep, ReducerEfficiency, RollerCurves};
use crate::model::{Design, Effect, Friction, FrictionModel, Plan, Scene};
use crate::units;
use rayon::prelude::*;

/// Crank angles re-evaluated in one piece: each piece warm-starts its rollers' feet from its
/// previous angle, as a sweep's chunk does.
const PIECE: usize = 64;

/// The efficiency of a scene whose loaded sweep is done (`discs`: each disc's curves, one for
/// a one-disc reducer, with `model` the loaded model of the disc at phase 0): the reducer's
/// curves and each disc's (empty for one disc). `None` when the plan does not compute it.
pub fn efficiency(
    design: &Design,
    model: &Model,
    (scene, plan): (&Scene, &Plan),
    discs: &[&LoadedSweep],
) -> Result<Option<(EfficiencyCurves, Vec<EfficiencyCurves>)>> {
    let Some(friction) = design
        .friction
        .filter(|_| plan.computes(Effect::Efficiency))
    else {
        return Ok(None);
    };
    let per_disc = disc_losses(&friction, design, model, scene, discs)?;
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
    let input = match friction.model {
        FrictionModel::Loss => None,
        FrictionModel::Coupled => Some(crank_input_torque(&friction, design, scene, discs)),
    };
    let reducer = reducer_figures(design, scene, &total, speed, input);
    let disc_curves = if per_disc.len() > 1 {
        per_disc.into_iter().map(|d| curves(d, None)).collect()
    } else {
        Vec::new()
    };
    Ok(Some((curves(total, Some(reducer)), disc_curves)))
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
        driver: flow.driver,
        output_power_nmm: flow.output_power_nmm,
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
/// the axis: T_in = Σ_k T_in,k + T0 (at the scene's speed), T_in,k disc k's share from its
/// bearing's recorded force (`Coupling::input_torque`).
fn crank_input_torque(
    friction: &Friction,
    design: &Design,
    scene: &Scene,
    discs: &[&LoadedSweep],
) -> Vec<f64> {
    let c = Coupling::new(friction, design);
    (0..scene.crank_rad.len())
        .map(|i| {
            let discs: f64 = discs
                .iter()
                .filter_map(|d| d.bearing.as_ref())
                .map(|b| c.input_torque(b.force_n[i], b.angle_rad[i]))
                .sum();
            discs + friction.no_load_torque_nmm.at_rpm(scene.input_speed_rpm)
        })
        .collect()
}

/// The mean of each path over the angles.
fn mean(loss: &[PathLosses]) -> PathLosses {
    let sum = loss.iter().fold(PathLosses::default(), |a, b| a.plus(b));
    sum.scaled(1.0 / loss.len().max(1) as f64)
}

/// Each disc's contact losses `[disc][angle]` from its loaded sweep: the loss model's sweep is
/// the frictionless balance, the coupled model's already carries the friction
/// (`scene::loaded_model`), so both read their forces and contact points the same way.
fn disc_losses(
    friction: &Friction,
    design: &Design,
    model: &Model,
    scene: &Scene,
    discs: &[&LoadedSweep],
) -> Result<Vec<Vec<PathLosses>>> {
    discs
        .iter()
        .enumerate()
        .map(|(k, d)| {
            sweep_losses(
                friction,
                design,
                model,
                scene,
                (design.disc_phase_rad(k), d),
            )
        })
        .collect()
}

/// A disc's contact losses at each of the scene's crank angles from its loaded curves `sweep`
/// (disc at crank phase `phase`; frictionless for the loss model, coupled for the coupled). The contact points and
/// normals of the rollers that carry a force are the ones the sweep recorded
/// (`LoadedSweep::roller_contacts`); at an angle it recorded none for (the lean first-order
/// sweep's) they are evaluated again at the angle's loaded pose (crank φ + phase, lag β, and the
/// centre's offset −Fb/kb in a compliant bearing); the forces are the sweep's.
fn sweep_losses(
    friction: &Friction,
    design: &Design,
    model: &Model,
    scene: &Scene,
    (phase, sweep): (f64, &LoadedSweep),
) -> Result<Vec<PathLosses>> {
    let crank = &scene.crank_rad;
    let indices: Vec<usize> = (0..crank.len()).collect();
    let pieces: Result<Vec<Vec<PathLosses>>> = indices
        .par_chunks(PIECE)
        .map(|piece| {
            let mut sol = AngleSolution::default();
            let mut reaches = Vec::new();
            piece
                .iter()
                .map(|&i| {
                    let phi = crank[i] + phase;
                    solution_at(model, sweep, (i, phi), &mut sol, &mut reaches)?;
                    Ok(contact_losses(friction, design, phi, &sol))
                })
                .collect()
        })
        .collect();
    Ok(pieces?.into_iter().flatten().collect())
}

/// A gap that proves a roller out of contact at the very pose it is evaluated at (so that
/// `Rollers::evaluate_within` skips it), or that proves nothing (so that it is evaluated), mm.
const SKIP_MM: f64 = 1e9;

/// The solution of angle `i` (crank `phi`, the disc's phase included) rebuilt from the sweep's
/// curves into `sol` (its previous rollers warm-start the feet): the states of the rollers
/// that carry a force at the loaded pose, with the sweep's forces (the others keep zero force
/// and are skipped: they lose nothing), the pins' forces, the bearing's force.
fn solution_at(
    model: &Model,
    sweep: &LoadedSweep,
    (i, phi): (usize, f64),
    sol: &mut AngleSolution,
    reaches: &mut Vec<Reach>,
) -> Result<()> {
    let bearing = sweep.bearing.as_ref().map(|b| {
        let angle = phi + b.angle_rad[i];
        Vec2::new(angle.cos(), angle.sin()) * b.force_n[i]
    });
    sol.bearing_force_n = bearing;
    if let (Some(rollers), Some(curves)) = (&model.rollers, &sweep.rollers) {
        if recorded_contacts(sweep, curves, i, sol) {
            return Ok(());
        }
        let offset = match (model.bearing_stiffness_n_per_mm, bearing) {
            (Some(kb), Some(fb)) => -fb / kb,
            _ => Vec2::zeros(),
        };
        let pose = Pose {
            crank_rad: phi,
            lag_rad: curves.lag_rad[i],
            centre_offset_mm: offset,
        };
        let first = sol.rollers.is_empty();
        reaches.clear();
        for (r, f) in curves.force_n.iter().enumerate() {
            let loaded = f[i] > 0.0;
            // A roller that comes into contact starts its foot from its guess, not from where
            // it was last evaluated (possibly many angles ago).
            let was_loaded = sol
                .rollers
                .get(r)
                .is_some_and(|s| s.force_n > 0.0 && !s.t.is_nan());
            if loaded && !was_loaded && !first {
                sol.rollers[r].t = rollers.mesh.foot_guess(r, &pose);
            }
            reaches.push(Reach {
                crank_rad: pose.crank_rad,
                lag_rad: pose.lag_rad,
                offset_mm: pose.centre_offset_mm,
                gap_mm: if loaded { -SKIP_MM } else { SKIP_MM },
            });
        }
        rollers
            .evaluate_within(&pose, &mut sol.rollers, reaches)
            .map_err(|e| {
                Error::computation(format!(
                    "crank angle {:.4}°: the rollers' contact points for the friction losses: {e}",
                    units::deg(phi)
                ))
            })?;
        for (s, f) in sol.rollers.iter_mut().zip(&curves.force_n) {
            s.force_n = f[i];
        }
    }
    pins_at(sweep, i, sol);
    Ok(())
}

/// The pins' forces of angle `i` into `sol` (their geometry plays no part in the losses).
fn pins_at(sweep: &LoadedSweep, i: usize, sol: &mut AngleSolution) {
    if let Some(pins) = &sweep.pins {
        sol.pins.clear();
        sol.pins.extend(pins.force_n.iter().map(|f| PinState {
            gap_mm: 0.0,
            force_n: f[i],
            stiffness_n_per_mm: 0.0,
            arm_mm: 0.0,
            direction: Vec2::zeros(),
            point: Vec2::zeros(),
            gap_slope_mm: 0.0,
        }));
    }
}

/// The loaded rollers of angle `i` from the contacts the sweep recorded (`roller_contacts`)
/// into `sol`, with the pins' forces: false (nothing written) where the sweep recorded none
/// for a roller that carries a force (the lean first-order sweep's angles), which are then
/// evaluated again.
fn recorded_contacts(
    sweep: &LoadedSweep,
    curves: &RollerCurves,
    i: usize,
    sol: &mut AngleSolution,
) -> bool {
    let Some(contacts) = &sweep.roller_contacts else {
        return false;
    };
    let recorded = |r: usize| contacts[r][i][2] != 0.0 || contacts[r][i][3] != 0.0;
    if (0..curves.force_n.len()).any(|r| curves.force_n[r][i] > 0.0 && !recorded(r)) {
        return false;
    }
    sol.rollers.clear();
    sol.rollers
        .extend(curves.force_n.iter().zip(contacts).map(|(f, c)| {
            let [x, y, nx, ny] = c[i];
            RollerState {
                gap_mm: 0.0,
                force_n: f[i],
                stiffness_n_per_mm: 0.0,
                arm_mm: 0.0,
                normal: Vec2::new(nx, ny),
                point: Vec2::new(x, y),
                // No foot to warm-start from: an angle evaluated again starts from its guess.
                t: f64::NAN,
            }
        }));
    pins_at(sweep, i, sol);
    true
}
