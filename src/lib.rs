//! `cycloid`: design checks for cycloidal speed reducers.
//!
//! Data flow: spec → geometry → contact → equilibrium → (optimise) → check → report.
//! Units inside the engine: mm, N, N·mm, rad, MPa. Conversions happen only in `spec` (input)
//! and `report` (output). Conventions are those of `shared/MODEL.md`, restated on the types.

pub mod accuracy;
pub mod check;
pub mod cli;
pub mod contact;
pub mod equilibrium;
pub mod error;
pub mod export;
pub mod geometry;
pub mod golden;
pub mod optimise;
pub mod quantity;
pub mod report;
pub mod scene;
pub mod spec;

pub use error::{Error, ErrorKind, Result};
