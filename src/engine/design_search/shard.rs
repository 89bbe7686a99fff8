//! Shard files of a design search split over processes (`cycloid design REQ --shard I/N`):
//! the global stage's evaluations of the candidates j ≡ I (mod N), j the index into
//! `global_candidates` (choice by choice, Sobol point by point, so every shard holds about
//! 1/N of every discrete choice and the shards take about the same time), and what a merge
//! needs to check that the shards belong together and to finish the search (the requirements'
//! text; the local refinement runs at the merge, `super::finish`).
//!
//! Format (little-endian), version 2 (version 1, refused, named each failure's requirement
//! in free text):
//! `MAGIC` (16 bytes), version u32, SHA-256 of the requirements text (32 bytes), seed u64,
//! candidates u64 (of the whole global stage), shard index u64 (0-based), shard count u64,
//! requirements path (u32 length + UTF-8), requirements text (u64 length + UTF-8); then per
//! candidate of the shard, in increasing j: its choice (teeth, pins, discs: u32 each), its
//! eight variables (f64), its stage (u8: 0 rules, 1 screen, 2 full check), its objectives
//! (u32 count + f64 each), its failures: every requirement it missed at that stage (u32
//! count; each the requirement's tag u8, 0 outer diameter, 1 axial length, 2 K1, 3 roller
//! gap, 4 ligament, 5 crown start, 6 a rule of the spec and 8 a limit, each followed by its
//! key as u32 length + UTF-8, 7 the torque; then the miss, u8 0 with the value and the limit
//! as f64, or 1 with what the engine said as u32 length + UTF-8); last, the SHA-256 of every
//! byte before it. Numbers are their IEEE-754 bits: the merge finishes from the very
//! evaluations the shards made, and counts what each design met from them.
//!
//! A shard comes from another machine: it is read whole and trusted in nothing it could get
//! wrong. Its checksum must match (a changed or cut byte anywhere), the requirements text its
//! hash, and it must hold exactly the candidates of its share (`decode`); at the merge every
//! candidate must be the one the requirements generate at its index, bit for bit, and every
//! evaluation be consistent (objectives exactly when feasible, a failure only of a requirement
//! its stage judges) (`merge`).

use super::candidate::{Candidate, Choice};
use super::evaluate::{Evaluation, Stage};
use super::failure::{Failure, Miss, Requirement};
use crate::engine::shard_file::{self, put_short_text, seal, Reader, RunWords};
use crate::error::{Error, Result};
use crate::model::requirements::Requirements;
use crate::model::requirements::Variables;

pub const MAGIC: &[u8; 16] = b"cycloid-dsg-shrd";
pub const VERSION: u32 = 2;

/// What a shard says about the search it belongs to: its text is the requirements file's,
/// its items the candidates of the whole global stage.
pub use crate::engine::shard_file::Header;

/// One shard read back: its header and its evaluations, in increasing candidate index.
#[derive(Debug, Clone)]
pub struct Shard {
    pub header: Header,
    pub evaluations: Vec<Evaluation>,
}

/// SHA-256 of a requirements file's text.
pub use crate::engine::shard_file::text_hash as requirements_hash;

pub use crate::engine::shard_file::shard_len;

/// The candidates of shard `(i, n)`: those of `all` whose index j ≡ i (mod n), in order.
pub fn share(all: &[Candidate], (i, n): (u64, u64)) -> Vec<Candidate> {
    let step = n.max(1) as usize;
    all.iter().skip(i as usize).step_by(step).copied().collect()
}

/// The bytes of a shard file.
pub fn encode(h: &Header, evaluations: &[Evaluation]) -> Vec<u8> {
    let capacity = 256 + h.text.len() + evaluations.len() * 128;
    let mut b = h.bytes((MAGIC, VERSION), &[], capacity);
    for e in evaluations {
        let c = e.candidate.choice;
        for n in [c.teeth, c.pins, c.discs] {
            b.extend_from_slice(&(n as u32).to_le_bytes());
        }
        for x in e.candidate.x.to_array() {
            b.extend_from_slice(&x.to_le_bytes());
        }
        b.push(match e.stage {
            Stage::Rules => 0,
            Stage::Screen => 1,
            Stage::Full => 2,
        });
        b.extend_from_slice(&(e.objectives.len() as u32).to_le_bytes());
        for v in &e.objectives {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&(e.failures.len() as u32).to_le_bytes());
        for f in &e.failures {
            failure(&mut b, f);
        }
    }
    seal(b)
}

/// A failure's bytes: the requirement's tag (`tag`) with, for a rule of the spec or a
/// limit, its key; then the miss: 0 and the value and limit, or 1 and what the engine said.
fn failure(b: &mut Vec<u8>, f: &Failure) {
    b.push(tag(&f.requirement));
    match &f.requirement {
        Requirement::SpecRule(at) => put_short_text(b, at),
        Requirement::Limit(def) => put_short_text(b, def.key),
        _ => {}
    }
    match &f.miss {
        Miss::Bound { value, limit } => {
            b.push(0);
            b.extend_from_slice(&value.to_le_bytes());
            b.extend_from_slice(&limit.to_le_bytes());
        }
        Miss::Said(m) => {
            b.push(1);
            put_short_text(b, m);
        }
    }
}

/// A requirement's tag in a shard.
fn tag(r: &Requirement) -> u8 {
    match r {
        Requirement::OuterDiameter => 0,
        Requirement::AxialLength => 1,
        Requirement::MaxK1 => 2,
        Requirement::MinRollerGap => 3,
        Requirement::MinLigament => 4,
        Requirement::CrownStart => 5,
        Requirement::SpecRule(_) => 6,
        Requirement::Torque => 7,
        Requirement::Limit(_) => 8,
    }
}

/// A failure of candidate `j`, as `failure` wrote it.
fn read_failure(r: &mut Reader, j: u64) -> Result<Failure> {
    let requirement = match r.u8()? {
        0 => Requirement::OuterDiameter,
        1 => Requirement::AxialLength,
        2 => Requirement::MaxK1,
        3 => Requirement::MinRollerGap,
        4 => Requirement::MinLigament,
        5 => Requirement::CrownStart,
        6 => Requirement::SpecRule(r.short_text("rule key")?),
        7 => Requirement::Torque,
        8 => {
            let key = r.short_text("limit key")?;
            Requirement::limit(&key).ok_or_else(|| {
                r.bad(&format!(
                    "candidate {j} misses the limit `{key}`, which this cycloid does not know: \
                     written by another version"
                ))
            })?
        }
        t => return Err(r.bad(&format!("candidate {j} holds the requirement tag {t}"))),
    };
    let miss = match r.u8()? {
        0 => Miss::Bound {
            value: r.f64()?,
            limit: r.f64()?,
        },
        1 => Miss::Said(r.short_text("message")?),
        f => return Err(r.bad(&format!("candidate {j} holds the miss flag {f}"))),
    };
    Ok(Failure { requirement, miss })
}

/// The evaluation of candidate j, as `encode` wrote it.
fn evaluation(r: &mut Reader, j: u64) -> Result<Evaluation> {
    let mut choice = [0usize; 3];
    for n in &mut choice {
        *n = r.u32()? as usize;
    }
    let mut x = [0.0; 8];
    for v in &mut x {
        *v = r.f64()?;
    }
    let stage = match r.u8()? {
        0 => Stage::Rules,
        1 => Stage::Screen,
        2 => Stage::Full,
        s => return Err(r.bad(&format!("candidate {j} holds the stage byte {s}"))),
    };
    let n = r.count(8)?;
    let mut objectives = Vec::with_capacity(n);
    for _ in 0..n {
        let v = r.f64()?;
        if !v.is_finite() {
            return Err(r.bad(&format!("candidate {j} holds the objective {v}")));
        }
        objectives.push(v);
    }
    // A failure takes at least 6 bytes (its tag, the miss flag and a length).
    let n = r.count(6)?;
    let failures = (0..n)
        .map(|_| read_failure(r, j))
        .collect::<Result<Vec<_>>>()?;
    Ok(Evaluation {
        candidate: Candidate {
            choice: Choice {
                teeth: choice[0],
                pins: choice[1],
                discs: choice[2],
            },
            x: Variables::from_array(x),
        },
        stage,
        failures,
        objectives,
    })
}

/// Decode the bytes of the shard file at `path`.
pub fn decode(path: &str, bytes: &[u8]) -> Result<Shard> {
    let mut r = Reader::open(
        path,
        bytes,
        "cycloid design",
        (MAGIC, "design shard mark"),
        VERSION,
    )?;
    let content = r.bytes;
    let (header, ()) = r.header(|_| Ok(()), ("requirements path", "requirements text"))?;
    let (candidates, index, count) = (header.items, header.index, header.count);
    r.check_header(
        &header,
        &format!("shard {index}/{count} of {candidates} candidates"),
        "the requirements it holds do not match the requirements' hash in its header",
    )?;
    let rows = shard_len(candidates, (index, count));
    // Each evaluation takes at least 85 bytes: no more rows than the file holds are read.
    if rows.saturating_mul(85) > (content.len() - r.at) as u64 {
        return Err(r.bad(&format!("it ends before its {rows} candidates")));
    }
    let evaluations = (0..rows)
        .map(|row| evaluation(&mut r, index + row * count))
        .collect::<Result<Vec<_>>>()?;
    if r.at != content.len() {
        return Err(r.bad(&format!(
            "{} bytes follow its {rows} candidates",
            content.len() - r.at
        )));
    }
    Ok(Shard {
        header,
        evaluations,
    })
}

/// Check that a complete set of shards (`names` their paths, for messages) belongs to one
/// search (`shard_file::check_set`: one requirements text by one path). The positions in
/// `shards` of the shards in index order.
pub fn check_set(names: &[String], shards: &[Shard]) -> Result<Vec<usize>> {
    let headers: Vec<&Header> = shards.iter().map(|s| &s.header).collect();
    let words = RunWords {
        run: "design search",
        text: "requirements file",
        items: "candidate count",
        // The front's specs name the requirements path: one run, one path.
        same_path: Some("requirements path"),
    };
    shard_file::check_set(names, &headers, &words)
}

/// The global stage's evaluations of every candidate, in the order of `global_candidates`,
/// from the shards of one run in index order (as `check_set` gives them) and their
/// requirements `req`: refused when a
/// shard's candidate is not the one `req` generates at its index (bit for bit: another
/// version of cycloid, or an altered shard) or an evaluation is not consistent.
/// The shards are consumed: their evaluations move into the result.
pub fn merge(req: &Requirements, ordered: Vec<(&str, Shard)>) -> Result<Vec<Evaluation>> {
    let candidates = super::global_candidates(req);
    let h0 = &ordered[0].1.header;
    let from_here = |what: &str, a: u64, b: u64| {
        Error::invalid_value(format!(
            "{}: the shards hold {a} {what}, their requirements `{}` give {b}: written by \
             another version of cycloid",
            ordered[0].0, h0.text_path
        ))
    };
    if h0.seed != u64::from(req.search.seed) {
        return Err(from_here("as seed", h0.seed, u64::from(req.search.seed)));
    }
    if h0.items != candidates.len() as u64 {
        return Err(from_here("candidates", h0.items, candidates.len() as u64));
    }
    let count = h0.count as usize;
    let mut all: Vec<Option<Evaluation>> = vec![None; candidates.len()];
    for (i, (name, s)) in ordered.into_iter().enumerate() {
        for (row, e) in s.evaluations.into_iter().enumerate() {
            let j = i + row * count;
            let c = &candidates[j];
            let bad = |why: &str| {
                Error::invalid_value(format!(
                    "{name}: shard {i} of {count} holds candidate {j} {why}: written by another \
                     version of cycloid, or altered"
                ))
            };
            let same = c.choice == e.candidate.choice
                && (c.x.to_array().iter())
                    .zip(&e.candidate.x.to_array())
                    .all(|(a, b)| a.to_bits() == b.to_bits());
            if !same {
                return Err(bad("other than its requirements generate"));
            }
            let objectives = if e.feasible() {
                req.objectives.len()
            } else {
                0
            };
            if e.objectives.len() != objectives {
                return Err(bad(&format!(
                    "with {} objectives, not the {objectives} of its {}",
                    e.objectives.len(),
                    if e.feasible() {
                        "requirements"
                    } else {
                        "failed check"
                    }
                )));
            }
            if e.stage != Stage::Full && e.failures.is_empty() {
                return Err(bad("stopped before the full check without a failure"));
            }
            // The counts of what no design met read each failure as missed at its stage.
            if let Some(f) = e
                .failures
                .iter()
                .find(|f| !super::missed::missed_at(&f.requirement, e.stage))
            {
                return Err(bad(&format!(
                    "stopped at the {:?} stage having missed `{}`, which that stage does not \
                     judge",
                    e.stage,
                    f.requirement.key()
                )));
            }
            all[j] = Some(e);
        }
    }
    all.into_iter()
        .enumerate()
        .map(|(j, e)| {
            e.ok_or_else(|| Error::invalid_value(format!("no shard holds candidate {j}")))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every split of up to 12 candidates gives each candidate to exactly one shard, and a
    /// shard's count is that of its residue, listed one by one.
    #[test]
    fn the_shares_cover_every_candidate_once() {
        let c = Candidate {
            choice: Choice {
                teeth: 9,
                pins: 6,
                discs: 1,
            },
            x: Variables::from_array([0.0; 8]),
        };
        for total in 0..=12u64 {
            let all: Vec<Candidate> = (0..total)
                .map(|j| Candidate {
                    x: Variables::from_array([j as f64; 8]),
                    ..c
                })
                .collect();
            for n in 1..=total.max(1) {
                let mut seen = vec![0; total as usize];
                for i in 0..n {
                    let s = share(&all, (i, n));
                    let residue = (0..total).filter(|j| j % n == i).count() as u64;
                    assert_eq!(s.len() as u64, residue);
                    assert_eq!(shard_len(total, (i, n)), residue);
                    for c in s {
                        seen[c.x.eccentricity_mm as usize] += 1;
                    }
                }
                assert!(seen.iter().all(|&k| k == 1), "{total}/{n}: {seen:?}");
            }
        }
    }
}
