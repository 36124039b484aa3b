//! One error type for the whole engine. Every message names what was wrong and, for input,
//! where it came from (file, key, value, allowed range), so the CLI and the explorer can show it
//! as is.

use thiserror::Error;

#[derive(Debug, Error, Clone, PartialEq)]
pub enum Error {
    /// A preset that could not be read or parsed (TOML syntax, unknown field, wrong type).
    #[error("{origin}: {message}")]
    Preset { origin: String, message: String },

    /// A value outside its allowed range.
    #[error("{origin}: {key} = {value} is out of range (allowed: {allowed})")]
    Range {
        origin: String,
        key: String,
        value: String,
        allowed: String,
    },

    /// A value that is allowed on its own but not together with others (e.g. a layup whose
    /// Poisson ratios give a non-positive determinant).
    #[error("{origin}: {message}")]
    Invalid { origin: String, message: String },

    /// A command-line argument that is malformed (e.g. `--set` without `=`, a bad range).
    #[error("{0}")]
    Usage(String),

    /// A numerical failure: non-finite matrices, no convergence, singular systems.
    #[error("numerical: {0}")]
    Numerical(String),

    /// File-system and output errors.
    #[error("{0}")]
    Io(String),
}

impl Error {
    pub fn numerical(msg: impl Into<String>) -> Self {
        Error::Numerical(msg.into())
    }
    pub fn usage(msg: impl Into<String>) -> Self {
        Error::Usage(msg.into())
    }
}

pub type Result<T> = std::result::Result<T, Error>;
