//! Helpers shared by the tests: the `cycloid` binary run in a scratch directory (`Scratch`,
//! `cycloid`), the paper's spec with edits (`PaperSpec`), designs built directly, a closed form
//! of the locus curvature, and the proptest strategy of valid designs.
//!
//! Nothing here calls the code under test to produce an expected value: the closed forms are
//! derived below from the definition of the locus in MODEL.md.
#![allow(dead_code)] // each test crate uses a different subset

use cycloid::model::{Design, Material, Modification, OutputPins};
use cycloid::spec::Spec;
use proptest::prelude::*;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The shipped spec: the paper's Table 1 design with its optimum modification, clearance only.
pub(crate) const PAPER: &str = include_str!("../../../specs/reducer.yaml");

/// A scratch directory, unique per call and process, removed when dropped.
pub(crate) struct Scratch {
    pub path: PathBuf,
}

impl Scratch {
    pub(crate) fn new(tag: &str) -> Scratch {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let path = std::env::temp_dir().join(format!(
            "cycloid-test-{tag}-{}-{}",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).unwrap();
        Scratch { path }
    }

    /// `name` inside the directory.
    pub(crate) fn join(&self, name: &str) -> PathBuf {
        self.path.join(name)
    }

    /// Write `name` (creating its directories).
    pub(crate) fn write(&self, name: &str, text: impl AsRef<[u8]>) {
        let path = self.path.join(name);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).unwrap();
        }
        std::fs::write(path, text).unwrap();
    }

    pub(crate) fn read(&self, name: &str) -> String {
        std::fs::read_to_string(self.path.join(name))
            .unwrap_or_else(|e| panic!("{name} was not written: {e}"))
    }

    pub(crate) fn exists(&self, name: &str) -> bool {
        self.path.join(name).exists()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.path);
    }
}

/// Every file under `dir`, relative path → bytes: what a run must leave as it was. Directories
/// are listed as `name/`; links and other non-regular files by name only (a link is not
/// followed, a FIFO would block).
pub(crate) fn files(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut std::collections::BTreeMap<String, Vec<u8>>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.strip_prefix(root).unwrap().display().to_string();
            let meta = std::fs::symlink_metadata(&path).unwrap();
            if meta.is_dir() {
                out.insert(format!("{name}/"), Vec::new());
                walk(root, &path, out);
            } else if meta.is_file() {
                out.insert(name, std::fs::read(&path).unwrap());
            } else {
                out.insert(name, Vec::new());
            }
        }
    }
    let mut out = std::collections::BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// What a run of the binary produced.
#[derive(Debug)]
pub(crate) struct Run {
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// The exit code (-1 when killed by a signal).
    pub(crate) fn code(&self) -> i32 {
        self.code.unwrap_or(-1)
    }

    /// (exit code, stdout, stderr).
    pub(crate) fn parts(self) -> (i32, String, String) {
        (self.code(), self.stdout, self.stderr)
    }
}

/// Longest a single run may take before the test calls it a hang.
const TIMEOUT: Duration = Duration::from_secs(300);

/// Run `cycloid ARGS` in `dir` (no colour, the date pinned by `SOURCE_DATE_EPOCH=0`). Output
/// goes to files (no pipe can fill up); a run longer than `TIMEOUT` is killed and fails.
pub(crate) fn cycloid(dir: &Path, args: &[&str]) -> Run {
    cycloid_with(dir, args, &[])
}

/// `cycloid` with extra environment variables.
pub(crate) fn cycloid_with(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> Run {
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let capture = std::env::temp_dir().join(format!("cycloid-test-out-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&capture).unwrap();
    let (out_path, err_path) = (capture.join("stdout"), capture.join("stderr"));
    let mut command = Command::new(env!("CARGO_BIN_EXE_cycloid"));
    command
        .args(args)
        .current_dir(dir)
        .env_remove("RUST_BACKTRACE")
        .env("NO_COLOR", "1")
        .env("SOURCE_DATE_EPOCH", "0")
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap());
    for (k, v) in env {
        command.env(k, v);
    }
    let mut child = command.spawn().expect("the cycloid binary runs");
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            let _ = std::fs::remove_dir_all(&capture);
            panic!("cycloid {args:?} did not finish within {TIMEOUT:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let run = Run {
        code: status.code(),
        stdout: String::from_utf8_lossy(&std::fs::read(&out_path).unwrap()).into_owned(),
        stderr: String::from_utf8_lossy(&std::fs::read(&err_path).unwrap()).into_owned(),
    };
    let _ = std::fs::remove_dir_all(&capture);
    run
}

/// `cycloid ARGS` in the repository's root (shipped specs by their relative path).
pub(crate) fn cycloid_here(args: &[&str]) -> Run {
    cycloid(Path::new(env!("CARGO_MANIFEST_DIR")), args)
}

/// The paper's spec (`specs/reducer.yaml`) as text, edited: the modification, the scenes (its
/// limits go with them), extra top-level sections, or any exact replacement.
#[derive(Debug, Clone)]
pub(crate) struct PaperSpec {
    text: String,
}

impl Default for PaperSpec {
    fn default() -> Self {
        PaperSpec {
            text: PAPER.to_string(),
        }
    }
}

impl PaperSpec {
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Replace `from` by `to`; `from` must occur exactly once, so that an edit can never
    /// silently do nothing.
    pub(crate) fn edit(mut self, from: &str, to: &str) -> Self {
        assert_eq!(
            self.text.matches(from).count(),
            1,
            "`{from}` must occur once in the spec"
        );
        self.text = self.text.replacen(from, to, 1);
        self
    }

    /// The modification (ΔRp, ΔRrp), mm.
    pub(crate) fn modification(mut self, shift_mm: f64, equidistant_mm: f64) -> Self {
        let mut replaced = 0;
        let lines: Vec<String> = self
            .text
            .lines()
            .map(|line| {
                let key = line.trim_start();
                if key.starts_with("shift_mm:") {
                    replaced += 1;
                    format!("  shift_mm: {shift_mm:?}")
                } else if key.starts_with("equidistant_mm:") {
                    replaced += 1;
                    format!("  equidistant_mm: {equidistant_mm:?}")
                } else {
                    line.to_string()
                }
            })
            .collect();
        assert_eq!(replaced, 2, "one shift_mm and one equidistant_mm");
        self.text = lines.join("\n") + "\n";
        self
    }

    /// The `scenes:` section and everything after it (the limits) replaced by `scenes`, the
    /// YAML items of the list.
    pub(crate) fn scenes(mut self, scenes: &str) -> Self {
        let at = self.text.find("\nscenes:").expect("the spec has scenes") + 1;
        self.text.truncate(at);
        self.text += "scenes:\n";
        self.text += scenes;
        self
    }

    /// One scene `rated`: 10 N·m over one mesh period (0°–36°) in `steps` angles, with
    /// clearance and roller contact (no limits).
    pub(crate) fn rated_period(self, steps: usize) -> Self {
        let crank = format!("{{ from_deg: 0.0, to_deg: 36.0, steps: {steps} }}");
        self.scenes(&scene_item(
            "rated",
            10.0,
            &crank,
            "clearance, roller_contact",
        ))
    }

    /// Top-level YAML appended at the end.
    pub(crate) fn with(mut self, extra: &str) -> Self {
        if !self.text.ends_with('\n') {
            self.text.push('\n');
        }
        self.text += extra;
        self
    }

    pub(crate) fn text(&self) -> &str {
        &self.text
    }

    /// The spec parsed and validated (named `path` in messages).
    pub(crate) fn parse(&self, path: &str) -> cycloid::spec::Spec {
        cycloid::spec::parse(path, &self.text)
            .unwrap_or_else(|e| panic!("test spec is valid: {e}\n{}", self.text))
    }
}

/// One item of a spec's `scenes:` list: `name` at `torque_nm` over `crank` (its YAML flow
/// mapping) with `effects` (comma-separated).
pub(crate) fn scene_item(name: &str, torque_nm: f64, crank: &str, effects: &str) -> String {
    format!(
        "  - name: {name}\n    output_torque_nm: {torque_nm:?}\n    crank: {crank}\n    \
         effects: [{effects}]\n"
    )
}

pub(crate) const STEEL: Material = Material {
    youngs_modulus_mpa: 206_000.0,
    poisson_ratio: 0.3,
};

/// A design with np rollers (nc = np − 1 teeth). Pins and materials do not enter the geometry.
pub(crate) fn design(rollers: usize, eccentricity_mm: f64, rp_mm: f64, rrp_mm: f64) -> Design {
    Design {
        teeth: rollers - 1,
        rollers,
        discs: 1,
        eccentricity_mm,
        roller_circle_radius_mm: rp_mm,
        roller_radius_mm: rrp_mm,
        face_width_mm: 8.0,
        pins: OutputPins {
            count: 6,
            circle_radius_mm: 0.5 * rp_mm,
            pin_radius_mm: 0.05 * rp_mm,
            hole_clearance_mm: 0.0,
            support: None,
        },
        disc_material: STEEL,
        roller_material: STEEL,
        strength: Default::default(),
        crank_bearing: None,
        deviations: Default::default(),
        friction: None,
        thermal: None,
        structure_compliance_rad_per_nmm: 0.0,
        density_kg_per_mm3: 7.85e-6,
        output_inertia_kgmm2: 0.0,
        roller_inertia_kgmm2: 0.0,
    }
}

pub(crate) fn modification(shift_mm: f64, equidistant_mm: f64, rotation_rad: f64) -> Modification {
    Modification {
        shift_mm,
        equidistant_mm,
        rotation_rad,
    }
}

/// The paper's design (Table 1): nc 9, np 10, e 2, Rp 30, Rrp 3 (from specs/reducer.yaml).
pub(crate) fn paper_design() -> Design {
    PaperSpec::new().parse("reducer.yaml").design
}

/// specs/reducer.yaml with its modification replaced, parsed and validated by `spec::parse`.
pub(crate) fn paper_spec(shift_mm: f64, equidistant_mm: f64) -> Spec {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/specs/reducer.yaml");
    PaperSpec::new()
        .modification(shift_mm, equidistant_mm)
        .parse(path)
}

/// Curvature of the locus C(t) = R(cos t, sin t) − e(cos nt, sin nt) (n = np) as a function of
/// x = cos(nc·t), derived by hand from C' and C'':
///   C'×C'' = R² + e²n³ − R·e·n(n+1)·x,   |C'|² = R² + e²n² − 2R·e·n·x,
///   κ_C = (C'×C'')/|C'|³.
pub(crate) fn locus_curvature_closed(rollers: usize, e: f64, r: f64, x: f64) -> f64 {
    let n = rollers as f64;
    (r * r + e * e * n.powi(3) - r * e * n * (n + 1.0) * x)
        / (r * r + e * e * n * n - 2.0 * r * e * n * x).powf(1.5)
}

/// Smallest convex radius of curvature of the locus and the parameter t ∈ [0, π/nc] (from the
/// root) where it occurs, in closed form. κ_C(x) = (A − Bx)/(D − Ex)^{3/2} has a single
/// stationary point x* = (3AE − 2BD)/(BE) = (3(1 + K²n) − (n + 1)(1 + K²))/(K(n + 1)),
/// K = e·n/R; the maximum curvature on [−1, 1] is at x* (if inside) or at an end.
pub(crate) fn min_convex_radius_closed(rollers: usize, e: f64, r: f64) -> (f64, f64) {
    let n = rollers as f64;
    let k = e * n / r;
    let x_star = (3.0 * (1.0 + k * k * n) - (n + 1.0) * (1.0 + k * k)) / (k * (n + 1.0));
    let (x, kappa) = [x_star.clamp(-1.0, 1.0), -1.0, 1.0]
        .into_iter()
        .map(|x| (x, locus_curvature_closed(rollers, e, r, x)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    (1.0 / kappa, x.acos() / (n - 1.0))
}

/// A valid design and a modification that keeps it valid.
#[derive(Debug, Clone)]
pub(crate) struct Case {
    pub design: Design,
    pub m: Modification,
}

impl Case {
    pub(crate) fn k1(&self) -> f64 {
        self.design.k1()
    }
}

/// Largest modification a case may carry: 0.3 mm, but small against the tooth depth (2e) and
/// the roller, so that the gaps stay a small-modification question.
fn modification_cap(e: f64, rrp: f64) -> f64 {
    0.3f64.min(0.15 * e).min(0.5 * rrp)
}

/// Build a case from unit parameters; `None` if the modification cannot be kept valid.
/// - np rollers, Rp, K1 = e·np/Rp in (0.1, 0.9);
/// - Rrp = u·0.8·min(ρmin, Rp·sin(π/np)): below 0.8 of the smallest convex radius of curvature
///   of the locus (no undercut) and of half the roller pitch (rollers do not overlap);
/// - ΔRp = a·cap, ΔRrp in [−cap, min(cap, 0.9·ρmin(Rp + ΔRp) − Rrp)] (still undercut-free).
#[allow(clippy::too_many_arguments)]
pub(crate) fn build_case(
    rollers: usize,
    rp: f64,
    k1: f64,
    u: f64,
    a: f64,
    b: f64,
    rotation_rad: f64,
) -> Option<Case> {
    let n = rollers as f64;
    let e = k1 * rp / n;
    let (rho, _) = min_convex_radius_closed(rollers, e, rp);
    let rrp = u * 0.8 * rho.min(rp * (PI / n).sin());
    let cap = modification_cap(e, rrp);
    let shift = a * cap;
    let (rho_shifted, _) = min_convex_radius_closed(rollers, e, rp + shift);
    let hi = cap.min(0.9 * rho_shifted - rrp);
    let lo = -cap;
    if hi <= lo || e * n / (rp + shift) >= 0.95 {
        return None;
    }
    Some(Case {
        design: design(rollers, e, rp, rrp),
        m: modification(shift, lo + b * (hi - lo), rotation_rad),
    })
}

/// Random valid designs with random modifications (no profile rotation).
pub(crate) fn cases() -> impl Strategy<Value = Case> {
    (
        4usize..=40,
        20.0f64..120.0,
        0.1f64..0.9,
        0.1f64..1.0,
        -1.0f64..1.0,
        0.0f64..1.0,
    )
        .prop_filter_map("modification must keep the design valid", |p| {
            build_case(p.0, p.1, p.2, p.3, p.4, p.5, 0.0)
        })
}

/// As `cases`, with a profile rotation Δδ of up to ±0.2 mrad.
pub(crate) fn rotated_cases() -> impl Strategy<Value = Case> {
    (cases(), -2e-4f64..2e-4).prop_map(|(mut c, d)| {
        c.m.rotation_rad = d;
        c
    })
}

/// Random valid designs with the profile unmodified.
pub(crate) fn unmodified_cases() -> impl Strategy<Value = Case> {
    cases().prop_map(|mut c| {
        c.m = Modification::default();
        c
    })
}

/// The minimiser of a unimodal `f` on [a, b] by golden-section search (100 steps shrink the
/// bracket by 0.618^100 ≈ 1e-21: to the round-off of the argument).
#[allow(dead_code)]
pub(crate) fn golden_section_min(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..100 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if f(x1) < f(x2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    0.5 * (a + b)
}

/// `text` (named `file`) is refused naming `key` and `rule`, at the file:line:column of `key`
/// as written (`locate`), and `cycloid check` on it exits 2.
pub(crate) fn assert_refused_at(dir: &Scratch, file: &str, text: &str, key: &str, rule: &str) {
    let shown = cycloid::spec::parse(file, text).expect_err(key).to_string();
    assert!(
        shown.contains(key) && shown.contains(rule),
        "{key}: {shown}"
    );
    let (line, column) = locate(text, key);
    assert!(
        shown.starts_with(&format!("{file}:{line}:{column}:")),
        "{key} at {line}:{column}: {shown}"
    );
    dir.write("bad.yaml", text);
    let run = cycloid(&dir.path, &["check", "bad.yaml"]);
    assert_eq!(run.code(), 2, "{key}: {}", run.stderr);
}

/// The line and column (1-based) where `key`'s last segment is written in `text`, searched
/// after its first segment (`section:`): the value of a flow mapping's key, or a block key.
/// Written out here from the text, not by the parser.
pub(crate) fn locate(text: &str, key: &str) -> (usize, usize) {
    let last = key.rsplit('.').next().unwrap();
    let last = last.split('[').next().unwrap();
    let (section, _) = key.split_once('.').unwrap();
    let section = section.split('[').next().unwrap();
    let start = text.find(&format!("{section}:")).unwrap();
    let offset = start + text[start..].find(&format!("{last}:")).unwrap();
    let line = text[..offset].matches('\n').count() + 1;
    let column = offset - text[..offset].rfind('\n').map_or(0, |p| p + 1) + 1;
    (line, column)
}

/// The spec's first scene run as `check` runs it (its plan, no files written); a failure
/// panics with the error.
pub(crate) fn run_first_scene(spec: &Spec) -> cycloid::model::results::SceneResult {
    use cycloid::engine::scene;
    let s = &spec.scenes[0];
    scene::run(
        spec,
        s,
        &scene::plan(spec, s, scene::Writes::default()),
        &Default::default(),
    )
    .unwrap()
}

/// The loaded sweep of one disc of `model` at `crank_rad` (`discs_sweep::sweep_reducer`, N = 1):
/// the disc's curves and the reducer's transmission.
pub(crate) fn one_disc_sweep(
    model: &cycloid::equilibrium::loaded::Model,
    crank_rad: &[f64],
    periodic: bool,
) -> Result<
    (
        cycloid::model::results::LoadedSweep,
        Option<cycloid::model::results::Transmission>,
    ),
    cycloid::equilibrium::sweep::SweepFailure,
> {
    use cycloid::equilibrium::discs_sweep::sweep_reducer;
    let swept = sweep_reducer(model, 1, crank_rad, (periodic, &cycloid::progress::Silent))?;
    let disc = swept.discs.into_iter().next().expect("one disc");
    Ok((disc, swept.transmission))
}

/// Sample `k` of the tolerance study `study` (a spec file in `dir`) written back as a spec
/// (`tolerance --write-sample`) and checked (`check --json`): the sample's spec and its results
/// JSON. Exit 0 or 1 required of the check (a sample may fail a limit).
pub(crate) fn replayed_sample(dir: &Path, study: &str, k: usize) -> (String, serde_json::Value) {
    let out = format!("sample{k}.yaml");
    let w = cycloid(
        dir,
        &["tolerance", study, "--write-sample", &k.to_string(), &out],
    );
    assert_eq!(w.code(), 0, "{w:?}");
    let c = cycloid(dir, &["check", &out, "--json", "c.json"]);
    assert!(c.code() <= 1, "{c:?}");
    let json = std::fs::read_to_string(dir.join("c.json")).unwrap();
    (out, serde_json::from_str(&json).unwrap())
}

/// `f` on a rayon pool of `threads` threads (results that must not depend on the thread count;
/// code that splits its work only with more than one).
pub(crate) fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads);
    pool.build().unwrap().install(f)
}
