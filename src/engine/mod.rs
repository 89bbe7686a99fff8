//! The engine: runs the scenes of a spec (`scene`), checks its limits (`check`) and golden
//! curves (`golden`), optimises the modification (`optimise`) and runs the accuracy ladder
//! (`accuracy`).

pub mod accuracy;
pub mod check;
pub mod golden;
pub mod optimise;
pub mod scene;
