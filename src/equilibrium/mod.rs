//! Quasi-static equilibrium of the disc (paper §3.2, MODEL.md "Equilibrium").
//!
//! Forces on the disc: rollers push along the inward contact normals, output pins push the
//! hole walls, the crank bearing holds the disc centre. Moments are about the disc centre;
//! the pins transmit the output torque T, the rollers balance it.

pub mod angle;
pub mod balance;
pub mod discs;
pub mod first_order_sweep;
pub mod pins;
pub mod rollers;
pub mod solve;
pub mod sweep;
