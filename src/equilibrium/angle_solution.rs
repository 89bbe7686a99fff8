//! The equilibrium at one crank angle (`AngleSolution`): plain data that the solvers fill and
//! the friction model's balances read. `loaded` re-exports it with the model it solves.

use super::pins::PinState;
use super::rollers::RollerState;
use crate::geometry::Vec2;

/// The equilibrium at one crank angle. Fixed frame; lags in rad (positive opposes the motion).
/// From `solve_angle` every roller state is exact; inside a sweep a roller proven out of reach
/// has zero force, a lower bound as its gap and the geometry of its last exact evaluation.
#[derive(Debug, Clone, Default)]
pub struct AngleSolution {
    /// β, when the rollers are modelled.
    pub lag_rad: Option<f64>,
    pub rollers: Vec<RollerState>,
    /// βo, when the pins are modelled.
    pub output_lag_rad: Option<f64>,
    pub pins: Vec<PinState>,
    /// Disc-centre displacement from e·(cos φ, sin φ) (compliant bearing), mm.
    pub centre_offset_mm: Vec2,
    /// Crank-bearing force on the disc, N, when `bearing` is modelled.
    pub bearing_force_n: Option<Vec2>,
    /// Largest relative residual of the force and moment balance (paper Eqs. 12–14).
    pub residual: Option<f64>,
}
