//! Issue 26's fault-injection harness. One fixture holds every kind of input a run reads: a
//! spec with measured points, a golden with its metadata, a tolerance study and its two shards,
//! a spec that does not load, and a symbolic link. Each row of `CASES` is a command, the
//! damage done to the fixture first (or the limit it pushes), and what must follow: the exit
//! code, where the message points, and every input file's bytes unchanged (only the files a
//! row names may appear). Shards are corrupted byte by byte besides.

use crate::common::{cycloid, files, Run, Scratch, PAPER};
use sha2::{Digest, Sha256};

/// The kind of fault a row injects.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Class {
    /// An output at the path of an input, however spelled.
    DataLoss,
    /// A damaged input that must not pass.
    FalsePass,
    /// A documented maximum, or beyond it: refused before allocation, with the bound named.
    Bound,
    /// An error that must name its spec location.
    Located,
    /// A spec written into another directory, which must check from there.
    Relocated,
}

/// One row: what runs, on what damage, and what must come out.
struct Case {
    class: Class,
    name: &'static str,
    /// The damage done to the fixture before the run.
    damage: fn(&Scratch),
    args: &'static [&'static str],
    code: i32,
    /// A part of the error output (a location, the bound, the input named).
    stderr: &'static str,
    /// Files the run writes (relative to the fixture); every other file keeps its bytes.
    writes: &'static [&'static str],
    /// For specs written elsewhere: a second run of the written spec, which must not be a
    /// usage or input error (exit 0 or 1).
    then: Option<&'static [&'static str]>,
}

/// The measured-points line of the fixture's spec, 1-based, where a missing file is reported.
const MEASURED_FILE_LINE: &str = "  file: disc.csv";

/// The fixture's spec: the paper's design measured (its own profile as the points), a golden
/// clearance curve, and a small tolerance study. 8 samples: with no failure the 95 % upper
/// bound of the rate is 1 − 0.025^(1/8) = 36.9 %, inside the allowed 50 %.
fn spec_text() -> String {
    format!(
        "{PAPER}measured_profile:\n{MEASURED_FILE_LINE}\n  format: csv\n  harmonics: 0\n  \
         fit: [shift_mm, equidistant_mm]\ntolerances:\n  scene: rated\n  \
         roller_radial_mm: 0.003\n  samples: 8\n  seed: 1\n  max_failure_rate: 0.5\n\
         golden_root: ../golden\ngolden:\n  - scene: rated\n    quantity: clearance_mm\n    \
         file: ../golden/m/clearance_mm.csv\n    tolerance: {{ abs: 1.0e-6 }}\n"
    )
}

/// A run that must succeed while the fixture is built.
fn ok(dir: &Scratch, args: &[&str]) {
    let run = cycloid(&dir.path, args);
    assert_eq!(run.code(), 0, "fixture: {args:?}: {run:?}");
}

/// The fixture: `specs/m.yaml` with `specs/disc.csv`, its golden and metadata under
/// `golden/m/`, the shards `shards/s0.bin` and `s1.bin` of its study, `specs/broken.yaml` (no
/// YAML), and `link` → `specs/sub`, so that `link/../m.yaml` is the spec.
fn fixture(tag: &str) -> Scratch {
    let dir = Scratch::new(tag);
    dir.write("specs/reducer.yaml", PAPER);
    ok(
        &dir,
        &["profile", "specs/reducer.yaml", "--csv", "specs/disc.csv"],
    );
    std::fs::remove_file(dir.join("specs/reducer.yaml")).unwrap();
    dir.write("specs/m.yaml", spec_text());
    std::fs::create_dir_all(dir.join("golden/m")).unwrap();
    ok(&dir, &["bless", "specs/m.yaml"]);
    std::fs::create_dir_all(dir.join("shards")).unwrap();
    for i in 0..2 {
        let (shard, out) = (format!("{i}/2"), format!("shards/s{i}.bin"));
        ok(
            &dir,
            &[
                "tolerance",
                "specs/m.yaml",
                "--shard",
                &shard,
                "--out",
                &out,
            ],
        );
    }
    dir.write("specs/broken.yaml", "name: x\nreducer: [\n");
    std::fs::create_dir_all(dir.join("specs/sub")).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(dir.join("specs/sub"), dir.join("link")).unwrap();
    dir
}

fn no_damage(_: &Scratch) {}

fn remove_measured(dir: &Scratch) {
    std::fs::remove_file(dir.join("specs/disc.csv")).unwrap();
}

/// A shard's byte offset of its first record, from the layout the format documents (MAGIC 16,
/// version 4, hash 32, four u64, limits u32, path u32 + bytes, text u64 + bytes).
fn records_start(bytes: &[u8]) -> usize {
    let u32_at = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
    let path_len_at = 16 + 4 + 32 + 32 + 4;
    let text_len_at = path_len_at + 4 + u32_at(path_len_at);
    let text_len = u64::from_le_bytes(bytes[text_len_at..text_len_at + 8].try_into().unwrap());
    text_len_at + 8 + text_len as usize
}

/// Change shard 0 with `edit` and write it back with its checksum made valid again: a shard
/// forged, or altered by a tool that knows the format, not cut or flipped by accident.
fn forge(dir: &Scratch, edit: impl FnOnce(&mut Vec<u8>)) {
    let path = dir.join("shards/s0.bin");
    let mut bytes = std::fs::read(&path).unwrap();
    bytes.truncate(bytes.len() - 32);
    edit(&mut bytes);
    let sum = Sha256::digest(&bytes);
    bytes.extend_from_slice(&sum);
    std::fs::write(&path, bytes).unwrap();
}

/// The first record's value −5 mm, its verdict byte left "passed" (1).
fn value_minus_5(dir: &Scratch) {
    forge(dir, |b| {
        let at = records_start(b);
        b[at..at + 8].copy_from_slice(&(-5.0f64).to_le_bytes());
    });
}

/// The first record's value NaN.
fn value_nan(dir: &Scratch) {
    forge(dir, |b| {
        let at = records_start(b);
        b[at..at + 8].copy_from_slice(&f64::NAN.to_le_bytes());
    });
}

/// One digit of the embedded spec changed (the seed 1 → 7), the header's hash left as it was.
fn spec_digit(dir: &Scratch) {
    forge(dir, |b| {
        let at = records_start(b);
        let text = String::from_utf8_lossy(&b[..at]).into_owned();
        let seed = text.find("seed: 1").expect("the embedded spec") + "seed: ".len();
        b[seed] = b'7';
    });
}

/// The header claims 2⁴⁰ samples (offset 16 + 4 + 32 + 8: after the seed).
fn samples_2_40(dir: &Scratch) {
    forge(dir, |b| {
        b[60..68].copy_from_slice(&(1u64 << 40).to_le_bytes())
    });
}

const MERGE: [&str; 4] = ["tolerance", "merge", "shards/s0.bin", "shards/s1.bin"];

const CASES: &[Case] = &[
    // Every output of every command against every input the run knows of.
    Case {
        class: Class::DataLoss,
        name: "check --json over the measured points",
        damage: no_damage,
        args: &["check", "specs/m.yaml", "--json", "specs/disc.csv"],
        code: 2,
        stderr: "would overwrite the measured points",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "check --junit over the golden",
        damage: no_damage,
        args: &[
            "check",
            "specs/m.yaml",
            "--junit",
            "golden/m/clearance_mm.csv",
        ],
        code: 2,
        stderr: "would overwrite the golden file of golden[0]",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "check of a spec that does not load, --junit over a file that is not ours",
        damage: no_damage,
        args: &["check", "specs/broken.yaml", "--junit", "specs/disc.csv"],
        code: 2,
        stderr: "not written: the spec did not load",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "tolerance --json over the measured points",
        damage: no_damage,
        args: &["tolerance", "specs/m.yaml", "--json", "specs/disc.csv"],
        code: 2,
        stderr: "--json specs/disc.csv would overwrite the measured points",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "tolerance --samples-csv over the measured points, spelled with ./",
        damage: no_damage,
        args: &[
            "tolerance",
            "specs/m.yaml",
            "--samples-csv",
            "specs/./disc.csv",
        ],
        code: 2,
        stderr: "would overwrite the measured points",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "tolerance --write-sample over the measured points",
        damage: no_damage,
        args: &[
            "tolerance",
            "specs/m.yaml",
            "--write-sample",
            "1",
            "specs/disc.csv",
        ],
        code: 2,
        stderr: "would overwrite the measured points",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "tolerance --shard --out over the golden",
        damage: no_damage,
        args: &[
            "tolerance",
            "specs/m.yaml",
            "--shard",
            "0/2",
            "--out",
            "golden/m/clearance_mm.csv",
        ],
        code: 2,
        stderr: "would overwrite the golden file",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "tolerance --json through a link and ..",
        damage: no_damage,
        args: &["tolerance", "specs/m.yaml", "--json", "link/../m.yaml"],
        code: 2,
        stderr: "would overwrite the spec",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "merge --json over the spec the shards name",
        damage: no_damage,
        args: &[
            MERGE[0],
            MERGE[1],
            MERGE[2],
            MERGE[3],
            "--json",
            "specs/m.yaml",
        ],
        code: 2,
        stderr: "would overwrite the spec",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "merge --samples-csv over the measured points of the spec the shards name",
        damage: no_damage,
        args: &[
            MERGE[0],
            MERGE[1],
            MERGE[2],
            MERGE[3],
            "--samples-csv",
            "specs/disc.csv",
        ],
        code: 2,
        stderr: "would overwrite the measured points",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "merge --json over a shard",
        damage: no_damage,
        args: &[
            MERGE[0],
            MERGE[1],
            MERGE[2],
            MERGE[3],
            "--json",
            "shards/s1.bin",
        ],
        code: 2,
        stderr: "would overwrite the shard file shards/s1.bin",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "profile --csv over the spec's measured points",
        damage: no_damage,
        args: &["profile", "specs/m.yaml", "--csv", "specs/disc.csv"],
        code: 2,
        stderr: "would overwrite the measured points",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "fit --form-csv over the golden's metadata",
        damage: no_damage,
        args: &[
            "fit",
            "specs/m.yaml",
            "--form-csv",
            "golden/m/clearance_mm.csv.meta.yaml",
        ],
        code: 2,
        stderr: "would overwrite the metadata of golden[0]",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "optimise --map over the measured points",
        damage: no_damage,
        args: &["optimise", "specs/m.yaml", "--map", "specs/disc.csv"],
        code: 2,
        stderr: "would overwrite the measured points",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "check --junit at a directory: refused before the run, not after it",
        damage: no_damage,
        args: &["check", "specs/m.yaml", "--junit", "golden"],
        code: 2,
        stderr: "--junit golden is a directory; give a file path",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::DataLoss,
        name: "tolerance --report at a file",
        damage: no_damage,
        args: &["tolerance", "specs/m.yaml", "--report", "specs/disc.csv"],
        code: 2,
        stderr: "--report specs/disc.csv is a file",
        writes: &[],
        then: None,
    },
    // Shards altered by a tool that knows the format (checksum made valid again).
    Case {
        class: Class::FalsePass,
        name: "a value set to −5 mm, its verdict left passed",
        damage: value_minus_5,
        args: &[MERGE[0], MERGE[1], MERGE[2], MERGE[3], "--json", "t.json"],
        code: 2,
        stderr: "shards/s0.bin",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::FalsePass,
        name: "a value set to NaN",
        damage: value_nan,
        args: &[MERGE[0], MERGE[1], MERGE[2], MERGE[3], "--json", "t.json"],
        code: 2,
        stderr: "holds the value NaN",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::FalsePass,
        name: "one digit of the embedded spec changed",
        damage: spec_digit,
        args: &[MERGE[0], MERGE[1], MERGE[2], MERGE[3], "--json", "t.json"],
        code: 2,
        stderr: "does not match the spec's hash",
        writes: &[],
        then: None,
    },
    // Documented maxima and beyond.
    Case {
        class: Class::Bound,
        name: "a shard header claiming 2^40 samples",
        damage: samples_2_40,
        args: &[MERGE[0], MERGE[1], MERGE[2], MERGE[3], "--json", "t.json"],
        code: 2,
        stderr: "shards/s0.bin",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::Bound,
        name: "--samples 1000000000, the documented maximum",
        damage: no_damage,
        args: &[
            "tolerance",
            "specs/m.yaml",
            "--samples",
            "1000000000",
            "--json",
            "t.json",
        ],
        code: 2,
        stderr: "beyond the 268435456 one study holds",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::Bound,
        name: "--shard N beyond the samples",
        damage: no_damage,
        args: &[
            "tolerance",
            "specs/m.yaml",
            "--shard",
            "0/1099511627776",
            "--out",
            "x.bin",
        ],
        code: 2,
        stderr: "N at most the 8 samples",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::Bound,
        name: "--report-crank-deg 1e300, beyond the crank angles a spec may give",
        damage: no_damage,
        args: &[
            "check",
            "specs/m.yaml",
            "--report",
            "rev",
            "--report-crank-deg",
            "1e300",
        ],
        code: 2,
        stderr: "--report-crank-deg 1e300 is beyond ±10000000°",
        writes: &[],
        then: None,
    },
    // Errors located at the key that names the file.
    Case {
        class: Class::Located,
        name: "check: the measured points are missing",
        damage: remove_measured,
        args: &["check", "specs/m.yaml"],
        code: 2,
        stderr: "LOCATED",
        writes: &[],
        then: None,
    },
    Case {
        class: Class::Located,
        name: "fit: the measured points are missing",
        damage: remove_measured,
        args: &["fit", "specs/m.yaml"],
        code: 2,
        stderr: "LOCATED",
        writes: &[],
        then: None,
    },
    // Specs written elsewhere check from where they are written.
    Case {
        class: Class::Relocated,
        name: "tolerance --write-sample into another directory",
        damage: no_damage,
        args: &[
            "tolerance",
            "specs/m.yaml",
            "--write-sample",
            "3",
            "out/s3.yaml",
        ],
        code: 0,
        stderr: "",
        writes: &["out/s3.yaml"],
        then: Some(&["check", "out/s3.yaml"]),
    },
    Case {
        class: Class::Relocated,
        name: "fit --write into another directory",
        damage: no_damage,
        args: &["fit", "specs/m.yaml", "--write", "out/fit.yaml"],
        code: 0,
        stderr: "",
        writes: &["out/fit.yaml"],
        then: Some(&["check", "out/fit.yaml"]),
    },
    Case {
        class: Class::Relocated,
        name: "fit --write into a directory reached through a link",
        damage: no_damage,
        args: &["fit", "specs/m.yaml", "--write", "link/fit.yaml"],
        code: 0,
        stderr: "",
        writes: &["specs/sub/fit.yaml"],
        then: Some(&["check", "link/fit.yaml"]),
    },
];

/// The spec location a missing measured-points file must be reported at: the line of
/// `file:` under `measured_profile`, column of the key.
fn measured_location() -> String {
    let text = spec_text();
    let line = text
        .lines()
        .position(|l| l == MEASURED_FILE_LINE)
        .expect("the measured line")
        + 1;
    format!("specs/m.yaml:{line}:3:")
}

/// Run one row on a fresh fixture and check all it promises.
fn run_case(case: &Case) {
    let dir = fixture("fault");
    std::fs::create_dir_all(dir.join("out")).unwrap();
    (case.damage)(&dir);
    let before = files(&dir.path);
    let run = cycloid(&dir.path, case.args);
    let what = format!("{:?} `{}` {:?}", case.class, case.name, case.args);
    assert_eq!(run.code(), case.code, "{what}: {run:?}");
    let want = match case.stderr {
        "LOCATED" => measured_location(),
        s => s.to_string(),
    };
    assert!(
        run.stderr.contains(&want),
        "{what}: wanted {want:?} in {}",
        run.stderr
    );
    let mut after = files(&dir.path);
    for w in case.writes {
        assert!(after.remove(*w).is_some(), "{what}: {w} was not written");
    }
    assert_eq!(
        after.keys().collect::<Vec<_>>(),
        before.keys().collect::<Vec<_>>(),
        "{what}: files appeared or vanished"
    );
    for (name, bytes) in &before {
        assert!(after[name] == *bytes, "{what}: {name} changed");
    }
    if let Some(then) = case.then {
        let Run { code, stderr, .. } = cycloid(&dir.path, then);
        assert!(
            matches!(code, Some(0 | 1)),
            "{what}: then {then:?} exited {code:?}: {stderr}"
        );
    }
}

/// Every row of the table, each class represented.
#[test]
fn every_injected_fault_is_refused_without_touching_an_input() {
    for class in [
        Class::DataLoss,
        Class::FalsePass,
        Class::Bound,
        Class::Located,
        Class::Relocated,
    ] {
        assert!(
            CASES.iter().any(|c| c.class == class),
            "no case of {class:?}"
        );
    }
    for case in CASES {
        run_case(case);
    }
}

/// Every byte of a shard flipped in turn (all bits of it): the merge refuses each, and writes
/// nothing. A flip in the checksum, the header, the embedded spec or a record must all show.
#[test]
fn a_shard_with_any_byte_changed_is_refused() {
    let dir = fixture("flip");
    let path = dir.join("shards/s0.bin");
    let good = std::fs::read(&path).unwrap();
    // Every byte of the header and spec, and of the records and checksum: a shard of 4
    // samples is a few kilobytes, a few seconds of runs.
    for at in 0..good.len() {
        let mut bad = good.clone();
        bad[at] ^= 0xff;
        std::fs::write(&path, &bad).unwrap();
        let run = cycloid(
            &dir.path,
            &[MERGE[0], MERGE[1], MERGE[2], MERGE[3], "--json", "t.json"],
        );
        assert_eq!(run.code(), 2, "byte {at} of {}: {run:?}", good.len());
        assert!(
            run.stderr.contains("shards/s0.bin"),
            "byte {at}: {}",
            run.stderr
        );
        assert!(!dir.exists("t.json"), "byte {at}: an output was written");
    }
}

/// Run `cycloid ARGS` (which must succeed) and read the spec it wrote to `out`.
fn written(dir: &Scratch, args: &[&str], out: &str) -> String {
    let mut args = args.to_vec();
    args.push(out);
    let run = cycloid(&dir.path, &args);
    assert_eq!(run.code(), 0, "{run:?}");
    dir.read(out)
}

/// The relocated spec names the same files as its source: the measured points and the golden
/// reached from `out/deeper/`; beside its source it keeps the paths as they were written.
#[test]
fn a_spec_written_elsewhere_names_the_same_files() {
    let dir = fixture("relocate");
    std::fs::create_dir_all(dir.join("out/deeper")).unwrap();
    let sample = ["tolerance", "specs/m.yaml", "--write-sample", "2"];
    let fit = ["fit", "specs/m.yaml", "--write"];
    let text = written(&dir, &sample, "out/deeper/s.yaml");
    assert!(
        text.contains("file: ../../golden/m/clearance_mm.csv"),
        "{text}"
    );
    // A sample is drawn from the drawing: its spec has no measured profile to reach.
    assert!(!text.contains("disc.csv"), "{text}");
    let text = written(&dir, &fit, "out/deeper/f.yaml");
    assert!(text.contains("file: ../../specs/disc.csv"), "{text}");
    assert!(
        text.contains("file: ../../golden/m/clearance_mm.csv"),
        "{text}"
    );
    let text = written(&dir, &sample, "specs/s.yaml");
    assert!(
        text.contains("file: ../golden/m/clearance_mm.csv"),
        "{text}"
    );
    let text = written(&dir, &fit, "specs/f.yaml");
    assert!(text.contains(MEASURED_FILE_LINE), "{text}");
    assert!(
        text.contains("file: ../golden/m/clearance_mm.csv"),
        "{text}"
    );
}
