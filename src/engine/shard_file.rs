//! The frame every shard file shares (`tolerance::shard`, `design_search::shard`): a 16-byte
//! mark, a format version (u32), the content, and last a SHA-256 of everything before it; and
//! a reader of its little-endian fields whose every refusal names the file and the command
//! that writes it.

use crate::error::{Error, Result};
use sha2::{Digest, Sha256};

/// Missing shards a merge's refusal lists by index, at most.
pub const MISSING_SHOWN: usize = 10;

/// How many items shard I of N holds: those k ≡ I (mod N), k < `items` (I is 0-based),
/// counted without listing them (a study may have 10⁹ samples, a shard header any number).
pub fn shard_len(items: u64, (index, count): (u64, u64)) -> u64 {
    items.saturating_sub(index).div_ceil(count.max(1))
}

/// Where each shard of a run of `count` shards is among those given: `indices` their headers'
/// indices (each < `count`, as the readers check), `names` their files, for messages.
/// Position k of the result is the position among those given of shard k. Refused when fewer
/// shards than `count` are given (the missing indices named, `MISSING_SHOWN` at most; nothing
/// is allocated for a header's count before this) or one is given twice. No fewer than
/// `count` indices below `count`, none twice, are every index: none is missing past this.
pub fn place(names: &[String], indices: &[u64], count: u64) -> Result<Vec<usize>> {
    if (indices.len() as u64) < count {
        let mut given = indices.to_vec();
        given.sort_unstable();
        given.dedup();
        let missing: Vec<String> = (0..count)
            .filter(|i| given.binary_search(i).is_err())
            .take(MISSING_SHOWN)
            .map(|i| i.to_string())
            .collect();
        let more = count - given.len() as u64 - missing.len() as u64;
        return Err(Error::invalid_value(format!(
            "shards of {count} missing: {}{} (0-based indices); merge needs every shard of the \
             run",
            missing.join(", "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        )));
    }
    let mut by_index: Vec<Option<usize>> = vec![None; count as usize];
    for (i, &index) in indices.iter().enumerate() {
        let slot = &mut by_index[index as usize];
        if let Some(j) = slot {
            return Err(Error::invalid_value(format!(
                "shard {index} of {count} is given twice: {} and {}",
                names[*j], names[i]
            )));
        }
        *slot = Some(i);
    }
    Ok(by_index.into_iter().flatten().collect())
}

/// What a shard says about the run it belongs to: the text the run was made from (a spec's, a
/// requirements file's: its SHA-256, path and text), the seed, the items of the whole run
/// (samples, candidates), and the shard's place among the run's.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    pub text_sha256: [u8; 32],
    pub seed: u64,
    /// Items of the whole run: the study's samples, the global stage's candidates.
    pub items: u64,
    /// 0-based shard index I and shard count N.
    pub index: u64,
    pub count: u64,
    pub text_path: String,
    pub text: String,
}

impl Header {
    /// A shard file's bytes before its content (`Reader::header` reads them back): `magic`,
    /// `version`, the text's SHA-256, the seed, items, index and count (u64 each), the
    /// format's own fields `own`, the path (u32 length + UTF-8) and the text (u64 length +
    /// UTF-8); `capacity` reserved for the whole file.
    pub fn bytes(
        &self,
        (magic, version): (&[u8; 16], u32),
        own: &[u8],
        capacity: usize,
    ) -> Vec<u8> {
        let mut b = Vec::with_capacity(capacity);
        b.extend_from_slice(magic);
        b.extend_from_slice(&version.to_le_bytes());
        b.extend_from_slice(&self.text_sha256);
        for v in [self.seed, self.items, self.index, self.count] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(own);
        put_short_text(&mut b, &self.text_path);
        b.extend_from_slice(&(self.text.len() as u64).to_le_bytes());
        b.extend_from_slice(self.text.as_bytes());
        b
    }
}

/// A u32 length, then the UTF-8 of `s` (`Reader::short_text`).
pub fn put_short_text(b: &mut Vec<u8>, s: &str) {
    b.extend_from_slice(&(s.len() as u32).to_le_bytes());
    b.extend_from_slice(s.as_bytes());
}

/// A run's words in a merge's refusals: the run (`design search`), its text (`requirements
/// file`), its items' count (`candidate count`), and whether shards of one run must name the
/// text by one path, with that path's words (`requirements path`).
pub struct RunWords {
    pub run: &'static str,
    pub text: &'static str,
    pub items: &'static str,
    pub same_path: Option<&'static str>,
}

/// Check that a complete set of shards (`names` their paths, for messages, `headers` theirs)
/// belongs to one run: refused when they differ in text, seed, item count or shard count, or
/// when a shard is missing or given twice (named by index). The positions in `headers` of the
/// shards in index order (`place`).
pub fn check_set(names: &[String], headers: &[&Header], words: &RunWords) -> Result<Vec<usize>> {
    let Some(h0) = headers.first() else {
        return Err(Error::invalid_value("merge needs at least one shard file"));
    };
    for (name, h) in names.iter().zip(headers) {
        let differs = |what: &str, a: String, b: String| {
            Error::invalid_value(format!(
                "{name} (shard {}) is of another {} than {} (shard {}): its {what} is {a}, not \
                 {b}; merge only the shards of one run",
                h.index, words.run, names[0], h0.index
            ))
        };
        if h.text_sha256 != h0.text_sha256 {
            return Err(differs(
                words.text,
                format!("`{}` (sha256 {})", h.text_path, hex(&h.text_sha256[..6])),
                format!("`{}` (sha256 {})", h0.text_path, hex(&h0.text_sha256[..6])),
            ));
        }
        if let Some(what) = words.same_path.filter(|_| h.text_path != h0.text_path) {
            return Err(differs(
                what,
                format!("`{}`", h.text_path),
                format!("`{}`", h0.text_path),
            ));
        }
        for (what, a, b) in [
            ("seed", h.seed, h0.seed),
            (words.items, h.items, h0.items),
            ("shard count", h.count, h0.count),
        ] {
            if a != b {
                return Err(differs(what, a.to_string(), b.to_string()));
            }
        }
    }
    let indices: Vec<u64> = headers.iter().map(|h| h.index).collect();
    place(names, &indices, h0.count)
}

/// SHA-256 of the text a shard names its run by (a spec's, a requirements file's).
pub fn text_hash(text: &str) -> [u8; 32] {
    Sha256::digest(text.as_bytes()).into()
}

/// Bytes as lower-case hex (a hash in a message).
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Bytes of the SHA-256 at the end of a shard file.
pub const CHECKSUM: usize = 32;

/// `b` (mark, version, content) with its SHA-256 appended: the file's bytes.
pub fn seal(mut b: Vec<u8>) -> Vec<u8> {
    let sum: [u8; CHECKSUM] = Sha256::digest(&b).into();
    b.extend_from_slice(&sum);
    b
}

/// Reads the fields of a shard in order; every shortfall is the same error.
pub struct Reader<'a> {
    /// The content (the checksum cut off once `open` has checked it).
    pub bytes: &'a [u8],
    /// The next field's offset in `bytes`.
    pub at: usize,
    path: &'a str,
    /// The command whose shards these are, e.g. "cycloid tolerance".
    command: &'static str,
}

impl<'a> Reader<'a> {
    /// Check the frame of the file `path` (`bytes`, written by `command`): its mark `magic`
    /// (named `mark` in the refusal), its format `version` and its checksum. The reader is
    /// left on the content after the version, the checksum cut off.
    pub fn open(
        path: &'a str,
        bytes: &'a [u8],
        command: &'static str,
        (magic, mark): (&[u8], &str),
        version: u32,
    ) -> Result<Self> {
        let mut r = Reader {
            bytes,
            at: 0,
            path,
            command,
        };
        if r.take(magic.len())? != magic {
            return Err(r.bad(&format!("it does not start with the {mark}")));
        }
        let found = r.u32()?;
        if found != version {
            return Err(r.bad(&format!(
                "format version {found}; this cycloid reads version {version}: write it again \
                 with this cycloid"
            )));
        }
        let Some(content) = bytes.len().checked_sub(CHECKSUM) else {
            return Err(r.bad("it ends early"));
        };
        let (content, sum) = bytes.split_at(content);
        if Sha256::digest(content).as_slice() != sum {
            return Err(r.bad(
                "its checksum does not match its contents: the file was changed or cut after it \
                 was written",
            ));
        }
        r.bytes = content;
        Ok(r)
    }

    /// The refusal of this file for `why`.
    pub fn bad(&self, why: &str) -> Error {
        Error::invalid_value(format!(
            "{}: not a shard file of `{}`: {why}",
            self.path, self.command
        ))
    }

    pub fn take(&mut self, n: usize) -> Result<&'a [u8]> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or_else(|| self.bad("it ends early"))?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }

    /// The next `N` bytes.
    fn array<const N: usize>(&mut self) -> Result<[u8; N]> {
        Ok(self.take(N)?.try_into().unwrap_or([0; N]))
    }

    pub fn u8(&mut self) -> Result<u8> {
        Ok(self.take(1)?[0])
    }

    pub fn u32(&mut self) -> Result<u32> {
        self.array().map(u32::from_le_bytes)
    }

    pub fn u64(&mut self) -> Result<u64> {
        self.array().map(u64::from_le_bytes)
    }

    pub fn f64(&mut self) -> Result<f64> {
        self.array().map(f64::from_le_bytes)
    }

    /// `n` bytes of UTF-8, the file's `what`.
    pub fn text(&mut self, n: usize, what: &str) -> Result<String> {
        let raw = self.take(n)?;
        String::from_utf8(raw.to_vec()).map_err(|_| self.bad(&format!("its {what} is not UTF-8")))
    }

    /// A u32 length, then that many bytes of UTF-8.
    pub fn short_text(&mut self, what: &str) -> Result<String> {
        let n = self.u32()? as usize;
        self.text(n, what)
    }

    /// A header as `Header::bytes` wrote it, after the version: `own` reads the format's own
    /// fields; `what` names the path and the text in a refusal.
    pub fn header<T>(
        &mut self,
        own: impl FnOnce(&mut Self) -> Result<T>,
        (path_what, text_what): (&str, &str),
    ) -> Result<(Header, T)> {
        let text_sha256 = self.array()?;
        let (seed, items, index, count) = (self.u64()?, self.u64()?, self.u64()?, self.u64()?);
        let own = own(self)?;
        let text_path = self.short_text(path_what)?;
        let n = self.u64()?;
        let n = usize::try_from(n).map_err(|_| self.bad("it ends early"))?;
        let text = self.text(n, text_what)?;
        let header = Header {
            text_sha256,
            seed,
            items,
            index,
            count,
            text_path,
            text,
        };
        Ok((header, own))
    }

    /// Refuse a header read back (`header`) that no shard of a run has: a shard count N of 0,
    /// an index I ≥ N, or more shards than the run's items (a run of none is one shard),
    /// refused for `place`; or a text other than the one its SHA-256 names, for `text`.
    pub fn check_header(&self, h: &Header, place: &str, text: &str) -> Result<()> {
        if h.count == 0 || h.index >= h.count || h.count > h.items.max(1) {
            return Err(self.bad(place));
        }
        if text_hash(&h.text) != h.text_sha256 {
            return Err(self.bad(text));
        }
        Ok(())
    }

    /// A count of items of at least `least` bytes each: no more than the bytes left hold.
    pub fn count(&mut self, least: usize) -> Result<usize> {
        let n = self.u32()? as usize;
        if n.saturating_mul(least) > self.bytes.len() - self.at {
            return Err(self.bad("it ends early"));
        }
        Ok(n)
    }
}
