//! The disc as an ASCII STL mesh: one facet per triangle, its unit normal outward, vertices
//! counter-clockwise seen from outside, mm, nine decimals (1 pm) as the CSV's coordinates.

use super::review::solid::{cross, dot};
use crate::geometry::disc_mesh::TriangleMesh;
use crate::spec::Spec;

/// The STL text of `mesh`, named after `spec`'s name (printable ASCII only; STL has no
/// escapes).
pub fn stl(spec: &Spec, mesh: &TriangleMesh) -> String {
    let name: String = (spec.name.chars())
        .map(|c| if c.is_ascii_graphic() { c } else { '_' })
        .collect();
    let mut out = format!("solid {name}\n");
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.vertices[i]);
        let n = unit_normal(a, b, c);
        out += &format!(
            "facet normal {:.9} {:.9} {:.9}\n outer loop\n",
            n[0], n[1], n[2]
        );
        for v in [a, b, c] {
            out += &format!("  vertex {:.9} {:.9} {:.9}\n", v[0], v[1], v[2]);
        }
        out += " endloop\nendfacet\n";
    }
    out + &format!("endsolid {name}\n")
}

/// (b − a) × (c − a), made unit; a degenerate triangle (zero area) gets the zero normal, which
/// STL readers recompute from the vertices.
fn unit_normal(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> [f64; 3] {
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
