//! Demonstration files: one CSV file per demonstration, a header row, an optional first
//! column `time` (seconds), then one column per state variable.

/// One demonstration: a multivariate time series sampled at a fixed rate.
#[derive(Debug, Clone, PartialEq)]
pub struct Demonstration {
    /// Where it came from (a file path or a generator name), used in messages.
    pub source: String,
    /// State-variable names, one per column (the `time` column excluded).
    pub columns: Vec<String>,
    /// Sample times in seconds, when the file had a `time` column.
    pub time: Option<Vec<f64>>,
    /// One row per sample, each `columns.len()` long, every value finite.
    pub rows: Vec<Vec<f64>>,
}
