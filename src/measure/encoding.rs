//! The text of a measured-points file from its bytes. A CMM or CAD program on Windows writes
//! its comments, labels and drawing texts in the machine's code page, not UTF-8: an R12 DXF
//! declares it in the header variable `$DWGCODEPAGE` (`ANSI_1252`, Western European), and a
//! DXF of AutoCAD 2007 or later is UTF-8 whatever that variable says.
//!
//! The rule: UTF-8 text is read as it is (a leading byte-order mark dropped); otherwise a DXF
//! whose `$DWGCODEPAGE` is `ANSI_1252` is decoded as Windows-1252 (the WHATWG Encoding
//! Standard's table), and any other file has each byte sequence that is not UTF-8 replaced by
//! U+FFFD. Either way the ASCII bytes, and so the line breaks, the group codes, the numbers and
//! the layer names the reader uses, are read as they are: a byte of another code page can only
//! be in a text the reader ignores, and in a number it makes the number unreadable (refused at
//! its line), never another number.

/// The characters of the bytes 0x80–0x9F in Windows-1252 (WHATWG `index-windows-1252`; the
/// five bytes it leaves undefined map to the C1 controls of the same value). 0xA0–0xFF are
/// U+00A0–U+00FF.
const WINDOWS_1252_80_9F: [char; 32] = [
    '\u{20AC}', '\u{81}', '\u{201A}', '\u{192}', '\u{201E}', '\u{2026}', '\u{2020}', '\u{2021}',
    '\u{2C6}', '\u{2030}', '\u{160}', '\u{2039}', '\u{152}', '\u{8D}', '\u{17D}', '\u{8F}',
    '\u{90}', '\u{2018}', '\u{2019}', '\u{201C}', '\u{201D}', '\u{2022}', '\u{2013}', '\u{2014}',
    '\u{2DC}', '\u{2122}', '\u{161}', '\u{203A}', '\u{153}', '\u{9D}', '\u{17E}', '\u{178}',
];

/// How a file that is not UTF-8 is decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fallback {
    /// Windows-1252 (a DXF of `$DWGCODEPAGE` `ANSI_1252`).
    Windows1252,
    /// Bytes that are not UTF-8 become U+FFFD.
    Replace,
}

/// The text of `bytes`: UTF-8 when it is (without a leading byte-order mark), else decoded as
/// `fallback` says.
pub fn decode(bytes: &[u8], fallback: Fallback) -> String {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(text) => text.to_string(),
        Err(_) if fallback == Fallback::Windows1252 => {
            bytes.iter().map(|&b| windows_1252(b)).collect()
        }
        Err(_) => String::from_utf8_lossy(bytes).into_owned(),
    }
}

/// The character of one Windows-1252 byte.
pub fn windows_1252(b: u8) -> char {
    match b {
        0x80..=0x9F => WINDOWS_1252_80_9F[(b - 0x80) as usize],
        _ => char::from(b),
    }
}

/// The fallback of a DXF file: the code page its header declares (`9 $DWGCODEPAGE`, then
/// group 3 with the name), read on its ASCII lines.
pub fn dxf_fallback(bytes: &[u8]) -> Fallback {
    let mut lines = bytes.split(|&b| b == b'\n').map(|l| l.trim_ascii());
    while let Some(line) = lines.next() {
        if line == b"$DWGCODEPAGE" {
            let _code = lines.next();
            if lines
                .next()
                .is_some_and(|v| v.eq_ignore_ascii_case(b"ANSI_1252"))
            {
                return Fallback::Windows1252;
            }
            break;
        }
        if line == b"ENTITIES" {
            break;
        }
    }
    Fallback::Replace
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Windows-1252 against characters whose code points are known independently: Ø is
    /// U+00D8 (Latin-1 Supplement, the byte's own value), € is U+20AC at 0x80, µ is U+00B5;
    /// ASCII is itself.
    #[test]
    fn windows_1252_decodes_the_known_characters() {
        assert_eq!(windows_1252(0xD8), 'Ø');
        assert_eq!(windows_1252(0x80), '€');
        assert_eq!(windows_1252(0xB5), 'µ');
        assert_eq!(windows_1252(b'7'), '7');
        let text = decode(b"1\n\xD8 18 H7\n10\n2.5\n", Fallback::Windows1252);
        assert_eq!(text, "1\nØ 18 H7\n10\n2.5\n");
    }

    /// UTF-8 stays UTF-8 even where the header names a code page (AutoCAD 2007 and later);
    /// without a known code page a stray byte becomes U+FFFD and takes no ASCII byte with it.
    #[test]
    fn utf8_is_kept_and_other_bytes_never_swallow_ascii() {
        assert_eq!(decode("Ø 18".as_bytes(), Fallback::Windows1252), "Ø 18");
        assert_eq!(decode(b"\xEF\xBB\xBFx", Fallback::Replace), "x");
        assert_eq!(
            decode(b"\xD8 1.5\n\xC3", Fallback::Replace),
            "\u{FFFD} 1.5\n\u{FFFD}"
        );
    }

    /// The code page is read from the header, case-insensitively, with CR-LF line ends.
    #[test]
    fn the_code_page_comes_from_the_header() {
        let dxf = b"0\r\nSECTION\r\n2\r\nHEADER\r\n9\r\n$DWGCODEPAGE\r\n3\r\nansi_1252\r\n";
        assert_eq!(dxf_fallback(dxf), Fallback::Windows1252);
        assert_eq!(
            dxf_fallback(b"9\n$DWGCODEPAGE\n3\nANSI_932\n"),
            Fallback::Replace
        );
        assert_eq!(
            dxf_fallback(b"0\nSECTION\n2\nENTITIES\n"),
            Fallback::Replace
        );
    }
}
