//! `cycloid`: design checks for cycloidal speed reducers.
//!
//! # The library's API
//!
//! What is stable for library users: one entry per command, each returning data —
//! [`check`] ([`CheckOptions`] → [`CheckRun`]), [`optimise`], [`accuracy`], [`tolerance`]
//! (with [`tolerance_shard`] and [`merge_shards`]), [`fit`], [`profile`], [`bless`]; the spec
//! ([`spec::load`], [`spec::parse`] → [`spec::Spec`]); the data model and the results of a
//! scene ([`model`], [`model::results::SceneResult`]); the error ([`Error`]: a kind and a
//! location); and the progress observer ([`progress::Progress`]).
//!
//! ```
//! let spec = cycloid::spec::load("specs/reducer.yaml")?;
//! let run = cycloid::check(&spec, &cycloid::CheckOptions::default(), &cycloid::progress::Silent)?;
//! assert!(run.passed());
//! # Ok::<(), cycloid::Error>(())
//! ```
//!
//! The other modules are public for this package's own binary, tests, benchmarks and examples,
//! are hidden from the documentation, and may change at any time.
//!
//! # Layers
//!
//! Each imports only the ones before it (`tests/architecture.rs` keeps it so):
//! - `error`, `units`, `numeric`, `progress`, `files`: errors, unit conversions, numeric
//!   helpers, the progress observer, safe I/O;
//! - `model`: the data model (design, scenes and plans, limits, studies, results) and the one
//!   registry of quantities;
//! - `spec`: YAML → raw → validated model, with located errors and the design rules;
//! - `geometry` → `contact` → `equilibrium`: the physics (`measure`, the identification of a
//!   measured disc, sits on `geometry`);
//! - `engine`: runs scenes, checks limits and goldens, optimises, runs the accuracy ladder, and
//!   [`engine::commands`], the entry of each command;
//! - `report`: every text for people, built from the engine's data: the terminal table, JSON,
//!   JUnit, the design review ([`report::review`]), the profile export, `--explain`;
//! - `cli`: the commands' arguments and printing.
//!
//! Units inside the engine: mm, N, N·mm, rad, MPa; every conversion is a `units` function,
//! called at the edges. Conventions are those of `docs/MODEL.md`, restated on the types.

pub mod error;
#[doc(hidden)]
pub mod files;
#[doc(hidden)]
pub mod numeric;
pub mod progress;
#[doc(hidden)]
pub mod units;

pub mod model;

pub mod spec;

#[doc(hidden)]
pub mod contact;
#[doc(hidden)]
pub mod equilibrium;
#[doc(hidden)]
pub mod geometry;
#[doc(hidden)]
pub mod measure;

#[doc(hidden)]
pub mod engine;

#[doc(hidden)]
pub mod report;

#[doc(hidden)]
pub mod cli;

pub use engine::commands::{
    accuracy, bless, check, fit, merge_shards, optimise, profile, tolerance, tolerance_shard,
    AsBuilt, CheckOptions, CheckRun, Merged, OptimiseRun, Review, ReviewOptions, ToleranceRun,
};
pub use error::{Error, ErrorKind, Result};
