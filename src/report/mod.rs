//! Outputs: the terminal table and the results JSON.

pub mod json;
pub mod optimisation;
pub mod table;
