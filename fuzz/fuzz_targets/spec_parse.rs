//! Fuzz the spec parser: any UTF-8 text either parses into a validated spec or gives an error
//! located as `file:line:column`; a parsed spec also passes through the plan that runs before
//! any computation (`report::explain`; the coverage of limits and goldens, `spec::coverage`, is
//! part of the parse). Never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    match cycloid::spec::parse("fuzz.yaml", text) {
        Ok(spec) => {
            let _ = cycloid::report::explain::explain(&spec, Default::default(), false);
        }
        Err(e) => {
            let rendered = e.to_string();
            assert!(e.location.is_some(), "error without a location: {rendered}");
            assert!(rendered.starts_with("fuzz.yaml:"), "{rendered}");
        }
    }
});
