//! One error type for every caller mistake. Each message says what was wrong, where, and what to
//! do, because it is often shown as-is to the end user of a web page or a command line.

use std::fmt;

/// Everything that can go wrong when building, refining, reading or writing a mesh.
#[derive(Clone, Debug, PartialEq)]
pub enum Error {
    /// The flat input arrays do not describe a mesh.
    InvalidMesh(String),
    /// An OBJ file could not be read; `line` is 1-based.
    Obj { line: usize, message: String },
    /// An option has a value the library does not know.
    InvalidOption(String),
    /// A crease, corner or hole tag names something the mesh does not have, or a sharpness is
    /// negative or NaN. The message names the tag.
    InvalidTag(String),
    /// An attribute channel does not fit the mesh, or its values are not finite. The message
    /// names the channel.
    InvalidAttribute(String),
    /// The mesh is valid but the chosen scheme is not defined on it.
    Unsupported(String),
    /// The predicted output exceeds the configured memory guard.
    TooLarge(String),
    /// Reading or writing a file failed.
    Io(String),
    /// The caller's progress callback asked the call to stop (see
    /// [`crate::scheme::Progress`]); the message says after which level.
    Cancelled(String),
}

impl Error {
    pub(crate) fn mesh(message: impl Into<String>) -> Self {
        Error::InvalidMesh(message.into())
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidMesh(m) => write!(f, "invalid mesh: {m}"),
            Error::Obj { line, message } => write!(f, "OBJ line {line}: {message}"),
            Error::InvalidOption(m) => write!(f, "invalid option: {m}"),
            Error::InvalidTag(m) => write!(f, "invalid tag: {m}"),
            Error::InvalidAttribute(m) => write!(f, "invalid attribute: {m}"),
            Error::Unsupported(m) => write!(f, "unsupported input: {m}"),
            Error::TooLarge(m) => write!(f, "output too large: {m}"),
            Error::Io(m) => write!(f, "{m}"),
            Error::Cancelled(m) => write!(f, "cancelled: {m}"),
        }
    }
}

impl std::error::Error for Error {}

pub type Result<T> = std::result::Result<T, Error>;
