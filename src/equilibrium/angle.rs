//! The loaded solve at one crank angle of a scene: the balances with a rigid bearing
//! (`rigid_bearing`) or a compliant one (`compliant_bearing`), then the bearing's force and the
//! residual of the equilibrium (`residual`), remembered for the next angle's guess (`work`).

use super::compliant_bearing::solve_compliant;
use super::loaded::{AngleSolution, Model};
use super::residual::residual_at;
use super::rigid_bearing::{net_force, solve_rigid};
use super::solve::SolveFailure;
use super::work::Work;
use crate::geometry::{unit, Vec2};

/// Solve one crank angle with the model's bearing, warm-started from `previous`.
pub fn solve_angle(
    model: &Model,
    crank: f64,
    previous: &AngleSolution,
) -> Result<AngleSolution, SolveFailure> {
    let mut work = Work::exact_from(previous.clone());
    if previous.lag_rad.is_some() || previous.output_lag_rad.is_some() {
        // One history entry at this very angle: the guess is the previous solution's lags.
        work.remember(crank, model.torque_nmm);
    }
    solve_into(model, crank, &mut work)?;
    Ok(work.sol)
}

/// Solve one crank angle into `work.sol`, then remember it for the next angle's guess.
pub fn solve_into(model: &Model, crank: f64, work: &mut Work) -> Result<(), SolveFailure> {
    work.forget_if_far(crank, model);
    work.e_phi = unit(crank);
    match model.bearing_stiffness_n_per_mm {
        Some(_) if model.coupled().is_some() => {
            return Err(SolveFailure::Evaluation(
                "the coupled friction model needs a rigid crank bearing (no \
                 bearing_stiffness_n_per_mm); use `friction.model: loss` with a compliant one"
                    .into(),
            ))
        }
        Some(kb) => work.sol = solve_compliant(model, kb, crank, work)?,
        None => solve_rigid(model, crank, work, Vec2::zeros())?,
    }
    if model.bearing {
        let fb = match model.bearing_stiffness_n_per_mm {
            Some(kb) => -kb * work.sol.centre_offset_mm,
            None => match model.coupled() {
                Some(c) => -c.net_force(crank, &work.sol),
                // The contacts' and the disc's centrifugal reaction (`Effect::Inertia`).
                None => -net_force(&work.sol) - model.centrifugal_n(work.e_phi),
            },
        };
        work.sol.bearing_force_n = Some(fb);
        work.sol.residual = Some(match model.coupled() {
            Some(c) => c.residual(crank, &work.sol, model.torque_nmm),
            // The forces at the disc centre: the bearing's and the centrifugal reaction.
            None => residual_at(
                model,
                work.e_phi,
                &work.sol,
                fb + model.centrifugal_n(work.e_phi),
            ),
        });
    }
    work.remember(crank, model.torque_nmm);
    Ok(())
}
