//! The closed form of the linear law along the face width against the Winkler reference of
//! 200 slices (issue 29), on `specs/reducer-loaded.yaml`'s rated scene (the paper's design at
//! 10 N·m over 108°, 1080 crank angles) tilted by 0.3 mrad about x and about y, straight and
//! with `specs/reducer-misaligned.yaml`'s crown. Prints the max face load factor, the max line
//! load, and the largest differences of lag, roller force and face load factor.
//!
//! Run: `cargo run --release --example face_width_reference`.

use cycloid::equilibrium::discs_sweep;
use cycloid::equilibrium::loaded::Model;
use cycloid::model::{Crowning, Misalignment, Plan};
use cycloid::progress::Silent;

fn main() {
    let spec = cycloid::spec::load("specs/reducer-loaded.yaml").expect("specs/reducer-loaded.yaml");
    for (label, crowning) in [
        ("straight", Crowning::None),
        (
            "crowned Rc 1000 mm, flat over 4 mm",
            Crowning::Circular {
                radius_mm: 1000.0,
                start_mm: 2.0,
            },
        ),
    ] {
        let mut scene = spec.scenes[0].clone();
        scene.face.crowning = crowning;
        scene.face.misalignment = Misalignment {
            about_x_rad: 0.3e-3,
            about_y_rad: 0.3e-3,
        };
        scene.face.slices = 200;
        let plan = Plan::for_scene(&scene);
        let closed = Model::new(&spec.design, &spec.modification, &scene, &plan);
        let mut sliced = closed.clone();
        sliced.rollers = sliced.rollers.map(|r| r.with_face_by_slices(&scene.face));
        let go = |m: &Model| {
            let t = std::time::Instant::now();
            let s = discs_sweep::sweep_reducer(m, 1, &scene.crank_rad, (true, &Silent)).unwrap();
            (
                s.discs.into_iter().next().unwrap(),
                t.elapsed().as_secs_f64(),
            )
        };
        let ((c, tc), (s, ts)) = (go(&closed), go(&sliced));
        let (rc, rs) = (c.rollers.unwrap(), s.rollers.unwrap());
        let (fc, fs) = (rc.face.unwrap(), rs.face.unwrap());
        let arcsec = 180.0 / std::f64::consts::PI * 3600.0;
        let max = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0, f64::max);
        let peak = max(&mut rc.force_n.iter().flatten().copied());
        let line = |f: &cycloid::model::results::FaceLoads| {
            max(&mut f.line_load_n_per_mm.iter().flatten().copied())
        };
        println!("{label}, tilted 0.3 mrad about x and y, 200 slices:");
        println!(
            "  max face load factor  closed form {:.4}  200 Winkler slices {:.4}",
            max(&mut fc.face_load_factor.iter().copied()),
            max(&mut fs.face_load_factor.iter().copied())
        );
        println!(
            "  max line load         closed form {:.3} N/mm  200 slices {:.3} N/mm",
            line(&fc),
            line(&fs)
        );
        println!(
            "  max roller force      {:.2} N; largest force difference {:.3e} N ({:.4} % of it)",
            peak,
            max(&mut rc
                .force_n
                .iter()
                .flatten()
                .zip(rs.force_n.iter().flatten())
                .map(|(a, b)| (a - b).abs())),
            100.0
                * max(&mut rc
                    .force_n
                    .iter()
                    .flatten()
                    .zip(rs.force_n.iter().flatten())
                    .map(|(a, b)| (a - b).abs()))
                / peak
        );
        println!(
            "  lag: max {:.3} arcsec; largest difference {:.2e} arcsec",
            max(&mut rc.lag_rad.iter().map(|l| l.abs() * arcsec)),
            max(&mut rc
                .lag_rad
                .iter()
                .zip(&rs.lag_rad)
                .map(|(a, b)| (a - b).abs() * arcsec))
        );
        println!(
            "  largest face-load-factor difference {:.3e} (relative {:.3e})",
            max(&mut fc
                .face_load_factor
                .iter()
                .zip(&fs.face_load_factor)
                .map(|(a, b)| (a - b).abs())),
            max(&mut fc
                .face_load_factor
                .iter()
                .zip(&fs.face_load_factor)
                .map(|(a, b)| (a - b).abs() / b.max(1e-300)))
        );
        println!("  sweep time: closed form {tc:.3} s, 200 slices {ts:.3} s");
    }
}
