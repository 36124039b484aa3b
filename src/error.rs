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

    /// A blade or aerodynamic definition file (BeamDyn, HAWC2, AeroDyn, ElastoDyn, polar) that
    /// could not be read or does not say what it must: the file, the line (1-based; 0 when the
    /// problem is the file as a whole) and what was expected there.
    #[error("{}", format_location(path, *line, message))]
    Format {
        path: String,
        line: usize,
        message: String,
    },

    /// A command-line argument that is malformed (e.g. `--set` without `=`, a bad range).
    #[error("{0}")]
    Usage(String),

    /// A numerical failure: non-finite matrices, no convergence, singular systems.
    #[error("numerical: {0}")]
    Numerical(String),

    /// A computation stopped because a newer request replaced it (the explorer's worker).
    #[error("cancelled: a newer request replaced this one")]
    Cancelled,

    /// File-system and output errors.
    #[error("{0}")]
    Io(String),
}

fn format_location(path: &str, line: usize, message: &str) -> String {
    if line == 0 {
        format!("{path}: {message}")
    } else {
        format!("{path}:{line}: {message}")
    }
}

impl Error {
    pub fn numerical(msg: impl Into<String>) -> Self {
        Error::Numerical(msg.into())
    }
    pub fn usage(msg: impl Into<String>) -> Self {
        Error::Usage(msg.into())
    }
    /// A numerical error prefixed with where it happened (`at`: the operating point, the values
    /// being varied), so the user knows which point to look at; other errors already name their
    /// origin and are returned unchanged, as is one already prefixed with the same place (a
    /// solver and its command may both add it).
    pub fn at(self, at: impl std::fmt::Display) -> Self {
        match self {
            Error::Numerical(m) => {
                let at = at.to_string();
                if m.starts_with(&format!("{at}: ")) {
                    Error::Numerical(m)
                } else {
                    Error::Numerical(format!("{at}: {m}"))
                }
            }
            e => e,
        }
    }
    /// A [`Error::Format`] at `line` of `path`.
    pub fn format(path: impl Into<String>, line: usize, message: impl Into<String>) -> Self {
        Error::Format {
            path: path.into(),
            line,
            message: message.into(),
        }
    }
}

pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    use super::Error;

    #[test]
    fn a_place_is_named_once() {
        let e = Error::numerical("Newton stalled").at("33 rpm").at("33 rpm");
        assert_eq!(
            e.to_string(),
            Error::numerical("33 rpm: Newton stalled").to_string()
        );
        // A different place still nests: the search's values around the operating point.
        let e = e.at("rotor speed = 33");
        assert!(e
            .to_string()
            .contains("rotor speed = 33: 33 rpm: Newton stalled"));
    }
}
