//! The review's crank-bearing life ([`engine::bearing_life`](crate::engine::bearing_life)): the rating life of every scene
//! that rated it, and why a scene could not.

use super::common::{data_table, Section};
use crate::engine::scene::{self, Note};
use crate::model::results::SceneResult;
use crate::numeric::number;
use crate::report::explain;
use crate::report::place::or_unbounded;
use crate::spec::Spec;
use maud::html;

/// The crank bearing's rating life of every scene that rated it.
pub(super) fn section(spec: &Spec, results: &[SceneResult]) -> Option<Section> {
    let rating = spec.design.crank_bearing?;
    // (scene, disc with several discs, its life): with several discs each disc has a bearing.
    let rated: Vec<_> = spec
        .scenes
        .iter()
        .zip(results)
        .flat_map(|(s, r)| {
            let named = r.names_discs();
            let each = r.discs.iter().enumerate();
            each.filter_map(move |(k, d)| Some((s, named.then_some(k), d.bearing_life?)))
        })
        .collect();
    // The notes of a life not rated, by kind: a scene's name may say "crank-bearing" too.
    let notes: Vec<String> = (scene::notes(spec).iter())
        .filter(|n| {
            matches!(
                n,
                Note::LifeNotRated { .. } | Note::LifeHoursNotRated { .. }
            )
        })
        .map(explain::note)
        .collect();
    if rated.is_empty() && notes.is_empty() {
        return None;
    }
    let body = html! {
        p.note {
            "ISO 281 with a varying load: P = (mean of Fb^p over whole loaded periods)^(1/p), \
             L10h = (C/P)^p · 10⁶ / (60 · n · (1 + 1/nc)) at the crank's speed relative to the \
             disc. C = " (number(rating.dynamic_load_rating_n)) " N, p = "
            (number(rating.life_exponent)) "."
        }
        (data_table(
            html! {
                th { "scene" } th { "input speed (rpm)" } th { "equivalent load P (N)" }
                th { "rating life L10h (h)" }
            },
            html! { @for (s, k, b) in &rated { tr {
                td { code { (s.name) } @if let Some(k) = k { " disc " (k) } }
                td { (s.input_speed_rpm.map_or("—".to_string(), number)) }
                td { (number(b.equivalent_load_n)) }
                td { (b.life_h.map_or("not rated".to_string(), |h| or_unbounded(h, number))) }
            } } },
        ))
        @for n in &notes { p.note { (n) } }
    };
    Some(Section::new(
        "crank-bearing-life",
        html! { "Crank-bearing life" },
        body,
    ))
}
