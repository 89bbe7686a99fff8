//! The spec parser on hostile input, on the stable toolchain: the committed fuzz corpus
//! (fuzz/corpus/spec_parse/, the seeds of `cargo +nightly fuzz run spec_parse`) and a few
//! thousand deterministic mutations of the shipped specs (byte flips, truncations, duplicated,
//! dropped and re-indented lines, swapped values, extreme and non-finite numbers, spliced
//! lines of another spec). Every input either parses, and then its plan is written
//! (`report::explain`), or gives an error rendered as `file:line:column: ...` — never a panic:
//! the fuzz target's own property (`fuzz/fuzz_targets/spec_parse_property.rs`), included.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

/// Mutations generated per seed file (the seeds are ~45 files: ~4,500 inputs).
const PER_SEED: usize = 100;

/// Deterministic xorshift64* generator: the same inputs on every run and machine.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Characters that matter to YAML or to the spec's keys and numbers.
const CHARS: &[char] = &[
    ':', '-', ' ', '\t', '\n', '\r', '[', ']', '{', '}', ',', '#', '"', '\'', '&', '*', '!', '|',
    '>', '%', '@', '`', '?', '0', '1', '9', '.', 'e', 'E', '+', '_', 'x', 'é', '∞', '\u{0}',
    '\u{feff}', '\u{2028}',
];

/// Values that stress the numbers of a spec: extremes, non-finite, wrong types, YAML oddities.
const VALUES: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1e308",
    "-1e308",
    "1e309",
    "4.9e-324",
    "1e-320",
    ".nan",
    ".NaN",
    ".inf",
    "-.inf",
    "NaN",
    "inf",
    "9223372036854775807",
    "-9223372036854775808",
    "18446744073709551616",
    "99999999999999999999999999",
    "0x7fffffff",
    "0o17",
    "1_000",
    "~",
    "null",
    "true",
    "''",
    "\"\"",
    "[]",
    "{}",
    "[1, 2]",
    "{a: 1}",
    "*anchor",
    "&anchor 1",
    "!!str 3",
    "!!binary aGVsbG8=",
    "|\n  text",
    "1e5",
    "3.0e-9",
    "1e7",
    "10000001",
    "2147483648",
];

fn mutate(text: &str, other: &str, rng: &mut Rng) -> String {
    let chars: Vec<char> = text.chars().collect();
    let lines: Vec<&str> = text.lines().collect();
    let line = |rng: &mut Rng| rng.below(lines.len());
    let join = |ls: Vec<String>| ls.join("\n") + "\n";
    let owned = || lines.iter().map(|l| l.to_string()).collect::<Vec<_>>();
    match rng.below(9) {
        // Flip one character.
        0 if !chars.is_empty() => {
            let mut c = chars.clone();
            let at = rng.below(c.len());
            c[at] = *rng.pick(CHARS);
            c.into_iter().collect()
        }
        // Insert one character.
        1 => {
            let mut c = chars.clone();
            let at = rng.below(c.len() + 1);
            c.insert(at, *rng.pick(CHARS));
            c.into_iter().collect()
        }
        // Truncate.
        2 => chars[..rng.below(chars.len() + 1)].iter().collect(),
        // Duplicate a line (a duplicate key, or a second list item).
        3 if !lines.is_empty() => {
            let mut ls = owned();
            let at = line(rng);
            ls.insert(at, ls[at].clone());
            join(ls)
        }
        // Drop a line (a missing key).
        4 if !lines.is_empty() => {
            let mut ls = owned();
            ls.remove(line(rng));
            join(ls)
        }
        // Swap the values of two `key: value` lines.
        5 => {
            let mut ls = owned();
            let keyed: Vec<usize> = (0..ls.len()).filter(|&i| ls[i].contains(": ")).collect();
            if keyed.len() >= 2 {
                let (a, b) = (*rng.pick(&keyed), *rng.pick(&keyed));
                let split = |l: &str| {
                    let (k, v) = l.split_once(": ").unwrap();
                    (k.to_string(), v.to_string())
                };
                let ((ka, va), (kb, vb)) = (split(&ls[a]), split(&ls[b]));
                ls[a] = format!("{ka}: {vb}");
                ls[b] = format!("{kb}: {va}");
            }
            join(ls)
        }
        // Replace a value (or a number inside a flow mapping) with an extreme one.
        6 => {
            let mut ls = owned();
            let keyed: Vec<usize> = (0..ls.len()).filter(|&i| ls[i].contains(": ")).collect();
            if !keyed.is_empty() {
                let a = *rng.pick(&keyed);
                let value = *rng.pick(VALUES);
                let l = ls[a].clone();
                let cut = match rng.below(2) {
                    0 => l.find(": "),
                    _ => l.rfind(": "),
                }
                .unwrap();
                let rest = &l[cut + 2..];
                let end = rest.find([',', '}', ' ', '#']).unwrap_or(rest.len());
                ls[a] = format!("{}: {value}{}", &l[..cut], &rest[end..]);
            }
            join(ls)
        }
        // Re-indent a line by ±2 spaces.
        7 if !lines.is_empty() => {
            let mut ls = owned();
            let at = line(rng);
            ls[at] = match ls[at].strip_prefix("  ") {
                Some(rest) if rng.below(2) == 0 => rest.to_string(),
                _ => format!("  {}", ls[at]),
            };
            join(ls)
        }
        // Splice a line of another spec in.
        _ => {
            let mut ls = owned();
            let others: Vec<&str> = other.lines().collect();
            if !others.is_empty() {
                let at = rng.below(ls.len() + 1);
                ls.insert(at, rng.pick(&others).to_string());
            }
            join(ls)
        }
    }
}

include!("../../fuzz/fuzz_targets/spec_parse_property.rs");

/// One input through the fuzz target's property (`spec_parse_property`): Ok(whether it
/// parsed), or Err with the message of the panic, an unlocated error's among them.
fn exercise(text: &str) -> Result<bool, String> {
    let outcome = catch_unwind(AssertUnwindSafe(|| spec_parse_property(text)));
    outcome.map_err(|panic| {
        let message = panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        format!("panic: {message}")
    })
}

fn corpus() -> Vec<(String, String)> {
    let dir = Path::new("fuzz/corpus/spec_parse");
    let mut files: Vec<(String, String)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap();
            // libFuzzer's `&str` target only sees valid UTF-8; so do we.
            let text = String::from_utf8_lossy(&bytes).into_owned();
            (p.display().to_string(), text)
        })
        .collect();
    files.sort();
    files
}

#[test]
fn the_corpus_never_panics_and_errors_are_located() {
    let files = corpus();
    assert!(files.len() >= 30, "the seed corpus is committed");
    let mut failures = Vec::new();
    for (name, text) in &files {
        if let Err(e) = exercise(text) {
            failures.push(format!("{name}: {e}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn mutations_of_the_specs_never_panic_and_errors_are_located() {
    let files = corpus();
    let seeds: Vec<&(String, String)> = files.iter().filter(|(_, t)| t.len() > 50).collect();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut parsed, mut refused, mut failures) = (0, 0, Vec::new());
    for (i, (name, text)) in seeds.iter().enumerate() {
        let other = &seeds[(i + 1) % seeds.len()].1;
        for k in 0..PER_SEED {
            // One to three mutations stacked.
            let mut input = mutate(text, other, &mut rng);
            for _ in 0..rng.below(3) {
                input = mutate(&input, other, &mut rng);
            }
            match exercise(&input) {
                Ok(true) => parsed += 1,
                Ok(false) => refused += 1,
                Err(e) => failures.push(format!("{name} mutation {k}: {e}\n--- input\n{input}")),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures, first:\n{}",
        failures.len(),
        failures[0]
    );
    // The mutations must exercise both paths.
    assert!(
        parsed > 100 && refused > 1000,
        "parsed {parsed}, refused {refused}"
    );
}
