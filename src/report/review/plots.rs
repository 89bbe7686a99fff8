//! The plots of one scene, driven by the quantity registry ([`model::quantity`](crate::model::quantity)). Each plot
//! names the registry's curves it draws and is left out when the scene computed none of them;
//! axis labels, units and legend names are the registry's; the subtitle gives the registry's
//! scalars of the drawn curves (`Quantity::of`: the smallest gap, the largest force, ... and
//! where); and every limit of the spec on such a scalar is drawn on its curve: a level as a
//! dashed red line, a spread (max − min, `quantity::SPREADS`) as a band of the limit's width
//! centred on the curve. More than `MAX_CURVES` curves of one quantity (one per roller) are
//! drawn as their envelope over the parts, with a part × crank heat map beside it.

use crate::model::quantity::{self as q, Curves, Of, Quantity, QUANTITIES, SPREADS};
use crate::model::results::{DiscResult, SceneResult};
use crate::numeric::{extremes, with_unit};
use crate::report::place;
use crate::report::svg::{
    axis_label, LinePlot, MapCell, MapPlot, Mark, RefLine, Series, PALETTE, RED,
};
use crate::report::table::figure;
use crate::spec::Spec;
use crate::units;

/// One figure of the report: its file, title, caption and SVG.
pub struct Plot {
    pub file: String,
    pub title: String,
    pub caption: String,
    pub svg: String,
}

/// More curves than this in one plot become an envelope and a heat map.
pub const MAX_CURVES: usize = 10;

/// Fewer crank angles than this are drawn as a mark per angle, not a line (a line through a
/// few locked angles would pass off as a curve over the mesh), and the title says how many.
pub const SPARSE_ANGLES: usize = 12;

/// A ripple under this fraction of the mean's magnitude is small (see `ripple_in_title`).
pub const SMALL_RIPPLE: f64 = 0.01;

/// A plot of registry curves over the crank angle.
struct PlotDef {
    /// The file name's last part.
    name: &'static str,
    title: &'static str,
    /// The curves drawn, in legend order.
    curves: &'static [&'static Quantity],
    /// Keys of the curves drawn dashed.
    dashed: &'static [&'static str],
    /// The y axis's name when the plot shows several quantities (their unit is added), else
    /// the first curve's label.
    y_label: Option<&'static str>,
    /// Values in µm rather than the registry's mm (a clearance of micrometres).
    micrometres: bool,
    /// Keep y = 0 inside the axis.
    include_zero: bool,
    /// A further reference line (the nominal ratio).
    reference: Option<fn(&Spec) -> RefLine>,
    /// Scaled for what the curve is, not for its ripple: when the ripple (max − min) is under
    /// `SMALL_RIPPLE` of the mean's magnitude, y = 0 is kept inside the axis, so that the curve
    /// reads as the near-constant it is, and the title states the ripple.
    ripple_in_title: bool,
    /// A scene at speed (`inertia`) says so in the title: the speed and the centripetal
    /// force the curve includes.
    speed_in_title: bool,
    caption: &'static str,
}

/// What a plot has unless it says otherwise: no dashed curve, the first curve's y label, the
/// registry's units, y = 0 not forced in, no further reference line.
const PLOT: PlotDef = PlotDef {
    name: "",
    title: "",
    curves: &[],
    dashed: &[],
    y_label: None,
    micrometres: false,
    include_zero: false,
    reference: None,
    ripple_in_title: false,
    speed_in_title: false,
    caption: "",
};

const PLOTS: &[PlotDef] = &[
    PlotDef {
        name: "torque-share",
        title: "Disc torque share",
        curves: &[&q::DISC_TORQUE],
        include_zero: true,
        caption: "The disc's share Tk of the output torque (MODEL.md \"Several discs\"): the \
                  discs' shares sum to T at every crank angle, and every disc has the \
                  reducer's output lag.",
        ..PLOT
    },
    PlotDef {
        name: "clearance",
        title: "Clearance per roller",
        curves: &[&q::CLEARANCE],
        micrometres: true,
        caption: "Normal gap of every roller to the modified profile at the ideal disc pose (no \
                  load); negative is interference.",
        ..PLOT
    },
    PlotDef {
        name: "backlash",
        title: "Backlash and lost motion (no load)",
        curves: &[&q::BACKLASH, &q::BACKLASH_REVERSE, &q::LOST_MOTION],
        dashed: &[q::BACKLASH_REVERSE.key],
        y_label: Some("angle"),
        include_zero: true,
        caption: "Disc rotation needed to close the first gap in the load direction (backlash), \
                  in the reverse direction, and their sum (lost motion).",
        ..PLOT
    },
    PlotDef {
        name: "roller-forces",
        title: "Roller forces",
        curves: &[&q::ROLLER_FORCE],
        include_zero: true,
        caption: "Contact force of every roller on the disc.",
        ..PLOT
    },
    PlotDef {
        name: "pressure",
        title: "Hertz peak pressure",
        curves: &[&q::CONTACT_PRESSURE],
        include_zero: true,
        caption: "p0 = sqrt(F·E*/(π·L·R*)) with the profile's local curvature at the contact.",
        ..PLOT
    },
    PlotDef {
        name: "face-load-factor",
        title: "Face load factor",
        curves: &[&q::FACE_LOAD_FACTOR],
        reference: Some(|_| RefLine {
            value: 1.0,
            label: "uniform face = 1".into(),
            color: "#7f7f7f".into(),
        }),
        caption: "Peak line load along the face over the rollers divided by the mean line load \
                  F/B of the roller that carries it, at each crank angle (1 on a uniform face; \
                  0 where no roller carries a force).",
        ..PLOT
    },
    PlotDef {
        name: "contacts",
        title: "Rollers in contact",
        curves: &[&q::CONTACTS],
        include_zero: true,
        caption: "Rollers carrying load at each crank angle.",
        ..PLOT
    },
    PlotDef {
        name: "te",
        title: "Loaded transmission error",
        curves: &[&q::TE],
        caption: "Lag of the output behind its ideal angle φ/nc under the scene's torque: disc \
                  lag β at the rollers plus output lag βo at the pins. The axis spans the TE \
                  alone, so that its ripple fills the plot; βo has its own plot.",
        ..PLOT
    },
    // βo on its own axis: on the TE's it would stretch the axis and flatten the TE ripple.
    PlotDef {
        name: "output-lag",
        title: "Output lag at the pins",
        curves: &[&q::OUTPUT_LAG],
        caption: "Output lag βo at the pins under the scene's torque, the part of the TE the \
                  output pins add. When its ripple is under 1 % of its mean, the axis starts at \
                  zero and the title gives the ripple.",
        ripple_in_title: true,
        ..PLOT
    },
    PlotDef {
        name: "ratio",
        title: "Transmission ratio",
        curves: &[&q::RATIO],
        reference: Some(|spec| RefLine {
            value: spec.design.teeth as f64,
            label: format!("nominal nc = {}", spec.design.teeth),
            color: "#7f7f7f".into(),
        }),
        caption: "κ = 1/(1/nc − dδ/dφ) by central differences; its harmonic mean over whole \
                  mesh periods is nc.",
        ..PLOT
    },
    PlotDef {
        name: "bearing-force",
        title: "Crank-bearing force",
        curves: &[&q::BEARING_FORCE],
        include_zero: true,
        speed_in_title: true,
        caption: "Magnitude of the force of the crank bearing on the disc, −(Σ roller + Σ pin \
                  forces), and at speed (effect inertia) the pull m·(e+de)·ω² that keeps the \
                  disc's centre on its orbit.",
        ..PLOT
    },
    PlotDef {
        name: "bearing-angle",
        title: "Crank-bearing force direction",
        curves: &[&q::BEARING_ANGLE],
        caption: "Direction of the bearing force, counter-clockwise from the eccentric \
                  direction (cos φ, sin φ).",
        ..PLOT
    },
    PlotDef {
        name: "pin-forces",
        title: "Output-pin forces",
        curves: &[&q::PIN_FORCE],
        include_zero: true,
        caption: "Force of every output pin on its hole; pins whose moment arm is negative \
                  carry no load.",
        ..PLOT
    },
];

/// A quantity's values as the plot shows them: (unit, conversion from the registry's unit).
fn shown(def: &PlotDef, unit: &'static str) -> (&'static str, fn(f64) -> f64) {
    if def.micrometres && unit == "mm" {
        ("µm", units::um)
    } else {
        (unit, |v| v)
    }
}

/// A value of `q` (in the registry's unit) as `def` shows it, with its unit ("-23.41 µm", "2").
fn shown_value(def: &PlotDef, q: &Quantity, value: f64) -> String {
    let (unit, convert) = shown(def, q.unit);
    with_unit(figure(q, convert(value)), unit)
}

/// Tick step of the crank axis: a sixth of a mesh period over one period, half a period over
/// a few, automatic beyond.
fn mesh_step(spec: &Spec, x: &[f64]) -> Option<f64> {
    let span = (x.last()? - x.first()?) * x.len() as f64 / (x.len() as f64 - 1.0).max(1.0);
    let period = units::deg(spec.design.mesh_period_rad());
    if span <= 1.5 * period {
        Some(period / 6.0)
    } else if span <= 4.5 * period {
        Some(period / 2.0)
    } else {
        None
    }
}

/// The crank axis of a scene, degrees, and its whole range (its end is not a sample: it wraps
/// to the start).
fn crank_axis(r: &SceneResult) -> (Vec<f64>, Option<(f64, f64)>) {
    let x: Vec<f64> = r.crank_rad.iter().map(|&a| units::deg(a)).collect();
    let range = match x.as_slice() {
        [a, b, ..] => Some((*a, a + (b - a) * x.len() as f64)),
        _ => None,
    };
    (x, range)
}

/// Every plot of a scene, or of its disc `disc` alone (`Some`: that disc's curves only, the
/// scene's being the reducer's and its only disc's); files are named `{prefix}-{plot}.svg`.
/// `at_speed`: what a scene at speed adds to the title of the plots that include the
/// centripetal force (`report::mass_properties::bearing_plot_note`).
pub fn scene_plots(
    spec: &Spec,
    (r, disc): (&SceneResult, Option<&DiscResult>),
    prefix: &str,
    at_speed: Option<&str>,
) -> Vec<Plot> {
    let of = Of { r, disc };
    PLOTS
        .iter()
        .flat_map(|def| plot(spec, of, def, prefix, at_speed))
        .collect()
}

/// One plot (and its heat map when the curves are too many), or nothing when the scene did not
/// compute its curves.
fn plot(spec: &Spec, of: Of<'_>, def: &PlotDef, prefix: &str, at_speed: Option<&str>) -> Vec<Plot> {
    let drawn: Vec<(&Quantity, Curves)> = def
        .curves
        .iter()
        .filter_map(|&q| Some((q, of.curves(q)?)))
        .collect();
    let Some((first, _)) = drawn.first() else {
        return Vec::new();
    };
    let (unit, convert) = shown(def, first.unit);
    let name = def.y_label.unwrap_or(first.label);
    let y_label = axis_label(name, unit);
    let (x, x_range) = crank_axis(of.r);
    let sparse = x.len() < SPARSE_ANGLES;
    let mut title = def.title.to_string();
    if sparse {
        title += &format!(" at {}", place::counted(x.len(), "crank angle"));
    }
    if let (true, Some(note)) = (def.speed_in_title, at_speed) {
        title += &format!(" {note}");
    }
    let small = def.ripple_in_title.then(|| small_ripple(&drawn)).flatten();
    if let Some(ripple) = small {
        title += &format!(" (ripple {})", shown_value(def, first, ripple));
    }
    let mut p = LinePlot::new(&title, "crank angle φ (deg)", &y_label);
    p.x_step = mesh_step(spec, &x);
    p.x_range = x_range;
    p.include_zero = def.include_zero || small.is_some();
    let mut notes = vec![def.caption.to_string()];
    let mut maps = Vec::new();
    for (k, (q, c)) in drawn.iter().enumerate() {
        let rows: Vec<Vec<f64>> = c
            .values
            .iter()
            .map(|row| row.iter().map(|&v| convert(v)).collect())
            .collect();
        match q.shape.per() {
            Some(part) if rows.len() > MAX_CURVES => {
                p.series.extend(envelope(&x, &rows, part));
                notes.push(format!(
                    "The {} {part}s are drawn as their envelope, the largest and smallest value \
                     over the {part}s at each angle; the heat map shows every {part}.",
                    rows.len()
                ));
                maps.push(heat_map(def, &x, &rows, part, &y_label, prefix));
            }
            Some(part) => {
                let (series, note) = per_part(&x, &rows, part);
                p.series.extend(series);
                notes.extend(note);
            }
            None => {
                let color = PALETTE[k % PALETTE.len()];
                let series = Series::new(q.label, x.clone(), rows[0].clone(), color);
                let dashed = def.dashed.contains(&q.key);
                p.series.push(Series { dashed, ..series });
            }
        }
    }
    if sparse {
        for s in &mut p.series {
            s.marks = Some(if s.dashed { Mark::Diamond } else { Mark::Dot });
        }
    }
    p.subtitle = scalars(of, &drawn, def);
    let limits = limit_lines(spec, &drawn, def);
    if !limits.is_empty() {
        notes.push("Dashed red: the spec's limits on these curves.".into());
    }
    p.ref_lines = limits;
    p.ref_lines.extend(def.reference.map(|line| line(spec)));
    let plot = Plot {
        file: format!("{prefix}-{}.svg", def.name),
        title,
        caption: notes.join(" "),
        svg: p.to_svg(),
    };
    std::iter::once(plot).chain(maps).collect()
}

/// The ripple (max − min over every drawn value, the registry's unit) when it is under
/// `SMALL_RIPPLE` of the mean's magnitude, else none.
fn small_ripple(drawn: &[(&Quantity, Curves)]) -> Option<f64> {
    let values: Vec<f64> = drawn
        .iter()
        .flat_map(|(_, c)| c.values.iter().flatten().copied())
        .filter(|v| v.is_finite())
        .collect();
    if values.is_empty() {
        return None;
    }
    let ((lo, _), (hi, _)) = extremes(&values);
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    (hi - lo < SMALL_RIPPLE * mean.abs()).then_some(hi - lo)
}

/// One curve per part, named `part i`; parts that are zero everywhere are left out and named
/// in the note.
fn per_part(x: &[f64], rows: &[Vec<f64>], part: &str) -> (Vec<Series>, Option<String>) {
    let mut series = Vec::new();
    let mut idle = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        if row.iter().all(|v| *v == 0.0) {
            idle.push(i.to_string());
        } else {
            let (name, color) = (format!("{part} {i}"), PALETTE[i % PALETTE.len()]);
            series.push(Series::new(name, x.to_vec(), row.clone(), color));
        }
    }
    let note = (!idle.is_empty()).then(|| {
        format!(
            "{}s without load over the sweep (not drawn): {}.",
            capitalised(part),
            idle.join(", ")
        )
    });
    (series, note)
}

/// `word` with its first letter upper-case.
pub(crate) fn capitalised(word: &str) -> String {
    let mut chars = word.chars();
    chars
        .next()
        .map_or(String::new(), |c| c.to_uppercase().chain(chars).collect())
}

/// The largest and the smallest value over the parts at each angle (the smallest is zero
/// everywhere for forces when some part is always idle: drawn all the same, so that the plot
/// says so).
fn envelope(x: &[f64], rows: &[Vec<f64>], part: &str) -> Vec<Series> {
    let over = |pick: fn(f64, f64) -> f64, start: f64| -> Vec<f64> {
        (0..x.len())
            .map(|k| rows.iter().map(|row| row[k]).fold(start, pick))
            .collect()
    };
    let largest = over(f64::max, f64::NEG_INFINITY);
    let smallest = over(f64::min, f64::INFINITY);
    [
        (format!("largest over the {part}s"), largest, PALETTE[0]),
        (format!("smallest over the {part}s"), smallest, PALETTE[1]),
    ]
    .into_iter()
    .map(|(name, y, color)| Series::new(name, x.to_vec(), y, color))
    .collect()
}

/// A part × crank heat map of per-part curves, `{prefix}-{plot}-map.svg`.
fn heat_map(
    def: &PlotDef,
    x: &[f64],
    rows: &[Vec<f64>],
    part: &str,
    z_label: &str,
    prefix: &str,
) -> Plot {
    let cells = rows
        .iter()
        .enumerate()
        .flat_map(|(i, row)| {
            row.iter().zip(x).map(move |(&z, &x)| MapCell {
                x,
                y: i as f64,
                z,
                feasible: true,
            })
        })
        .collect();
    let title = format!("{}: every {part}", def.title);
    let plot = MapPlot {
        subtitle: format!("{} {part}s × {} crank angles", rows.len(), x.len()),
        ..MapPlot::of_cells(&title, "crank angle φ (deg)", part, z_label, cells)
    };
    Plot {
        file: format!("{prefix}-{}-map.svg", def.name),
        caption: format!(
            "One row per {part}, one column per crank angle; the colour is the {z_label}."
        ),
        title,
        svg: plot.to_svg(),
    }
}

/// The registry's scalars of the drawn curves, with where they occur, for the subtitle.
fn scalars(of: Of<'_>, drawn: &[(&Quantity, Curves)], def: &PlotDef) -> String {
    QUANTITIES
        .iter()
        .filter(|s| drawn.iter().any(|(q, _)| s.of == Some(q.key)))
        .filter_map(|s| {
            let e = of.scalar(s)?;
            let value = shown_value(def, s, e.value);
            Some(format!("{} {value}: {}", s.label, place::text(&e.at)))
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The spec's limits on scalars of the drawn curves: a level as a line at the limit, a spread
/// as a band of the limit's width centred on the curve's mid-range.
fn limit_lines(spec: &Spec, drawn: &[(&Quantity, Curves)], def: &PlotDef) -> Vec<RefLine> {
    let mut lines = Vec::new();
    for limit in &spec.limits.entries {
        let scalar = limit.def.quantity;
        let Some((_, curves)) = drawn.iter().find(|(c, _)| Some(c.key) == scalar.of) else {
            continue;
        };
        let (_, convert) = shown(def, scalar.unit);
        let line = |value: f64, label: String| RefLine {
            value,
            label,
            color: RED.into(),
        };
        let shown_limit = shown_value(def, scalar, limit.value);
        if SPREADS.contains(&scalar) {
            let values: Vec<f64> = curves.values.concat();
            let ((lo, _), (hi, _)) = extremes(&values);
            let (mid, half) = (convert((lo + hi) / 2.0), convert(limit.value) / 2.0);
            lines.push(line(
                mid + half,
                format!("limit: max − min ≤ {shown_limit}"),
            ));
            lines.push(line(mid - half, String::new()));
        } else {
            lines.push(line(convert(limit.value), format!("limit {shown_limit}")));
        }
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The envelope of three parts, by hand: the largest and smallest at each angle.
    #[test]
    fn the_envelope_is_the_largest_and_smallest_over_the_parts() {
        let rows = vec![
            vec![1.0, 5.0, -2.0],
            vec![3.0, 2.0, 0.0],
            vec![0.0, 4.0, -1.0],
        ];
        let e = envelope(&[0.0, 1.0, 2.0], &rows, "roller");
        assert_eq!(e.len(), 2);
        assert_eq!(
            (e[0].name.as_str(), &e[0].y[..]),
            ("largest over the rollers", &[3.0, 5.0, 0.0][..])
        );
        assert_eq!(
            (e[1].name.as_str(), &e[1].y[..]),
            ("smallest over the rollers", &[0.0, 2.0, -2.0][..])
        );
    }
}
