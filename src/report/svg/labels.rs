//! Label placement: each label's box estimated from its text (`base::text_width`) and font
//! size, tried at candidate positions around its anchor, nearest first, and put at the first
//! that stays inside the frame and clear of every obstacle (the boxes of labels placed before
//! it, the segments of curves and arrows, filled discs, circle outlines); a label moved far
//! from its anchor gets a leader line. One small pass for every drawing of the kit, so that no
//! plot needs its own offsets.

use super::base::{px, text_width};
use maud::{html, Markup};

/// A pixel box, x0 ≤ x1 and y0 ≤ y1 (y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    pub x0: f64,
    pub y0: f64,
    pub x1: f64,
    pub y1: f64,
}

impl Bounds {
    pub fn new(x0: f64, y0: f64, x1: f64, y1: f64) -> Self {
        Bounds { x0, y0, x1, y1 }
    }

    /// Whether the two boxes share an inner point (touching edges do not).
    pub fn overlaps(&self, o: &Bounds) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// Whether `o` lies wholly inside.
    pub fn contains(&self, o: &Bounds) -> bool {
        o.x0 >= self.x0 && o.x1 <= self.x1 && o.y0 >= self.y0 && o.y1 <= self.y1
    }

    /// Whether the segment a–b passes through the box (Liang–Barsky clipping: the segment's
    /// parameter interval inside each pair of edges, intersected).
    pub fn hits_segment(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        t0 <= t1
    }

    /// Distances from `c` to the box's nearest and farthest points.
    fn distances(&self, c: (f64, f64)) -> (f64, f64) {
        let near = self.nearest(c);
        let far_x = (c.0 - self.x0).abs().max((c.0 - self.x1).abs());
        let far_y = (c.1 - self.y0).abs().max((c.1 - self.y1).abs());
        ((near.0 - c.0).hypot(near.1 - c.1), far_x.hypot(far_y))
    }

    /// The box's point nearest to `p`.
    pub fn nearest(&self, p: (f64, f64)) -> (f64, f64) {
        (p.0.clamp(self.x0, self.x1), p.1.clamp(self.y0, self.y1))
    }
}

/// What a label must keep clear of, pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle {
    Box(Bounds),
    /// A straight piece of a curve, an arrow or a line.
    Segment((f64, f64), (f64, f64)),
    /// A filled disc (centre, radius): a label may not cover any of it.
    Disc((f64, f64), f64),
    /// A circle's outline (centre, radius): a label may lie inside or outside, not across it.
    Ring((f64, f64), f64),
}

impl Obstacle {
    fn hit_by(&self, b: &Bounds) -> bool {
        match *self {
            Obstacle::Box(o) => b.overlaps(&o),
            Obstacle::Segment(p, q) => b.hits_segment(p, q),
            Obstacle::Disc(c, r) => b.distances(c).0 < r,
            Obstacle::Ring(c, r) => {
                let (near, far) = b.distances(c);
                near <= r && far >= r
            }
        }
    }
}

/// Obstacles of a polyline: one segment per pair of consecutive points.
pub fn polyline(points: &[(f64, f64)]) -> impl Iterator<Item = Obstacle> + '_ {
    points.windows(2).map(|w| Obstacle::Segment(w[0], w[1]))
}

/// A label to place: its text and font size, the point it names, how far its box keeps from
/// that point at least (pixels) and the direction it prefers (pixels, y down; any length).
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    pub text: String,
    pub size: f64,
    pub anchor: (f64, f64),
    pub gap: f64,
    pub toward: (f64, f64),
}

/// A placed label: its box, where its text starts (anchor "start", baseline y), the leader
/// line from its anchor when it was moved far, and the label's text and font size.
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    pub bounds: Bounds,
    pub x: f64,
    pub y: f64,
    pub leader: Option<((f64, f64), (f64, f64))>,
    pub text: String,
    pub size: f64,
}

/// White margin kept around a label's text, pixels (the text's halo is 0.14 em wide).
const PAD: f64 = 2.0;

/// The box of `text` at font size `size` with its centre at (cx, cy): its estimated width, and
/// from the cap height above the baseline to the descenders below it (0.8 and 0.25 em), grown
/// by PAD on every side.
pub fn box_of(text: &str, size: f64, (cx, cy): (f64, f64)) -> Bounds {
    let (w, h) = (text_width(text, size) + 2.0 * PAD, 1.05 * size + 2.0 * PAD);
    Bounds::new(cx - w / 2.0, cy - h / 2.0, cx + w / 2.0, cy + h / 2.0)
}

/// Extra distances beyond a label's gap tried in turn, pixels; beyond the second a leader
/// line joins the label to its anchor.
const STEPS: [f64; 9] = [0.0, 5.0, 11.0, 18.0, 27.0, 38.0, 52.0, 70.0, 95.0];

/// Directions tried at each distance.
const DIRECTIONS: usize = 24;

/// The frame and obstacles of one drawing, and the placing of its labels.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    pub frame: Bounds,
    pub obstacles: Vec<Obstacle>,
}

impl Layout {
    pub fn new(frame: Bounds) -> Self {
        Layout {
            frame,
            obstacles: Vec::new(),
        }
    }

    /// How many obstacles the box hits.
    fn hits(&self, b: &Bounds) -> usize {
        self.obstacles.iter().filter(|o| o.hit_by(b)).count()
    }

    /// Place `label` at the first candidate, nearest distance first and the preferred
    /// direction first at each distance, inside the frame and clear of every obstacle; when
    /// none is clear, the candidate inside the frame that hits the fewest. Its box (and leader)
    /// become obstacles of the labels placed after it.
    pub fn place(&mut self, label: &Label) -> Placed {
        let (w, h) = {
            let b = box_of(&label.text, label.size, (0.0, 0.0));
            (b.x1 - b.x0, b.y1 - b.y0)
        };
        let norm = label.toward.0.hypot(label.toward.1);
        let prefer = if norm > 0.0 {
            label.toward.1.atan2(label.toward.0)
        } else {
            0.0
        };
        // Directions alternately either side of the preferred one.
        let turns = (0..DIRECTIONS).map(|k| {
            let side = if k % 2 == 1 { 1.0 } else { -1.0 };
            prefer + side * (k.div_ceil(2)) as f64 * std::f64::consts::TAU / DIRECTIONS as f64
        });
        let turns: Vec<f64> = turns.collect();
        let (ax, ay) = label.anchor;
        let mut best: Option<(bool, usize, Bounds, usize)> = None;
        'search: for (s, step) in STEPS.iter().enumerate() {
            for &t in &turns {
                let (ux, uy) = (t.cos(), t.sin());
                // The box's centre so that its edge nearest the anchor is gap + step away
                // along the direction (a box's half-extent along u: |ux|·w/2 + |uy|·h/2,
                // capped so that a diagonal does not push it twice as far).
                let reach = (ux.abs() * w / 2.0 + uy.abs() * h / 2.0).min((w / 2.0).hypot(h / 2.0));
                let d = label.gap + step + reach;
                let b = box_of(&label.text, label.size, (ax + ux * d, ay + uy * d));
                let outside = !self.frame.contains(&b);
                let hits = self.hits(&b);
                let key = (outside, hits);
                if best.is_none_or(|(o, n, _, _)| key < (o, n)) {
                    best = Some((outside, hits, b, s));
                }
                if !outside && hits == 0 {
                    break 'search;
                }
            }
        }
        let (_, _, bounds, s) = best.expect("at least one candidate");
        let leader = (s >= 2).then(|| (label.anchor, bounds.nearest(label.anchor)));
        self.obstacles.push(Obstacle::Box(bounds));
        if let Some((a, b)) = leader {
            self.obstacles.push(Obstacle::Segment(a, b));
        }
        Placed {
            bounds,
            x: bounds.x0 + PAD,
            y: bounds.y0 + PAD + 0.8 * label.size,
            leader,
            text: label.text.clone(),
            size: label.size,
        }
    }
}

impl Placed {
    /// The label as SVG: its leader line (thin grey, class `leader`) and its text (class
    /// `label`, a white halo, start-anchored), in `color`.
    pub fn draw(&self, color: &str, bold: bool) -> Markup {
        html! {
            @if let Some((a, b)) = self.leader {
                line.leader x1=(px(a.0)) y1=(px(a.1)) x2=(px(b.0)) y2=(px(b.1)) stroke="#777"
                    stroke-width="0.8" {}
            }
            text.label x=(px(self.x)) y=(px(self.y)) font-size=(self.size)
                font-weight=[bold.then_some("bold")] fill=(color) stroke="white"
                stroke-width=(self.size * 0.28) stroke-linejoin="round" paint-order="stroke" {
                    (self.text)
                }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A segment through a box, one beside it, one ending inside it; by hand.
    #[test]
    fn segments_through_a_box_are_found() {
        let b = Bounds::new(0.0, 0.0, 10.0, 10.0);
        assert!(b.hits_segment((-5.0, 5.0), (15.0, 5.0)));
        assert!(b.hits_segment((5.0, 5.0), (50.0, 50.0)));
        assert!(!b.hits_segment((-5.0, 12.0), (15.0, 12.0)));
        assert!(!b.hits_segment((11.0, -20.0), (30.0, 20.0)));
        // The diagonal near the corner (12, 0)–(0, 12) passes through (6, 6): inside.
        assert!(b.hits_segment((12.0, 0.0), (0.0, 12.0)));
        // (30, 0)–(0, 30) passes 20 from the origin along x = y: outside the 10 × 10 box.
        assert!(!b.hits_segment((30.0, 0.0), (0.0, 30.0)));
    }

    /// A ring is hit only across its outline; a disc by any overlap.
    #[test]
    fn rings_are_hit_across_their_outline_and_discs_anywhere() {
        let inside = Bounds::new(-2.0, -2.0, 2.0, 2.0);
        assert!(!Obstacle::Ring((0.0, 0.0), 10.0).hit_by(&inside));
        assert!(Obstacle::Disc((0.0, 0.0), 10.0).hit_by(&inside));
        let across = Bounds::new(8.0, -1.0, 12.0, 1.0);
        assert!(Obstacle::Ring((0.0, 0.0), 10.0).hit_by(&across));
        let outside = Bounds::new(11.0, -1.0, 15.0, 1.0);
        assert!(!Obstacle::Ring((0.0, 0.0), 10.0).hit_by(&outside));
        assert!(!Obstacle::Disc((0.0, 0.0), 10.0).hit_by(&outside));
    }

    /// A label whose preferred side is blocked by a line goes elsewhere, clear of the line,
    /// the first label and the frame; a second label at the same anchor does not cover the
    /// first.
    #[test]
    fn labels_avoid_lines_each_other_and_the_frame() {
        let mut layout = Layout::new(Bounds::new(0.0, 0.0, 200.0, 200.0));
        layout
            .obstacles
            .push(Obstacle::Segment((110.0, 0.0), (110.0, 200.0)));
        let label = Label {
            text: "17298 N".into(),
            size: 11.0,
            anchor: (100.0, 100.0),
            gap: 4.0,
            toward: (1.0, 0.0),
        };
        let a = layout.place(&label);
        let b = layout.place(&label);
        for p in [&a, &b] {
            assert!(!p.bounds.hits_segment((110.0, 0.0), (110.0, 200.0)));
            assert!(layout.frame.contains(&p.bounds));
        }
        assert!(!a.bounds.overlaps(&b.bounds));
        // Near the frame's corner, pushed right by its preference, it stays inside.
        let c = layout.place(&Label {
            anchor: (195.0, 195.0),
            ..label
        });
        assert!(layout.frame.contains(&c.bounds), "{c:?}");
    }
}
