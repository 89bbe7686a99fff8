//! The cluster run for real (issue 26): `examples/slurm/tolerance.sbatch` submits the shipped
//! tolerance study as a job array of 4 shards and its merge to a Slurm cluster — the one-node
//! cluster `tools/slurm-one-node.sh` sets up on this machine — and the merged study must be the
//! unsharded `cycloid tolerance` run byte for byte: the JSON, the per-sample CSV, the review page
//! and the report the merge job printed. Likewise (issue 31) `examples/slurm/design.sbatch`: a
//! design search as 3 array tasks and a merge job gives the unsharded `cycloid design`'s front,
//! byte for byte but for the wall time. The two run one after the other (`SERIAL`).
//!
//! The tests change nothing on the machine: they install nothing and start no daemon. They run
//! where a cluster answers (`sinfo` lists a node up: `.ci/run` starts one with
//! `tools/slurm-one-node.sh` before the tests) and are skipped otherwise, printing why.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use crate::common::{cycloid, Scratch};

/// The shipped spec the README submits (2000 samples: ~1 s of one core for the whole study).
const SPEC: &str = "reducer-tolerance.yaml";

const SHARDS: usize = 4;

/// Held by each test for its whole run: one sets the cluster up and uses it at a time.
static SERIAL: Mutex<()> = Mutex::new(());

/// How long the jobs may take once submitted. The study computes in about a second; the rest
/// is Slurm's scheduling (a pass every few seconds, the merge waiting for the array). Generous,
/// so that a loaded machine does not fail it, and bounded, so that a stuck job cannot hang CI.
const JOBS_TIMEOUT: Duration = Duration::from_secs(300);

/// Job states after which a job changes no more (`scontrol show job`'s JobState).
const FINAL_STATES: &[&str] = &[
    "COMPLETED",
    "FAILED",
    "CANCELLED",
    "TIMEOUT",
    "NODE_FAIL",
    "OUT_OF_MEMORY",
    "BOOT_FAIL",
    "DEADLINE",
    "PREEMPTED",
];

fn repo(path: &str) -> String {
    format!("{}/{path}", env!("CARGO_MANIFEST_DIR"))
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Run a program to its end; its output, or a panic naming it when it cannot be started.
fn run(program: &str, args: &[&str], dir: &Path) -> Output {
    Command::new(program)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("{program} {args:?} did not start: {e}"))
}

/// `None` when a Slurm cluster answers, else why the tests skip (`answering` on this PATH).
fn cluster() -> Option<String> {
    answering(&std::env::var_os("PATH").unwrap_or_default())
}

/// `None` when `sinfo`, looked up on `path`, lists a node idle, mixed or allocated (as
/// tools/slurm-one-node.sh waits for); else why no cluster answers. Nothing is set up here.
fn answering(path: &std::ffi::OsStr) -> Option<String> {
    const START: &str = "start one with `bash tools/slurm-one-node.sh` (as root), as .ci/run does";
    let out = Command::new("sinfo")
        .args(["--noheader", "--Node", "--format=%t"])
        .env("PATH", path)
        .output();
    let out = match out {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Some(format!(
                "no Slurm cluster answers: `sinfo` is not on PATH; {START}"
            ))
        }
        Err(e) => {
            return Some(format!(
                "no Slurm cluster answers: `sinfo` did not run ({e}); {START}"
            ))
        }
        Ok(out) => out,
    };
    let stdout = text(&out.stdout);
    let states: Vec<&str> = stdout.split_whitespace().collect();
    if !out.status.success() {
        let err = text(&out.stderr);
        let why = err.lines().next().unwrap_or("no message").trim();
        return Some(format!(
            "no Slurm cluster answers: `sinfo` failed ({}: {why}); {START}",
            out.status
        ));
    }
    if states.iter().any(|s| ["idle", "mix", "alloc"].contains(s)) {
        return None;
    }
    Some(format!(
        "no Slurm node is up: `sinfo` lists {}; {START}",
        match states.is_empty() {
            true => "no node".to_string(),
            false => format!("the states {}", states.join(", ")),
        }
    ))
}

/// The array's and the merge's job ids from the script's last line,
/// "submitted array job A (N tasks) and merge job M".
fn job_ids(stdout: &str) -> (String, String) {
    let line = stdout.lines().last().unwrap_or_default();
    let words: Vec<&str> = line.split_whitespace().collect();
    let id = |i: usize| {
        words
            .get(i)
            .filter(|w| w.bytes().all(|b| b.is_ascii_digit()))
            .map(|w| w.to_string())
            .unwrap_or_else(|| panic!("no job ids in the script's output: {stdout:?}"))
    };
    assert!(
        line.starts_with("submitted array job") && line.contains("and merge job"),
        "{stdout:?}"
    );
    (id(3), id(words.len() - 1))
}

/// `scontrol show job ID`: one record per job (per task of an array).
fn show_job(id: &str) -> String {
    let out = run("scontrol", &["show", "job", id], Path::new("/"));
    text(&out.stdout) + &text(&out.stderr)
}

/// Every `KEY=value` of a `scontrol show job` output, in order (one per job of an array).
fn fields<'a>(record: &'a str, key: &str) -> Vec<&'a str> {
    let prefix = format!("{key}=");
    record
        .split_whitespace()
        .filter_map(|w| w.strip_prefix(prefix.as_str()))
        .collect()
}

/// What the jobs left, for a failure message: their records and their logs.
fn evidence(dir: &Path, array: &str, merge: &str) -> String {
    let mut s = format!(
        "scontrol show job {array}:\n{}\nscontrol show job {merge}:\n{}\n",
        show_job(array),
        show_job(merge)
    );
    let mut logs: Vec<_> = std::fs::read_dir(dir.join("logs"))
        .map(|d| d.map(|e| e.unwrap().path()).collect())
        .unwrap_or_default();
    logs.sort();
    for log in logs {
        let body = std::fs::read(&log).unwrap_or_default();
        s += &format!("--- {}:\n{}\n", log.display(), text(&body));
    }
    s
}

/// The merge job `merge` completed with exit 0 after the array `array` ran as `shards` tasks,
/// each to success and each writing `shards/{stem}-I.bin` in `dir` (the jobs' evidence in
/// every failure's message).
fn assert_array_and_merge_completed(
    dir: &Path,
    (array, merge): (&str, &str),
    shards: usize,
    stem: &str,
) {
    let record = wait_for_merge(dir, array, merge);
    let why = || evidence(dir, array, merge);
    assert_eq!(fields(&record, "JobState"), ["COMPLETED"], "{}", why());
    assert_eq!(fields(&record, "ExitCode"), ["0:0"], "{}", why());
    let tasks = show_job(array);
    assert_eq!(
        fields(&tasks, "JobState"),
        vec!["COMPLETED"; shards],
        "{}",
        why()
    );
    for i in 0..shards {
        assert!(
            dir.join(format!("shards/{stem}-{i}.bin")).is_file(),
            "{}",
            why()
        );
    }
}

/// `bash SCRIPT INPUT SHARDS` in `dir` (an sbatch script of examples/slurm/ submitting an
/// array and its merge), asserted to succeed: the array's and the merge's job ids.
fn submit(dir: &Path, script: &str, input: &str, shards: &str) -> (String, String) {
    let submit = Command::new("bash")
        .args([&repo(script), input, shards])
        .current_dir(dir)
        .env("CYCLOID", env!("CARGO_BIN_EXE_cycloid"))
        .env("SOURCE_DATE_EPOCH", "0")
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let stdout = text(&submit.stdout);
    assert!(submit.status.success(), "{stdout}{}", text(&submit.stderr));
    job_ids(&stdout)
}

/// Waits until the merge job is in a final state (or can never run); its record.
fn wait_for_merge(dir: &Path, array: &str, merge: &str) -> String {
    let start = Instant::now();
    loop {
        let record = show_job(merge);
        let state = fields(&record, "JobState").first().map(|s| s.to_string());
        if state.as_deref().is_some_and(|s| FINAL_STATES.contains(&s)) {
            return record;
        }
        // A failed task leaves the merge pending for ever (afterok can no longer be met).
        let never = fields(&record, "Reason").contains(&"DependencyNeverSatisfied");
        if never || start.elapsed() > JOBS_TIMEOUT {
            let _ = run("scancel", &[array, merge], Path::new("/"));
            panic!(
                "the merge job {merge} {} (state {state:?}); jobs cancelled.\n{}",
                if never {
                    "can never run: a task of the array failed".to_string()
                } else {
                    format!("did not finish within {JOBS_TIMEOUT:?}")
                },
                evidence(dir, array, merge)
            );
        }
        std::thread::sleep(Duration::from_millis(500));
    }
}

/// The first line where two texts differ (the files are too long to print whole).
fn first_difference(a: &[u8], b: &[u8]) -> String {
    let (a, b) = (text(a), text(b));
    let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    match (0..la.len().max(lb.len())).find(|&i| la.get(i) != lb.get(i)) {
        Some(i) => format!(
            "line {}: merged {:?}, unsharded {:?}",
            i + 1,
            la.get(i),
            lb.get(i)
        ),
        None => format!("same lines, {} against {} bytes", a.len(), b.len()),
    }
}

fn same_file(cluster: &Path, whole: &Path, name: &str) {
    let read = |dir: &Path| {
        std::fs::read(dir.join(name))
            .unwrap_or_else(|e| panic!("{}: {e}", dir.join(name).display()))
    };
    let (merged, unsharded) = (read(cluster), read(whole));
    assert!(
        merged == unsharded,
        "{name}: the merged study differs from the unsharded run at {}",
        first_difference(&merged, &unsharded)
    );
}

/// The shipped study as 4 Slurm array tasks and a dependent merge job equals the unsharded run,
/// byte for byte: the JSON (it holds no time or host: the spec's name and path, the settings,
/// the statistics and the worst samples), the CSV of every sample, the review page and its
/// histogram (the page's date pinned by SOURCE_DATE_EPOCH, exported to the jobs), and the
/// report the merge printed to its log. Both run the same spec path from their own directory.
#[test]
fn the_sbatch_study_on_a_one_node_cluster_equals_the_unsharded_run() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(reason) = cluster() {
        // Not through the test harness's capture: the reason must show in a passing run.
        let _ = writeln!(std::io::stderr(), "slurm_cluster: skipped: {reason}");
        return;
    }
    let dir = Scratch::new("slurm");
    let spec = std::fs::read(repo(&format!("specs/{SPEC}"))).unwrap();
    let (on_cluster, whole) = (dir.join("cluster"), dir.join("whole"));
    for d in [&on_cluster, &whole] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join(SPEC), &spec).unwrap();
    }
    let (array, merge) = submit(
        &on_cluster,
        "examples/slurm/tolerance.sbatch",
        SPEC,
        &SHARDS.to_string(),
    );

    // The unsharded run, while the cluster computes (common::cycloid pins SOURCE_DATE_EPOCH=0).
    let unsharded = cycloid(
        &whole,
        &[
            "tolerance",
            SPEC,
            "--json",
            "tolerance.json",
            "--samples-csv",
            "samples.csv",
            "--report",
            "tolerance-review",
        ],
    );
    assert_eq!(unsharded.code(), 0, "{unsharded:?}");

    // The array ran as SHARDS tasks, each to success, each writing its shard.
    assert_array_and_merge_completed(&on_cluster, (&array, &merge), SHARDS, "shard");

    let listing = |d: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(d.join("tolerance-review"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    assert_eq!(listing(&on_cluster), listing(&whole), "the review's files");
    for name in [
        "tolerance.json",
        "samples.csv",
        "tolerance-review/index.html",
        "tolerance-review/tolerance-min_clearance_mm.svg",
    ] {
        same_file(&on_cluster, &whole, name);
    }
    let log = std::fs::read_to_string(on_cluster.join(format!("logs/tolerance-merge-{merge}.out")))
        .unwrap();
    assert_eq!(
        log,
        unsharded.stdout + &unsharded.stderr,
        "the merge job's log"
    );
}

/// Design shards on the cluster.
const DESIGN_SHARDS: usize = 3;

/// The small search of `design_search` (64 Sobol points, a 32-design front, under a second) as
/// 3 Slurm array tasks and a dependent merge job equals the unsharded `cycloid design --out
/// front`: every spec of the front, front.csv and the plot byte for byte, the page and the
/// report the merge printed to its log but for the wall time (which differs between any two
/// runs).
#[test]
fn the_sbatch_design_search_on_a_one_node_cluster_equals_the_unsharded_run() {
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(reason) = cluster() {
        let _ = writeln!(std::io::stderr(), "slurm_cluster: skipped: {reason}");
        return;
    }
    let dir = Scratch::new("slurm-design");
    let (on_cluster, whole) = (dir.join("cluster"), dir.join("whole"));
    for d in [&on_cluster, &whole] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join("small.yaml"), crate::design_search::SMALL).unwrap();
    }
    let (array, merge) = submit(
        &on_cluster,
        "examples/slurm/design.sbatch",
        "small.yaml",
        &DESIGN_SHARDS.to_string(),
    );

    let unsharded = cycloid(&whole, &["design", "small.yaml", "--out", "front"]);
    assert_eq!(unsharded.code(), 0, "{unsharded:?}");

    assert_array_and_merge_completed(&on_cluster, (&array, &merge), DESIGN_SHARDS, "design");
    let merged = crate::common::files(&on_cluster.join("front"));
    let unsharded_files = crate::common::files(&whole.join("front"));
    assert_eq!(
        merged.keys().collect::<Vec<_>>(),
        unsharded_files.keys().collect::<Vec<_>>(),
        "the front's files"
    );
    assert!(merged.len() >= 5, "{:?}", merged.keys());
    // Each front design's review folder (`design-01/`, its files compared under their own
    // names) is listed with a trailing `/` and holds no bytes of its own.
    for name in (merged.keys()).filter(|n| *n != "index.html" && !n.ends_with('/')) {
        same_file(&on_cluster.join("front"), &whole.join("front"), name);
    }
    let page = |d: &Path| {
        crate::design_shard::without_wall_time(
            &std::fs::read_to_string(d.join("front/index.html")).unwrap(),
        )
    };
    assert_eq!(page(&on_cluster), page(&whole), "index.html");
    let log =
        std::fs::read_to_string(on_cluster.join(format!("logs/design-merge-{merge}.out"))).unwrap();
    assert_eq!(
        crate::design_shard::without_wall_time(&log),
        crate::design_shard::without_wall_time(&(unsharded.stdout + &unsharded.stderr)),
        "the merge job's log"
    );
}

/// What the tests say when they skip, from a PATH whose `sinfo` is missing or a stand-in
/// script: nothing is installed or started to make a cluster answer (issue 44 item 2).
#[test]
fn without_a_cluster_the_tests_skip_and_say_why() {
    let start = "start one with `bash tools/slurm-one-node.sh` (as root), as .ci/run does";
    let dir = Scratch::new("slurm-skip");
    let bin = |name: &str, script: &str| {
        use std::os::unix::fs::PermissionsExt;
        let d = dir.join(name);
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("sinfo"), format!("#!/bin/sh\n{script}\n")).unwrap();
        std::fs::set_permissions(d.join("sinfo"), std::fs::Permissions::from_mode(0o755)).unwrap();
        d.into_os_string()
    };
    std::fs::create_dir_all(dir.join("empty")).unwrap();
    assert_eq!(
        answering(dir.join("empty").as_os_str()),
        Some(format!(
            "no Slurm cluster answers: `sinfo` is not on PATH; {start}"
        ))
    );
    let down = bin("down", "echo down; echo drain");
    assert_eq!(
        answering(&down),
        Some(format!(
            "no Slurm node is up: `sinfo` lists the states down, drain; {start}"
        ))
    );
    let none = bin("none", "exit 0");
    assert_eq!(
        answering(&none),
        Some(format!(
            "no Slurm node is up: `sinfo` lists no node; {start}"
        ))
    );
    let refused = bin(
        "refused",
        "echo 'slurm_load_node: Unable to contact slurm controller' >&2; exit 1",
    );
    assert_eq!(
        answering(&refused),
        Some(format!(
            "no Slurm cluster answers: `sinfo` failed (exit status: 1: slurm_load_node: Unable \
             to contact slurm controller); {start}"
        ))
    );
    assert_eq!(answering(&bin("up", "echo mix")), None);
}
