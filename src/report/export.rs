//! Profile export: the modified disc profile as CSV points and as a closed DXF polyline,
//! spaced so that the chordal error (distance of the true profile from each chord) stays
//! under a tolerance.

use crate::engine::commands::{Disc, DiscSource};
pub use crate::geometry::polyline::{polyline, ProfilePoint};
use crate::model::design::disc_phase_rad;
use crate::numeric::fixed;
use crate::spec::Spec;
use crate::units;
use serde::Serialize;

fn header_lines(spec: &Spec, tolerance_mm: f64, count: usize) -> Vec<String> {
    let m = &spec.modification;
    vec![
        format!("cycloid profile of spec `{}` ({})", spec.name, spec.path),
        format!(
            "modification: shift {} mm, equidistant {} mm, rotation {} deg",
            m.shift_mm,
            m.equidistant_mm,
            units::deg(m.rotation_rad)
        ),
        format!(
            "units: mm, disc frame (origin at disc centre, tooth root on +x); \
             {count} points, chordal error <= {} um",
            units::um(tolerance_mm)
        ),
    ]
}

/// The profile as columns, one value per point in profile order (disc frame, mm; the outward
/// unit normal; the curvature, 1/mm, positive where convex), and the output-pin holes of the
/// DXF (centres on the pin circle, hole radius). What `profile --csv` writes (at its
/// decimals) and the Python `profile` returns as arrays.
#[derive(Serialize)]
pub struct ProfileDoc {
    pub x_mm: Vec<f64>,
    pub y_mm: Vec<f64>,
    pub normal_x: Vec<f64>,
    pub normal_y: Vec<f64>,
    pub curvature_per_mm: Vec<f64>,
    pub holes_x_mm: Vec<f64>,
    pub holes_y_mm: Vec<f64>,
    pub hole_radius_mm: f64,
}

impl ProfileDoc {
    /// The document of the profile `points` of `spec`.
    pub fn new(spec: &Spec, points: &[ProfilePoint]) -> Self {
        let column = |f: fn(&ProfilePoint) -> f64| points.iter().map(f).collect();
        let pins = &spec.design.pins;
        let centres: Vec<[f64; 2]> = (0..pins.count).map(|j| pins.centre_mm(j)).collect();
        ProfileDoc {
            x_mm: column(|p| p.point.x),
            y_mm: column(|p| p.point.y),
            normal_x: column(|p| p.normal.x),
            normal_y: column(|p| p.normal.y),
            curvature_per_mm: column(|p| p.curvature_per_mm),
            holes_x_mm: centres.iter().map(|c| c[0]).collect(),
            holes_y_mm: centres.iter().map(|c| c[1]).collect(),
            hole_radius_mm: spec.design.hole_radius_mm(),
        }
    }
}

/// CSV text: `#` header lines, then the profile document's point columns,
/// x_mm,y_mm,normal_x,normal_y,curvature_per_mm.
pub fn csv(spec: &Spec, points: &[ProfilePoint], tolerance_mm: f64) -> String {
    let mut out: String = header_lines(spec, tolerance_mm, points.len())
        .iter()
        .map(|l| format!("# {l}\n"))
        .collect();
    let d = ProfileDoc::new(spec, points);
    out += "x_mm,y_mm,normal_x,normal_y,curvature_per_mm\n";
    for i in 0..d.x_mm.len() {
        out += &format!(
            "{:.9},{:.9},{:.12},{:.12},{:.9e}\n",
            d.x_mm[i], d.y_mm[i], d.normal_x[i], d.normal_y[i], d.curvature_per_mm[i]
        );
    }
    out
}

/// DXF (R12) text of the profile document: one closed POLYLINE on layer PROFILE, and the
/// output-pin holes as CIRCLE entities on layers HOLE_0 … HOLE_{M−1} (hole j at angle 2πj/M on
/// the pin circle, its radius the pin's plus e plus the hole clearance; cut in the same set-up,
/// they fix the rotation modification), units mm ($INSUNITS = 4).
pub fn dxf(spec: &Spec, points: &[ProfilePoint], tolerance_mm: f64) -> String {
    let d = ProfileDoc::new(spec, points);
    let mut out = String::new();
    let mut pair = |code: i32, value: &str| out += &format!("{code}\n{value}\n");
    for line in header_lines(spec, tolerance_mm, points.len()) {
        pair(999, &line);
    }
    for (code, value) in [(0, "SECTION"), (2, "HEADER"), (9, "$INSUNITS"), (70, "4")] {
        pair(code, value);
    }
    pair(0, "ENDSEC");
    for (code, value) in [
        (0, "SECTION"),
        (2, "ENTITIES"),
        (0, "POLYLINE"),
        (8, "PROFILE"),
    ] {
        pair(code, value);
    }
    for (code, value) in [(66, "1"), (70, "1"), (10, "0.0"), (20, "0.0"), (30, "0.0")] {
        pair(code, value);
    }
    for (x, y) in d.x_mm.iter().zip(&d.y_mm) {
        pair(0, "VERTEX");
        pair(8, "PROFILE");
        pair(10, &format!("{x:.9}"));
        pair(20, &format!("{y:.9}"));
        pair(30, "0.0");
    }
    for (code, value) in [(0, "SEQEND"), (8, "PROFILE")] {
        pair(code, value);
    }
    for (j, (x, y)) in d.holes_x_mm.iter().zip(&d.holes_y_mm).enumerate() {
        pair(0, "CIRCLE");
        pair(8, &format!("HOLE_{j}"));
        pair(10, &format!("{x:.9}"));
        pair(20, &format!("{y:.9}"));
        pair(30, "0.0");
        pair(40, &format!("{:.9}", d.hole_radius_mm));
    }
    for (code, value) in [(0, "ENDSEC"), (0, "EOF")] {
        pair(code, value);
    }
    out
}

/// The lines `profile` prints about the STEP solid (`pieces`: its cubic pieces, when it was
/// written) and the STL mesh (`triangles`: its triangles, when it was written) of `disc`: what
/// they hold and what they do not (no bore without the bearing's outer diameter).
pub fn solid_lines(
    disc: &Disc,
    pieces: Option<usize>,
    triangles: Option<usize>,
    tolerance_um: f64,
) -> String {
    let mut out = String::new();
    let profile = match disc.source {
        DiscSource::Drawing => "the drawing's profile",
        DiscSource::Ground => {
            "the disc as ground (the drawing's modification with reducer.deviations' grinding \
             and form errors)"
        }
        DiscSource::Measured => "the disc as built (identified from `measured_profile`)",
    };
    if let Some(n) = pieces {
        out += &format!(
            "STEP solid: {profile} as {n} cubic B-spline pieces within {tolerance_um} um, \
             extruded over the face width\n"
        );
    }
    if let Some(n) = triangles {
        out += &format!("STL mesh: {profile}, {n} triangles within {tolerance_um} um, closed\n");
    }
    out += &format!("holes: {} output-pin holes; ", disc.holes.len());
    out += &match disc.bore {
        Some(c) => format!("bore {} mm\n", crate::numeric::input(2.0 * c.radius_mm)),
        None => "no bore (give reducer.crank_bearing.outer_diameter_mm to cut one)\n".to_string(),
    };
    let n = disc.bodies.len();
    if n > 1 {
        out += &format!(
            "discs: {n} bodies, each disc where the reducer puts it at crank angle 0 (the \
             reducer's frame: origin on the input axis, roller 0 on +x):\n"
        );
    }
    for (k, body) in disc.bodies.iter().enumerate().filter(|_| n > 1) {
        let p = &body.placement;
        let part = if body.hole_turn_rad == 0.0 {
            "disc 1's part".to_string()
        } else {
            format!(
                "a part of its own: its holes turned {} deg from disc 1's about its teeth",
                fixed(units::deg(body.hole_turn_rad), 4)
            )
        };
        out += &format!(
            "  disc {}: crank phase {} deg, centre ({}, {}) mm, turned {} deg, z {} to {} mm; \
             {part}\n",
            k + 1,
            fixed(units::deg(disc_phase_rad(k, n)), 1),
            fixed(p.centre.x, 4),
            fixed(p.centre.y, 4),
            fixed(units::deg(p.turn_rad), 4),
            fixed(p.z_mm, 3),
            fixed(p.z_mm + disc.face_width_mm, 3),
        );
    }
    out
}
