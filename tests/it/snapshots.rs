//! Snapshot regression (insta): the `check` table of the shipped spec, the paper's summary
//! numbers, and the error messages for bad specs. Numbers are rounded to 4 significant digits,
//! far coarser than the golden tolerances, so solver noise cannot flip them. Update on purpose
//! with `INSTA_UPDATE=always cargo test --release --test it snapshots::` and review the diff.

use crate::common;

fn cycloid(args: &[&str]) -> (i32, String, String) {
    common::cycloid_here(args).parts()
}

/// x to 4 significant digits, as text.
fn sig4(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (3 - x.abs().log10().floor() as i32).max(0) as usize;
    let scale = 10f64.powi(x.abs().log10().floor() as i32 - 3);
    let rounded = (x / scale).round() * scale;
    format!("{rounded:.digits$}")
}

#[test]
fn check_table_of_the_shipped_spec() {
    let (code, out, err) = cycloid(&["check", "specs/reducer.yaml"]);
    assert_eq!(code, 0, "{err}");
    insta::assert_snapshot!("check_table_reducer", out);
}

#[test]
fn check_table_of_a_failing_spec_puts_the_failure_first() {
    // Only the limit rows: the golden rows carry deviations at the level of the files' rounding.
    let (code, out, _) = cycloid(&["check", "specs/paper-negative-start.yaml"]);
    assert_eq!(code, 1);
    let kept: Vec<&str> = out.lines().filter(|l| !l.contains("golden:")).collect();
    insta::assert_snapshot!("check_table_negative_start", kept.join("\n"));
}

#[test]
fn paper_summary_numbers() {
    let dir = common::Scratch::new("snap-summary");
    let mut summary = String::new();
    for name in ["paper", "paper-positive-start", "paper-negative-start"] {
        let json = dir.join(&format!("{name}.json"));
        let (code, _, err) = cycloid(&[
            "check",
            &format!("specs/{name}.yaml"),
            "--json",
            json.to_str().unwrap(),
        ]);
        assert!(code == 0 || code == 1, "{err}");
        let doc: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
        // The keys of every scene together (clearance in one, loads in another).
        let mut merged = serde_json::Map::new();
        // The optimiser's `study` scene (coarser sampling) is not part of the summary.
        for scene in doc["scenes"].as_array().unwrap() {
            if scene["name"] != "study" {
                merged.extend(scene.as_object().unwrap().clone());
            }
        }
        let s = serde_json::Value::Object(merged);
        let f = |k: &str| s[k].as_f64().unwrap_or_else(|| panic!("{k}"));
        let at = &s["min_clearance_at"];
        // Where the minimum is, unless several places tie with it (then round-off picks one).
        let min = f("min_clearance_mm");
        let ties = s["clearance_mm"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|row| row.as_array().unwrap())
            .filter(|g| (g.as_f64().unwrap() - min).abs() < 1e-9)
            .count();
        let place = if ties == 1 {
            format!(
                "roller {}, crank {}°, tooth phase {}",
                at["roller"],
                sig4(at["crank_deg"].as_f64().unwrap()),
                sig4(at["tooth_phase"].as_f64().unwrap())
            )
        } else {
            format!("{ties} places tie")
        };
        summary += &format!(
            "{name}: passed {}\n  min clearance {} µm ({place})\n  \
             max roller force {} N, max contact pressure {} MPa, fewest rollers in contact {}\n  \
             max pin force {} N, max bearing force {} N\n  \
             TE {} … {} arcsec (fluctuation {}), ratio {} … {} (fluctuation {})\n  \
             equilibrium residual below 1e-9: {}\n",
            doc["passed"],
            sig4(min * 1000.0),
            sig4(f("max_roller_force_n")),
            sig4(f("max_contact_pressure_mpa")),
            f("min_rollers_in_contact"),
            sig4(f("max_pin_force_n")),
            sig4(f("max_bearing_force_n")),
            sig4(f("te_min_arcsec")),
            sig4(f("te_max_arcsec")),
            sig4(f("te_fluctuation_arcsec")),
            sig4(f("ratio_min")),
            sig4(f("ratio_max")),
            sig4(f("ratio_fluctuation")),
            f("max_residual") < 1e-9,
        );
    }
    insta::assert_snapshot!("paper_summary", summary);
}

#[test]
fn error_messages_for_bad_specs() {
    let mut names: Vec<String> = std::fs::read_dir("tests/bad-specs")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".yaml"))
        .collect();
    names.sort();
    assert!(names.len() >= 10);
    let mut all = String::new();
    for name in names {
        let (code, out, err) = cycloid(&["check", &format!("tests/bad-specs/{name}")]);
        assert_eq!(code, 2, "{name}: {out}{err}");
        assert!(out.is_empty(), "{name} printed a table: {out}");
        all += &format!("{name}\n  {}\n", err.trim_end());
    }
    insta::assert_snapshot!("bad_spec_errors", all);
}

#[test]
fn colour_only_when_asked() {
    let text = std::fs::read_to_string("specs/paper-negative-start.yaml").unwrap();
    let spec = cycloid::spec::parse("x.yaml", &text).unwrap();
    let scene = &spec.scenes[0];
    let r = cycloid::engine::scene::run(
        &spec,
        scene,
        &cycloid::model::Plan::for_scene(scene),
        &Default::default(),
    )
    .unwrap();
    let summaries = cycloid::engine::summary::summarise(&[r]);
    let checks = cycloid::engine::verdict::evaluate(&spec, &summaries).unwrap();
    let plain = cycloid::report::table::render_styled(&checks, false);
    let coloured = cycloid::report::table::render_styled(&checks, true);
    assert!(!plain.contains('\x1b'));
    assert!(coloured.contains("\x1b[1;31mFAIL\x1b[0m"));
    // Colour never changes the layout.
    let stripped = coloured
        .replace("\x1b[1;31m", "")
        .replace("\x1b[32m", "")
        .replace("\x1b[0m", "");
    assert_eq!(stripped, plain);
    assert!(!cycloid::report::table::use_color(false));
    // The binary's stdout here is a pipe: no colour even without NO_COLOR.
    let out = common::cycloid_with(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")),
        &["check", "specs/paper-negative-start.yaml"],
        &[("NO_COLOR", "")],
    );
    assert!(!out.stdout.contains('\x1b'));
}

#[test]
fn failures_come_first_the_furthest_outside_first() {
    use cycloid::engine::verdict::{Bound, Check, CheckKind};
    use cycloid::model::place::{Crank, Place, Site};
    let check = |id: &str, value: f64, limit: f64, bound: Bound| Check {
        id: id.into(),
        kind: CheckKind::Limit,
        value,
        limit,
        unit: "",
        bound,
        passed: match bound {
            Bound::Max => value <= limit,
            Bound::Min => value >= limit,
        },
        at: cycloid::engine::verdict::Evidence::Place(Place::of(Site::Crank(Crank {
            index: 0,
            rad: 0.0,
        }))),
    };
    let checks = vec![
        check("s/passes", 1.0, 2.0, Bound::Max),
        check("s/ten_percent_over", 1100.0, 1000.0, Bound::Max),
        check("s/three_times_under", -0.03, 0.015, Bound::Min),
        check("s/also_passes", 5.0, 1.0, Bound::Min),
        check("s/one_percent_over", 1.01, 1.0, Bound::Max),
    ];
    let order: Vec<&str> = cycloid::report::table::ordered(&checks)
        .iter()
        .map(|c| c.id.as_str())
        .collect();
    assert_eq!(
        order,
        [
            "s/three_times_under",
            "s/ten_percent_over",
            "s/one_percent_over",
            "s/passes",
            "s/also_passes"
        ]
    );
}
