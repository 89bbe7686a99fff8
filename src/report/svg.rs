//! A small SVG plotting kit for the design-review report: line plots with axes, ticks, tick
//! labels, axis labels with units, a legend and a title; a heat map with a colour bar; and a
//! world-to-pixel frame for drawings in mm. No dependencies, plain SVG 1.1 text.

use std::fmt::Write;

/// Ten colours that stay apart (the "tab10" set).
pub const PALETTE: [&str; 10] = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
    "#bcbd22", "#17becf",
];

pub const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

/// Escape text for SVG/XML.
pub fn esc(text: &str) -> String {
    crate::report::junit::escape(text)
}

/// A pixel coordinate with two decimals (enough for any screen, keeps files small).
pub fn px(x: f64) -> String {
    let s = format!("{x:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

/// Rough width of text in pixels (for layout only).
pub fn text_width(text: &str, size: f64) -> f64 {
    text.chars().count() as f64 * size * 0.58
}

/// Axis ticks at 1, 2, 2.5 or 5 × 10^k covering [lo, hi].
#[derive(Debug, Clone, PartialEq)]
pub struct Ticks {
    pub lo: f64,
    pub hi: f64,
    pub step: f64,
    pub values: Vec<f64>,
    pub decimals: usize,
}

/// Nice ticks for the range [lo, hi], about `target` of them. With `expand` the range grows
/// to the outer ticks; otherwise it stays and only inner ticks are kept.
pub fn ticks(mut lo: f64, mut hi: f64, target: usize, expand: bool) -> Ticks {
    if !(lo.is_finite() && hi.is_finite()) {
        lo = 0.0;
        hi = 1.0;
    }
    if hi - lo <= f64::EPSILON * lo.abs().max(hi.abs()).max(1e-300) * 16.0 {
        // A flat curve: open a band around it.
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.05 };
        lo -= pad;
        hi += pad;
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let (first, last) = if expand {
        ((lo / step).floor() * step, (hi / step).ceil() * step)
    } else {
        (
            (lo / step - 1e-9).ceil() * step,
            (hi / step + 1e-9).floor() * step,
        )
    };
    let n = ((last - first) / step).round() as i64;
    let values: Vec<f64> = (0..=n.max(0))
        .map(|k| {
            let v = first + k as f64 * step;
            if v.abs() < step * 1e-9 {
                0.0
            } else {
                v
            }
        })
        .collect();
    let mut decimals = (-step.log10().floor()).max(0.0) as usize;
    if ((step / 10f64.powi(-(decimals as i32))) - (step / 10f64.powi(-(decimals as i32))).round())
        .abs()
        > 1e-6
    {
        decimals += 1;
    }
    let (lo, hi) = if expand { (first, last) } else { (lo, hi) };
    Ticks {
        lo,
        hi,
        step,
        values,
        decimals,
    }
}

impl Ticks {
    pub fn label(&self, v: f64) -> String {
        let s = format!("{v:.*}", self.decimals);
        if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
            s[1..].to_string()
        } else {
            s.replace('-', "−")
        }
    }
}

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

/// A horizontal reference line (a limit), drawn dashed with its label.
#[derive(Debug, Clone, PartialEq)]
pub struct RefLine {
    pub value: f64,
    pub label: String,
    pub color: String,
}

/// A line plot with axes, ticks, axis labels, legend and title.
#[derive(Debug, Clone, PartialEq)]
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

impl LinePlot {
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        LinePlot {
            title: title.into(),
            subtitle: String::new(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            ref_lines: Vec::new(),
            width: 660.0,
            height: 400.0,
            x_step: None,
            include_zero: false,
            x_range: None,
        }
    }

    fn ranges(&self) -> (f64, f64, f64, f64) {
        let finite = |v: &f64| v.is_finite();
        let xs = self
            .series
            .iter()
            .flat_map(|s| s.x.iter())
            .filter(|v| finite(v));
        let (mut x0, mut x1) = (f64::INFINITY, f64::NEG_INFINITY);
        for &x in xs {
            x0 = x0.min(x);
            x1 = x1.max(x);
        }
        let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
        for &y in self
            .series
            .iter()
            .flat_map(|s| s.y.iter())
            .filter(|v| finite(v))
        {
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        for r in &self.ref_lines {
            y0 = y0.min(r.value);
            y1 = y1.max(r.value);
        }
        if self.include_zero {
            y0 = y0.min(0.0);
            y1 = y1.max(0.0);
        }
        if !x0.is_finite() {
            (x0, x1) = (0.0, 1.0);
        }
        if let Some((a, b)) = self.x_range.filter(|(a, b)| b > a) {
            (x0, x1) = (a, b);
        }
        if !y0.is_finite() {
            (y0, y1) = (0.0, 1.0);
        }
        (x0, x1, y0, y1)
    }

    /// The plot as a standalone SVG document.
    pub fn to_svg(&self) -> String {
        let (x0, x1, y0, y1) = self.ranges();
        let xt = match self.x_step {
            Some(step) if step > 0.0 => {
                let mut t = ticks(x0, x1, 6, false);
                let first = (x0 / step - 1e-9).ceil() * step;
                t.values = (0..)
                    .map(|k| first + k as f64 * step)
                    .take_while(|v| *v <= x1 + 1e-9)
                    .collect();
                t.step = step;
                t.decimals = if step.fract() == 0.0 { 0 } else { 1 };
                t
            }
            _ => ticks(x0, x1, 7, false),
        };
        let yt = ticks(y0, y1, 6, true);
        let label_w = yt
            .values
            .iter()
            .map(|v| text_width(&yt.label(*v), 12.0))
            .fold(0.0, f64::max);
        let legend: Vec<&Series> = self.series.iter().filter(|s| !s.name.is_empty()).collect();
        let show_legend = legend.len() > 1 || !self.ref_lines.is_empty();
        let legend_w = if show_legend {
            let names = legend.iter().map(|s| s.name.as_str());
            let refs = self.ref_lines.iter().map(|r| r.label.as_str());
            names
                .chain(refs)
                .map(|n| text_width(n, 12.0))
                .fold(0.0, f64::max)
                + 44.0
        } else {
            0.0
        };
        let top = if self.subtitle.is_empty() { 44.0 } else { 62.0 };
        let (left, right, bottom) = (label_w + 42.0, 16.0 + legend_w, 52.0);
        let (w, h) = (self.width, self.height);
        let (pw, ph) = (w - left - right, h - top - bottom);
        let sx = |x: f64| left + (x - xt.lo) / (xt.hi - xt.lo) * pw;
        let sy = |y: f64| top + ph - (y - yt.lo) / (yt.hi - yt.lo) * ph;
        let mut s = header(w, h);
        titles(&mut s, left, &self.title, &self.subtitle);
        // Grid, ticks and tick labels.
        for &v in &yt.values {
            let y = sy(v);
            let _ = writeln!(
                s,
                r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#e3e3e3"/><text x="{}" y="{}" font-size="12" text-anchor="end">{}</text>"##,
                px(left),
                px(left + pw),
                px(left - 6.0),
                px(y + 4.0),
                esc(&yt.label(v)),
                y = px(y)
            );
        }
        for &v in &xt.values {
            let x = sx(v);
            let _ = writeln!(
                s,
                r##"<line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="#e3e3e3"/><text x="{x}" y="{}" font-size="12" text-anchor="middle">{}</text>"##,
                px(top),
                px(top + ph + 5.0),
                px(top + ph + 19.0),
                esc(&xt.label(v)),
                x = px(x)
            );
        }
        if yt.lo < 0.0 && yt.hi > 0.0 {
            let _ = writeln!(
                s,
                r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#999"/>"##,
                px(left),
                px(left + pw),
                y = px(sy(0.0))
            );
        }
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#333"/>"##,
            px(left),
            px(top),
            px(pw),
            px(ph)
        );
        // Axis labels (with units, as given).
        axis_labels(
            &mut s,
            (left, top, pw, ph),
            h - 12.0,
            &self.x_label,
            &self.y_label,
        );
        // Curves, clipped to the plot area.
        let _ = writeln!(
            s,
            r#"<clipPath id="area"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath><g clip-path="url(#area)" fill="none" stroke-width="1.6" stroke-linejoin="round">"#,
            px(left),
            px(top),
            px(pw),
            px(ph)
        );
        for r in &self.ref_lines {
            let _ = writeln!(
                s,
                r#"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="{}" stroke-width="1.5" stroke-dasharray="7 4"/>"#,
                px(left),
                px(left + pw),
                r.color,
                y = px(sy(r.value))
            );
        }
        for series in &self.series {
            for run in polyline_runs(&series.x, &series.y) {
                let pts: Vec<String> = run
                    .iter()
                    .map(|&(x, y)| format!("{},{}", px(sx(x)), px(sy(y))))
                    .collect();
                let dash = if series.dashed {
                    r#" stroke-dasharray="5 3""#
                } else {
                    ""
                };
                let _ = writeln!(
                    s,
                    r#"<polyline stroke="{}"{dash} points="{}"/>"#,
                    series.color,
                    pts.join(" ")
                );
            }
        }
        s += "</g>\n";
        if show_legend {
            let lx = left + pw + 14.0;
            let mut ly = top + 8.0;
            for series in legend {
                let dash = if series.dashed {
                    r#" stroke-dasharray="5 3""#
                } else {
                    ""
                };
                let _ = writeln!(
                    s,
                    r#"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="{}" stroke-width="2.5"{dash}/><text x="{}" y="{}" font-size="12">{}</text>"#,
                    px(lx),
                    px(lx + 22.0),
                    series.color,
                    px(lx + 28.0),
                    px(ly + 4.0),
                    esc(&series.name),
                    y = px(ly)
                );
                ly += 18.0;
            }
            for r in &self.ref_lines {
                let _ = writeln!(
                    s,
                    r#"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="{}" stroke-width="1.5" stroke-dasharray="7 4"/><text x="{}" y="{}" font-size="12">{}</text>"#,
                    px(lx),
                    px(lx + 22.0),
                    r.color,
                    px(lx + 28.0),
                    px(ly + 4.0),
                    esc(&r.label),
                    y = px(ly)
                );
                ly += 18.0;
            }
        }
        s += "</svg>\n";
        s
    }
}

/// Split a curve into runs of finite points (a gap where a value is missing or infinite).
fn polyline_runs(x: &[f64], y: &[f64]) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for (&a, &b) in x.iter().zip(y) {
        if a.is_finite() && b.is_finite() {
            runs.last_mut().expect("one run").push((a, b));
        } else if !runs.last().expect("one run").is_empty() {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// The opening of a standalone SVG document with a white background.
pub fn header(w: f64, h: f64) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\" font-family=\"{FONT}\" fill=\"#222\">\n\
         <rect width=\"{w}\" height=\"{h}\" fill=\"white\"/>\n",
        w = px(w),
        h = px(h)
    )
}

/// Viridis colour map, t in [0, 1].
pub fn viridis(t: f64) -> String {
    const STOPS: [(f64, f64, f64); 9] = [
        (68.0, 1.0, 84.0),
        (71.0, 44.0, 122.0),
        (59.0, 81.0, 139.0),
        (44.0, 113.0, 142.0),
        (33.0, 144.0, 141.0),
        (39.0, 173.0, 129.0),
        (92.0, 200.0, 99.0),
        (170.0, 220.0, 50.0),
        (253.0, 231.0, 37.0),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let f = t * (STOPS.len() - 1) as f64;
    let k = (f.floor() as usize).min(STOPS.len() - 2);
    let w = f - k as f64;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    let mix = |p: f64, q: f64| (p + w * (q - p)).round() as u8;
    format!(
        "#{:02x}{:02x}{:02x}",
        mix(a.0, b.0),
        mix(a.1, b.1),
        mix(a.2, b.2)
    )
}

/// One cell of an objective map: the objective `z` at (x, y), non-finite when the point could
/// not be evaluated (a design rule), and whether it satisfies every constraint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapCell {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub feasible: bool,
}

/// The symbol of a map marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    Circle,
    Diamond,
    Star,
}

/// A labelled point on a map (a start, an optimum, a published value).
#[derive(Debug, Clone, PartialEq)]
pub struct Marker {
    pub x: f64,
    pub y: f64,
    pub label: String,
    pub color: String,
    pub shape: Shape,
}

/// A map of an objective over two variables: cells coloured by the objective (a log scale when
/// it spans more than `LOG_SPAN`), infeasible cells washed out and hatched, further sample
/// points, a path, labelled markers, a colour bar and a legend under the axes.
#[derive(Debug, Clone, PartialEq)]
pub struct MapPlot {
    pub title: String,
    /// A second, smaller line under the title.
    pub subtitle: String,
    pub x_label: String,
    pub y_label: String,
    pub z_label: String,
    /// Samples on a grid; drawn as cells through the distinct x and y values.
    pub cells: Vec<MapCell>,
    /// Further evaluated points (x, y, feasible), e.g. a global sample.
    pub samples: Vec<(f64, f64, bool)>,
    /// Legend text of the samples.
    pub samples_label: String,
    /// A path in order (e.g. the iterates of a local search).
    pub path: Vec<(f64, f64)>,
    /// Legend text of the path.
    pub path_label: String,
    pub markers: Vec<Marker>,
    /// Colour range; default: the feasible cells' objective (every cell's when none is).
    pub z_range: Option<(f64, f64)>,
    pub width: f64,
}

/// The colour scale turns logarithmic when the largest objective exceeds the smallest (> 0)
/// by this factor.
pub const LOG_SPAN: f64 = 20.0;

/// Draws a legend swatch with its left edge at x, centred on y.
type Swatch<'a> = Box<dyn Fn(f64, f64) -> String + 'a>;

const HATCH: &str = r##"<defs><pattern id="hatch" width="7" height="7" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="7" height="7" fill="white" fill-opacity="0.55"/><line x1="0" y1="0" x2="0" y2="7" stroke="white" stroke-width="2.5"/></pattern></defs>"##;

fn distinct(mut v: Vec<f64>) -> Vec<f64> {
    v.retain(|x| x.is_finite());
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * (1.0 + b.abs()));
    v
}

/// Cell edges around sorted centres.
fn edges(c: &[f64]) -> Vec<f64> {
    match c {
        [] => vec![0.0, 1.0],
        [x] => vec![x - 0.5, x + 0.5],
        _ => {
            let mut e = vec![c[0] - (c[1] - c[0]) / 2.0];
            e.extend(c.windows(2).map(|w| (w[0] + w[1]) / 2.0));
            let n = c.len();
            e.push(c[n - 1] + (c[n - 1] - c[n - 2]) / 2.0);
            e
        }
    }
}

/// Ticks of a logarithmic axis over [lo, hi] (0 < lo < hi): 1·10^k, else 1, 2, 5·10^k, else
/// every digit, whichever first gives at least four.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let mut out = Vec::new();
    for mults in [
        &[1.0][..],
        &[1.0, 2.0, 5.0][..],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0][..],
    ] {
        out = (k0..=k1)
            .flat_map(|k| mults.iter().map(move |m| m * 10f64.powi(k)))
            .filter(|v| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9))
            .collect();
        if out.len() >= 4 {
            break;
        }
    }
    out
}

/// A tick value of a log axis with as many decimals as it needs (0.05, 2, 300).
fn log_label(v: f64) -> String {
    let decimals = (-(v.log10() + 1e-9).floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// The symbol of a marker at (cx, cy), pixels.
fn symbol(shape: Shape, cx: f64, cy: f64, color: &str) -> String {
    let outline = r#"stroke="white" stroke-width="2""#;
    match shape {
        Shape::Circle => format!(
            r#"<circle cx="{}" cy="{}" r="6.5" fill="{color}" {outline}/>"#,
            px(cx),
            px(cy)
        ),
        Shape::Diamond => format!(
            r#"<path d="M{},{} l8,8 l-8,8 l-8,-8 Z" fill="{color}" {outline}/>"#,
            px(cx),
            px(cy - 8.0)
        ),
        Shape::Star => {
            let pts: Vec<String> = (0..10)
                .map(|k| {
                    let r = if k % 2 == 0 { 10.0 } else { 4.2 };
                    let a = std::f64::consts::PI * (k as f64 / 5.0 - 0.5);
                    format!("{},{}", px(cx + r * a.cos()), px(cy + r * a.sin()))
                })
                .collect();
            format!(
                r#"<polygon points="{}" fill="{color}" {outline} stroke-linejoin="round"/>"#,
                pts.join(" ")
            )
        }
    }
}

/// A small cross for an infeasible sample, visible on dark and light cells.
fn cross_mark(cx: f64, cy: f64, r: f64) -> String {
    let d = format!(
        "M{},{} L{},{} M{},{} L{},{}",
        px(cx - r),
        px(cy - r),
        px(cx + r),
        px(cy + r),
        px(cx - r),
        px(cy + r),
        px(cx + r),
        px(cy - r)
    );
    format!(
        r##"<path d="{d}" stroke="#222" stroke-width="3"/><path d="{d}" stroke="white" stroke-width="1.3"/>"##
    )
}

fn dot_mark(cx: f64, cy: f64) -> String {
    format!(
        r##"<circle cx="{}" cy="{}" r="2.8" fill="white" stroke="#222" stroke-width="1"/>"##,
        px(cx),
        px(cy)
    )
}

/// A text with a white halo, so that it reads on any cell colour.
fn halo_text(x: f64, y: f64, anchor: &str, color: &str, text: &str) -> String {
    format!(
        r#"<text x="{x}" y="{y}" font-size="12" font-weight="bold" text-anchor="{anchor}" fill="white" stroke="white" stroke-width="3.5" stroke-linejoin="round">{t}</text><text x="{x}" y="{y}" font-size="12" font-weight="bold" text-anchor="{anchor}" fill="{color}">{t}</text>"#,
        x = px(x),
        y = px(y),
        t = esc(text)
    )
}

impl MapPlot {
    /// Whether the colour scale is logarithmic.
    pub fn log_scale(&self) -> bool {
        let (lo, hi) = self.z_bounds();
        lo > 0.0 && hi / lo > LOG_SPAN
    }

    fn z_bounds(&self) -> (f64, f64) {
        if let Some((lo, hi)) = self.z_range.filter(|(a, b)| a.is_finite() && b.is_finite()) {
            return (lo.min(hi), lo.max(hi));
        }
        let feasible: Vec<f64> = self
            .cells
            .iter()
            .filter(|c| c.feasible && c.z.is_finite())
            .map(|c| c.z)
            .collect();
        let zs = if feasible.is_empty() {
            self.cells
                .iter()
                .map(|c| c.z)
                .filter(|z| z.is_finite())
                .collect()
        } else {
            feasible
        };
        let lo = zs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if lo.is_finite() {
            (lo, hi)
        } else {
            (0.0, 1.0)
        }
    }

    /// Legend entries: (swatch, text).
    fn legend(&self) -> Vec<(Swatch<'_>, String)> {
        let mut out: Vec<(Swatch, String)> = Vec::new();
        if self.cells.iter().any(|c| c.z.is_finite() && !c.feasible) {
            out.push((
                Box::new(|x, y| {
                    format!(
                        r##"<rect x="{}" y="{}" width="22" height="12" fill="{}"/><rect x="{}" y="{}" width="22" height="12" fill="url(#hatch)" stroke="#555" stroke-width="0.8"/>"##,
                        px(x),
                        px(y - 6.0),
                        viridis(0.35),
                        px(x),
                        px(y - 6.0)
                    )
                }),
                "infeasible: a constraint is violated".into(),
            ));
        }
        if self.cells.iter().any(|c| !c.z.is_finite()) {
            out.push((
                Box::new(|x, y| {
                    format!(
                        r##"<rect x="{}" y="{}" width="22" height="12" fill="white" stroke="#555" stroke-width="0.8"/>"##,
                        px(x),
                        px(y - 6.0)
                    )
                }),
                "not evaluated: breaks a design rule".into(),
            ));
        }
        if self.samples.iter().any(|s| s.2) {
            out.push((
                Box::new(|x, y| dot_mark(x + 11.0, y)),
                format!("{} (feasible)", self.samples_label),
            ));
        }
        if self.samples.iter().any(|s| !s.2) {
            out.push((
                Box::new(|x, y| cross_mark(x + 11.0, y, 3.5)),
                format!("{} (infeasible)", self.samples_label),
            ));
        }
        if self.path.len() > 1 {
            out.push((
                Box::new(|x, y| {
                    format!(
                        r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#d62728" stroke-width="2"/><circle cx="{}" cy="{y}" r="2.2" fill="#d62728"/>"##,
                        px(x),
                        px(x + 22.0),
                        px(x + 11.0),
                        y = px(y)
                    )
                }),
                self.path_label.clone(),
            ));
        }
        for m in &self.markers {
            let (shape, color) = (m.shape, m.color.clone());
            out.push((
                Box::new(move |x, y| symbol(shape, x + 11.0, y, &color)),
                m.label.clone(),
            ));
        }
        out
    }

    pub fn to_svg(&self) -> String {
        let xs = distinct(self.cells.iter().map(|c| c.x).collect());
        let ys = distinct(self.cells.iter().map(|c| c.y).collect());
        let (xe, ye) = (edges(&xs), edges(&ys));
        let (mut x_lo, mut x_hi) = (xe[0], *xe.last().unwrap_or(&1.0));
        let (mut y_lo, mut y_hi) = (ye[0], *ye.last().unwrap_or(&1.0));
        let extra = self
            .path
            .iter()
            .copied()
            .chain(self.samples.iter().map(|s| (s.0, s.1)))
            .chain(self.markers.iter().map(|m| (m.x, m.y)));
        for (x, y) in extra {
            if x.is_finite() && y.is_finite() {
                x_lo = x_lo.min(x);
                x_hi = x_hi.max(x);
                y_lo = y_lo.min(y);
                y_hi = y_hi.max(y);
            }
        }
        let xt = ticks(x_lo, x_hi, 6, false);
        let yt = ticks(y_lo, y_hi, 6, false);
        let (z_lo, z_hi) = self.z_bounds();
        let log = self.log_scale();
        let (z_ticks, z_text): (Vec<f64>, Box<dyn Fn(f64) -> String>) = if log {
            (log_ticks(z_lo, z_hi), Box::new(log_label))
        } else {
            let t = ticks(z_lo, z_hi, 6, false);
            (t.values.clone(), Box::new(move |v| t.label(v)))
        };
        let zn = |z: f64| {
            if log {
                (z.ln() - z_lo.ln()) / (z_hi.ln() - z_lo.ln())
            } else if z_hi > z_lo {
                (z - z_lo) / (z_hi - z_lo)
            } else {
                0.5
            }
        };
        let label_w = yt
            .values
            .iter()
            .map(|v| text_width(&yt.label(*v), 12.0))
            .fold(0.0, f64::max);
        let zlabel_w = z_ticks
            .iter()
            .map(|v| text_width(&z_text(*v), 12.0))
            .fold(0.0, f64::max);
        let legend = self.legend();
        let w = self.width;
        // Legend entries in columns under the axes, as many columns as the widest fits.
        let widest = legend
            .iter()
            .map(|(_, text)| 30.0 + text_width(text, 12.0) + 16.0)
            .fold(0.0, f64::max);
        let columns = (((w - 28.0) / widest.max(1.0)).floor() as usize).clamp(1, 3);
        let col_w = (w - 28.0) / columns as f64;
        let slots: Vec<(f64, usize)> = (0..legend.len())
            .map(|k| (14.0 + col_w * (k % columns) as f64, k / columns))
            .collect();
        let row = legend.len().saturating_sub(1) / columns;
        let rows = if legend.is_empty() { 0 } else { row + 1 };
        let top = if self.subtitle.is_empty() { 44.0 } else { 62.0 };
        let (left, right) = (label_w + 44.0, 76.0 + zlabel_w);
        let pw = w - left - right;
        let ph = pw.min(460.0);
        let legend_top = top + ph + 58.0;
        let h = legend_top + 18.0 * rows as f64 + 6.0;
        let (xl, xh) = (xt.lo.min(x_lo), xt.hi.max(x_hi));
        let (yl, yh) = (yt.lo.min(y_lo), yt.hi.max(y_hi));
        let sx = |x: f64| left + (x - xl) / (xh - xl) * pw;
        let sy = |y: f64| top + ph - (y - yl) / (yh - yl) * ph;
        let mut s = header(w, h);
        s += HATCH;
        s += "\n";
        titles(&mut s, left, &self.title, &self.subtitle);
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#f4f4f4"/>"##,
            px(left),
            px(top),
            px(pw),
            px(ph)
        );
        let index = |v: &[f64], a: f64| {
            v.iter()
                .position(|b| (b - a).abs() <= 1e-12 * (1.0 + a.abs()))
        };
        let mut hatched = String::new();
        for c in &self.cells {
            let (Some(i), Some(j)) = (index(&xs, c.x), index(&ys, c.y)) else {
                continue;
            };
            let fill = if c.z.is_finite() {
                viridis(zn(c.z))
            } else {
                "#ffffff".into()
            };
            let (ax, bx) = (sx(xe[i]), sx(xe[i + 1]));
            let (ay, by) = (sy(ye[j + 1]), sy(ye[j]));
            let rect = format!(
                r#"x="{}" y="{}" width="{}" height="{}""#,
                px(ax),
                px(ay),
                px(bx - ax),
                px(by - ay)
            );
            let _ = writeln!(
                s,
                r#"<rect class="cell" {rect} fill="{fill}" stroke="{fill}" stroke-width="0.5"/>"#
            );
            if c.z.is_finite() && !c.feasible {
                let _ = writeln!(
                    hatched,
                    r#"<rect {rect} fill="url(#hatch)" class="infeasible"/>"#
                );
            }
        }
        s += &hatched;
        for &v in &yt.values {
            let _ = writeln!(
                s,
                r##"<text x="{}" y="{}" font-size="12" text-anchor="end">{}</text><line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#333"/>"##,
                px(left - 8.0),
                px(sy(v) + 4.0),
                esc(&yt.label(v)),
                px(left - 5.0),
                px(left),
                y = px(sy(v))
            );
        }
        for &v in &xt.values {
            let _ = writeln!(
                s,
                r##"<text x="{x}" y="{}" font-size="12" text-anchor="middle">{}</text><line x1="{x}" y1="{}" x2="{x}" y2="{}" stroke="#333"/>"##,
                px(top + ph + 19.0),
                esc(&xt.label(v)),
                px(top + ph),
                px(top + ph + 5.0),
                x = px(sx(v))
            );
        }
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#333"/>"##,
            px(left),
            px(top),
            px(pw),
            px(ph)
        );
        let _ = writeln!(
            s,
            r#"<clipPath id="area"><rect x="{}" y="{}" width="{}" height="{}"/></clipPath><g clip-path="url(#area)" fill="none">"#,
            px(left - 10.0),
            px(top - 10.0),
            px(pw + 20.0),
            px(ph + 20.0)
        );
        for &(x, y, feasible) in &self.samples {
            if x.is_finite() && y.is_finite() {
                s += &if feasible {
                    dot_mark(sx(x), sy(y))
                } else {
                    cross_mark(sx(x), sy(y), 3.5)
                };
                s += "\n";
            }
        }
        let path: Vec<(f64, f64)> = self
            .path
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| (sx(x), sy(y)))
            .collect();
        if path.len() > 1 {
            let pts: Vec<String> = path
                .iter()
                .map(|&(x, y)| format!("{},{}", px(x), px(y)))
                .collect();
            let _ = writeln!(
                s,
                r##"<polyline class="path" points="{p}" stroke="white" stroke-width="4.5" stroke-linejoin="round"/><polyline points="{p}" stroke="#d62728" stroke-width="2" stroke-linejoin="round"/>"##,
                p = pts.join(" ")
            );
            for &(x, y) in &path {
                let _ = writeln!(
                    s,
                    r##"<circle cx="{}" cy="{}" r="2.2" fill="#d62728"/>"##,
                    px(x),
                    px(y)
                );
            }
        }
        s += "</g>\n";
        // Markers, then their labels placed where they stay inside the axes and clear of the
        // other markers and labels.
        let spots: Vec<(f64, f64)> = self.markers.iter().map(|m| (sx(m.x), sy(m.y))).collect();
        // Largest symbol first, so that markers on the same spot (an optimum on a published
        // value) all stay visible.
        let mut order: Vec<usize> = (0..self.markers.len()).collect();
        order.sort_by_key(|&k| match self.markers[k].shape {
            Shape::Star => 0,
            Shape::Diamond => 1,
            Shape::Circle => 2,
        });
        for k in order {
            let (m, (cx, cy)) = (&self.markers[k], spots[k]);
            s += &symbol(m.shape, cx, cy, &m.color);
            s += "\n";
        }
        let mut boxes: Vec<(f64, f64, f64, f64)> = spots
            .iter()
            .map(|&(x, y)| (x - 9.0, y - 9.0, x + 9.0, y + 9.0))
            .collect();
        // The path too, sampled every few pixels along its segments.
        for pair in path.windows(2) {
            let ((ax, ay), (bx, by)) = (pair[0], pair[1]);
            let n = ((bx - ax).hypot(by - ay) / 4.0).ceil().max(1.0) as usize;
            for k in 0..=n {
                let t = k as f64 / n as f64;
                let (x, y) = (ax + t * (bx - ax), ay + t * (by - ay));
                boxes.push((x - 2.0, y - 2.0, x + 2.0, y + 2.0));
            }
        }
        let overlaps = |a: &(f64, f64, f64, f64), b: &(f64, f64, f64, f64)| {
            a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
        };
        for (m, &(cx, cy)) in self.markers.iter().zip(&spots) {
            let tw = text_width(&m.label, 12.0) + 4.0;
            let candidates = [
                (12.0, 0.0),
                (-12.0, 0.0),
                (12.0, -16.0),
                (12.0, 16.0),
                (-12.0, -16.0),
                (-12.0, 16.0),
                (12.0, -32.0),
                (12.0, 32.0),
                (-12.0, -32.0),
                (-12.0, 32.0),
            ];
            let place = |&(dx, dy): &(f64, f64)| {
                let x0 = if dx > 0.0 { cx + dx } else { cx + dx - tw };
                (x0, cy + dy - 9.0, x0 + tw, cy + dy + 5.0)
            };
            let inside = |b: &(f64, f64, f64, f64)| {
                b.0 >= left && b.2 <= left + pw && b.1 >= top && b.3 <= top + ph
            };
            // Inside the axes first, then the fewest overlaps, then the order above.
            let chosen = candidates
                .iter()
                .min_by_key(|c| {
                    let b = place(c);
                    let hits = boxes.iter().filter(|o| overlaps(&b, o)).count();
                    (!inside(&b), hits)
                })
                .unwrap_or(&candidates[0]);
            let b = place(chosen);
            boxes.push(b);
            let (anchor, x) = if chosen.0 > 0.0 {
                ("start", cx + chosen.0)
            } else {
                ("end", cx + chosen.0)
            };
            s += &halo_text(x, cy + chosen.1 + 4.0, anchor, &m.color, &m.label);
            s += "\n";
        }
        // Colour bar.
        let (bx, bw) = (left + pw + 16.0, 16.0);
        let steps = 48;
        for k in 0..steps {
            let t0 = k as f64 / steps as f64;
            let y = top + ph * (1.0 - t0 - 1.0 / steps as f64);
            let _ = writeln!(
                s,
                r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{}"/>"#,
                px(bx),
                px(y),
                px(bw),
                px(ph / steps as f64 + 0.5),
                viridis(t0 + 0.5 / steps as f64)
            );
        }
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="#333"/>"##,
            px(bx),
            px(top),
            px(bw),
            px(ph)
        );
        for &v in &z_ticks {
            let y = top + ph * (1.0 - zn(v));
            let _ = writeln!(
                s,
                r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#333"/><text x="{}" y="{}" font-size="12">{}</text>"##,
                px(bx + bw),
                px(bx + bw + 4.0),
                px(bx + bw + 7.0),
                px(y + 4.0),
                esc(&z_text(v)),
                y = px(y)
            );
        }
        let z_label = if log {
            format!("{} (log scale)", self.z_label)
        } else {
            self.z_label.clone()
        };
        let _ = writeln!(
            s,
            r#"<text transform="translate({},{}) rotate(-90)" font-size="13" text-anchor="middle">{}</text>"#,
            px(w - 8.0),
            px(top + ph / 2.0),
            esc(&z_label)
        );
        axis_labels(
            &mut s,
            (left, top, pw, ph),
            top + ph + 40.0,
            &self.x_label,
            &self.y_label,
        );
        // Legend under the axes.
        for ((swatch, text), &(x, row)) in legend.iter().zip(&slots) {
            let y = legend_top + 18.0 * row as f64;
            s += &swatch(x, y);
            let _ = writeln!(
                s,
                r#"<text x="{}" y="{}" font-size="12">{}</text>"#,
                px(x + 30.0),
                px(y + 4.0),
                esc(text)
            );
        }
        s += "</svg>\n";
        s
    }
}

/// A plot's title (bold, top left) and subtitle (grey, below it, when given).
fn titles(s: &mut String, left: f64, title: &str, subtitle: &str) {
    let _ = writeln!(
        s,
        r#"<text x="{}" y="24" font-size="16" font-weight="bold">{}</text>"#,
        px(left),
        esc(title)
    );
    if !subtitle.is_empty() {
        let _ = writeln!(
            s,
            r##"<text x="{}" y="44" font-size="12" fill="#555">{}</text>"##,
            px(left),
            esc(subtitle)
        );
    }
}

/// Axis labels of a plot area (left, top, width, height): x centred under it with its baseline
/// at `x_baseline`, y rotated along the left edge.
fn axis_labels(
    s: &mut String,
    (left, top, pw, ph): (f64, f64, f64, f64),
    x_baseline: f64,
    x_label: &str,
    y_label: &str,
) {
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" font-size="13" text-anchor="middle">{}</text>"#,
        px(left + pw / 2.0),
        px(x_baseline),
        esc(x_label)
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate({},{}) rotate(-90)" font-size="13" text-anchor="middle">{}</text>"#,
        px(16.0),
        px(top + ph / 2.0),
        esc(y_label)
    );
}

/// Maps world coordinates (mm, y up) into a pixel box (y down), same scale on both axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    pub scale: f64,
    pub x0: f64,
    pub y0: f64,
    pub ox: f64,
    pub oy: f64,
}

impl Frame {
    /// Fit the world box [x0, x1] × [y0, y1] centred in a w × h pixel box at (ox, oy).
    pub fn fit(world: (f64, f64, f64, f64), pixels: (f64, f64, f64, f64)) -> Frame {
        let (x0, x1, y0, y1) = world;
        let (ox, oy, w, h) = pixels;
        let scale = (w / (x1 - x0)).min(h / (y1 - y0));
        Frame {
            scale,
            x0: (x0 + x1) / 2.0,
            y0: (y0 + y1) / 2.0,
            ox: ox + w / 2.0,
            oy: oy + h / 2.0,
        }
    }

    pub fn x(&self, x: f64) -> f64 {
        self.ox + (x - self.x0) * self.scale
    }

    pub fn y(&self, y: f64) -> f64 {
        self.oy - (y - self.y0) * self.scale
    }

    pub fn len(&self, l: f64) -> f64 {
        l * self.scale
    }

    /// "x,y" of a world point.
    pub fn point(&self, x: f64, y: f64) -> String {
        format!("{},{}", px(self.x(x)), px(self.y(y)))
    }
}
