//! The compliant bearing (stiffness kb): the disc centre moves by u until the bearing's force
//! on the disc, −kb·u, balances the contacts' net force, with β and βo balancing the torque at
//! every u (`rigid_bearing::solve_rigid` at the offset u). Newton on u with the Jacobian
//! reduced from the analytic 4×4 one (nalgebra); where it cannot settle, continuation in the
//! bearing's stiffness and roots along the principal directions (`solve_compliant`).

use super::balance::moment;
use super::loaded::{AngleSolution, Model};
use super::rigid_bearing::{net_force, solve_rigid};
use super::solve::{monotone_root, Balance, Settings, SolveFailure};
use super::work::Work;
use crate::geometry::Vec2;
#[cfg(test)]
use crate::geometry::{clearance::Pose, unit};
use nalgebra::{Matrix4, Vector4};

/// Residual vector of the compliant problem and the per-row scales.
fn compliant_residual(model: &Model, kb: f64, sol: &AngleSolution) -> (Vector4<f64>, Vector4<f64>) {
    let f = net_force(sol);
    let u = sol.centre_offset_mm;
    let (mr, _, sr) = moment(&sol.rollers);
    let (mp, _, sp) = moment(&sol.pins);
    let scale = force_scale(kb, sol);
    let t = model.torque_nmm.abs();
    (
        Vector4::new(
            f.x - kb * u.x,
            f.y - kb * u.y,
            mr - model.torque_nmm,
            mp - model.torque_nmm,
        ),
        Vector4::new(scale, scale, t.max(sr), t.max(sp)).map(|s| s.max(1e-300)),
    )
}

/// Evaluate rollers and pins at x = (ux, uy, β, βo) (the finite-difference check of
/// `compliant_jacobian`).
#[cfg(test)]
fn evaluate_at(
    model: &Model,
    crank: f64,
    x: &Vector4<f64>,
    sol: &mut AngleSolution,
) -> Result<(), SolveFailure> {
    let (r, p) = (model.rollers.as_ref(), model.pins.as_ref());
    let (Some(r), Some(p)) = (r, p) else {
        return Err(SolveFailure::Evaluation(
            "a compliant bearing needs rollers and pins".into(),
        ));
    };
    sol.centre_offset_mm = Vec2::new(x[0], x[1]);
    sol.lag_rad = Some(x[2]);
    sol.output_lag_rad = Some(x[3]);
    let pose = Pose::new(crank, x[2], sol.centre_offset_mm);
    r.evaluate(&pose, &mut sol.rollers)?;
    p.evaluate_at(
        unit(crank),
        (-crank / model.teeth as f64 + x[2]).sin_cos(),
        sol.centre_offset_mm,
        x[3],
        &mut sol.pins,
    );
    Ok(())
}

/// Jacobian of `compliant_residual` (contact normals and arms held fixed over a step).
fn compliant_jacobian(kb: f64, sol: &AngleSolution) -> Matrix4<f64> {
    let mut j = Matrix4::zeros();
    j[(0, 0)] = -kb;
    j[(1, 1)] = -kb;
    for s in &sol.rollers {
        let (k, n, l) = (s.stiffness_n_per_mm, s.normal, s.arm_mm);
        // f = −F·n, F = F(−gap), ∂gap/∂u = −n, ∂gap/∂β = −l.
        for a in 0..2 {
            for b in 0..2 {
                j[(a, b)] -= k * n[a] * n[b];
            }
            j[(a, 2)] -= k * l * n[a];
            j[(2, a)] += k * l * n[a];
        }
        j[(2, 2)] += k * l * l;
    }
    for s in &sol.pins {
        let (k, d, a, g) = (s.stiffness_n_per_mm, s.direction, s.arm_mm, s.gap_slope_mm);
        // f = F·û, ∂gap/∂u = û, ∂gap/∂βo = g.
        for r in 0..2 {
            for c in 0..2 {
                j[(r, c)] -= k * d[r] * d[c];
            }
            j[(r, 3)] -= k * g * d[r];
            j[(3, r)] -= k * a * d[r];
        }
        j[(3, 3)] -= k * a * g;
    }
    j
}

/// Compliant bearing: the disc centre moves by u until the bearing's force on the disc, −kb·u,
/// balances the contacts' net force f(u): R(u) = f(u) − kb·u = 0, with β and βo balancing the
/// torque at every u (`solve_rigid` at the offset u: bracketed, robust 1-D solves).
///
/// Newton on u alone, with the Jacobian of R reduced from the full 4×4 one
/// (`compliant_jacobian`) by eliminating the lags λ = (β, βo), whose balances hold at every
/// iterate: ∂R/∂u = J_uu − J_uλ·J_λλ⁻¹·J_λu (a Schur complement). ∂R/∂u ≈ −(kb·I + K_eff)
/// with K_eff the contacts' stiffness left after the lags follow, so a step is never longer
/// than the force over the contacts' stiffness, however soft the bearing (1e3 N/mm under
/// contacts of 1e6 N/mm, where a fixed-point iteration converges by 1e-3 per step). Steps are
/// halved until the force residual shrinks (a contact opening or closing makes R kinked; a
/// step that pushes a roller out of its closest-point reach cannot be evaluated).
pub(super) fn solve_compliant(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
) -> Result<AngleSolution, SolveFailure> {
    let start = if work.near(crank, model) {
        work.sol.centre_offset_mm
    } else {
        Vec2::zeros()
    };
    match centre_newton(model, kb, crank, work, start) {
        Ok(sol) => Ok(sol),
        Err(direct) => stiffness_continuation(model, kb, crank, work).map_err(|_| direct),
    }
}

/// The compliant solve by continuation in the bearing's stiffness: from 10⁴·kb (the disc
/// centre nearly fixed) down to kb by factors of 10, each stage started from the last. The
/// centre moves continuously with the stiffness, so every stage starts near its answer, where
/// the direct Newton from rest can meet kinks of the residual (contacts that open and close)
/// between rest and an answer half a millimetre away (a 1000 N/mm bearing at 10 N·m).
fn stiffness_continuation(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
) -> Result<AngleSolution, SolveFailure> {
    let mut u = Vec2::zeros();
    for stage in (1..=4).rev() {
        u = centre_newton(model, kb * 10f64.powi(stage), crank, work, u)?.centre_offset_mm;
    }
    centre_newton(model, kb, crank, work, u)
}

/// Newton on the centre offset from `start` (see `solve_compliant`).
fn centre_newton(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    start: Vec2,
) -> Result<AngleSolution, SolveFailure> {
    let mut u = start;
    let tol = compliant_tolerance(model);
    let mut force = centre_residual(model, kb, crank, work, u)?;
    let mut best = work.sol.clone();
    let mut exact_jacobian = false;
    for _ in 0..MAX_CENTRE_STEPS {
        if force_merit(model, kb, &best) <= tol {
            return Ok(best);
        }
        let step = if exact_jacobian {
            let jacobian = jacobian_by_differences(model, kb, crank, work, u)?;
            work.sol = best.clone();
            jacobian.lu().solve(&(-force)).unwrap_or_else(|| force / kb)
        } else {
            centre_step(kb, &best, force)
        };
        let mut length = 1.0;
        let before = force.norm();
        loop {
            let trial = u + step * length;
            let trial_force = (trial.iter().all(|x| x.is_finite())
                && solve_rigid(model, crank, work, trial).is_ok())
            .then(|| force_residual(model, kb, &work.sol));
            // Sufficient decrease of |f − kb·u|, for which the Newton direction is a descent
            // direction (a residual relative to Σ|F| + kb·|u| is not: its scale grows with u).
            if trial_force.is_some_and(|f| f.norm() < (1.0 - 1e-4 * length) * force.norm()) {
                (u, force) = (trial, trial_force.unwrap_or(force));
                best = work.sol.clone();
                if u.norm() > model.eccentricity_mm {
                    return Err(out_of_mesh(kb, u, force, model));
                }
                break;
            }
            length *= 0.5;
            if length < 1e-12 {
                // Newton cycles at a kink of R (a contact just closing at the answer, where the
                // stiffness in its direction jumps from ~kb to the contact's).
                work.sol = best.clone();
                return directional_roots(model, kb, crank, work, u, best);
            }
        }
        // A step shortened more than twice, or one that did not halve the residual: the
        // approximate Jacobian (contact normals and arms held fixed) misses the geometric
        // stiffness F·∂n/∂u, which matters when the bearing is as soft as F/ρ, and errs most
        // in the soft direction where the lags take up the motion; the next steps take the
        // reduced Jacobian by finite differences.
        exact_jacobian |= length < 0.25 || force.norm() > 0.5 * before;
    }
    // Out of steps short of the tolerance: Newton crawled (a Jacobian nearly singular along the
    // orbit's tangent, where the disc turning with the crank moves no contact, and the other
    // force row growing as the square of the step: the line search keeps 1/128 to 1/256 of each).
    work.sol = best.clone();
    match settled(best.clone(), force_merit(model, kb, &best)) {
        Ok(sol) => Ok(sol),
        Err(_) => directional_roots(model, kb, crank, work, u, best),
    }
}

/// Finish a compliant solve that Newton cannot (it cycles at a kink, or crawls and runs out of
/// steps). Where the contacts only resist, R is strongly monotone (the symmetric part of ∂R/∂u
/// is ≤ −kb: the bearing's own stiffness plus the contacts'), so along any unit direction e the
/// component e·R(u + s·e) decreases strictly in s, and its root is a monotone 1-D problem that
/// `monotone_root` brackets and solves whatever the kinks. Not everywhere: the contacts'
/// geometric stiffness can be negative along the orbit's tangent, and a preloaded disc on a
/// soft bearing has two equilibria at some angles (300 N/mm at 1 N·m at 41.5°: a sweep snaps
/// between them), where a root is the one the bracket closes on. Alternate such roots along the
/// principal directions of the reduced Jacobian (by differences), which are nearly decoupled
/// near the answer, until the force residual meets the tolerance.
fn directional_roots(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    mut u: Vec2,
    mut best: AngleSolution,
) -> Result<AngleSolution, SolveFailure> {
    let tol = compliant_tolerance(model);
    for _ in 0..MAX_DIRECTIONAL_ROUNDS {
        if force_merit(model, kb, &best) <= tol {
            return Ok(best);
        }
        let jacobian = jacobian_by_differences(model, kb, crank, work, u)?;
        let symmetric = (jacobian + jacobian.transpose()) * 0.5;
        let directions = symmetric.symmetric_eigen().eigenvectors;
        for e in directions.column_iter() {
            let e = Vec2::new(e[0], e[1]);
            let slope = -(e.dot(&(jacobian * e))).min(-kb);
            let scale = force_scale(kb, &best);
            let root = monotone_root(
                |s: f64| {
                    centre_residual(model, kb, crank, work, u + e * s).map(|r| Balance {
                        value: -e.dot(&r),
                        slope,
                        scale,
                        resolution: 0.0,
                    })
                },
                0.0,
                0.0,
                &Settings {
                    rel_tol: 0.1 * tol,
                    initial_step: 1e-6,
                    max_range: model.eccentricity_mm,
                    ..model.settings
                },
            )?;
            u += e * root.x;
            solve_rigid(model, crank, work, u)?;
            best = work.sol.clone();
            if u.norm() > model.eccentricity_mm {
                return Err(out_of_mesh(kb, u, force_residual(model, kb, &best), model));
            }
        }
    }
    work.sol = best.clone();
    let merit = force_merit(model, kb, &best);
    settled(best, merit)
}

/// Rounds of `directional_roots`.
const MAX_DIRECTIONAL_ROUNDS: usize = 20;

/// R(u) = f(u) − kb·u with the lags solved at the offset u.
fn centre_residual(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    u: Vec2,
) -> Result<Vec2, SolveFailure> {
    solve_rigid(model, crank, work, u)?;
    Ok(force_residual(model, kb, &work.sol))
}

/// The scale of the force residual: Σ|F| + kb·|u|.
fn force_scale(kb: f64, sol: &AngleSolution) -> f64 {
    sol.rollers.iter().map(|s| s.force_n).sum::<f64>()
        + sol.pins.iter().map(|s| s.force_n).sum::<f64>()
        + kb * sol.centre_offset_mm.norm()
}

/// The force residual f(u) − kb·u of a solution, N.
fn force_residual(model: &Model, kb: f64, sol: &AngleSolution) -> Vec2 {
    let (r, _) = compliant_residual(model, kb, sol);
    Vec2::new(r[0], r[1])
}

/// A bearing so soft under the load that the disc centre leaves the mesh: once it has moved by
/// more than the eccentricity (the scale of the whole mesh: the disc centre orbits the input
/// axis at e), the rollers no longer hold the disc in its tooth spaces.
fn out_of_mesh(kb: f64, u: Vec2, force: Vec2, model: &Model) -> SolveFailure {
    SolveFailure::OutOfMesh {
        bearing_n_per_mm: kb,
        torque_nmm: model.torque_nmm,
        offset_mm: u.norm(),
        unbalanced_n: force.norm(),
        eccentricity_mm: model.eccentricity_mm,
    }
}

/// The end of a compliant solve that ran out of steps: accepted within the documented 1e-9.
fn settled(sol: AngleSolution, merit: f64) -> Result<AngleSolution, SolveFailure> {
    if merit <= 1e-9 {
        Ok(sol)
    } else {
        Err(SolveFailure::NotConverged {
            x: sol.lag_rad.unwrap_or(0.0),
            residual: merit,
        })
    }
}

/// The force merit a compliant solve converges to: 10× the solver's relative tolerance
/// (1e-10), a decade inside the documented 1e-9 of the reported residual (Eqs. 12–14), whose
/// moment rows about the fixed origin weigh the same force misses by other lever arms.
fn compliant_tolerance(model: &Model) -> f64 {
    model.settings.rel_tol * 10.0
}

/// Newton steps of the centre a compliant solve may take.
const MAX_CENTRE_STEPS: usize = 100;

/// The largest relative residual of the compliant problem: the force rows relative to
/// Σ|F| + kb·|u|, the moment rows (held by the lags' own solves) relative to the torque.
fn force_merit(model: &Model, kb: f64, sol: &AngleSolution) -> f64 {
    let (r, s) = compliant_residual(model, kb, sol);
    r.component_div(&s).amax()
}

/// ∂R/∂u by central differences of R(u), the lags re-solved at each offset: exact to the
/// differences' error, geometric stiffness included. The step h is 1e-6 of the larger of |u|
/// and the gap resolution's scale (1e-3 mm): far above the round-off of R, far below the
/// distance over which the contact set changes. `work` is left at the last offset tried.
fn jacobian_by_differences(
    model: &Model,
    kb: f64,
    crank: f64,
    work: &mut Work,
    u: Vec2,
) -> Result<nalgebra::Matrix2<f64>, SolveFailure> {
    let residual = |work: &mut Work, x: Vec2| centre_residual(model, kb, crank, work, x);
    let h = 1e-6 * u.norm().max(1e-3);
    let mut jacobian = nalgebra::Matrix2::zeros();
    for axis in 0..2 {
        let mut d = Vec2::zeros();
        d[axis] = h;
        let column = (residual(work, u + d)? - residual(work, u - d)?) / (2.0 * h);
        jacobian.set_column(axis, &column);
    }
    Ok(jacobian)
}

/// The Newton step of the centre offset: −(∂R/∂u)⁻¹·R with the lags eliminated from the 4×4
/// Jacobian (Schur complement; a lag whose balance has no slope, no contact on its side, is not
/// eliminated).
fn centre_step(kb: f64, sol: &AngleSolution, force: Vec2) -> Vec2 {
    let j = compliant_jacobian(kb, sol);
    let mut reduced = j.fixed_view::<2, 2>(0, 0).into_owned();
    for l in 2..4 {
        let pivot = j[(l, l)];
        if pivot != 0.0 {
            let (column, row) = (j.fixed_view::<2, 1>(0, l), j.fixed_view::<1, 2>(l, 0));
            reduced -= column * row / pivot;
        }
    }
    reduced.lu().solve(&(-force)).unwrap_or_else(|| force / kb)
}

#[cfg(test)]
mod tests {
    use super::{compliant_jacobian, compliant_residual, evaluate_at, solve_rigid, Work};
    use super::{AngleSolution, Model};
    use crate::geometry::{unit, Vec2};
    use crate::model::{Effect, Plan};
    use nalgebra::Vector4;
    use proptest::prelude::*;

    /// The rigid equilibrium at `crank`, as `angle::solve_angle` solves it from nothing (the
    /// bearing's force and the residual left out: the test reads the lags and the states).
    fn rigid_solution(model: &Model, crank: f64) -> AngleSolution {
        let mut work = Work::exact_from(AngleSolution::default());
        work.e_phi = unit(crank);
        solve_rigid(model, crank, &mut work, Vec2::zeros()).unwrap();
        work.sol
    }

    proptest! {
        /// The analytic 4×4 Jacobian of the compliant problem (rows: force x, y, roller moment,
        /// pin moment; columns: ux, uy, β, βo) against central differences of the residual, at
        /// lightly loaded states of the paper's design on bearings of 1e3–1e9 N/mm.
        ///
        /// The Jacobian holds contact normals and arms fixed over a step; what it leaves out is
        /// the geometric stiffness, each force times the turn of its normal and arm, bounded by
        /// ΣF·(κ + 1/e)·(1 + R)² for a unit change (κ the largest locus curvature, 1/e that of
        /// a pin's direction, R = Rp + e the lever), times R more on a moment row and on a lag
        /// column. At 1e-3 N·m the forces are ~0.05 N, so that bound is ~1e-4 of the contact
        /// stiffness terms it sits beside: a wrong sign or a missing term (~k·l, ~k·l²) cannot
        /// hide in it. The differences step 1e-10 mm (1e-10/R rad), inside every contact's
        /// approach or opening (states with a gap within 1e-8 mm of closing are drawn again),
        /// so no contact opens or closes; their round-off, 1e-14 mm of gap times 7e5 N/mm over
        /// 2e-10 mm, is ~40 N/mm, inside the 1e-4 relative part.
        #[test]
        fn compliant_jacobian_matches_finite_differences(
            stiffness_exp in 3.0f64..9.0,
            crank in 0.0f64..std::f64::consts::TAU,
            offset in (-1.0f64..1.0, -1.0f64..1.0),
        ) {
            let s = crate::spec::load("specs/paper.yaml").unwrap();
            let mut scene = s.scenes.iter().find(|c| c.name == "rated").unwrap().clone();
            scene.output_torque_nmm = 1.0;
            let kb = 10f64.powf(stiffness_exp);
            let plan = Plan::of("rated", &[Effect::Bearing]);
            // The lags of the rigid equilibrium (independent of the compliant solver, which
            // uses the Jacobian under test), at a centre offset of a few nanometres.
            let rigid = Model::new(&s.design, &s.modification, &scene, &plan);
            let sol = rigid_solution(&rigid, crank);
            scene.bearing_stiffness_n_per_mm = Some(kb);
            let model = Model::new(&s.design, &s.modification, &scene, &plan);
            let (ux, uy) = (offset.0 * 1e-8, offset.1 * 1e-8);
            let x = Vector4::new(ux, uy, sol.lag_rad.unwrap(), sol.output_lag_rad.unwrap());
            let mut at = sol.clone();
            evaluate_at(&model, crank, &x, &mut at).unwrap();
            // A contact at its threshold within the differences' reach (a pin whose arm nearly
            // vanishes has a gap of ~1e-12 mm) makes the residual kinked there: the two sides
            // differ by its whole stiffness, and no derivative exists to compare.
            let gaps = at.rollers.iter().map(|r| r.gap_mm).chain(at.pins.iter().map(|p| p.gap_mm));
            prop_assume!(gaps.into_iter().all(|g| g.abs() > 1e-8));
            let analytic = compliant_jacobian(kb, &at);
            let d = &s.design;
            let lever = d.roller_circle_radius_mm + d.eccentricity_mm;
            let h = [1e-10, 1e-10, 1e-10 / lever, 1e-10 / lever];
            let residual = |x: Vector4<f64>| {
                let mut e = sol.clone();
                evaluate_at(&model, crank, &x, &mut e).unwrap();
                compliant_residual(&model, kb, &e).0
            };
            let forces: f64 = at.rollers.iter().map(|r| r.force_n).sum::<f64>()
                + at.pins.iter().map(|p| p.force_n).sum::<f64>();
            let profile = &model.rollers.as_ref().unwrap().mesh.profile;
            let kappa = (0..=200)
                .map(|k| profile.locus().curvature_at(-1.0 + 0.01 * k as f64).abs())
                .fold(0.0, f64::max);
            let geometric = forces * (kappa + 1.0 / d.eccentricity_mm) * (1.0 + lever).powi(2);
            let factor = [1.0, 1.0, 1.0 + lever, 1.0 + lever];
            for j in 0..4 {
                let mut step = Vector4::zeros();
                step[j] = h[j];
                let column = (residual(x + step) - residual(x - step)) / (2.0 * h[j]);
                for i in 0..4 {
                    let (a, b) = (analytic[(i, j)], column[i]);
                    let tol = 1e-4 * a.abs().max(b.abs()) + geometric * factor[i] * factor[j];
                    prop_assert!((a - b).abs() <= tol, "J[{i}][{j}]: analytic {a:e}, differences {b:e}, tol {tol:e}");
                }
            }
        }
    }
}
