//! Errors: a kind plus, where known, a source location. Rendered in one place (`Display`).
//!
//! Every error maps to exit code 2 in `main`; a failed *check* is not an error (exit 1).

use std::fmt;

/// A position in a spec file, 1-based as editors show it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    pub file: String,
    pub line: usize,
    pub column: usize,
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
}

impl ErrorKind {
    fn label(self) -> &'static str {
        match self {
            ErrorKind::Io => "i/o error",
            ErrorKind::Syntax => "spec error",
            ErrorKind::InvalidValue => "invalid value",
            ErrorKind::ImpossibleDesign => "impossible design",
            ErrorKind::Computation => "computation failed",
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Error {
    pub kind: ErrorKind,
    pub message: String,
    /// Dotted key path in the spec (`reducer.roller_radius_mm`), when the error is about a key.
    pub key_path: Option<String>,
    pub location: Option<Location>,
}

impl Error {
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Error {
            kind,
            message: message.into(),
            key_path: None,
            location: None,
        }
    }

    pub fn at_key(mut self, key_path: impl Into<String>) -> Self {
        self.key_path = Some(key_path.into());
        self
    }

    pub fn at(mut self, location: Location) -> Self {
        self.location = Some(location);
        self
    }

    pub fn io(path: &str, err: std::io::Error) -> Self {
        Error::new(ErrorKind::Io, format!("{path}: {err}"))
    }

    pub fn computation(message: impl Into<String>) -> Self {
        Error::new(ErrorKind::Computation, message)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(loc) = &self.location {
            write!(f, "{}:{}:{}: ", loc.file, loc.line, loc.column)?;
        }
        write!(f, "{}: ", self.kind.label())?;
        if let Some(path) = &self.key_path {
            write!(f, "{path}: ")?;
        }
        write!(f, "{}", self.message)
    }
}

impl std::error::Error for Error {}

pub type Result<T> = std::result::Result<T, Error>;
