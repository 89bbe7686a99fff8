//! `cycloid check`: run the library's `check`, print the checks table and the headline
//! results, and write the JSON, JUnit and design review asked for.

use super::output::{distinct_outputs, inputs_of, print, print_keeping};
use super::output::{write_file, write_review};
use super::{CheckArgs, Outcome};
use crate::engine::commands::{self, CheckOptions, CheckRun, ReviewOptions};
use crate::engine::scene::{self, Writes};
use crate::error::{ErrorKind, Result};
use crate::report::terminal::Terminal;
use crate::{report, spec};
use std::io::Write;
use std::path::Path;

/// `cycloid check`; a run that stops on an error still writes it as a JUnit error case.
pub(super) fn run(args: &CheckArgs, out: &mut dyn Write) -> Result<Outcome> {
    distinct_outputs(&inputs_of(&args.spec, None), &args.paths())?;
    let mut guarded = false;
    let result = checked(args, out, &mut guarded);
    let (Err(e), Some(path)) = (result.as_ref(), args.junit.as_deref()) else {
        return result;
    };
    if matches!(e.kind, ErrorKind::Usage | ErrorKind::OutputClosed) {
        return result;
    }
    // CI shows the error as a test case too; the error itself still goes to stderr. A spec
    // that did not load names files nobody knows (its goldens, its measured points): then the
    // case replaces only a JUnit report of ours or nothing.
    if guarded || ours_or_absent(path) {
        let doc = report::junit::error_document(&args.spec, &e.to_string());
        let _ = write_file(path, &doc);
        return result;
    }
    let mut e = result.unwrap_err();
    e.message += &format!(
        "\n(--junit {path}: not written: the spec did not load, so the files it names are \
         unknown, and {path} is not a JUnit report of cycloid)"
    );
    Err(e)
}

/// Whether `path` holds nothing yet, or a JUnit report `cycloid` wrote (its first bytes).
fn ours_or_absent(path: &str) -> bool {
    use std::io::Read;
    let Ok(mut file) = std::fs::File::open(path) else {
        return !std::path::Path::new(path).exists();
    };
    let mut head = [0u8; 160];
    let n = file.read(&mut head).unwrap_or(0);
    let head = String::from_utf8_lossy(&head[..n]);
    head.starts_with("<?xml") && head.contains("<testsuites name=\"cycloid\"")
}

/// `check` itself; `guarded` is set once every file the spec names is known and no output
/// replaces one of them.
fn checked(args: &CheckArgs, out: &mut dyn Write, guarded: &mut bool) -> Result<Outcome> {
    let spec = spec::load(&args.spec)?;
    distinct_outputs(&inputs_of(&args.spec, Some(&spec)), &args.paths())?;
    *guarded = true;
    let writes = Writes {
        json: args.json.is_some(),
        report: args.report.is_some(),
    };
    if args.explain {
        print(
            out,
            &report::explain::explain(&spec, writes, args.tolerance),
        )?;
        return Ok(Outcome::Passed);
    }
    let options = CheckOptions {
        writes,
        tolerance: args.tolerance,
        review: review_options(args)?,
    };
    let run = commands::check(&spec, &options, &Terminal)?;
    print_run(&run, args, out)?;
    write_outputs(&run, args, out)?;
    print(out, &report::table::verdict_line(&run.checks))?;
    Ok(Outcome::of(run.passed()))
}

/// The review's options from `--report-crank-deg` and `--report-map-steps` (the angle checked
/// even without `--report`, the maps only with it).
fn review_options(args: &CheckArgs) -> Result<Option<ReviewOptions>> {
    let steps = if args.report.is_some() {
        args.report_map_steps
    } else {
        0
    };
    let review = ReviewOptions::new(args.report_crank_deg, steps)?;
    Ok(args.report.as_ref().map(|_| review))
}

/// The terminal's account of a run: the disc as built, the studies, the checks table, the
/// resolution warning, the headline results and the notes.
fn print_run(run: &CheckRun, args: &CheckArgs, out: &mut dyn Write) -> Result<()> {
    let spec = &run.spec;
    print(out, &format!("cycloid check `{}`\n", spec.name))?;
    if let Some(a) = &run.as_built {
        print(
            out,
            &format!("{}\n", report::as_built::describe(spec, &a.identification)),
        )?;
    }
    for (s, r) in spec.studies.iter().zip(&run.studies) {
        print(out, &report::optimisation::render(spec, s, r))?;
    }
    let styles: &[&str] = match args.color {
        true => &report::table::STYLES,
        false => &[],
    };
    print_keeping(
        out,
        &report::table::render_styled(&run.checks, args.color),
        styles,
    )?;
    if let Some(w) = run
        .resolution
        .as_ref()
        .and_then(report::accuracy::resolution_warning)
    {
        print(out, &format!("warning: {w}\n"))?;
    }
    print(out, &report::table::render_summary(&run.summaries))?;
    print(
        out,
        &report::mass_properties::headlines(spec, &run.mass, &run.unbalance),
    )?;
    for note in scene::notes(spec) {
        print(out, &format!("note: {}\n", report::explain::note(&note)))?;
    }
    Ok(())
}

/// The JSON, JUnit and design review asked for.
fn write_outputs(run: &CheckRun, args: &CheckArgs, out: &mut dyn Write) -> Result<()> {
    let spec = &run.spec;
    if let Some(p) = &args.json {
        let doc = report::json::Document::new(&report::json::Contents::of(run));
        crate::files::write_atomic_with(Path::new(p), |out| doc.write_to(out))?;
    }
    if let Some(p) = &args.junit {
        write_file(
            p,
            report::junit::document(&spec.name, &spec.path, &run.checks),
        )?;
    }
    let Some(review) = &run.review else {
        return Ok(());
    };
    if let Some((l, seconds)) = &review.ladder {
        print(out, &report::accuracy::ladder_line(l, *seconds))?;
    }
    if let Some(dir) = &args.report {
        write_review(out, dir, &report::check_review::render(run, review))?;
    }
    Ok(())
}
