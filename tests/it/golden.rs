//! Golden curves: whole-curve comparison with interpolation, a perturbed golden failing with
//! exit 1 at the right place, `bless` reporting what moved, and the spec errors around goldens.

use cycloid::engine::golden::{compare, GoldenCurves};
use cycloid::model::quantity::{Curves, Quantity, QUANTITIES};
use cycloid::model::GoldenTolerance;
use std::path::Path;

use crate::common::{cycloid_here, cycloid_with, scene_item, PaperSpec, Scratch};

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> Scratch {
    Scratch::new(&format!("golden-{name}"))
}

fn run(args: &[&str]) -> (i32, String, String) {
    cycloid_here(args).parts()
}

/// The paper's design with one loaded scene sampled with `steps` angles over one mesh period
/// and the given golden entries.
fn spec_text(steps: usize, golden: &str) -> String {
    PaperSpec::new()
        .rated_period(steps)
        .with(&format!("golden:\n{golden}"))
        .text()
        .to_string()
}

const TE_GOLDEN: &str = "  - scene: rated
    quantity: te_arcsec
    file: golden/te.csv
    tolerance: { abs: 0.01, rel: 1.0e-6 }
  - scene: rated
    quantity: roller_force_n
    file: golden/forces.csv
    tolerance: { abs: 0.01, rel: 1.0e-6 }
";

fn write(path: &Path, text: &str) {
    std::fs::write(path, text).unwrap();
}

fn p(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn a_golden_sampled_at_0_2_deg_checks_results_at_0_1_deg_and_back() {
    let dir = scratch("sampling");
    let spec = dir.join("spec.yaml");
    // Golden at 0.2°, results at 0.1°: every golden angle is a computed angle.
    write(&spec, &spec_text(180, TE_GOLDEN));
    let (code, out, err) = run(&["bless", p(&spec)]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("new: 180 crank angles"), "{out}");
    write(&spec, &spec_text(360, TE_GOLDEN));
    let json = dir.join("r.json");
    let (code, out, err) = run(&["check", p(&spec), "--json", p(&json)]);
    assert_eq!(code, 0, "{out}{err}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let goldens = doc["golden"].as_array().unwrap();
    assert_eq!(goldens.len(), 2);
    assert_eq!(goldens[0]["points_compared"], 180);
    assert_eq!(goldens[1]["points_compared"], 180 * 10);
    // Exact samples: only the 10-digit rounding of the file is left.
    assert!(goldens[0]["worst"]["deviation"].as_f64().unwrap() < 1e-6);

    // Golden at 0.1°, results at 0.2°: the results set the angles, the golden is sampled.
    let (code, _, _) = run(&["bless", p(&spec)]);
    assert_eq!(code, 0);
    write(&spec, &spec_text(180, TE_GOLDEN));
    let (code, out, err) = run(&["check", p(&spec), "--json", p(&json)]);
    assert_eq!(code, 0, "{out}{err}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(doc["golden"][0]["points_compared"], 180);
}

#[test]
fn a_perturbed_golden_fails_with_exit_1_and_names_the_worst_point() {
    let dir = scratch("perturbed");
    let spec = dir.join("spec.yaml");
    write(&spec, &spec_text(360, TE_GOLDEN));
    assert_eq!(run(&["bless", p(&spec)]).0, 0);
    // Move the TE at crank 12.3° by 0.05 arcsec (5× the band) and at 20° by 0.02.
    let te = dir.join("golden/te.csv");
    let text = std::fs::read_to_string(&te).unwrap();
    let moved: Vec<String> = text
        .lines()
        .map(|line| {
            let (phi, v) = line.split_once(',').unwrap();
            let bump = match phi {
                "12.3" => 0.05,
                "20" => 0.02,
                _ => return line.to_string(),
            };
            format!("{phi},{}", v.parse::<f64>().unwrap() + bump)
        })
        .collect();
    write(&te, &(moved.join("\n") + "\n"));
    let json = dir.join("r.json");
    let junit = dir.join("r.xml");
    let (code, out, err) = run(&["check", p(&spec), "--json", p(&json), "--junit", p(&junit)]);
    assert_eq!(code, 1, "{out}{err}");
    let row = out
        .lines()
        .find(|l| l.contains("golden:te_arcsec"))
        .unwrap();
    assert!(row.contains("FAIL"), "{out}");
    assert!(row.contains("crank 12.30°"), "{row}");
    // The failing golden is listed before the passing one.
    let fail_at = out.find("golden:te_arcsec").unwrap();
    let pass_at = out.find("golden:roller_force_n").unwrap();
    assert!(fail_at < pass_at, "{out}");
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let worst = &doc["golden"][0]["worst"];
    assert_eq!(doc["golden"][0]["passed"], false);
    assert!((worst["crank_deg"].as_f64().unwrap() - 12.3).abs() < 1e-9);
    assert!((worst["deviation"].as_f64().unwrap() - 0.05).abs() < 1e-6);
    assert_eq!(doc["passed"], false);
    let xml = std::fs::read_to_string(&junit).unwrap();
    assert!(xml.contains("failures=\"1\""), "{xml}");
    assert!(xml.contains("crank 12.30°"), "{xml}");

    // Blessing prints what moved, by how much and where, and the check passes again.
    let (code, out, _) = run(&["bless", p(&spec)]);
    assert_eq!(code, 0);
    let line = out.lines().find(|l| l.contains("te_arcsec")).unwrap();
    assert!(line.contains("max |change| 0.05000 arcsec"), "{line}");
    assert!(line.contains("crank 12.30°"), "{line}");
    assert!(line.contains("OUTSIDE"), "{line}");
    let forces = out.lines().find(|l| l.contains("roller_force_n")).unwrap();
    assert!(forces.contains("unchanged"), "{forces}");
    assert_eq!(run(&["check", p(&spec)]).0, 0);
}

#[test]
fn bless_keeps_a_review_while_the_curve_stays_in_its_band_and_resets_it_otherwise() {
    let dir = scratch("review");
    let spec = dir.join("spec.yaml");
    write(&spec, &spec_text(90, TE_GOLDEN));
    assert_eq!(run(&["bless", p(&spec)]).0, 0);
    let meta = dir.join("golden/te.csv.meta.yaml");
    let text = std::fs::read_to_string(&meta).unwrap();
    assert!(text.contains("NOT REVIEWED"), "{text}");
    assert!(text.contains("date: 1970-01-01"), "{text}");
    assert!(text.contains("spec_sha256:"), "{text}");
    let reviewed = text
        .lines()
        .map(|l| {
            if l.starts_with("reviewed:") {
                "reviewed: checked by hand".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    write(&meta, &reviewed);
    // A year later, nothing changed: the review and the date stay.
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let later = cycloid_with(
        here,
        &["bless", p(&spec)],
        &[("SOURCE_DATE_EPOCH", "31536000")],
    );
    assert_eq!(later.code(), 0, "{later:?}");
    let text = std::fs::read_to_string(&meta).unwrap();
    assert!(text.contains("reviewed: checked by hand"), "{text}");
    assert!(text.contains("date: 1970-01-01"), "{text}");
    // A different torque moves the TE far outside its band: the review no longer holds.
    write(
        &spec,
        &spec_text(90, TE_GOLDEN).replace("output_torque_nm: 10.0", "output_torque_nm: 20.0"),
    );
    assert_eq!(run(&["bless", p(&spec)]).0, 0);
    let text = std::fs::read_to_string(&meta).unwrap();
    assert!(text.contains("NOT REVIEWED since 1970-01-01"), "{text}");
    assert!(text.contains("checked by hand"), "{text}");
}

#[test]
fn a_missing_golden_file_is_exit_2_naming_it_and_suggesting_bless() {
    let dir = scratch("missing");
    let spec = dir.join("spec.yaml");
    write(&spec, &spec_text(36, TE_GOLDEN));
    let (code, out, err) = run(&["check", p(&spec)]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.contains("golden/te.csv"), "{err}");
    assert!(err.contains("does not exist"), "{err}");
    assert!(err.contains("cycloid bless"), "{err}");
    // Located at the golden's `file` key.
    let text = spec_text(36, TE_GOLDEN);
    let line = text
        .lines()
        .position(|l| l.contains("file: golden/te.csv"))
        .unwrap()
        + 1;
    assert!(err.contains(&format!("spec.yaml:{line}:5:")), "{err}");
}

/// A golden of a curve the scene's effects cover but its run cannot hold says which quantity
/// is missing and why, at the golden's `quantity` key, exit 2 (`bless` here; `check` reads
/// the curve through the same `engine::golden::computed`): a
/// disc's torque share on a one-disc reducer (computed with several discs only; it used to
/// say "a ratio needs at least 3 crank angles"), and a ratio over 2 crank angles.
#[test]
fn a_golden_of_a_curve_the_run_left_out_says_what_is_missing_and_why() {
    let dir = scratch("not-computed");
    let spec = dir.join("spec.yaml");
    let golden = |quantity: &str| {
        format!(
            "  - scene: rated\n    quantity: {quantity}\n    file: golden/g.csv\n    \
             tolerance: {{ abs: 0.01, rel: 1.0e-6 }}\n"
        )
    };
    // `bless` on `text` stops at the golden's quantity line with "scene `scene` computed no
    // `quantity` {why}".
    let refused = |text: &str, scene: &str, quantity: &str, why: &str| {
        write(&spec, text);
        let line = 1 + text
            .lines()
            .position(|l| l.contains(&format!("quantity: {quantity}")))
            .unwrap();
        let (code, out, err) = run(&["bless", p(&spec)]);
        assert_eq!(code, 2, "{out}{err}");
        assert_eq!(
            err,
            format!(
                "{}:{line}:5: invalid value: golden[0].quantity: scene `{scene}` computed no \
                 `{quantity}` {why}\n",
                p(&spec)
            )
        );
    };
    for (steps, quantity, why) in [
        (
            36,
            "torque_nm",
            "(disc torque share Tk): a disc's share of the torque is computed with several \
             discs only",
        ),
        (
            2,
            "ratio",
            "(transmission ratio κ = dφ/dφout): a ratio needs at least 3 crank angles, the \
             scene has 2",
        ),
    ] {
        refused(&spec_text(steps, &golden(quantity)), "rated", quantity, why);
    }
    // A torsion loop without friction has no hysteresis (specs/reducer-torsion.yaml).
    let torsion = std::fs::read_to_string("specs/reducer-torsion.yaml").unwrap();
    let text = torsion.replacen(
        "limits:\n",
        "golden:\n  - scene: torsion\n    quantity: hysteresis_loss_arcmin\n    file: g.csv\n    \
         tolerance: { abs: 0.01, rel: 1.0e-6 }\nlimits:\n",
        1,
    );
    refused(
        &text,
        "torsion",
        "hysteresis_loss_arcmin",
        "(hysteresis loss (friction, at zero torque)): its torsion loop has no friction to lose \
         (give `reducer.friction`)",
    );
}

#[test]
fn a_golden_whose_columns_or_range_no_longer_match_is_exit_2() {
    let dir = scratch("mismatch");
    let spec = dir.join("spec.yaml");
    write(&spec, &spec_text(36, TE_GOLDEN));
    assert_eq!(run(&["bless", p(&spec)]).0, 0);
    // Half the crank range: the golden covers more than the scene.
    write(
        &spec,
        &spec_text(18, TE_GOLDEN).replace("to_deg: 36.0", "to_deg: 18.0"),
    );
    let (code, _, err) = run(&["check", p(&spec)]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("but the scene 0° to 17°"), "{err}");
    assert!(err.contains("re-bless"), "{err}");
}

fn curve(xs: &[f64], f: impl Fn(f64) -> f64) -> Vec<f64> {
    xs.iter().map(|&x| f(x)).collect()
}

fn grid(step: f64, n: usize) -> Vec<f64> {
    (0..n).map(|k| k as f64 * step).collect()
}

#[test]
fn compare_interpolates_the_finer_curve_at_the_coarser_angles() {
    let f = |x: f64| 100.0 + 5.0 * (x.to_radians() * 10.0).sin();
    let columns = vec!["te_arcsec".to_string()];
    let coarse = grid(0.15, 240);
    let fine = grid(0.1, 360);
    let golden = GoldenCurves {
        crank_deg: coarse.clone(),
        curves: Curves {
            columns: columns.clone(),
            values: vec![curve(&coarse, f)],
        },
    };
    let now = Curves {
        columns: columns.clone(),
        values: vec![curve(&fine, f)],
    };
    let tol = GoldenTolerance {
        abs: 1e-3,
        rel: 0.0,
    };
    let c = compare(&golden, &fine, &now, tol, (None, None), None).unwrap();
    // Linear interpolation error ≤ h²·max|f''|/8 with f'' = 5·(10·π/180)² per deg².
    let bound = 0.1f64.powi(2) * 5.0 * (10f64.to_radians()).powi(2) / 8.0;
    assert!(c.worst.deviation <= bound * 1.01, "{c:?}");
    assert!(c.passed);
    assert_eq!(c.points, 240); // 0° … 35.85°, all inside the results (0° … 35.9°)

    // The other way round: the coarse results set the angles.
    let golden = GoldenCurves {
        crank_deg: fine.clone(),
        curves: now.clone(),
    };
    let coarse_now = Curves {
        columns,
        values: vec![curve(&coarse, |x| f(x) + if x == 6.0 { 0.01 } else { 0.0 })],
    };
    let c = compare(&golden, &coarse, &coarse_now, tol, (None, None), None).unwrap();
    assert!(!c.passed);
    assert!((c.worst.at.crank_deg - 6.0).abs() < 1e-9, "{c:?}");
    assert!((c.worst.deviation - 0.01).abs() < 1e-9);
    assert!((c.worst.ratio() - 10.0).abs() < 1e-6);
}

/// The worst point of a comparison names its column's part (column k is the quantity's part k,
/// `Shape::part`) and the angle as compared: a bump of 10 bands in one column at 1.875° (an
/// exact binary, a tie at two decimals) is found in that column at that angle, and read "… at
/// crank 1.88°" as `{:.2}` rounds 1.875 (to even); the angle taken through radians and back
/// reads 1.87°. A quantity of one curve names no part.
#[test]
fn compare_names_the_part_and_the_angle_of_its_worst_point() {
    use cycloid::model::place::{GoldenAt, Part};
    let xs = grid(0.125, 288);
    let f = |x: f64| 100.0 + 5.0 * (x.to_radians() * 10.0).sin();
    let tol = GoldenTolerance {
        abs: 1e-3,
        rel: 0.0,
    };
    for (columns, bumped, part) in [
        (
            vec!["roller_0", "roller_1", "roller_2"],
            2,
            Some((Part::Roller, 2)),
        ),
        (vec!["pin_0", "pin_1"], 1, Some((Part::Pin, 1))),
        (vec!["te_arcsec"], 0, None),
    ] {
        let columns: Vec<String> = columns.into_iter().map(String::from).collect();
        let values = |bump: f64| {
            (0..columns.len())
                .map(|c| {
                    curve(&xs, |x| {
                        f(x) + if c == bumped && x == 1.875 { bump } else { 0.0 }
                    })
                })
                .collect()
        };
        let golden = GoldenCurves {
            crank_deg: xs.clone(),
            curves: Curves {
                columns: columns.clone(),
                values: values(0.0),
            },
        };
        let now = Curves {
            columns: columns.clone(),
            values: values(0.01),
        };
        let c = compare(&golden, &xs, &now, tol, (None, part.map(|(p, _)| p)), None).unwrap();
        let at = GoldenAt {
            part,
            crank_deg: 1.875,
        };
        assert_eq!((c.worst.at, c.worst.disc), (at, None), "{c:?}");
        let words = match part {
            Some((Part::Roller, i)) => format!("roller {i} at crank 1.88°"),
            Some((Part::Pin, i)) => format!("pin {i} at crank 1.88°"),
            None => "crank 1.88°".to_string(),
        };
        assert_eq!(cycloid::report::place::text(&c.worst.place()), words);
        assert_eq!(cycloid::report::golden::in_row(&c.worst), words);
    }
}

/// On a one-disc reducer a golden of `disc: 0` (which validation allows) is the golden without
/// `disc`: `bless` words where its curve moved the same, without naming the disc. Two goldens
/// of the roller forces, one with `disc: 0`, one without, are moved alike (roller 0 at 12.3°
/// by 0.5 N) and blessed again: their lines are the same but for the file (before, the first
/// said "disc 0: roller 0 at crank 12.30°").
#[test]
fn bless_does_not_name_the_disc_of_a_one_disc_reducer() {
    let dir = scratch("one-disc");
    let spec = dir.join("spec.yaml");
    let golden = |file: &str, disc: &str| {
        format!(
            "  - scene: rated\n    quantity: roller_force_n\n{disc}    file: golden/{file}.csv\n    \
             tolerance: {{ abs: 0.01, rel: 1.0e-6 }}\n"
        )
    };
    let entries = golden("named", "    disc: 0\n") + &golden("plain", "");
    write(&spec, &spec_text(360, &entries));
    assert_eq!(run(&["bless", p(&spec)]).0, 0);
    for file in ["named", "plain"] {
        let path = dir.join(&format!("golden/{file}.csv"));
        let moved: Vec<String> = (std::fs::read_to_string(&path).unwrap().lines())
            .map(|line| match line.split_once(',') {
                Some(("12.3", rest)) => {
                    let (first, others) = rest.split_once(',').unwrap();
                    format!("12.3,{},{others}", first.parse::<f64>().unwrap() + 0.5)
                }
                _ => line.to_string(),
            })
            .collect();
        write(&path, &(moved.join("\n") + "\n"));
    }
    let (code, out, err) = run(&["bless", p(&spec)]);
    assert_eq!(code, 0, "{out}{err}");
    let line = |file: &str| {
        let line = out
            .lines()
            .find(|l| l.contains(&format!("{file}.csv")))
            .unwrap();
        line.replace(&format!("{file}.csv"), "FILE.csv")
    };
    assert!(
        line("plain").contains("at roller 0 at crank 12.30°"),
        "{out}"
    );
    assert_eq!(line("named"), line("plain"));
}

/// With several discs a golden's points name the disc whose curve it holds
/// (`specs/reducer-two-discs.yaml`: TE of the reducer, a torque of disc 0 and of disc 1, a
/// bearing force of disc 1); the check's row names the disc in its id (`[disc 1]`) and words
/// the place without it, as the shipped outputs have.
#[test]
fn a_golden_of_a_disc_names_the_disc_in_its_place() {
    let spec = cycloid::spec::load("specs/reducer-two-discs.yaml").unwrap();
    let run = cycloid::check(
        &spec,
        &cycloid::CheckOptions::default(),
        &cycloid::progress::Silent,
    )
    .unwrap();
    let discs: Vec<Option<usize>> = run.goldens.iter().map(|g| g.golden.disc).collect();
    assert_eq!(discs, [None, Some(0), Some(1), Some(1)]);
    for g in &run.goldens {
        for point in [&g.comparison.worst, &g.comparison.largest] {
            assert_eq!(point.disc, g.golden.disc);
            let words = cycloid::report::place::text(&point.place());
            let row = cycloid::report::golden::in_row(point);
            match g.golden.disc {
                Some(k) => assert_eq!(words, format!("disc {k}: {row}")),
                None => assert_eq!(words, row),
            }
        }
    }
}

#[test]
fn compare_wraps_angles_and_handles_infinite_values() {
    let xs = grid(1.0, 10);
    let golden = GoldenCurves {
        crank_deg: xs.clone(),
        curves: Curves {
            columns: vec!["bearing_angle_deg".into()],
            values: vec![curve(&xs, |_| 179.9995)],
        },
    };
    let now = Curves {
        columns: vec!["bearing_angle_deg".into()],
        values: vec![curve(&xs, |_| -179.9999)],
    };
    let tol = GoldenTolerance {
        abs: 1e-3,
        rel: 0.0,
    };
    let c = compare(&golden, &xs, &now, tol, (Some(360.0), None), None).unwrap();
    assert!(c.passed && c.worst.deviation < 1e-3, "{c:?}");
    assert!(
        !compare(&golden, &xs, &now, tol, (None, None), None)
            .unwrap()
            .passed
    );

    let inf = GoldenCurves {
        crank_deg: xs.clone(),
        curves: Curves {
            columns: vec!["backlash_arcsec".into()],
            values: vec![curve(&xs, |_| f64::INFINITY)],
        },
    };
    let same = inf.curves.clone();
    assert!(
        compare(&inf, &xs, &same, tol, (None, None), None)
            .unwrap()
            .passed
    );
    let finite = Curves {
        columns: vec!["backlash_arcsec".into()],
        values: vec![curve(&xs, |_| 1.0)],
    };
    assert!(
        !compare(&inf, &xs, &finite, tol, (None, None), None)
            .unwrap()
            .passed
    );
}

/// The crank-bearing force's angle is a direction: a golden of it written a whole turn off
/// (every value + 360°) is the same curve, and `check` passes it through the whole path (spec,
/// run, registry, comparison); half a turn off is the opposite direction and fails.
#[test]
fn a_bearing_angle_golden_a_whole_turn_off_is_the_same_curve() {
    let dir = scratch("bearing-angle-turn");
    let spec = dir.join("spec.yaml");
    let crank = "{ from_deg: 0.0, to_deg: 36.0, steps: 90 }";
    let text = PaperSpec::new()
        .scenes(&scene_item(
            "rated",
            10.0,
            crank,
            "clearance, roller_contact, bearing",
        ))
        .with(
            "golden:\n  - scene: rated\n    quantity: bearing_angle_deg\n    \
             file: golden/angle.csv\n    tolerance: { abs: 0.001, rel: 0.0 }\n",
        )
        .text()
        .to_string();
    write(&spec, &text);
    let (code, out, err) = run(&["bless", p(&spec)]);
    assert_eq!(code, 0, "{out}{err}");
    let csv = dir.join("golden/angle.csv");
    let blessed = std::fs::read_to_string(&csv).unwrap();
    let turned = |by: f64| -> String {
        let mut lines = blessed.lines();
        let mut text = format!("{}\n", lines.next().unwrap());
        for line in lines {
            let (crank, angle) = line.split_once(',').unwrap();
            let angle: f64 = angle.parse().unwrap();
            text += &format!("{crank},{}\n", angle + by);
        }
        text
    };
    write(&csv, &turned(360.0));
    let (code, out, err) = run(&["check", p(&spec)]);
    assert_eq!(code, 0, "a whole turn off is the same angle:\n{out}{err}");
    write(&csv, &turned(180.0));
    let (code, out, err) = run(&["check", p(&spec)]);
    assert_eq!(
        code, 1,
        "half a turn off is the opposite direction:\n{out}{err}"
    );
}

#[test]
fn golden_csv_reads_back_what_it_writes_and_rejects_bad_files() {
    let g = GoldenCurves {
        crank_deg: vec![0.0, 0.1, 0.2],
        curves: Curves {
            columns: vec!["roller_0".into(), "roller_1".into()],
            values: vec![vec![1.0 / 3.0, 0.0, -2.5e-7], vec![1e6, 12.0, -1e300]],
        },
    };
    let text = g.to_csv();
    assert!(text.starts_with("crank_deg,roller_0,roller_1\n0,0.3333333333,1000000\n"));
    let back = GoldenCurves::parse("x.csv", &text).unwrap();
    assert_eq!(back.crank_deg, g.crank_deg);
    assert_eq!(back.curves.values[1], g.curves.values[1]);
    assert!((back.curves.values[0][0] - 1.0 / 3.0).abs() < 1e-10);
    for (bad, why) in [
        ("", "empty file"),
        ("angle,x\n0,1\n", "first column must be `crank_deg`"),
        ("crank_deg,x\n0,1,2\n", "3 cells, the header has 2"),
        ("crank_deg,x\n0,one\n", "`one` is not a number"),
        ("crank_deg,x\n1,1\n0,1\n", "increasing"),
        ("crank_deg,x\n", "no data rows"),
        // A computed value is finite; `inf` or `nan` in a golden is a broken file.
        (
            "crank_deg,x\n0,1\n1,inf\n",
            "x.csv:3: `inf` is not a finite number",
        ),
        (
            "crank_deg,x\n0,NaN\n",
            "x.csv:2: `NaN` is not a finite number",
        ),
        // A row cut out of the middle leaves a double step.
        (
            "crank_deg,x\n0,1\n1,1\n3,1\n4,1\n",
            "x.csv:4: crank 3° follows 1°",
        ),
    ] {
        let e = GoldenCurves::parse("x.csv", bad).unwrap_err();
        assert!(e.contains(why), "{bad:?}: {e}");
    }
}

/// The keys of the registry curves `r` computed, each checked equal to the JSON array of the
/// same name in `json` (a scene's object, or a disc's).
fn curves_in_json(
    json: &serde_json::Value,
    curves: &dyn Fn(&Quantity) -> Option<Curves>,
) -> Vec<&'static str> {
    let mut seen = Vec::new();
    for q in QUANTITIES {
        let Some(c) = curves(q) else { continue };
        seen.push(q.key);
        let arr = &json[q.key];
        let rows: Vec<Vec<f64>> = if q.shape.per().is_some() {
            arr.as_array()
                .unwrap()
                .iter()
                .map(|row| {
                    row.as_array()
                        .unwrap()
                        .iter()
                        .map(|v| v.as_f64().unwrap())
                        .collect()
                })
                .collect()
        } else {
            vec![arr
                .as_array()
                .unwrap_or_else(|| panic!("{} missing", q.key))
                .iter()
                .map(|v| v.as_f64().unwrap_or(f64::INFINITY))
                .collect()]
        };
        assert_eq!(rows.len(), c.values.len(), "{}", q.key);
        for (a, b) in rows.iter().zip(&c.values) {
            for (x, y) in a.iter().zip(b) {
                assert!(x == y || (x - y).abs() <= 1e-12 * y.abs(), "{}", q.key);
            }
        }
    }
    seen
}

#[test]
fn every_golden_quantity_is_the_json_array_of_the_same_name() {
    let text = std::fs::read_to_string("specs/paper.yaml").unwrap();
    // One disc, and two: a disc's curves then sit under `discs[k]`.
    for (discs, text) in [
        (1, text.clone()),
        (
            2,
            // (its goldens name no disc: the two-disc spec leaves them out)
            text[..text.find("\ngolden_root:").unwrap()].replacen(
                "  rollers: 10",
                "  discs: 2\n  rollers: 10",
                1,
            ),
        ),
    ] {
        let spec = cycloid::spec::parse("specs/paper.yaml", &text).unwrap();
        assert_eq!(spec.design.discs, discs);
        let mut scene = spec.scenes[1].clone();
        scene.crank_rad.truncate(12);
        scene.effects = cycloid::model::Effect::listed().collect();
        // The plan of a run that writes the results JSON: every quantity is read.
        let writes = cycloid::engine::scene::Writes {
            json: true,
            report: false,
        };
        let plan = cycloid::engine::scene::plan(&spec, &scene, writes);
        let r = cycloid::engine::scene::run(&spec, &scene, &plan, &Default::default()).unwrap();
        let results = std::slice::from_ref(&r);
        let summaries = cycloid::engine::summary::marked(&spec, results);
        let doc = cycloid::report::json::scenes_value(&spec, results, &summaries).unwrap();
        let json = &doc["scenes"][0];
        let mut seen = curves_in_json(json, &|q| q.curves(&r));
        for (k, disc) in r.discs.iter().enumerate().filter(|_| r.names_discs()) {
            seen.extend(curves_in_json(&json["discs"][k], &|q| q.disc_curves(disc)));
        }
        seen.sort();
        seen.dedup();
        // Every curve over the crank angle (a torsion scene's figures are per locked angle, of
        // another kind of scene; a disc's torque share needs several discs).
        let curves = QUANTITIES
            .iter()
            .filter(|q| !q.is_scalar() && q.effect != cycloid::model::Effect::Torsion)
            // The efficiency's curves need `reducer.friction`, which specs/paper.yaml has not
            // (tests/it/friction.rs reads them from the JSON of a spec with friction).
            .filter(|q| q.effect != cycloid::model::Effect::Efficiency)
            // The pins' bending stress needs `output_pins.support` (tests/it/strength.rs).
            .filter(|q| q.effect != cycloid::model::Effect::Strength)
            .filter(|q| discs > 1 || q.key != "torque_nm")
            // The load along the face needs a scene that resolves the face (face_slices ≥ 2
            // with a crown or tilt; tests/it/face_width.rs reads them).
            .filter(|q| !cycloid::model::quantity::NEEDS_FACE.contains(q))
            .count();
        assert_eq!(
            seen.len(),
            curves,
            "{discs} disc(s): the scene computes every curve"
        );
    }
}

/// Every file under `dir`: path → (bytes, modification time).
fn snapshot(dir: &Path) -> Vec<(std::path::PathBuf, Vec<u8>, std::time::SystemTime)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.extend(snapshot(&path));
        } else {
            let modified = std::fs::metadata(&path).unwrap().modified().unwrap();
            out.push((path.clone(), std::fs::read(&path).unwrap(), modified));
        }
    }
    out.sort();
    out
}

/// `bless` on an unchanged engine writes nothing: the shipped goldens (of every shipped spec
/// that has some) stay byte for byte, not even renamed in place (their modification times
/// stay), and it says so. Their metadata is current (the spec hashes match the specs), so not
/// even a metadata file is due. A curve moved beyond its tolerance is written, with a new date.
#[test]
fn bless_on_an_unchanged_engine_writes_nothing() {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = scratch("twice");
    for sub in ["specs", "golden"] {
        let status = std::process::Command::new("cp")
            .args(["-r", &here.join(sub).display().to_string()])
            .arg(dir.join(sub))
            .status()
            .unwrap();
        assert!(status.success());
    }
    let before = snapshot(&dir.join("golden"));
    let mut blessed = 0;
    for spec in [
        "paper.yaml",
        "reducer-two-discs.yaml",
        "paper-negative-start.yaml",
    ] {
        // Named as a user at the repository's root names it, or not: no change either way.
        let path = dir.join("specs").join(spec);
        let run = crate::common::cycloid(&dir.path, &["bless", &path.display().to_string()]);
        assert_eq!(run.code(), 0, "{run:?}");
        assert!(
            run.stdout
                .contains("no change beyond their tolerances: nothing written"),
            "{spec}: {}",
            run.stdout
        );
        blessed += 1;
    }
    assert_eq!(blessed, 3);
    assert!(
        snapshot(&dir.join("golden")) == before,
        "bless changed a golden"
    );
    // The same spec at twice the torque: its TE moves far beyond 0.01 arcsec.
    let spec = dir.join("specs/paper.yaml");
    let text = std::fs::read_to_string(&spec).unwrap();
    let rated = "    output_torque_nm: 10.0\n";
    assert_eq!(text.matches(rated).count(), 1, "{text}");
    std::fs::write(&spec, text.replace(rated, "    output_torque_nm: 20.0\n")).unwrap();
    let later = cycloid_with(
        &dir.path,
        &["bless", &spec.display().to_string()],
        &[("SOURCE_DATE_EPOCH", "31536000")],
    );
    assert_eq!(later.code(), 0, "{later:?}");
    let meta = std::fs::read_to_string(dir.join("golden/paper/te_arcsec.csv.meta.yaml")).unwrap();
    assert!(meta.contains("date: 1971-01-01"), "{meta}");
    // The clearance curve does not depend on the torque: kept as it was.
    let meta =
        std::fs::read_to_string(dir.join("golden/paper/clearance_mm.csv.meta.yaml")).unwrap();
    assert!(!meta.contains("date: 1971-01-01"), "{meta}");
}
