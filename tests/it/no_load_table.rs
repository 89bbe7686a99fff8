//! `reducer.friction.no_load_torque_nmm` as a table over the input speed (issue 42): linear in
//! speed between its pairs, held beyond its ends, read at each scene's speed; a bad table is
//! refused where written.

use crate::common::{cycloid, Scratch};
use serde_json::Value;

const EFF: &str = include_str!("../../specs/reducer-efficiency.yaml");

/// A catalogue-like running-torque curve: 20 N·mm at 500 rpm, 30 at 1000, 60 at 3000.
const TABLE: &str = "no_load_torque_nmm: [[500.0, 20.0], [1000.0, 30.0], [3000.0, 60.0]]";

/// The shipped efficiency spec without its limits, its no-load torque `t0` (the text after the
/// key) and its speed `rpm`.
fn spec(t0: &str, rpm: &str) -> String {
    let text = EFF[..EFF.find("\nlimits:").unwrap() + 1].to_string();
    let line = "no_load_torque_nmm: 30.0";
    assert_eq!(text.matches(line).count(), 1);
    text.replacen(line, t0, 1).replacen(
        "input_speed_rpm: 1500.0",
        &format!("input_speed_rpm: {rpm}"),
        1,
    )
}

/// The `power_loss_w` of scene `rated` of `check --json`.
fn losses(text: &str) -> Value {
    let dir = Scratch::new("no-load-table");
    dir.write("s.yaml", text);
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml", "--json", "r.json"]).parts();
    assert_eq!(code, 0, "{out}{err}");
    let doc: Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    doc["scenes"][0]["power_loss_w"].clone()
}

/// At 1500 rpm the table gives 30 + (60 − 30)·(1500 − 1000)/(3000 − 1000) = 37.5 N·mm, at
/// 4000 rpm (beyond its end) 60 and at 100 rpm (before its start) 20: every loss of the scene
/// is then that of the same spec with the one number, bit for bit (the interpolation of these
/// values is exact in binary), and the no-load loss is T0·ω.
#[test]
fn the_table_is_linear_between_its_pairs_and_held_beyond() {
    for (rpm, t0) in [("1500.0", "37.5"), ("4000.0", "60.0"), ("100.0", "20.0")] {
        let table = losses(&spec(TABLE, rpm));
        let constant = losses(&spec(&format!("no_load_torque_nmm: {t0}"), rpm));
        assert_eq!(table, constant, "at {rpm} rpm");
        let omega = rpm.parse::<f64>().unwrap() * std::f64::consts::TAU / 60.0;
        let want = t0.parse::<f64>().unwrap() * omega * 1e-3;
        let got = table["no_load"].as_f64().unwrap();
        // 1e-12: ω and the W conversion rounded.
        assert!(
            (got / want - 1.0).abs() < 1e-12,
            "{got} W vs {want} W at {rpm} rpm"
        );
    }
}

/// A table not increasing in speed, with a negative torque or empty, and a table where a scene
/// computes the efficiency without a speed: exit 2 at the key (or the scene), with the numbers.
#[test]
fn a_bad_table_is_refused_where_written() {
    let line = |t: &str| {
        spec(t, "1500.0")
            .lines()
            .position(|l| l.contains(t))
            .unwrap()
            + 1
    };
    let cases = [
        (
            "no_load_torque_nmm: [[1000.0, 20.0], [1000.0, 30.0]]",
            "reducer.friction.no_load_torque_nmm",
            "pair 1 at 1000 rpm follows 1000 rpm",
        ),
        (
            "no_load_torque_nmm: [[0.0, 20.0], [1000.0, -3.0]]",
            "reducer.friction.no_load_torque_nmm",
            "pair 1 must be zero or positive, got -3",
        ),
        (
            "no_load_torque_nmm: []",
            "reducer.friction.no_load_torque_nmm",
            "got 0",
        ),
    ];
    let dir = Scratch::new("no-load-bad");
    for (t0, key, says) in cases {
        dir.write("s.yaml", spec(t0, "1500.0"));
        let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
        assert_eq!(code, 2, "{t0}: {out}{err}");
        let at = format!("s.yaml:{}:", line(t0));
        assert!(
            err.contains(&at) && err.contains(key) && err.contains(says),
            "{t0}: {err}"
        );
    }
    // No speed: the table cannot be read, refused at the scene.
    let text = spec(TABLE, "1500.0").replacen("    input_speed_rpm: 1500.0      # n\n", "", 1);
    dir.write("s.yaml", &text);
    let (code, out, err) = cycloid(&dir.path, &["check", "s.yaml"]).parts();
    assert_eq!(code, 2, "{out}{err}");
    assert!(
        err.contains("scenes[0]") && err.contains("input_speed_rpm"),
        "{err}"
    );
}
