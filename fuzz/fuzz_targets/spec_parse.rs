//! Fuzz the spec parser with the property of `spec_parse_property.rs`: any UTF-8 text parses
//! into a validated spec whose plan is written, or gives an error located as
//! `file:line:column`. Never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

include!("spec_parse_property.rs");

fuzz_target!(|text: &str| {
    spec_parse_property(text);
});
