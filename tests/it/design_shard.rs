//! `cycloid design --shard I/N` and `cycloid design merge` (issue 31, item 4: "shards merge bit
//! for bit"): the shards of a search, merged, write what the unsharded run writes — the
//! front's specs, `front.csv`, the plots, the page and the terminal report — byte for byte
//! but for the wall time (which differs between any two runs); a feasible and an infeasible
//! search, 1 and 3 shards, and a Slurm job array's tasks. A merge refuses a set that is not one
//! whole run: a shard missing or given twice, a shard of other requirements, a cut file (exit
//! 2, naming the file, writing nothing).
//!
//! The reference is the unsharded run, an independent path through the search: the shards
//! evaluate the global stage in other processes, in other orders, and hand their numbers over
//! through the shard format, so a lost bit anywhere (a number rounded, a failure dropped, a
//! candidate misplaced) shows in the front or the report.

use crate::common::{self, cycloid, files, Scratch};
use crate::design_search::SMALL;

/// The report line and the page's passage of the wall time, cut out: from `wall time ` to the
/// end of its line or element.
pub(crate) fn without_wall_time(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("wall time ") {
        out.push_str(&rest[..at]);
        out.push_str("wall time _");
        let tail = &rest[at..];
        let end = tail.find(['\n', '<']).unwrap_or(tail.len());
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// `cycloid design small.yaml --shard I/N --out OUT` in `dir`, asserted to succeed.
fn write_shard(dir: &std::path::Path, (i, n): (usize, usize), out: &str) -> common::Run {
    let shard = format!("{i}/{n}");
    let r = cycloid(
        dir,
        &["design", "small.yaml", "--shard", &shard, "--out", out],
    );
    assert_eq!(r.code(), 0, "{r:?}");
    r
}

/// `SMALL` run whole into `whole/front` and as `n` shards merged into `sharded/front` (the
/// shards given to the merge in reverse order); the two runs' (exit code, stdout).
fn whole_and_merged(dir: &Scratch, text: &str, n: usize) -> ((i32, String), (i32, String)) {
    for d in ["whole", "sharded"] {
        dir.write(&format!("{d}/small.yaml"), text);
    }
    let whole = cycloid(
        &dir.join("whole"),
        &["design", "small.yaml", "--out", "front"],
    );
    assert!(whole.stderr.is_empty(), "{whole:?}");
    let sharded = dir.join("sharded");
    let mut shards = Vec::new();
    for i in 0..n {
        let out = format!("shard-{i}.bin");
        let r = write_shard(&sharded, (i, n), &out);
        assert!(r.stdout.contains(&format!("shard {i}/{n}")), "{r:?}");
        shards.push(out);
    }
    shards.reverse();
    let mut args = vec!["design", "merge", "--out", "front"];
    args.extend(shards.iter().map(String::as_str));
    let merged = cycloid(&sharded, &args);
    assert!(merged.stderr.is_empty(), "{merged:?}");
    assert!(
        merged
            .stdout
            .contains(&format!("(the merge of {n} shards: the local refinement;")),
        "{}",
        merged.stdout
    );
    ((whole.code(), whole.stdout), (merged.code(), merged.stdout))
}

/// Every file of the two fronts is the same, byte for byte; the page but for its wall time.
fn same_fronts(dir: &Scratch) -> usize {
    let whole = files(&dir.join("whole/front"));
    let merged = files(&dir.join("sharded/front"));
    assert_eq!(
        whole.keys().collect::<Vec<_>>(),
        merged.keys().collect::<Vec<_>>(),
        "the files written"
    );
    for (name, bytes) in &whole {
        let theirs = &merged[name];
        if name == "index.html" {
            let text = |b: &[u8]| without_wall_time(&String::from_utf8_lossy(b));
            assert_eq!(text(bytes), text(theirs), "index.html");
        } else {
            assert!(
                bytes == theirs,
                "{name} differs between the merge and the whole run"
            );
        }
    }
    whole.len()
}

#[test]
fn shards_merge_bit_for_bit() {
    // Without refinement the front is the global stage's own designs, their objectives as the
    // shards carried them; with it, the refinement starts from the shards' front.
    let unrefined = SMALL.replace("refine_budget: 12", "refine_budget: 0");
    for (text, n) in [(SMALL, 1), (SMALL, 3), (unrefined.as_str(), 3)] {
        let dir = Scratch::new("design-shard");
        let (whole, merged) = whole_and_merged(&dir, text, n);
        assert_eq!(whole.0, 0, "{}", whole.1);
        assert_eq!(merged.0, 0, "{}", merged.1);
        assert_eq!(without_wall_time(&whole.1), without_wall_time(&merged.1));
        // The front's specs, front.csv, its plot and the page: several designs, so the
        // comparison covers their order too.
        let written = same_fronts(&dir);
        assert!(written >= 2 + 3, "{written} files");
    }
}

#[test]
fn an_infeasible_search_merges_to_the_same_report_of_what_no_design_met() {
    // The requirements of `design_search`'s infeasible case (1 mm of clearance, 100 MPa):
    // every design fails, at the rules, the screen or the full check, so the report is built
    // from the failures the shards carry (their requirements, values, limits and messages,
    // and the stage each design reached: the counts of each requirement).
    let text = SMALL
        .replace("min_clearance_mm: 0.005", "min_clearance_mm: 1.0")
        .replace(
            "max_contact_pressure_mpa: 1500.0",
            "max_contact_pressure_mpa: 100.0",
        );
    let dir = Scratch::new("design-shard-infeasible");
    let (whole, merged) = whole_and_merged(&dir, &text, 3);
    assert_eq!(whole.0, 1, "{}", whole.1);
    assert_eq!(merged.0, 1, "{}", merged.1);
    assert!(whole
        .1
        .contains("FAIL: no design meets limits.min_clearance_mm"));
    assert_eq!(without_wall_time(&whole.1), without_wall_time(&merged.1));
    same_fronts(&dir);
}

#[test]
fn the_tasks_of_a_slurm_job_array_are_the_shards() {
    // `--array=1-3`: task ids 1 to 3 are shards 0 to 2, the same bytes as `--shard I/3`.
    let dir = Scratch::new("design-shard-slurm");
    let text = SMALL.replace("samples: 64", "samples: 8");
    dir.write("small.yaml", &text);
    for id in 1..=3 {
        let i = id - 1;
        write_shard(&dir.path, (i, 3), &format!("s{i}.bin"));
        let id = id.to_string();
        let env = [
            ("SLURM_ARRAY_TASK_ID", id.as_str()),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        let out = format!("task{id}.bin");
        let r = common::cycloid_with(&dir.path, &["design", "small.yaml", "--out", &out], &env);
        assert_eq!(r.code(), 0, "{r:?}");
        assert!(
            std::fs::read(dir.join(&out)).unwrap()
                == std::fs::read(dir.join(&format!("s{i}.bin"))).unwrap(),
            "task {id} is not shard {i}/3"
        );
    }
    // A shard without --out has nowhere to go: a usage error, before any work.
    let env = [
        ("SLURM_ARRAY_TASK_ID", "0"),
        ("SLURM_ARRAY_TASK_COUNT", "3"),
    ];
    let r = common::cycloid_with(&dir.path, &["design", "small.yaml"], &env);
    assert_eq!(r.code(), 2, "{r:?}");
    assert!(r.stderr.contains("needs --out SHARD_FILE"), "{}", r.stderr);
}

#[test]
fn a_merge_refuses_a_set_that_is_not_one_whole_run() {
    // Small and quick: 8 Sobol points, no refinement.
    let text = SMALL
        .replace("samples: 64", "samples: 8")
        .replace("refine_budget: 12", "refine_budget: 0");
    // Other requirements of the same seed, candidates and shard count: a limit changed, which
    // only the requirements' hash tells.
    let other = text.replace(
        "max_contact_pressure_mpa: 1500.0",
        "max_contact_pressure_mpa: 1400.0",
    );
    let dir = Scratch::new("design-shard-refuse");
    dir.write("small.yaml", &text);
    dir.write("other/small.yaml", &other);
    let shard = |sub: &Scratch, at: &str, i: usize| {
        write_shard(&sub.join(at), (i, 3), &format!("s{i}.bin"));
    };
    for i in 0..3 {
        shard(&dir, "", i);
    }
    shard(&dir, "other", 2);
    std::fs::copy(dir.join("s1.bin"), dir.join("s1-again.bin")).unwrap();
    let whole = std::fs::read(dir.join("s2.bin")).unwrap();
    // Cut anywhere: the last byte, or half the file.
    dir.write("s2-cut.bin", &whole[..whole.len() - 1]);
    dir.write("s2-half.bin", &whole[..whole.len() / 2]);

    let merge = |shards: &[&str]| {
        let mut args = vec!["design", "merge", "--out", "front"];
        args.extend(shards);
        let r = cycloid(&dir.path, &args);
        assert_eq!(r.code(), 2, "{shards:?}: {r:?}");
        assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
        assert!(r.stdout.is_empty(), "{r:?}");
        assert!(
            !dir.exists("front"),
            "{shards:?}: the merge wrote its front"
        );
        r.stderr
    };
    // The whole message, once.
    assert_eq!(
        merge(&["s0.bin", "s2.bin"]),
        "invalid value: shards of 3 missing: 1 (0-based indices); merge needs every shard of \
         the run\n"
    );
    let e = merge(&["s0.bin", "s1.bin", "s1-again.bin"]);
    assert!(
        e.contains("shard 1 of 3 is given twice: s1.bin and s1-again.bin"),
        "{e}"
    );
    let e = merge(&["s0.bin", "s1.bin", "other/s2.bin"]);
    assert!(
        e.contains(
            "other/s2.bin (shard 2) is of another design search than s0.bin (shard 0): its \
             requirements file is `small.yaml` (sha256"
        ),
        "{e}"
    );
    for cut in ["s2-cut.bin", "s2-half.bin"] {
        let e = merge(&["s0.bin", "s1.bin", cut]);
        assert!(
            e.contains(&format!(
                "{cut}: not a shard file of `cycloid design`: its checksum does not match its \
                 contents"
            )),
            "{e}"
        );
    }
    // Not a shard at all: the requirements file itself.
    let e = merge(&["s0.bin", "s1.bin", "small.yaml"]);
    assert!(
        e.contains("small.yaml: not a shard file of `cycloid design`"),
        "{e}"
    );
    // The whole set merges (the refusals above are of the sets, not of the shards).
    let r = cycloid(
        &dir.path,
        &[
            "design", "merge", "--out", "front", "s2.bin", "s0.bin", "s1.bin",
        ],
    );
    assert!(r.code() == 0 || r.code() == 1, "{r:?}");
    assert!(dir.exists("front/index.html"));
}

/// Issue 39 §5: a merge run from another directory than its shards never writes over the
/// requirements file they were made from, named `design-01.yaml` like the front's first spec:
/// found beside the shard (the recorded path is relative to where the shards ran) and, with
/// the shard elsewhere, by its text. Exit 2, the file as it was, nothing written.
#[test]
fn a_merge_from_another_directory_keeps_the_requirements_file() {
    // SMALL's front is not empty (`shards_merge_bit_for_bit`): it writes `design-01.yaml`.
    let text = SMALL.replace("refine_budget: 12", "refine_budget: 0");
    let dir = Scratch::new("design-merge-requirements");
    dir.write("design-01.yaml", &text);
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let r = cycloid(
        &dir.path,
        &[
            "design",
            "design-01.yaml",
            "--shard",
            "0/1",
            "--out",
            "s.bin",
        ],
    );
    assert_eq!(r.code(), 0, "{r:?}");
    dir.write("shards/s.bin", std::fs::read(dir.join("s.bin")).unwrap());
    for (shard, why) in [
        (
            "../s.bin",
            "would overwrite the requirements file design-01.yaml",
        ),
        (
            "../shards/s.bin",
            "would overwrite design-01.yaml, which holds the requirements",
        ),
    ] {
        let before = files(&dir.path);
        let r = cycloid(&dir.join("sub"), &["design", "merge", shard, "--out", ".."]);
        assert_eq!(r.code(), 2, "{shard}: {r:?}");
        assert!(r.stderr.contains(why), "{shard}: {}", r.stderr);
        assert_eq!(files(&dir.path), before, "{shard}: a file changed");
    }
}

/// Issue 39 §5: an output file whose path is a directory of the user's (`front/front.csv/`)
/// is refused, exit 2, the directory and its content left where they were, nothing written.
#[test]
fn a_directory_at_an_output_file_path_is_left_alone() {
    let text = SMALL
        .replace("samples: 64", "samples: 8")
        .replace("refine_budget: 12", "refine_budget: 0");
    let dir = Scratch::new("design-out-dir");
    dir.write("small.yaml", &text);
    dir.write("front/front.csv/mine.txt", "the user's");
    let before = files(&dir.path);
    let r = cycloid(&dir.path, &["design", "small.yaml", "--out", "front"]);
    assert_eq!(r.code(), 2, "{r:?}");
    assert!(
        r.stderr
            .contains("front/front.csv is a directory, not a file"),
        "{}",
        r.stderr
    );
    assert_eq!(
        files(&dir.path),
        before,
        "a file changed, appeared or vanished"
    );
}

/// A shard whose header no run has is refused by the decoder in the design search's words
/// (the check is `shard_file::Reader::check_header`, shared with the tolerance study's
/// shards): an index at its count, more shards than candidates, no shards, and requirements
/// that are not the ones the header's hash names.
#[test]
fn a_header_no_search_has_is_refused_in_its_words() {
    use cycloid::engine::design_search::shard::{decode, encode, requirements_hash, Header};
    let header = |index, count, text: &str| Header {
        text_sha256: requirements_hash("requirements"),
        seed: 1,
        items: 4,
        index,
        count,
        text_path: "req.yaml".into(),
        text: text.into(),
    };
    for (h, says) in [
        (header(2, 2, "requirements"), "shard 2/2 of 4 candidates"),
        (header(0, 5, "requirements"), "shard 0/5 of 4 candidates"),
        (header(0, 0, "requirements"), "shard 0/0 of 4 candidates"),
        (
            header(0, 2, "requirements, changed"),
            "the requirements it holds do not match the requirements' hash in its header",
        ),
    ] {
        let e = decode("s.bin", &encode(&h, &[])).unwrap_err();
        let expected = format!("s.bin: not a shard file of `cycloid design`: {says}");
        assert_eq!(e.message, expected, "{h:?}");
    }
}
