//! `accuracy`: one scene on a ladder of settings, each rung's error against the finest.

use crate::engine::accuracy::{self, Event, Ladder, Options};
use crate::error::Result;
use crate::spec::Spec;

/// Run scene `scene` of `spec` on the ladder `options` describes; `on_event` hears of the
/// layout first and of each rung as it finishes (the finest first: it takes longest).
pub fn accuracy(
    spec: &Spec,
    scene: usize,
    options: &Options,
    on_event: &mut dyn FnMut(Event),
) -> Result<Ladder> {
    accuracy::run(spec, scene, options, on_event).map_err(|e| spec.locate(e))
}
