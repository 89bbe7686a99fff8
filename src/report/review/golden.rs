//! The review's golden curves: each compared point by point with its reviewed reference.

use super::common::{data_table, verdict, Section};
use crate::engine::golden::GoldenResult;
use crate::numeric::number;
use crate::numeric::with_unit;
use maud::html;

pub(super) fn section(goldens: &[GoldenResult]) -> Option<Section> {
    if goldens.is_empty() {
        return None;
    }
    let body = html! {
        p.note { "Each curve compared point by point with its reviewed reference; the worst \
                  point is the one furthest outside (or least inside) its band abs + rel·|golden|." }
        (data_table(
            html! { th { "curve" } th { "golden file" } th { "worst |deviation|" }
                th { "band there" } th { "where" } th { "points" } th { "verdict" } },
            html! {
                @for g in goldens {
                    @let w = &g.comparison.worst;
                    tr class=(verdict(g.comparison.passed)) {
                        td { code { (g.golden.scene) "/" (g.golden.quantity.key) (g.golden.disc_suffix()) } }
                        td { code { (g.golden.path.display()) } }
                        td.num { (with_unit(number(w.deviation), g.golden.quantity.unit)) }
                        td.num { (with_unit(number(w.band), g.golden.quantity.unit)) }
                        td { (crate::report::golden::in_row(w)) }
                        td.num { (g.comparison.points) }
                        td.verdict { (if g.comparison.passed { "pass" } else { "FAIL" }) }
                    }
                }
            },
        ))
    };
    Some(Section::new("golden", html! { "Golden curves" }, body))
}
