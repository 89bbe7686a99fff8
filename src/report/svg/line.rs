//! Line plots: curves over a shared x axis with nice ticks, grid, axis labels, dashed
//! reference lines (limits) and a legend to the right that grows the figure rather than clip.

use super::base::{document, points, px, span, text_width, widest};
use super::frame::{self, Area};
use super::ticks::{self, ticks, Ticks};
use maud::html;

/// One curve of a line plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub name: String,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub color: String,
    pub dashed: bool,
    /// Drawn as a mark per point, no line (a few samples, which a line would pass off as a
    /// smooth curve), or a line.
    pub marks: Option<Mark>,
}

/// The mark of a point of a series drawn as points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mark {
    /// A filled dot.
    Dot,
    /// An open diamond (a point singled out on a curve).
    Diamond,
}

impl Series {
    pub fn new(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>, color: &str) -> Self {
        Series {
            name: name.into(),
            x,
            y,
            color: color.to_string(),
            dashed: false,
            marks: None,
        }
    }

    /// The same series drawn as marks.
    pub fn marked(self, mark: Mark) -> Self {
        Series {
            marks: Some(mark),
            ..self
        }
    }
}

/// An axis label: the quantity and its unit in parentheses, "max roller force (N)", or the
/// quantity alone without a unit (a ratio).
pub fn axis_label(name: &str, unit: &str) -> String {
    match unit {
        "" => name.to_string(),
        unit => format!("{name} ({unit})"),
    }
}

/// A cut in the y axis: the values between `lo` and `hi` (a band with no data, e.g. a
/// torsion curve's dead band) are left out, the axis drawn as two panels, the lower spanning
/// the data up to `lo` and the upper from `hi`, each with its own ticks; the cut is marked on
/// the frame (zigzags), bracketed at `at_x` and labelled `label`.
#[derive(Debug, Clone, PartialEq)]
pub struct YCut {
    pub lo: f64,
    pub hi: f64,
    pub at_x: f64,
    pub label: String,
}

/// A horizontal reference line (a limit), drawn dashed with its label in the legend.
#[derive(Debug, Clone, PartialEq)]
pub struct RefLine {
    pub value: f64,
    pub label: String,
    pub color: String,
}

/// A line plot with axes, ticks, axis labels, legend and title.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LinePlot {
    pub title: String,
    /// A second, smaller line under the title (what is not shown, how it was computed).
    pub subtitle: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub ref_lines: Vec<RefLine>,
    pub width: f64,
    pub height: f64,
    /// Fixed x tick step (e.g. 6° over a 36° mesh period), or automatic.
    pub x_step: Option<f64>,
    /// Keep y = 0 inside the axis (forces, clearances).
    pub include_zero: bool,
    /// Fixed x range (e.g. the whole crank range, whose end is not a sample), or the data's.
    pub x_range: Option<(f64, f64)>,
    /// A cut in the y axis, applied when each panel's ticks stay on its side of the cut.
    pub y_cut: Option<YCut>,
}

/// Height of the cut between the panels of a cut y axis, pixels.
const CUT_PX: f64 = 34.0;

/// The y axis: one range, or two panels around a cut.
enum YAxis {
    Whole(Ticks),
    Cut { lower: Ticks, upper: Ticks },
}

/// Height of one legend entry, pixels.
const ROW: f64 = 18.0;

impl LinePlot {
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        LinePlot {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            width: 660.0,
            height: 400.0,
            ..Default::default()
        }
    }

    /// The x and y axes: the data's range (or `x_range`), the reference lines and zero when
    /// asked for inside, no reference line on the frame.
    fn axes(&self) -> (Ticks, Ticks) {
        let (x0, x1) = self
            .x_range
            .filter(|(a, b)| b > a)
            .or_else(|| span(self.series.iter().flat_map(|s| &s.x)))
            .unwrap_or((0.0, 1.0));
        let refs = self.ref_lines.iter().map(|r| &r.value);
        let zero = self.include_zero.then_some(&0.0);
        let ys = self
            .series
            .iter()
            .flat_map(|s| &s.y)
            .chain(refs)
            .chain(zero);
        let (y0, y1) = span(ys).unwrap_or((0.0, 1.0));
        let xt = match self.x_step {
            Some(step) if step > 0.0 => ticks::every(x0, x1, step),
            _ => ticks(x0, x1, 7, false),
        };
        let mut yt = ticks(y0, y1, 6, true);
        // No limit and no extreme of a curve on the frame, where it would hide (zero, the
        // floor of forces, may sit on it).
        let levels = self.ref_lines.iter().map(|r| r.value).chain([y1, y0]);
        for v in levels.filter(|v| *v != 0.0) {
            yt.clear_of(v);
        }
        (xt, yt)
    }

    /// The y axis: the whole range, or with `y_cut` two panels, each with nice ticks over the
    /// data on its side of the cut (both panels must stay on their side, else no cut).
    fn y_axis(&self, whole: Ticks) -> YAxis {
        let Some(cut) = &self.y_cut else {
            return YAxis::Whole(whole);
        };
        let ys = self.series.iter().flat_map(|s| &s.y);
        let below = span(ys.clone().filter(|&&v| v <= cut.lo));
        let above = span(ys.filter(|&&v| v >= cut.hi));
        let (Some((l0, l1)), Some((u0, u1))) = (below, above) else {
            return YAxis::Whole(whole);
        };
        let (lower, upper) = (ticks(l0, l1, 3, true), ticks(u0, u1, 3, true));
        if lower.hi < upper.lo {
            YAxis::Cut { lower, upper }
        } else {
            YAxis::Whole(whole)
        }
    }

    /// Legend entries: (swatch colour, dashed, text, width of the swatch's line, mark).
    fn legend(&self) -> Vec<Entry<'_>> {
        let curves = self.series.iter().filter(|s| !s.name.is_empty());
        let mut out: Vec<_> = curves
            .map(|s| Entry {
                color: &s.color,
                dash: s.dashed.then_some("5 3"),
                text: &s.name,
                width: 2.5,
                mark: s.marks,
            })
            .collect();
        if out.len() < 2 && self.ref_lines.is_empty() {
            return Vec::new();
        }
        out.extend(
            self.ref_lines
                .iter()
                .filter(|r| !r.label.is_empty())
                .map(|r| Entry {
                    color: &r.color,
                    dash: Some("7 4"),
                    text: &r.label,
                    width: 1.5,
                    mark: None,
                }),
        );
        out
    }

    /// The plot as a standalone SVG document.
    pub fn to_svg(&self) -> String {
        let (xt, whole) = self.axes();
        let y_axis = self.y_axis(whole);
        let tick_sets: Vec<&Ticks> = match &y_axis {
            YAxis::Whole(t) => vec![t],
            YAxis::Cut { lower, upper } => vec![lower, upper],
        };
        let label_w = tick_sets
            .iter()
            .map(|t| widest(t.values.iter().map(|&v| t.label(v))))
            .fold(0.0, f64::max);
        let legend = self.legend();
        let legend_w = legend
            .iter()
            .map(|e| text_width(e.text, 12.0) + 44.0)
            .fold(0.0, f64::max);
        let (left, bottom) = (label_w + 42.0, 52.0);
        let subtitle = frame::wrap(&self.subtitle, self.width - left - 8.0);
        let top = frame::top(subtitle.len());
        // The figure grows to hold a long subtitle and every legend entry.
        let h = (self.height + (top - frame::top(1)).max(0.0))
            .max(top + 16.0 + ROW * legend.len() as f64);
        let a = Area {
            left,
            top,
            width: self.width - left - 16.0 - legend_w,
            height: h - top - bottom,
        };
        // The panels, (ticks, area) from the bottom up.
        let panels: Vec<(&Ticks, Area)> = match &y_axis {
            YAxis::Whole(t) => vec![(t, a)],
            YAxis::Cut { lower, upper } => {
                let height = (a.height - CUT_PX) / 2.0;
                let upper_area = Area { height, ..a };
                let lower_area = Area {
                    top: a.top + height + CUT_PX,
                    height,
                    ..a
                };
                vec![(lower, lower_area), (upper, upper_area)]
            }
        };
        let sx = |x: f64| a.left + (x - xt.lo) / (xt.hi - xt.lo) * a.width;
        let in_panel = |y: f64, (t, p): &(&Ticks, Area)| {
            p.top + p.height - (y - t.lo) / (t.hi - t.lo) * p.height
        };
        // Below the cut in the lower panel, above it in the upper, across it straight from the
        // one to the other (monotonic: a step through the cut is drawn through the gap).
        let sy = |y: f64| match panels.as_slice() {
            [lower, upper] if y > lower.0.hi && y < upper.0.lo => {
                let t = (y - lower.0.hi) / (upper.0.lo - lower.0.hi);
                lower.1.top + t * (upper.1.bottom() - lower.1.top)
            }
            [lower, upper] if y >= upper.0.lo => in_panel(y, upper),
            [only, ..] => in_panel(y, only),
            [] => a.bottom(),
        };
        let cut = match (&y_axis, &self.y_cut) {
            (YAxis::Cut { .. }, Some(c)) => Some(c),
            _ => None,
        };
        let body = html! {
            (frame::titles(left, &self.title, &subtitle))
            @for (t, p) in &panels {
                @for &v in &t.values {
                    @let y = in_panel(v, &(t, *p));
                    line x1=(px(p.left)) y1=(px(y)) x2=(px(p.right())) y2=(px(y))
                        stroke="#e3e3e3" {}
                    text x=(px(p.left - 6.0)) y=(px(y + 4.0)) font-size="12" text-anchor="end" {
                        (t.label(v))
                    }
                }
                @if t.lo < 0.0 && t.hi > 0.0 {
                    @let y = in_panel(0.0, &(t, *p));
                    line x1=(px(p.left)) y1=(px(y)) x2=(px(p.right())) y2=(px(y)) stroke="#999" {}
                }
            }
            @for &v in &xt.values {
                line x1=(px(sx(v))) y1=(px(a.top)) x2=(px(sx(v))) y2=(px(a.bottom() + 5.0))
                    stroke="#e3e3e3" {}
                text x=(px(sx(v))) y=(px(a.bottom() + 19.0)) font-size="12"
                    text-anchor="middle" { (xt.label(v)) }
            }
            @for (_, p) in &panels { (p.outline()) }
            @if let (Some(c), [lower, upper]) = (cut, panels.as_slice()) {
                (cut_marks(c, &a, (upper.1.bottom(), lower.1.top), sx(c.at_x), (sy(c.lo), sy(c.hi))))
            }
            (frame::axis_labels(&a, h - 12.0, &self.x_label, &self.y_label))
            (a.clip("area", 0.0))
            // Marks on the frame (the first and last angle) drawn whole.
            (a.clip("marks", 6.0))
            g clip-path="url(#area)" fill="none" stroke-width="1.6" stroke-linejoin="round" {
                @for r in &self.ref_lines {
                    line x1=(px(a.left)) y1=(px(sy(r.value))) x2=(px(a.right()))
                        y2=(px(sy(r.value))) stroke=(r.color) stroke-width="1.5"
                        stroke-dasharray="7 4" {}
                }
            }
            g fill="none" stroke-width="1.6" stroke-linejoin="round" {
                @for s in &self.series {
                    g.series aria-label=[(!s.name.is_empty()).then_some(&s.name)]
                        clip-path=(if s.marks.is_some() { "url(#marks)" } else { "url(#area)" }) {
                        @for run in runs(&s.x, &s.y) {
                            @let pts: Vec<(f64, f64)> = run.into_iter().map(|(x, y)| (sx(x), sy(y))).collect();
                            @match s.marks {
                                Some(m) => @for &(x, y) in &pts { (mark(m, x, y, &s.color)) },
                                None => polyline stroke=(s.color)
                                    stroke-dasharray=[s.dashed.then_some("5 3")]
                                    points=(points(pts)) {},
                            }
                        }
                    }
                }
            }
            @for (k, e) in legend.iter().enumerate() {
                @let (x, y) = (a.right() + 14.0, top + 8.0 + ROW * k as f64);
                @match e.mark {
                    Some(m) => (mark(m, x + 11.0, y, e.color)),
                    None => line x1=(px(x)) y1=(px(y)) x2=(px(x + 22.0)) y2=(px(y))
                        stroke=(e.color) stroke-width=(e.width) stroke-dasharray=[e.dash] {},
                }
                text x=(px(x + 28.0)) y=(px(y + 4.0)) font-size="12" { (e.text) }
            }
        };
        document(self.width, h, body)
    }
}

/// A legend entry: the swatch's colour, dashes, line width or mark, and the text.
struct Entry<'a> {
    color: &'a str,
    dash: Option<&'a str>,
    text: &'a str,
    width: f64,
    mark: Option<Mark>,
}

/// A point's mark at (x, y), pixels: a dot 3 px in radius, or an open diamond 4.5 px.
fn mark(m: Mark, x: f64, y: f64, color: &str) -> maud::Markup {
    match m {
        Mark::Dot => html! {
            circle.mark cx=(px(x)) cy=(px(y)) r="3" fill=(color) stroke="none" {}
        },
        Mark::Diamond => html! {
            path.mark d=(format!("M{},{} l4.5,4.5 l-4.5,4.5 l-4.5,-4.5 Z", px(x), px(y - 4.5)))
                fill="none" stroke=(color) stroke-width="1.5" {}
        },
    }
}

/// The marks of a cut y axis: the gap between the panels (from `gap.0` down to `gap.1`)
/// zigzagged on both edges, a bracket from the cut's `lo` to `hi` (pixels `span`) at x, and
/// the cut's label beside it.
fn cut_marks(c: &YCut, a: &Area, gap: (f64, f64), x: f64, span: (f64, f64)) -> maud::Markup {
    let zigzag = |edge: f64| {
        let mid = (gap.0 + gap.1) / 2.0;
        points([
            (edge, gap.0),
            (edge - 5.0, mid - 5.0),
            (edge + 5.0, mid + 5.0),
            (edge, gap.1),
        ])
    };
    let (y_lo, y_hi) = span;
    // The side of the bracket with more room, the text made smaller (down to 9 px) to fit it.
    let (right, left) = (a.right() - 8.0 - (x + 12.0), x - 12.0 - (a.left + 8.0));
    let (lx, anchor, room) = if right >= left {
        (x + 12.0, "start", right)
    } else {
        (x - 12.0, "end", left)
    };
    let size = (12.0 * room / text_width(&c.label, 12.0)).clamp(9.0, 12.0);
    html! {
        g.cut fill="none" stroke="#555" {
            polyline points=(zigzag(a.left)) {}
            polyline points=(zigzag(a.right())) {}
            path d=(format!("M{},{} h6 V{} h-6", px(x), px(y_lo), px(y_hi))) stroke-width="1.2" {}
        }
        text.cut-label x=(px(lx)) y=(px((gap.0 + gap.1) / 2.0 + 4.0)) font-size=(px(size))
            text-anchor=(anchor) fill="#333" { (c.label) }
    }
}

/// Split a curve into runs of finite points (a gap where a value is missing or infinite).
fn runs(x: &[f64], y: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let points: Vec<(f64, f64)> = x.iter().copied().zip(y.iter().copied()).collect();
    let runs = points.split(|(a, b)| !(a.is_finite() && b.is_finite()));
    runs.filter(|run| !run.is_empty())
        .map(<[_]>::to_vec)
        .collect()
}
