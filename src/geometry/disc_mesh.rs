//! The disc as a closed triangle mesh (what `profile --stl` writes): the profile's polyline and
//! the circles' inscribed polygons, each within the tolerance, as walls from z = 0 to z = B,
//! and the two faces triangulated between them (ear clipping with the holes bridged in,
//! the `earcut` crate).

use super::disc_solid::{circle_polygon, Circle};
use super::Vec2;

/// Triangles over shared vertices, each counter-clockwise seen from outside the solid (its
/// normal outward). Disc frame, mm.
#[derive(Debug, Clone, PartialEq)]
pub struct TriangleMesh {
    pub vertices: Vec<[f64; 3]>,
    pub triangles: Vec<[usize; 3]>,
}

/// The mesh of the prism from z = 0 to `face_width_mm` whose face is the region inside
/// `outline` (counter-clockwise, the profile's polyline) less `circles`, every circle an
/// inscribed polygon within `tolerance_mm`. `None` when the face's triangulation does not
/// cover it (ear clipping leaves a self-touching region untriangulated); the caller says so.
pub fn disc_mesh(
    outline: &[Vec2],
    circles: &[Circle],
    face_width_mm: f64,
    tolerance_mm: f64,
) -> Option<TriangleMesh> {
    // Rings: the outline counter-clockwise, each hole clockwise, so that every ring has the
    // material on its left and its wall's outward normal on its right.
    let mut rings = vec![outline.to_vec()];
    rings.extend(
        circles
            .iter()
            .map(|c| circle_polygon(c, tolerance_mm, true)),
    );
    let flat: Vec<Vec2> = rings.iter().flatten().copied().collect();
    let n = flat.len();
    let mut vertices: Vec<[f64; 3]> = flat.iter().map(|p| [p.x, p.y, 0.0]).collect();
    vertices.extend(flat.iter().map(|p| [p.x, p.y, face_width_mm]));
    let mut triangles = Vec::with_capacity(4 * n);
    let mut start = 0;
    for ring in &rings {
        for i in 0..ring.len() {
            let (a, b) = (start + i, start + (i + 1) % ring.len());
            triangles.push([a, b, b + n]);
            triangles.push([a, b + n, a + n]);
        }
        start += ring.len();
    }
    for [a, b, c] in face_triangles(&rings, &flat)? {
        triangles.push([a + n, b + n, c + n]);
        triangles.push([a, c, b]);
    }
    Some(TriangleMesh {
        vertices,
        triangles,
    })
}

/// Counter-clockwise triangles of the face between the rings, as indices into `flat` (the
/// rings one after the other). A face of V vertices and H holes has V + 2H − 2 triangles
/// (Euler's formula for a triangulated disc with H holes); fewer means a part was left out.
fn face_triangles(rings: &[Vec<Vec2>], flat: &[Vec2]) -> Option<Vec<[usize; 3]>> {
    let mut hole_starts = Vec::new();
    let mut start = 0;
    for ring in &rings[..rings.len() - 1] {
        start += ring.len();
        hole_starts.push(start);
    }
    let mut indices: Vec<usize> = Vec::new();
    earcut::Earcut::new().earcut(flat.iter().map(|p| [p.x, p.y]), &hole_starts, &mut indices);
    let expected = flat.len() + 2 * hole_starts.len() - 2;
    if indices.len() != 3 * expected {
        return None;
    }
    let triangles = indices.chunks_exact(3).map(|t| {
        let [a, b, c] = [t[0], t[1], t[2]];
        let area2 = super::cross(flat[b] - flat[a], flat[c] - flat[a]);
        if area2 < 0.0 {
            [a, c, b]
        } else {
            [a, b, c]
        }
    });
    Some(triangles.collect())
}

/// a · b.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The unit normal of the triangle (a, b, c), outward for a triangle of a `TriangleMesh`:
/// (b − a) × (c − a), made unit (−0 written as 0); a degenerate triangle (zero area) gets the
/// zero normal, which STL readers recompute from the vertices.
pub fn unit_normal(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = cross(u, v);
    let len = dot(n, n).sqrt();
    if len > 0.0 {
        n.map(|x| x / len + 0.0)
    } else {
        [0.0; 3]
    }
}
