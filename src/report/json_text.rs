//! The results JSON's text, streamed through one buffer: a curve's numbers written without
//! serde's per-number path, everything else serialised by serde_json into the same buffer.
//! What it writes is the text serde_json's compact serialiser gives for the same values, byte
//! for byte (the tests below hold it); `report::json` says what is written.
//!
//! Why not serde_json alone: a 3,600-angle scene is about 165,000 numbers, and serde's path
//! for each (the sequence's state, the separator, the finiteness test, a write into the
//! buffer) costs a fifth of formatting it; and serde_json takes a value already written as
//! text only through `RawValue`, which parses it again (BENCHMARKS.md "JSON output").

use super::finite::not_finite;
use serde::ser::{Error as _, SerializeMap};
use serde::Serialize;
use std::io::Write;

/// serde_json's compact format, with zeros (most of the forces and pressures: a roller out of
/// contact) written without the float formatter, which costs as much for 0.0 as for any
/// number.
struct Compact;

impl serde_json::ser::Formatter for Compact {
    fn write_f64<W: ?Sized + Write>(&mut self, out: &mut W, value: f64) -> std::io::Result<()> {
        let mut digits = zmij::Buffer::new();
        out.write_all(
            zero(value)
                .unwrap_or_else(|| digits.format_finite(value))
                .as_bytes(),
        )
    }
}

/// "0.0" or "-0.0" for a zero, as serde_json writes them; `None` for any other number.
fn zero(value: f64) -> Option<&'static str> {
    match value == 0.0 {
        true if value.is_sign_negative() => Some("-0.0"),
        true => Some("0.0"),
        false => None,
    }
}

/// `value` serialised by serde_json (compact, `Compact`'s zeros) at the end of `buf`.
fn serialize_into<T: ?Sized + Serialize>(buf: &mut Vec<u8>, value: &T) -> serde_json::Result<()> {
    value.serialize(&mut serde_json::Serializer::with_formatter(buf, Compact))
}

/// `,0.0` 64 times: a run of positive zeros (a roller out of contact over a range of crank
/// angles) is copied from it at once.
const COMMA_ZEROS: [u8; 256] = {
    let mut zeros = [0; 256];
    let mut i = 0;
    while i < zeros.len() {
        zeros[i] = b",0.0"[i % 4];
        i += 1;
    }
    zeros
};

/// `[x0,x1,…]` at the end of `buf`: each number in serde_json's shortest round-trip form
/// (zmij's, the formatter serde_json calls), a non-finite one an error. The buffer is grown
/// once, for the longest numbers (zmij's 24 bytes); a run of positive zeros (most of the
/// forces and pressures) is one copy from `COMMA_ZEROS` and a negative zero a constant.
pub fn numbers(buf: &mut Vec<u8>, row: &[f64]) -> serde_json::Result<()> {
    let mut digits = zmij::Buffer::new();
    buf.reserve(2 + 25 * row.len());
    buf.push(b'[');
    // The first number without its comma (written, then taken out), the rest each after one.
    let mut i = 0;
    if !row.is_empty() {
        let start = buf.len();
        i = number(buf, &mut digits, row)?;
        buf.remove(start);
    }
    while i < row.len() {
        i += number(buf, &mut digits, &row[i..])?;
    }
    buf.push(b']');
    Ok(())
}

/// `,x` for `row`'s first number, or `,0.0,0.0…` for the run of positive zeros it starts (up
/// to 64); how many numbers it wrote.
#[inline(always)]
fn number(buf: &mut Vec<u8>, digits: &mut zmij::Buffer, row: &[f64]) -> serde_json::Result<usize> {
    let x = row[0];
    // Finite and not zero, in one comparison of the bits without the sign: the common case.
    if (x.to_bits() & !(1 << 63)).wrapping_sub(1) < f64::INFINITY.to_bits() - 1 {
        buf.push(b',');
        buf.extend_from_slice(digits.format_finite(x).as_bytes());
        Ok(1)
    } else if x.to_bits() == 0 {
        // Whole blocks of eight zeros each tested by one OR of their bits (a run is mostly
        // whole blocks: the run up to 64 costs about one instruction a zero, not six), then
        // the zeros after the last block one by one.
        let row = &row[..row.len().min(COMMA_ZEROS.len() / 4)];
        let blocks = (row.chunks_exact(8))
            .take_while(|b| b.iter().fold(0, |bits, z| bits | z.to_bits()) == 0)
            .count();
        let ones = row[8 * blocks..].iter().take_while(|z| z.to_bits() == 0);
        let run = 8 * blocks + ones.count();
        buf.extend_from_slice(&COMMA_ZEROS[..4 * run]);
        Ok(run)
    } else if x == 0.0 {
        buf.extend_from_slice(b",-0.0");
        Ok(1)
    } else {
        Err(not_finite(x))
    }
}

/// `n` as the whole number it is; an error, not a rounding, where it is not one (a count of
/// the registry never is: `report::json::Counts`).
pub fn count(n: f64) -> Result<u64, String> {
    // `n as u64` back to a double is `n` only for a whole `n` in range (`fract` is a call of
    // libm's trunc on this target, the largest part of a count's cost).
    match n >= 0.0 && n < u64::MAX as f64 && (n as u64) as f64 == n {
        true => Ok(n as u64),
        false => Err(format!(
            "a count is {n}, not a whole number (a bug: please report it with the spec)"
        )),
    }
}

/// `[n0,n1,…]` at the end of `buf`: each `count` in decimal by itoa, as serde_json writes a
/// `u64` (it calls itoa).
pub fn counts(buf: &mut Vec<u8>, row: &[f64]) -> serde_json::Result<()> {
    let mut digits = itoa::Buffer::new();
    buf.push(b'[');
    for (i, &n) in row.iter().enumerate() {
        if i > 0 {
            buf.push(b',');
        }
        match count(n).map_err(serde_json::Error::custom)? {
            // Rollers in contact: one digit, the common case, without itoa's call.
            n @ 0..10 => buf.push(b'0' + n as u8),
            n => buf.extend_from_slice(digits.format(n).as_bytes()),
        }
    }
    buf.push(b']');
    Ok(())
}

/// `[[…],[…],…]`: rows of numbers (`numbers`), each row to the buffer then on.
pub fn rows<'r>(text: &mut Text, rows: impl Iterator<Item = &'r [f64]>) -> serde_json::Result<()> {
    text.push(b"[")?;
    for (i, row) in rows.enumerate() {
        text.push(if i > 0 { b"," } else { b"" })?;
        text.with(|buf| numbers(buf, row))?;
    }
    text.push(b"]")
}

/// Text on its way to a writer: appended to a buffer, which goes to the writer whenever it
/// holds 64 KiB (it stays in cache and is reused, where a buffer of the whole file would be
/// new memory, a page fault every 4 KiB). A value serialised by serde (`Object`'s
/// `SerializeMap`) goes into the buffer whole first: a scene's discs' documents and a duty
/// cycle's bins grow it to their size. A long scene's back fields are written by a second
/// thread into a buffer of their own (`Text::in_memory`, up to the scene's text when the
/// writer is slow), passed on after the front's (`Text::pass`).
pub struct Text<'a> {
    buf: Vec<u8>,
    /// Where the buffer goes when full; none for text kept in memory (`Text::in_memory`).
    out: Option<&'a mut dyn Write>,
}

impl<'a> Text<'a> {
    const FLUSH_AT: usize = 64 << 10;

    pub fn new(out: &'a mut dyn Write) -> Self {
        Text {
            buf: Vec::with_capacity(2 * Self::FLUSH_AT),
            out: Some(out),
        }
    }

    /// Text that stays in its buffer (`bytes` reads it, `into_bytes` takes it), room for
    /// `capacity` bytes made at once (untouched room costs no page).
    pub fn in_memory(capacity: usize) -> Text<'static> {
        Text {
            buf: Vec::with_capacity(capacity),
            out: None,
        }
    }

    /// The text in memory so far (all of it for `in_memory` text).
    pub fn bytes(&self) -> &[u8] {
        &self.buf
    }

    /// The text in memory.
    pub fn into_bytes(self) -> Vec<u8> {
        self.buf
    }

    /// `bytes` as they are.
    pub fn push(&mut self, bytes: &[u8]) -> serde_json::Result<()> {
        self.buf.extend_from_slice(bytes);
        self.flush_when_full()
    }

    /// `bytes` as they are, text another `Text` wrote in memory: to the writer after the
    /// buffer, without a copy into it.
    pub fn pass(&mut self, bytes: &[u8]) -> serde_json::Result<()> {
        match &mut self.out {
            Some(out) => {
                out.write_all(&self.buf).map_err(serde_json::Error::io)?;
                self.buf.clear();
                out.write_all(bytes).map_err(serde_json::Error::io)
            }
            None => self.push(bytes),
        }
    }

    /// What `write` appends to the buffer.
    pub fn with(
        &mut self,
        write: impl FnOnce(&mut Vec<u8>) -> serde_json::Result<()>,
    ) -> serde_json::Result<()> {
        write(&mut self.buf)?;
        self.flush_when_full()
    }

    fn flush_when_full(&mut self) -> serde_json::Result<()> {
        match &mut self.out {
            Some(out) if self.buf.len() >= Self::FLUSH_AT => {
                out.write_all(&self.buf).map_err(serde_json::Error::io)?;
                self.buf.clear();
            }
            _ => (),
        }
        Ok(())
    }

    /// Write what is left in the buffer.
    pub fn finish(mut self) -> std::io::Result<()> {
        if let Some(out) = &mut self.out {
            out.write_all(&self.buf)?;
        }
        self.buf.clear();
        Ok(())
    }
}

/// A JSON object being written, `{"key":value,…}`: its values serialised by serde_json
/// (`SerializeMap`), written by a function of this module (`raw`), or another object's
/// entries (`flatten`). `end` closes it.
pub struct Object<'t, 'a> {
    text: &'t mut Text<'a>,
    empty: bool,
}

impl<'t, 'a> Object<'t, 'a> {
    pub fn new(text: &'t mut Text<'a>) -> serde_json::Result<Self> {
        text.push(b"{")?;
        Ok(Object { text, empty: true })
    }

    /// More entries of an object whose first entry is written elsewhere: each after a comma,
    /// and no braces (`end` is not called).
    pub fn after_first(text: &'t mut Text<'a>) -> Self {
        Object { text, empty: false }
    }

    /// `"key":` then what `write` writes.
    pub fn raw(
        &mut self,
        key: &str,
        write: impl FnOnce(&mut Text<'a>) -> serde_json::Result<()>,
    ) -> serde_json::Result<()> {
        self.serialize_key(key)?;
        write(self.text)
    }

    /// The entries of `value`, which serialises as a JSON object (a struct), as this object's
    /// (serde's `flatten`, without its buffering).
    pub fn flatten<T: Serialize>(&mut self, value: &T) -> serde_json::Result<()> {
        let mut object = Vec::new();
        serialize_into(&mut object, value)?;
        match object.as_slice() {
            [b'{', b'}'] => Ok(()),
            [b'{', inner @ .., b'}'] => {
                self.separate()?;
                self.text.push(inner)
            }
            _ => Err(serde_json::Error::custom(
                "a flattened value is not an object",
            )),
        }
    }

    /// Entries another `Object` wrote in memory (`Text::pass`).
    pub fn pass(&mut self, bytes: &[u8]) -> serde_json::Result<()> {
        self.text.pass(bytes)
    }

    fn separate(&mut self) -> serde_json::Result<()> {
        match std::mem::replace(&mut self.empty, false) {
            true => Ok(()),
            false => self.text.push(b","),
        }
    }
}

impl SerializeMap for Object<'_, '_> {
    type Ok = ();
    type Error = serde_json::Error;

    /// A key must serialise as a string (serde_json would quote a number; none is written).
    fn serialize_key<T: ?Sized + Serialize>(&mut self, key: &T) -> serde_json::Result<()> {
        self.separate()?;
        self.text.with(|buf| {
            let start = buf.len();
            serialize_into(buf, key)?;
            if buf.get(start) != Some(&b'"') {
                return Err(serde_json::Error::custom("a key is not a string"));
            }
            buf.push(b':');
            Ok(())
        })
    }

    fn serialize_value<T: ?Sized + Serialize>(&mut self, value: &T) -> serde_json::Result<()> {
        self.text.with(|buf| serialize_into(buf, value))
    }

    fn end(self) -> serde_json::Result<()> {
        self.text.push(b"}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_chacha::rand_core::SeedableRng;
    use rand_distr::{Distribution as _, StandardUniform};

    fn serde(value: &impl Serialize) -> String {
        serde_json::to_string(value).unwrap()
    }

    fn ours(write: impl FnOnce(&mut Vec<u8>) -> serde_json::Result<()>) -> String {
        let mut buf = Vec::new();
        write(&mut buf).unwrap();
        String::from_utf8(buf).unwrap()
    }

    /// The numbers' text is serde_json's own for the numbers a result holds (forces of a few
    /// newtons, angles in arcseconds, pressures) and for the edges of the format: zeros of
    /// both signs, subnormals, the largest and smallest normal numbers, the switch to an
    /// exponent (1e16, 1e-7 and their neighbours), and 100,000 numbers of random bits
    /// (every exponent and mantissa pattern, the non-finite ones left out).
    #[test]
    fn numbers_are_written_as_serde_json_writes_them() {
        let mut edge = vec![
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            1.0 / 3.0,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            f64::MIN_POSITIVE / 3.0,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            1e15,
            1e16,
            1e17,
            1e21,
            1e22,
            1e-5,
            1e-6,
            1e-7,
            123456789.0,
            2.5e-4,
        ];
        for x in [1e16_f64, 1e-7, 1e21] {
            edge.push(f64::from_bits(x.to_bits() - 1));
            edge.push(f64::from_bits(x.to_bits() + 1));
        }
        assert_eq!(ours(|b| numbers(b, &edge)), serde(&edge));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(40);
        let random: Vec<f64> = (0..100_000)
            .map(|_| f64::from_bits(StandardUniform.sample(&mut rng)))
            .filter(|x| x.is_finite())
            .collect();
        assert_eq!(ours(|b| numbers(b, &random)), serde(&random));
        let rows = vec![random[..3].to_vec(), vec![], vec![0.0, 2.0]];
        let mut out = Vec::new();
        let mut text = Text::new(&mut out);
        super::rows(&mut text, rows.iter().map(Vec::as_slice)).unwrap();
        text.finish().unwrap();
        assert_eq!(String::from_utf8(out).unwrap(), serde(&rows));
        assert_eq!(ours(|b| numbers(b, &[])), "[]");
        // Runs of zeros shorter and longer than one copy (64) and than a block of eight (7,
        // 13: a block and five after it), first, last and between numbers, with a negative
        // zero breaking one.
        for (lead, run) in [
            (0, 1),
            (0, 7),
            (3, 13),
            (0, 64),
            (1, 65),
            (2, 130),
            (1, 200),
        ] {
            let mut row = vec![1.5; lead];
            row.extend(std::iter::repeat_n(0.0, run));
            row.push(-0.0);
            row.extend(std::iter::repeat_n(0.0, run));
            row.push(2.0);
            assert_eq!(
                ours(|b| numbers(b, &row)),
                serde(&row),
                "{lead} then {run} zeros"
            );
            row.truncate(lead + run);
            assert_eq!(
                ours(|b| numbers(b, &row)),
                serde(&row),
                "{lead} then {run} zeros"
            );
        }
    }

    /// Counts are serde_json's text for the same `u64`s (0, one and several digits, the
    /// largest below 2⁶⁴ a double holds); a fraction, a negative count or a NaN is an error.
    #[test]
    fn counts_are_written_as_serde_json_writes_integers() {
        let whole = [0.0, 1.0, 9.0, 10.0, 12.0, 1e15, 18446744073709549568.0];
        let expected: Vec<u64> = vec![0, 1, 9, 10, 12, 1_000_000_000_000_000, 18446744073709549568];
        assert_eq!(ours(|b| counts(b, &whole)), serde(&expected));
        assert_eq!(ours(|b| counts(b, &[])), "[]");
        for bad in [0.5, -1.0, f64::NAN, 2f64.powi(64)] {
            let error = counts(&mut Vec::new(), &[1.0, bad]).unwrap_err();
            assert!(error.to_string().contains("not a whole number"), "{error}");
        }
    }

    /// A non-finite number is an error, as `Finite` makes it, not the `null` serde_json
    /// writes.
    #[test]
    fn a_non_finite_number_is_an_error() {
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let error = numbers(&mut Vec::new(), &[1.0, x]).unwrap_err();
            assert!(error.to_string().contains("JSON cannot hold"), "{error}");
        }
    }

    /// An object of a flattened struct, serialised and raw entries is the object
    /// serde_json writes for the same entries, through buffers smaller and larger than the
    /// one the text is flushed at; an empty struct adds no separator.
    #[test]
    fn an_object_is_the_object_serde_json_writes() {
        #[derive(Serialize)]
        struct Head {
            a: u32,
            b: &'static str,
        }
        #[derive(Serialize)]
        struct Nothing {}
        let long: Vec<f64> = (0..20_000).map(|i| f64::from(i) / 7.0).collect();
        let mut out = Vec::new();
        let mut text = Text::new(&mut out);
        let mut object = Object::new(&mut text).unwrap();
        object.flatten(&Nothing {}).unwrap();
        object.flatten(&Head { a: 1, b: "x\"y" }).unwrap();
        object.flatten(&Nothing {}).unwrap();
        object.serialize_entry("c", &[0.5, -0.0, 0.0]).unwrap();
        object.raw("d", |t| t.with(|b| numbers(b, &long))).unwrap();
        object.raw("e", |t| t.with(|b| numbers(b, &[2.0]))).unwrap();
        object.end().unwrap();
        text.finish().unwrap();
        let expected =
            serde_json::json!({"a": 1, "b": "x\"y", "c": [0.5, -0.0, 0.0], "d": long, "e": [2.0]});
        assert_eq!(String::from_utf8(out).unwrap(), serde(&expected));
        let mut out = Vec::new();
        let mut text = Text::new(&mut out);
        Object::new(&mut text).unwrap().end().unwrap();
        text.finish().unwrap();
        assert_eq!(out, b"{}");
        // A number as a key is refused (serde_json quotes it; written bare it is no JSON).
        let mut out = Vec::new();
        let mut text = Text::new(&mut out);
        let mut object = Object::new(&mut text).unwrap();
        assert!(object.serialize_entry(&7, &1.0).is_err());
    }
}
