//! Reading measured points: CSV from a measuring machine, or a DXF drawing of the disc.
//!
//! CSV (RFC 4180 quoting, read by the `csv` crate): `#` comment lines, then a header naming the
//! columns, of which `x_mm` and `y_mm` are required and `feature` optional (other columns are
//! ignored, so `cycloid profile --csv` output reads back); each row a point, `feature`
//! `profile` (the default) or `hole:J`.
//! DXF: the vertices of closed LWPOLYLINE and POLYLINE entities are profile points (an open
//! one is refused at its line, not skipped); a closed SPLINE gives its fit points when it has
//! them (they lie on the curve), else points of the curve itself (`spline_sample_count`,
//! `spline::Spline`, rational or not); a CIRCLE on layer `HOLE_J` is the bore of hole J, read
//! as 72 points on it. The drawing's unit (`$INSUNITS`) must be millimetres (4) or unitless
//! (0, or no `$INSUNITS`: the numbers are read as mm); the file ends at `EOF`, after which only
//! whitespace may follow. Text that is not UTF-8 is decoded as `encoding` says.
//! Errors name the file and line (exit 2). A file gives at most `MAX_POINTS` points.

use super::encoding::{self, Fallback};
use super::{Feature, MeasuredPoint};
use crate::error::{Error, Location, Result};
use crate::geometry::{unit, Vec2};
use crate::model::measured::PointsFormat;
use std::f64::consts::TAU;

/// Points read from a circle of a DXF drawing.
pub const CIRCLE_POINTS: usize = 72;

/// Points read per control point of a SPLINE without fit points: a cubic span between two
/// knots is then sampled at 32 points, its chords within (span/32)²·κ/8 of the curve — below a
/// nanometre for the spans of a disc profile (the points lie on the curve; the chords do not
/// enter the fit).
pub const SPLINE_POINTS_PER_CONTROL: usize = 32;

/// Most points a SPLINE without fit points is sampled at, unless it has more control points
/// (then one per control point): 2^16 points on the curve are 3 µm apart along the paper's
/// 191 mm profile, far denser than any fit needs, and a CAD export of thousands of control
/// points (spans of a few µm) gains nothing from 32 points per span.
pub const SPLINE_POINTS_MAX: usize = 1 << 16;

/// Highest SPLINE degree read: de Boor's algorithm costs p² operations per point, and CAD
/// programs write degrees 1 to 10 (AutoCAD's range); 32 leaves room and bounds the cost.
pub const MAX_SPLINE_DEGREE: usize = 32;

/// Most points a measured-points file may give (profile and holes, every CSV row, polyline
/// vertex and spline or circle point): 10^7. A CMM scan of a disc holds thousands to tens of
/// thousands of points, an optical scan millions; 10^7 points take 400 MB (40 bytes each) beside
/// the file's text (`MAX_FILE_BYTES`), and the fit thins a denser profile to what its Jacobian
/// holds (`thinning`, `fit::MAX_JACOBIAN_ENTRIES`).
pub const MAX_POINTS: usize = 10_000_000;

/// Largest measured-points file read, bytes: `MAX_POINTS` CSV rows of 48 bytes (two
/// coordinates of ~20 characters, a comma, a line end and room for a short `feature`), 480 MB.
/// Other inputs keep `files::MAX_INPUT_BYTES`.
pub const MAX_FILE_BYTES: u64 = 48 * MAX_POINTS as u64;

/// The points of a file.
pub fn read(path: &str, format: PointsFormat) -> Result<Vec<MeasuredPoint>> {
    let bytes = crate::files::read_bytes(
        std::path::Path::new(path),
        "measured profile",
        MAX_FILE_BYTES,
    )?;
    match format {
        PointsFormat::Csv => {
            let text = encoding::decode(&bytes, Fallback::Replace);
            parse_csv_at_most(path, &text, MAX_POINTS)
        }
        PointsFormat::Dxf => {
            let text = encoding::decode(&bytes, encoding::dxf_fallback(&bytes));
            parse_dxf_at_most(path, &text, MAX_POINTS)
        }
    }
}

fn at(path: &str, line: usize, message: String) -> Error {
    Error::invalid_value(message).at(Location::new(path, line, 1))
}

/// The error of one point more than `max` (`MAX_POINTS`), at the line that gave it.
fn too_many(path: &str, line: usize, max: usize) -> Error {
    at(
        path,
        line,
        format!(
            "more than {max} measured points: a file gives at most {max} (a CMM scan of a \
             disc holds thousands to tens of thousands, an optical scan millions; the fit \
             thins a denser profile itself); thin the points, e.g. every k-th"
        ),
    )
}

/// `feature` of a row: `profile` or `hole:J`.
fn feature(text: &str) -> Option<Feature> {
    match text.trim() {
        "" | "profile" => Some(Feature::Profile),
        other => other
            .strip_prefix("hole:")
            .and_then(|j| j.trim().parse().ok())
            .map(Feature::Hole),
    }
}

/// The records of a CSV text with the line each starts on, one at a time: fields unquoted
/// (RFC 4180) and trimmed, comment lines (`#`, after any blanks) and blank lines left out.
fn csv_records<'t>(
    path: &'t str,
    text: &'t str,
) -> impl Iterator<Item = Result<(usize, csv::StringRecord)>> + 't {
    let reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .from_reader(text.as_bytes());
    reader.into_records().filter_map(move |record| {
        let record = match record {
            Ok(record) => record,
            Err(e) => {
                let line = e.position().map_or(1, |p| p.line() as usize);
                return Some(Err(at(path, line, format!("not a CSV row: {e}"))));
            }
        };
        let line = record.position().map_or(1, |p| p.line() as usize);
        let blank = record.iter().all(str::is_empty);
        let comment = record.get(0).is_some_and(|f| f.starts_with('#'));
        (!blank && !comment).then_some(Ok((line, record)))
    })
}

/// The points of a CSV text, refusing more than `max` (`read` gives `MAX_POINTS`; a parameter
/// so that the bound is tested without a file of 10^7 rows).
pub fn parse_csv_at_most(path: &str, text: &str, max: usize) -> Result<Vec<MeasuredPoint>> {
    let mut rows = csv_records(path, text);
    let (header_line, header) = rows
        .next()
        .transpose()?
        .ok_or_else(|| at(path, 1, "the file has no header line and no points".into()))?;
    let column = |name: &str| header.iter().position(|n| n == name);
    let (Some(x), Some(y)) = (column("x_mm"), column("y_mm")) else {
        let header = header.iter().collect::<Vec<_>>().join(",");
        return Err(at(
            path,
            header_line,
            format!("the header `{header}` must name the columns x_mm and y_mm (and optionally feature)"),
        ));
    };
    let f = column("feature");
    let mut points = Vec::new();
    for row in rows {
        let (line, cells) = row?;
        if points.len() == max {
            return Err(too_many(path, line, max));
        }
        let number = |c: usize, name: &str| -> Result<f64> {
            let cell = cells.get(c).unwrap_or("");
            cell.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    at(
                        path,
                        line,
                        format!("{name} `{cell}` is not a finite number"),
                    )
                })
        };
        let point = Vec2::new(number(x, "x_mm")?, number(y, "y_mm")?);
        let cell = f.and_then(|c| cells.get(c)).unwrap_or("");
        let feature = feature(cell).ok_or_else(|| {
            at(
                path,
                line,
                format!("feature `{cell}` is neither `profile` nor `hole:J` (J the hole's number from 0)"),
            )
        })?;
        points.push(MeasuredPoint {
            point,
            feature,
            line,
        });
    }
    Ok(points)
}

/// A group code, its value and the line of the code.
type Pair<'a> = (usize, i32, &'a str);

/// The group-code/value pairs of a DXF file, with the line of each code, up to the pair
/// `0 EOF`. After it only whitespace may follow (an editor's blank line); anything else is
/// refused at its line: a second drawing appended to the file would otherwise be dropped
/// unseen.
fn pairs<'a>(path: &str, text: &'a str) -> Result<Vec<Pair<'a>>> {
    let mut lines = text.lines().enumerate();
    let mut out = Vec::new();
    while let Some((i, code)) = lines.next() {
        let line = i + 1;
        let code = code.trim().parse::<i32>().map_err(|_| {
            at(
                path,
                line,
                format!("`{}` is not a DXF group code", code.trim()),
            )
        })?;
        let value = lines.next().map_or("", |(_, v)| v.trim());
        out.push((line, code, value));
        if code == 0 && value == "EOF" {
            if let Some((i, after)) = lines.find(|(_, l)| !l.trim().is_empty()) {
                return Err(at(
                    path,
                    i + 1,
                    format!(
                        "`{}` after the end of the drawing (`EOF` at line {}): a DXF file \
                         ends at EOF; remove what follows, or split a second drawing into its \
                         own file",
                        after.trim(),
                        line + 1
                    ),
                ));
            }
            break;
        }
    }
    Ok(out)
}

/// The names of the DXF drawing units, by their `$INSUNITS` code (AutoCAD DXF reference).
const UNITS: [&str; 25] = [
    "unitless",
    "inches",
    "feet",
    "miles",
    "millimetres",
    "centimetres",
    "metres",
    "kilometres",
    "microinches",
    "mils",
    "yards",
    "ångströms",
    "nanometres",
    "microns",
    "decimetres",
    "decametres",
    "hectometres",
    "gigametres",
    "astronomical units",
    "light years",
    "parsecs",
    "US survey feet",
    "US survey inches",
    "US survey yards",
    "US survey miles",
];

/// The drawing's unit (`9 $INSUNITS`, then group 70) must be millimetres (4). Unitless (0) or
/// no `$INSUNITS` (an R12 drawing has none) leaves the numbers without a unit: they are read
/// as mm, the unit of the measured points. Any other unit is refused at its line, naming it:
/// the points would be read as mm and scaled by its ratio to mm.
fn require_mm(path: &str, all: &[Pair<'_>]) -> Result<()> {
    let Some(k) = all.iter().position(|p| p.1 == 9 && p.2 == "$INSUNITS") else {
        return Ok(());
    };
    let Some(&(line, _, value)) = all.get(k + 1).filter(|p| p.1 == 70) else {
        return Err(at(
            path,
            all[k].0,
            "$INSUNITS without its group 70 value".into(),
        ));
    };
    let code = value.parse::<i64>().ok();
    if matches!(code, Some(0 | 4)) {
        return Ok(());
    }
    let unit = code
        .and_then(|c| usize::try_from(c).ok())
        .and_then(|c| UNITS.get(c))
        .map_or_else(|| "an unknown unit".to_string(), |u| (*u).to_string());
    Err(at(
        path,
        line + 1,
        format!(
            "the drawing is in {unit} ($INSUNITS {value}): measured points are read in \
             millimetres ($INSUNITS 4, or 0 for unitless numbers read as mm); export the \
             drawing in mm"
        ),
    ))
}

/// One entity of the ENTITIES section: its type, first line and the pairs up to the next.
struct Entity<'a> {
    kind: &'a str,
    line: usize,
    pairs: &'a [Pair<'a>],
}

impl Entity<'_> {
    fn value(&self, code: i32) -> Option<&str> {
        self.pairs.iter().find(|p| p.1 == code).map(|p| p.2)
    }

    fn number(&self, path: &str, code: i32) -> Result<f64> {
        let (line, _, v) = self.pairs.iter().find(|p| p.1 == code).ok_or_else(|| {
            at(
                path,
                self.line,
                format!("{} without group code {code}", self.kind),
            )
        })?;
        parse_number(path, *line, v)
    }

    fn closed(&self) -> bool {
        self.value(70)
            .and_then(|v| v.parse::<i32>().ok())
            .is_some_and(|flags| flags & 1 == 1)
    }

    /// The (line, x, y) of every 10/20 pair.
    fn vertices(&self, path: &str) -> Result<Vec<(usize, Vec2)>> {
        self.pairs_of(path, (10, 20))
    }

    /// The (line, x, y) of every pair of the codes (x, y).
    fn pairs_of(&self, path: &str, (cx, cy): (i32, i32)) -> Result<Vec<(usize, Vec2)>> {
        let mut out = Vec::new();
        let mut x = None;
        for (line, code, v) in self.pairs {
            if *code == cx {
                x = Some((*line, parse_number(path, *line, v)?));
            } else if *code == cy {
                if let Some((l, xv)) = x.take() {
                    out.push((l, Vec2::new(xv, parse_number(path, *line, v)?)));
                }
            }
        }
        Ok(out)
    }

    /// Every value of group `code`, as numbers.
    fn numbers(&self, path: &str, code: i32) -> Result<Vec<f64>> {
        self.pairs
            .iter()
            .filter(|p| p.1 == code)
            .map(|(line, _, v)| parse_number(path, *line, v))
            .collect()
    }

    /// A SPLINE's profile points: its fit points, or points of the curve
    /// (`spline_sample_count`); `room` is how many more points the file may give.
    fn spline_points(&self, path: &str, room: usize, max: usize) -> Result<Vec<(usize, Vec2)>> {
        let fit = self.pairs_of(path, (11, 21))?;
        let refuse = |m: String| at(path, self.line, m);
        if fit.len() >= 3 {
            let closed = self.closed() || (fit[0].1 - fit[fit.len() - 1].1).norm() < 1e-9;
            if !closed {
                return Err(refuse(OPEN_SPLINE.into()));
            }
            return Ok(fit);
        }
        let control: Vec<Vec2> = self.vertices(path)?.into_iter().map(|(_, p)| p).collect();
        let mut weights = self.numbers(path, 41)?;
        if weights.is_empty() {
            weights = vec![1.0; control.len()];
        }
        let degree = self.number(path, 71)?;
        if !(degree >= 1.0 && degree <= MAX_SPLINE_DEGREE as f64 && degree.fract() == 0.0) {
            return Err(refuse(format!(
                "a SPLINE of degree {degree}: the degree is a whole number 1 to \
                 {MAX_SPLINE_DEGREE} (CAD programs write 1 to 10; each point costs degree² \
                 operations)"
            )));
        }
        let spline = super::spline::Spline {
            degree: degree as usize,
            knots: self.numbers(path, 40)?,
            control,
            weights,
        };
        if let Some(problem) = spline.problem() {
            return Err(refuse(format!("a SPLINE that is no B-spline: {problem}")));
        }
        if !spline.is_closed() {
            return Err(refuse(OPEN_SPLINE.into()));
        }
        let count = spline_sample_count(spline.control.len());
        if count > room {
            return Err(too_many(path, self.line, max));
        }
        Ok(spline
            .sample(count)
            .into_iter()
            .map(|p| (self.line, p))
            .collect())
    }
}

/// The points a SPLINE of `control` control points (and no fit points) is read as:
/// `SPLINE_POINTS_PER_CONTROL` per control point, at most `SPLINE_POINTS_MAX` unless the
/// spline has more control points, then one per control point.
pub fn spline_sample_count(control: usize) -> usize {
    (SPLINE_POINTS_PER_CONTROL * control).min(SPLINE_POINTS_MAX.max(control))
}

/// What an open SPLINE is told.
const OPEN_SPLINE: &str = "an open SPLINE (its ends apart): profile points are read from one \
     closed curve; close it in the CAD program, or delete it if it is not the disc outline";

/// The number of the value `v` of the pair whose code is at `line`, finite.
fn parse_number(path: &str, line: usize, v: &str) -> Result<f64> {
    v.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| at(path, line + 1, format!("`{v}` is not a finite number")))
}

fn entities<'a>(all: &'a [Pair<'a>]) -> Vec<Entity<'a>> {
    (all.chunk_by(|_, next| next.1 != 0))
        .filter(|e| e[0].1 == 0)
        .map(|e| Entity {
            kind: e[0].2,
            line: e[0].0,
            pairs: &e[1..],
        })
        .collect()
}

/// The points of a DXF text, refusing more than `max` (`MAX_POINTS`), as `parse_csv_at_most`.
pub fn parse_dxf_at_most(path: &str, text: &str, max: usize) -> Result<Vec<MeasuredPoint>> {
    let all = pairs(path, text)?;
    require_mm(path, &all)?;
    let mut list = entities(&all).into_iter().peekable();
    let mut points = Vec::new();
    let mut closed_profiles = 0;
    while let Some(e) = list.next() {
        match e.kind {
            "LWPOLYLINE" => {
                refuse_open(path, &e)?;
                closed_profiles += 1;
                push_profile(&mut points, e.vertices(path)?);
            }
            "SPLINE" => {
                closed_profiles += 1;
                let room = max.saturating_sub(points.len());
                push_profile(&mut points, e.spline_points(path, room, max)?);
            }
            "POLYLINE" => {
                refuse_open(path, &e)?;
                closed_profiles += 1;
                let mut vertices = Vec::new();
                while let Some(v) = list.next_if(|v| v.kind == "VERTEX") {
                    vertices.extend(v.vertices(path)?);
                }
                push_profile(&mut points, vertices);
            }
            "CIRCLE" => {
                let layer = e.value(8).unwrap_or("");
                let j = layer
                    .strip_prefix("HOLE_")
                    .and_then(|j| j.parse::<usize>().ok())
                    .ok_or_else(|| {
                        at(
                            path,
                            e.line,
                            format!(
                                "a CIRCLE on layer `{layer}`: circles are read as pin holes and \
                                 must be on layer HOLE_J (J the hole's number from 0)"
                            ),
                        )
                    })?;
                let centre = Vec2::new(e.number(path, 10)?, e.number(path, 20)?);
                let radius = e.number(path, 40)?;
                for k in 0..CIRCLE_POINTS {
                    let a = TAU * k as f64 / CIRCLE_POINTS as f64;
                    points.push(MeasuredPoint {
                        point: centre + unit(a) * radius,
                        feature: Feature::Hole(j),
                        line: e.line,
                    });
                }
            }
            _ => {}
        }
        if points.len() > max {
            return Err(too_many(path, e.line, max));
        }
    }
    if closed_profiles == 0 {
        return Err(at(
            path,
            1,
            "the drawing has no closed LWPOLYLINE, POLYLINE or SPLINE: the disc profile must be \
             one closed curve"
                .into(),
        ));
    }
    Ok(points)
}

/// An open polyline is not read as profile points, and not skipped either (its points would
/// vanish from the fit unseen): the file is refused at its line.
fn refuse_open(path: &str, e: &Entity<'_>) -> Result<()> {
    if e.closed() {
        return Ok(());
    }
    Err(at(
        path,
        e.line,
        format!(
            "an open {} (group 70 without its closed bit): profile points are read from one \
             closed polyline; close it in the CAD program, or delete it if it is not the disc \
             outline",
            e.kind
        ),
    ))
}

fn push_profile(points: &mut Vec<MeasuredPoint>, vertices: Vec<(usize, Vec2)>) {
    points.extend(vertices.into_iter().map(|(line, point)| MeasuredPoint {
        point,
        feature: Feature::Profile,
        line,
    }));
}
