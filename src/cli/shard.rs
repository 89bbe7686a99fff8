//! Which shard of a tolerance study or a design search a run computes: `--shard I/N`, or the task of a Slurm job
//! array.

use crate::error::{Error, Result};
use crate::files;
use std::path::{Path, PathBuf};

/// The shard files `paths` read whole, each a regular file of at most `max_bytes` (a FIFO or a
/// device would be read without end): (path, bytes).
pub(super) fn read_shard_files(paths: &[String], max_bytes: u64) -> Result<Vec<(String, Vec<u8>)>> {
    paths
        .iter()
        .map(|p| {
            Ok((
                p.clone(),
                files::read_bytes(Path::new(p), "shard file", max_bytes)?,
            ))
        })
        .collect()
}

/// The shard files as inputs no output may replace: ("the shard file P", P).
pub(super) fn shard_inputs(paths: &[String]) -> Vec<(String, PathBuf)> {
    paths
        .iter()
        .map(|p| (format!("the shard file {p}"), PathBuf::from(p)))
        .collect()
}

/// `--shard I/N`: 0 ≤ I < N, 1 ≤ N ≤ `samples` (what is split, named `noun`).
pub fn parse_shard(text: &str, samples: u64, noun: &str) -> Result<(u64, u64)> {
    let rule = |why: String| {
        Error::invalid_value(format!(
            "--shard {text}: {why}; a shard is I/N with 0 <= I < N (0-based) and N at most the \
             {samples} {noun}"
        ))
    };
    let (i, n) = text
        .split_once('/')
        .ok_or_else(|| rule("not of the form I/N".into()))?;
    let (i, n): (u64, u64) = match (i.trim().parse(), n.trim().parse()) {
        (Ok(i), Ok(n)) => (i, n),
        _ => return Err(rule("I and N must be whole numbers".into())),
    };
    if n == 0 || n > samples {
        return Err(rule(format!("N = {n} shards")));
    }
    if i >= n {
        return Err(rule(format!("shard index {i} is not below N = {n}")));
    }
    Ok((i, n))
}

/// The environment variable that declines a job array's shard: `0` runs the whole study or
/// search in a task (an array whose tasks run several specs), `1` or unset takes the shard.
pub(super) const DECLINE_VAR: &str = "CYCLOID_SLURM_SHARD";

/// The shard of a Slurm job array task, of `samples` units named `noun`: I =
/// SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN (so `--array=0-99` and `--array=1-100` both give
/// I = 0 … 99), N = SLURM_ARRAY_TASK_COUNT. The array must be contiguous (no step, no list): I
/// must come out below N. None when `DECLINE_VAR` is `0`.
pub(super) fn slurm_shard(samples: u64, noun: &str) -> Result<Option<(u64, u64)>> {
    let var = |name: &str| std::env::var(name).ok();
    match var(DECLINE_VAR).as_deref().map(str::trim) {
        None | Some("1") => {}
        Some("0") => return Ok(None),
        Some(other) => {
            return Err(Error::invalid_value(format!(
                "{DECLINE_VAR}={other}: give 0 (run the whole study in each task) or 1 (a task \
                 of a Slurm job array computes its shard, the default)"
            )))
        }
    }
    let (Some(id), Some(count)) = (var("SLURM_ARRAY_TASK_ID"), var("SLURM_ARRAY_TASK_COUNT"))
    else {
        return Ok(None);
    };
    let number = |name: &str, v: &str| {
        v.trim().parse::<u64>().map_err(|_| {
            Error::invalid_value(format!(
                "{name}={v}: not a whole number (from the Slurm job array)"
            ))
        })
    };
    let id = number("SLURM_ARRAY_TASK_ID", &id)?;
    let min = match var("SLURM_ARRAY_TASK_MIN") {
        Some(m) => number("SLURM_ARRAY_TASK_MIN", &m)?,
        None => 0,
    };
    let count = number("SLURM_ARRAY_TASK_COUNT", &count)?;
    // A stepped array (--array=0-6:2) numbers its tasks 0, 2, 4, 6: task ids would not be the
    // shard indices 0 … N−1, and half the shards would be refused only after the others ran.
    if let Some(step) = var("SLURM_ARRAY_TASK_STEP") {
        if number("SLURM_ARRAY_TASK_STEP", &step)? != 1 {
            return Err(Error::invalid_value(format!(
                "SLURM_ARRAY_TASK_STEP={step}: the job array has a step; give it as one \
                 contiguous range such as --array=0-{}",
                count.saturating_sub(1)
            )));
        }
    }
    let i = id.checked_sub(min).ok_or_else(|| {
        Error::invalid_value(format!(
            "SLURM_ARRAY_TASK_ID {id} is below SLURM_ARRAY_TASK_MIN {min}"
        ))
    })?;
    parse_shard(&format!("{i}/{count}"), samples, noun)
        .map(Some)
        .map_err(|e| {
            Error::invalid_value(format!(
                "from the Slurm job array (task id {id}, min {min}, count {count}): {}; give the \
                 array as a contiguous range such as --array=0-{}",
                e.message,
                count.saturating_sub(1)
            ))
        })
}
