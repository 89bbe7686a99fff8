//! The integration tests, one binary (`cargo test --release --test it`): one module per
//! subject, the helpers in `common`. One binary links the library once instead of once per
//! file. Run one subject with `cargo test --release --test it snapshots::`.
//!
//! The tests share one process: a test writes only under its own `common::Scratch` (unique
//! per call), never to a fixed path, and sets no environment variable or working directory of
//! the process (a child's environment goes through `common::cycloid_with`).
//!
//! Proptest's regressions of a module here are in `tests/proptest-regressions/MODULE.txt`
//! (proptest's `SourceParallel` default: beside the directory of this `main.rs`).
//! `tests/architecture.rs` stays its own binary.

mod common;

mod accuracy;
mod as_built_review;
mod bearing_life;
mod clearance_sweep;
mod cli;
mod cli_help;
mod contact;
mod design_missed;
mod design_search;
mod design_shard;
mod deviations;
mod disc_solid;
mod discs;
mod duty_cycle;
mod equilibrium;
mod export;
mod face_width;
mod fault_injection;
mod first_order_sweep;
mod first_order_validity;
mod flanks;
mod friction;
mod friction_coupled;
mod friction_torsion;
mod fuzz_corpus;
mod geometry;
mod golden;
mod golden_physics;
mod hard_cases;
mod inertia;
mod junit;
mod mass_properties;
mod measure;
mod measure_cli;
mod measured_inputs;
mod mesh_minimum;
mod no_load_table;
mod optimise;
mod ordinary_inputs;
mod period;
mod physical_bounds;
mod pin_beam;
mod printed_figures;
mod progress;
mod readme;
mod reliability;
mod report;
mod result_shape;
mod results_json;
mod review_plots;
mod reviewer_texts;
mod same_outputs;
mod slurm_cluster;
mod snapshots;
mod spec_locate;
mod specs_exit_codes;
mod strength;
mod tolerance;
mod torsion;
