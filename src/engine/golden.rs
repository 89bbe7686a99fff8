//! Golden curves: reviewed reference curves that a scene's results must stay close to.
//!
//! A golden file is CSV with a header: `crank_deg`, then one column per roller or pin
//! (`roller_0`, ...) or one column named after the quantity (`te_arcsec`). Beside it,
//! `<file>.meta.yaml` (`te.csv` → `te.csv.meta.yaml`; older goldens have `te.meta.yaml`, still
//! read) records the spec it came from (path and SHA-256), the tool version, the date and what a
//! person reviewed. `cycloid bless` writes both together; `cycloid check` reads the CSV.
//!
//! A golden is evidence, so a broken one is an error, never a pass: a file that does not cover
//! the scene's crank range, whose angles are not evenly spaced (rows missing) or that holds a
//! non-finite value is exit 2 with its file and line. `bless` writes only under the spec's
//! directory (or the `golden_root` it declares), never over a file that is not a golden, and
//! replaces all the files of a spec or none.
//!
//! Comparison: the curve with fewer samples sets the angles compared; the other one is
//! linearly interpolated there (exactly sampled when the grids nest, e.g. 0.2° inside 0.1°).
//! A point passes when |value − golden| ≤ abs + rel·|golden|. The worst point is the one
//! furthest outside (or least inside) its band.

use crate::error::{Error, Result};
use crate::files;
use crate::model::place::{GoldenAt, Part, Place, Site};
use crate::model::quantity::Curves;
use crate::model::results::SceneResult;
use crate::model::{Golden, GoldenTolerance};
use crate::numeric;
use crate::spec::Spec;
use crate::units;
use serde::{Deserialize, Serialize};
use std::io::ErrorKind::NotFound;
use std::path::{Path, PathBuf};

/// Crank angles closer than this (degrees) are the same sample.
const SAME_ANGLE_DEG: f64 = 1e-7;

/// The content of a golden CSV file.
#[derive(Debug, Clone, PartialEq)]
pub struct GoldenCurves {
    pub crank_deg: Vec<f64>,
    pub curves: Curves,
}

/// Format a number for a golden file: 10 significant digits, shortest text that reads back
/// to that rounded value (the rounding, 5e-11 relative, is far below any sensible tolerance).
pub fn csv_number(x: f64) -> String {
    if x.is_nan() {
        return "nan".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.into();
    }
    let rounded: f64 = format!("{x:.9e}").parse().unwrap_or(x);
    if rounded == 0.0 {
        "0".into()
    } else {
        format!("{rounded}")
    }
}

impl GoldenCurves {
    /// CSV text: header, then one row per crank angle.
    pub fn to_csv(&self) -> String {
        let mut out = String::from("crank_deg");
        for c in &self.curves.columns {
            out.push(',');
            out.push_str(c);
        }
        out.push('\n');
        for (k, phi) in self.crank_deg.iter().enumerate() {
            out.push_str(&csv_number(*phi));
            for col in &self.curves.values {
                out.push(',');
                out.push_str(&csv_number(col[k]));
            }
            out.push('\n');
        }
        out
    }

    /// Parse CSV text; `name` is used in messages. Lines starting with `#` are comments.
    pub fn parse(name: &str, text: &str) -> std::result::Result<GoldenCurves, String> {
        let mut lines = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let (_, header) = lines
            .next()
            .ok_or_else(|| format!("{name}: empty file, expected a header `crank_deg,...`"))?;
        let mut names = header.split(',').map(|h| h.trim().to_string());
        if names.next().as_deref() != Some("crank_deg") {
            return Err(format!(
                "{name}:1: the first column must be `crank_deg`, got `{header}`"
            ));
        }
        let columns: Vec<String> = names.collect();
        if columns.is_empty() {
            return Err(format!("{name}:1: no value columns after `crank_deg`"));
        }
        let mut crank_deg = Vec::new();
        let mut line_of = Vec::new();
        let mut values = vec![Vec::new(); columns.len()];
        for (n, line) in lines {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            if cells.len() != columns.len() + 1 {
                return Err(format!(
                    "{name}:{}: {} cells, the header has {}",
                    n + 1,
                    cells.len(),
                    columns.len() + 1
                ));
            }
            let mut numbers = cells.iter().map(|c| match c.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(format!(
                    "{name}:{}: `{c}` is not a finite number; a golden holds computed values, \
                     which are finite",
                    n + 1
                )),
                Err(_) => Err(format!("{name}:{}: `{c}` is not a number", n + 1)),
            });
            let phi = numbers.next().unwrap_or(Ok(0.0))?;
            if !phi.is_finite() || crank_deg.last().is_some_and(|&last| phi <= last) {
                return Err(format!(
                    "{name}:{}: crank angles must be finite and increasing, got {phi}",
                    n + 1
                ));
            }
            crank_deg.push(phi);
            line_of.push(n + 1);
            for (col, v) in values.iter_mut().zip(numbers) {
                col.push(v?);
            }
        }
        if crank_deg.is_empty() {
            return Err(format!("{name}: no data rows"));
        }
        even_steps(&crank_deg).map_err(|(k, m)| format!("{name}:{}: {m}", line_of[k]))?;
        Ok(GoldenCurves {
            crank_deg,
            curves: Curves { columns, values },
        })
    }
}

/// A golden's crank angles are evenly spaced, as `bless` writes them: a missing row shows as a
/// wider step. The tolerance covers the 10-digit rounding of each angle (5e-10 relative, twice
/// for a difference) with room to spare, and is far below a doubled step. On failure, the
/// index of the angle that ends the odd step and a message.
fn even_steps(deg: &[f64]) -> std::result::Result<(), (usize, String)> {
    let (Some(&first), Some(&last)) = (deg.first(), deg.last()) else {
        return Ok(());
    };
    if deg.len() < 3 {
        return Ok(());
    }
    // The median step: rows cut out anywhere leave most steps as they were.
    let mut steps: Vec<f64> = deg.windows(2).map(|w| w[1] - w[0]).collect();
    steps.sort_by(f64::total_cmp);
    let typical = steps[steps.len() / 2];
    let slack = 1e-3 * typical + 1e-9 * first.abs().max(last.abs());
    match deg
        .windows(2)
        .position(|w| ((w[1] - w[0]) - typical).abs() > slack)
    {
        None => Ok(()),
        Some(k) => Err((
            k + 1,
            format!(
                "crank {}° follows {}°, a step of {}° where the golden's steps are {}°: rows \
                 are missing or out of place; restore the file or re-bless it",
                csv_number(deg[k + 1]),
                csv_number(deg[k]),
                csv_number(deg[k + 1] - deg[k]),
                csv_number(typical)
            ),
        )),
    }
}

/// Whether two crank angles are the same sample: within `slack`, `SAME_ANGLE_DEG` and the
/// 10-digit rounding of a golden's angles.
fn same_angle(a: f64, b: f64, slack: f64) -> bool {
    (a - b).abs() <= slack + SAME_ANGLE_DEG + 1e-9 * a.abs().max(b.abs())
}

/// One compared point.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    pub column: String,
    /// Its column's part and its angle, as compared.
    pub at: GoldenAt,
    /// The disc whose curve the golden holds (`Golden::disc`), with several discs.
    pub disc: Option<usize>,
    pub golden: f64,
    pub value: f64,
    /// |value − golden|.
    pub deviation: f64,
    /// abs + rel·|golden|.
    pub band: f64,
}

impl Point {
    /// Where it lies, for `report::place` to word.
    pub fn place(&self) -> Place {
        Place {
            disc: self.disc,
            ..Place::of(Site::Golden(self.at))
        }
    }

    /// deviation / band: ≤ 1 inside the band.
    pub fn ratio(&self) -> f64 {
        if self.deviation == 0.0 {
            0.0
        } else if self.band > 0.0 {
            self.deviation / self.band
        } else {
            f64::INFINITY
        }
    }
}

/// A whole-curve comparison.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// Number of (angle, column) points compared.
    pub points: usize,
    /// The point furthest outside (or closest to the edge of) its band.
    pub worst: Point,
    /// The point with the largest |deviation|.
    pub largest: Point,
    pub passed: bool,
}

/// The difference a − b, taken into (−period/2, period/2] for a wrapping angle.
fn difference(a: f64, b: f64, period: Option<f64>) -> f64 {
    match period {
        Some(p) if (a - b).is_finite() => {
            let d = (a - b).rem_euclid(p);
            if d > p / 2.0 {
                d - p
            } else {
                d
            }
        }
        _ => a - b,
    }
}

/// Linear interpolation of a sampled curve at x (exact at a sample). `None` outside the range.
fn interpolate(xs: &[f64], ys: &[f64], x: f64, period: Option<f64>) -> Option<f64> {
    let k = xs.partition_point(|&v| v < x - SAME_ANGLE_DEG);
    if k < xs.len() && (xs[k] - x).abs() <= SAME_ANGLE_DEG {
        return Some(ys[k]);
    }
    if k == 0 || k >= xs.len() {
        return None;
    }
    let (x0, x1) = (xs[k - 1], xs[k]);
    let w = (x - x0) / (x1 - x0);
    Some(ys[k - 1] + w * difference(ys[k], ys[k - 1], period))
}

fn deviation(value: f64, golden: f64, period: Option<f64>) -> f64 {
    if value == golden {
        0.0
    } else {
        let d = difference(value, golden, period).abs();
        if d.is_nan() {
            f64::INFINITY
        } else {
            d
        }
    }
}

/// Compare computed curves (at `now_deg`) with a golden. Errors (columns or crank ranges that
/// do not match) mean the golden does not describe this quantity any more: re-bless it.
/// `period` is the quantity's wrap-around (360 for an angle in degrees), if any; `part` what
/// column k is a curve of (`Shape::part`: roller k, pin k), if the quantity has a curve per part;
/// `disc` the disc the points name (`Point::disc`), if any.
pub fn compare(
    golden: &GoldenCurves,
    now_deg: &[f64],
    now: &Curves,
    tolerance: GoldenTolerance,
    (period, part): (Option<f64>, Option<Part>),
    disc: Option<usize>,
) -> std::result::Result<Comparison, String> {
    if golden.curves.columns != now.columns {
        return Err(format!(
            "the golden has columns [{}] but the scene computes [{}]",
            golden.curves.columns.join(", "),
            now.columns.join(", ")
        ));
    }
    let (g0, g1) = (
        golden.crank_deg[0],
        *golden.crank_deg.last().unwrap_or(&0.0),
    );
    let (r0, r1) = (now_deg[0], *now_deg.last().unwrap_or(&0.0));
    // Both curves cover the scene's range: from the same first angle to last angles at most
    // one step of the coarser apart (0.2° steps end at 107.8°, 0.1° steps at 107.9°).
    let slack = numeric::step(now_deg).max(numeric::step(&golden.crank_deg));
    if !(same_angle(g0, r0, 0.0) && same_angle(g1, r1, slack)) {
        let n = csv_number;
        return Err(format!(
            "the golden covers crank {}° to {}° ({} rows) but the scene {}° to {}° ({} angles)",
            n(g0),
            n(g1),
            golden.crank_deg.len(),
            n(r0),
            n(r1),
            now_deg.len()
        ));
    }
    // The coarser curve sets the angles; the finer one is interpolated there.
    let golden_sets = golden.crank_deg.len() <= now_deg.len();
    let mut points = 0;
    let mut worst: Option<Point> = None;
    let mut largest: Option<Point> = None;
    for (c, column) in now.columns.iter().enumerate() {
        let part = part.map(|p| (p, c));
        let (gy, ry) = (&golden.curves.values[c], &now.values[c]);
        let (base_x, base_y, other_x, other_y) = if golden_sets {
            (&golden.crank_deg[..], &gy[..], now_deg, &ry[..])
        } else {
            (now_deg, &ry[..], &golden.crank_deg[..], &gy[..])
        };
        for (&x, &b) in base_x.iter().zip(base_y) {
            let Some(o) = interpolate(other_x, other_y, x, period) else {
                continue;
            };
            let (g, v) = if golden_sets { (b, o) } else { (o, b) };
            let p = Point {
                column: column.clone(),
                at: GoldenAt { part, crank_deg: x },
                disc,
                golden: g,
                value: v,
                deviation: deviation(v, g, period),
                band: tolerance.band(g),
            };
            points += 1;
            if worst.as_ref().is_none_or(|w| p.ratio() > w.ratio()) {
                worst = Some(p.clone());
            }
            if largest.as_ref().is_none_or(|w| p.deviation > w.deviation) {
                largest = Some(p);
            }
        }
    }
    let (Some(worst), Some(largest)) = (worst, largest) else {
        return Err("the golden and the scene share no crank angle".into());
    };
    Ok(Comparison {
        points,
        passed: worst.ratio() <= 1.0,
        worst,
        largest,
    })
}

/// A golden of a spec compared with its scene.
#[derive(Debug, Clone, PartialEq)]
pub struct GoldenResult {
    pub golden: Golden,
    pub comparison: Comparison,
}

fn file_error(g: &Golden, message: String) -> Error {
    Error::invalid(format!("{}.file", g.key), message)
}

/// Read every golden file of a spec (before any computation, so a missing file fails fast).
pub fn load_all(spec: &Spec) -> Result<Vec<GoldenCurves>> {
    spec.golden
        .iter()
        .map(|g| {
            if std::fs::symlink_metadata(&g.path).is_err_and(|e| e.kind() == NotFound) {
                return Err(file_error(
                    g,
                    format!(
                        "golden file `{}` does not exist; create it with `cycloid bless {}` \
                         (paths are relative to the spec file's directory)",
                        g.path.display(),
                        spec.path
                    ),
                ));
            }
            let text = files::read_text(&g.path, "golden file", files::MAX_INPUT_BYTES)
                .map_err(|e| file_error(g, e.message))?;
            GoldenCurves::parse(&g.path.display().to_string(), &text)
                .map_err(|m| file_error(g, format!("bad golden file: {m}")))
        })
        .collect()
}

/// The computed curves of a golden's quantity, in output units, their crank angles in degrees,
/// and the disc their points name (`Point::disc`): the golden's disc when the scene has several
/// (`SceneResult::names_discs`); a one-disc reducer's disc 0 is not named, as a golden without
/// `disc` (`Place::disc`).
pub fn computed(g: &Golden, results: &[SceneResult]) -> Result<(Vec<f64>, Curves, Option<usize>)> {
    let q = g.quantity;
    let r = results
        .iter()
        .find(|r| r.name == g.scene)
        .ok_or_else(|| Error::computation(format!("scene `{}` was not run", g.scene)))?;
    // A disc's curve of the disc named (with one disc, `disc: 0` or none), else the scene's.
    let curves = match g.disc {
        Some(k) if !q.of_reducer() => r.discs.get(k).and_then(|d| q.disc_curves(d)),
        _ => q.curves(r),
    };
    let curves = curves.ok_or_else(|| {
        let message = if r.names_discs() && g.disc.is_none() {
            format!(
                "scene `{}` computed no `{}` (with {} discs a disc's curve needs `disc: k` in \
                 the golden entry)",
                g.scene,
                g.quantity,
                r.discs.len()
            )
        } else {
            super::missing::not_computed(q, r)
        };
        Error::invalid(format!("{}.quantity", g.key), message)
    })?;
    let deg = r.crank_rad.iter().map(|&a| units::deg(a)).collect();
    Ok((deg, curves, g.disc.filter(|_| r.names_discs())))
}

/// Compare every golden of a spec with the results.
pub fn evaluate(
    spec: &Spec,
    results: &[SceneResult],
    loaded: &[GoldenCurves],
) -> Result<Vec<GoldenResult>> {
    spec.golden
        .iter()
        .zip(loaded)
        .map(|(g, golden)| {
            let (deg, curves, disc) = computed(g, results)?;
            let of = (g.quantity.period(), g.quantity.shape.part());
            let comparison =
                compare(golden, &deg, &curves, g.tolerance, of, disc).map_err(|m| {
                    file_error(
                        g,
                        format!(
                            "golden file `{}` does not match scene `{}`: {m}; if the change is \
                         intended, re-bless with `cycloid bless {}`",
                            g.path.display(),
                            g.scene,
                            spec.path
                        ),
                    )
                })?;
            Ok(GoldenResult {
                golden: g.clone(),
                comparison,
            })
        })
        .collect()
}

/// The metadata file beside a golden CSV: `te.csv` → `te.csv.meta.yaml` (its whole name, so
/// `te.csv` and `te.txt` keep separate reviews).
pub fn meta_path(csv: &Path) -> PathBuf {
    let mut name = csv.file_name().unwrap_or_default().to_os_string();
    name.push(".meta.yaml");
    csv.with_file_name(name)
}

/// The metadata name of goldens blessed before `meta_path` kept the extension: `te.meta.yaml`.
/// Read (when it is about the same scene and quantity) and replaced by `meta_path` at the
/// next bless.
pub fn legacy_meta_path(csv: &Path) -> PathBuf {
    csv.with_extension("meta.yaml")
}

/// What `<name>.meta.yaml` holds. `reviewed` is written by a person; `bless` keeps it while
/// the curve stays inside its tolerance and marks it NOT REVIEWED when the curve moves out.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Meta {
    pub spec: String,
    pub spec_name: String,
    pub spec_sha256: String,
    pub scene: String,
    pub quantity: String,
    pub unit: String,
    pub crank: String,
    pub tolerance: MetaTolerance,
    pub tool_version: String,
    pub date: String,
    pub reviewed: String,
}

#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct MetaTolerance {
    pub abs: f64,
    pub rel: f64,
}

/// Placeholder review text of a golden nobody has reviewed yet.
pub const NOT_REVIEWED: &str = "NOT REVIEWED: written by `cycloid bless`; a person must check \
     these curves against an independent reason (a hand calculation, another implementation, a \
     physical law) and replace this text with what was checked";

/// Largest metadata file read, bytes: a review is a paragraph.
const MAX_META_BYTES: u64 = 1 << 20;

/// A golden's previous metadata and the file it is in: `meta_path`, else the legacy name when
/// that file describes the same scene and quantity (two goldens `te.csv` and `te.txt` once
/// shared `te.meta.yaml`).
pub fn previous_meta(g: &Golden) -> Option<(PathBuf, serde_yaml::Value)> {
    let read = |path: PathBuf| {
        let text = files::read_text(&path, "golden metadata", MAX_META_BYTES).ok()?;
        let v: serde_yaml::Value = serde_yaml::from_str(&text).ok()?;
        Some((path, v))
    };
    read(meta_path(&g.path)).or_else(|| {
        read(legacy_meta_path(&g.path)).filter(|m| {
            meta_field(Some(m), "scene").as_deref() == Some(g.scene.as_str())
                && meta_field(Some(m), "quantity").as_deref() == Some(g.quantity.key)
        })
    })
}

/// A text field of a golden's metadata (`reviewed`, `date`, `scene`), if it can be read.
fn meta_field(meta: Option<&(PathBuf, serde_yaml::Value)>, field: &str) -> Option<String> {
    meta?.1.get(field)?.as_str().map(str::to_string)
}

/// SHA-256 of a text as lowercase hex (what `sha256sum` prints for the file).
pub fn sha256_hex(text: &str) -> String {
    super::shard_file::hex(&super::shard_file::text_hash(text))
}

/// Today's date (UTC) as YYYY-MM-DD; `SOURCE_DATE_EPOCH` (seconds) overrides the clock.
pub fn today() -> String {
    let secs = std::env::var("SOURCE_DATE_EPOCH")
        .ok()
        .and_then(|s| s.trim().parse::<i64>().ok())
        .unwrap_or_else(|| {
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_secs() as i64)
        });
    // Days since 1970-01-01 to a civil date (H. Hinnant's algorithm).
    let z = secs.div_euclid(86_400) + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

/// What blessing did to one golden file.
#[derive(Debug, Clone, PartialEq)]
pub enum BlessChange {
    /// No file before.
    New,
    /// The previous file could not be compared (unreadable, other columns or range).
    Replaced(String),
    /// Compared with the previous file.
    Compared(Comparison),
}

#[derive(Debug, Clone, PartialEq)]
pub struct Blessed {
    pub golden: Golden,
    pub rows: usize,
    pub change: BlessChange,
    pub written: Written,
}

/// What `bless` wrote of one golden.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Written {
    /// The curve and its metadata: new, or moved beyond its tolerance.
    Curve,
    /// Only the metadata: the curve stayed within its tolerance, a field of its metadata (the
    /// spec's hash, path or the tolerance) was stale.
    Metadata,
    /// Nothing: the curve stayed within its tolerance and its metadata is current.
    Nothing,
}

/// Where `bless` may write: the spec's directory tree and the `golden_root` it declares.
fn bless_roots(spec: &Spec) -> Vec<PathBuf> {
    let dir = Path::new(&spec.path)
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::iter::once(dir.to_path_buf())
        .chain(spec.golden_root.clone())
        .map(|p| files::identity(&p))
        .collect()
}

/// Refuse, before anything is written, a golden that `bless` must not write: a path outside
/// `bless_roots`, an existing file that is not a golden (not a regular file, or no metadata
/// beside it: the spec itself, a drawing, someone's notes), or a path that the spec or
/// another golden's file or metadata also has.
fn check_writable(spec: &Spec) -> Result<()> {
    let roots = bless_roots(spec);
    let mut claimed = vec![(
        files::identity(Path::new(&spec.path)),
        "the spec".to_string(),
    )];
    if let Some(m) = &spec.measured {
        claimed.push((
            files::identity(Path::new(&m.path)),
            "the measured points".into(),
        ));
    }
    for g in &spec.golden {
        let id = files::identity(&g.path);
        if !roots.iter().any(|r| id.starts_with(r)) {
            let allowed: Vec<String> = roots.iter().map(|r| r.display().to_string()).collect();
            return Err(file_error(
                g,
                format!(
                    "`{}` is {}, outside {}: bless writes goldens only under the spec's \
                     directory or the `golden_root` the spec declares",
                    g.file,
                    id.display(),
                    allowed.join(" and ")
                ),
            ));
        }
        if let Ok(m) = std::fs::metadata(&g.path) {
            if !(m.is_file() && (meta_path(&g.path).is_file() || previous_meta(g).is_some())) {
                return Err(file_error(
                    g,
                    format!(
                        "`{}` exists and is not a golden (no `{}` beside it); bless does not \
                         overwrite it: move it away or name another file",
                        g.path.display(),
                        meta_path(&g.path).display()
                    ),
                ));
            }
        }
        for path in [g.path.clone(), meta_path(&g.path)] {
            let id = files::identity(&path);
            if let Some((_, what)) = claimed.iter().find(|(c, _)| *c == id) {
                return Err(file_error(
                    g,
                    format!("`{}` is also {what}", path.display()),
                ));
            }
            claimed.push((id, format!("a file of {}", g.key)));
        }
    }
    Ok(())
}

/// Rewrite every golden file of a spec from the results, each with its metadata beside it:
/// all of them or, on any error, none.
pub fn bless(spec: &Spec, results: &[SceneResult]) -> Result<Vec<Blessed>> {
    check_writable(spec)?;
    let date = today();
    let mut batch = files::Batch::default();
    let mut out = Vec::new();
    for g in &spec.golden {
        let (crank_deg, curves, disc) = computed(g, results)?;
        let period = g.quantity.period();
        let new = GoldenCurves { crank_deg, curves };
        let deg = &new.crank_deg;
        // Compare what will be written (rounded) with what was there.
        let csv = new.to_csv();
        let written = GoldenCurves::parse(&g.path.display().to_string(), &csv).map_err(|m| {
            Error::computation(format!(
                "scene `{}` computed a `{}` that cannot be a golden ({m}); nothing was blessed",
                g.scene, g.quantity
            ))
        })?;
        let change = match std::fs::metadata(&g.path) {
            Err(_) => BlessChange::New,
            Ok(_) => match files::read_text(&g.path, "golden file", files::MAX_INPUT_BYTES)
                .map_err(|e| e.message)
                .and_then(|text| GoldenCurves::parse("old", &text))
                .and_then(|old| {
                    compare(
                        &old,
                        &written.crank_deg,
                        &written.curves,
                        g.tolerance,
                        (period, g.quantity.shape.part()),
                        disc,
                    )
                }) {
                Ok(c) => BlessChange::Compared(c),
                Err(m) => BlessChange::Replaced(m),
            },
        };
        let previous = previous_meta(g);
        // A curve within its tolerance of the one there is kept as it was, with its date,
        // version and review; only a stale field of its metadata (the spec's hash, path,
        // tolerance) is brought up to date.
        let kept = matches!(&change, BlessChange::Compared(c) if c.passed);
        let old = |field: &str, now: &str| match meta_field(previous.as_ref(), field) {
            Some(old) if kept => old,
            _ => now.to_string(),
        };
        let date = old("date", &date);
        let reviewed = match (kept, meta_field(previous.as_ref(), "reviewed")) {
            (true, Some(old)) => old,
            (_, Some(old)) if !old.starts_with("NOT REVIEWED") => format!(
                "NOT REVIEWED since {date}: the curve moved outside its tolerance when blessed. \
                 Previous review: {old}"
            ),
            _ => NOT_REVIEWED.to_string(),
        };
        let meta = Meta {
            // The path it was blessed by, as given then: how a later run names it is no change.
            spec: old("spec", &spec.path),
            spec_name: spec.name.clone(),
            spec_sha256: sha256_hex(&spec.source),
            scene: g.scene.clone(),
            quantity: g.quantity.to_string(),
            unit: g.quantity.unit.to_string(),
            crank: format!(
                "{} angles from {}° to {}°",
                deg.len(),
                csv_number(deg[0]),
                csv_number(*deg.last().unwrap_or(&0.0))
            ),
            tolerance: MetaTolerance {
                abs: g.tolerance.abs,
                rel: g.tolerance.rel,
            },
            tool_version: old("tool_version", env!("CARGO_PKG_VERSION")),
            date,
            reviewed,
        };
        if let Some(dir) = g.path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| Error::io(&dir.display().to_string(), e))?;
        }
        let meta_text =
            serde_yaml::to_string(&meta).map_err(|e| Error::computation(e.to_string()))?;
        let meta_now = meta_path(&g.path);
        // A review under the legacy name moves to the current one.
        let legacy = previous.map(|(old, _)| old).filter(|old| *old != meta_now);
        let meta_same = legacy.is_none()
            && std::fs::read_to_string(&meta_now).is_ok_and(|old| old == meta_text);
        let written = match (kept, meta_same) {
            (true, true) => Written::Nothing,
            (true, false) => Written::Metadata,
            (false, _) => Written::Curve,
        };
        if written == Written::Curve {
            batch.add(&g.path, csv.as_bytes())?;
        }
        if written != Written::Nothing {
            batch.add(&meta_now, meta_text.as_bytes())?;
        }
        if let Some(old) = legacy {
            batch.remove(&old);
        }
        out.push(Blessed {
            golden: g.clone(),
            rows: deg.len(),
            change,
            written,
        });
    }
    batch.commit()?;
    Ok(out)
}
