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
}

impl Series {
    pub fn new(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>, color: &str) -> Self {
        Series {
            name: name.into(),
            x,
            y,
            color: color.to_string(),
            dashed: false,
        }
    }
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

    /// Legend entries: (swatch colour, dashed, text, width of the swatch's line).
    fn legend(&self) -> Vec<(&str, Option<&str>, &str, f64)> {
        let curves = self.series.iter().filter(|s| !s.name.is_empty());
        let mut out: Vec<_> = curves
            .map(|s| {
                (
                    s.color.as_str(),
                    s.dashed.then_some("5 3"),
                    s.name.as_str(),
                    2.5,
                )
            })
            .collect();
        if out.len() < 2 && self.ref_lines.is_empty() {
            return Vec::new();
        }
        out.extend(
            self.ref_lines
                .iter()
                .filter(|r| !r.label.is_empty())
                .map(|r| (r.color.as_str(), Some("7 4"), r.label.as_str(), 1.5)),
        );
        out
    }

    /// The plot as a standalone SVG document.
    pub fn to_svg(&self) -> String {
        let (xt, yt) = self.axes();
        let label_w = widest(yt.values.iter().map(|&v| yt.label(v)));
        let legend = self.legend();
        let legend_w = legend
            .iter()
            .map(|e| text_width(e.2, 12.0) + 44.0)
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
        let sx = |x: f64| a.left + (x - xt.lo) / (xt.hi - xt.lo) * a.width;
        let sy = |y: f64| a.top + a.height - (y - yt.lo) / (yt.hi - yt.lo) * a.height;
        let body = html! {
            (frame::titles(left, &self.title, &subtitle))
            @for &v in &yt.values {
                line x1=(px(a.left)) y1=(px(sy(v))) x2=(px(a.right())) y2=(px(sy(v)))
                    stroke="#e3e3e3" {}
                text x=(px(a.left - 6.0)) y=(px(sy(v) + 4.0)) font-size="12" text-anchor="end" {
                    (yt.label(v))
                }
            }
            @for &v in &xt.values {
                line x1=(px(sx(v))) y1=(px(a.top)) x2=(px(sx(v))) y2=(px(a.bottom() + 5.0))
                    stroke="#e3e3e3" {}
                text x=(px(sx(v))) y=(px(a.bottom() + 19.0)) font-size="12"
                    text-anchor="middle" { (xt.label(v)) }
            }
            @if yt.lo < 0.0 && yt.hi > 0.0 {
                line x1=(px(a.left)) y1=(px(sy(0.0))) x2=(px(a.right())) y2=(px(sy(0.0)))
                    stroke="#999" {}
            }
            (a.outline())
            (frame::axis_labels(&a, h - 12.0, &self.x_label, &self.y_label))
            (a.clip("area", 0.0))
            g clip-path="url(#area)" fill="none" stroke-width="1.6" stroke-linejoin="round" {
                @for r in &self.ref_lines {
                    line x1=(px(a.left)) y1=(px(sy(r.value))) x2=(px(a.right()))
                        y2=(px(sy(r.value))) stroke=(r.color) stroke-width="1.5"
                        stroke-dasharray="7 4" {}
                }
                @for s in &self.series {
                    @for run in runs(&s.x, &s.y) {
                        polyline stroke=(s.color) stroke-dasharray=[s.dashed.then_some("5 3")]
                            points=(points(run.into_iter().map(|(x, y)| (sx(x), sy(y))))) {}
                    }
                }
            }
            @for (k, (color, dash, text, width)) in legend.iter().enumerate() {
                @let (x, y) = (a.right() + 14.0, top + 8.0 + ROW * k as f64);
                line x1=(px(x)) y1=(px(y)) x2=(px(x + 22.0)) y2=(px(y)) stroke=(color)
                    stroke-width=(width) stroke-dasharray=[dash] {}
                text x=(px(x + 28.0)) y=(px(y + 4.0)) font-size="12" { (text) }
            }
        };
        document(self.width, h, body)
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
