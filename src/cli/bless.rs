//! `cycloid bless`: rewrite a spec's golden files from the current results and say what moved.

use super::output::print;
use super::Outcome;
use crate::engine::commands;
use crate::error::Result;
use crate::spec;
use std::io::Write;

pub(super) fn run(path: &str, out: &mut dyn Write) -> Result<Outcome> {
    let spec = spec::load(path)?;
    if spec.golden.is_empty() {
        print(
            out,
            &format!(
                "cycloid bless `{}`: the spec has no `golden` entries, nothing to bless\n",
                spec.name
            ),
        )?;
        return Ok(Outcome::Passed);
    }
    let blessed = commands::bless(&spec)?;
    print(out, &crate::report::golden::bless_report(&spec, &blessed))?;
    Ok(Outcome::Passed)
}
