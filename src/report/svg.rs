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
        let _ = writeln!(
            s,
            r#"<text x="{}" y="24" font-size="16" font-weight="bold">{}</text>"#,
            px(left),
            esc(&self.title)
        );
        if !self.subtitle.is_empty() {
            let _ = writeln!(
                s,
                r##"<text x="{}" y="44" font-size="12" fill="#555">{}</text>"##,
                px(left),
                esc(&self.subtitle)
            );
        }
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
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" font-size="13" text-anchor="middle">{}</text>"#,
            px(left + pw / 2.0),
            px(h - 12.0),
            esc(&self.x_label)
        );
        let _ = writeln!(
            s,
            r#"<text transform="translate({},{}) rotate(-90)" font-size="13" text-anchor="middle">{}</text>"#,
            px(16.0),
            px(top + ph / 2.0),
            esc(&self.y_label)
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

/// A map of an objective over two variables, with an optional path and markers.
#[derive(Debug, Clone, PartialEq)]
pub struct MapPlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub z_label: String,
    /// Samples (x, y, z); drawn as cells of a grid through the distinct x and y values.
    pub cells: Vec<(f64, f64, f64)>,
    pub path: Vec<(f64, f64)>,
    /// Labelled markers (start, optimum, a published value).
    pub markers: Vec<(f64, f64, String, String)>,
    pub width: f64,
    pub height: f64,
}

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

impl MapPlot {
    pub fn to_svg(&self) -> String {
        let xs = distinct(self.cells.iter().map(|c| c.0).collect());
        let ys = distinct(self.cells.iter().map(|c| c.1).collect());
        let (xe, ye) = (edges(&xs), edges(&ys));
        let mut x_lo = xe[0];
        let mut x_hi = *xe.last().unwrap_or(&1.0);
        let mut y_lo = ye[0];
        let mut y_hi = *ye.last().unwrap_or(&1.0);
        for &(x, y) in self.path.iter().chain(
            self.markers
                .iter()
                .map(|m| (m.0, m.1))
                .collect::<Vec<_>>()
                .iter(),
        ) {
            if x.is_finite() && y.is_finite() {
                x_lo = x_lo.min(x);
                x_hi = x_hi.max(x);
                y_lo = y_lo.min(y);
                y_hi = y_hi.max(y);
            }
        }
        let xt = ticks(x_lo, x_hi, 6, false);
        let yt = ticks(y_lo, y_hi, 6, false);
        let zs: Vec<f64> = self
            .cells
            .iter()
            .map(|c| c.2)
            .filter(|z| z.is_finite())
            .collect();
        let z_lo = zs.iter().copied().fold(f64::INFINITY, f64::min);
        let z_hi = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let zt = ticks(z_lo, z_hi, 6, false);
        let label_w = yt
            .values
            .iter()
            .map(|v| text_width(&yt.label(*v), 12.0))
            .fold(0.0, f64::max);
        let zlabel_w = zt
            .values
            .iter()
            .map(|v| text_width(&zt.label(*v), 12.0))
            .fold(0.0, f64::max);
        let (w, h) = (self.width, self.height);
        let (left, right, top, bottom) = (label_w + 42.0, 70.0 + zlabel_w, 44.0, 52.0);
        let (pw, ph) = (w - left - right, h - top - bottom);
        let (xl, xh) = (xt.lo.min(x_lo), xt.hi.max(x_hi));
        let (yl, yh) = (yt.lo.min(y_lo), yt.hi.max(y_hi));
        let sx = |x: f64| left + (x - xl) / (xh - xl) * pw;
        let sy = |y: f64| top + ph - (y - yl) / (yh - yl) * ph;
        let zn = |z: f64| {
            if z_hi > z_lo {
                (z - z_lo) / (z_hi - z_lo)
            } else {
                0.5
            }
        };
        let mut s = header(w, h);
        let _ = writeln!(
            s,
            r#"<text x="{}" y="24" font-size="16" font-weight="bold">{}</text>"#,
            px(left),
            esc(&self.title)
        );
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="#f4f4f4"/>"##,
            px(left),
            px(top),
            px(pw),
            px(ph)
        );
        for &(x, y, z) in &self.cells {
            let (Some(i), Some(j)) = (
                xs.iter()
                    .position(|v| (v - x).abs() <= 1e-12 * (1.0 + x.abs())),
                ys.iter()
                    .position(|v| (v - y).abs() <= 1e-12 * (1.0 + y.abs())),
            ) else {
                continue;
            };
            let fill = if z.is_finite() {
                viridis(zn(z))
            } else {
                "#ffffff".into()
            };
            let (ax, bx) = (sx(xe[i]), sx(xe[i + 1]));
            let (ay, by) = (sy(ye[j + 1]), sy(ye[j]));
            let _ = writeln!(
                s,
                r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="{fill}" stroke-width="0.5"/>"#,
                px(ax),
                px(ay),
                px(bx - ax),
                px(by - ay)
            );
        }
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
        if self.path.len() > 1 {
            let pts: Vec<String> = self
                .path
                .iter()
                .map(|&(x, y)| format!("{},{}", px(sx(x)), px(sy(y))))
                .collect();
            let _ = writeln!(
                s,
                r##"<polyline points="{}" fill="none" stroke="white" stroke-width="4"/><polyline points="{}" fill="none" stroke="#d62728" stroke-width="2"/>"##,
                pts.join(" "),
                pts.join(" ")
            );
            for &(x, y) in &self.path {
                let _ = writeln!(
                    s,
                    r##"<circle cx="{}" cy="{}" r="2.5" fill="#d62728"/>"##,
                    px(sx(x)),
                    px(sy(y))
                );
            }
        }
        let mut placed: Vec<(f64, f64)> = Vec::new();
        for (x, y, label, color) in &self.markers {
            let (cx, mut cy) = (sx(*x), sy(*y));
            // Markers on the same spot (an optimum on a published value): stack the labels.
            let same = placed
                .iter()
                .filter(|(px_, py_)| (px_ - cx).abs() < 30.0 && (py_ - sy(*y)).abs() < 14.0)
                .count();
            placed.push((cx, sy(*y)));
            let marker_y = cy;
            cy += 16.0 * same as f64;
            let _ = writeln!(
                s,
                r#"<circle cx="{}" cy="{}" r="6" fill="{color}" stroke="white" stroke-width="2"/><text x="{}" y="{}" font-size="12" font-weight="bold" fill="white" stroke="white" stroke-width="3" paint-order="stroke">{}</text><text x="{}" y="{}" font-size="12" font-weight="bold" fill="{color}">{}</text>"#,
                px(cx),
                px(marker_y),
                px(cx + 9.0),
                px(cy - 7.0),
                esc(label),
                px(cx + 9.0),
                px(cy - 7.0),
                esc(label)
            );
        }
        // Colour bar.
        let (bx, bw) = (left + pw + 18.0, 16.0);
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
        for &v in &zt.values {
            let y = top + ph * (1.0 - zn(v));
            let _ = writeln!(
                s,
                r##"<line x1="{}" y1="{y}" x2="{}" y2="{y}" stroke="#333"/><text x="{}" y="{}" font-size="12">{}</text>"##,
                px(bx + bw),
                px(bx + bw + 4.0),
                px(bx + bw + 7.0),
                px(y + 4.0),
                esc(&zt.label(v)),
                y = px(y)
            );
        }
        let _ = writeln!(
            s,
            r#"<text transform="translate({},{}) rotate(-90)" font-size="13" text-anchor="middle">{}</text>"#,
            px(w - 10.0),
            px(top + ph / 2.0),
            esc(&self.z_label)
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" font-size="13" text-anchor="middle">{}</text>"#,
            px(left + pw / 2.0),
            px(h - 12.0),
            esc(&self.x_label)
        );
        let _ = writeln!(
            s,
            r#"<text transform="translate({},{}) rotate(-90)" font-size="13" text-anchor="middle">{}</text>"#,
            px(16.0),
            px(top + ph / 2.0),
            esc(&self.y_label)
        );
        s += "</svg>\n";
        s
    }
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
