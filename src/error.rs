//! Errors: a kind plus, where known, a source location. Rendered in one place (`Display`).
//!
//! Every error maps to exit code 2 in `main`; a failed *check* is not an error (exit 1).

use std::fmt;

/// A position in a spec file, 1-based as editors show it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file's path, as it was given.
    pub file: String,
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1 (1 when only the line is known).
    pub column: usize,
}

impl Location {
    /// Line `line`, column `column` of the file `file`.
    pub fn new(file: &str, line: usize, column: usize) -> Location {
        let file = file.to_string();
        Location { file, line, column }
    }
}

/// What went wrong, in the user's terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// The file could not be read or written.
    Io,
    /// YAML syntax, a wrong type or an unknown key.
    Syntax,
    /// A value that no design can have (non-positive size, unknown effect, empty crank range).
    InvalidValue,
    /// A design rule that the geometry breaks (undercut, overlap, K1 >= 1, ...).
    ImpossibleDesign,
    /// A solver that did not converge, or produced a non-finite number.
    Computation,
    /// Command-line options that contradict each other (two outputs at one path, an output
    /// that is an input): nothing was written.
    Usage,
    /// Standard output was closed by its reader (`cycloid check … | head`): not a failure, the
    /// run stops quietly with exit 0 and writes no file.
    OutputClosed,
}

impl ErrorKind {
    fn label(self) -> &'static str {
        match self {
            ErrorKind::Io => "i/o error",
            ErrorKind::Syntax => "spec error",
            ErrorKind::InvalidValue => "invalid value",
            ErrorKind::ImpossibleDesign => "impossible design",
            ErrorKind::Computation => "computation failed",
            ErrorKind::Usage => "usage error",
            ErrorKind::OutputClosed => "output closed",
        }
    }
}

/// The library's one error: what went wrong ([`ErrorKind`]), a message, and where, when it is
/// known (a key path in the spec, a file position). `Display` writes it as
/// `file:line:column: kind: key.path: message`.
#[derive(Debug, Clone, PartialEq)]
pub struct Error {
    /// What went wrong, in the user's terms.
    pub kind: ErrorKind,
    /// The explanation, in the user's terms (without the kind, the key path or the location).
    pub message: String,
    /// Dotted key path in the spec (`reducer.roller_radius_mm`), when the error is about a key.
    pub key_path: Option<String>,
    /// Where in a file, when known.
    pub location: Option<Location>,
}

impl Error {
    /// An error of `kind` with `message`, not yet located.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Error {
            kind,
            message: message.into(),
            key_path: None,
            location: None,
        }
    }

    /// The same error, about the spec key `key_path` (dotted: `scenes[0].crank.steps`).
    pub fn at_key(mut self, key_path: impl Into<String>) -> Self {
        self.key_path = Some(key_path.into());
        self
    }

    /// The same error, located at `location`.
    pub fn at(mut self, location: Location) -> Self {
        self.location = Some(location);
        self
    }

    /// An [`ErrorKind::Io`] error about the file at `path`.
    pub fn io(path: &str, err: std::io::Error) -> Self {
        Error::new(ErrorKind::Io, format!("{path}: {err}"))
    }

    /// An invalid value of the spec key `key_path` (located in the spec by `spec`).
    pub fn invalid(key_path: impl Into<String>, message: String) -> Self {
        Error::new(ErrorKind::InvalidValue, message).at_key(key_path)
    }

    /// An [`ErrorKind::InvalidValue`] error about no spec key: a flag's value, or a refusal of
    /// the spec or a file as a whole.
    pub fn invalid_value(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::InvalidValue, message)
    }

    /// An [`ErrorKind::Computation`] error: a computation that could not give its result.
    pub fn computation(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::Computation, message)
    }
}

impl fmt::Display for Error {
    /// `file:line:column: kind: key.path: message`, with control characters escaped: names
    /// and paths come from the user and must not drive the terminal.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(loc) = &self.location {
            write!(
                f,
                "{}:{}:{}: ",
                printable(&loc.file, &[]),
                loc.line,
                loc.column
            )?;
        }
        write!(f, "{}: ", self.kind.label())?;
        if let Some(path) = &self.key_path {
            write!(f, "{}: ", printable(path, &[]))?;
        }
        write!(f, "{}", printable(&self.message, &[]))
    }
}

/// Whether a character can change what a terminal shows beyond itself: control characters
/// (escape sequences, carriage return, backspace) and the bidirectional overrides that reorder
/// text. Line feeds and tabs are layout, not control.
fn controls(c: char) -> bool {
    (c.is_control() && c != '\n' && c != '\t')
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// Text for a terminal: every control character escaped as Rust writes it (`\u{1b}`), except
/// the sequences in `keep` (the tool's own colours), which pass unchanged.
pub fn printable<'a>(text: &'a str, keep: &[&str]) -> std::borrow::Cow<'a, str> {
    if !text.chars().any(controls) {
        return text.into();
    }
    let mut out = String::with_capacity(text.len() + 16);
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if let Some(k) = keep.iter().find(|k| rest.starts_with(**k)) {
            out.push_str(k);
            rest = &rest[k.len()..];
            continue;
        }
        if controls(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
        rest = &rest[c.len_utf8()..];
    }
    out.into()
}

impl std::error::Error for Error {}

/// A result whose error is the library's [`Error`].
pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    use super::*;

    /// Escape sequences, carriage returns and bidi overrides are shown, not obeyed; line
    /// breaks, tabs, ordinary Unicode and the kept colour codes pass unchanged.
    #[test]
    fn control_characters_are_escaped() {
        assert_eq!(printable("a\u{1b}[2Jb\rc", &[]), "a\\u{1b}[2Jb\\u{d}c");
        assert_eq!(printable("x\u{202e}y", &[]), "x\\u{202e}y");
        assert_eq!(printable("ΔRp 12°\n\tok", &[]), "ΔRp 12°\n\tok");
        assert_eq!(
            printable(
                "\u{1b}[32mpass\u{1b}[0m\u{1b}[31m",
                &["\u{1b}[32m", "\u{1b}[0m"]
            ),
            "\u{1b}[32mpass\u{1b}[0m\\u{1b}[31m"
        );
    }
}
