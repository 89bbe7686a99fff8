//! Reading inputs and writing outputs without losing data.
//!
//! Inputs are read only from regular files of bounded size (a FIFO or `/dev/zero` would be read
//! without end). Every output is written to a temporary file in its target's directory and
//! renamed into place, so a killed run or a full disk never leaves a cut-off file where a
//! complete one was; a `Batch` of several files replaces all of them or none.

use crate::error::{Error, ErrorKind, Result};
use std::fs::{self, File};
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Largest input file read (a spec or a golden CSV), bytes: 64 MiB, far above any real one (the
/// paper's largest golden is 90 KiB), and a bound on what a wrong path can make the tool read.
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// The bytes of a regular file of at most `max_bytes`. `what` names the file's role in
/// messages ("spec", "shard file").
pub fn read_bytes(path: &Path, what: &str, max_bytes: u64) -> Result<Vec<u8>> {
    let shown = path.display().to_string();
    let meta = fs::metadata(path).map_err(|e| Error::io(&shown, e))?;
    if !meta.is_file() {
        return Err(Error::new(
            ErrorKind::Io,
            format!("{shown}: the {what} is not a regular file (a directory, FIFO or device); give a file"),
        ));
    }
    let too_big = |size: String| {
        Error::new(
            ErrorKind::Io,
            format!("{shown}: the {what} is {size} bytes, more than the {max_bytes} bytes read"),
        )
    };
    if meta.len() > max_bytes {
        return Err(too_big(meta.len().to_string()));
    }
    let mut bytes = Vec::new();
    File::open(path)
        .and_then(|f| f.take(max_bytes + 1).read_to_end(&mut bytes))
        .map_err(|e| Error::io(&shown, e))?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_big(format!("over {max_bytes}")));
    }
    Ok(bytes)
}

/// The text of a regular file of at most `max_bytes`, a leading UTF-8 byte-order mark removed.
/// `what` names the file's role in messages ("spec", "golden file").
pub fn read_text(path: &Path, what: &str, max_bytes: u64) -> Result<String> {
    let shown = path.display().to_string();
    let bytes = read_bytes(path, what, max_bytes)?;
    let text = String::from_utf8(bytes).map_err(|e| {
        Error::new(
            ErrorKind::Io,
            format!(
                "{shown}: the {what} is not UTF-8 text (byte {} is invalid)",
                e.utf8_error().valid_up_to()
            ),
        )
    })?;
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => text,
    })
}

/// A temporary path beside `path`, unique within the process and across processes.
fn temporary(path: &Path) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.{}-{n}.tmp", std::process::id()))
}

/// Write a temporary file beside `path` with `write`, flushed to disk; its path.
fn stage(path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<PathBuf> {
    let shown = path.display().to_string();
    if path.file_name().is_none() {
        return Err(Error::new(
            ErrorKind::Io,
            format!("`{shown}` names no file"),
        ));
    }
    // A rename would move a directory aside (a batch) or fail late: refuse it before writing.
    if fs::metadata(path).is_ok_and(|m| m.is_dir()) {
        return Err(Error::new(
            ErrorKind::Io,
            format!("{shown} is a directory, not a file: it is left as it is and nothing was written; remove it or write elsewhere"),
        ));
    }
    let temp = temporary(path);
    let result = File::options()
        .write(true)
        .create_new(true)
        .open(&temp)
        .and_then(|file| {
            let mut out = io::BufWriter::new(file);
            write(&mut out)?;
            let file = out.into_inner().map_err(|e| e.into_error())?;
            file.sync_all()
        });
    match result {
        Ok(()) => Ok(temp),
        Err(e) => {
            let _ = fs::remove_file(&temp);
            Err(Error::io(&shown, e))
        }
    }
}

/// Write `path` atomically: `write` fills a temporary file in the same directory, which then
/// replaces `path` by a rename. On any error `path` is untouched and no temporary file is left.
pub fn write_atomic_with(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<()> {
    let temp = stage(path, write)?;
    fs::rename(&temp, path).map_err(|e| {
        let _ = fs::remove_file(&temp);
        Error::io(&path.display().to_string(), e)
    })
}

/// Write `bytes` to `path` atomically (`write_atomic_with`).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic_with(path, |out| out.write_all(bytes))
}

/// Several files replaced together: each is staged beside its target, and `commit` renames
/// them into place in the order they were added (so the file that indexes the others goes
/// last), or, if any step fails, leaves every target as it was.
#[derive(Debug, Default)]
pub struct Batch {
    /// (staged temporary file, target); no temporary file: the target is to be removed.
    staged: Vec<(Option<PathBuf>, PathBuf)>,
}

impl Batch {
    /// Stage `path` with the content `write` produces.
    pub fn add_with(
        &mut self,
        path: &Path,
        write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
    ) -> Result<()> {
        let temp = stage(path, write)?;
        self.staged.push((Some(temp), path.to_path_buf()));
        Ok(())
    }

    /// Stage `path` with `bytes`.
    pub fn add(&mut self, path: &Path, bytes: &[u8]) -> Result<()> {
        self.add_with(path, |out| out.write_all(bytes))
    }

    /// Remove `path` with the batch (a file the new ones replace under another name); put
    /// back if the batch fails.
    pub fn remove(&mut self, path: &Path) {
        self.staged.push((None, path.to_path_buf()));
    }

    /// Replace every target. Targets that exist are first moved aside to a backup; if a rename
    /// fails, the targets already replaced get their backups back, so the batch replaces all of
    /// its files or none.
    pub fn commit(mut self) -> Result<()> {
        let mut done: Vec<(PathBuf, Option<PathBuf>)> = Vec::new();
        for (temp, target) in &self.staged {
            let backup = if fs::symlink_metadata(target).is_ok() {
                let backup = temporary(target);
                if let Err(e) = fs::rename(target, &backup) {
                    return Err(undo(&done, target, e));
                }
                Some(backup)
            } else {
                None
            };
            let Some(temp) = temp else {
                if backup.is_some() {
                    done.push((target.clone(), backup));
                }
                continue;
            };
            if let Err(e) = fs::rename(temp, target) {
                if let Some(b) = &backup {
                    let _ = fs::rename(b, target);
                }
                return Err(undo(&done, target, e));
            }
            done.push((target.clone(), backup));
        }
        // Every temporary file is in place: none is left for `drop` to remove.
        self.staged.clear();
        for (_, backup) in done {
            if let Some(b) = backup {
                let _ = fs::remove_file(b);
            }
        }
        Ok(())
    }
}

/// Put the replaced targets of a failed commit back (the batch, dropped, removes its
/// temporary files).
fn undo(done: &[(PathBuf, Option<PathBuf>)], failed: &Path, e: io::Error) -> Error {
    for (target, backup) in done.iter().rev() {
        match backup {
            Some(b) => {
                let _ = fs::rename(b, target);
            }
            None => {
                let _ = fs::remove_file(target);
            }
        }
    }
    Error::io(&failed.display().to_string(), e)
}

impl Drop for Batch {
    /// A batch dropped without a `commit` that succeeded (an error while staging a later file,
    /// or a commit that failed) leaves no temporary files behind.
    fn drop(&mut self) {
        for temp in self.staged.iter().filter_map(|(t, _)| t.as_ref()) {
            let _ = fs::remove_file(temp);
        }
    }
}

/// A path as the file system resolves it, for telling whether two paths, which need not exist
/// yet, name the same file: absolute, and walked component by component as the kernel walks
/// it: each existing prefix has its symbolic links followed before the next component, so a
/// `..` after a link leaves the link's target (`link/../s.yaml` is the `s.yaml` beside the
/// target, not beside the link). Past the first missing component nothing can be a link, and
/// `.` and `..` are resolved by name.
pub fn identity(path: &Path) -> PathBuf {
    use std::path::Component;
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut resolved = PathBuf::new();
    let mut exists = true;
    for c in absolute.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                resolved.pop();
            }
            other => {
                resolved.push(other.as_os_str());
                if exists {
                    match fs::canonicalize(&resolved) {
                        Ok(real) => resolved = real,
                        Err(_) => exists = false,
                    }
                }
            }
        }
    }
    resolved
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("cycloid-files-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    /// A write that fails half-way (the disk filled up, the process was told to stop) leaves
    /// the old file whole and no temporary file beside it.
    #[test]
    fn a_failed_write_leaves_the_old_file_untouched() {
        let dir = scratch("fail");
        let path = dir.join("spec.yaml");
        fs::write(&path, "old content\n").unwrap();
        let err = write_atomic_with(&path, |out| {
            out.write_all(b"new cont")?;
            Err(io::Error::new(io::ErrorKind::StorageFull, "disk full"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("disk full"), "{err}");
        assert_eq!(fs::read_to_string(&path).unwrap(), "old content\n");
        assert_eq!(entries(&dir), ["spec.yaml"]);
        write_atomic(&path, b"new content\n").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "new content\n");
        assert_eq!(entries(&dir), ["spec.yaml"]);
        let _ = fs::remove_dir_all(&dir);
    }

    /// An output whose path is an existing directory is refused before anything is written:
    /// neither a single write nor a batch moves the directory aside or writes a file.
    #[test]
    fn a_directory_at_an_output_path_is_refused_and_left_alone() {
        let dir = scratch("dir");
        fs::create_dir_all(dir.join("front.csv")).unwrap();
        fs::write(dir.join("front.csv/keep"), "mine").unwrap();
        let err = write_atomic(&dir.join("front.csv"), b"x").unwrap_err();
        assert!(err.to_string().contains("is a directory"), "{err}");
        let mut batch = Batch::default();
        batch.add(&dir.join("a.csv"), b"a").unwrap();
        assert!(batch.add(&dir.join("front.csv"), b"x").is_err());
        drop(batch);
        assert_eq!(entries(&dir), ["front.csv"]);
        assert_eq!(
            fs::read_to_string(dir.join("front.csv/keep")).unwrap(),
            "mine"
        );
        let _ = fs::remove_dir_all(&dir);
    }

    /// A batch whose second file cannot be staged replaces nothing; a batch that stages
    /// every file replaces them all, new files included.
    #[test]
    fn a_batch_replaces_all_its_files_or_none() {
        let dir = scratch("batch");
        let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
        fs::write(&a, "a0").unwrap();
        fs::write(&b, "b0").unwrap();
        let mut batch = Batch::default();
        batch.add(&a, b"a1").unwrap();
        let failed = batch.add_with(&b, |_| Err(io::Error::other("killed")));
        assert!(failed.is_err());
        drop(batch);
        assert_eq!(fs::read_to_string(&a).unwrap(), "a0");
        assert_eq!(fs::read_to_string(&b).unwrap(), "b0");
        assert_eq!(entries(&dir), ["a.csv", "b.csv"]);
        let c = dir.join("c.csv");
        let mut batch = Batch::default();
        for (p, t) in [(&a, "a2"), (&b, "b2"), (&c, "c2")] {
            batch.add(p, t.as_bytes()).unwrap();
        }
        batch.commit().unwrap();
        for (p, t) in [(&a, "a2"), (&b, "b2"), (&c, "c2")] {
            assert_eq!(fs::read_to_string(p).unwrap(), t);
        }
        assert_eq!(entries(&dir), ["a.csv", "b.csv", "c.csv"]);
        let _ = fs::remove_dir_all(&dir);
    }

    /// A commit whose rename fails (here: the second file's directory vanished after it was
    /// staged) puts back the files it had already replaced.
    #[test]
    fn a_failed_commit_restores_what_it_replaced() {
        let dir = scratch("commit");
        let sub = dir.join("sub");
        fs::create_dir_all(&sub).unwrap();
        let (a, b) = (dir.join("a.csv"), sub.join("b.csv"));
        fs::write(&a, "a0").unwrap();
        let mut batch = Batch::default();
        batch.add(&a, b"a1").unwrap();
        batch.add(&b, b"b1").unwrap();
        fs::remove_dir_all(&sub).unwrap();
        assert!(batch.commit().is_err());
        assert_eq!(fs::read_to_string(&a).unwrap(), "a0");
        assert_eq!(entries(&dir), ["a.csv"]);
        let _ = fs::remove_dir_all(&dir);
    }

    /// A removal in a batch happens with the batch, and is undone with it.
    #[test]
    fn a_batch_removes_a_file_all_or_none() {
        let dir = scratch("remove");
        let (old, new) = (dir.join("te.meta.yaml"), dir.join("te.csv.meta.yaml"));
        fs::write(&old, "review").unwrap();
        let sub = dir.join("sub");
        fs::create_dir_all(&sub).unwrap();
        let mut batch = Batch::default();
        batch.add(&new, b"review").unwrap();
        batch.remove(&old);
        batch.add(&sub.join("x"), b"x").unwrap();
        fs::remove_dir_all(&sub).unwrap();
        assert!(batch.commit().is_err());
        assert_eq!(entries(&dir), ["te.meta.yaml"]);
        let mut batch = Batch::default();
        batch.add(&new, b"review").unwrap();
        batch.remove(&old);
        batch.commit().unwrap();
        assert_eq!(entries(&dir), ["te.csv.meta.yaml"]);
        let _ = fs::remove_dir_all(&dir);
    }

    /// Two spellings of one file have one identity, whether or not the file exists.
    #[test]
    fn paths_to_one_file_have_one_identity() {
        let dir = scratch("identity");
        fs::create_dir_all(dir.join("a")).unwrap();
        fs::write(dir.join("s.yaml"), "x").unwrap();
        let same = [
            (dir.join("s.yaml"), dir.join("a/../s.yaml")),
            (dir.join("new.json"), dir.join("./a/../new.json")),
            (dir.join("a/new.json"), dir.join("a/./new.json")),
        ];
        for (x, y) in same {
            assert_eq!(identity(&x), identity(&y), "{x:?} {y:?}");
        }
        assert_ne!(
            identity(&dir.join("s.yaml")),
            identity(&dir.join("a/s.yaml"))
        );
        let _ = fs::remove_dir_all(&dir);
    }

    /// A `..` after a symbolic link leaves the link's target, as the kernel resolves it: the
    /// output `link/../s.yaml` with `link` → `sub/deep` is `sub/s.yaml`, the spec there.
    #[cfg(unix)]
    #[test]
    fn a_parent_after_a_link_leaves_the_links_target() {
        let dir = scratch("link-parent");
        fs::create_dir_all(dir.join("sub/deep")).unwrap();
        fs::write(dir.join("sub/s.yaml"), "x").unwrap();
        std::os::unix::fs::symlink(dir.join("sub/deep"), dir.join("link")).unwrap();
        let through_link = dir.join("link/../s.yaml");
        // What the file system opens through that spelling: the spec in `sub`.
        assert_eq!(fs::read_to_string(&through_link).unwrap(), "x");
        assert_eq!(identity(&through_link), identity(&dir.join("sub/s.yaml")));
        assert_ne!(identity(&through_link), identity(&dir.join("s.yaml")));
        // A new file below a link, and `..` past the first missing component.
        assert_eq!(
            identity(&dir.join("link/new/../n.json")),
            identity(&dir.join("sub/deep/n.json"))
        );
        let _ = fs::remove_dir_all(&dir);
    }

    /// Only regular files of bounded size are read; a byte-order mark is dropped.
    #[test]
    fn inputs_are_regular_bounded_files() {
        let dir = scratch("read");
        let path = dir.join("s.yaml");
        fs::write(&path, "\u{feff}name: x\n").unwrap();
        assert_eq!(read_text(&path, "spec", 100).unwrap(), "name: x\n");
        let err = read_text(&path, "spec", 4).unwrap_err().to_string();
        assert!(err.contains("more than the 4 bytes"), "{err}");
        let err = read_text(&dir, "spec", 100).unwrap_err().to_string();
        assert!(err.contains("not a regular file"), "{err}");
        if Path::new("/dev/zero").exists() {
            let err = read_text(Path::new("/dev/zero"), "spec", 100).unwrap_err();
            assert!(err.to_string().contains("not a regular file"), "{err}");
        }
        let _ = fs::remove_dir_all(&dir);
    }
}
