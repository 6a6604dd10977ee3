//! Errors of the GMM/GMR baseline.

use crate::demos::DemoError;
use crate::dtw::DtwError;

/// What can go wrong configuring, fitting, querying, saving or loading the baseline.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GmrError {
    /// A parameter is out of its valid range (checked once by `GmrParams::check`).
    #[error("invalid GMR parameter `{name}` = {value}: {reason}")]
    InvalidParam {
        /// Parameter name.
        name: &'static str,
        /// The rejected value, as text.
        value: String,
        /// What is allowed.
        reason: &'static str,
    },
    /// An initial posture that is not one finite value per column of the model.
    #[error("initial posture {found}: needs {expected} finite values ({columns})")]
    BadInitial {
        /// The posture given, as text.
        found: String,
        /// Values needed.
        expected: usize,
        /// The model's columns, comma-separated.
        columns: String,
    },
    /// Fewer demonstrations than the pipeline needs.
    #[error("the GMM/GMR baseline needs at least {required} demonstrations to align and to estimate their spread, got {found}")]
    TooFewDemonstrations {
        /// Demonstrations given.
        found: usize,
        /// Minimum.
        required: usize,
    },
    /// The demonstrations themselves are invalid or disagree (columns, widths).
    #[error(transparent)]
    Demo(#[from] DemoError),
    /// A demonstration never moves faster than the idle threshold.
    #[error("{source_name}: the demonstration never moves faster than the idle threshold {threshold} rad/s; nothing is left after trimming")]
    NoMotion {
        /// Demonstration source.
        source_name: String,
        /// The threshold in force.
        threshold: f64,
    },
    /// DTW failed (empty or mismatched sequences).
    #[error(transparent)]
    Dtw(#[from] DtwError),
    /// Fewer data points than mixture components.
    #[error("{points} data points cannot support {components} mixture components; use fewer components or more points")]
    TooFewPoints {
        /// Points given.
        points: usize,
        /// Components requested.
        components: usize,
    },
    /// A data point has the wrong width or a non-finite value.
    #[error("data point {index}: {message}")]
    BadPoint {
        /// 0-based index.
        index: usize,
        /// What is wrong.
        message: String,
    },
    /// A covariance is not positive definite even after regularisation.
    #[error("component {component}: covariance is not positive definite (reg_covar = {reg_covar}); increase reg_covar or use fewer components")]
    DegenerateCovariance {
        /// 0-based component.
        component: usize,
        /// Regularisation in force.
        reg_covar: f64,
    },
    /// EM did not reach the tolerance within the iteration budget.
    #[error("EM with {components} components did not converge within {max_iterations} iterations; raise max_iterations or the tolerance")]
    NotConverged {
        /// Components.
        components: usize,
        /// Iteration budget.
        max_iterations: u64,
    },
    /// Another failure reported by the EM implementation (linfa-clustering).
    #[error("EM with {components} components failed: {message}")]
    Em {
        /// Components.
        components: usize,
        /// The message of linfa-clustering.
        message: String,
    },
    /// Mixture parameters that do not form a valid model (counts, sizes, weights, symmetry).
    #[error("invalid mixture: {message}")]
    InvalidModel {
        /// What is wrong.
        message: String,
    },
    /// A query time is not finite, or a sample period not positive.
    #[error("invalid query: {message}")]
    Query {
        /// What is wrong.
        message: String,
    },
    /// A model file cannot be read or written.
    #[error("{path}: {source}")]
    Io {
        /// File path.
        path: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// A model file is not in the expected format.
    #[error("{path}: line {line}: {message}")]
    Format {
        /// File path.
        path: String,
        /// 1-based line.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A model file of another format version.
    #[error("{path}: GMR model format version {found}, this build reads version {supported}")]
    Version {
        /// File path.
        path: String,
        /// Version in the file.
        found: String,
        /// Version this build reads.
        supported: u32,
    },
}
