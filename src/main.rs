//! `cycloid` binary: parse arguments, run, map the outcome to an exit code.

use clap::Parser;
use cycloid::cli::{self, Cli, Outcome};
use cycloid::ErrorKind;
use std::io::{IsTerminal, Write};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args = match Cli::try_parse() {
        Ok(args) => args,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    let stdout = std::io::stdout();
    let color = cycloid::report::table::use_color(stdout.is_terminal());
    match cli::run_with(args, &mut stdout.lock(), color) {
        Ok(Outcome::Passed) => ExitCode::SUCCESS,
        Ok(Outcome::ChecksFailed) => ExitCode::from(1),
        // A reader that closed standard output (`| head`) has what it wanted: quietly done.
        Err(e) if e.kind == ErrorKind::OutputClosed => ExitCode::SUCCESS,
        Err(e) => {
            // Not eprintln!, which panics when stderr is closed too.
            let _ = writeln!(std::io::stderr(), "{e}");
            ExitCode::from(2)
        }
    }
}
