//! JUnit XML: well-formed (parsed with quick-xml), one test case per check and golden curve,
//! failures carrying the value, the limit and how far outside; an invalid spec is one error.

use crate::common;
use quick_xml::events::Event;
use quick_xml::Reader;

struct Parsed {
    testcases: Vec<(String, String)>,
    failures: Vec<String>,
    errors: Vec<String>,
    root_attrs: Vec<(String, String)>,
}

/// Parse the whole document; panics on anything that is not well-formed XML.
fn parse(xml: &str) -> Parsed {
    let mut reader = Reader::from_str(xml);
    reader.config_mut().check_end_names = true;
    let mut out = Parsed {
        testcases: Vec::new(),
        failures: Vec::new(),
        errors: Vec::new(),
        root_attrs: Vec::new(),
    };
    loop {
        match reader.read_event().expect("well-formed XML") {
            Event::Start(e) | Event::Empty(e) => {
                let name = String::from_utf8(e.name().as_ref().to_vec()).unwrap();
                let attrs: Vec<(String, String)> = e
                    .attributes()
                    .map(|a| {
                        let a = a.expect("well-formed attribute");
                        (
                            String::from_utf8(a.key.as_ref().to_vec()).unwrap(),
                            a.unescape_value().expect("valid escapes").into_owned(),
                        )
                    })
                    .collect();
                let get = |k: &str| {
                    attrs
                        .iter()
                        .find(|(n, _)| n == k)
                        .map(|(_, v)| v.clone())
                        .unwrap_or_default()
                };
                match name.as_str() {
                    "testsuites" => out.root_attrs = attrs.clone(),
                    "testcase" => out.testcases.push((get("classname"), get("name"))),
                    "failure" => out.failures.push(get("message")),
                    "error" => out.errors.push(get("message")),
                    _ => {}
                }
            }
            Event::Eof => break,
            _ => {}
        }
    }
    out
}

fn check(spec: &str, junit: &std::path::Path) -> i32 {
    common::cycloid_here(&["check", spec, "--junit", junit.to_str().unwrap()]).code()
}

fn scratch(name: &str) -> common::Scratch {
    common::Scratch::new(&format!("junit-{name}"))
}

#[test]
fn a_failing_spec_gives_one_case_per_check_and_golden_with_the_numbers_in_the_failure() {
    let dir = scratch("failing");
    let path = dir.join("r.xml");
    assert_eq!(check("specs/paper-negative-start.yaml", &path), 1);
    let xml = std::fs::read_to_string(&path).unwrap();
    let doc = parse(&xml);
    // 1 limit + 7 golden curves.
    assert_eq!(doc.testcases.len(), 8, "{xml}");
    assert!(doc
        .root_attrs
        .contains(&("failures".to_string(), "1".to_string())));
    assert!(doc
        .testcases
        .iter()
        .any(|(c, n)| c.ends_with(".mesh.limits") && n == "min_clearance_mm"));
    assert_eq!(
        doc.testcases
            .iter()
            .filter(|(c, n)| c.contains(".golden") && n.starts_with("golden:"))
            .count(),
        7
    );
    assert_eq!(doc.failures.len(), 1);
    let m = &doc.failures[0];
    for part in [
        "value -0.02341 mm",
        "limit ≥ 0.01500 mm",
        "0.03841 mm outside",
        "roller 9",
    ] {
        assert!(m.contains(part), "{part} not in {m}");
    }
}

#[test]
fn golden_cases_state_the_deviation_and_the_band() {
    let dir = scratch("passing");
    let path = dir.join("r.xml");
    assert_eq!(check("specs/paper.yaml", &path), 0);
    let xml = std::fs::read_to_string(&path).unwrap();
    let doc = parse(&xml);
    // 1 limit + 7 goldens + 4 optimisation studies (their constraints).
    assert_eq!(doc.testcases.len(), 12);
    assert!(doc.failures.is_empty());
    assert!(xml.contains("within tolerance band"), "{xml}");
}

#[test]
fn an_invalid_spec_is_one_error_case() {
    let dir = scratch("invalid");
    let spec = dir.join("bad.yaml");
    let text = std::fs::read_to_string("specs/reducer.yaml")
        .unwrap()
        .replace("face_width_mm", "face_widht_mm");
    std::fs::write(&spec, text).unwrap();
    let path = dir.join("r.xml");
    assert_eq!(check(spec.to_str().unwrap(), &path), 2);
    let doc = parse(&std::fs::read_to_string(&path).unwrap());
    assert_eq!(doc.testcases.len(), 1);
    assert_eq!(doc.errors.len(), 1);
    assert!(doc.errors[0].contains("face_widht_mm"), "{}", doc.errors[0]);
}

/// A spec that does not load names files nobody knows yet (its goldens, its measured
/// points): its JUnit error case then replaces only a JUnit report of cycloid or nothing. A
/// points file given as `--junit` (issue 26: `check BROKEN.yaml --junit disc.csv` overwrote
/// it) is left byte for byte, the error says why; a report of an earlier run is replaced; a
/// spec that loads has its outputs checked against every file it names first, as before.
#[test]
fn a_spec_that_does_not_load_overwrites_no_input_with_its_junit_case() {
    let dir = scratch("unloaded");
    let spec = dir.join("bad.yaml");
    let text = std::fs::read_to_string("specs/reducer.yaml")
        .unwrap()
        .replace("face_width_mm", "face_widht_mm")
        + "measured_profile: {file: disc.csv, format: csv, harmonics: 0, fit: [shift_mm]}\n";
    std::fs::write(&spec, text).unwrap();
    let points = dir.join("disc.csv");
    std::fs::write(&points, "x_mm,y_mm\n1,2\n").unwrap();
    let args = [
        "check",
        spec.to_str().unwrap(),
        "--junit",
        points.to_str().unwrap(),
    ];
    let r = common::cycloid_here(&args);
    assert_eq!(r.code(), 2, "{r:?}");
    assert_eq!(
        std::fs::read_to_string(&points).unwrap(),
        "x_mm,y_mm\n1,2\n"
    );
    assert!(
        r.stderr
            .contains("disc.csv: not written: the spec did not load"),
        "{}",
        r.stderr
    );
    // An earlier report is replaced by the error case.
    let report = dir.join("r.xml");
    std::fs::write(
        &report,
        cycloid::report::junit::error_document("old.yaml", "old"),
    )
    .unwrap();
    assert_eq!(check(spec.to_str().unwrap(), &report), 2);
    let doc = std::fs::read_to_string(&report).unwrap();
    assert!(
        doc.contains("face_widht_mm") && !doc.contains("old.yaml"),
        "{doc}"
    );
}

#[test]
fn text_is_escaped() {
    let e = cycloid::report::junit::escape("a<b & \"c\" 'd' > \u{1}");
    assert_eq!(e, "a&lt;b &amp; &quot;c&quot; &apos;d&apos; &gt;  ");
    let doc = cycloid::report::junit::error_document("x<&>.yaml", "bad \"thing\" <here>");
    let parsed = parse(&doc);
    assert_eq!(parsed.errors, vec!["bad \"thing\" <here>".to_string()]);
}

/// The strength checks are test cases of the scene's limits; the failing static safety's
/// failure names its value, its bound and where it is governed (the largest bearing force
/// and its crank angle, recomputed from the results JSON by `strength::strength_places`).
#[test]
fn the_strength_checks_are_cases_and_a_failing_one_says_its_part_and_place() {
    let dir = scratch("strength");
    dir.write("spec.yaml", crate::strength::strength_failing());
    let out = common::cycloid(
        &dir.path,
        &["check", "spec.yaml", "--json", "r.json", "--junit", "r.xml"],
    );
    assert_eq!(out.code, Some(1), "{}{}", out.stdout, out.stderr);
    let parsed = parse(&dir.read("r.xml"));
    let results: serde_json::Value = serde_json::from_str(&dir.read("r.json")).unwrap();
    let places = crate::strength::strength_places(&results);
    let class = "cycloid.paper-table-1-strength.rated.limits".to_string();
    let cases: Vec<(String, String)> = (places.iter())
        .map(|(key, _, _)| (class.clone(), key.to_string()))
        .collect();
    assert_eq!(parsed.testcases, cases);
    let (_, s0, at) = &places[3];
    assert_eq!(parsed.failures.len(), 1, "{:?}", parsed.failures);
    let failure = &parsed.failures[0];
    assert!(
        failure.starts_with(&format!("value {s0}, limit ≥ 8.000: ")),
        "{failure}"
    );
    assert!(
        failure.ends_with(&format!(" outside; {at}")),
        "{failure}\n{at}"
    );
}
