//! The disc as an ASCII STL mesh: one facet per triangle, its unit normal outward, vertices
//! counter-clockwise seen from outside, mm, nine decimals (1 pm) as the CSV's coordinates.

use crate::geometry::disc_mesh::{unit_normal, TriangleMesh};
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
