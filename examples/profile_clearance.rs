//! One clearance sweep of the paper optimum, for instruction counts under callgrind:
//! `cargo build --release --example profile_clearance && valgrind --tool=callgrind
//! target/release/examples/profile_clearance backlash 360` (`gaps`, `backlash` or `min`, then
//! the number of crank angles over one mesh period). Compare against a run with 36 angles to
//! remove the set-up cost. A third argument repeats the sweep and prints the fastest time, a
//! fourth gives the disc a form error of that many harmonics.

use cycloid::geometry::clearance::{self, Mesh, Scope};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let what = args.get(1).map_or("backlash", String::as_str);
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(360);
    let repeats: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let spec = cycloid::spec::load("specs/paper.yaml").expect("specs/paper.yaml");
    let mut design = spec.design.clone();
    // A fourth argument: a form error of that many harmonics (orders from 2 without the
    // multiples of nc, 0.3 µm each), the disc as built of `benches/measure.rs`.
    let harmonics: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(0);
    design.deviations.form = (2..=harmonics)
        .filter(|k| k % design.teeth != 0)
        .map(|k| cycloid::model::FormTerm {
            order: k,
            cos_mm: 3e-4 * (k as f64).cos(),
            sin_mm: 3e-4 * (k as f64).sin(),
        })
        .collect();
    let mesh = Mesh::new(&design, &spec.modification);
    let crank: Vec<f64> = (0..n)
        .map(|k| std::f64::consts::TAU / 10.0 * k as f64 / n as f64)
        .collect();
    let mut fastest = f64::INFINITY;
    let mut min = 0.0;
    for _ in 0..repeats {
        let start = std::time::Instant::now();
        min = match what {
            "min" => clearance::min_gap(&mesh, &crank).expect("min gap").gap_mm,
            "gaps" => {
                clearance::sweep(&mesh, &crank, Scope::Gaps, &cycloid::progress::Silent)
                    .expect("sweep")
                    .min
                    .gap_mm
            }
            _ => {
                clearance::sweep(&mesh, &crank, Scope::Backlash, &cycloid::progress::Silent)
                    .expect("sweep")
                    .min
                    .gap_mm
            }
        };
        fastest = fastest.min(start.elapsed().as_secs_f64());
    }
    println!(
        "{what}, {n} angles: min gap {min} mm, fastest {:.3} ms",
        fastest * 1e3
    );
}
