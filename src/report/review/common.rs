//! The building blocks every section of the design review (and the tolerance study's review)
//! shares: a section with its anchor and heading, a figure, a table, a verdict's class, a
//! numbered anchor or file name from a name.

use crate::model::results::SceneResult;
use crate::model::Scene;
use crate::spec::Spec;
use maud::{html, Markup};

/// A section of the page: its anchor, its heading (in the table of contents too) and body.
pub(super) struct Section {
    pub(super) id: String,
    pub(super) heading: Markup,
    pub(super) body: Markup,
}

impl Section {
    pub(super) fn new(id: impl Into<String>, heading: Markup, body: Markup) -> Section {
        let id = id.into();
        Section { id, heading, body }
    }
}

pub(super) fn figure(file: &str, title: &str, caption: &str) -> Markup {
    html! {
        figure {
            img src=(file) alt=(title);
            figcaption { b { (title) } ". " (caption) }
        }
    }
}

/// A table that scrolls sideways instead of running off a narrow window.
pub(super) fn scrolling(table: Markup) -> Markup {
    html! { div.scroll { (table) } }
}

/// A number with a true minus sign.
pub(super) fn signed(text: String) -> String {
    text.replace('-', "−")
}

/// A table (in a `scrolling` box) with one header row of `head`'s cells above `rows`.
pub(super) fn data_table(head: Markup, rows: Markup) -> Markup {
    scrolling(html! { table { thead { tr { (head) } } tbody { (rows) } } })
}

pub(super) fn verdict(passed: bool) -> &'static str {
    if passed {
        "pass"
    } else {
        "fail"
    }
}

/// The anchor or file-name start of the `k`th (from 0) `kind` named `name`: "scene-1-rated",
/// numbered from 1, of the name its ASCII letters, digits, `-` and `_`, anything else `_`. The
/// name alone is not unique (`a b` and `a_b` give the same), so the number is always there.
pub(super) fn numbered(kind: &str, k: usize, name: &str) -> String {
    let kept = |c: char| c.is_ascii_alphanumeric() || c == '-' || c == '_';
    format!("{kind}-{}-{}", k + 1, name.replace(|c: char| !kept(c), "_"))
}

/// The scenes whose result has what `pick` takes from it (a duty cycle, efficiency curves):
/// (index, scene, what it took), in the spec's order.
pub(super) fn scenes_with<'a, T>(
    spec: &'a Spec,
    results: &'a [SceneResult],
    pick: impl Fn(&'a SceneResult) -> Option<T>,
) -> Vec<(usize, &'a Scene, T)> {
    let each = spec.scenes.iter().zip(results).enumerate();
    each.filter_map(|(k, (s, r))| Some((k, s, pick(r)?)))
        .collect()
}
