//! Every spec under specs/ (and its subdirectories, e.g. specs/hard/) runs through
//! `cycloid check` with its expected exit code. A new spec must be added to the table, so
//! nothing ships unchecked.

use crate::common;

/// (file name, exit code, why).
const EXPECTED: &[(&str, i32, &str)] = &[
    ("reducer.yaml", 0, "paper optimum, clearance only"),
    (
        "requirements-robot-joint.yaml",
        2,
        "a requirements file for `cycloid design`, not a spec: `check` refuses its keys",
    ),
    (
        "requirements-duty-cycle.yaml",
        2,
        "a requirements file for `cycloid design` (a duty cycle, friction), not a spec",
    ),
    (
        "reducer-measured.yaml",
        0,
        "paper optimum as built: points with a planted 4 µm form error",
    ),
    (
        "reducer-tolerance.yaml",
        0,
        "paper optimum, clearance only, with its drawing's tolerances (check alone ignores them)",
    ),
    (
        "reducer-loaded.yaml",
        0,
        "paper optimum under 10 N·m, every effect, accuracy ladder for the design review",
    ),
    (
        "reducer-misaligned.yaml",
        0,
        "paper optimum crowned, aligned and tilted 0.3 mrad about x and y: the face load limits",
    ),
    (
        "reducer-crown-study.yaml",
        0,
        "paper optimum tilted 0.3 mrad about x and y: the crown study's optimum face load factor",
    ),
    (
        "reducer-torsion.yaml",
        0,
        "paper optimum: torsion at 4 locked angles, crank-bearing life at 20 N·m",
    ),
    (
        "reducer-pin-beams.yaml",
        0,
        "paper optimum with cantilever output pins and a structure compliance: torsion, life",
    ),
    (
        "reducer-strength.yaml",
        0,
        "paper optimum with cantilever pins: pin stress, contact fatigue, static safety",
    ),
    (
        "reducer-efficiency.yaml",
        0,
        "paper optimum with friction: efficiency, losses and temperature at 20 N·m, 1500 rpm",
    ),
    (
        "reducer-duty-cycle.yaml",
        0,
        "paper optimum through a robot joint's 4-bin duty cycle: Palmgren–Miner life 7571 h",
    ),
    (
        "reducer-at-speed.yaml",
        0,
        "two discs with a bore, density and output inertia: mass and inertia at the input",
    ),
    (
        "reducer-two-discs.yaml",
        0,
        "paper optimum with two discs: equal shares, torsion, bearing life, per-disc goldens",
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
    // Hard cases (issue 6, tests/it/hard_cases.rs): each spec says what it probes.
    ("hard/zero-modification.yaml", 0, "every roller touches"),
    ("hard/nano-modification.yaml", 0, "1e-9 mm modifications"),
    ("hard/torque-1e-6.yaml", 0, "1e-6 N·m, four scenes"),
    (
        "hard/torque-1e5.yaml",
        1,
        "1e5 N·m on a 3× reducer: ~13 GPa fails the pressure limit",
    ),
    (
        "hard/torque-1e5-beyond-capacity.yaml",
        2,
        "1e5 N·m on the paper's design: beyond what the disc holds",
    ),
    (
        "hard/preload-zero-torque.yaml",
        0,
        "interference preload, zero torque",
    ),
    ("hard/k1-0.95.yaml", 0, "K1 = 0.95"),
    ("hard/k1-1.0.yaml", 2, "K1 = 1: impossible design"),
    (
        "hard/undercut-99pct.yaml",
        0,
        "roller radius at 98.9 % of the undercut limit",
    ),
    (
        "hard/undercut-101pct.yaml",
        2,
        "undercut: impossible design",
    ),
    (
        "hard/rollers-3.yaml",
        0,
        "3 rollers, 2 pins: torsion across a 0.21 rad dead band",
    ),
    ("hard/rollers-4.yaml", 0, "4 rollers"),
    ("hard/rollers-80.yaml", 0, "80 rollers"),
    (
        "hard/hole-clearance.yaml",
        0,
        "hole clearance above the roller clearance",
    ),
    (
        "hard/multi-revolution.yaml",
        0,
        "from mid-period over three revolutions",
    ),
    ("hard/tiny-face-width.yaml", 0, "1 µm face width"),
    (
        "hard/zero-modification-zero-torque.yaml",
        0,
        "unmodified profile at rest",
    ),
    (
        "hard/preload-compliant-bearing.yaml",
        0,
        "preload on a soft crank bearing",
    ),
    (
        "hard/sharp-root.yaml",
        0,
        "a root sharper than the modification: a roller closes both ways",
    ),
];

/// Spec files under `dir`, one level of subdirectories deep, as paths relative to specs/.
fn spec_files(dir: &str, prefix: &str, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let entry = entry.unwrap();
        let name = entry.file_name().to_string_lossy().into_owned();
        if entry.file_type().unwrap().is_dir() {
            if prefix.is_empty() {
                spec_files(&format!("{dir}/{name}"), &format!("{name}/"), out);
            }
        } else if name.ends_with(".yaml") || name.ends_with(".yml") {
            out.push(format!("{prefix}{name}"));
        }
    }
}

#[test]
fn every_spec_exits_as_expected() {
    let mut found = Vec::new();
    spec_files("specs", "", &mut found);
    found.sort();
    let mut listed: Vec<String> = EXPECTED.iter().map(|e| e.0.to_string()).collect();
    listed.sort();
    assert_eq!(
        found, listed,
        "specs/ and the table of expected exit codes differ"
    );
    for (name, code, why) in EXPECTED {
        let out = common::cycloid_here(&["check", &format!("specs/{name}")]);
        assert_eq!(
            out.code,
            Some(*code),
            "specs/{name} ({why}):\n{}{}",
            out.stdout,
            out.stderr
        );
    }
}
