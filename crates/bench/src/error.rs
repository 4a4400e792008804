//! Errors of the benchmark harness: every one names the file (and, for scenario files, the
//! line and key) it came from.

use std::path::PathBuf;

/// What can go wrong while reading a scenario, running trials or writing results.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The scenario file is not valid TOML or does not fit the schema (toml's message
    /// carries the line, column and key).
    #[error("{file}: {message}")]
    Toml {
        /// The scenario file (or `suite:NAME`).
        file: String,
        /// toml's message, with line and column.
        message: String,
    },
    /// A value in the scenario file is not acceptable (`FILE:LINE: key ...`, or
    /// `FILE: key ...` when the key is missing and so has no line).
    #[error("{file}{}: key `{key}`: {message}", .line.map_or(String::new(), |l| format!(":{l}")))]
    Scenario {
        /// The scenario file (or `suite:NAME`).
        file: String,
        /// 1-based line of the offending value (`None` when the key is missing).
        line: Option<usize>,
        /// The key, e.g. `strategies` or `env[2].map`.
        key: String,
        /// What is wrong.
        message: String,
    },
    /// Reading or writing a file failed.
    #[error("{path}: {cause}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause, already in the message: not a `#[source]`, or reporters that print
        /// the chain (`{:#}`) would repeat it.
        cause: std::io::Error,
    },
    /// A file is not of the kind expected (a directory, a device, too large), found before
    /// it is read.
    #[error("{path}: {message}")]
    File {
        /// The file.
        path: PathBuf,
        /// What was expected and what was found.
        message: String,
    },
    /// The results database failed.
    #[error("{path}: {cause}")]
    Sql {
        /// The database file.
        path: PathBuf,
        /// The cause, already in the message: not a `#[source]`, or reporters that print
        /// the chain (`{:#}`) would repeat it and SQLite's own wording of it.
        cause: rusqlite::Error,
    },
    /// A database does not hold what is expected (another scenario, a foreign schema).
    #[error("{path}: {message}")]
    Store {
        /// The database file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// Anything else, described in words (bad command-line values, plotting failures).
    #[error("{0}")]
    Other(String),
}

impl BenchError {
    /// An SQLite error on `path`.
    pub fn sql(path: &std::path::Path) -> impl FnOnce(rusqlite::Error) -> BenchError + '_ {
        move |cause| BenchError::Sql {
            path: path.to_path_buf(),
            cause,
        }
    }

    /// An I/O error on `path`.
    pub fn io(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> BenchError + '_ {
        move |cause| BenchError::Io {
            path: path.to_path_buf(),
            cause,
        }
    }
}
