//! Export benchmarks (divan): the disc's STEP solid and STL mesh at the default 0.5 µm, from
//! the spec to the text written. Run: `cargo bench --bench export`.

use cycloid::engine::commands;
use cycloid::report::{step, stl};
use cycloid::spec::{self, Spec};
use std::hint::black_box;

fn main() {
    divan::main();
}

fn paper() -> Spec {
    spec::load("specs/reducer.yaml").expect("specs/reducer.yaml")
}

/// `profile --step`: the B-spline pieces of every tooth and the STEP text.
#[divan::bench(sample_count = 20)]
fn step_solid_0_5um(b: divan::Bencher) {
    let spec = paper();
    b.bench(|| {
        let solids = commands::disc(&spec).unwrap().solids(0.5e-3).unwrap();
        black_box(step::step(&spec, &solids))
    });
}

/// `profile --stl`: the polyline, the circles' polygons, the faces' triangulation and the STL
/// text.
#[divan::bench(sample_count = 20)]
fn stl_mesh_0_5um(b: divan::Bencher) {
    let spec = paper();
    b.bench(|| {
        let mesh = commands::disc(&spec).unwrap().placed_mesh(0.5e-3).unwrap();
        black_box(stl::stl(&spec, &mesh))
    });
}
