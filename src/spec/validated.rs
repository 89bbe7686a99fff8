//! The validated spec (`Spec`): the model a spec describes, in engine units, with the text it
//! came from.

use crate::model::{Design, Golden, Limits, Modification, Scene, Study};

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

impl Spec {
    /// Give an error about one of this spec's keys the key's location in the spec file.
    pub fn locate(&self, e: crate::error::Error) -> crate::error::Error {
        super::locate::locate_key(e, &self.path, &self.source)
    }
}

/// `accuracy:` of a spec: which scene's ladder the design review shows, and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Accuracy {
    /// Index into `Spec::scenes`.
    pub scene: usize,
    pub options: crate::model::accuracy::Options,
}
