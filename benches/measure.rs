//! Identification benchmark (divan): `cargo bench --bench measure`. Numbers go in BENCHMARKS.md.
//! Issue 16's target: 10⁴ points with 60 harmonics in under 100 ms.

use cycloid::geometry::profile::Profile;
use cycloid::geometry::Vec2;
use cycloid::measure::fit::{self, Request};
use cycloid::measure::{Feature, MeasuredPoint};
use cycloid::model::measured::Fitted;
use cycloid::model::Modification;
use cycloid::spec;
use std::f64::consts::TAU;
use std::hint::black_box;

fn main() {
    divan::main();
}

/// 10⁴ points around the paper optimum's profile (ΔRp 0.125, ΔRrp 0.1593) with a 2 µm
/// form error of order 7, turned by 0.7 rad and moved by (25, −10) mm, with a deterministic
/// ±1 µm wobble normal to the profile.
fn points(n: usize) -> Vec<MeasuredPoint> {
    let s = spec::load("specs/reducer.yaml").expect("specs/reducer.yaml");
    let profile = Profile::new(&s.design, &s.modification);
    let (sin, cos) = 0.7f64.sin_cos();
    (0..n)
        .map(|i| {
            let t = TAU * (i as f64 + 0.5) / n as f64;
            let wobble = 1e-3 * (1e4 * t).sin();
            let w = 2e-3 * (7.0 * t).cos() + wobble;
            let p = profile.point(t) - profile.normal(t) * w;
            MeasuredPoint {
                point: Vec2::new(cos * p.x - sin * p.y + 25.0, sin * p.x + cos * p.y - 10.0),
                feature: Feature::Profile,
                line: i + 2,
            }
        })
        .collect()
}

/// Identify centre, orientation, ΔRp, ΔRrp and a 60-harmonic form error (53 orders, 106
/// coefficients: 111 unknowns) from 10⁴ points.
#[divan::bench(sample_count = 20)]
fn fit_10k_points_60_harmonics(b: divan::Bencher) {
    let s = spec::load("specs/reducer.yaml").expect("specs/reducer.yaml");
    let pts = points(10_000);
    let request = Request {
        design: &s.design,
        nominal: Modification::default(),
        fit: Fitted {
            shift: true,
            equidistant: true,
            rotation: false,
        },
        harmonics: 60,
    };
    b.bench(|| fit::identify(black_box(&request), &pts).unwrap());
}

/// The generated profile's clearance sweep (gaps and backlash of every roller), 3,600 crank
/// angles over one mesh period: the baseline of `clearance_sweep_as_built_3600`.
#[divan::bench(sample_count = 20)]
fn clearance_sweep_generated_3600(b: divan::Bencher) {
    clearance_sweep(b, Vec::new());
}

/// The same sweep on the disc as built: the paper optimum with a form error of 53 harmonics
/// (orders 2 to 60 without the multiples of 9, 0.3 µm each, phases spread), the size of what
/// `fit` identifies with `harmonics: 60`. Issue 16's target: at most 3× the generated one.
#[divan::bench(sample_count = 20)]
fn clearance_sweep_as_built_3600(b: divan::Bencher) {
    let form = (2..=60usize)
        .filter(|k| k % 9 != 0)
        .map(|k| cycloid::model::FormTerm {
            order: k,
            cos_mm: 3e-4 * (k as f64).cos(),
            sin_mm: 3e-4 * (k as f64).sin(),
        })
        .collect();
    clearance_sweep(b, form);
}

/// The clearance sweep with backlash of the paper optimum with the form error `form`, 3,600
/// crank angles over one mesh period.
fn clearance_sweep(b: divan::Bencher, form: Vec<cycloid::model::FormTerm>) {
    use cycloid::geometry::clearance::{sweep, Mesh, Scope};
    let s = spec::load("specs/reducer.yaml").expect("specs/reducer.yaml");
    let mut design = s.design.clone();
    design.deviations.form = form;
    let mesh = Mesh::new(&design, &s.modification);
    let crank: Vec<f64> = (0..3600).map(|k| TAU / 10.0 * k as f64 / 3600.0).collect();
    b.bench(|| {
        sweep(
            black_box(&mesh),
            &crank,
            Scope::Backlash,
            &cycloid::progress::Silent,
        )
        .unwrap()
    });
}
