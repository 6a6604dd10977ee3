//! What `cosco export` exports: a reproduction CSV, or a model's reproduction made on the spot.

use std::path::Path;

use super::trajectory::{ExportError, Trajectory};
use crate::{labelled, steps};

/// Rate of a reproduction's `step` column when the file has no `time` column: the arm's
/// encoders' (the demonstrations' clock), Hz.
pub const DEFAULT_STEP_RATE_HZ: f64 = 40.0;

/// A reproduction CSV (`cosco reproduce`'s `step` column, GMM/GMR's or any file with a
/// `time` column, then one column per joint); without `time`, one posture every
/// `1 / step_rate_hz` s.
pub fn from_reproduction_file(path: &Path, step_rate_hz: f64) -> Result<Trajectory, ExportError> {
    let d = steps::read_reproduction(path)?;
    Trajectory::from_demonstration(&d, step_rate_hz)
}

/// The initial posture of a model's reproduction.
pub enum Initial<'a> {
    /// Given values, one per variable.
    Values(&'a [f64]),
    /// The first row of a demonstration CSV.
    From(&'a Path),
}

/// Gesture `label` (required with a model of several) of the model saved at `model`,
/// reproduced from `initial`, one posture every `1 / step_rate_hz` s.
pub fn from_model(
    model: &Path,
    label: Option<&str>,
    initial: Initial<'_>,
    step_rate_hz: f64,
) -> Result<Trajectory, ExportError> {
    let m = labelled::load_gesture_model(model)?;
    let branch = m.branch(label).map_err(labelled::LabelledError::from)?;
    let initial = match initial {
        Initial::Values(v) => v.to_vec(),
        Initial::From(p) => steps::initial_from_file(branch, p)?,
    };
    let rep = labelled::reproduce_gesture(&m, &model.display().to_string(), label, &initial)?;
    let d = crate::demos::Demonstration {
        source: model.display().to_string(),
        columns: m.columns().to_vec(),
        time: None,
        rows: rep.postures,
    };
    Trajectory::from_demonstration(&d, step_rate_hz)
}
