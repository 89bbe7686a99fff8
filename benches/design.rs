//! Design-search benchmarks (divan). Run: `RAYON_NUM_THREADS=1 cargo bench --bench design`.
//! Numbers go in BENCHMARKS.md: designs screened per second and fully checked per second on one
//! core, on `specs/requirements-robot-joint.yaml` (np 30, loaded period 29 mesh periods for M 6
//! or 8 at nc 29, 24 crank angles per mesh period).

use cycloid::engine::design_search::{evaluate, Candidate, Choice};
use cycloid::model::requirements::Requirements;
use std::hint::black_box;

fn main() {
    divan::main();
}

fn requirements() -> Requirements {
    cycloid::spec::requirements::load("specs/requirements-robot-joint.yaml")
        .expect("specs/requirements-robot-joint.yaml")
}

/// A design of the robot joint's front (nc 29, M 8, one disc): it passes the screen and the
/// full check.
fn feasible() -> Candidate {
    Candidate {
        choice: Choice {
            teeth: 29,
            pins: 8,
            discs: 1,
        },
        x: cycloid::model::requirements::Variables::from_array([
            1.163, 41.02, 2.333, 7.129, 25.53, 4.5, -0.0022, 0.0157,
        ]),
    }
}

/// The rules and the screen of a design that passes them (a quarter of the crank angles of the
/// full check, every scene).
#[divan::bench(sample_count = 20)]
fn screen(b: divan::Bencher) {
    let req = requirements();
    let c = feasible();
    assert!(evaluate::screen(&req, &c).unwrap().is_none());
    b.bench(|| evaluate::screen(black_box(&req), black_box(&c)).unwrap());
}

/// The full check of the same design.
#[divan::bench(sample_count = 20)]
fn full_check(b: divan::Bencher) {
    let req = requirements();
    let c = feasible();
    assert!(evaluate::full(&req, &c).unwrap().feasible());
    b.bench(|| evaluate::full(black_box(&req), black_box(&c)).unwrap());
}

/// The rules alone, of a design the envelope rejects (no physics).
#[divan::bench]
fn rules(b: divan::Bencher) {
    let req = requirements();
    let mut c = feasible();
    c.x.roller_circle_radius_mm = 60.0;
    assert!(!evaluate::evaluate(&req, &c).unwrap().feasible());
    b.bench(|| evaluate::evaluate(black_box(&req), black_box(&c)).unwrap());
}
