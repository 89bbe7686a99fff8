//! A spec's scenes by name, for the sections that name one and for messages.

use crate::error::{Error, Result};
use crate::model::Scene;

/// The index of the scene named `name`; else an error at `key` that lists the scenes.
pub fn scene_index(scenes: &[Scene], name: &str, key: &str) -> Result<usize> {
    scenes.iter().position(|s| s.name == name).ok_or_else(|| {
        Error::invalid(
            key,
            format!("no scene named `{name}`; scenes: {}", scene_names(scenes)),
        )
    })
}

/// Refuse the first scene that asks for the first-order geometry, at its key: `why` says what
/// needs the exact one ("…, but {why}").
pub fn refuse_first_order(scenes: &[Scene], why: &str) -> Result<()> {
    match (scenes.iter()).position(|s| s.geometry == crate::model::GeometryMode::FirstOrder) {
        Some(i) => Err(Error::invalid(
            format!("scenes[{i}].geometry"),
            format!(
                "scene `{}` asks for the first-order geometry, but {why}",
                scenes[i].name
            ),
        )),
        None => Ok(()),
    }
}

/// The scenes' names, comma-separated, for messages about an unknown scene.
pub fn scene_names(scenes: &[Scene]) -> String {
    scenes
        .iter()
        .map(|s| s.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Refuse scene `index` at `key` when it runs a duty cycle: `what` (a golden curve, a study,
/// the accuracy ladder, a tolerance study) reads one run of a scene over its crank angles, and
/// a duty-cycle scene runs one per bin.
pub(crate) fn refuse_duty(scenes: &[Scene], index: usize, key: &str, what: &str) -> Result<()> {
    let scene = &scenes[index];
    match &scene.duty_cycle {
        Some(bins) => Err(Error::invalid(
            key,
            format!(
                "scene `{}` runs a duty cycle ({} bins, one run each): {what} needs one run of \
                 a scene; name a scene with its own `output_torque_nm`",
                scene.name,
                bins.len()
            ),
        )),
        None => Ok(()),
    }
}
