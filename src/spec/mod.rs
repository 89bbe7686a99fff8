//! Spec loading: YAML text → `raw` (serde) → the validated model (engine units).
//!
//! Errors carry `file:line:column` and the key path. Syntax errors take their location from the
//! YAML parser (`yaml`); value and design-rule errors locate their key in the text (`locate`).

pub(crate) mod bearing_life;
pub(crate) mod bearing_push;
pub(crate) mod coverage;
pub(crate) mod deviations;
pub mod duty_cycle;
pub mod edit;
pub(crate) mod face;
pub(crate) mod friction;
pub(crate) mod inertia;
#[doc(hidden)]
pub mod locate;
pub(crate) mod mass;
pub(crate) mod measured;
pub(crate) mod paths;
pub(crate) mod periods;
pub(crate) mod raw;
pub mod relocate;
pub mod requirements;
pub(crate) mod requirements_raw;
#[doc(hidden)]
pub mod rules;
pub(crate) mod scenes;
pub(crate) mod strength;
pub(crate) mod tolerances;
pub(crate) mod validate;
mod validated;
mod values;
pub(crate) mod yaml;

use crate::error::Result;
pub use crate::model::scene::MAX_ROLLER_ANGLES;
pub use locate::{locate, locate_offset};
pub use paths::resolve;
pub use scenes::{refuse_first_order, scene_index, scene_names};
pub use validate::{crank_angles, MAX_CRANK_DEG};
pub use validated::{Accuracy, Spec};

/// Read and validate a spec file.
pub fn load(path: &str) -> Result<Spec> {
    let text = crate::files::read_text(
        std::path::Path::new(path),
        "spec",
        crate::files::MAX_INPUT_BYTES,
    )?;
    parse(path, &text)
}

/// Parse and validate spec text; `path` is used in messages only.
pub fn parse(path: &str, text: &str) -> Result<Spec> {
    let raw = yaml::parse_raw(path, text)?;
    let spec = validate::build(path, text, raw).map_err(|e| locate::locate_error(e, path, text))?;
    coverage::check(&spec).map_err(|e| spec.locate(e))?;
    Ok(spec)
}

/// Validate a spec built in code in the spec's raw form (a design search's candidate,
/// `engine::design_search::candidate::raw_spec`): the checks `parse` makes once the YAML is
/// read, with no text (an error names its key path, no line).
pub(crate) fn from_raw(path: &str, raw: raw::RawSpec) -> Result<Spec> {
    let spec = validate::build(path, "", raw)?;
    coverage::check(&spec)?;
    Ok(spec)
}
