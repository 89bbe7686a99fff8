//! What every plot shares: the plot area in pixels with its title, axis labels and box, and
//! the mapping of a drawing in mm (y up) into pixels (y down) at one scale.

use super::base::px;
use maud::{html, Markup};

/// The plot area of a figure, pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Area {
    pub left: f64,
    pub top: f64,
    pub width: f64,
    pub height: f64,
}

impl Area {
    pub fn right(&self) -> f64 {
        self.left + self.width
    }

    pub fn bottom(&self) -> f64 {
        self.top + self.height
    }

    /// The area's outline.
    pub fn outline(&self) -> Markup {
        html! {
            rect x=(px(self.left)) y=(px(self.top)) width=(px(self.width))
                height=(px(self.height)) fill="none" stroke="#333" {}
        }
    }

    /// A clip path named `id` around the area, grown by `pad` pixels on every side.
    pub fn clip(&self, id: &str, pad: f64) -> Markup {
        html! {
            clipPath id=(id) {
                rect x=(px(self.left - pad)) y=(px(self.top - pad))
                    width=(px(self.width + 2.0 * pad)) height=(px(self.height + 2.0 * pad)) {}
            }
        }
    }
}

/// A subtitle in lines that fit `width` pixels (at font size 12), broken between words.
pub fn wrap(text: &str, width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if super::base::text_width(&format!("{line} {word}"), 12.0) <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// Top of the plot area under a title and `subtitle_lines` lines of subtitle, which is also
/// where the next subtitle line's baseline would be.
pub fn top(subtitle_lines: usize) -> f64 {
    44.0 + 18.0 * subtitle_lines as f64
}

/// A plot's title (bold, top left at `left`) and subtitle lines (grey, below it).
pub fn titles(left: f64, title: &str, subtitle: &[String]) -> Markup {
    html! {
        text x=(px(left)) y="24" font-size="16" font-weight="bold" { (title) }
        @for (k, line) in subtitle.iter().enumerate() {
            text x=(px(left)) y=(px(top(k))) font-size="12" fill="#555" { (line) }
        }
    }
}

/// Axis labels of a plot area: x centred under it with its baseline at `x_baseline`, y
/// rotated along the figure's left edge.
pub fn axis_labels(a: &Area, x_baseline: f64, x_label: &str, y_label: &str) -> Markup {
    html! {
        text x=(px(a.left + a.width / 2.0)) y=(px(x_baseline)) font-size="13"
            text-anchor="middle" { (x_label) }
        (rotated(16.0, a.top + a.height / 2.0, y_label))
    }
}

/// Text turned to read upwards, centred on (x, y).
pub fn rotated(x: f64, y: f64, text: &str) -> Markup {
    html! {
        text transform=(format!("translate({},{}) rotate(-90)", px(x), px(y))) font-size="13"
            text-anchor="middle" { (text) }
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

    /// A world point in pixels.
    pub fn at(&self, p: crate::geometry::Vec2) -> (f64, f64) {
        (self.x(p.x), self.y(p.y))
    }

    pub fn len(&self, l: f64) -> f64 {
        l * self.scale
    }

    /// A closed path through world points.
    pub fn path(&self, pts: &[crate::geometry::Vec2]) -> String {
        format!(
            "M{} Z",
            super::base::points(pts.iter().map(|&p| self.at(p)))
        )
    }

    /// A scale bar of `length` (world) labelled `label`, its right end at (right, y) pixels.
    pub fn scale_bar(&self, right: f64, y: f64, length: f64, label: &str) -> Markup {
        let l = self.len(length);
        html! {
            line x1=(px(right - l)) y1=(px(y)) x2=(px(right)) y2=(px(y)) stroke="#333"
                stroke-width="2" {}
            text x=(px(right - l / 2.0)) y=(px(y - 6.0)) font-size="12" text-anchor="middle" {
                (label)
            }
        }
    }
}
