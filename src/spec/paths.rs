//! Paths a spec names (goldens, measured points, `golden_root:`), resolved against the spec
//! file's directory.

/// Resolve a path the spec names against the spec file's directory, dropping `.` and `dir/..`
/// pairs so messages show `golden/x.csv` rather than `specs/../golden/x.csv`.
pub fn resolve(spec_path: &str, file: &str) -> std::path::PathBuf {
    use std::path::{Component, Path, PathBuf};
    let base = Path::new(spec_path).parent().unwrap_or(Path::new(""));
    let mut out = PathBuf::new();
    for c in base.join(file).components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                let last = out.components().next_back();
                if matches!(last, Some(Component::Normal(_))) {
                    out.pop();
                } else {
                    out.push("..");
                }
            }
            other => out.push(other.as_os_str()),
        }
    }
    out
}
