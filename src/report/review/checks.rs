//! The review's verdicts: every check of a limit with its value and where.

use super::common::{data_table, verdict, Section};
use crate::engine::verdict::Check;
use crate::report::table;
use maud::html;

pub(super) fn section(checks: &[Check]) -> Section {
    let body = html! {
        p.note { "Failures first, the furthest outside its limit first." }
        (data_table(
            html! { th { "check" } th { "value" } th { "limit" } th { "verdict" } th { "where" } },
            html! {
                @for c in table::ordered(checks) {
                    tr class=(verdict(c.passed)) {
                        td { code { (c.id) } }
                        td.num { (table::value(c)) }
                        td.num { (table::limit(c)) }
                        td.verdict { (if c.passed { "pass" } else { "FAIL" }) }
                        td { (crate::report::table::evidence(&c.at)) }
                    }
                }
            },
        ))
    };
    Section::new("checks", html! { "Checks" }, body)
}
