//! Issue 40's contract for a refactor: a change that moves code keeps every output. Each
//! spec below (one disc, two discs, a duty cycle, torsion with friction, efficiency, strength,
//! inertia at speed, a tilted face: every result shape and every effect's document) is run
//! through `check --json --report`, and its terminal text with the exit code, its results JSON
//! and every file of its review are hashed (SHA-256 of each file, listed by path, the list
//! hashed) and held to the digest recorded with the build before the change
//! (`tools/output-digests.sh`, which does the same with shell tools, so the digests do not come
//! from this code). Masked, as `tools/same-outputs.sh` masks them: the output directory's path
//! and the accuracy ladder's wall-clock cells. `tools/same-outputs.sh` compares all 34 shipped
//! specs byte for byte (minutes); this is the part CI can afford (seconds).
//!
//! A change that alters an output on purpose re-records the digests with its own build and
//! names the change in its commit.

use crate::common::{cycloid_here, files, Scratch};
use sha2::{Digest, Sha256};
use std::path::Path;

/// (spec under `specs/`, digest), recorded by `tools/output-digests.sh`: first with the build
/// of 4234b47 (before issue 40's one run path, typed locations and registry documents, which
/// kept them), then re-recorded when the disc's mass properties became exact (the profile's
/// moments by the trapezoid rule instead of a 0.1 µm polygon: the mass fields of every
/// results JSON, the review's mass row, J_c's last printed digit of the paper's optimum, and
/// the centripetal force of `reducer-at-speed` moved by up to 3e-6 relative), then when a
/// round-off centroid offset and unbalance force became words (the review's mass row of every
/// spec, "centroid on the centre"; `reducer-at-speed`'s unbalance in its terminal line and its
/// scene's note, "no unbalance force"; the JSON unchanged), then when the review's captions of
/// the torsion curve and of the power lost on each path began with a capital like the others
/// (`reducer-torsion`, `reducer-two-discs`, `reducer-efficiency`), and the torsion section's
/// hysteresis sentence ("Hysteresis loss 0: …", `reducer-torsion`, `reducer-two-discs`), then
/// when the three captions that ended without a full stop took one (the torsion curve's, the
/// efficiency against torque's and the power lost on each path's).
#[rustfmt::skip]
const RECORDED: &[(&str, &str)] = &[
    ("reducer", "d39184c4c79e58baf96fb8e134575ac3aea4ef3c258fc24cdd17e48473f8ed87"),
    ("reducer-loaded", "aa6638e93dbd8145cc656fe4118516f5f46fc3ccc85e1508b241ba49f1bff7b1"),
    ("reducer-two-discs", "b46789f40ff5e45a4f9db398e33550ad6702c0134c17efa25a8d3d3fde3dcb23"),
    ("reducer-duty-cycle", "0e1e9cc48e3d27e8a9e917b881824269f5a5df78476966f23466ff8229d52e88"),
    ("reducer-torsion", "6b95c9d862cffe35c708d042e0340b13216e4ccd17dff63268fe736bea7ab984"),
    ("reducer-efficiency", "493b9708600c785d4773e02eb912eb184b45ab1f942ca6ea2436856f2644a495"),
    ("reducer-strength", "b20ecc4e6767a0862ae9a20e147317c020131643be61a6ce81e263f9999f0acd"),
    ("reducer-at-speed", "d98152553d70a8ca8fe46b43b5619b70fa856a74afd59537d594a51ca14b373b"),
    ("reducer-misaligned", "bdf465e501873becb7348b0661c372dc7bf09241d0af952b57e3bdb946ff3760"),
];

/// The wall-clock figures masked as the shell's `sed -E` masks them:
/// `s/in [0-9]+\.[0-9]+ s\b/in <time> s/g` ("13 rungs in 0.86 s"), then
/// `s/>[0-9]+(\.[0-9]+)? m?s</><time></g` (the accuracy ladder's cells, `>0.4 ms<`).
fn mask_times(text: &str) -> String {
    let text = replace_matches(text, "in ", "in <time> s", seconds_end);
    replace_matches(&text, ">", "><time><", cell_end)
}

/// `text` with each match replaced: a match starts with `start` and ends where `end` (given
/// the bytes and where `start` ends) says; matches are taken left to right, not overlapping.
fn replace_matches(
    text: &str,
    start: &str,
    with: &str,
    end: fn(&[u8], usize) -> Option<usize>,
) -> String {
    let b = text.as_bytes();
    let (mut out, mut copied, mut i) = (String::with_capacity(text.len()), 0, 0);
    while i < b.len() {
        match b[i..]
            .starts_with(start.as_bytes())
            .then(|| end(b, i + start.len()))
        {
            Some(Some(e)) => {
                out.push_str(&text[copied..i]);
                out.push_str(with);
                (i, copied) = (e, e);
            }
            _ => i += 1,
        }
    }
    out.push_str(&text[copied..]);
    out
}

/// The end of `[0-9]+` from `from`, if there is at least one digit.
fn digits(b: &[u8], from: usize) -> Option<usize> {
    let end = (from..).find(|&j| !b.get(j).is_some_and(u8::is_ascii_digit))?;
    (end > from).then_some(end)
}

/// Where `[0-9]+\.[0-9]+ s\b` from `i` ends, if it matches there.
fn seconds_end(b: &[u8], i: usize) -> Option<usize> {
    let i = digits(b, i)?;
    let i = digits(b, (b.get(i) == Some(&b'.')).then_some(i + 1)?)?;
    let word = |j: usize| {
        b.get(j)
            .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
    };
    (b.get(i..i + 2) == Some(b" s") && !word(i + 2)).then_some(i + 2)
}

/// Where `[0-9]+(\.[0-9]+)? m?s<` from `i` ends (after the `<`), if it matches there.
fn cell_end(b: &[u8], i: usize) -> Option<usize> {
    let mut i = digits(b, i)?;
    if b.get(i) == Some(&b'.') {
        i = digits(b, i + 1)?;
    }
    if b.get(i) != Some(&b' ') {
        return None;
    }
    i += 1 + usize::from(b.get(i + 1) == Some(&b'm'));
    (b.get(i) == Some(&b's') && b.get(i + 1) == Some(&b'<')).then_some(i + 2)
}

/// The digest of a run's directory: each file's SHA-256 and `./path` as `sha256sum` lists
/// them, in byte order of the path, the list hashed.
fn digest(dir: &Path) -> String {
    let mut list = String::new();
    for (name, bytes) in files(dir).into_iter().filter(|(n, _)| !n.ends_with('/')) {
        list.push_str(&format!("{:x}  ./{name}\n", Sha256::digest(&bytes)));
    }
    format!("{:x}", Sha256::digest(list.as_bytes()))
}

fn run(scratch: &Scratch, spec: &str) -> String {
    let dir = scratch.join(spec);
    std::fs::create_dir_all(&dir).unwrap();
    let (json, review) = (dir.join("results.json"), dir.join("review"));
    let run = cycloid_here(&[
        "check",
        &format!("specs/{spec}.yaml"),
        "--json",
        json.to_str().unwrap(),
        "--report",
        review.to_str().unwrap(),
    ]);
    let prefix = format!("{}/", dir.display());
    let stdout = format!("{}exit {}\n", run.stdout, run.code());
    std::fs::write(dir.join("stdout"), mask_times(&stdout.replace(&prefix, ""))).unwrap();
    for (name, bytes) in files(&review) {
        if name.ends_with(".html") {
            let text = String::from_utf8(bytes).unwrap().replace(&prefix, "");
            std::fs::write(review.join(name), mask_times(&text)).unwrap();
        }
    }
    digest(&dir)
}

#[test]
fn the_shipped_specs_outputs_are_those_recorded_before_the_change() {
    let scratch = Scratch::new("same-outputs");
    let moved: Vec<String> = RECORDED
        .iter()
        .filter_map(|&(spec, recorded)| {
            let now = run(&scratch, spec);
            (now != recorded).then(|| format!("{spec}: recorded {recorded}, now {now}"))
        })
        .collect();
    assert!(
        moved.is_empty(),
        "outputs differ from the recording (run tools/same-outputs.sh with the build before \
         the change to see which bytes):\n{}",
        moved.join("\n")
    );
}

/// The mask catches the ladder's cells and nothing else that looks like them.
#[test]
fn only_wall_clock_cells_are_masked() {
    assert_eq!(
        mask_times("<td>0.4 ms</td><td>12 s</td><td>3.25 s<x>0.4ms<"),
        "<td><time></td><td><time></td><td><time><x>0.4ms<"
    );
    assert_eq!(mask_times(">1.5 mm<>s<> ms<"), ">1.5 mm<>s<> ms<");
    assert_eq!(
        mask_times("13 rungs in 0.86 s; in 12.5 s. in 3 s, in 1.5 sec, in 0.2 s_"),
        "13 rungs in <time> s; in <time> s. in 3 s, in 1.5 sec, in 0.2 s_"
    );
}
