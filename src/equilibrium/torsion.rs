//! Friction in a torsion loop (MODEL.md "Friction, efficiency and heat"): the input is locked,
//! the disc turns about its own centre, and every contact's Coulomb friction resists that
//! turn. On the loading branch (σ = +1) the disc's lag grows, unloading (σ = −1) it shrinks;
//! each branch is a sequence of quasi-static balances in full sliding with the coupled
//! friction of `coupling` (`Sliding::Torsion`).
//!
//! The rollers' and the bearing's sliding signs follow from σ and the geometry alone. A hole
//! slides over its pin at −O_d·u − ρ·X·u per unit turn (`friction::sliding::torsion_pin_sliding`), with
//! ρ = dβo/dβ the pins' deflection per unit turn of the disc: on a branch both lags follow the
//! torque, so ρ = (∂T/∂β)/(∂T/∂βo), the ratio of the rollers' and the pins' balance slopes at
//! the solution. Each point is solved with the ρ of the last one and solved again while the
//! new ρ turns a pin's sliding the other way (`RATIO_PASSES` at most: a pin whose sliding
//! changes sign with ρ sits where it does not slide, and either sign of its friction is then
//! within the model's resolution of that point).

use crate::equilibrium::coupling::Sliding;
use crate::equilibrium::discs::{solve_coupled, CoupledWork, Discs};
use crate::equilibrium::solve::SolveFailure;

/// The most solves of one point of a branch while ρ turns a pin's sliding.
const RATIO_PASSES: usize = 4;

/// A point of a branch in full sliding: the torsion angle γ (rad, the twist of whatever is in
/// series with the discs included) and the discs' own lag β (rad), the turn that the rollers'
/// and the bearing's friction resist and, when they stick, hold.
#[derive(Debug, Clone, Copy)]
pub struct BranchPoint {
    pub torsion_rad: f64,
    pub disc_rad: f64,
}

impl BranchPoint {
    /// The elastic twist in series with the discs at this point, γ − β (rad): the pins'
    /// deflection βo and the structure's c_s·T. It follows the torque whether the discs slide
    /// or stick: a spring in series stores and returns its energy, it opens no loop.
    pub fn series_rad(self) -> f64 {
        self.torsion_rad - self.disc_rad
    }
}

/// The discs' own lag β (rad) at the last solve of `work`: the disc's roller lag (with several
/// discs, their mean: each one's γ = β_k + βo_k, and they stick and slide together).
fn disc_lag(work: &CoupledWork) -> f64 {
    let lags: Vec<f64> = work.works.iter().filter_map(|w| w.sol.lag_rad).collect();
    lags.iter().sum::<f64>() / lags.len().max(1) as f64
}

/// The torsion loop's two branches in full sliding at the locked crank angle `crank_rad`:
/// loading (σ = +1) up through `up` (the torques, ascending, N·mm), then unloading (σ = −1)
/// back down, each point warm-started from the last; both returned in `up`'s order. A point's
/// torsion angle is γ + c_s·T (`structure_rad_per_nmm` = c_s, the rest of the reducer in
/// series). A failed solve: its torque and why.
pub fn branches(
    discs: &Discs,
    crank_rad: f64,
    up: &[f64],
    structure_rad_per_nmm: f64,
) -> Result<(Vec<BranchPoint>, Vec<BranchPoint>), (f64, SolveFailure)> {
    let mut discs = discs.clone();
    let mut work = CoupledWork::new(&discs);
    let mut branch = |sigma: f64, torques: &mut dyn Iterator<Item = f64>| {
        set_branch(&mut discs, &mut work, sigma);
        torques
            .map(|t| {
                let gamma = solve_point(&mut discs, crank_rad, t, &mut work).map_err(|f| (t, f))?;
                Ok(BranchPoint {
                    torsion_rad: gamma + structure_rad_per_nmm * t,
                    disc_rad: disc_lag(&work),
                })
            })
            .collect::<Result<Vec<BranchPoint>, _>>()
    };
    let loading = branch(1.0, &mut up.iter().copied())?;
    let mut unloading = branch(-1.0, &mut up.iter().rev().copied())?;
    unloading.reverse();
    Ok((loading, unloading))
}

/// Put every disc of `discs` (and of `work`, once it holds their models) on the branch σ
/// (`sigma`, +1 loading, −1 unloading), each keeping its ρ.
pub fn set_branch(discs: &mut Discs, work: &mut CoupledWork, sigma: f64) {
    for m in discs.models.iter_mut().chain(work.models.iter_mut()) {
        if let Some(c) = m.coupling.as_mut() {
            if let Sliding::Torsion { pin_ratio, .. } = c.sliding {
                c.sliding = Sliding::Torsion { sigma, pin_ratio };
            }
        }
    }
}

/// The reducer's output lag γ (rad) at the output torque `torque_nmm` on the branch the discs
/// are on, at the locked crank angle `crank_rad`, warm-started from `work` (the last solve of
/// the same angle): the coupled balance of the discs ([`equilibrium::discs`](crate::equilibrium::discs)); with one
/// disc γ = β + βo, β the disc's lag (rollers) and βo the pins' deflection (0 when the pins are
/// not modelled). Every disc's ρ is then that of this point, for the next.
pub fn solve_point(
    discs: &mut Discs,
    crank_rad: f64,
    torque_nmm: f64,
    work: &mut CoupledWork,
) -> Result<f64, SolveFailure> {
    discs.torque_nmm = torque_nmm;
    let mut pass = 0;
    loop {
        let gamma = solve_coupled(discs, crank_rad, work)?;
        pass += 1;
        if !update_pin_ratios(work) || pass == RATIO_PASSES {
            return Ok(gamma);
        }
    }
}

/// Set each disc's ρ to the ratio of its balances' slopes at its last solution; whether a
/// loaded pin's sliding sign changed with it (the point must be solved again).
fn update_pin_ratios(work: &mut CoupledWork) -> bool {
    let mut changed = false;
    for (m, w) in work.models.iter_mut().zip(&work.works) {
        let Some(c) = m.coupling.as_mut() else {
            continue;
        };
        let Sliding::Torsion { sigma, .. } = c.sliding else {
            continue;
        };
        let (rollers, pins) = w.slopes;
        let ratio = rollers / pins;
        if !(ratio.is_finite() && ratio >= 0.0) {
            continue;
        }
        let centre = w.e_phi * c.eccentricity_mm + w.sol.centre_offset_mm;
        changed |= c.pin_signs_change(w.e_phi, centre, &w.sol.pins, ratio);
        c.sliding = Sliding::Torsion {
            sigma,
            pin_ratio: ratio,
        };
    }
    changed
}
