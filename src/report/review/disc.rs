//! The review's disc at one crank angle, drawn as [`engine::drawing`](crate::engine::drawing) computed it: the whole disc
//! with its holes, the pins, the rollers and the forces; and a true-scale close-up of the
//! tightest roller's gap (`disc::section`).

use super::common::{figure, Section};
use crate::engine::commands::solid_picture::SolidPicture;
use crate::engine::commands::DiscSource;
use crate::engine::drawing::{Disc, Part};
use crate::geometry::{z_cross, Vec2};
use crate::numeric::number;
use crate::report::svg::frame::Frame;
use crate::report::svg::labels::{self, Bounds, Label, Layout, Obstacle};
use crate::report::svg::{document, px, ticks, RED};
use crate::spec::Spec;
use crate::units;
use maud::{html, Markup};

/// Colours of the forces on the disc: rollers, output pins, crank bearing.
const PIN_GREEN: &str = "#2ca02c";
const BEARING_PURPLE: &str = "#9467bd";

/// The longest force arrow and the shortest drawn, mm.
const ARROW_MM: f64 = 12.0;
const SHORTEST_ARROW_MM: f64 = 2.5;

/// The disc at the drawing's crank angle and the close-up of its tightest roller.
pub(super) fn section(
    spec: &Spec,
    disc: &Disc,
    solid: Option<&SolidPicture>,
    files: &mut Vec<(String, String)>,
) -> Section {
    let d = &spec.design;
    let phi = format!("{:.2}", units::deg(disc.crank_rad));
    let (whole, whole_caption) = whole(disc, d.teeth, d.eccentricity_mm);
    let (detail, detail_caption) = close_up(disc);
    files.push(("disc.svg".into(), whole));
    files.push(("disc-detail.svg".into(), detail));
    let solid = solid.map(|s| {
        let (svg, drawn) = super::solid::picture(s);
        files.push(("disc-solid.svg".into(), svg));
        solid_caption(s, d.pins.count, drawn)
    });
    let body = html! {
        div.grid {
            (figure("disc.svg", &format!("Disc, rollers and output pins at crank φ = {phi}°"),
                &whole_caption))
            @if let Some(caption) = &solid {
                (figure("disc-solid.svg", "The disc as a solid", caption))
            }
            (figure("disc-detail.svg", "Close-up of the smallest gap", &detail_caption))
        }
    };
    Section::new("disc", html! { "The disc at crank φ = " (phi) "°" }, body)
}

/// The solid's caption: the view, what the mesh is, its tolerance, the face width and bore.
fn solid_caption(s: &SolidPicture, holes: usize, drawn: usize) -> String {
    let bore = match s.bore_diameter_mm {
        Some(d) => format!("the crank bearing's bore ⌀ {} mm", number(d)),
        None => "no bore (reducer.crank_bearing.outer_diameter_mm not given)".into(),
    };
    let built = match s.source {
        DiscSource::Drawing => "",
        DiscSource::Ground => " as ground (with reducer.deviations' grinding and form errors)",
        DiscSource::Measured => " as built (identified from the measured profile)",
    };
    format!(
        "Isometric view, from the +x, −y side above the face z = B, of the closed triangle \
         mesh that profile --stl writes{built}, here at a chordal tolerance of {} µm (the \
         export's default is 0.5 µm) to keep the picture small: {} triangles, of which the \
         {drawn} facing the viewer are drawn, flat-shaded by their normals, far to near. Face \
         width B = {} mm; {holes} output-pin holes; {bore}.",
        number(units::um(s.tolerance_mm)),
        s.mesh.triangles.len(),
        number(s.face_width_mm),
    )
}

/// An arrow from `from` to `to` (world): its shaft and head, the segments a label must keep
/// clear of, and the label to place at its head (pointing on along the arrow).
fn arrow(f: &Frame, from: Vec2, to: Vec2, color: &str, label: &str) -> Option<Arrow> {
    let d = to - from;
    let len = f.len(d.norm());
    if len < 1.0 {
        return None;
    }
    let u = Vec2::new(d.x, -d.y) / d.norm();
    let (hx, hy) = f.at(to);
    let head = 9.0_f64.min(len * 0.5);
    let (bx, by) = (hx - u.x * head, hy - u.y * head);
    let side = z_cross(u) * head * 0.45;
    let (fx, fy) = f.at(from);
    let corners = [
        (hx, hy),
        (bx + side.x, by + side.y),
        (bx - side.x, by - side.y),
    ];
    let head_points = crate::report::svg::points(corners);
    let mut segments = vec![Obstacle::Segment((fx, fy), (bx, by))];
    segments.extend(labels::polyline(&[
        corners[0], corners[1], corners[2], corners[0],
    ]));
    Some(Arrow {
        drawn: html! {
            line x1=(px(fx)) y1=(px(fy)) x2=(px(bx)) y2=(px(by)) stroke=(color)
                stroke-width="2.2" {}
            polygon points=(head_points) fill=(color) {}
        },
        segments,
        label: Label {
            text: label.to_string(),
            size: 11.0,
            anchor: (hx, hy),
            gap: 3.0,
            toward: (u.x, u.y),
        },
        color: color.to_string(),
    })
}

/// A force arrow as drawn, what labels avoid, and its label.
struct Arrow {
    drawn: Markup,
    segments: Vec<Obstacle>,
    label: Label,
    color: String,
}

/// The forces as arrows at one scale (the largest ARROW_MM long, none shorter than
/// SHORTEST_ARROW_MM so that small forces stay visible). A roller's arrow ends at its contact
/// (it starts in the roller); a pin's and the bearing's start at their point.
fn force_arrows(f: &Frame, disc: &Disc) -> Vec<Arrow> {
    let Some(loaded) = &disc.loaded else {
        return Vec::new();
    };
    let biggest = loaded
        .forces
        .iter()
        .map(|f| f.force_n.norm())
        .fold(0.0, f64::max);
    let k = ARROW_MM / biggest;
    let mut out = Vec::new();
    for force in &loaded.forces {
        let n = force.force_n.norm();
        let drawn = force.force_n * k * (SHORTEST_ARROW_MM / (n * k)).max(1.0);
        let label = format!("{} N", number(n));
        out.extend(match force.part {
            Part::Roller(_) => arrow(f, force.point - drawn, force.point, RED, &label),
            Part::Pin(_) => arrow(f, force.point, force.point + drawn, PIN_GREEN, &label),
            Part::Bearing => arrow(
                f,
                force.point,
                force.point + drawn,
                BEARING_PURPLE,
                &format!("Fb {label}"),
            ),
        });
    }
    out
}

/// Circles of `radius_mm` around `centres` as SVG subpaths, to follow the profile's path in
/// one `path` with `fill-rule="evenodd"`: the disc with its holes cut out.
pub(super) fn hole_cutouts(f: &Frame, centres: &[Vec2], radius_mm: f64) -> String {
    let r = f.len(radius_mm);
    centres
        .iter()
        .map(|&c| {
            let (x, y) = f.at(c);
            let (x, y, d, back, r) = (px(x - r), px(y), px(2.0 * r), px(-2.0 * r), px(r));
            format!(" M{x},{y} a{r},{r} 0 1,0 {d},0 a{r},{r} 0 1,0 {back},0 Z")
        })
        .collect()
}

/// The disc at its pose with the rollers, pins and forces: (SVG, caption). The labels (roller
/// numbers, forces) are placed by `svg::labels` clear of the profile, the holes, pins, rollers,
/// the crank, the arrows and each other, inside the figure under its titles.
pub fn whole(disc: &Disc, teeth: usize, eccentricity_mm: f64) -> (String, String) {
    let outer = disc.roller_circle_radius_mm + disc.roller_radius_mm;
    let half = outer + 7.0;
    let (w, h) = (660.0, 700.0);
    let f = Frame::fit((-half, half, -half, half), (10.0, 50.0, w - 20.0, h - 60.0));
    let phi = units::deg(disc.crank_rad);
    let tight = disc.tightest.roller;
    let holes = hole_cutouts(&f, &disc.holes, disc.hole_radius_mm);
    let (cx, cy) = f.at(disc.centre);
    let (ox, oy) = (f.x(0.0), f.y(0.0));
    let arrows = force_arrows(&f, disc);
    let scale_bar = (w - 30.0 - f.len(10.0), h - 36.0, w - 30.0, h - 18.0);
    let mut layout = Layout::new(Bounds::new(2.0, 50.0, w - 2.0, h - 2.0));
    let profile: Vec<(f64, f64)> = disc.profile.iter().map(|&p| f.at(p)).collect();
    layout.obstacles.extend(labels::polyline(&profile));
    if let (Some(&first), Some(&last)) = (profile.first(), profile.last()) {
        layout.obstacles.push(Obstacle::Segment(last, first));
    }
    let r_hole = f.len(disc.hole_radius_mm);
    let r_pin = f.len(disc.pin_radius_mm);
    let r_roller = f.len(disc.roller_radius_mm);
    layout
        .obstacles
        .extend(disc.holes.iter().map(|&c| Obstacle::Ring(f.at(c), r_hole)));
    layout
        .obstacles
        .extend(disc.pins.iter().map(|&c| Obstacle::Disc(f.at(c), r_pin)));
    // A roller's ring with its stroke (2.5 px on the tightest).
    let rollers = disc
        .rollers
        .iter()
        .map(|&c| Obstacle::Disc(f.at(c), r_roller + 1.5));
    layout.obstacles.extend(rollers);
    layout.obstacles.push(Obstacle::Segment((ox, oy), (cx, cy)));
    layout.obstacles.push(Obstacle::Disc((ox, oy), 4.0));
    layout.obstacles.push(Obstacle::Disc((cx, cy), 4.0));
    let bar = Bounds::new(scale_bar.0 - 10.0, scale_bar.1, scale_bar.2, scale_bar.3);
    layout.obstacles.push(Obstacle::Box(bar));
    for a in &arrows {
        layout.obstacles.extend(a.segments.iter().copied());
    }
    // The roller numbers first, outward of their roller; then the forces, on along their arrow.
    let numbers: Vec<_> = disc
        .rollers
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            let (x, y) = f.at(c);
            let label = Label {
                text: i.to_string(),
                size: 13.0,
                anchor: (x, y),
                gap: r_roller + 3.0,
                toward: (x - ox, y - oy),
            };
            let color = if i == tight { RED } else { "#333" };
            (layout.place(&label), color)
        })
        .collect();
    let forces: Vec<_> = arrows
        .iter()
        .map(|a| (layout.place(&a.label), a.color.as_str()))
        .collect();
    let body = html! {
        text x="14" y="24" font-size="16" font-weight="bold" { "Disc at crank φ = " (format!("{phi:.2}")) "°" }
        text x="14" y="42" font-size="12" fill="#555" {
            "fixed frame; disc centre e·(cos φ, sin φ), disc turned by ψ = −φ/nc"
            @if disc.loaded.is_some() { " + β (loaded)" }
        }
        circle cx=(px(ox)) cy=(px(oy)) r=(px(f.len(disc.roller_circle_radius_mm)))
            fill="none" stroke="#aaa" stroke-dasharray="4 4" {}
        path.profile d=(f.path(&disc.profile) + &holes) fill="#cfe0f1" fill-rule="evenodd"
            stroke="#1f4e79" stroke-width="1.2" {}
        @for (j, &p) in disc.pins.iter().enumerate() {
            @let (x, y) = f.at(p);
            circle.pin cx=(px(x)) cy=(px(y)) r=(px(r_pin)) fill="#6b6b6b" stroke="#333" {}
            text x=(px(x)) y=(px(y + 4.0)) font-size="11" text-anchor="middle" fill="white" { (j) }
        }
        @for (i, &c) in disc.rollers.iter().enumerate() {
            @let (x, y) = f.at(c);
            circle.roller cx=(px(x)) cy=(px(y)) r=(px(r_roller)) fill="#e6e6e6"
                stroke=(if i == tight { RED } else { "#444" })
                stroke-width=(if i == tight { "2.5" } else { "1" }) {}
        }
        line.crank x1=(px(ox)) y1=(px(oy)) x2=(px(cx)) y2=(px(cy)) stroke=(RED)
            stroke-width="2" {}
        circle cx=(px(ox)) cy=(px(oy)) r="3" fill="#333" {}
        circle cx=(px(cx)) cy=(px(cy)) r="3" fill=(RED) {}
        g.arrows { @for a in &arrows { (a.drawn) } }
        @for (placed, color) in numbers.iter().chain(&forces) {
            (placed.draw(color, false))
        }
        (f.scale_bar(w - 30.0, h - 20.0, 10.0, "10 mm"))
    };
    let m = disc.pins.len();
    let mut caption = format!(
        "Blue: the modified disc ({teeth} teeth) with its {m} output-pin holes; grey circles: the \
         {} rollers (numbered) and the {m} pins; red line: the crank from the input axis to the \
         disc centre (e = {} mm). Roller {tight}, ringed in red, has the smallest gap at this \
         angle: {} µm.",
        disc.rollers.len(),
        number(eccentricity_mm),
        number(units::um(disc.tightest.gap_mm))
    );
    if let Some(l) = disc.loaded.as_ref().filter(|l| !l.forces.is_empty()) {
        caption += &format!(
            " Arrows: forces on the disc in scene `{}` at this angle, to one scale — red \
             rollers, green output pins, purple the crank bearing (the largest is {ARROW_MM} mm \
             long; none is drawn shorter than {SHORTEST_ARROW_MM} mm).",
            match l.disc {
                Some(k) => format!("{} (disc {k})", l.scene),
                None => l.scene.clone(),
            }
        );
    }
    (document(w, h, body), caption)
}

/// A small drawing of the disc (`size` px square, no text): its profile with the holes, the
/// rollers and the pins at the drawing's crank angle, as in `whole`; for a list of designs.
pub fn thumbnail(disc: &Disc, size: f64) -> String {
    let half = disc.roller_circle_radius_mm + disc.roller_radius_mm;
    let f = Frame::fit(
        (-half, half, -half, half),
        (2.0, 2.0, size - 2.0, size - 2.0),
    );
    let holes = hole_cutouts(&f, &disc.holes, disc.hole_radius_mm);
    let circles = |centres: &[Vec2], radius_mm: f64, fill: &'static str| {
        let r = px(f.len(radius_mm));
        html! { @for &c in centres {
            @let (x, y) = f.at(c);
            circle cx=(px(x)) cy=(px(y)) r=(r) fill=(fill) stroke="#444" stroke-width="0.5" {}
        } }
    };
    let body = html! {
        path.profile d=(f.path(&disc.profile) + &holes) fill="#cfe0f1" fill-rule="evenodd"
            stroke="#1f4e79" stroke-width="0.8" {}
        (circles(&disc.rollers, disc.roller_radius_mm, "#e6e6e6"))
        (circles(&disc.pins, disc.pin_radius_mm, "#6b6b6b"))
    };
    document(size, size, body)
}

/// The tightest roller against the disc flank, true scale, the gap along the normal:
/// (SVG, caption). The gap, tens of µm against a disc of tens of mm, cannot be seen in the
/// whole drawing.
pub fn close_up(disc: &Disc) -> (String, String) {
    let c = &disc.tightest;
    let window = (c.gap_mm.abs() * 14.0).clamp(0.3, 3.0);
    let (w, h) = (560.0, 560.0);
    let f = Frame::fit(
        (-window / 2.0, window / 2.0, -window * 0.4, window * 0.6),
        (40.0, 60.0, w - 80.0, h - 110.0),
    );
    // Disc material: the flank, closed far below the window.
    let mut wedge = c.flank.clone();
    wedge.push(Vec2::new(0.0, -50.0));
    let (x, y0, y1) = (f.x(0.0), f.y(0.0), f.y(c.gap_mm));
    let (color, what) = if c.gap_mm >= 0.0 {
        (PIN_GREEN, "gap")
    } else {
        (RED, "interference")
    };
    let (wx, wy, wl) = (f.x(-window / 2.0), f.y(window * 0.6), f.len(window));
    let bar = ticks(0.0, window / 3.0, 1, false).step;
    let tick = |y: f64| {
        html! { line x1=(px(x - 8.0)) y1=(px(y)) x2=(px(x + 8.0)) y2=(px(y)) stroke=(color) {} }
    };
    // The gap's label inside the window, clear of the flank, the roller's outline and the
    // gap's own marks.
    let mut layout = Layout::new(Bounds::new(wx, wy, wx + wl, wy + wl));
    let flank: Vec<(f64, f64)> = c.flank.iter().map(|&p| f.at(p)).collect();
    layout.obstacles.extend(labels::polyline(&flank));
    let (roller, r_roller) = (f.at(c.roller_centre), f.len(c.roller_radius_mm));
    layout.obstacles.push(Obstacle::Ring(roller, r_roller));
    layout.obstacles.push(Obstacle::Segment((x, y0), (x, y1)));
    for y in [y0, y1] {
        layout
            .obstacles
            .push(Obstacle::Segment((x - 8.0, y), (x + 8.0, y)));
    }
    let gap_label = layout.place(&Label {
        text: format!("{what} {} µm", number(units::um(c.gap_mm))),
        size: 14.0,
        anchor: (x + 10.0, (y0 + y1) / 2.0),
        gap: 2.0,
        toward: (1.0, 0.0),
    });
    let body = html! {
        text x="14" y="24" font-size="16" font-weight="bold" {
            "Roller " (c.roller) " at crank φ = " (format!("{:.2}", units::deg(disc.crank_rad)))
            "°, close-up"
        }
        text x="14" y="42" font-size="12" fill="#555" {
            "true scale, " (number(window)) " mm across; disc frame turned so the contact normal "
            "points up"
        }
        clipPath id="win" { rect x=(px(wx)) y=(px(wy)) width=(px(wl)) height=(px(wl)) {} }
        g clip-path="url(#win)" {
            path.profile d=(f.path(&wedge)) fill="#cfe0f1" stroke="#1f4e79" stroke-width="1.5" {}
            circle cx=(px(roller.0)) cy=(px(roller.1)) r=(px(r_roller)) fill="#e6e6e6"
                fill-opacity="0.85" stroke="#444" stroke-width="1.5" {}
        }
        line x1=(px(x)) y1=(px(y0)) x2=(px(x)) y2=(px(y1)) stroke=(color) stroke-width="2" {}
        (tick(y0))
        (tick(y1))
        (gap_label.draw(color, true))
        rect x=(px(wx)) y=(px(wy)) width=(px(wl)) height=(px(wl)) fill="none" stroke="#333" {}
        (f.scale_bar(f.x(window / 2.0), h - 22.0, bar, &format!("{:.0} µm", units::um(bar))))
    };
    let caption = format!(
        "Roller {} (grey) against the disc flank (blue) at tooth phase {} (0 root, 0.5 tip), \
         unloaded ideal pose, true scale. The smallest gap over the whole mesh is in the checks \
         table and the clearance plot.",
        c.roller,
        crate::numeric::phase(c.tooth_phase)
    );
    (document(w, h, body), caption)
}
