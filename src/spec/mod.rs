//! Spec loading: YAML text → `raw` (serde) → the validated model (engine units).
//!
//! Errors carry `file:line:column` and the key path. Syntax errors take their location from the
//! YAML parser (`yaml`); value and design-rule errors locate their key in the text (`locate`).

pub mod deviations;
pub mod locate;
pub mod measured;
pub mod raw;
pub mod rules;
pub mod tolerances;
pub mod validate;
pub mod yaml;

use crate::error::Result;
pub use crate::model::scene::MAX_ROLLER_ANGLES;
use crate::model::{Design, Golden, Limits, Modification, Scene, Study};
pub use locate::{locate, locate_offset};
pub use validate::{crank_angles, resolve};

/// A validated spec, with the text it came from (for error locations and hashing).
#[derive(Debug, Clone)]
pub struct Spec {
    pub name: String,
    pub path: String,
    pub source: String,
    pub design: Design,
    pub modification: Modification,
    pub scenes: Vec<Scene>,
    pub limits: Limits,
    pub studies: Vec<Study>,
    pub golden: Vec<Golden>,
    /// `golden_root:` resolved against the spec's directory: where goldens may be written
    /// besides the spec's own directory tree.
    pub golden_root: Option<std::path::PathBuf>,
    /// The accuracy ladder the design review shows (`accuracy:`), if asked for.
    pub accuracy: Option<Accuracy>,
    /// Points measured on the disc (`measured_profile:`), if given.
    pub measured: Option<crate::model::measured::MeasuredProfile>,
    /// Tolerance bands and the Monte Carlo study of them (`tolerances:`), if given.
    pub tolerances: Option<crate::model::tolerances::PartTolerances>,
}

/// `accuracy:` of a spec: which scene's ladder the design review shows, and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Accuracy {
    /// Index into `Spec::scenes`.
    pub scene: usize,
    pub options: crate::model::accuracy::Options,
}

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
    validate::build(path, text, raw).map_err(|e| locate::locate_error(e, path, text))
}

/// The index of the scene named `name`; else an error at `key` that lists the scenes.
pub fn scene_index(scenes: &[Scene], name: &str, key: &str) -> Result<usize> {
    scenes.iter().position(|s| s.name == name).ok_or_else(|| {
        crate::error::Error::new(
            crate::error::ErrorKind::InvalidValue,
            format!("no scene named `{name}`; scenes: {}", scene_names(scenes)),
        )
        .at_key(key)
    })
}

/// Refuse the first scene that asks for the first-order geometry, at its key: `why` says what
/// needs the exact one ("…, but {why}").
pub fn refuse_first_order(scenes: &[Scene], why: &str) -> Result<()> {
    match (scenes.iter()).position(|s| s.geometry == crate::model::GeometryMode::FirstOrder) {
        Some(i) => Err(crate::error::Error::new(
            crate::error::ErrorKind::InvalidValue,
            format!(
                "scene `{}` asks for the first-order geometry, but {why}",
                scenes[i].name
            ),
        )
        .at_key(format!("scenes[{i}].geometry"))),
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
