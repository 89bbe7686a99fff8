//! The loaded sweep the benchmarks and `examples/profile_sweep.rs` measure (shared by path).

use cycloid::equilibrium::loaded::Model;
use cycloid::model::GeometryMode;
use cycloid::spec::{self};

/// The paper optimum's 10 N·m scene (`rated`; scene 0, `mesh`, is the unloaded one) with
/// rollers, pins and a rigid bearing in `geometry`, on the paper's design with `rollers`
/// rollers (10, the paper's; one tooth fewer), and `n` crank angles over one mesh period of
/// that design, 2π/rollers of crank. With an odd count two discs do not mesh in one phase,
/// and their split of the torque moves with the crank.
pub(crate) fn rated_sweep(geometry: GeometryMode, n: usize, rollers: usize) -> (Model, Vec<f64>) {
    rated_sweep_of(geometry, n, rollers, |_| ())
}

/// `rated_sweep` of the paper's design changed by `change` first (pins that bend, discs).
pub(crate) fn rated_sweep_of(
    geometry: GeometryMode,
    n: usize,
    rollers: usize,
    change: impl Fn(&mut cycloid::model::Design),
) -> (Model, Vec<f64>) {
    let mut s = spec::load("specs/paper.yaml").expect("specs/paper.yaml");
    (s.design.rollers, s.design.teeth) = (rollers, rollers - 1);
    change(&mut s.design);
    let mut scene = s
        .scenes
        .iter()
        .find(|c| c.name == "rated")
        .expect("rated")
        .clone();
    scene.geometry = geometry;
    let model = Model::new(
        &s.design,
        &s.modification,
        &scene,
        &cycloid::model::Plan::of("rated", &[cycloid::model::Effect::Bearing]),
    );
    let crank = (0..n)
        .map(|k| std::f64::consts::TAU / rollers as f64 * k as f64 / n as f64)
        .collect();
    (model, crank)
}
