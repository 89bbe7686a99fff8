//! Maps of a value over a grid of two variables: cells coloured by the value (viridis; a log
//! scale when it spans more than `LOG_SPAN`), infeasible cells washed out and hatched, further
//! sample points, a path, labelled markers, a colour bar and a legend under the axes. Objective
//! maps of a study use all of it; a roller × crank heat map only the cells.

use super::base::{document, points, px, span, widest, RED};
use super::frame::{self, Area};
use super::labels::{self, Bounds, Label, Layout, Obstacle};
use super::ticks::{log_label, log_ticks, ticks};
use base64::Engine;
use maud::{html, Markup};

/// One cell of a map: the value `z` at (x, y), non-finite when the point could not be
/// evaluated (a design rule), and whether it satisfies every constraint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapCell {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub feasible: bool,
}

/// The symbol of a map marker, from the smallest to the largest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
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

/// A map over a grid with its markings (see the module).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MapPlot {
    pub title: String,
    /// A second, smaller line under the title.
    pub subtitle: String,
    pub x_label: String,
    pub y_label: String,
    /// Whether the x and y axes are logarithmic (every x, or y, then > 0): the cells, samples,
    /// path and markers are placed by the logarithm of their value, the ticks at 1-2-5 steps.
    pub log_axes: (bool, bool),
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
    pub width: f64,
}

/// The colour scale turns logarithmic when the largest value exceeds the smallest (> 0) by
/// this factor.
pub const LOG_SPAN: f64 = 20.0;

/// Half the size of a sample's mark, pixels: small against a cell (a 15 × 15 map's cell is
/// about 30 px), so that the global sample (several per cell: ~830 on the paper's 225 cells)
/// leaves the cells' colour readable.
const SAMPLE_PX: f64 = 1.6;

/// A grid of more cells than this is drawn as one embedded image, a pixel per cell, rather
/// than a rectangle per cell (a roller × crank heat map has tens of thousands).
pub const RASTER_ABOVE: usize = 2500;

/// Viridis colour map, t in [0, 1], as RGB: linear between nine stops 0xRRGGBB.
fn viridis_rgb(t: f64) -> [u8; 3] {
    const STOPS: [u32; 9] = [
        0x440154, 0x472c7a, 0x3b518b, 0x2c718e, 0x21908d, 0x27ad81, 0x5cc863, 0xaadc32, 0xfde725,
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let f = t * (STOPS.len() - 1) as f64;
    let k = (f.floor() as usize).min(STOPS.len() - 2);
    let w = f - k as f64;
    let channel = |stop: u32, c: usize| f64::from((stop >> (16 - 8 * c)) & 0xff);
    std::array::from_fn(|c| {
        let (a, b) = (channel(STOPS[k], c), channel(STOPS[k + 1], c));
        (a + w * (b - a)).round() as u8
    })
}

/// "#rrggbb" of a colour.
fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// Viridis colour map, t in [0, 1], as "#rrggbb".
pub fn viridis(t: f64) -> String {
    hex(viridis_rgb(t))
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

fn index(v: &[f64], a: f64) -> Option<usize> {
    v.iter()
        .position(|b| (b - a).abs() <= 1e-12 * (1.0 + a.abs()))
}

const HATCH: &str = r##"<defs><pattern id="hatch" width="7" height="7" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="7" height="7" fill="white" fill-opacity="0.55"/><line x1="0" y1="0" x2="0" y2="7" stroke="white" stroke-width="2.5"/></pattern></defs>"##;

/// What a legend entry shows.
enum Swatch {
    Hatched,
    Blank,
    Dot,
    Cross,
    Path,
    Marker(Shape, String),
}

/// A legend swatch with its left edge at x, centred on y.
fn swatch(s: &Swatch, x: f64, y: f64) -> Markup {
    let box_at = |fill: &str| {
        html! {
            rect x=(px(x)) y=(px(y - 6.0)) width="22" height="12" fill=(fill) stroke="#555"
                stroke-width="0.8" {}
        }
    };
    match s {
        Swatch::Hatched => html! {
            rect x=(px(x)) y=(px(y - 6.0)) width="22" height="12" fill=(viridis(0.35)) {}
            (box_at("url(#hatch)"))
        },
        Swatch::Blank => box_at("white"),
        Swatch::Dot => dot_mark(x + 11.0, y),
        Swatch::Cross => cross_mark(x + 11.0, y, SAMPLE_PX + 0.5),
        Swatch::Path => html! {
            line x1=(px(x)) y1=(px(y)) x2=(px(x + 22.0)) y2=(px(y)) stroke=(RED)
                stroke-width="2" {}
            circle cx=(px(x + 11.0)) cy=(px(y)) r="2.2" fill=(RED) {}
        },
        Swatch::Marker(shape, color) => symbol(*shape, x + 11.0, y, color),
    }
}

/// The symbol of a marker at (cx, cy), pixels.
fn symbol(shape: Shape, cx: f64, cy: f64, color: &str) -> Markup {
    let star = || {
        points((0..10).map(|k| {
            let r = if k % 2 == 0 { 10.0 } else { 4.2 };
            let a = std::f64::consts::PI * (k as f64 / 5.0 - 0.5);
            (cx + r * a.cos(), cy + r * a.sin())
        }))
    };
    html! {
        @match shape {
            Shape::Circle => circle.marker cx=(px(cx)) cy=(px(cy)) r="6.5" fill=(color) stroke="white"
                stroke-width="2" {},
            Shape::Diamond => path.marker d=(format!("M{},{} l8,8 l-8,8 l-8,-8 Z", px(cx), px(cy - 8.0)))
                fill=(color) stroke="white" stroke-width="2" {},
            Shape::Star => polygon.marker points=(star()) fill=(color) stroke="white" stroke-width="2"
                stroke-linejoin="round" {},
        }
    }
}

/// A small cross for an infeasible sample, visible on dark and light cells (a white stroke
/// on a dark one), 2r across.
fn cross_mark(cx: f64, cy: f64, r: f64) -> Markup {
    let at = |dx: f64, dy: f64| format!("{},{}", px(cx + dx), px(cy + dy));
    let (a, b, c, d) = (at(-r, -r), at(r, r), at(-r, r), at(r, -r));
    let d = format!("M{a} L{b} M{c} L{d}");
    html! {
        path d=(d) stroke="#222" stroke-width="1.6" {}
        path d=(d) stroke="white" stroke-width="0.6" {}
    }
}

/// A feasible sample: a hollow ring, so that the cell's colour shows through it.
fn dot_mark(cx: f64, cy: f64) -> Markup {
    html! {
        circle cx=(px(cx)) cy=(px(cy)) r=(px(SAMPLE_PX)) fill="none" stroke="white"
            stroke-width="1.6" {}
        circle cx=(px(cx)) cy=(px(cy)) r=(px(SAMPLE_PX)) fill="none" stroke="#222"
            stroke-width="0.7" {}
    }
}

/// Ticks and the range they span: each tick's position on the drawn scale and its label.
struct AxisTicks {
    lo: f64,
    hi: f64,
    ticks: Vec<(f64, String)>,
}

/// Ticks over [lo, hi] with their labels: 1-2-5 steps of a logarithmic scale (`log`, 0 < lo),
/// else round linear ticks inside the range.
fn labelled(lo: f64, hi: f64, log: bool) -> AxisTicks {
    if log {
        let ticks = log_ticks(lo, hi).into_iter().map(|v| (v, log_label(v)));
        let ticks = ticks.collect();
        return AxisTicks { lo, hi, ticks };
    }
    let t = ticks(lo, hi, 6, false);
    let ticks = t.values.iter().map(|&v| (v, t.label(v))).collect();
    let (lo, hi) = (t.lo, t.hi);
    AxisTicks { lo, hi, ticks }
}

/// Ticks over [lo, hi] of a linear axis, or of a logarithmic one whose drawn values are the
/// logarithms (`MapPlot::in_log_space`): 1-2-5 steps of the values, placed at their logarithms.
fn axis_ticks(lo: f64, hi: f64, log: bool) -> AxisTicks {
    let (from, to) = (lo.exp(), hi.exp());
    if log && from > 0.0 && to.is_finite() {
        let ticks = labelled(from, to, true).ticks.into_iter();
        let ticks = ticks.map(|(v, label)| (v.ln(), label)).collect();
        return AxisTicks { lo, hi, ticks };
    }
    labelled(lo, hi, false)
}

/// A pixel box (x0, y0, x1, y1).
type Box4 = (f64, f64, f64, f64);

impl MapPlot {
    /// A map of `cells` alone (no samples, path or markers), 660 px wide, its colour range the
    /// cells'.
    pub fn of_cells(
        title: &str,
        x_label: &str,
        y_label: &str,
        z_label: &str,
        cells: Vec<MapCell>,
    ) -> Self {
        MapPlot {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            z_label: z_label.into(),
            cells,
            width: 660.0,
            ..Default::default()
        }
    }

    /// Whether the colour scale is logarithmic.
    pub fn log_scale(&self) -> bool {
        let (lo, hi) = self.z_bounds();
        lo > 0.0 && hi / lo > LOG_SPAN
    }

    /// The colour range: the feasible cells' values (every cell's when none is).
    fn z_bounds(&self) -> (f64, f64) {
        let any_feasible = self.cells.iter().any(|c| c.z.is_finite() && c.feasible);
        let zs = self.cells.iter().filter(|c| c.feasible || !any_feasible);
        span(zs.map(|c| &c.z)).unwrap_or((0.0, 1.0))
    }

    /// Position of z on the colour scale, 0 to 1.
    fn scale(&self, z: f64) -> f64 {
        let (lo, hi) = self.z_bounds();
        if self.log_scale() {
            (z.ln() - lo.ln()) / (hi.ln() - lo.ln())
        } else if hi > lo {
            (z - lo) / (hi - lo)
        } else {
            0.5
        }
    }

    /// Colour-bar ticks and their labels.
    fn z_ticks(&self) -> Vec<(f64, String)> {
        let (lo, hi) = self.z_bounds();
        labelled(lo, hi, self.log_scale()).ticks
    }

    fn legend(&self) -> Vec<(Swatch, String)> {
        let (mut out, samples) = (Vec::new(), &self.samples_label);
        if self.cells.iter().any(|c| c.z.is_finite() && !c.feasible) {
            let text = "infeasible: a constraint is violated";
            out.push((Swatch::Hatched, text.into()));
        }
        if self.cells.iter().any(|c| !c.z.is_finite()) {
            out.push((Swatch::Blank, "not evaluated: breaks a design rule".into()));
        }
        if self.samples.iter().any(|s| s.2) {
            out.push((Swatch::Dot, format!("{samples} (feasible)")));
        }
        if self.samples.iter().any(|s| !s.2) {
            out.push((Swatch::Cross, format!("{samples} (infeasible)")));
        }
        if self.path.len() > 1 {
            out.push((Swatch::Path, self.path_label.clone()));
        }
        for m in &self.markers {
            out.push((Swatch::Marker(m.shape, m.color.clone()), m.label.clone()));
        }
        out
    }

    /// A cell's colour: viridis, white when not evaluated.
    fn fill(&self, c: &MapCell) -> [u8; 3] {
        if c.z.is_finite() {
            viridis_rgb(self.scale(c.z))
        } else {
            [255; 3]
        }
    }

    /// The cells as one rectangle each (infeasible ones hatched on top).
    fn cell_rects(&self, xs: &[f64], ys: &[f64], to_px: impl Fn(usize, usize) -> Box4) -> Markup {
        let placed: Vec<(&MapCell, Box4)> = self
            .cells
            .iter()
            .filter_map(|c| Some((c, to_px(index(xs, c.x)?, index(ys, c.y)?))))
            .collect();
        html! {
            @for (c, (x0, y0, x1, y1)) in &placed {
                @let fill = hex(self.fill(c));
                rect.cell x=(px(*x0)) y=(px(*y0)) width=(px(x1 - x0)) height=(px(y1 - y0))
                    fill=(fill) stroke=(fill) stroke-width="0.5" {}
            }
            @for (c, (x0, y0, x1, y1)) in &placed {
                @if c.z.is_finite() && !c.feasible {
                    rect.infeasible x=(px(*x0)) y=(px(*y0)) width=(px(x1 - x0))
                        height=(px(y1 - y0)) fill="url(#hatch)" {}
                }
            }
        }
    }

    /// The cells as one PNG image over `area`, a pixel per cell (a regular grid), infeasible
    /// cells washed out; `None` if the image cannot be encoded.
    fn cell_image(&self, xs: &[f64], ys: &[f64], a: &Area) -> Option<Markup> {
        let (w, h) = (xs.len(), ys.len());
        let mut rgb = vec![255u8; 3 * w * h];
        for c in &self.cells {
            let (Some(i), Some(j)) = (index(xs, c.x), index(ys, c.y)) else {
                continue;
            };
            let mut color = self.fill(c);
            if c.z.is_finite() && !c.feasible {
                color = color.map(|v| (v as f64 + 0.55 * (255.0 - v as f64)).round() as u8);
            }
            let at = 3 * ((h - 1 - j) * w + i);
            rgb[at..at + 3].copy_from_slice(&color);
        }
        let mut png = Vec::new();
        let mut encoder = png::Encoder::new(&mut png, w as u32, h as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().ok()?;
        writer.write_image_data(&rgb).ok()?;
        writer.finish().ok()?;
        let href = format!(
            "data:image/png;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&png)
        );
        Some(html! {
            image.cells x=(px(a.left)) y=(px(a.top)) width=(px(a.width)) height=(px(a.height))
                preserveAspectRatio="none" style="image-rendering:pixelated" href=(href) {}
        })
    }

    /// Samples and the path, clipped to the axes (grown by 10 px).
    fn samples_and_path(
        &self,
        path: &[(f64, f64)],
        to_px: impl Fn(f64, f64) -> (f64, f64),
    ) -> Markup {
        let finite = |x: f64, y: f64| x.is_finite() && y.is_finite();
        html! {
            g.samples clip-path="url(#area)" fill="none" {
                @for &(x, y, feasible) in &self.samples {
                    @if finite(x, y) {
                        @let (px_, py_) = to_px(x, y);
                        @if feasible { (dot_mark(px_, py_)) } @else { (cross_mark(px_, py_, SAMPLE_PX)) }
                    }
                }
            }
            g clip-path="url(#area)" fill="none" {
                @if path.len() > 1 {
                    polyline.path points=(points(path.iter().copied())) stroke="white"
                        stroke-width="4.5" stroke-linejoin="round" {}
                    polyline points=(points(path.iter().copied())) stroke=(RED) stroke-width="2"
                        stroke-linejoin="round" {}
                    @for &(x, y) in path {
                        circle cx=(px(x)) cy=(px(y)) r="2.2" fill=(RED) {}
                    }
                }
            }
        }
    }

    /// Markers (largest symbol first, so that markers on one spot all stay visible), then
    /// their labels placed by `labels::Layout` inside the axes, clear of the markers, the path
    /// and each other.
    fn markers(&self, spots: &[(f64, f64)], path: &[(f64, f64)], a: &Area) -> Markup {
        let mut order: Vec<usize> = (0..self.markers.len()).collect();
        order.sort_by_key(|&k| std::cmp::Reverse(self.markers[k].shape));
        let frame = Bounds::new(a.left, a.top, a.right(), a.bottom());
        let mut layout = Layout::new(frame);
        // A symbol is at most 10 px from its centre (the star's points), 11 with its outline.
        let symbols = spots.iter().map(|&c| Obstacle::Disc(c, 11.0));
        layout.obstacles.extend(symbols);
        layout.obstacles.extend(labels::polyline(path));
        let placed: Vec<_> = self
            .markers
            .iter()
            .zip(spots)
            .map(|(m, &c)| {
                let label = Label {
                    text: m.label.clone(),
                    size: 12.0,
                    anchor: c,
                    gap: 11.0,
                    toward: (1.0, 0.0),
                };
                (layout.place(&label), m)
            })
            .collect();
        html! {
            @for k in order {
                (symbol(self.markers[k].shape, spots[k].0, spots[k].1, &self.markers[k].color))
            }
            @for (p, m) in &placed {
                (p.draw(&m.color, true))
            }
        }
    }

    /// The colour bar to the right of the axes, with its ticks and label.
    fn colour_bar(&self, a: &Area, w: f64) -> Markup {
        let (bx, bw, steps) = (a.right() + 16.0, 16.0, 48);
        let scale = if self.log_scale() { " (log scale)" } else { "" };
        let z_label = format!("{}{scale}", self.z_label);
        html! {
            @for k in 0..steps {
                @let t0 = k as f64 / steps as f64;
                rect x=(px(bx)) y=(px(a.top + a.height * (1.0 - t0 - 1.0 / steps as f64)))
                    width=(px(bw)) height=(px(a.height / steps as f64 + 0.5))
                    fill=(viridis(t0 + 0.5 / steps as f64)) {}
            }
            rect x=(px(bx)) y=(px(a.top)) width=(px(bw)) height=(px(a.height)) fill="none"
                stroke="#333" {}
            @for (v, text) in self.z_ticks() {
                @let y = a.top + a.height * (1.0 - self.scale(v));
                line x1=(px(bx + bw)) y1=(px(y)) x2=(px(bx + bw + 4.0)) y2=(px(y)) stroke="#333" {}
                text x=(px(bx + bw + 7.0)) y=(px(y + 4.0)) font-size="12" { (text) }
            }
            (frame::rotated(w - 8.0, a.top + a.height / 2.0, &z_label))
        }
    }

    pub fn to_svg(&self) -> String {
        match self.log_axes {
            (false, false) => self.draw(),
            _ => self.in_log_space().draw(),
        }
    }

    /// This map with every value of a logarithmic axis replaced by its natural logarithm (a
    /// value ≤ 0, which no log axis holds, turns NaN and is left out as non-finite), to be
    /// drawn on linear pixels with `axis_ticks` labelling the logarithms by their values.
    fn in_log_space(&self) -> MapPlot {
        let (lx, ly) = self.log_axes;
        let f = |v: f64, log: bool| {
            if !log {
                v
            } else if v > 0.0 {
                v.ln()
            } else {
                f64::NAN
            }
        };
        let mut m = self.clone();
        for c in &mut m.cells {
            (c.x, c.y) = (f(c.x, lx), f(c.y, ly));
        }
        for s in &mut m.samples {
            (s.0, s.1) = (f(s.0, lx), f(s.1, ly));
        }
        for p in &mut m.path {
            *p = (f(p.0, lx), f(p.1, ly));
        }
        for k in &mut m.markers {
            (k.x, k.y) = (f(k.x, lx), f(k.y, ly));
        }
        m.cells.retain(|c| c.x.is_finite() && c.y.is_finite());
        m
    }

    fn draw(&self) -> String {
        let xs = distinct(self.cells.iter().map(|c| c.x).collect());
        let ys = distinct(self.cells.iter().map(|c| c.y).collect());
        let (xe, ye) = (edges(&xs), edges(&ys));
        let (mut x_lo, mut x_hi) = (xe[0], xe[xe.len() - 1]);
        let (mut y_lo, mut y_hi) = (ye[0], ye[ye.len() - 1]);
        let extra = self
            .path
            .iter()
            .copied()
            .chain(self.samples.iter().map(|s| (s.0, s.1)))
            .chain(self.markers.iter().map(|m| (m.x, m.y)));
        for (x, y) in extra.filter(|(x, y)| x.is_finite() && y.is_finite()) {
            (x_lo, x_hi) = (x_lo.min(x), x_hi.max(x));
            (y_lo, y_hi) = (y_lo.min(y), y_hi.max(y));
        }
        let xt = axis_ticks(x_lo, x_hi, self.log_axes.0);
        let yt = axis_ticks(y_lo, y_hi, self.log_axes.1);
        let label_w = widest(yt.ticks.iter().map(|(_, label)| label));
        let zlabel_w = widest(self.z_ticks().into_iter().map(|(_, l)| l));
        let legend = self.legend();
        let w = self.width;
        // Legend entries in columns under the axes, as many columns as the widest fits.
        let entry_w = 30.0 + widest(legend.iter().map(|(_, text)| text)) + 16.0;
        let columns = (((w - 28.0) / entry_w).floor() as usize).clamp(1, 3);
        let col_w = (w - 28.0) / columns as f64;
        let rows = legend.len().div_ceil(columns);
        let left = label_w + 44.0;
        let subtitle = frame::wrap(&self.subtitle, w - left - 8.0);
        let top = frame::top(subtitle.len());
        let pw = w - left - 76.0 - zlabel_w;
        let a = Area {
            left,
            top,
            width: pw,
            height: pw.min(460.0),
        };
        let legend_top = a.bottom() + 58.0;
        let h = legend_top + 18.0 * rows as f64 + 6.0;
        let (xl, xh) = (xt.lo.min(x_lo), xt.hi.max(x_hi));
        let (yl, yh) = (yt.lo.min(y_lo), yt.hi.max(y_hi));
        let sx = |x: f64| a.left + (x - xl) / (xh - xl) * a.width;
        let sy = |y: f64| a.bottom() - (y - yl) / (yh - yl) * a.height;
        let image = (self.cells.len() > RASTER_ABOVE).then(|| self.cell_image(&xs, &ys, &a));
        let cells = image.flatten().unwrap_or_else(|| {
            self.cell_rects(&xs, &ys, |i, j| {
                (sx(xe[i]), sy(ye[j + 1]), sx(xe[i + 1]), sy(ye[j]))
            })
        });
        let path: Vec<(f64, f64)> = self
            .path
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .map(|&(x, y)| (sx(x), sy(y)))
            .collect();
        let spots: Vec<(f64, f64)> = self.markers.iter().map(|m| (sx(m.x), sy(m.y))).collect();
        let body = html! {
            (maud::PreEscaped(HATCH))
            (frame::titles(left, &self.title, &subtitle))
            rect x=(px(a.left)) y=(px(a.top)) width=(px(a.width)) height=(px(a.height))
                fill="#f4f4f4" {}
            (cells)
            @for &(v, ref label) in &yt.ticks {
                text x=(px(a.left - 8.0)) y=(px(sy(v) + 4.0)) font-size="12" text-anchor="end" {
                    (label)
                }
                line x1=(px(a.left - 5.0)) y1=(px(sy(v))) x2=(px(a.left)) y2=(px(sy(v)))
                    stroke="#333" {}
            }
            @for &(v, ref label) in &xt.ticks {
                text x=(px(sx(v))) y=(px(a.bottom() + 19.0)) font-size="12" text-anchor="middle" {
                    (label)
                }
                line x1=(px(sx(v))) y1=(px(a.bottom())) x2=(px(sx(v))) y2=(px(a.bottom() + 5.0))
                    stroke="#333" {}
            }
            (a.outline())
            (a.clip("area", 10.0))
            (self.samples_and_path(&path, |x, y| (sx(x), sy(y))))
            (self.markers(&spots, &path, &a))
            (self.colour_bar(&a, w))
            (frame::axis_labels(&a, a.bottom() + 40.0, &self.x_label, &self.y_label))
            @for (k, (sw, text)) in legend.iter().enumerate() {
                @let (x, y) = (14.0 + col_w * (k % columns) as f64, legend_top + 18.0 * (k / columns) as f64);
                (swatch(sw, x, y))
                text x=(px(x + 30.0)) y=(px(y + 4.0)) font-size="12" { (text) }
            }
        };
        document(w, h, body)
    }
}

#[cfg(test)]
mod tests {
    use super::{MapCell, MapPlot};

    /// The x of every `<text>` whose content is `label` in `svg`.
    fn text_x(svg: &str, label: &str) -> Vec<f64> {
        svg.split("<text")
            .skip(1)
            .filter(|t| t.split('>').nth(1).and_then(|c| c.split('<').next()) == Some(label))
            .filter_map(|t| t.split("x=\"").nth(1)?.split('"').next()?.parse().ok())
            .collect()
    }

    /// A crown radius searched from 100 mm to 10 m in its logarithm: the decades' ticks sit
    /// equally far apart (a log axis), and the cells span the axis evenly (log-spaced cells of
    /// one width). On the linear axis the crown study's map drew, 100 to 1000 mm took a tenth of
    /// the width of 1000 to 10,000 mm. Pixel positions are written to 0.01 px.
    #[test]
    fn a_log_axis_puts_decades_equally_apart() {
        let xs: Vec<f64> = (0..9).map(|i| 100.0 * 10f64.powf(i as f64 / 4.0)).collect();
        let cells = xs
            .iter()
            .flat_map(|&x| {
                (0..3).map(move |j| MapCell {
                    x,
                    y: j as f64,
                    z: x.ln() + j as f64,
                    feasible: true,
                })
            })
            .collect();
        let plot = MapPlot {
            log_axes: (true, false),
            ..MapPlot::of_cells("t", "crown radius Rc (mm)", "start (mm)", "z", cells)
        };
        let svg = plot.to_svg();
        let at = |l: &str| {
            let x = text_x(&svg, l);
            assert_eq!(x.len(), 1, "one tick labelled {l}: {x:?}");
            x[0]
        };
        let (a, b, c) = (at("100"), at("1000"), at("10000"));
        assert!(a < b && b < c, "{a} {b} {c}");
        assert!(
            ((b - a) - (c - b)).abs() <= 0.02,
            "decades {} and {} px",
            b - a,
            c - b
        );
        let widths: Vec<f64> = svg
            .split("<rect class=\"cell\"")
            .skip(1)
            .filter_map(|t| t.split("width=\"").nth(1)?.split('"').next()?.parse().ok())
            .collect();
        assert_eq!(widths.len(), 27);
        let (lo, hi) = widths
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), w| (l.min(*w), h.max(*w)));
        assert!(hi - lo <= 0.02, "cell widths {lo}..{hi} px");
    }
}
