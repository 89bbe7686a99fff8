//! One loaded sweep of the paper optimum, for instruction counts under callgrind:
//! `cargo build --release --example profile_sweep && valgrind --tool=callgrind
//! target/release/examples/profile_sweep exact 3600` (geometry `exact` or `first_order`,
//! then the number of crank angles over one mesh period). Compare against a run with 36 angles
//! to remove the set-up cost.

use cycloid::equilibrium::curves;
use cycloid::equilibrium::sweep::Model;
use cycloid::spec::{self, GeometryMode};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let geometry = match args.get(1).map(String::as_str) {
        Some("first_order") => GeometryMode::FirstOrder,
        _ => GeometryMode::Exact,
    };
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3600);
    let s = spec::load("specs/paper.yaml").expect("specs/paper.yaml");
    // The 10 N·m scene (scene 0, `mesh`, is the unloaded one).
    let mut scene = s
        .scenes
        .iter()
        .find(|c| c.name == "rated")
        .expect("rated")
        .clone();
    scene.geometry = geometry;
    let model = Model::new(&s.design, &s.modification, &scene, true, true, true);
    let crank: Vec<f64> = (0..n)
        .map(|k| std::f64::consts::TAU / 10.0 * k as f64 / n as f64)
        .collect();
    let sweep = curves::sweep(&model, &crank, true).expect("sweep");
    let te = &sweep.transmission.expect("te").te_rad;
    println!("{} angles, TE[0] = {:e} rad", te.len(), te[0]);
}
