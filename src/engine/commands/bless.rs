//! `bless`: rewrite the golden files of a spec from the current results, on purpose.

use crate::engine::golden::{self, Blessed};
use crate::engine::scene;
use crate::error::Result;
use crate::spec::Spec;

/// Run the scenes that a golden of `spec` refers to and rewrite every golden file (each with
/// its metadata, or none); what moved, per file. A spec without goldens blesses nothing.
///
/// ```
/// // A copy of the shipped spec with a golden of its own, in a folder of its own.
/// let dir = std::env::temp_dir().join(format!("cycloid-doc-bless-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let text = std::fs::read_to_string("specs/reducer.yaml").unwrap()
///     + "golden:\n  - {scene: rated, quantity: clearance_mm, file: clearance.csv, tolerance: {abs: 1.0e-6}}\n";
/// let path = dir.join("reducer.yaml");
/// std::fs::write(&path, text).unwrap();
/// let spec = cycloid::spec::load(path.to_str().unwrap())?;
/// let blessed = cycloid::bless(&spec)?;
/// assert_eq!(blessed.len(), 1);
/// assert!(dir.join("clearance.csv").is_file());
/// std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), cycloid::Error>(())
/// ```
pub fn bless(spec: &Spec) -> Result<Vec<Blessed>> {
    if spec.golden.is_empty() {
        return Ok(Vec::new());
    }
    let results = (spec.scenes.iter())
        .filter(|s| spec.golden.iter().any(|g| g.scene == s.name))
        .map(|s| {
            let plan = scene::plan(spec, s, scene::Writes::default());
            scene::run(spec, s, &plan, &Default::default())
        })
        .collect::<Result<Vec<_>>>();
    (results.and_then(|r| golden::bless(spec, &r))).map_err(|e| spec.locate(e))
}
