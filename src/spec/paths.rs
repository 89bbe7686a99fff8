//! Paths a spec names (goldens, measured points, `golden_root:`), resolved against the spec
//! file's directory.

/// Resolve a path the spec names against the spec file's directory, dropping `.` and `dir/..`
/// pairs so messages show `golden/x.csv` rather than `specs/../golden/x.csv`. A `dir` that is a
/// symbolic link keeps its `..`: the kernel leaves the link's target there, not the link's
/// directory (`link/../x.csv` is the `x.csv` beside the target).
pub fn resolve(spec_path: &str, file: &str) -> std::path::PathBuf {
    use std::path::{Component, Path, PathBuf};
    let base = Path::new(spec_path).parent().unwrap_or(Path::new(""));
    let mut out = PathBuf::new();
    for c in base.join(file).components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                let last = out.components().next_back();
                let link = std::fs::symlink_metadata(&out).is_ok_and(|m| m.is_symlink());
                if matches!(last, Some(Component::Normal(_))) && !link {
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
