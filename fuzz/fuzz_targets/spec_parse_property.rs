// The property the spec parser is fuzzed for, in one file that both the fuzz target
// (`spec_parse.rs`, on nightly) and its stable stand-in (`tests/it/fuzz_corpus.rs`, in CI)
// include: a change of the library's calls breaks the test build, so the fuzz target, which no
// CI step builds, cannot fall behind unseen.

/// Any text either parses into a validated spec (which runs the coverage checks of limits and
/// goldens, `spec::coverage`), whose plan `report::explain` then writes, or gives an error
/// rendered as `fuzz.yaml:LINE:COLUMN: ...` with LINE and COLUMN from 1. Returns whether it
/// parsed; an error without its location panics, as any other failure of the property.
fn spec_parse_property(text: &str) -> bool {
    match cycloid::spec::parse("fuzz.yaml", text) {
        Ok(spec) => {
            let _ = cycloid::report::explain::explain(&spec, Default::default(), false);
            true
        }
        Err(e) => {
            let rendered = e.to_string();
            let located = rendered
                .strip_prefix("fuzz.yaml:")
                .and_then(|r| r.split_once(':'))
                .and_then(|(line, r)| Some((line, r.split_once(": ")?.0)))
                .is_some_and(|(line, column)| {
                    line.parse::<usize>().is_ok_and(|l| l >= 1)
                        && column.parse::<usize>().is_ok_and(|c| c >= 1)
                });
            assert!(
                located && e.location.is_some(),
                "error without file:line:column: {rendered}"
            );
            false
        }
    }
}
