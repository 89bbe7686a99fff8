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
/// the centripetal force of `reducer-at-speed` moved by up to 3e-6 relative).
#[rustfmt::skip]
const RECORDED: &[(&str, &str)] = &[
    ("reducer", "b83200f73b963e440add1c7c4fe5321eb51c234becdc00697491cea0d29ee2ea"),
    ("reducer-loaded", "22d04db65affcf44901d8a046a9521f1fa38f6aaf7b716173db0c35698be5284"),
    ("reducer-two-discs", "33400b554d3a0b11d864e6b0babe4f8ae75b7db38ee763c2df503730c08340d6"),
    ("reducer-duty-cycle", "afeced971b12319ed4a228e015168268d15d27aeb2f6efe0b1eba7b0129fe651"),
    ("reducer-torsion", "ccabf8a050d49ef1910a7b2eb074e80f3767ab1c89059e531c0373de0714bb95"),
    ("reducer-efficiency", "2ca2cf37ebbaf6896a9daafff084f4bc7054129d6f60633a218ffa3e48ab472b"),
    ("reducer-strength", "5d821eeee325bd68696967c95c5a50e04c95fc731a4a4aaa168c43f147a974b4"),
    ("reducer-at-speed", "ef08ea7b507318022125be748f386748fa3b27af56e9bbdfdccd4f8ad9c39167"),
    ("reducer-misaligned", "4fe5f0c364e123ce78b289e342b175525298517b19e77ac5480a23b33b479ede"),
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
