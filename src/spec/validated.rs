//! The validated spec (`Spec`): the model a spec describes, in engine units, with the text it
//! came from.

use crate::model::{Design, Golden, Limits, Modification, Scene, Study};

/// A validated spec, with the text it came from (for error locations and hashing).
#[derive(Debug, Clone)]
pub struct Spec {
    /// The spec's name (`name:`).
    pub name: String,
    /// The path it was loaded from, as given; files it names resolve against its directory.
    pub path: String,
    /// The YAML text it was parsed from: errors are located in it, and its SHA-256 names it in
    /// reports, golden metadata and tolerance shards.
    pub source: String,
    /// The reducer (`reducer:`).
    pub design: Design,
    /// The tooth-profile modification (`modification:`; zero when not given).
    pub modification: Modification,
    /// The load scenes (`scenes:`), in the spec's order.
    pub scenes: Vec<Scene>,
    /// The acceptance limits (`limits:`).
    pub limits: Limits,
    /// The optimisation studies (`optimise:`, one or a list; empty when not given).
    pub studies: Vec<Study>,
    /// The golden curves (`golden:`).
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
    /// The ladder's resolutions and tolerances (`accuracy:`'s other keys).
    pub options: crate::model::accuracy::Options,
}
