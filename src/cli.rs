//! Command-line interface: argument parsing and the commands. `main` only maps the outcome to
//! an exit code (0 pass, 1 a check failed, 2 invalid input or computation).

use crate::engine::{
    accuracy, as_built, check, drawing, golden, optimise, resolution, scene, summary,
};
use crate::error::{Error, ErrorKind, Result};
use crate::geometry::profile::Profile;
use crate::report::export;
use crate::{files, numeric};
use crate::{report, spec};
use clap::{Parser, Subcommand};
use std::io::Write;
use std::path::{Path, PathBuf};

mod tolerance;

#[derive(Debug, Parser)]
#[command(
    name = "cycloid",
    version,
    about = "Design checks for cycloidal speed reducers",
    after_help = "Exit codes: 0 every check passed, 1 a check failed, 2 invalid input or a \
                  computation that could not be done (the message says where and why)."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Run every scene of a spec and check its limits.
    Check {
        /// The YAML spec.
        spec: String,
        /// Write the results as JSON to this path.
        #[arg(long)]
        json: Option<String>,
        /// Print what will be computed and why, then stop.
        #[arg(long)]
        explain: bool,
        /// Write a JUnit XML report (one test case per check and golden curve) to this path.
        #[arg(long)]
        junit: Option<String>,
        /// Write a design-review report (index.html and SVG plots) into this directory.
        #[arg(long)]
        report: Option<String>,
        /// Crank angle of the disc drawing in the report, degrees [default: where the smallest
        /// gap occurs].
        #[arg(long, allow_negative_numbers = true)]
        report_crank_deg: Option<f64>,
        /// Grid points per variable of each study's objective map in the report (0: no map;
        /// the map costs steps² evaluations per study).
        #[arg(long, default_value_t = DEFAULT_REPORT_MAP_STEPS)]
        report_map_steps: usize,
        /// Also run the Monte Carlo of the spec's `tolerances:` (as `cycloid tolerance`); its
        /// failure rate against `max_failure_rate` joins the checks.
        #[arg(long)]
        tolerance: bool,
    },
    /// Optimise the tooth-profile modification as the spec's `optimise` section says.
    Optimise {
        /// The YAML spec; its `optimise` section (one study or a list) says what to optimise.
        spec: String,
        /// Run only this study (default: all).
        #[arg(long)]
        study: Option<String>,
        /// Write the spec with the optimum of the study (the first, or --study) filled in.
        #[arg(long)]
        write: Option<String>,
        /// Write the objective over a grid of the first two variables as CSV.
        #[arg(long)]
        map: Option<String>,
        /// Grid points per variable for --map.
        #[arg(long, default_value_t = 21)]
        map_steps: usize,
    },
    /// Run a scene on a ladder of settings (crank steps per mesh period, geometry, contact law,
    /// solver tolerance) and print each rung's error against the finest rung and its time.
    Accuracy {
        /// The YAML spec.
        spec: String,
        /// The scene to run [default: the spec's `accuracy.scene`, else the first scene with
        /// roller contact, else the first scene].
        #[arg(long)]
        scene: Option<String>,
        /// Crank steps per mesh period of the finest rung, the reference: 12·2^k, at least 24
        /// [default: the spec's `accuracy.finest_steps_per_period`, else 3072].
        #[arg(long, allow_negative_numbers = true)]
        finest: Option<i64>,
        /// Crank steps per mesh period of the rungs that change one setting [default: the
        /// cheapest steps rung that meets every tolerance, else the finest].
        #[arg(long, allow_negative_numbers = true)]
        settings_steps: Option<i64>,
        /// Tolerance on the TE curve and the TE fluctuation, arcsec [default: 0.1].
        #[arg(long, allow_negative_numbers = true)]
        te_tol_arcsec: Option<f64>,
        /// Tolerance on the max roller and bearing forces, N [default: 0.5].
        #[arg(long, allow_negative_numbers = true)]
        force_tol_n: Option<f64>,
        /// Tolerance on the ratio fluctuation κmax − κmin [default: 1e-4].
        #[arg(long, allow_negative_numbers = true)]
        ratio_tol: Option<f64>,
        /// Tolerance on the min clearance, µm [default: 0.1].
        #[arg(long, allow_negative_numbers = true)]
        clearance_tol_um: Option<f64>,
    },
    /// Rewrite the golden files of a spec from the current results, on purpose, and print
    /// what moved. CI never blesses.
    Bless {
        /// The YAML spec whose `golden` files are rewritten.
        spec: String,
    },
    /// Identify the disc of the spec's `measured_profile` points: centre, orientation, the
    /// fitted modifications and the form error, with uncertainties.
    Fit {
        /// The YAML spec with the `measured_profile` section whose points are identified.
        spec: String,
        /// Write the spec with the identified modification filled in.
        #[arg(long)]
        write: Option<String>,
        /// Write the form-error curve (t_deg, w_um) as CSV.
        #[arg(long)]
        form_csv: Option<String>,
    },
    /// Monte Carlo of the spec's `tolerances:`: draw as-built reducers, run the study's scene
    /// on each, and report the distribution of every limited quantity and the failure rate;
    /// `tolerance merge SHARD...` joins the shards of a split run.
    Tolerance(ToleranceArgs),
    /// Export the modified disc profile as CSV points and a DXF polyline.
    Profile {
        /// The YAML spec whose design and modification give the profile.
        spec: String,
        /// Write the profile points as CSV (x_mm, y_mm) to this path (optional).
        #[arg(long)]
        csv: Option<String>,
        /// Write the profile as a closed DXF polyline to this path (optional).
        #[arg(long)]
        dxf: Option<String>,
        /// Largest chordal error of the exported polyline, µm (at least 0.001).
        #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
        tolerance_um: f64,
    },
}

/// `cycloid tolerance SPEC [options]`, or `cycloid tolerance merge SHARD...`.
#[derive(Debug, clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct ToleranceArgs {
    #[command(subcommand)]
    pub merge: Option<ToleranceCommand>,
    /// The YAML spec with a `tolerances:` section.
    #[arg(required = true)]
    pub spec: Option<String>,
    /// Samples of the study [default: the spec's `tolerances.samples`].
    #[arg(long)]
    pub samples: Option<usize>,
    /// Write the study as JSON to this path.
    #[arg(long)]
    pub json: Option<String>,
    /// Write one CSV row per sample (its deviations and limited quantities) to this path.
    #[arg(long)]
    pub samples_csv: Option<String>,
    /// Compute only shard I of N (0-based: samples k with k mod N = I) and write it to --out;
    /// without it, Slurm's SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT are honoured.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// The shard file a sharded run writes.
    #[arg(long)]
    pub out: Option<String>,
    /// Also compute the derivative of every limited quantity by every toleranced deviation,
    /// the linear stack-up and the Pareto of the tolerances.
    #[arg(long)]
    pub sensitivity: bool,
    /// Write the spec with sample K's deviations as `reducer.deviations` to OUT (for `cycloid
    /// check` to replay), and run nothing else.
    #[arg(long, num_args = 2, value_names = ["K", "OUT"])]
    pub write_sample: Option<Vec<String>>,
    /// Write a design review of the study (index.html and SVG plots) into this directory.
    #[arg(long)]
    pub report: Option<String>,
}

/// Subcommands of `cycloid tolerance`.
#[derive(Debug, Subcommand)]
pub enum ToleranceCommand {
    /// Join the shard files of one run into the study's report (the same, bit for bit, as the
    /// unsharded run's).
    Merge {
        /// Every shard file of the run, in any order.
        #[arg(required = true)]
        shards: Vec<String>,
        /// Write the study as JSON to this path.
        #[arg(long)]
        json: Option<String>,
        /// Write one CSV row per sample to this path.
        #[arg(long)]
        samples_csv: Option<String>,
        /// Write a design review of the study into this directory.
        #[arg(long)]
        report: Option<String>,
    },
}

/// How a command ended when it did not fail with an error.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    Passed,
    ChecksFailed,
}

/// Write an output file atomically (a temporary file renamed into place).
fn write_file(path: &str, text: &str) -> Result<()> {
    files::write_atomic(Path::new(path), text.as_bytes())
}

/// Refuse, before anything is written, outputs that would destroy an input or one another: an
/// empty path, an output at the path of one of `inputs` (what it is, its path), or two
/// outputs at one path. `outputs` are (option, path if given); a `--report` directory also
/// claims its `index.html`.
fn distinct_outputs(inputs: &[(String, PathBuf)], outputs: &[(&str, Option<&str>)]) -> Result<()> {
    let usage = |m: String| Error::new(ErrorKind::Usage, format!("{m}; nothing was written"));
    let mut claimed: Vec<(String, PathBuf)> = inputs
        .iter()
        .map(|(what, p)| (what.clone(), files::identity(p)))
        .collect();
    for &(flag, path) in outputs {
        let Some(path) = path else { continue };
        if path.is_empty() {
            return Err(usage(format!("{flag} \"\": an empty path names no file")));
        }
        let mut ids = vec![files::identity(Path::new(path))];
        if flag == "--report" {
            ids.push(ids[0].join("index.html"));
        }
        for id in ids {
            if let Some((what, _)) = claimed.iter().find(|(_, c)| *c == id) {
                return Err(usage(format!(
                    "{flag} {path} would overwrite {what}; give another path"
                )));
            }
            claimed.push((format!("the output of {flag}"), id));
        }
    }
    Ok(())
}

/// The files a spec's run reads or owns, which no output may replace: the spec, and each
/// golden file with its metadata.
fn inputs_of(spec_path: &str, spec: Option<&spec::Spec>) -> Vec<(String, PathBuf)> {
    let mut inputs = vec![("the spec".to_string(), PathBuf::from(spec_path))];
    for g in spec.map_or(&[][..], |s| &s.golden) {
        inputs.push((format!("the golden file of {}", g.key), g.path.clone()));
        for meta in golden::meta_paths(&g.path) {
            inputs.push((format!("the metadata of {}", g.key), meta));
        }
    }
    inputs
}

/// Run a parsed command, writing the user-facing text to `out` (without colour).
pub fn run(cli: Cli, out: &mut dyn Write) -> Result<Outcome> {
    run_with(cli, out, false)
}

/// Run a parsed command; `color` colours the verdicts of the checks table.
pub fn run_with(cli: Cli, out: &mut dyn Write, color: bool) -> Result<Outcome> {
    match cli.command {
        Command::Check {
            spec,
            json,
            explain,
            junit,
            report,
            report_crank_deg,
            report_map_steps,
            tolerance,
        } => {
            let outputs = Outputs {
                json: json.as_deref(),
                junit: junit.as_deref(),
                report: report.as_deref(),
                report_crank_deg,
                report_map_steps,
                color,
            };
            distinct_outputs(&inputs_of(&spec, None), &outputs.paths())?;
            let result = run_check(&spec, &outputs, (explain, tolerance), out);
            match (&result, outputs.junit) {
                (Err(e), Some(path))
                    if !matches!(e.kind, ErrorKind::Usage | ErrorKind::OutputClosed) =>
                {
                    // CI shows the error as a test case too; the error itself still goes to
                    // stderr.
                    let doc = report::junit::error_document(&spec, &e.to_string());
                    let _ = write_file(path, &doc);
                }
                _ => {}
            }
            result
        }
        Command::Bless { spec } => run_bless(&spec, out),
        Command::Accuracy {
            spec,
            scene,
            finest,
            settings_steps,
            te_tol_arcsec,
            force_tol_n,
            ratio_tol,
            clearance_tol_um,
        } => {
            let asked = AccuracyArgs {
                scene,
                finest,
                settings_steps,
                tolerances: [te_tol_arcsec, force_tol_n, ratio_tol, clearance_tol_um],
            };
            run_accuracy(&spec, &asked, out)
        }
        Command::Optimise {
            spec,
            study,
            write,
            map,
            map_steps,
        } => run_optimise(
            &spec,
            study.as_deref(),
            write.as_deref(),
            map.as_deref(),
            map_steps,
            out,
        ),
        Command::Profile {
            spec,
            csv,
            dxf,
            tolerance_um,
        } => run_profile(&spec, csv.as_deref(), dxf.as_deref(), tolerance_um, out),
        Command::Fit {
            spec,
            write,
            form_csv,
        } => run_fit(&spec, write.as_deref(), form_csv.as_deref(), out),
        Command::Tolerance(args) => tolerance::run(args, out),
    }
}

/// Print text for a person, its control characters escaped (names come from the spec).
fn print(out: &mut dyn Write, text: &str) -> Result<()> {
    print_keeping(out, text, &[])
}

/// `print`, letting the sequences in `keep` (the tool's own colours) through.
fn print_keeping(out: &mut dyn Write, text: &str, keep: &[&str]) -> Result<()> {
    out.write_all(crate::error::printable(text, keep).as_bytes())
        .map_err(stdout_error)
}

/// A failed write to standard output; a reader that closed it (`| head`) is `OutputClosed`.
fn stdout_error(e: std::io::Error) -> Error {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        Error::new(ErrorKind::OutputClosed, "standard output was closed")
    } else {
        Error::io("<stdout>", e)
    }
}

/// Where `check` writes its results besides the terminal.
struct Outputs<'a> {
    json: Option<&'a str>,
    junit: Option<&'a str>,
    report: Option<&'a str>,
    report_crank_deg: Option<f64>,
    report_map_steps: usize,
    color: bool,
}

impl Outputs<'_> {
    /// The files and directories this run writes, by option.
    fn paths(&self) -> [(&'static str, Option<&str>); 3] {
        [
            ("--json", self.json),
            ("--junit", self.junit),
            ("--report", self.report),
        ]
    }
}

/// Default grid of the report's objective maps: 15 × 15 = 225 evaluations per study, about
/// as many as the study itself.
pub const DEFAULT_REPORT_MAP_STEPS: usize = 15;
/// Largest grid of a report map (101² = 10 201 evaluations per study).
pub const MAX_REPORT_MAP_STEPS: usize = 101;

fn run_check(
    path: &str,
    outputs: &Outputs,
    (explain, tolerance): (bool, bool),
    out: &mut dyn Write,
) -> Result<Outcome> {
    let spec = spec::load(path)?;
    check::validate(&spec).map_err(|e| locate(e, &spec))?;
    let mut inputs = inputs_of(path, Some(&spec));
    if let Some(m) = &spec.measured {
        inputs.push(("the measured points".to_string(), m.path.clone().into()));
    }
    distinct_outputs(&inputs, &outputs.paths())?;
    let writes = scene::Writes {
        json: outputs.json.is_some(),
        report: outputs.report.is_some(),
    };
    if explain {
        print(out, &report::explain::explain(&spec, writes))?;
        if let Some(m) = &spec.measured {
            let line = format!(
                "\nas built: every scene runs on the disc identified from `{}` (its \
                 modification and form error), exact geometry\n",
                m.path
            );
            print(out, &line)?;
        }
        return Ok(Outcome::Passed);
    }
    let designed_modification = spec.measured.as_ref().map(|_| spec.modification);
    // The tolerance study draws from the drawing, whatever disc the other checks run on.
    let drawing = (tolerance && spec.measured.is_some()).then(|| spec.clone());
    let (spec, identified, designed) =
        match as_built::identify(&spec).map_err(|e| locate(e, &spec))? {
            Some((built, id)) => {
                // The design review shows each scene as designed beside as built.
                let designed = match outputs.report {
                    Some(_) => Some(run_scenes(&spec, writes).map_err(|e| locate(e, &spec))?),
                    None => None,
                };
                (built, Some(id), designed)
            }
            None => (spec, None, None),
        };
    if let Some(deg) = outputs.report_crank_deg.filter(|d| !d.is_finite()) {
        return Err(Error::new(
            ErrorKind::InvalidValue,
            format!("--report-crank-deg must be a finite angle, got {deg}"),
        ));
    }
    let steps = outputs.report_map_steps;
    if outputs.report.is_some() && (steps == 1 || steps > MAX_REPORT_MAP_STEPS) {
        return Err(Error::new(
            ErrorKind::InvalidValue,
            format!(
                "--report-map-steps must be 0 (no map) or 2 to {MAX_REPORT_MAP_STEPS}, got {steps}"
            ),
        ));
    }
    // Read the golden files before computing anything: a missing one fails fast.
    let golden_curves = golden::load_all(&spec).map_err(|e| locate(e, &spec))?;
    let results = run_scenes(&spec, writes).map_err(|e| locate(e, &spec))?;
    let mut checks = check::evaluate(&spec, &results).map_err(|e| locate(e, &spec))?;
    let studies = run_studies(&spec, spec.studies.iter().collect());
    checks.extend(check::optimisation(&spec, &studies));
    let goldens =
        golden::evaluate(&spec, &results, &golden_curves).map_err(|e| locate(e, &spec))?;
    checks.extend(goldens.iter().map(check::Check::from_golden));
    // The full accuracy ladder runs only for the design review; `check` alone runs the steps
    // rungs it needs to judge the accuracy scene's resolution (`engine::resolution`).
    let ladder = match (&spec.accuracy, outputs.report) {
        (Some(a), Some(_)) => Some(run_ladder(&spec, a)?),
        _ => None,
    };
    let resolution = match (&spec.accuracy, &ladder) {
        (Some(a), Some((l, _))) => Some(resolution::of_ladder(
            l,
            spec.scenes[a.scene].crank_rad.len(),
        )),
        (Some(a), None) => Some(resolution::run(&spec, a.scene, &a.options)?),
        _ => None,
    };
    if let (true, Some(r)) = (spec.limits.accuracy_resolved, &resolution) {
        checks.push(check::resolution(r));
    }
    if tolerance {
        checks.push(tolerance::check(drawing.as_ref().unwrap_or(&spec))?);
    }
    print(out, &format!("cycloid check `{}`\n", spec.name))?;
    if let Some(id) = &identified {
        print(out, &format!("{}\n", report::as_built::describe(&spec, id)))?;
    }
    for (s, r) in spec.studies.iter().zip(&studies) {
        print(out, &report::optimisation::render(&spec, s, r))?;
    }
    let styles: &[&str] = if outputs.color {
        &report::table::STYLES
    } else {
        &[]
    };
    print_keeping(
        out,
        &report::table::render_styled(&checks, outputs.color),
        styles,
    )?;
    if let Some(w) = resolution
        .as_ref()
        .and_then(report::accuracy::resolution_warning)
    {
        print(out, &format!("{w}\n"))?;
    }
    let summaries = summary::summarise(&results);
    print(out, &report::table::render_summary(&summaries))?;
    for note in report::explain::notes(&spec) {
        print(out, &format!("note: {note}\n"))?;
    }
    if let Some(p) = outputs.json {
        let doc = report::json::Document::new(&report::json::Contents {
            spec: &spec,
            checks: &checks,
            results: &results,
            goldens: &goldens,
            summaries: &summaries,
            studies: &studies,
        });
        report::json::write(std::path::Path::new(p), &doc)?;
    }
    if let Some(p) = outputs.junit {
        write_file(p, &report::junit::document(&spec.name, &spec.path, &checks))?;
    }
    if let Some((l, seconds)) = &ladder {
        print(out, &ladder_line(l, *seconds))?;
    }
    if let Some(dir) = outputs.report {
        let views: Vec<_> = spec
            .studies
            .iter()
            .zip(&studies)
            .map(|(s, r)| {
                let cells = if steps >= 2 {
                    map_with_progress(&spec, s, steps, &r.optimum.modification)
                } else {
                    Vec::new()
                };
                report::optimisation::view(&spec, s, r, &cells, steps)
            })
            .collect();
        let crank_rad = outputs
            .report_crank_deg
            .map_or_else(|| drawing::default_crank_rad(&results), crate::units::rad);
        let disc = drawing::disc(&spec, crank_rad)?;
        // The resolution warning `check` printed, as a banner under the verdict.
        let warnings: Vec<String> = resolution
            .as_ref()
            .and_then(report::accuracy::resolution_warning)
            .map(|w| w.strip_prefix("warning: ").unwrap_or(&w).to_string())
            .into_iter()
            .collect();
        let input = report::review::ReportInput {
            spec: &spec,
            checks: &checks,
            results: &results,
            goldens: &goldens,
            disc: &disc,
            optimisation: &views,
            accuracy: ladder.as_ref().map(|(l, _)| l),
            warnings: &warnings,
            as_built: identified.as_ref().zip(designed.as_deref()).map(
                |(identification, designed)| report::review::AsBuiltView {
                    identification,
                    designed_modification: designed_modification.unwrap_or(spec.modification),
                    designed,
                },
            ),
        };
        let files = report::review::write(std::path::Path::new(dir), &input)?;
        print(
            out,
            &format!(
                "design review: {} ({} files)\n",
                std::path::Path::new(dir).join("index.html").display(),
                files.len()
            ),
        )?;
    }
    Ok(if checks.iter().all(|c| c.passed) {
        Outcome::Passed
    } else {
        Outcome::ChecksFailed
    })
}

/// The accuracy ladder of the design review and its wall-clock time, s.
fn run_ladder(spec: &spec::Spec, a: &spec::Accuracy) -> Result<(accuracy::Ladder, f64)> {
    let start = std::time::Instant::now();
    // Steps rungs 12 … finest, and at most four settings rungs.
    let rungs = (a.options.finest / accuracy::COARSEST).trailing_zeros() as u64 + 1 + 4;
    let bar = report::terminal::Bar::new("accuracy ladder", "rungs", rungs, 0);
    let ladder = accuracy::run(spec, a.scene, &a.options, &mut |event| {
        if let accuracy::Event::Rung(..) = event {
            crate::progress::Progress::advance(&bar, 1);
        }
    })?;
    Ok((ladder, start.elapsed().as_secs_f64()))
}

/// The line `check --report` prints about the ladder.
fn ladder_line(ladder: &accuracy::Ladder, seconds: f64) -> String {
    format!(
        "accuracy ladder of scene `{}`: {} rungs in {seconds:.2} s; cheapest meeting every \
         tolerance: {}\n",
        ladder.layout.scene,
        ladder.rungs.len(),
        match ladder.cheapest {
            Some(i) => format!("`{}`", ladder.rungs[i].label),
            None => "none".to_string(),
        }
    )
}

fn run_bless(path: &str, out: &mut dyn Write) -> Result<Outcome> {
    let spec = spec::load(path)?;
    check::validate(&spec).map_err(|e| locate(e, &spec))?;
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
    // Run only the scenes that a golden refers to.
    let mut results = Vec::new();
    for s in &spec.scenes {
        if spec.golden.iter().any(|g| g.scene == s.name) {
            let plan = scene::plan(&spec, s, scene::Writes::default());
            let r = scene::run(&spec, s, &plan).map_err(|e| locate(e, &spec))?;
            results.push(r);
        }
    }
    let blessed = golden::bless(&spec, &results).map_err(|e| locate(e, &spec))?;
    print(out, &report::golden::bless_report(&spec, &blessed))?;
    Ok(Outcome::Passed)
}

/// Every scene, in parallel; results (and the first error) in spec order.
fn run_scenes(
    spec: &spec::Spec,
    writes: scene::Writes,
) -> Result<Vec<crate::model::results::SceneResult>> {
    use rayon::prelude::*;
    let plans: Vec<_> = spec
        .scenes
        .iter()
        .map(|s| scene::plan(spec, s, writes))
        .collect();
    // A bar for large scenes only: the sweeps of every scene, in crank angles.
    let total: usize = spec
        .scenes
        .iter()
        .zip(&plans)
        .map(|(s, plan)| s.crank_rad.len() * scene::sweeps(plan, spec.design.discs))
        .sum();
    let bar = report::terminal::Bar::new(
        "solving the scenes",
        "crank angles",
        total as u64,
        report::terminal::WORTH_SHOWING * 10,
    );
    let settings = crate::equilibrium::solve::Settings::default();
    let results: Vec<Result<crate::model::results::SceneResult>> = spec
        .scenes
        .par_iter()
        .zip(&plans)
        .map(|(s, plan)| scene::run_with_observed(spec, (s, plan), &settings, &bar))
        .collect();
    results.into_iter().collect()
}

/// Studies in parallel, in spec order, counting evaluations on a terminal.
fn run_studies(
    spec: &spec::Spec,
    studies: Vec<&crate::model::Study>,
) -> Vec<optimise::StudyResult> {
    use rayon::prelude::*;
    if studies.is_empty() {
        return Vec::new();
    }
    // At most this many evaluations: local runs often stop before their budget, and then the
    // bar ends short of full.
    let most: usize = studies.iter().map(|s| optimise::most_evaluations(s)).sum();
    let what = format!(
        "optimising {} stud{}",
        studies.len(),
        if studies.len() == 1 { "y" } else { "ies" }
    );
    let progress = report::terminal::Bar::new(&what, "evaluations at most", most as u64, 0);
    let results = studies
        .par_iter()
        .map(|s| optimise::run_study_with(spec, s, &progress))
        .collect();
    drop(progress);
    results
}

/// `optimise::map`, with a bar of its cells on a terminal.
fn map_with_progress(
    spec: &spec::Spec,
    study: &crate::model::Study,
    steps: usize,
    around: &crate::model::Modification,
) -> Vec<optimise::problem::Evaluation> {
    let cells = if study.variables.len() > 1 {
        steps * steps
    } else {
        steps
    };
    let what = format!("objective map of `{}`", study.name);
    let progress = report::terminal::Bar::new(&what, "cells", cells as u64, 0);
    let map = optimise::map(spec, study, steps, around, &progress);
    drop(progress);
    map
}

/// `optimise --write OUT`: the spec of a study's optimum, written only when it is feasible;
/// returns what to tell the user.
fn write_optimum(
    spec: &spec::Spec,
    path: &str,
    study: &crate::model::Study,
    r: &optimise::StudyResult,
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
    let text = optimise::write::optimum_spec(
        out_path,
        &spec.source,
        &r.optimum.modification,
        &name,
        &header,
    )?;
    write_file(out_path, &text)?;
    Ok(format!(
        "wrote {out_path} (`{name}`) with the optimum of `{}`\n",
        r.name
    ))
}

/// The options of `cycloid accuracy` as given; unset ones come from the spec's `accuracy`
/// section, else the defaults.
struct AccuracyArgs {
    scene: Option<String>,
    finest: Option<i64>,
    settings_steps: Option<i64>,
    /// TE (arcsec), force (N), ratio, clearance (µm).
    tolerances: [Option<f64>; 4],
}

fn run_accuracy(path: &str, asked: &AccuracyArgs, out: &mut dyn Write) -> Result<Outcome> {
    let bad = |flag: &str, m: String| Error::new(ErrorKind::InvalidValue, format!("--{flag}: {m}"));
    let spec = spec::load(path)?;
    let from_spec = spec.accuracy.as_ref();
    let scene = match &asked.scene {
        Some(name) => spec
            .scenes
            .iter()
            .position(|s| &s.name == name)
            .ok_or_else(|| {
                bad(
                    "scene",
                    format!(
                        "no scene named `{name}`; scenes: {}",
                        spec::scene_names(&spec.scenes)
                    ),
                )
            })?,
        None => from_spec.map_or_else(|| accuracy::default_scene(&spec), |a| a.scene),
    };
    let mut options = from_spec.map_or_else(accuracy::Options::default, |a| a.options);
    if let Some(n) = asked.finest {
        options.finest =
            accuracy::ladder_steps(n, 2 * accuracy::COARSEST).map_err(|m| bad("finest", m))?;
    }
    if let Some(n) = asked.settings_steps {
        options.settings_steps = Some(
            accuracy::ladder_steps(n, accuracy::COARSEST).map_err(|m| bad("settings-steps", m))?,
        );
    }
    let t = &mut options.tolerances;
    for ((flag, value), slot) in [
        "te-tol-arcsec",
        "force-tol-n",
        "ratio-tol",
        "clearance-tol-um",
    ]
    .into_iter()
    .zip(asked.tolerances)
    .zip([
        &mut t.te_arcsec,
        &mut t.force_n,
        &mut t.ratio,
        &mut t.clearance_um,
    ]) {
        if let Some(v) = value {
            *slot = accuracy::tolerance(v).map_err(|m| bad(flag, m))?;
        }
    }
    accuracy::check(&spec.design, &spec.scenes[scene], &options).map_err(|(which, m)| {
        let flag = match which {
            accuracy::Setting::Scene => "scene",
            accuracy::Setting::Finest => "finest",
            accuracy::Setting::SettingsSteps => "settings-steps",
        };
        bad(flag, m)
    })?;
    // Rows are printed as their runs finish: the finest run comes first and takes longest.
    let mut written: Result<()> = Ok(());
    let ladder = accuracy::run(&spec, scene, &options, &mut |event| {
        let text = match event {
            accuracy::Event::Started(layout) => report::accuracy::header(layout),
            accuracy::Event::Rung(layout, rung) => report::accuracy::row(layout, rung, false),
        };
        if written.is_ok() {
            written = print(out, &text).and_then(|_| out.flush().map_err(stdout_error));
        }
    })?;
    written?;
    print(out, &report::accuracy::footer(&ladder))?;
    Ok(Outcome::Passed)
}

/// Give an error about a spec key the key's location in the spec file.
fn locate(mut e: Error, spec: &spec::Spec) -> Error {
    if e.location.is_none() {
        if let Some((line, column)) = e
            .key_path
            .as_deref()
            .and_then(|k| spec::locate(&spec.source, k))
        {
            e.location = Some(crate::error::Location {
                file: spec.path.clone(),
                line,
                column,
            });
        }
    }
    e
}

/// Finest chordal tolerance `profile` accepts, µm.
pub const MIN_TOLERANCE_UM: f64 = 0.001;

fn run_profile(
    path: &str,
    csv: Option<&str>,
    dxf: Option<&str>,
    tolerance_um: f64,
    out: &mut dyn Write,
) -> Result<Outcome> {
    if !(tolerance_um.is_finite() && tolerance_um > 0.0) {
        return Err(Error::new(
            ErrorKind::InvalidValue,
            format!(
                "--tolerance-um must be a positive number, got {}",
                numeric::input(tolerance_um)
            ),
        ));
    }
    // Below a nanometre the point count explodes (≈ 1/√tolerance) and the chords approach the
    // rounding of f64 coordinates; the export would run for hours and exhaust memory.
    if tolerance_um < MIN_TOLERANCE_UM {
        return Err(Error::new(
            ErrorKind::InvalidValue,
            format!(
                "--tolerance-um must be at least {MIN_TOLERANCE_UM} (1 nm), got {}",
                numeric::input(tolerance_um)
            ),
        ));
    }
    distinct_outputs(&inputs_of(path, None), &[("--csv", csv), ("--dxf", dxf)])?;
    let spec = spec::load(path)?;
    let tol = tolerance_um / 1000.0;
    let points = export::polyline(&Profile::new(&spec.design, &spec.modification), tol);
    if let Some(p) = csv {
        write_file(p, &export::csv(&spec, &points, tol))?;
    }
    if let Some(p) = dxf {
        write_file(p, &export::dxf(&spec, &points, tol))?;
    }
    print(
        out,
        &format!(
            "profile of `{}`: {} points, chordal error <= {tolerance_um} um\n",
            spec.name,
            points.len()
        ),
    )?;
    Ok(Outcome::Passed)
}

fn run_optimise(
    path: &str,
    only: Option<&str>,
    write: Option<&str>,
    map: Option<&str>,
    map_steps: usize,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let spec = spec::load(path)?;
    let outputs = [("--write", write), ("--map", map)];
    distinct_outputs(&inputs_of(path, Some(&spec)), &outputs)?;
    if spec.studies.is_empty() {
        return Err(Error::new(
            ErrorKind::InvalidValue,
            format!("{path}: the spec has no `optimise` section"),
        ));
    }
    let chosen: Vec<&crate::model::Study> = match only {
        Some(name) => {
            let s = spec
                .studies
                .iter()
                .find(|s| s.name == name)
                .ok_or_else(|| {
                    Error::new(
                        ErrorKind::InvalidValue,
                        format!(
                            "no study named `{name}`; studies: {}",
                            spec.studies
                                .iter()
                                .map(|s| s.name.as_str())
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    )
                })?;
            vec![s]
        }
        None => spec.studies.iter().collect(),
    };
    if map.is_some() && !(2..=MAX_REPORT_MAP_STEPS).contains(&map_steps) {
        return Err(Error::new(
            ErrorKind::InvalidValue,
            format!("--map-steps must be 2 to {MAX_REPORT_MAP_STEPS}, got {map_steps}"),
        ));
    }
    let mut all_feasible = true;
    let results = run_studies(&spec, chosen.clone());
    for (k, (study, r)) in chosen.iter().zip(results).enumerate() {
        print(out, &report::optimisation::render(&spec, study, &r))?;
        all_feasible &= r.optimum.feasible();
        if k == 0 {
            if let Some(p) = write {
                print(out, &write_optimum(&spec, path, study, &r, p)?)?;
            }
            if let Some(p) = map {
                let cells = map_with_progress(&spec, study, map_steps, &r.optimum.modification);
                write_file(p, &report::optimisation::map_csv(study, &cells))?;
                print(
                    out,
                    &format!("wrote the objective map of `{}` to {p}\n", r.name),
                )?;
            }
        }
    }
    Ok(if all_feasible {
        Outcome::Passed
    } else {
        Outcome::ChecksFailed
    })
}

/// `cycloid fit`: identify the measured disc, print it, and write what was asked.
fn run_fit(
    path: &str,
    write: Option<&str>,
    form_csv: Option<&str>,
    out: &mut dyn Write,
) -> Result<Outcome> {
    let spec = spec::load(path)?;
    check::validate(&spec).map_err(|e| locate(e, &spec))?;
    let measured = spec.measured.as_ref().ok_or_else(|| {
        Error::new(
            crate::ErrorKind::InvalidValue,
            format!(
                "{path}: the spec has no `measured_profile:` section; add \
                 `measured_profile: {{file: points.csv, format: csv, harmonics: 0, fit: \
                 [shift_mm, equidistant_mm]}}`"
            ),
        )
    })?;
    let mut inputs = inputs_of(path, Some(&spec));
    inputs.push((
        "the measured points".to_string(),
        std::path::PathBuf::from(&measured.path),
    ));
    distinct_outputs(&inputs, &[("--write", write), ("--form-csv", form_csv)])?;
    let id = as_built::fit(&spec, measured)?;
    print(out, &report::fit::render(&spec, &id))?;
    if let Some(p) = form_csv {
        write_file(p, &report::fit::form_csv(&spec, &id))?;
    }
    if let Some(p) = write {
        let text = optimise::write::with_modification(p, &spec.source, &id.modification)?;
        let mut deviations = spec.design.deviations.clone();
        deviations.form = as_built::form_terms(&id);
        let text = if deviations.form.is_empty() {
            text
        } else {
            crate::engine::tolerance::write::with_deviations(&text, path, &deviations, p)?
        };
        write_file(p, &text)?;
        let what = if deviations.form.is_empty() {
            "the identified modification"
        } else {
            "the identified modification and form error (reducer.deviations.form)"
        };
        print(out, &format!("wrote {p} with {what}\n"))?;
    }
    Ok(Outcome::Passed)
}
