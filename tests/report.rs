//! The design-review report: index.html, the SVGs it links, well-formed SVG with axis labels
//! that carry units, and the optimisation map drawn from synthetic data.

use cycloid::report::html::{render, OptimisationView, ReportInput};
use quick_xml::events::Event;
use quick_xml::Reader;
use std::process::Command;

fn well_formed(name: &str, xml: &str) {
    let mut reader = Reader::from_str(xml);
    reader.config_mut().check_end_names = true;
    loop {
        match reader.read_event() {
            Ok(Event::Eof) => break,
            Ok(_) => {}
            Err(e) => panic!(
                "{name} is not well-formed at {}: {e}",
                reader.buffer_position()
            ),
        }
    }
}

fn linked_files(html: &str) -> Vec<String> {
    html.split("src=\"")
        .skip(1)
        .map(|s| s[..s.find('"').unwrap()].to_string())
        .collect()
}

#[test]
fn check_writes_a_page_with_every_plot_it_links() {
    let dir = std::env::temp_dir().join(format!("cycloid-report-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_cycloid"))
        .args(["check", "specs/paper-negative-start.yaml", "--report"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("index.html"), "{stdout}");
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    assert!(html.contains("FAILED: 1 of 8 checks fail"));
    assert!(html.contains("paper-table-1-negative-start"));
    // Traceable: the spec's SHA-256 and the tool version.
    let sha = cycloid::golden::sha256_hex(
        &std::fs::read_to_string("specs/paper-negative-start.yaml").unwrap(),
    );
    assert!(html.contains(&sha));
    assert!(html.contains(env!("CARGO_PKG_VERSION")));
    // Every check with its verdict; the failure first.
    let fail = html.find("mesh/min_clearance_mm").unwrap();
    let golden = html.find("rated/golden:te_arcsec").unwrap();
    assert!(fail < golden);
    let files = linked_files(&html);
    for expected in [
        "disc.svg",
        "disc-detail.svg",
        "mesh-clearance.svg",
        "rated-roller-forces.svg",
        "rated-te.svg",
        "rated-ratio.svg",
        "rated-bearing-force.svg",
        "rated-bearing-angle.svg",
        "rated-pin-forces.svg",
    ] {
        assert!(files.iter().any(|f| f == expected), "{expected} not linked");
    }
    for f in &files {
        let svg = std::fs::read_to_string(dir.join(f)).unwrap_or_else(|_| panic!("{f} missing"));
        assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
        well_formed(f, &svg);
        assert!(!svg.contains("NaN") && !svg.contains("inf"), "{f}");
    }
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
    // Axis labels with units.
    for (file, labels) in [
        (
            "mesh-clearance.svg",
            &["crank angle φ (deg)", "clearance (µm)", "limit 15.00 µm"][..],
        ),
        (
            "rated-roller-forces.svg",
            &["roller force (N)", "roller 2"][..],
        ),
        ("rated-te.svg", &["TE δ = β + βo (arcsec)"][..]),
        (
            "rated-ratio.svg",
            &["ratio κ = dφ/dφout", "nominal nc = 9"][..],
        ),
        ("rated-bearing-force.svg", &["bearing force |Fb| (N)"][..]),
        (
            "rated-bearing-angle.svg",
            &["bearing force angle ε (deg)"][..],
        ),
        ("rated-pin-forces.svg", &["pin force (N)"][..]),
        ("disc.svg", &["10 mm", "Disc at crank φ = 10.90°"][..]),
    ] {
        let svg = read(file);
        for l in labels {
            assert!(svg.contains(l), "{file} lacks `{l}`");
        }
    }
    let detail = read("disc-detail.svg");
    assert!(detail.contains("interference -23.41 µm"), "{detail}");
    // The drawing is at the angle of the smallest gap; a chosen angle overrides it.
    let out = Command::new(env!("CARGO_BIN_EXE_cycloid"))
        .args([
            "check",
            "specs/paper.yaml",
            "--report-crank-deg",
            "12.5",
            "--report",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert!(read("disc.svg").contains("Disc at crank φ = 12.50°"));
    assert!(
        read("disc.svg").contains("Fb "),
        "the loaded scene draws the bearing force"
    );
}

#[test]
fn the_optimisation_map_and_path_are_drawn_when_given() {
    let text = std::fs::read_to_string("specs/reducer.yaml").unwrap();
    let spec = cycloid::spec::parse("specs/reducer.yaml", &text).unwrap();
    let mut scene = spec.scenes[0].clone();
    scene.crank_rad.truncate(20);
    let r = cycloid::scene::run(&spec, &scene, &cycloid::scene::Plan::for_scene(&scene)).unwrap();
    // A synthetic bowl with its minimum at (0.125, 0.16), infeasible where ΔRrp − ΔRp < 0.015.
    let mut map = Vec::new();
    for i in 0..21 {
        for j in 0..21 {
            let (x, y) = (0.05 + 0.01 * i as f64, 0.05 + 0.01 * j as f64);
            let z = if y - x < 0.015 {
                f64::NAN
            } else {
                0.04 + (x - 0.125).powi(2) + 2.0 * (y - 0.16).powi(2)
            };
            map.push((x, y, z));
        }
    }
    let view = OptimisationView {
        x_label: "shift ΔRp (mm)".into(),
        y_label: "equidistant ΔRrp (mm)".into(),
        objective_label: "ratio fluctuation κmax − κmin".into(),
        map,
        path: vec![
            (0.135, 0.15),
            (0.13, 0.155),
            (0.126, 0.159),
            (0.125, 0.1593),
        ],
        start: Some((0.135, 0.15)),
        optimum: Some((0.125, 0.1593)),
        references: vec![(0.125, 0.1593, "paper".into())],
    };
    let files = render(&ReportInput {
        spec: &spec,
        checks: &[],
        results: std::slice::from_ref(&r),
        goldens: &[],
        crank_deg: Some(0.0),
        optimisation: Some(&view),
        accuracy: None,
    });
    // CYCLOID_KEEP_REPORT=DIR keeps the synthetic report to look at.
    if let Some(dir) = std::env::var_os("CYCLOID_KEEP_REPORT") {
        std::fs::create_dir_all(&dir).unwrap();
        for (name, text) in &files {
            std::fs::write(std::path::Path::new(&dir).join(name), text).unwrap();
        }
    }
    let (_, html) = &files[0];
    assert!(html.contains("src=\"optimisation.svg\""));
    let (_, svg) = files.iter().find(|(n, _)| n == "optimisation.svg").unwrap();
    well_formed("optimisation.svg", svg);
    for l in [
        "shift ΔRp (mm)",
        "equidistant ΔRrp (mm)",
        "ratio fluctuation",
        ">start<",
        ">optimum<",
        ">paper<",
    ] {
        assert!(svg.contains(l), "optimisation.svg lacks `{l}`");
    }
    // 441 cells, infeasible ones white; the path as a polyline.
    assert_eq!(svg.matches("<rect").count() - 1 - 1 - 48 - 1 - 1, 441);
    assert!(svg.contains("fill=\"#ffffff\""));
    assert!(svg.contains("<polyline points="));
    // Without a view there is no optimisation section.
    let files = render(&ReportInput {
        spec: &spec,
        checks: &[],
        results: std::slice::from_ref(&r),
        goldens: &[],
        crank_deg: None,
        optimisation: None,
        accuracy: None,
    });
    assert!(!files.iter().any(|(n, _)| n == "optimisation.svg"));
}

#[test]
fn ticks_are_round_numbers_covering_the_range() {
    use cycloid::report::svg::ticks;
    let t = ticks(763.99, 770.08, 6, true);
    assert_eq!(t.values, vec![762.0, 764.0, 766.0, 768.0, 770.0, 772.0]);
    assert_eq!(t.label(764.0), "764");
    let t = ticks(8.9898, 9.032, 6, true);
    assert_eq!(t.step, 0.01);
    assert_eq!(t.label(9.0), "9.00");
    let t = ticks(-23.4, 15.0, 6, true);
    assert_eq!(t.label(-20.0), "−20");
    let t = ticks(0.0, 0.25, 5, false);
    assert_eq!(t.label(0.05), "0.05");
    // A flat curve still gets an axis.
    assert!(ticks(5.0, 5.0, 6, true).values.len() >= 2);
}
