//! Shard files of a study split over processes (`--shard I/N`): the records of the samples
//! k ≡ I (mod N) and what a merge needs to check that the shards belong together and to
//! rebuild the study (the spec's text; the deviations are drawn again from (seed, k)).
//!
//! Format (little-endian), version 2:
//! `MAGIC` (16 bytes), version u32, SHA-256 of the spec text (32 bytes), seed u64, samples
//! u64, shard index u64 (0-based), shard count u64, limits L u32, spec path (u32 length +
//! UTF-8), spec text (u64 length + UTF-8); then per sample of the shard, in increasing k, its
//! L limit values (f64) and L verdicts (one byte each, 1 passed, 0 failed); last, the SHA-256
//! of every byte before it.
//!
//! A shard comes from another machine: it is read whole and trusted in nothing it could get
//! wrong. Its checksum must match (a changed byte anywhere), the spec text its hash, every
//! value be finite and every verdict byte 0 or 1 (`decode`); at the merge every verdict must
//! follow from its value and the spec's limit (`Merged::study`).

use super::{shard_len, Records};
use crate::engine::shard_file::{check_set, seal, Reader, RunWords};
use crate::error::{Error, Result};

pub const MAGIC: &[u8; 16] = b"cycloid-tol-shrd";
pub const VERSION: u32 = 2;

/// What a shard says about the study it belongs to: its text is the spec's, its items the
/// study's samples.
pub use crate::engine::shard_file::Header;

/// One shard read back: its header, the limits L of each sample, and its records.
#[derive(Debug, Clone)]
pub struct Shard {
    pub header: Header,
    pub limits: u32,
    pub records: Records,
}

/// SHA-256 of a spec's text.
pub use crate::engine::shard_file::text_hash as spec_hash;

/// The bytes of a shard file.
pub fn encode(h: &Header, limits: u32, records: &Records) -> Vec<u8> {
    let capacity = 128 + h.text.len() + records.values.len() * 9;
    let mut b = h.bytes((MAGIC, VERSION), &limits.to_le_bytes(), capacity);
    let l = limits as usize;
    for (v, p) in records.values.chunks(l).zip(records.passed.chunks(l)) {
        for x in v {
            b.extend_from_slice(&x.to_le_bytes());
        }
        b.extend(p.iter().map(|&p| p as u8));
    }
    seal(b)
}

/// Decode the bytes of the shard file at `path`.
pub fn decode(path: &str, bytes: &[u8]) -> Result<Shard> {
    let mut r = Reader::open(
        path,
        bytes,
        "cycloid tolerance",
        (MAGIC, "shard mark"),
        VERSION,
    )?;
    let bytes = r.bytes;
    let (header, limits) = r.header(Reader::u32, ("spec", "spec"))?;
    let (samples, index, count) = (header.items, header.index, header.count);
    let place = format!(
        "shard {index}/{count} with {}",
        super::limits_counted(limits as usize)
    );
    if limits == 0 {
        return Err(r.bad(&place));
    }
    r.check_header(
        &header,
        &place,
        "the spec it holds does not match the spec's hash in its header",
    )?;
    let l = limits as usize;
    let rows = shard_len(samples, (index, count));
    let body = &bytes[r.at..];
    let expected = rows as u128 * 9 * l as u128;
    if body.len() as u128 != expected {
        return Err(r.bad(&format!(
            "{} bytes of records, not the {expected} of {rows} samples",
            body.len()
        )));
    }
    // The body holds them: rows·l fits in memory.
    let cells = body.len() / 9;
    let mut records = Records {
        values: Vec::with_capacity(cells),
        passed: Vec::with_capacity(cells),
    };
    for (row, cells) in body.chunks_exact(9 * l).enumerate() {
        let k = index + row as u64 * count;
        let (v, p) = cells.split_at(8 * l);
        let values = v
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_default()));
        for value in values {
            if !value.is_finite() {
                return Err(r.bad(&format!("sample {k} holds the value {value}")));
            }
            records.values.push(value);
        }
        for &b in p {
            if b > 1 {
                return Err(r.bad(&format!(
                    "sample {k} holds the verdict byte {b}, neither 0 (failed) nor 1 (passed)"
                )));
            }
            records.passed.push(b == 1);
        }
    }
    Ok(Shard {
        header,
        limits,
        records,
    })
}

/// The records of every sample, in sample order, from a complete set of shards (`names` the
/// shards' paths, for messages): refused when they differ in spec, seed, sample count or
/// shard count, or when a shard is missing or given twice (named by index).
pub fn merge(names: &[String], shards: &[Shard]) -> Result<Records> {
    let headers: Vec<&Header> = shards.iter().map(|s| &s.header).collect();
    let words = RunWords {
        run: "study",
        text: "spec",
        items: "sample count",
        same_path: None,
    };
    check_set(names, &headers, &words)?;
    let (h0, count) = (&shards[0].header, shards[0].header.count);
    let l = shards[0].limits as usize;
    let n = h0.items as usize;
    if n.saturating_mul(l) > super::MAX_SAMPLE_LIMITS {
        return Err(Error::invalid_value(format!(
            "the shards hold {n} samples × {l} limits, beyond the {} sample-limits one study \
             holds",
            super::MAX_SAMPLE_LIMITS
        )));
    }
    let mut records = Records {
        values: vec![0.0; n * l],
        passed: vec![false; n * l],
    };
    for s in shards {
        let (i, c) = (s.header.index as usize, count as usize);
        for (row, (v, p)) in s
            .records
            .values
            .chunks_exact(l)
            .zip(s.records.passed.chunks_exact(l))
            .enumerate()
        {
            let k = i + row * c;
            records.values[k * l..(k + 1) * l].copy_from_slice(v);
            records.passed[k * l..(k + 1) * l].copy_from_slice(p);
        }
    }
    Ok(records)
}
