//! Errors of training, reproduction, save and load.

use std::path::PathBuf;

/// Why training or reproduction was refused.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HsomError {
    /// A goal or via-point that cannot be met ([`crate::condition::Conditions::check`]).
    #[error(transparent)]
    Condition(#[from] crate::condition::ConditionError),
    /// Settings out of their documented range, or a configuration its model's part does not
    /// fit.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// No demonstration was given.
    #[error("no demonstrations to train on")]
    NoDemonstrations,
    /// An update's demonstration records other variables than the model learned.
    #[error("demonstration {demo} has columns {found:?}, but the model learned {expected:?}: an update takes demonstrations of the same variables in the same order")]
    UpdateColumns {
        /// The demonstration's source.
        demo: String,
        /// Its columns.
        found: Vec<String>,
        /// The model's.
        expected: Vec<String>,
    },
    /// An update's demonstration is sampled at another rate than the model's.
    #[error("demonstration {demo} is sampled every {found} s, but the model learned demonstrations sampled every {expected} s: an update takes the same rate (within 1 %; resample it, e.g. `cosco train --resample`)")]
    UpdatePeriod {
        /// The demonstration's source.
        demo: String,
        /// Its median sample period, seconds.
        found: f64,
        /// The model's.
        expected: f64,
    },
    /// An update that would count more demonstrations learned from than a model may
    /// ([`MAX_LEARNED`](crate::hsom::MAX_LEARNED)).
    #[error("{of} learned from {learned} demonstrations (learned); {new} more would pass {most}, the most a model counts")]
    TooManyLearned {
        /// `the model` or `gesture "LABEL"`.
        of: String,
        /// Demonstrations learned from.
        learned: u64,
        /// Demonstrations the update brings.
        new: usize,
        /// The most a model counts.
        most: u64,
    },
    /// The operation needs another algorithm than the model's.
    #[error("{what} needs a model trained with algorithm = events (this one: {algorithm})")]
    NeedsEvents {
        /// What was asked.
        what: String,
        /// The model's algorithm.
        algorithm: String,
    },
    /// A reading is too long to align with the plan it is a reading of.
    #[error("the reading has {rows} samples; at most {most} can be aligned with this model's plan of {plan} (a bound on the work of one alignment)")]
    ReadingTooLong {
        /// Samples of the reading.
        rows: usize,
        /// The most that can be aligned with this plan.
        most: usize,
        /// Samples of the plan.
        plan: usize,
    },
    /// A demonstration is too short for one state-action pair at the configuration's
    /// action horizon.
    #[error("demonstration {demo} has {rows} sample(s); at least {needed} are needed (actionHorizon + 1, and never fewer than 2)")]
    TooShort {
        /// The demonstration's source.
        demo: String,
        /// Its number of samples.
        rows: usize,
        /// The fewest samples accepted.
        needed: usize,
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
    /// A value too large to train on once normalised (distances would overflow).
    #[error("demonstration {demo}, sample {row}, column {column}: {value:e} is {normalised:e} once normalised; training needs magnitudes of at most 1e100 (use normalisation global or perDimension, or rescale the data)")]
    OutOfScale {
        /// The demonstration's source.
        demo: String,
        /// Sample index.
        row: usize,
        /// Column index.
        column: usize,
        /// The value in the data.
        value: f64,
        /// The value after normalisation (may be infinite when the data's range overflows).
        normalised: f64,
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
    /// A model file of a newer format version than this program reads.
    #[error("{path}: model format version {found} was written by a newer version of cosco-hsom; this program reads version {expected}: update it, or retrain the model with this version (`cosco train`)")]
    Newer {
        /// The file.
        path: PathBuf,
        /// Version in the file.
        found: u32,
        /// Supported version.
        expected: u32,
    },
    /// A model file of another kind than asked for (one gesture, several).
    #[error("{path}: the file holds a model of kind {found}; {expected} expected (a model of several gestures loads with GestureModel::load and the `cosco` commands)")]
    Kind {
        /// The file.
        path: PathBuf,
        /// The kind in the file's header.
        found: String,
        /// The kinds accepted.
        expected: String,
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

/// Why a multi-gesture step was refused.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GestureError {
    /// A label the model does not hold.
    #[error("no gesture {label:?} in the model; it holds: {labels}")]
    UnknownLabel {
        /// The label asked for.
        label: String,
        /// The model's labels, comma-separated.
        labels: String,
    },
    /// A multi-gesture model asked to reproduce without a label.
    #[error("the model holds several gestures ({labels}): choose one with --gesture NAME (or gesture=NAME)")]
    LabelNeeded {
        /// The model's labels, comma-separated.
        labels: String,
    },
    /// Recognition asked of a model without labels.
    #[error("a single-gesture model has no labels to recognise: train on labelled directories (demos/<label>/*.csv)")]
    NoLabels,
    /// A model of several gestures read from a file of an older format: its thresholds are
    /// calibrated on another score.
    #[error("the model's recognition thresholds were calibrated by an older version's score (model format 26): retrain it with `cosco train` to recognise with it (it still reproduces every gesture)")]
    Recalibrate,
    /// A label that is not a plain word.
    #[error("gesture label {label:?} (from {source_dir}) is not a plain word: use letters, digits, '_' and '-' only")]
    BadLabel {
        /// The label.
        label: String,
        /// Where it came from (a directory, or `in memory`).
        source_dir: String,
    },
    /// The same label given twice.
    #[error("gesture label {label:?} is given twice")]
    DuplicateLabel {
        /// The label.
        label: String,
    },
    /// A label without demonstrations.
    #[error("gesture {label:?} has no demonstrations")]
    EmptyLabel {
        /// The label.
        label: String,
    },
    /// Labelled sets that are not valid as sets: gestures recording different variables
    /// ([`check_gesture_columns`](crate::demos::check_gesture_columns)).
    #[error(transparent)]
    Demo(#[from] crate::demos::DemoError),
    /// Several gestures need the events extension (the paper's procedure trains every level
    /// at once, so its upper levels cannot be split by label).
    #[error("several gestures need algorithm = events (configs/nao-gestures.xml); this configuration uses the paper's algorithm")]
    NeedsEvents,
    /// Labelled demonstrations given to a model of one unlabelled gesture.
    #[error("the model holds one unlabelled gesture: teach it a directory of CSV files, not labelled directories (train on labelled directories, DIR/<label>/*.csv, to teach several gestures)")]
    UnlabelledUpdate,
    /// Training or reproduction was refused.
    #[error(transparent)]
    Hsom(#[from] HsomError),
    /// A model file could not be saved or loaded.
    #[error(transparent)]
    Persist(#[from] PersistError),
}
