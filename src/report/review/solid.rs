//! The disc as a solid, pictured beside the drawing: the triangle mesh the engine built
//! ([`engine::commands::solid_picture`](crate::engine::commands::solid_picture)) in an isometric view, each facet
//! facing the viewer flat-shaded by its normal against a fixed light, drawn far to near
//! (the painter's algorithm).
//!
//! Order: every wall first, far to near by its centroid, then the top face z = B. Seen from
//! above (the view's z > 0) nothing of a wall lies in front of the top face: a sight line that
//! leaves an outer wall toward the viewer runs outward, away from the face, and one that leaves
//! a hole's wall runs up through the hole. The bottom face never faces the viewer.

use crate::engine::commands::solid_picture::SolidPicture;
use crate::geometry::disc_mesh::{cross, dot, unit_normal};
use crate::numeric::extent;
use crate::report::svg::{document, px, trimmed};
use maud::{html, PreEscaped};

/// The view direction, toward the viewer (isometric: equal angles with the three axes), disc
/// frame: from the +x, −y side, above the face z = B.
pub const VIEW: [f64; 3] = [
    0.577_350_269_189_625_8,
    -0.577_350_269_189_625_8,
    0.577_350_269_189_625_8,
];

/// The light's direction (toward the light), unit: above, to the viewer's left.
const LIGHT: [f64; 3] = [
    -0.267_261_241_912_424_4,
    -0.534_522_483_824_848_8,
    0.801_783_725_737_273_2,
];

/// Picture size, pixels, and the margin around the solid.
const W: f64 = 660.0;
const H: f64 = 520.0;
const MARGIN: f64 = 16.0;

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    a.map(|x| x / n)
}

/// The view's screen axes, mm: right r = ẑ × v (horizontal) and up u = v × r, so that
/// (r, u, v) is right-handed and the screen point of p is (p·r, −p·u) with y down.
pub fn screen_axes() -> ([f64; 3], [f64; 3]) {
    let r = unit(cross([0.0, 0.0, 1.0], VIEW));
    (r, cross(VIEW, r))
}

/// A facet as drawn: its screen points (mm, y down), its depth along the view (larger is
/// nearer), whether it is on the top face, and its grey.
struct Facet {
    points: [(f64, f64); 3],
    depth: f64,
    top: bool,
    shade: u8,
}

/// The facets that face the viewer (n·v > 0; a wall seen edge-on is left out), far to near,
/// the top face last.
fn facets(solid: &SolidPicture) -> Vec<Facet> {
    let (r, u) = screen_axes();
    let mesh = &solid.mesh;
    let mut out: Vec<Facet> = (mesh.triangles.iter())
        .filter_map(|t| {
            let [a, b, c] = t.map(|i| mesh.vertices[i]);
            // A degenerate triangle's zero normal faces nobody.
            let n = unit_normal(a, b, c);
            if dot(n, VIEW) <= 1e-9 {
                return None;
            }
            let lit = 0.3 + 0.7 * dot(n, LIGHT).max(0.0);
            let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
            Some(Facet {
                points: [a, b, c].map(|p| (dot(p, r), -dot(p, u))),
                depth: dot(centroid, VIEW),
                top: n[2] > 0.5,
                shade: (255.0 * lit).round() as u8,
            })
        })
        .collect();
    out.sort_by(|f, g| (f.top, f.depth).partial_cmp(&(g.top, g.depth)).unwrap());
    out
}

/// The picture: an SVG whose `<g class="solid">` holds one `<polygon>` per facet drawn, its
/// points in screen mm (class `face` on the top face, `wall` on a wall), scaled into place
/// by the group's transform; and how many facets it draws.
pub fn picture(solid: &SolidPicture) -> (String, usize) {
    let drawn = facets(solid);
    let xs = drawn.iter().flat_map(|f| f.points.map(|p| p.0));
    let ys = drawn.iter().flat_map(|f| f.points.map(|p| p.1));
    let ((x0, x1), (y0, y1)) = (extent(xs), extent(ys));
    let top = 34.0;
    let scale = ((W - 2.0 * MARGIN) / (x1 - x0)).min((H - top - MARGIN) / (y1 - y0));
    let tx = 0.5 * W - scale * 0.5 * (x0 + x1);
    let ty = top + 0.5 * (H - top - MARGIN) - scale * 0.5 * (y0 + y1);
    let mut polygons = String::with_capacity(100 * drawn.len());
    for f in &drawn {
        let g = format!("{:02x}", f.shade);
        // Screen coordinates in mm, to 1 µm.
        let pts: Vec<String> = (f.points.iter())
            .map(|&(x, y)| format!("{},{}", trimmed(x, 3), trimmed(y, 3)))
            .collect();
        let class = if f.top { "face" } else { "wall" };
        polygons += &format!(
            "<polygon class=\"{class}\" points=\"{}\" fill=\"#{g}{g}{g}\" stroke=\"#{g}{g}{g}\"/>",
            pts.join(" ")
        );
    }
    let body = html! {
        text x="16" y="22" font-size="15" font-weight="bold" {
            "The disc as a solid (isometric view of the STL mesh)"
        }
        g.solid transform=(format!("translate({},{}) scale({})", px(tx), px(ty), format!("{scale:.6}")))
            stroke-width=(format!("{:.4}", 0.8 / scale)) stroke-linejoin="round" {
            (PreEscaped(polygons))
        }
    };
    (document(W, H, body), drawn.len())
}
