//! `bless`: rewrite the golden files of a spec from the current results, on purpose.

use crate::engine::golden::{self, Blessed};
use crate::engine::scene;
use crate::error::Result;
use crate::spec::Spec;

/// Run the scenes that a golden of `spec` refers to and rewrite every golden file (each with
/// its metadata, or none); what moved, per file. A spec without goldens blesses nothing.
pub fn bless(spec: &Spec) -> Result<Vec<Blessed>> {
    if spec.golden.is_empty() {
        return Ok(Vec::new());
    }
    let mut results = Vec::new();
    for s in &spec.scenes {
        if spec.golden.iter().any(|g| g.scene == s.name) {
            let plan = scene::plan(spec, s, scene::Writes::default());
            let r = scene::run(spec, s, &plan, &Default::default()).map_err(|e| spec.locate(e))?;
            results.push(r);
        }
    }
    golden::bless(spec, &results).map_err(|e| spec.locate(e))
}
