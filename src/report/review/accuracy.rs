//! The review's accuracy ladder: one row per rung, its errors against the reference and its
//! time, the cheapest rung that meets every tolerance highlighted; observed orders below.

use super::common::{data_table, Section};
use crate::engine::accuracy::{self as acc, Ladder, Variation};
use crate::numeric::number;
use crate::report::accuracy::{self as text, seconds_text, skipped_text};
use maud::html;

/// The accuracy ladder as a table: one row per rung, errors against the reference, times, the
/// cheapest rung that meets every tolerance highlighted; observed orders and notes below.
pub(super) fn section(ladder: &Ladder) -> Section {
    let l = &ladder.layout;
    let missing = text::not_computed(l);
    let settings_rungs = text::has_settings_rungs(ladder);
    let other_law = ladder
        .rungs
        .iter()
        .any(|r| r.variation == Variation::ContactLaw);
    let orders: Vec<_> = l
        .quantities
        .iter()
        .map(|&q| (q, ladder.orders(q)))
        .filter(|(_, o)| !o.is_empty())
        .collect();
    let body = html! {
        p.note {
            "Scene " code { (l.scene) } " over crank " (number(l.from_deg)) "° to "
            (number(l.to_deg)) "° (" (text::steps_text(l.periods)) " mesh periods) on a ladder of \
            settings. The reference is the finest rung: " (l.finest) " steps per mesh period, "
            (l.geometry.name()) " geometry, " (l.law.name()) ", solver rel_tol 1e-11. Each error \
            is |rung − reference| in the quantity's unit; the TE curve's is the largest difference \
            between the reference and the rung's curve interpolated linearly between its crank \
            angles. Times are wall-clock measurements of the rung's run (the fastest of up to "
            (acc::REPEATS) " runs for runs under " (acc::REPEAT_BELOW_S * 1000.0) " ms)."
            @if !missing.is_empty() { " Not computed by this scene (no column): "
                (missing.join(", ")) "." }
            @if settings_rungs {
                " The rungs that change one setting run at " (ladder.settings_steps)
                " steps per mesh period"
                @if ladder.settings_steps == l.finest {
                    " (the finest, so their errors are the setting's own effect)."
                } @else { "; their errors include that resolution's, shown by its steps rung." }
            }
            @if other_law { " Another contact law is another model: its difference from the \
                reference is a model difference, not a discretisation error, and it is never the \
                cheapest." }
            @for &k in &ladder.skipped { " Skipped: " (skipped_text(k)) "." }
        }
        p {
            @match ladder.cheapest {
                Some(i) if ladder.rungs[i].is_reference => "Only the reference meets every \
                    tolerance; its own error is not measured (no finer rung).",
                Some(i) => { "Cheapest rung meeting every tolerance: " b { (ladder.rungs[i].label) }
                    " (" (text::steps_text(ladder.rungs[i].steps_per_period)) " steps per mesh period, "
                    (ladder.rungs[i].angles) " crank angles): the least work (fewest crank \
                    angles, then the coarsest settings) among the rungs that meet them; the times \
                    are information, not the choice." },
                None => "No rung meets every tolerance.",
            }
            @if let Some(i) = ladder.cheapest_slices {
                " The face-slices rungs run the scene's own " (l.angles_own) " crank angles with \
                the face cut into more and more slices and compare with the finest. Fewest \
                slices meeting every tolerance: " b { (ladder.rungs[i].label) } "."
            }
        }
        (data_table(
            html! {
                th { "rung" } th { "steps per mesh period" } th { "crank angles" }
                th { "geometry" } th { "contact law" } th { "solver rel_tol" } th { "time" }
                @for q in &l.quantities {
                    th { (q.label()) @if !q.unit().is_empty() { " (" (q.unit()) ")" }
                        br; span.note { "tol " (text::short(q.tolerance(&l.tolerances))) } }
                }
                th { "tolerances" }
            },
            html! {
                @for (i, r) in ladder.rungs.iter().enumerate() {
                    @let cheapest = ladder.cheapest == Some(i) || ladder.cheapest_slices == Some(i);
                    @let (class, verdict) = text::verdict(r, &l.tolerances);
                    tr class=(if cheapest { "pass cheapest" } else { class }) {
                        td { (r.label) }
                        td.num { (text::steps_text(r.steps_per_period)) }
                        td.num { (r.angles) }
                        td { (r.geometry.name()) }
                        td { (r.law.name()) }
                        td.num { (format!("{:e}", r.rel_tol)) }
                        td.num { (seconds_text(r.seconds)) }
                        @for &q in &l.quantities {
                            @let over = !r.is_reference && !r.model_difference
                                && r.error(q).is_some_and(|e| !q.within(e, &l.tolerances));
                            td.num.over[over] { (text::error_cell(r, q)) }
                        }
                        td.verdict { (verdict) @if cheapest { " — " b { "cheapest" } } }
                    }
                }
            },
        ))
        @if let Some((first, _)) = orders.first() {
            p.note { "Observed order of convergence log2(e(N)/e(2N)) of the steps rungs (— where \
                      an error is at round-off), and the least-squares fit over N = 12 … \
                      finest/4." }
            (data_table(
                html! { th { "quantity" }
                    @for (n, _) in ladder.orders(*first) { th { (n) "→" (2 * n) } } th { "fit" } },
                html! {
                    @for (q, o) in &orders {
                        tr {
                            td { (q.label()) }
                            @for (_, p) in o { td.num { (text::order_text(*p)) } }
                            td.num { b { (text::order_text(ladder.fitted_order(*q))) } }
                        }
                    }
                },
            ))
        }
    };
    let heading = html! { "Accuracy ladder: what accuracy costs in time" };
    Section::new("accuracy", heading, body)
}
