//! Quasi-static equilibrium of the disc (paper §3.2, MODEL.md "Equilibrium").
//!
//! Forces on the disc: rollers push along the inward contact normals, output pins push the
//! hole walls, the crank bearing holds the disc centre. Moments are about the disc centre;
//! the pins transmit the output torque T, the rollers balance it.

pub mod angle;
mod angle_solution;
pub mod balance;
mod compliant_bearing;
pub mod coupling;
pub mod discs;
pub mod discs_sweep;
pub mod first_order_sweep;
pub mod friction;
pub mod loaded;
pub mod losses;
pub mod pin_beam;
pub mod pin_stress;
pub mod pins;
pub mod residual;
mod rigid_bearing;
pub mod rollers;
pub mod solve;
pub mod sweep;
pub mod torsion;
pub mod work;
