//! One loaded sweep of the paper optimum, for instruction counts under callgrind:
//! `cargo build --release --example profile_sweep && valgrind --tool=callgrind
//! target/release/examples/profile_sweep exact 3600` (geometry `exact` or `first_order`,
//! then the number of crank angles over one mesh period). Compare against a run with 36 angles
//! to remove the set-up cost. A third argument N runs N discs (default 1; 0 is one), a fourth
//! the roller count (default 10, the paper's; 11 puts two discs out of phase,
//! `common::rated_sweep`).

use cycloid::equilibrium::discs_sweep;
use cycloid::model::GeometryMode;

#[path = "../benches/common/mod.rs"]
mod common;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let geometry = match args.get(1).map(String::as_str) {
        Some("first_order") => GeometryMode::FirstOrder,
        _ => GeometryMode::Exact,
    };
    let n: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(3600);
    // A third argument: that many discs on the crank (`equilibrium::discs`).
    let discs: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1);
    let rollers: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(10);
    let (model, crank) = common::rated_sweep(geometry, n, rollers);
    let silent = &cycloid::progress::Silent;
    let transmission = discs_sweep::sweep_reducer(&model, discs.max(1), &crank, (true, silent))
        .expect("sweep")
        .transmission;
    let te = &transmission.expect("te").te_rad;
    println!("{} angles, TE[0] = {:e} rad", te.len(), te[0]);
}
