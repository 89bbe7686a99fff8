//! `accuracy`: one scene on a ladder of settings, each rung's error against the finest.

use crate::engine::accuracy::{self, Event, Ladder, Options};
use crate::error::Result;
use crate::spec::Spec;

/// Run scene `scene` of `spec` on the ladder `options` describes; `on_event` hears of the
/// layout first and of each rung as it finishes (the finest first: it takes longest).
///
/// ```
/// use cycloid::model::accuracy::Options;
/// let spec = cycloid::spec::load("specs/reducer.yaml")?;
/// let options = Options { finest: 48, ..Options::default() };
/// let mut rungs = 0;
/// let ladder = cycloid::accuracy(&spec, 0, &options, &mut |_| rungs += 1)?;
/// // The layout, then one event per rung; the reference is the finest steps rung.
/// assert_eq!(rungs, ladder.rungs.len() + 1);
/// assert_eq!(ladder.reference().steps_per_period, 48.0);
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn accuracy(
    spec: &Spec,
    scene: usize,
    options: &Options,
    on_event: &mut dyn FnMut(Event),
) -> Result<Ladder> {
    accuracy::run(spec, scene, options, on_event).map_err(|e| spec.locate(e))
}
