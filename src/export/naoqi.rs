//! NAOqi: the arguments of `ALMotion.angleInterpolation(names, angleLists, timeLists,
//! isAbsolute)` as JSON, under their API names; `scripts/play_on_nao.py` sends them.
//!
//! NAOqi's times are seconds from the call and must be strictly positive and increasing, so
//! the trajectory's first point (its initial posture, at time 0) is placed one sample period
//! after the call; `play_on_nao.py` brings the arm to that posture first, slowly.

use serde::Serialize;

use crate::trajectory::Trajectory;

/// The JSON document.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[allow(non_snake_case)] // NAOqi's argument names
pub struct AngleInterpolation {
    /// Joint names.
    pub names: Vec<String>,
    /// Per joint, its angles (rad; LHand the open fraction).
    pub angleLists: Vec<Vec<f64>>,
    /// Per joint, the time of each angle, s from the call.
    pub timeLists: Vec<Vec<f64>>,
    /// Angles are absolute.
    pub isAbsolute: bool,
}

/// The arguments for `t`, with every time shifted by the first interval (or 0.025 s for a
/// single point) so that the first is positive.
pub fn arguments(t: &Trajectory) -> AngleInterpolation {
    let lead = match t.times.as_slice() {
        [a, b, ..] => b - a,
        _ => 0.025,
    };
    let times: Vec<f64> = t.times.iter().map(|x| x + lead).collect();
    AngleInterpolation {
        names: t.names.clone(),
        angleLists: (0..t.names.len())
            .map(|k| t.positions.iter().map(|p| p[k]).collect())
            .collect(),
        timeLists: vec![times; t.names.len()],
        isAbsolute: true,
    }
}

/// The JSON bytes (pretty-printed).
pub fn to_json(t: &Trajectory) -> Vec<u8> {
    let mut v = serde_json::to_vec_pretty(&arguments(t)).unwrap_or_default();
    v.push(b'\n');
    v
}
