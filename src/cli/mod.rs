//! Command-line interface: argument parsing (`args`), output paths and writing (`output`), and
//! one file per command that calls the library's entry ([`engine::commands`](crate::engine::commands)) and prints. `main`
//! only maps the outcome to an exit code (0 pass, 1 a check failed, 2 invalid input or
//! computation).

mod accuracy;
pub mod args;
mod bless;
mod check;
mod design;
mod fit;
mod optimise;
mod output;
mod profile;
mod shard;
mod tolerance;

pub use args::{
    AccuracyArgs, CheckArgs, Cli, Command, DesignArgs, DesignCommand, OptimiseArgs, ProfileArgs,
    ToleranceArgs, ToleranceCommand, DEFAULT_REPORT_MAP_STEPS,
};
pub use shard::parse_shard;

use crate::error::Result;
use std::io::Write;

/// How a command ended when it did not fail with an error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    Passed,
    ChecksFailed,
}

impl Outcome {
    /// `Passed` when every check `passed`, else `ChecksFailed`.
    pub fn of(passed: bool) -> Self {
        if passed {
            Outcome::Passed
        } else {
            Outcome::ChecksFailed
        }
    }
}

/// Run a parsed command, writing the user-facing text to `out` (without colour).
pub fn run(cli: Cli, out: &mut dyn Write) -> Result<Outcome> {
    run_with(cli, out, false)
}

/// Run a parsed command; `color` colours the verdicts of the checks table.
pub fn run_with(cli: Cli, out: &mut dyn Write, color: bool) -> Result<Outcome> {
    match cli.command {
        Command::Check(args) => check::run(&CheckArgs { color, ..args }, out),
        Command::Bless { spec } => bless::run(&spec, out),
        Command::Accuracy(args) => accuracy::run(&args, out),
        Command::Optimise(args) => optimise::run(&args, out),
        Command::Profile(args) => profile::run(&args, out),
        Command::Fit {
            spec,
            write,
            form_csv,
        } => fit::run(&spec, write.as_deref(), form_csv.as_deref(), out),
        Command::Tolerance(args) => tolerance::run(args, out),
        Command::Design(args) => design::run(args, out),
    }
}
