//! The review's headline results of every scene ([`engine::summary`](crate::engine::summary)).

use super::common::{data_table, Section};
use crate::engine::summary::SceneSummary;
use crate::report::table;
use maud::html;

/// The headline results of every scene, from its `summaries` as the run marked them
/// ([`engine::summary::marked`](crate::engine::summary::marked)).
/// A value beyond its plausible band (`engine::plausibility`) is marked in its row, not failed.
pub(super) fn section(summaries: &[SceneSummary]) -> Section {
    let body = html! {
        p.note { "What each scene computed, at a glance: the extremes of its curves and where \
                  they occur." }
        (data_table(
            html! { th { "scene" } th { "result" } th { "value" } th { "where" } },
            html! {
                @for s in summaries {
                    @if s.headlines.is_empty() {
                        tr { td { code { (s.scene) } } td colspan="3" {
                            "no headline results (the scene computes none of them)" } }
                    }
                    @let rows = table::summary_rows(s, summaries);
                    @for (k, row) in rows.iter().enumerate() {
                        tr.implausible[row.marked] {
                            @if k == 0 {
                                td rowspan=(rows.len()) { code { (s.scene) } }
                            }
                            td { (row.label) }
                            td.num { (row.value) }
                            td { (row.at) }
                        }
                    }
                }
            },
        ))
    };
    Section::new("summary", html! { "Headline results" }, body)
}
