//! The command line's arguments (clap): every command and option, with the help text users
//! see.

use clap::{Parser, Subcommand};

/// Default grid of the report's objective maps: 15 × 15 = 225 evaluations per study, about
/// as many as the study itself.
pub const DEFAULT_REPORT_MAP_STEPS: usize = 15;

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
    Check(CheckArgs),
    /// Optimise the tooth-profile modification as the spec's `optimise` section says.
    Optimise(OptimiseArgs),
    /// Run a scene on a ladder of settings (crank steps per mesh period, geometry, contact law,
    /// solver tolerance) and print each rung's error against the finest rung and its time.
    Accuracy(AccuracyArgs),
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
    /// Search a requirements file's design space for the Pareto front of checked designs;
    /// `design merge SHARD...` finishes a search split over processes.
    Design(DesignArgs),
    /// Export the modified disc profile as CSV points and a DXF polyline, and the disc as a
    /// STEP solid and an STL mesh.
    Profile(ProfileArgs),
}

/// `cycloid profile SPEC [options]`: the files it writes (each optional, at least one).
#[derive(Debug, clap::Args)]
pub struct ProfileArgs {
    /// The YAML spec whose design and modification give the profile.
    pub spec: String,
    /// Write the profile points as CSV (x_mm, y_mm) to this path (optional).
    #[arg(long)]
    pub csv: Option<String>,
    /// Write the profile as a closed DXF polyline to this path (optional).
    #[arg(long)]
    pub dxf: Option<String>,
    /// Write the disc as one STEP (AP214) solid to this path (optional).
    #[arg(long)]
    pub step: Option<String>,
    /// Write the disc as a closed ASCII STL mesh to this path (optional).
    #[arg(long)]
    pub stl: Option<String>,
    /// Largest chordal error of the exported polyline, µm (at least 0.001); also the
    /// largest distance of the STEP solid's and the STL mesh's surface from the disc.
    #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
    pub tolerance_um: f64,
}

/// `cycloid accuracy SPEC [options]`: the options as given; unset ones come from the spec's
/// `accuracy` section, else the defaults.
#[derive(Debug, clap::Args)]
pub struct AccuracyArgs {
    /// The YAML spec.
    pub spec: String,
    /// The scene to run [default: the spec's `accuracy.scene`, else the first scene with
    /// roller contact, else the first scene].
    #[arg(long)]
    pub scene: Option<String>,
    /// Crank steps per mesh period of the finest rung, the reference: 12·2^k, at least 24
    /// [default: the spec's `accuracy.finest_steps_per_period`, else 3072].
    #[arg(long, allow_negative_numbers = true)]
    pub finest: Option<i64>,
    /// Crank steps per mesh period of the rungs that change one setting [default: the
    /// cheapest steps rung that meets every tolerance, else the finest].
    #[arg(long, allow_negative_numbers = true)]
    pub settings_steps: Option<i64>,
    /// Tolerance on the TE curve and the TE fluctuation, arcsec [default: 0.1].
    #[arg(long, allow_negative_numbers = true)]
    pub te_tol_arcsec: Option<f64>,
    /// Tolerance on the max roller and bearing forces, N [default: 0.5].
    #[arg(long, allow_negative_numbers = true)]
    pub force_tol_n: Option<f64>,
    /// Tolerance on the ratio fluctuation κmax − κmin [default: 1e-4].
    #[arg(long, allow_negative_numbers = true)]
    pub ratio_tol: Option<f64>,
    /// Tolerance on the min clearance, µm [default: 0.1].
    #[arg(long, allow_negative_numbers = true)]
    pub clearance_tol_um: Option<f64>,
}

/// `cycloid check SPEC [options]`: where it writes its results besides the terminal, and what
/// else it runs.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// The YAML spec.
    pub spec: String,
    /// Write the results as JSON to this path.
    #[arg(long)]
    pub json: Option<String>,
    /// Print what will be computed and why, then stop.
    #[arg(long)]
    pub explain: bool,
    /// Write a JUnit XML report (one test case per check and golden curve) to this path.
    #[arg(long)]
    pub junit: Option<String>,
    /// Write a design-review report (index.html and SVG plots) into this directory.
    #[arg(long)]
    pub report: Option<String>,
    /// Crank angle of the disc drawing in the report, degrees [default: where the smallest
    /// gap occurs].
    #[arg(long, allow_negative_numbers = true)]
    pub report_crank_deg: Option<f64>,
    /// Grid points per variable of each study's objective map in the report (0: no map;
    /// the map costs steps² evaluations per study).
    #[arg(long, default_value_t = DEFAULT_REPORT_MAP_STEPS)]
    pub report_map_steps: usize,
    /// Also run the Monte Carlo of the spec's `tolerances:` (as `cycloid tolerance`); its
    /// failure rate against `max_failure_rate` joins the checks.
    #[arg(long)]
    pub tolerance: bool,
    /// Whether the checks table's verdicts are coloured: not an option, set by `run_with`.
    #[arg(skip)]
    pub color: bool,
}

impl CheckArgs {
    /// The files and directories this run writes, by option.
    pub(super) fn paths(&self) -> [(&'static str, Option<&str>); 3] {
        [
            ("--json", self.json.as_deref()),
            ("--junit", self.junit.as_deref()),
            ("--report", self.report.as_deref()),
        ]
    }
}

/// `cycloid optimise SPEC [options]`.
#[derive(Debug, clap::Args)]
pub struct OptimiseArgs {
    /// The YAML spec; its `optimise` section (one study or a list) says what to optimise.
    pub spec: String,
    /// Run only this study (default: all).
    #[arg(long)]
    pub study: Option<String>,
    /// Write the spec with the optimum of the study (the first, or --study) filled in.
    #[arg(long)]
    pub write: Option<String>,
    /// Write the objective over a grid of the first two variables as CSV.
    #[arg(long)]
    pub map: Option<String>,
    /// Grid points per variable for --map.
    #[arg(long, default_value_t = 21)]
    pub map_steps: usize,
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

/// `cycloid design REQUIREMENTS [options]`, or `cycloid design merge SHARD...`.
#[derive(Debug, clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct DesignArgs {
    #[command(subcommand)]
    pub merge: Option<DesignCommand>,
    /// The YAML requirements file (ratio, torques, envelope, limits, objectives, the search's
    /// space).
    #[arg(required = true)]
    pub requirements: Option<String>,
    /// Write each front design's spec, front.csv and the review page index.html into this
    /// directory; with --shard, the shard file.
    #[arg(long)]
    pub out: Option<String>,
    /// Compute only shard I of N of the global stage (0-based: the candidates j with
    /// j mod N = I) and write it to --out; without it, Slurm's SLURM_ARRAY_TASK_ID and
    /// SLURM_ARRAY_TASK_COUNT are honoured.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
}

/// Subcommands of `cycloid design`.
#[derive(Debug, Subcommand)]
pub enum DesignCommand {
    /// Join the shard files of one search, run its local refinement and write what the
    /// unsharded run writes (the same front, bit for bit).
    Merge {
        /// Every shard file of the run, in any order.
        #[arg(required = true)]
        shards: Vec<String>,
        /// Write each front design's spec, front.csv and the review page index.html into this
        /// directory.
        #[arg(long)]
        out: Option<String>,
    },
}
