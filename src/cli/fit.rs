//! `cycloid fit`: identify the measured disc, print it, and write what was asked.

use super::output::{distinct_outputs, inputs_of, print, write_file, write_spec};
use super::Outcome;
use crate::engine::{as_built, commands};
use crate::error::Result;
use crate::{report, spec};
use std::io::Write;

pub(super) fn run(
    path: &str,
    write: Option<&str>,
    form_csv: Option<&str>,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let spec = spec::load(path)?;
    let outputs = [("--write", write), ("--form-csv", form_csv)];
    distinct_outputs(&inputs_of(path, Some(&spec)), &outputs)?;
    let id = commands::fit(&spec)?;
    print(out, &report::fit::render(&spec, &id))?;
    if let Some(p) = form_csv {
        write_file(p, report::fit::form_csv(&spec, &id))?;
    }
    if let Some(p) = write {
        let text = spec::edit::with_modification(p, &spec.source, &id.modification)?;
        let mut deviations = spec.design.deviations.clone();
        deviations.form = as_built::form_terms(&id);
        let (text, what) = if deviations.form.is_empty() {
            (text, "the identified modification")
        } else {
            (
                spec::edit::with_deviations(&text, path, &deviations, p)?,
                "the identified modification and form error (reducer.deviations.form)",
            )
        };
        write_spec(path, p, &text)?;
        print(out, &format!("wrote {p} with {what}\n"))?;
    }
    Ok(Outcome::Passed)
}
