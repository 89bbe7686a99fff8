//! The review's headline results of every scene ([`engine::summary`](crate::engine::summary)).

use super::common::{data_table, section, Section};
use crate::engine::summary::summarise;
use crate::model::results::SceneResult;
use crate::report::table;
use maud::html;

/// The headline results of every scene ([`engine::summary`](crate::engine::summary)).
pub(super) fn summary_section(results: &[SceneResult]) -> Section {
    let summaries = summarise(results);
    let body = html! {
        p.note { "What each scene computed, at a glance: the extremes of its curves and where \
                  they occur." }
        (data_table(
            html! { th { "scene" } th { "result" } th { "value" } th { "where" } },
            html! {
                @for s in &summaries {
                    @if s.headlines.is_empty() {
                        tr { td { code { (s.scene) } } td colspan="3" {
                            "no headline results (the scene computes none of them)" } }
                    }
                    @for (k, h) in s.headlines.iter().enumerate() {
                        tr {
                            @if k == 0 {
                                td rowspan=(s.headlines.len()) { code { (s.scene) } }
                            }
                            td { (h.quantity.label) }
                            td.num { (table::headline_value(h)) }
                            td { (table::headline_at(h, s, &summaries)) }
                        }
                    }
                }
            },
        ))
    };
    section("summary", html! { "Headline results" }, body)
}
