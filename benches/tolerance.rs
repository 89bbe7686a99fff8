//! Tolerance Monte Carlo benchmarks (divan). Run: `RAYON_NUM_THREADS=1 cargo bench --bench
//! tolerance`. Numbers go in BENCHMARKS.md. Targets (issue 15): 1,000 samples of the paper's
//! 108° rated scene in under 10 s on one core; a merge of 100 shards of 10⁴ samples in under 1 s.

use cycloid::engine::tolerance::{shard, summary, Records, ToleranceStudy};
use cycloid::progress::Silent;
use cycloid::spec::{self, Spec};
use std::hint::black_box;

fn main() {
    divan::main();
}

/// specs/reducer.yaml (the paper's optimum) with its scene over 108° of crank in 540 angles
/// (three mesh periods, two pin periods) with rollers, pins and the crank bearing, limits on
/// the roller and bearing forces, and every kind of part toleranced (bands of a few µm).
fn study_spec(samples: usize) -> Spec {
    let text = std::fs::read_to_string("specs/reducer.yaml").expect("specs/reducer.yaml");
    let text = text
        .replace(
            "crank: { from_deg: 0.0, to_deg: 36.0, steps: 360 }",
            "crank: { from_deg: 0.0, to_deg: 108.0, steps: 540 }",
        )
        .replace("effects: [clearance]", "effects: [bearing]")
        .replace(
            "min_clearance_mm: 0.015",
            "max_roller_force_n: 5000.0\n  max_bearing_force_n: 5000.0",
        );
    let text = format!(
        "{text}tolerances:\n  scene: rated\n  samples: {samples}\n  max_failure_rate: 0.0027\n  \
         eccentricity_mm: 0.002\n  roller_radial_mm: 0.003\n  roller_tangential_mm: 0.003\n  \
         roller_radius_mm: 0.002\n  pin_radial_mm: 0.004\n  pin_tangential_mm: 0.004\n  \
         hole_radial_mm: 0.005\n  hole_tangential_mm: 0.005\n  shift_mm: 0.002\n  \
         equidistant_mm: 0.002\n"
    );
    spec::parse("specs/reducer.yaml", &text).expect("the benchmark spec is valid")
}

/// 1,000 samples, each the 540-angle loaded sweep of the deviated reducer and its limits.
#[divan::bench(sample_count = 2, sample_size = 1)]
fn study_1000_samples_108deg(b: divan::Bencher) {
    let spec = study_spec(1000);
    let study = ToleranceStudy::new(&spec, None).unwrap();
    b.bench(|| study.run(black_box((0, 1)), &Silent).unwrap());
}

/// Reading, checking and joining 100 shard files of 10⁴ samples each (two limits), then the
/// summary of the 10⁶ samples (sorts for the quantiles, Clopper–Pearson, the worst samples)
/// and the terminal report: `cycloid tolerance merge` without the spec's parse.
#[divan::bench(sample_count = 5, sample_size = 1)]
fn merge_100_shards_of_10k(b: divan::Bencher) {
    let (shards, count) = (100u64, 1_000_000u64);
    let spec = study_spec(count as usize);
    let study = ToleranceStudy::new(&spec, None).unwrap();
    let dir = std::env::temp_dir().join(format!("cycloid-bench-merge-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut state = 0x9e3779b97f4a7c15u64;
    let mut noise = move || {
        // xorshift64: realistic unsorted values for the quantile sorts.
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut names = Vec::new();
    for i in 0..shards {
        let rows = cycloid::engine::tolerance::shard_len(count, (i, shards)) as usize;
        let mut records = Records::default();
        for _ in 0..rows {
            let (f, g) = (4000.0 + 100.0 * noise(), 900.0 + 10.0 * noise());
            records.values.extend([f, g]);
            records.passed.extend([true, true]);
        }
        let header = shard::Header {
            text_sha256: shard::spec_hash(&spec.source),
            seed: 0,
            items: count,
            index: i,
            count: shards,
            text_path: spec.path.clone(),
            text: spec.source.clone(),
        };
        let path = dir.join(format!("s{i}"));
        std::fs::write(&path, shard::encode(&header, 2, &records)).unwrap();
        names.push(path.display().to_string());
    }
    b.bench(|| {
        let read: Vec<_> = names
            .iter()
            .map(|p| shard::decode(p, &std::fs::read(p).unwrap()).unwrap())
            .collect();
        let records = shard::merge(&names, &read).unwrap();
        let s = summary::summarise(&study, &records);
        cycloid::report::tolerance::render(&study, &s, &records, None)
    });
    let _ = std::fs::remove_dir_all(&dir);
}
