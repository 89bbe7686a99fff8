//! Every spec under specs/ runs through `cycloid check` with its expected exit code. A new spec
//! must be added to the table, so nothing ships unchecked.

use std::process::Command;

/// (file name, exit code, why).
const EXPECTED: &[(&str, i32, &str)] = &[
    ("reducer.yaml", 0, "paper optimum, clearance only"),
    (
        "reducer-loaded.yaml",
        0,
        "paper optimum under 10 N·m, every effect, accuracy ladder for the design review",
    ),
    (
        "paper.yaml",
        0,
        "paper optimum (0.125, 0.1593) with its golden curves",
    ),
    (
        "paper-positive-start.yaml",
        0,
        "paper's positive start (0.135, 0.150): 15 µm, exactly on dt",
    ),
    (
        "paper-negative-start.yaml",
        1,
        "paper's negative start (−0.15, −0.135): −23 µm at mid-flank fails min_clearance",
    ),
    (
        "paper-negative-optimum.yaml",
        0,
        "this engine's negative optimum (−0.020130, 0): 15 µm, on dt at mid-flank",
    ),
    (
        "paper-positive-optimum.yaml",
        0,
        "this engine's positive ratio optimum (0.169641, 0.229179): 59.5 µm",
    ),
];

#[test]
fn every_spec_exits_as_expected() {
    let mut found: Vec<String> = std::fs::read_dir("specs")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".yaml") || n.ends_with(".yml"))
        .collect();
    found.sort();
    let mut listed: Vec<String> = EXPECTED.iter().map(|e| e.0.to_string()).collect();
    listed.sort();
    assert_eq!(
        found, listed,
        "specs/ and the table of expected exit codes differ"
    );
    for (name, code, why) in EXPECTED {
        let out = Command::new(env!("CARGO_BIN_EXE_cycloid"))
            .args(["check", &format!("specs/{name}")])
            .env("NO_COLOR", "1")
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(*code),
            "specs/{name} ({why}):\n{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
    }
}
