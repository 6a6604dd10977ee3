//! Executing a learned gesture on the simulated arm: the predicted postures go to the position
//! controller, from the initial posture, and the executed trajectory is recorded at 40 Hz.

use super::{Controller, ControllerConfig, NaoArm, Recording, SimError, TargetTrajectory};
use crate::robot::Robot;

/// How predicted postures become servo targets.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Transition {
    /// One predicted posture per recording tick, linear in between (the paper: "execute the
    /// transition from posture to posture").
    #[default]
    Linear,
    /// Beyond the paper: keep only the key poses of the predicted sequence (Ramer-Douglas-
    /// Peucker simplification of the (step, posture) polyline: every dropped posture lies within
    /// `tolerance` rad of the simplified path) at their own time index, and join them with
    /// minimum-jerk transitions. Removes the jitter and sharp edges below `tolerance`, keeps
    /// the timing and the extremes.
    MinimumJerk {
        /// Largest joint-space distance (rad) of a dropped posture from the simplified path.
        tolerance: f64,
    },
}

impl Transition {
    /// Parse `linear` or `min-jerk` / `min-jerk:TOL` (tolerance in rad, default 0.02).
    pub fn parse(s: &str) -> Result<Transition, SimError> {
        let bad = || {
            SimError::Invalid(format!(
                "transition '{s}': allowed `linear`, `min-jerk` or `min-jerk:TOL` with TOL a tolerance in rad > 0"
            ))
        };
        match s.split_once(':') {
            None if s == "linear" => Ok(Transition::Linear),
            None if s == "min-jerk" => Ok(Transition::MinimumJerk { tolerance: 0.02 }),
            Some(("min-jerk", t)) => {
                let tolerance: f64 = t.parse().map_err(|_| bad())?;
                if tolerance.is_finite() && tolerance > 0.0 {
                    Ok(Transition::MinimumJerk { tolerance })
                } else {
                    Err(bad())
                }
            }
            _ => Err(bad()),
        }
    }

    /// The postures to send, one per tick, after this transition's shaping.
    pub fn shape(&self, postures: &[Vec<f64>]) -> Vec<Vec<f64>> {
        match *self {
            Transition::Linear => postures.to_vec(),
            Transition::MinimumJerk { tolerance } => {
                min_jerk_through_key_poses(postures, tolerance)
            }
        }
    }

    /// Short name for reports.
    pub fn name(&self) -> String {
        match self {
            Transition::Linear => "linear".into(),
            Transition::MinimumJerk { tolerance } => format!("min-jerk:{tolerance}"),
        }
    }
}

fn dist_to_segment(p: &[f64], a: &[f64], b: &[f64], u: f64) -> f64 {
    // distance in joint space from p to the point of segment a-b at the same time fraction u
    p.iter()
        .zip(a.iter().zip(b))
        .map(|(x, (y, z))| (x - (y + u * (z - y))).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Indices of the key poses: Ramer-Douglas-Peucker on the time-indexed polyline (the
/// distance of a posture to a segment is measured at its own time, so timing is kept).
pub fn key_pose_indices(postures: &[Vec<f64>], tolerance: f64) -> Vec<usize> {
    let n = postures.len();
    if n <= 2 {
        return (0..n).collect();
    }
    let mut keep = vec![false; n];
    keep[0] = true;
    keep[n - 1] = true;
    let mut stack = vec![(0usize, n - 1)];
    while let Some((i, j)) = stack.pop() {
        if j <= i + 1 {
            continue;
        }
        let (mut worst, mut at) = (0.0, i);
        for k in i + 1..j {
            let u = (k - i) as f64 / (j - i) as f64;
            let d = dist_to_segment(&postures[k], &postures[i], &postures[j], u);
            if d > worst {
                worst = d;
                at = k;
            }
        }
        if worst > tolerance {
            keep[at] = true;
            stack.push((i, at));
            stack.push((at, j));
        }
    }
    (0..n).filter(|&k| keep[k]).collect()
}

/// Key poses (see [`key_pose_indices`]) joined by minimum-jerk transitions, one posture per
/// original step.
pub fn min_jerk_through_key_poses(postures: &[Vec<f64>], tolerance: f64) -> Vec<Vec<f64>> {
    let keys = key_pose_indices(postures, tolerance);
    let mut out = Vec::with_capacity(postures.len());
    for w in keys.windows(2) {
        let (i, j) = (w[0], w[1]);
        out.extend(crate::curve::minimum_jerk(
            &postures[i],
            &postures[j],
            j - i,
        ));
    }
    if let Some(last) = postures.last() {
        out.push(last.clone());
    }
    out
}

/// Execute `postures` (one per tick of `rate_hz`, the first being the initial posture) on the
/// simulated arm, starting at the first posture, and record the encoders at `rate_hz`.
/// Postures outside the joint ranges are an error naming the joint (no silent clamping).
pub fn execute_postures<const N: usize>(
    arm: &NaoArm<N>,
    postures: &[Vec<f64>],
    rate_hz: f64,
) -> Result<Recording, SimError> {
    let Some(first) = postures.first() else {
        return Err(SimError::Invalid("no postures to execute".into()));
    };
    if first.len() != N {
        return Err(SimError::Invalid(format!(
            "postures have {} values, the arm has {N} joints",
            first.len()
        )));
    }
    let controller = Controller::new(ControllerConfig {
        record_rate_hz: rate_hz,
        ..ControllerConfig::default()
    })?;
    let trajectory = TargetTrajectory::<N>::at_rate_for(arm.robot(), rate_hz, postures)?;
    let mut sim = arm.sim()?;
    sim.set_posture(first)?;
    controller.follow(&mut sim, &trajectory)
}

/// Clamp learned postures into the joint ranges before execution, counting the values that
/// were outside (the report shows the count: nothing is fixed silently). NaN is an error.
pub fn clamp_to_ranges(postures: &[Vec<f64>]) -> Result<(Vec<Vec<f64>>, usize), SimError> {
    clamp_to_ranges_of(Robot::LeftArm, postures)
}

/// [`clamp_to_ranges`] into `robot`'s joint ranges.
pub fn clamp_to_ranges_of(
    robot: Robot,
    postures: &[Vec<f64>],
) -> Result<(Vec<Vec<f64>>, usize), SimError> {
    let joints = robot.joints();
    let mut clamped = 0;
    let mut out = Vec::with_capacity(postures.len());
    for (i, p) in postures.iter().enumerate() {
        if p.len() != joints.len() {
            return Err(SimError::Invalid(format!(
                "posture {i} has {} values, the arm has {} joints",
                p.len(),
                joints.len()
            )));
        }
        let mut row = Vec::with_capacity(joints.len());
        for (spec, &v) in joints.iter().zip(p) {
            let c = super::spec::clamp_joint(spec, v)?;
            if c != v {
                clamped += 1;
            }
            row.push(c);
        }
        out.push(row);
    }
    Ok((out, clamped))
}

#[cfg(test)]
mod tests;
