//! `cycloid`: design checks for cycloidal speed reducers.
//!
//! Layers, each importing only the ones before it (`tests/architecture.rs` keeps it so):
//! - `error`, `units`, `numeric`, `progress`, `files`: errors, unit conversions, numeric
//!   helpers, the progress observer, safe I/O;
//! - `model`: the data model (design, scenes and plans, limits, studies, results) and the one
//!   registry of quantities;
//! - `spec`: YAML → raw → validated model, with located errors and the design rules;
//! - `geometry` → `contact` → `equilibrium`: the physics (`measure`, the identification of a
//!   measured disc, sits on `geometry`);
//! - `engine`: runs scenes, checks limits and goldens, optimises, runs the accuracy ladder;
//! - `report`: every text for people, built from the engine's data: the terminal table, JSON,
//!   JUnit, the design review (`report::review`), the profile export, `--explain`;
//! - `cli`: the commands.
//!
//! Units inside the engine: mm, N, N·mm, rad, MPa; every conversion is a `units` function,
//! called at the edges. Conventions are those of `shared/MODEL.md`, restated on the types.

pub mod error;
pub mod files;
pub mod numeric;
pub mod progress;
pub mod units;

pub mod model;

pub mod spec;

pub mod contact;
pub mod equilibrium;
pub mod geometry;
pub mod measure;

pub mod engine;

pub mod report;

pub mod cli;

pub use error::{Error, ErrorKind, Result};
