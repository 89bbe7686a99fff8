//! Issue 39 §5, "false pass": every value a spec gives for a physical quantity is checked
//! against a physical bound where it is written (file:line:column, the bound and the value),
//! so that no absurd input computes an inf that then passes. Before the bounds a tilt of
//! 1e300 mrad printed a bearing force of inf N and passed, h·A of 1e-200 printed "inf °C",
//! and 1e307 rpm gave an infinite power.

use crate::common::{cycloid, Scratch};

/// The shipped spec `name` with `from` replaced by `to` (once, where written).
fn edited(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(format!("specs/{name}")).unwrap();
    assert_eq!(text.matches(from).count(), 1, "{name}: {from}");
    text.replacen(from, to, 1)
}

/// The line and column (1-based) where `written` first occurs in `text`.
fn locate(text: &str, written: &str) -> (usize, usize) {
    let offset = text.find(written).unwrap();
    let line = text[..offset].matches('\n').count() + 1;
    (
        line,
        offset - text[..offset].rfind('\n').map_or(0, |p| p + 1) + 1,
    )
}

/// `text` is refused at the line and column where its bad key is written (`written`, the key
/// and its value as the text has them), naming the key's last segments `named`, `bound` and
/// `value`; and `cycloid check` exits 2 on it.
fn refused(dir: &Scratch, text: &str, written: &str, named: &str, bound: &str, value: &str) {
    let shown = cycloid::spec::parse("bad.yaml", text)
        .expect_err(named)
        .to_string();
    let (line, column) = locate(text, written);
    assert!(
        shown.starts_with(&format!("bad.yaml:{line}:{column}:")),
        "{named} at {line}:{column}: {shown}"
    );
    for part in [named, bound, value] {
        assert!(shown.contains(part), "{named}: no {part:?} in {shown}");
    }
    dir.write("bad.yaml", text);
    let run = cycloid(&dir.path, &["check", "bad.yaml"]);
    assert_eq!(run.code(), 2, "{named}: {}", run.stderr);
    assert!(!run.stdout.contains("inf"), "{named}: {}", run.stdout);
}

#[test]
fn absurd_physical_values_are_refused_where_written() {
    let dir = Scratch::new("physical-bounds");
    let tilt = "about_x_mrad: 0.3";
    // 1e300 mrad gave an infinite bearing force; 30 mrad, well inside double range, is beyond
    // the first-order face model and was blamed on "a preload or an interference".
    for value in ["1.0e300", "30.0", "-5.5"] {
        let written = format!("about_x_mrad: {value}");
        let text = edited("reducer-misaligned.yaml", tilt, &written);
        let shown = value.trim_end_matches(".0").replace("1.0e300", "1e300");
        refused(
            &dir,
            &text,
            &written,
            "misalignment.about_x_mrad",
            "±5 mrad",
            &shown,
        );
    }
    // A tilt as built, under reducer.deviations, is held to the same bound.
    let text = edited(
        "reducer-misaligned.yaml",
        "reducer:\n",
        "reducer:\n  deviations:\n    misalignment: { about_y_mrad: 6.0 }\n",
    );
    refused(
        &dir,
        &text,
        "about_y_mrad: 6.0",
        "deviations.misalignment.about_y_mrad",
        "±5 mrad",
        "6",
    );
    // h·A of 1e-200 made the temperature rise P/(h·A) infinite.
    for (key, from, bound) in [
        (
            "housing_area_m2",
            "housing_area_m2: 0.06",
            "[0.0001, 100] m²",
        ),
        (
            "heat_transfer_w_per_m2k",
            "heat_transfer_w_per_m2k: 20.0",
            "[0.1, 100000] W/(m²·K)",
        ),
    ] {
        let written = format!("{key}: 1.0e-200");
        let text = edited("reducer-efficiency.yaml", from, &written);
        refused(
            &dir,
            &text,
            &written,
            &format!("thermal.{key}"),
            bound,
            "1e-200",
        );
    }
    let text = edited(
        "reducer-efficiency.yaml",
        "input_speed_rpm: 1500.0",
        "input_speed_rpm: 1.0e307",
    );
    refused(
        &dir,
        &text,
        "input_speed_rpm: 1.0e307",
        "input_speed_rpm",
        "100000 rpm",
        "1e307",
    );
    // A duty cycle's bin: 2e5 rpm, above the bound.
    let text = edited(
        "reducer-duty-cycle.yaml",
        "input_speed_rpm: 2000.0",
        "input_speed_rpm: 2.0e5",
    );
    refused(
        &dir,
        &text,
        "input_speed_rpm: 2.0e5",
        "duty_cycle[1].input_speed_rpm",
        "100000 rpm",
        "200000",
    );
}

/// A friction coefficient below 0 or not a number is told so, not given the text written for
/// one of 1 or more ("no engineering contact's"), which it is not.
#[test]
fn a_negative_or_nan_friction_coefficient_is_told_what_it_is() {
    let dir = Scratch::new("mu-messages");
    let from = "mu: 0.0025";
    for (value, shown) in [("-0.05", "-0.05"), (".nan", "NaN")] {
        let written = format!("mu: {value}");
        let text = edited("reducer-efficiency.yaml", from, &written);
        refused(
            &dir,
            &text,
            &written,
            "mu",
            "0 (no friction) or more",
            shown,
        );
        let err = cycloid::spec::parse("bad.yaml", &text)
            .unwrap_err()
            .to_string();
        assert!(!err.contains("1 or more"), "{err}");
    }
    // One of 1 or more keeps its own text.
    let text = edited("reducer-efficiency.yaml", from, "mu: 1.5");
    refused(&dir, &text, "mu: 1.5", "mu", "1 or more", "1.5");
}
