//! `cycloid optimise`: run the spec's studies, print each, and write the optimum's spec and
//! the objective map asked for.

use super::output::{distinct_outputs, inputs_of, print, write_file, write_spec};
use super::{OptimiseArgs, Outcome};
use crate::engine::commands::{self, MAX_MAP_STEPS};
use crate::engine::optimise::StudyResult;
use crate::error::{Error, Result};
use crate::model::Study;
use crate::report::terminal::Terminal;
use crate::{report, spec};
use std::io::Write;

pub(super) fn run(args: &OptimiseArgs, out: &mut dyn Write) -> Result<Outcome> {
    let path = args.spec.as_str();
    let spec = spec::load(path)?;
    let (write, map) = (args.write.as_deref(), args.map.as_deref());
    let outputs = [("--write", write), ("--map", map)];
    distinct_outputs(&inputs_of(path, Some(&spec)), &outputs)?;
    if args.map.is_some() && !commands::map_steps_allowed(args.map_steps) {
        return Err(Error::invalid_value(format!(
            "--map-steps must be 2 to {MAX_MAP_STEPS}, got {}",
            args.map_steps
        )));
    }
    let map_steps = map.map(|_| args.map_steps);
    let run = commands::optimise(&spec, args.study.as_deref(), map_steps, &Terminal)?;
    for (k, (study, r)) in run.studies.iter().enumerate() {
        print(out, &report::optimisation::render(&spec, study, r))?;
        if k > 0 {
            continue;
        }
        if let Some(p) = write {
            print(out, &write_optimum(&spec, path, study, r, p)?)?;
        }
        if let (Some(p), Some(cells)) = (map, &run.map) {
            write_file(p, report::optimisation::map_csv(study, cells))?;
            print(
                out,
                &format!("wrote the objective map of `{}` to {p}\n", r.name),
            )?;
        }
    }
    Ok(Outcome::of(run.feasible()))
}

/// `optimise --write OUT`: the spec of a study's optimum, written only when it is feasible;
/// returns what to tell the user.
fn write_optimum(
    spec: &spec::Spec,
    path: &str,
    study: &Study,
    r: &StudyResult,
    out_path: &str,
) -> Result<String> {
    if !r.optimum.feasible() {
        return Ok(format!(
            "no feasible optimum of `{}` was found: nothing written to {out_path}\n",
            r.name
        ));
    }
    let name = format!("{}-{}-optimum", spec.name, r.name);
    let mut header = format!(
        "# Written by `cycloid optimise {path} --study {}`: the optimum of that study, {} = {};\n\
         # {}.\n",
        r.name,
        study
            .objective
            .iter()
            .map(|(o, _)| o.name)
            .collect::<Vec<_>>()
            .join(" + "),
        crate::numeric::number(r.optimum.objective),
        report::optimisation::found(r.found),
    );
    if let Some(v) = report::optimisation::verification_text(study, r) {
        header += &format!("# {}.\n", v.replace('\n', " "));
    }
    let text = spec::edit::optimum_spec(
        out_path,
        &spec.source,
        &r.optimum.point.modification,
        study
            .variables
            .iter()
            .any(|v| v.kind.of_crown())
            .then_some(&r.optimum.point.crowning),
        &name,
        &header,
    )?;
    write_spec(path, out_path, &text)?;
    Ok(format!(
        "wrote {out_path} (`{name}`) with the optimum of `{}`\n",
        r.name
    ))
}
