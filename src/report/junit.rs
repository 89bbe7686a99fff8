//! JUnit XML for CI servers: one test case per check and per golden curve, grouped in one test
//! suite per spec. A failed check is a `<failure>` whose message carries the value, the limit
//! and how far outside it lies; an invalid spec or a failed computation is one `<error>` case.

use crate::engine::verdict::{Check, CheckKind};
use crate::numeric::{number, with_unit};

/// Escape text for XML attributes and character data.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // XML 1.0 forbids most control characters, even escaped.
            c if (c as u32) < 0x20 && !matches!(c, '\t' | '\n' | '\r') => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// One line saying what the check found.
pub fn message(c: &Check) -> String {
    let op = c.bound.symbol();
    let beyond = crate::engine::limit::beyond(c.value, c.limit, c.bound);
    match c.kind {
        CheckKind::Limit => {
            // As the terminal reads it: a failure rate in percent (`table::shown_in`).
            let (scale, unit) = super::table::shown_in(c);
            let verdict = if c.passed {
                format!("{} inside", with_unit(number(-beyond * scale), unit))
            } else {
                format!("{} outside", with_unit(number(beyond * scale), unit))
            };
            format!(
                "value {}, limit {op} {}: {verdict}; {}",
                super::table::value(c),
                with_unit(number(c.limit * scale), unit),
                super::table::evidence(&c.at)
            )
        }
        CheckKind::Golden => format!(
            "deviation {} {} tolerance band {}{}; {}",
            with_unit(number(c.value), c.unit),
            if c.passed { "within" } else { "outside" },
            with_unit(number(c.limit), c.unit),
            // The band's multiple, to four significant digits ("2.5e-7× the band", not
            // "0.000×"); none for a zero band.
            if c.limit > 0.0 {
                format!(" ({}× the band)", crate::numeric::number(c.value / c.limit))
            } else {
                String::new()
            },
            super::table::evidence(&c.at)
        ),
    }
}

fn classname(suite: &str, c: &Check) -> String {
    let kind = match c.kind {
        CheckKind::Limit => "limits",
        CheckKind::Golden => "golden",
    };
    format!("cycloid.{suite}.{}.{kind}", c.scene())
}

/// The document for a finished run.
pub fn document(spec_name: &str, spec_path: &str, checks: &[Check]) -> String {
    let failures = checks.iter().filter(|c| !c.passed).count();
    let mut cases = format!(
        "    <properties>\n      <property name=\"spec\" value=\"{}\"/>\n      \
         <property name=\"tool_version\" value=\"{}\"/>\n    </properties>\n",
        escape(spec_path),
        env!("CARGO_PKG_VERSION")
    );
    for c in checks {
        let text = escape(&message(c));
        cases += &format!(
            "    <testcase classname=\"{}\" name=\"{}\" time=\"0\">\n",
            escape(&classname(spec_name, c)),
            escape(c.name())
        );
        if c.passed {
            cases += &format!("      <system-out>{text}</system-out>\n");
        } else {
            let kind = match c.kind {
                CheckKind::Limit => "limit",
                CheckKind::Golden => "golden",
            };
            cases += &format!(
                "      <failure message=\"{text}\" type=\"{kind}\">{}: {text}</failure>\n",
                escape(&c.id)
            );
        }
        cases += "    </testcase>\n";
    }
    suite(spec_name, checks.len(), failures, 0, &cases)
}

/// The document for a run that stopped on an error (exit 2): one test case in error.
pub fn error_document(spec_path: &str, error: &str) -> String {
    let (path, text) = (escape(spec_path), escape(error));
    let case = format!(
        "    <testcase classname=\"cycloid\" name=\"check {path}\" time=\"0\">\n      \
         <error message=\"{text}\" type=\"invalid\">{text}</error>\n    </testcase>\n"
    );
    suite(spec_path, 1, 0, 1, &case)
}

/// The XML document of one test suite, `name`, of `tests` cases (`failures` failed, `errors`
/// in error) around `cases`, its properties and test cases.
fn suite(name: &str, tests: usize, failures: usize, errors: usize, cases: &str) -> String {
    let counts = format!("tests=\"{tests}\" failures=\"{failures}\" errors=\"{errors}\"");
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"cycloid\" {counts}>\n  \
         <testsuite name=\"{}\" {counts} skipped=\"0\" time=\"0\">\n{cases}  </testsuite>\n\
         </testsuites>\n",
        escape(name)
    )
}
