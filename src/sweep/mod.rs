//! Sweeps (`cosco sweep`, docs/SWEEPS.md): every combination of robots, gestures, seeds,
//! configurations, noise levels, numbers of demonstrations, height overrides, evaluations and
//! methods from one TOML spec, run on a thread pool or split into shards for a cluster's job
//! arrays, one JSON file per run, merged into tables and box plots.
//!
//! - [`spec`]: the spec file, checked up front; the grid in a fixed order.
//! - [`robots`]: the `robot` axis: the robots' names, default gestures, catalogues, models.
//! - [`shard`]: `--shard I/N` and SLURM's job-array variables.
//! - [`run`]: one run (the `simulate --no-render` pipeline) and its file.
//! - [`runner`]: the sweep: output-directory checks, resume, the thread pool.
//! - [`merge`](mod@merge): tables (Markdown, CSV), paired wins, box plots, failed runs.

pub mod merge;
pub mod robots;
pub mod run;
pub mod runner;
pub mod shard;
pub mod spec;

use std::path::{Path, PathBuf};

use serde::{de::DeserializeOwned, Serialize};

use crate::fsutil::write_atomic;

pub use crate::metrics::registry::SWEEP as METRICS;
pub use merge::{merge, MergeSummary, Stats};
pub use run::{execute_run, MethodRecord, RunRecord};
pub use runner::{run_sweep, Manifest, Progress, SweepOptions, SweepSummary};
pub use shard::Shard;
pub use spec::{method_name, AxisValues, Evaluation, Height, MethodAxis, RunPlan, SweepSpec, AXES};

/// Why a sweep or a merge refused to start or stopped. Every message names the file, field
/// or value and what is allowed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepError {
    /// The spec file is invalid.
    #[error("spec {file}: {message}")]
    Spec {
        /// The spec file.
        file: PathBuf,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// An option (shard, threads) is invalid.
    #[error("{0}")]
    Invalid(String),
    /// The output directory cannot be used for this spec.
    #[error("output directory {path}: {message}")]
    OutDir {
        /// The directory.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// A file of the sweep directory is unreadable or not what it should be.
    #[error("{path}: {message}")]
    Record {
        /// The file.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// Reading or writing failed.
    #[error("cannot {action} {path}: {source}")]
    Io {
        /// What was being done.
        action: &'static str,
        /// The file or directory.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A plot could not be drawn or written.
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

impl SweepError {
    /// The I/O error of `action` on `path` (for `map_err`).
    fn io(action: &'static str, path: &Path) -> impl FnOnce(std::io::Error) -> SweepError {
        let path = path.to_path_buf();
        move |source| SweepError::Io {
            action,
            path,
            source,
        }
    }
}

/// Read the JSON file `path` (`action` names the reading in an I/O error; `bad` says what is
/// wrong with a file that is not a `T`).
fn read_json<T: DeserializeOwned>(
    path: &Path,
    action: &'static str,
    bad: impl FnOnce(serde_json::Error) -> String,
) -> Result<T, SweepError> {
    let bytes = std::fs::read(path).map_err(SweepError::io(action, path))?;
    serde_json::from_slice(&bytes).map_err(|e| SweepError::Record {
        path: path.to_path_buf(),
        message: bad(e),
    })
}

/// Write `value` as pretty JSON to `path`, atomically (a killed sweep leaves the old file or
/// none, never half a file).
fn write_json(path: &Path, value: &impl Serialize, action: &'static str) -> Result<(), SweepError> {
    let json = serde_json::to_vec_pretty(value).map_err(|e| SweepError::Record {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    write_atomic(path, &json).map_err(SweepError::io(action, path))
}
