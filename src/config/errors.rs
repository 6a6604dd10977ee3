//! Errors of configuration loading and validation.

use std::path::PathBuf;

/// Why a configuration was refused. Every message names the file (or source), the field and
/// the offending value.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ConfigError {
    /// The file could not be read.
    #[error("cannot read configuration {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The text is not well-formed XML.
    #[error("{file}:{line}:{column}: malformed XML: {message}")]
    Malformed {
        /// The file.
        file: String,
        /// 1-based line of the error.
        line: usize,
        /// 1-based column (in characters) of the error.
        column: usize,
        /// What the XML parser said.
        message: String,
    },
    /// Well-formed XML that does not follow the schema (e.g. an unknown element).
    #[error("{file}: {message} (see docs/CONFIG.md for the schema)")]
    Schema {
        /// The file.
        file: String,
        /// What is wrong.
        message: String,
    },
    /// A required element is absent.
    #[error("{file}: missing required element <{field}>")]
    Missing {
        /// The file.
        file: String,
        /// Path of the element, e.g. `levels/level[2]/rows`.
        field: String,
    },
    /// A level of the hierarchy is not listed.
    #[error("{file}: missing <level index=\"{index}\"> in <levels>: height {height} needs levels 0 to {}, {listed} listed", height - 1)]
    MissingLevel {
        /// The file.
        file: String,
        /// The first missing index.
        index: usize,
        /// The configured height.
        height: usize,
        /// The number of `<level>` elements.
        listed: usize,
    },
    /// A value is unparsable or out of range.
    #[error("{file}: invalid value {value:?} for <{field}>: {reason}")]
    Invalid {
        /// The file.
        file: String,
        /// Path of the element.
        field: String,
        /// The value as written.
        value: String,
        /// What is expected.
        reason: String,
    },
    /// A setting this implementation no longer offers.
    #[error("{file}: <{field}> was retired: {now} (docs/CONFIG.md, \"Retired settings\")")]
    Retired {
        /// The file.
        file: String,
        /// Path of the element.
        field: String,
        /// What it is now.
        now: String,
    },
    /// A setting the chosen algorithm does not read.
    #[error("{file}: <{field}> is read only by algorithm {reads}, not by the chosen algorithm {chosen}; remove it (docs/CONFIG.md)")]
    NotRead {
        /// The file.
        file: String,
        /// Path of the element.
        field: String,
        /// The algorithm that reads it.
        reads: String,
        /// The configuration's algorithm.
        chosen: String,
    },
}
