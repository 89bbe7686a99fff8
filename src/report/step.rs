//! The disc as a STEP solid (ISO 10303-21, AP214 `AUTOMOTIVE_DESIGN`): one
//! `MANIFOLD_SOLID_BREP` per disc (each of several where the reducer puts it), whose faces are
//! the profile's flanks (one face per tooth, a `B_SPLINE_SURFACE_WITH_KNOTS` extruding the
//! tooth's cubic `B_SPLINE_CURVE_WITH_KNOTS`), each hole and the bore (two half-cylinders
//! each) and the two planes z = 0 and z = B of the disc frame, in mm.
//!
//! Orientation (ISO 10303-42): a face's normal points out of the material, and each of its
//! loops runs counter-clockwise about that normal for the outer bound, clockwise for an inner
//! one; every edge is used by two faces in opposite directions (a closed shell).

use crate::geometry::disc_solid::{Bezier, Circle, DiscSolid};
use crate::geometry::placement::Placement;
use crate::spec::Spec;

/// Entity instances, numbered from #1 in the order they are added; every point and direction
/// moved by `at` from the disc frame (the disc being written).
struct Data {
    entities: Vec<String>,
    at: Placement,
}

type Id = usize;
type Point = [f64; 3];

const Z: Point = [0.0, 0.0, 1.0];
const X: Point = [1.0, 0.0, 0.0];

impl Data {
    fn add(&mut self, entity: String) -> Id {
        self.entities.push(entity);
        self.entities.len()
    }

    fn point(&mut self, p: Point) -> Id {
        let p = self.at.point(p);
        self.triple("CARTESIAN_POINT", p)
    }

    fn direction(&mut self, d: Point) -> Id {
        let d = self.at.direction(d);
        self.triple("DIRECTION", d)
    }

    /// An entity `kind` of three reals (a point or a direction, already placed).
    fn triple(&mut self, kind: &str, p: Point) -> Id {
        let [x, y, z] = p.map(real);
        self.add(format!("{kind}('',({x},{y},{z}))"))
    }

    fn placement(&mut self, origin: Point, axis: Point) -> Id {
        let (o, z, x) = (self.point(origin), self.direction(axis), self.direction(X));
        self.add(format!("AXIS2_PLACEMENT_3D('',#{o},#{z},#{x})"))
    }

    fn vertex(&mut self, p: Point) -> Id {
        let p = self.point(p);
        self.add(format!("VERTEX_POINT('',#{p})"))
    }

    fn edge(&mut self, from: Id, to: Id, curve: Id) -> Id {
        self.add(format!("EDGE_CURVE('',#{from},#{to},#{curve},.T.)"))
    }

    /// A vertical edge from `from` (at `p`, z = 0) up to `to`, of length `height`.
    fn vertical(&mut self, from: Id, to: Id, p: Point, height: f64) -> Id {
        let (origin, z) = (self.point(p), self.direction(Z));
        let v = self.add(format!("VECTOR('',#{z},{})", real(height)));
        let line = self.add(format!("LINE('',#{origin},#{v})"));
        self.edge(from, to, line)
    }

    /// An edge loop of (edge, forward) pairs.
    fn edge_loop(&mut self, edges: &[(Id, bool)]) -> Id {
        let oriented: Vec<String> = edges
            .iter()
            .map(|&(e, forward)| {
                let o = self.add(format!("ORIENTED_EDGE('',*,*,#{e},{})", logical(forward)));
                format!("#{o}")
            })
            .collect();
        self.add(format!("EDGE_LOOP('',({}))", oriented.join(",")))
    }

    /// A face on `surface` (its normal the surface's when `same_sense`) bounded by the outer
    /// loop and the inner ones.
    fn face(&mut self, surface: Id, same_sense: bool, outer: Id, inner: &[Id]) -> Id {
        let mut bounds = vec![self.add(format!("FACE_OUTER_BOUND('',#{outer},.T.)"))];
        for &l in inner {
            bounds.push(self.add(format!("FACE_BOUND('',#{l},.T.)")));
        }
        let bounds: Vec<String> = bounds.iter().map(|b| format!("#{b}")).collect();
        self.add(format!(
            "ADVANCED_FACE('',({}),#{surface},{})",
            bounds.join(","),
            logical(same_sense)
        ))
    }

    /// One tooth's control points at height z: P0 then P1, P2, P3 of each piece.
    fn controls(&mut self, pieces: &[Bezier], z: f64) -> Vec<String> {
        let mut controls = vec![pieces[0].control[0]];
        controls.extend(pieces.iter().flat_map(|b| b.control[1..].iter().copied()));
        (controls.iter())
            .map(|c| format!("#{}", self.point([c.x, c.y, z])))
            .collect()
    }

    /// A cubic B-spline through `controls` (one tooth's): knots the pieces' ends in t, end
    /// multiplicity 4 and interior 3 (each piece its own Bézier span).
    fn bspline(&mut self, pieces: &[Bezier], controls: &[String]) -> Id {
        let (mults, knots) = knots(pieces);
        self.add(format!(
            "B_SPLINE_CURVE_WITH_KNOTS('',3,({}),.UNSPECIFIED.,.F.,.F.,({mults}),({knots}),\
             .UNSPECIFIED.)",
            controls.join(",")
        ))
    }

    /// The flank of one tooth: the B-spline surface cubic in t and linear in z between the
    /// tooth's curves at z = 0 and z = B (exactly their extrusion). A B-spline surface rather
    /// than a `SURFACE_OF_LINEAR_EXTRUSION`: Open CASCADE integrates a face's area and volume
    /// span by span of a B-spline surface's knots, and over an extrusion's whole parameter
    /// range at once, which missed 6e-5 of the disc's volume.
    fn flank(&mut self, pieces: &[Bezier], bottom: &[String], top: &[String], b: f64) -> Id {
        let (mults, knots) = knots(pieces);
        let rows: Vec<String> = (bottom.iter().zip(top))
            .map(|(p, q)| format!("({p},{q})"))
            .collect();
        self.add(format!(
            "B_SPLINE_SURFACE_WITH_KNOTS('',3,1,({}),.UNSPECIFIED.,.F.,.F.,.F.,({mults}),(2,2),\
             ({knots}),(0.,{}),.UNSPECIFIED.)",
            rows.join(","),
            real(b)
        ))
    }
}

/// The knot multiplicities and knots of a tooth's B-spline, as STEP lists' contents.
fn knots(pieces: &[Bezier]) -> (String, String) {
    let mut knots = vec![real(pieces[0].t[0])];
    knots.extend(pieces.iter().map(|b| real(b.t[1])));
    let mut mults = vec!["3"; pieces.len() + 1];
    mults[0] = "4";
    mults[pieces.len()] = "4";
    (mults.join(","), knots.join(","))
}

/// A STEP real: the shortest decimal that reads back as the same double, always with a point
/// (Display never writes an exponent); −0 as 0.
fn real(x: f64) -> String {
    let s = format!("{}", x + 0.0);
    if s.contains('.') {
        s
    } else {
        s + "."
    }
}

fn logical(b: bool) -> &'static str {
    if b {
        ".T."
    } else {
        ".F."
    }
}

/// A STEP string of `text`: apostrophes and backslashes doubled, anything but printable ASCII
/// as `?` (the spec's name is free text).
fn string(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '\'' => "''".to_string(),
            '\\' => "\\\\".to_string(),
            ' '..='~' => c.to_string(),
            _ => "?".to_string(),
        })
        .collect()
}

/// The profile's faces: per tooth k, the bottom and top B-spline edges, the vertical edge at
/// its start, and the flank face. Returns the bottom and top edges (each tooth's, in order).
fn profile_faces(data: &mut Data, solid: &DiscSolid, faces: &mut Vec<Id>) -> (Vec<Id>, Vec<Id>) {
    let b = solid.face_width_mm;
    let starts: Vec<Point> = (solid.teeth.iter())
        .map(|pieces| [pieces[0].control[0].x, pieces[0].control[0].y, 0.0])
        .collect();
    let bottom_v: Vec<Id> = starts.iter().map(|&p| data.vertex(p)).collect();
    let top_v: Vec<Id> = starts
        .iter()
        .map(|&[x, y, _]| data.vertex([x, y, b]))
        .collect();
    let verticals: Vec<Id> = (0..starts.len())
        .map(|k| data.vertical(bottom_v[k], top_v[k], starts[k], b))
        .collect();
    let (mut bottom_e, mut top_e) = (Vec::new(), Vec::new());
    let n = starts.len();
    for (k, pieces) in solid.teeth.iter().enumerate() {
        let next = (k + 1) % n;
        let bottom = data.controls(pieces, 0.0);
        let top = data.controls(pieces, b);
        let curve = data.bspline(pieces, &bottom);
        let top_curve = data.bspline(pieces, &top);
        let eb = data.edge(bottom_v[k], bottom_v[next], curve);
        let et = data.edge(top_v[k], top_v[next], top_curve);
        let surface = data.flank(pieces, &bottom, &top, b);
        // The surface's normal ∂S/∂t × ∂S/∂z = Γ' × z points out of a counter-clockwise
        // profile.
        let l = data.edge_loop(&[
            (eb, true),
            (verticals[next], true),
            (et, false),
            (verticals[k], false),
        ]);
        faces.push(data.face(surface, true, l, &[]));
        bottom_e.push(eb);
        top_e.push(et);
    }
    (bottom_e, top_e)
}

/// A circle's two half-cylinder faces (normal toward its axis, out of the material); returns
/// its bottom and top inner loops.
fn circle_faces(data: &mut Data, c: &Circle, b: f64, faces: &mut Vec<Id>) -> (Id, Id) {
    let (x, y, r) = (c.centre.x, c.centre.y, c.radius_mm);
    let axis_b = data.placement([x, y, 0.0], Z);
    let axis_t = data.placement([x, y, b], Z);
    let circle_b = data.add(format!("CIRCLE('',#{axis_b},{})", real(r)));
    let circle_t = data.add(format!("CIRCLE('',#{axis_t},{})", real(r)));
    let ends = [[x + r, y, 0.0], [x - r, y, 0.0]];
    let vb = ends.map(|p| data.vertex(p));
    let vt = ends.map(|[px, py, _]| data.vertex([px, py, b]));
    // Half 0 runs counter-clockwise from angle 0 to π, half 1 from π to 2π.
    let cb = [
        data.edge(vb[0], vb[1], circle_b),
        data.edge(vb[1], vb[0], circle_b),
    ];
    let ct = [
        data.edge(vt[0], vt[1], circle_t),
        data.edge(vt[1], vt[0], circle_t),
    ];
    let v = [0, 1].map(|i| data.vertical(vb[i], vt[i], ends[i], b));
    let cylinder = data.add(format!("CYLINDRICAL_SURFACE('',#{axis_b},{})", real(r)));
    for (h, other) in [(0, 1), (1, 0)] {
        let l = data.edge_loop(&[
            (v[h], true),
            (ct[h], true),
            (v[other], false),
            (cb[h], false),
        ]);
        faces.push(data.face(cylinder, false, l, &[]));
    }
    let bottom = data.edge_loop(&[(cb[0], true), (cb[1], true)]);
    let top = data.edge_loop(&[(ct[1], false), (ct[0], false)]);
    (bottom, top)
}

/// The STEP text of the discs of `spec`: one `MANIFOLD_SOLID_BREP` per body, each solid
/// moved by its placement (one disc in its frame, or each disc of several where the reducer
/// puts it), all in one shape representation.
pub fn step(spec: &Spec, bodies: &[(DiscSolid, Placement)]) -> String {
    let mut data = Data {
        entities: Vec::new(),
        at: Placement::IDENTITY,
    };
    let name = string(&spec.name);
    let context = product_context(&mut data, &name);
    let mut items = Vec::new();
    for (k, (solid, at)) in bodies.iter().enumerate() {
        data.at = *at;
        let body = match bodies.len() {
            1 => name.clone(),
            _ => format!("{name} disc {}", k + 1),
        };
        items.push(format!("#{}", brep(&mut data, solid, &body)));
    }
    data.at = Placement::IDENTITY;
    let origin = data.placement([0.0; 3], Z);
    let units = units(&mut data);
    let shape = data.add(format!(
        "ADVANCED_BREP_SHAPE_REPRESENTATION('{name}',(#{origin},{}),#{units})",
        items.join(",")
    ));
    data.add(format!(
        "SHAPE_DEFINITION_REPRESENTATION(#{context},#{shape})"
    ));
    file(&data, &name)
}

/// One disc's closed shell and solid, placed by `data.at`.
fn brep(data: &mut Data, solid: &DiscSolid, name: &str) -> Id {
    let mut faces = Vec::new();
    let (bottom_e, top_e) = profile_faces(data, solid, &mut faces);
    let (mut bottom_inner, mut top_inner) = (Vec::new(), Vec::new());
    for c in solid.circles() {
        let (lb, lt) = circle_faces(data, c, solid.face_width_mm, &mut faces);
        bottom_inner.push(lb);
        top_inner.push(lt);
    }
    // z = 0 faces −z: its outer loop runs clockwise seen from +z (the profile backwards).
    let reversed: Vec<(Id, bool)> = bottom_e.iter().rev().map(|&e| (e, false)).collect();
    let outer = data.edge_loop(&reversed);
    let plane_b = data.placement([0.0, 0.0, 0.0], [0.0, 0.0, -1.0]);
    let plane_b = data.add(format!("PLANE('',#{plane_b})"));
    faces.push(data.face(plane_b, true, outer, &bottom_inner));
    let forward: Vec<(Id, bool)> = top_e.iter().map(|&e| (e, true)).collect();
    let outer = data.edge_loop(&forward);
    let plane_t = data.placement([0.0, 0.0, solid.face_width_mm], Z);
    let plane_t = data.add(format!("PLANE('',#{plane_t})"));
    faces.push(data.face(plane_t, true, outer, &top_inner));
    let faces: Vec<String> = faces.iter().map(|f| format!("#{f}")).collect();
    let shell = data.add(format!("CLOSED_SHELL('',({}))", faces.join(",")));
    data.add(format!("MANIFOLD_SOLID_BREP('{name}',#{shell})"))
}

/// The product structure a CAD system files a part under; returns its shape definition.
fn product_context(data: &mut Data, name: &str) -> Id {
    let app = data.add("APPLICATION_CONTEXT('automotive design')".into());
    data.add(format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let pc = data.add(format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = data.add(format!("PRODUCT('{name}','{name}','',(#{pc}))"));
    data.add(format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
    ));
    let formation = data.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let pdc = data.add(format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let pd = data.add(format!(
        "PRODUCT_DEFINITION('design','',#{formation},#{pdc})"
    ));
    data.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"))
}

/// The representation context: mm, radians, steradians, and a length uncertainty of 1e-7 mm
/// (Open CASCADE's confusion tolerance; the solid's own points are written exactly).
fn units(data: &mut Data) -> Id {
    let mm = data.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))".into());
    let rad = data.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))".into());
    let sr = data.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())".into());
    let u = data.add(format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#{mm},'distance_accuracy_value',\
         'confusion accuracy')"
    ));
    data.add(format!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{u}))\
         GLOBAL_UNIT_ASSIGNED_CONTEXT((#{mm},#{rad},#{sr}))REPRESENTATION_CONTEXT('',''))"
    ))
}

/// The exchange file: header, then one entity instance a line.
fn file(data: &Data, name: &str) -> String {
    let mut out = String::from("ISO-10303-21;\nHEADER;\n");
    out +=
        &format!("FILE_DESCRIPTION(('cycloid disc {name}: exact modified profile, mm'),'2;1');\n");
    out += &format!("FILE_NAME('{name}','',(''),(''),'cycloid','cycloid','');\n");
    out += "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
    for (i, e) in data.entities.iter().enumerate() {
        out += &format!("#{}={e};\n", i + 1);
    }
    out += "ENDSEC;\nEND-ISO-10303-21;\n";
    out
}
