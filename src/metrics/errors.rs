//! Errors of the fidelity metrics.

/// Bad input to the metrics: the message names the trajectory (`reproduction` or
/// `demonstration N`, 0-based) and the sample.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MetricsError {
    /// No demonstration to compare with.
    #[error("fidelity metrics need at least one demonstration")]
    NoDemonstrations,
    /// A trajectory without samples (or without joints).
    #[error("{which} has no samples or no joint values")]
    Empty {
        /// Which trajectory.
        which: String,
    },
    /// A sample of another width than the reproduction's first sample.
    #[error("{which}, sample {sample}: {found} joint values, expected {expected}")]
    Width {
        /// Which trajectory.
        which: String,
        /// 0-based sample.
        sample: usize,
        /// Expected width.
        expected: usize,
        /// Width found.
        found: usize,
    },
    /// A NaN or infinite value.
    #[error("{which}, sample {sample}: non-finite value {value}")]
    NotFinite {
        /// Which trajectory.
        which: String,
        /// 0-based sample.
        sample: usize,
        /// The value.
        value: f64,
    },
    /// Wrist positions whose count differs from the joint samples.
    #[error("{which}: {wrist} wrist positions for {joints} joint samples; give one per sample")]
    WristLength {
        /// Which trajectory.
        which: String,
        /// Wrist positions.
        wrist: usize,
        /// Joint samples.
        joints: usize,
    },
    /// A demonstration that never moves faster than the idle threshold.
    #[error("{which} never moves faster than {threshold} rad/s: it has no motion to compare with")]
    NoMotion {
        /// Which trajectory.
        which: String,
        /// Threshold in force.
        threshold: f64,
    },
    /// DTW refused its inputs.
    #[error(transparent)]
    Dtw(#[from] crate::dtw::DtwError),
    /// A setting out of range.
    #[error("invalid metrics setting `{name}` = {value}: {reason}")]
    InvalidParam {
        /// Setting name.
        name: &'static str,
        /// Value as text.
        value: String,
        /// What is allowed.
        reason: &'static str,
    },
}
