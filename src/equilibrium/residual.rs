//! How far a solution is from equilibrium: the relative residual of the paper's Eqs. 12–14,
//! evaluated independently of how the solution was found.

use super::loaded::{AngleSolution, Model};
use super::solve::rel;
use crate::geometry::{cross, unit, Vec2};

/// Relative residual of the paper's Eqs. 12–14, evaluated independently of how the solution
/// was found: force balance (Eqs. 12–13), moment balance about the fixed origin with every
/// force at its contact point and the bearing force at the disc centre, and the pin/roller
/// moment equality about the disc centre (Eq. 14).
pub fn residual(model: &Model, crank: f64, sol: &AngleSolution, bearing: Vec2) -> f64 {
    residual_at(model, unit(crank), sol, bearing)
}

/// `residual` with the eccentric direction e_φ = (cos φ, sin φ) given, in one pass over the
/// forces in contact.
pub(super) fn residual_at(model: &Model, e_phi: Vec2, sol: &AngleSolution, bearing: Vec2) -> f64 {
    let mut sums = BalanceSums::default();
    for r in sol.rollers.iter().filter(|r| r.force_n != 0.0) {
        sums.roller(r.point, r.force_n, r.force_vector(), r.force_n * r.arm_mm);
    }
    for p in sol.pins.iter().filter(|p| p.force_n != 0.0) {
        sums.pin(p.point, p.force_n, p.force_vector(), p.force_n * p.arm_mm);
    }
    sums.relative(
        model,
        e_phi * model.eccentricity_mm + sol.centre_offset_mm,
        bearing,
    )
}

/// Sums of the forces on the disc for the residual of Eqs. 12–14: Σf, Σ|f|, Σ p×f and Σ|p×f|
/// about the origin, and the moments Σ F·l (rollers) and Σ F·a (pins) about the disc centre
/// with their scales.
#[derive(Debug, Default)]
pub(super) struct BalanceSums {
    force: Vec2,
    force_scale: f64,
    moment: f64,
    moment_scale: f64,
    rollers: (f64, f64),
    pins: (f64, f64),
}

impl BalanceSums {
    /// A force f of magnitude |`magnitude`| at p (the forces are a magnitude times a unit
    /// direction, so |f| is known without a square root).
    fn add(&mut self, p: Vec2, magnitude: f64, f: Vec2) {
        let m = cross(p, f);
        self.force += f;
        self.force_scale += magnitude.abs();
        self.moment += m;
        self.moment_scale += m.abs();
    }

    /// A roller force f = F·(unit direction) at p, with moment F·l about the disc centre.
    pub(super) fn roller(&mut self, p: Vec2, force_n: f64, f: Vec2, moment: f64) {
        self.add(p, force_n, f);
        self.rollers.0 += moment;
        self.rollers.1 += moment.abs();
    }

    /// A pin force f = F·(unit direction) at p, with moment F·a about the disc centre.
    pub(super) fn pin(&mut self, p: Vec2, force_n: f64, f: Vec2, moment: f64) {
        self.add(p, force_n, f);
        self.pins.0 += moment;
        self.pins.1 += moment.abs();
    }

    /// Σf of the forces added so far.
    pub(super) fn net_force(&self) -> Vec2 {
        self.force
    }

    /// With the bearing force at the disc centre: the largest relative residual.
    pub(super) fn relative(mut self, model: &Model, centre: Vec2, bearing: Vec2) -> f64 {
        if bearing != Vec2::zeros() {
            self.add(centre, bearing.norm(), bearing);
        }
        let ((mr, sr), (mp, sp)) = (self.rollers, self.pins);
        rel(self.force.norm(), self.force_scale)
            .max(rel(self.moment, self.moment_scale))
            .max(rel(mp - mr, sr.max(sp).max(model.torque_nmm.abs())))
    }
}
