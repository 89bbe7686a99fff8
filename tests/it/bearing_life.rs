//! The crank-bearing life on ordinary inputs that used to fail (issue 26): a reducer as built
//! whose loaded period is longer than the drawing's (a tolerance study's draws, a disc measured
//! with a form error), an unloaded bearing (no finite life), an exponent that overflows the
//! life, and a crank range that is not whole loaded periods. Each is either computed or refused
//! before anything runs with the rule, its numbers and its location: never the unlocated "L10h
//! is missing" of a scene that ran without a life to check.

use crate::common::{cycloid, Scratch};
use cycloid::engine::bearing_life::{equivalent_load, life_h};
use cycloid::model::results::UNBOUNDED_LIFE_H;

/// The shipped torsion spec: the paper's design with a crank bearing (C = 12 kN), a torsion
/// scene and a rated scene at 20 N·m over the loaded period 0°–108°, `min_bearing_life_h`.
const TORSION: &str = include_str!("../../specs/reducer-torsion.yaml");

/// `TORSION` with `from` replaced by `to` (exactly once).
fn edited(from: &str, to: &str) -> String {
    assert_eq!(TORSION.matches(from).count(), 1, "`{from}`");
    TORSION.replacen(from, to, 1)
}

const RATED_RANGE: &str = "crank: { from_deg: 0.0, to_deg: 108.0, steps: 1080 }";

/// (exit code, stdout, stderr) of `cycloid ARGS` on `text` written as `s.yaml`, in `dir`.
fn run(dir: &Scratch, text: &str, args: &[&str]) -> (i32, String, String) {
    dir.write("s.yaml", text);
    cycloid(&dir.path, args).parts()
}

/// The rated scene's crank range as written, at `scenes[1].crank` of `s.yaml` (line 38).
const AT_RATED_CRANK: &str = "s.yaml:38:5: invalid value: scenes[1].crank: ";

/// A tolerance study draws rollers off their places: the loaded curves then repeat only after
/// lcm(360°, 54°) = 1080° (the gaps after a crank turn, the pins' pattern every
/// 360°·nc/(np·M) = 54°), so the drawing's 108° is a tenth of a load cycle. Before anything
/// runs the study is refused at the scene's crank range, naming the drawn kind and the whole
/// range; over 0°–1080° it runs and judges every sample's life.
#[test]
fn a_tolerance_study_of_a_bearing_life_spans_the_drawn_period() {
    let dir = Scratch::new("life-tolerance");
    let tolerances = "tolerances:\n  scene: rated\n  roller_radial_mm: 0.003\n  samples: 4\n  \
                      seed: 1\n  max_failure_rate: 0.5\n";
    let text = format!("{TORSION}{tolerances}");
    let (code, out, err) = run(&dir, &text, &["tolerance", "s.yaml"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.starts_with(AT_RATED_CRANK), "{err}");
    for part in [
        "crank range 0° to 108° is not a whole number of loaded periods (1080° for the reducer \
         as built, the parts the tolerance study draws: tolerances.roller_radial_mm)",
        "the nearest ranges of whole periods: 0° to 1080° (1 period)",
    ] {
        assert!(err.contains(part), "missing `{part}` in {err}");
    }
    let whole = text.replace(
        RATED_RANGE,
        "crank: { from_deg: 0.0, to_deg: 1080.0, steps: 2160 }",
    );
    let (code, out, err) = run(&dir, &whole, &["tolerance", "s.yaml"]);
    assert!(code == 0 || code == 1, "{out}{err}");
    assert!(out.contains("min_bearing_life_h ≥ 5000 h"), "{out}");
}

/// The disc identified from measured points carries a form error (its harmonics, however
/// small), which repeats only after a whole turn of the disc, nc = 9 crank turns = 3240°: the
/// spec's 108° is refused at its crank range before any scene runs (it used to run and stop
/// on "L10h is missing", with no location).
#[test]
fn a_measured_disc_with_a_form_error_needs_its_whole_period() {
    let dir = Scratch::new("life-measured");
    dir.write("made.yaml", TORSION);
    let (code, _, err) = cycloid(&dir.path, &["profile", "made.yaml", "--csv", "disc.csv"]).parts();
    assert_eq!(code, 0, "{err}");
    let measured = "measured_profile: {file: disc.csv, format: csv, harmonics: 2}\nlimits:";
    let text = edited("limits:", measured);
    let (code, out, err) = run(&dir, &text, &["check", "s.yaml"]);
    assert_eq!(code, 2, "{out}{err}");
    assert!(err.starts_with(AT_RATED_CRANK), "{err}");
    for part in [
        "(3240° for the reducer as built, the disc identified from `measured_profile`",
        "0° to 3240° (1 period)",
    ] {
        assert!(err.contains(part), "missing `{part}` in {err}");
    }
}

/// A crank range that is not whole loaded periods says the period and the nearest whole
/// ranges: 360° is 3⅓ periods of 108°, so 0°–324° and 0°–432°; 65.45° is less than one, so
/// 0°–108° alone.
#[test]
fn a_partial_load_cycle_names_the_nearest_whole_ranges() {
    let dir = Scratch::new("life-ranges");
    for (range, expected) in [
        (
            "crank: { from_deg: 0.0, to_deg: 360.0, steps: 3600 }",
            "0° to 360° is not a whole number of loaded periods (108.0°): the equivalent load \
             is a mean over whole load cycles (ISO 281); the nearest ranges of whole periods: \
             0° to 324° (3 periods) or 0° to 432° (4 periods)",
        ),
        (
            "crank: { from_deg: 0.0, to_deg: 65.45, steps: 100 }",
            "the nearest ranges of whole periods: 0° to 108° (1 period)",
        ),
    ] {
        let (code, out, err) = run(&dir, &edited(RATED_RANGE, range), &["check", "s.yaml"]);
        assert_eq!(code, 2, "{out}{err}");
        assert!(err.starts_with(AT_RATED_CRANK), "{err}");
        assert!(err.contains(expected), "{err}");
    }
}

/// At zero torque the bearing carries nothing (P = 0 N) and never wears: its life is
/// unbounded. It is written as the largest double (JSON has no ∞), the check passes and its
/// place says "unbounded"; no null, no inf anywhere in the JSON.
#[test]
fn an_unloaded_bearing_has_an_unbounded_life_that_passes() {
    let dir = Scratch::new("life-unloaded");
    let text = edited("    output_torque_nm: 20.0", "    output_torque_nm: 0.0");
    let (code, out, err) = run(&dir, &text, &["check", "s.yaml", "--json", "r.json"]);
    assert_eq!(code, 0, "{out}{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("rated/min_bearing_life_h"))
        .unwrap();
    assert!(
        line.contains("pass") && line.contains("unbounded: P = 0 N"),
        "{line}"
    );
    let json: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    assert_finite(&json, "r.json");
    assert_eq!(json["scenes"][1]["bearing_life_h"].as_f64(), Some(f64::MAX));
    assert_eq!(
        json["scenes"][1]["bearing_equivalent_load_n"].as_f64(),
        Some(0.0)
    );
}

/// Every number in `v` is finite, and nothing is null (what a non-finite number would be).
fn assert_finite(v: &serde_json::Value, at: &str) {
    use serde_json::Value;
    match v {
        Value::Null => panic!("null at {at}"),
        Value::Number(n) => assert!(n.as_f64().is_some_and(f64::is_finite), "{at}: {n}"),
        Value::Array(a) => a
            .iter()
            .enumerate()
            .for_each(|(i, x)| assert_finite(x, &format!("{at}[{i}]"))),
        Value::Object(o) => o
            .iter()
            .for_each(|(k, x)| assert_finite(x, &format!("{at}.{k}"))),
        _ => {}
    }
}

/// The life's formula never gives ∞: no load is unbounded, and so is a life beyond the largest
/// double ((C/P)^p·10⁶ h past 1.8e308: C/P = 1e100 at p = 10/3 gives 1e333), while a finite
/// life keeps its value (the hand value 39 561.3 h of `torsion.rs`).
#[test]
fn the_life_is_finite_or_unbounded_never_infinite() {
    assert_eq!(
        life_h(0.0, 12_000.0, 10.0 / 3.0, 1500.0, 9),
        UNBOUNDED_LIFE_H
    );
    assert_eq!(
        life_h(12_000.0 * 1e-100, 12_000.0, 10.0 / 3.0, 1500.0, 9),
        UNBOUNDED_LIFE_H
    );
    let p = equivalent_load(&[1000.0; 3], 10.0 / 3.0);
    let life = life_h(p, 12_000.0, 10.0 / 3.0, 1500.0, 9);
    assert_eq!(p, 1000.0);
    assert!((life - 39_561.3).abs() <= 1e-5 * 39_561.3, "{life}");
}

/// An exponent outside 1 to 10 is refused at its key, naming ISO 281's values (at 1000 the
/// life (C/P)^p overflowed and the check stopped on a missing life); 10 itself computes.
#[test]
fn a_life_exponent_beyond_the_physical_range_is_refused() {
    let dir = Scratch::new("life-exponent");
    let exponent = "life_exponent: 3.3333333333333335";
    let (code, out, err) = run(
        &dir,
        &edited(exponent, "life_exponent: 1000"),
        &["check", "s.yaml"],
    );
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.starts_with(
            "s.yaml:24:5: invalid value: reducer.crank_bearing.life_exponent: must be between 1 \
             and 10, got 1000: ISO 281 uses 3 for ball bearings and 10/3 for roller bearings"
        ),
        "{err}"
    );
    let (code, out, err) = run(
        &dir,
        &edited(exponent, "life_exponent: 10.0"),
        &["check", "s.yaml"],
    );
    assert!(code == 0 || code == 1, "{out}{err}");
}
