//! From the testbed to a robot: a reproduction (or any joint trajectory) time-scaled,
//! checked against the robot's limits, and written for NAOqi ([`naoqi`]: the arguments of
//! `ALMotion.angleInterpolation`), for ROS 2 (an MCAP file of
//! `trajectory_msgs/msg/JointTrajectory`, see [`crate::ros2`]) or as CSV at a chosen rate.
//!
//! ```
//! use cosco_hsom::export::{limits, Trajectory};
//! let names = vec!["LShoulderPitch".to_string()];
//! let t = Trajectory::new(names, vec![0.0, 0.5, 1.0], vec![vec![1.4], vec![1.0], vec![0.6]]).unwrap();
//! let arm = limits::nao_left_arm();
//! arm.check(&t, 0.5).unwrap(); // 0.8 rad/s, well within half of 8.27 rad/s
//! let fast = t.scaled(0.05).unwrap(); // 16 rad/s
//! assert!(arm.check(&fast, 0.5).is_err());
//! let (slowed, report) = limits::slow_to_limits(&arm, &fast, 0.5).unwrap();
//! assert!(report.duration_after_s > 0.19 && arm.check(&slowed, 0.5).is_ok());
//! ```

#[cfg(feature = "sim")]
pub mod executed;
pub mod limits;
pub mod naoqi;
mod request;

pub use crate::trajectory::{ExportError, Trajectory};
pub use request::{export_request, ExportRequest, DEFAULT_STEP_RATE_HZ};

use serde::Serialize;

/// Output format (`--format naoqi|ros2|csv`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Format {
    /// JSON arguments of NAOqi's `ALMotion.angleInterpolation`.
    Naoqi,
    /// MCAP with a ROS 2 `trajectory_msgs/msg/JointTrajectory`.
    Ros2,
    /// CSV (`time`, then one column per joint) at a chosen rate.
    Csv,
}

/// What an export did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExportReport {
    /// Points written.
    pub points: usize,
    /// Joints written.
    pub joints: Vec<String>,
    /// Duration of the input, s.
    pub source_duration_s: f64,
    /// Duration written, s.
    pub duration_s: f64,
    /// The slow-down `--clamp` applied (factor 1: none needed).
    pub clamp: Option<limits::Slowdown>,
    /// The fastest joint of what was written, as a fraction of its maximum velocity.
    pub peak_velocity_fraction: f64,
    /// That joint.
    pub peak_joint: String,
}

impl ExportReport {
    /// Human-readable lines.
    pub fn lines(&self) -> Vec<String> {
        let mut v = vec![format!(
            "{} points of {} joints, {:.3} s (input {:.3} s); fastest joint {} at {:.3} of its maximum velocity",
            self.points,
            self.joints.len(),
            self.duration_s,
            self.source_duration_s,
            self.peak_joint,
            self.peak_velocity_fraction
        )];
        if let Some(c) = &self.clamp {
            if c.factor > 1.0 {
                v.push(format!(
                    "--clamp: slowed down {:.3} times ({} set the pace): {:.3} s -> {:.3} s",
                    c.factor, c.joint, c.duration_before_s, c.duration_after_s
                ));
            } else {
                v.push("--clamp: within the limits, timing unchanged".into());
            }
        }
        v
    }
}

/// Time-scale as `r` asks (`speed` times faster, or stretched to last `duration` s), check
/// against `limits` at `r.velocity_fraction` (or slow down with `r.clamp`), resample a CSV to
/// `r.rate`: the trajectory to write and the report.
pub fn prepare(
    t: &Trajectory,
    limits: &limits::RobotLimits,
    r: &ExportRequest,
) -> Result<(Trajectory, ExportReport), ExportError> {
    let source_duration = t.duration();
    let timed = match (r.speed, r.duration) {
        (None, None) => t.clone(),
        (Some(f), _) => {
            if !(f.is_finite() && f > 0.0) {
                return Err(ExportError::Option {
                    option: "--speed",
                    value: format!("{f}"),
                    allowed: "a finite factor > 0 (2: twice as fast)",
                });
            }
            t.scaled(1.0 / f)?
        }
        (None, Some(d)) => {
            if !(d.is_finite() && d > 0.0) || source_duration <= 0.0 {
                return Err(ExportError::Option {
                    option: "--duration",
                    value: format!("{d}"),
                    allowed: "a finite duration > 0 s, for a trajectory of at least two points",
                });
            }
            t.scaled(d / source_duration)?
        }
    };
    let (out, clamp) = if r.clamp {
        let (s, slowdown) = limits::slow_to_limits(limits, &timed, r.velocity_fraction)?;
        (s, Some(slowdown))
    } else {
        limits.check(&timed, r.velocity_fraction)?;
        (timed, None)
    };
    let out = match (r.format, r.rate) {
        (Format::Csv, Some(hz)) => out.at_rate(hz)?,
        _ => out,
    };
    let fastest = limits.fastest(&out)?;
    let report = ExportReport {
        points: out.times.len(),
        joints: out.names.clone(),
        source_duration_s: source_duration,
        duration_s: out.duration(),
        clamp,
        peak_velocity_fraction: fastest.as_ref().map_or(0.0, |f| f.ratio),
        peak_joint: fastest.map_or_else(String::new, |f| f.joint),
    };
    Ok((out, report))
}

/// The bytes of a trajectory in `format` (`Ros2` needs the feature `ros2`; `executed`, the
/// arm's recorded encoder readings, goes into the MCAP file as `sensor_msgs/msg/JointState`).
pub fn encode(
    t: &Trajectory,
    format: Format,
    executed: Option<&Trajectory>,
) -> Result<Vec<u8>, ExportError> {
    match format {
        Format::Naoqi => Ok(naoqi::to_json(t)),
        Format::Csv => Ok(crate::demos::to_csv_bytes(&t.to_demonstration("export"))?),
        #[cfg(feature = "ros2")]
        Format::Ros2 => crate::ros2::trajectory_mcap(t, executed),
        #[cfg(not(feature = "ros2"))]
        Format::Ros2 => {
            let _ = executed;
            Err(ExportError::Option {
                option: "--format",
                value: "ros2".into(),
                allowed: "naoqi or csv: this build has no ROS 2 support (feature `ros2`)",
            })
        }
    }
}

#[cfg(test)]
mod tests;
