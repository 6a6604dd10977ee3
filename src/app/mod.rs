//! One way in: the library's user-level operations on files and values, each one function
//! that the `cosco` binary and the Python package (`python/`) both call, so that the checks
//! and messages are the same from either. Needs no simulator: where an operation can use the
//! simulated arm (`cosco evaluate`'s wrist paths), the caller passes it in. It only calls
//! down: the rooms below it never reach up into it.
//!
//! - [`files`]: the configuration ([`crate::config`]'s, or its built-in default),
//!   demonstration files ([`crate::demo_sets`]), model files, reproduction files.
//! - [`train`]: train one gesture or several, from values or from files.
//! - [`reproduce`]: reproduce from an initial posture, resume after a reading, continue a
//!   prefix, step in the loop; the reproduction CSV.
//! - [`recognize`]: recognise demonstration files with a model of several gestures.
//! - [`evaluate`]: a reproduction's fidelity against demonstrations; `cosco inspect`'s lines.
//! - [`export`]: a reproduction to a robot's formats, and demonstrations from a ROS 2 bag.
//!
//! Each value is checked once, where it enters: a file's layout and columns when it is read,
//! an initial posture by the hierarchy ([`Hsom::reproduce`](crate::hsom::Hsom::reproduce)),
//! whose error this layer names the model on. Every error is an [`Error`], naming the file,
//! field or option and what is allowed.
//!
//! ```
//! use cosco_hsom::app;
//! use cosco_hsom::config::HsomParams;
//! let mut p = HsomParams::table1();
//! p.state_length = 2;
//! p.action_length = 2;
//! p.training_steps = 200;
//! let cfg = p.check("example").unwrap();
//! let rows: Vec<Vec<f64>> = (0..30).map(|i| vec![i as f64 / 30.0, 0.5]).collect();
//! let demos = app::demonstrations_from_rows(vec![rows.clone(), rows], None).unwrap();
//! let model = app::train(&cfg, &demos, None).unwrap();
//! assert_eq!(model.columns(), ["x0", "x1"]);
//! let e = app::reproduce(&model, "in memory", None, &[0.0], None).unwrap_err();
//! assert!(e.to_string().contains("the initial posture has 1 values; the model in memory learned 2"));
//! ```

pub mod evaluate;
pub mod export;
pub mod files;
pub mod recognize;
pub mod reproduce;
pub mod train;

#[cfg(test)]
mod tests;

use std::path::PathBuf;

pub use evaluate::{evaluate_files, inspect, Evaluation};
#[cfg(feature = "ros2")]
pub use export::import;
pub use export::{export, own_contacts, ExportFrom};
pub use files::{
    check_model_output, config, demonstrations_from_rows, load_gesture_model, read_demos,
    read_reproduction, save_gesture_model,
};
pub use recognize::{
    answer_line, recognize_files, recognize_paths, recognize_stream, RecognisedFile,
};
pub use reproduce::{
    aimed, aimed_stepper, conditions, continue_file, reproduce, reproduce_file, resume, stepper,
    with_duration, ReproduceFile, ReproduceRequest,
};
pub use train::{train, train_files, update, update_files};

pub use crate::errors::error_line;

/// Why an operation was refused. The wrapped errors name their file, field and value; the
/// others name them here, with what is allowed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The configuration was refused.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// A demonstration was refused.
    #[error(transparent)]
    Demo(#[from] crate::demos::DemoError),
    /// Training or reproduction was refused.
    #[error(transparent)]
    Hsom(#[from] crate::hsom::HsomError),
    /// A goal or via-point was refused.
    #[error(transparent)]
    Condition(#[from] crate::condition::ConditionError),
    /// A target to point or look at was refused.
    #[error(transparent)]
    Aim(#[from] crate::aim::AimError),
    /// A stepper refused a posture or a goal, or could not re-plan.
    #[error(transparent)]
    Stepper(#[from] crate::stepper::StepperError),
    /// A model of several gestures refused a label, a set or a sequence.
    #[error(transparent)]
    Gesture(#[from] crate::hsom::GestureError),
    /// A model file could not be saved or loaded.
    #[error(transparent)]
    Persist(#[from] crate::hsom::PersistError),
    /// Exporting a trajectory or importing a bag was refused.
    #[error(transparent)]
    Export(#[from] crate::export::ExportError),
    /// An output cannot be written where it was asked.
    #[error(transparent)]
    Output(#[from] crate::fsutil::NotWritable),
    /// A file or directory that cannot be used as given: its extension, its place, its
    /// layout or its columns.
    #[error("{path}: {reason}")]
    File {
        /// The file or directory.
        path: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// A value that is not allowed: an option's, an initial posture, column names.
    #[error("{what} {reason}")]
    Value {
        /// The value (`--initial:`, `the initial posture`, `columns:`).
        what: String,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// An output file could not be written.
    #[error("writing {}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Resuming after an encoder reading failed.
    #[error("resuming after {}", path.display())]
    Resume {
        /// The encoder reading.
        path: PathBuf,
        /// The cause.
        source: Box<Error>,
    },
    /// A reproduction could not be scored against its demonstrations.
    #[error("{}: scoring it against the demonstrations", path.display())]
    Evaluate {
        /// The reproduction file.
        path: PathBuf,
        /// The cause.
        source: evaluate::BoxError,
    },
}

impl Error {
    /// [`Error::File`]: `path` cannot be used, `reason` says why and what is allowed.
    pub(crate) fn file(path: &std::path::Path, reason: impl Into<String>) -> Error {
        Error::File {
            path: path.display().to_string(),
            reason: reason.into(),
        }
    }

    /// [`Error::Value`]: `what` is not allowed, `reason` says why and what is.
    pub fn value(what: impl Into<String>, reason: impl Into<String>) -> Error {
        Error::Value {
            what: what.into(),
            reason: reason.into(),
        }
    }
}

/// The result of an operation.
pub type Result<T> = std::result::Result<T, Error>;
