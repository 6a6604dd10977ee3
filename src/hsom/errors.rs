//! Errors of training, reproduction, save and load.

use std::path::PathBuf;

/// Why training or reproduction was refused.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HsomError {
    /// No demonstration was given.
    #[error("no demonstrations to train on")]
    NoDemonstrations,
    /// A demonstration has fewer than two samples (no state-action pair).
    #[error("demonstration {demo} has {rows} sample(s); at least 2 are needed")]
    TooShort {
        /// The demonstration's source.
        demo: String,
        /// Its number of samples.
        rows: usize,
    },
    /// A sample has another number of values than the configuration's stateLength.
    #[error("demonstration {demo}, sample {row}: {found} values, but the configuration's stateLength is {expected}")]
    DimensionMismatch {
        /// The demonstration's source (or "initial posture").
        demo: String,
        /// Sample index.
        row: usize,
        /// stateLength.
        expected: usize,
        /// Found length.
        found: usize,
    },
    /// A NaN or infinite value.
    #[error("demonstration {demo}, sample {row}, column {column}: not a finite number")]
    NonFinite {
        /// The demonstration's source (or "initial posture").
        demo: String,
        /// Sample index.
        row: usize,
        /// Column index.
        column: usize,
    },
}

/// Why a model could not be saved or loaded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PersistError {
    /// Reading or writing failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Neither `.bin` nor `.txt`.
    #[error("{path}: unknown model file extension; use .bin (binary) or .txt (plain text)")]
    UnknownExtension {
        /// The file.
        path: PathBuf,
    },
    /// Not a CoSCo-HSOM model file.
    #[error("{path}: not a CoSCo-HSOM model file (bad magic/format line)")]
    BadMagic {
        /// The file.
        path: PathBuf,
    },
    /// A model file of another format version.
    #[error("{path}: model format version {found}, this program reads version {expected}: retrain the model with this version (`cosco train`)")]
    Version {
        /// The file.
        path: PathBuf,
        /// Version in the file.
        found: u32,
        /// Supported version.
        expected: u32,
    },
    /// The file ends early.
    #[error("{path}: truncated model file ({what})")]
    Truncated {
        /// The file.
        path: PathBuf,
        /// What was being read.
        what: String,
    },
    /// Sizes or values that contradict each other or the embedded configuration.
    #[error("{path}: corrupted or inconsistent model file: {what}")]
    Corrupted {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
}
