//! Every subcommand's `--help` describes the command and each of its arguments, and the
//! top-level help states the exit codes.

use clap::CommandFactory;
use cycloid::cli::Cli;

#[test]
fn every_argument_of_every_subcommand_is_described() {
    let cli = Cli::command();
    let mut undocumented = Vec::new();
    for sub in cli.get_subcommands() {
        if sub.get_about().is_none() {
            undocumented.push(sub.get_name().to_string());
        }
        for arg in sub.get_arguments() {
            if arg.get_help().is_none() && arg.get_id() != "help" {
                undocumented.push(format!("{} {}", sub.get_name(), arg.get_id()));
            }
        }
    }
    assert!(undocumented.is_empty(), "no help text: {undocumented:?}");
    let help = Cli::command().render_long_help().to_string();
    assert!(help.contains("Exit codes: 0"), "{help}");
}
