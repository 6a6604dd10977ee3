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
pub mod source;

pub use request::{export_request, ExportRequest};

use std::path::Path;

use serde::Serialize;

use crate::demos::{DemoError, Demonstration};

/// What can go wrong exporting. Every variant names what it is about.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// A trajectory that is not one (lengths, times).
    #[error("{source_name}: {reason}")]
    Invalid {
        /// Where the trajectory came from.
        source_name: String,
        /// What is wrong.
        reason: String,
    },
    /// A posture outside a joint's range.
    #[error("joint {joint} at t = {time_s:.3} s: {value} is outside its range [{lower}, {upper}]; a posture out of range cannot be sent to the robot")]
    OutOfRange {
        /// Joint.
        joint: String,
        /// Time of the posture, s.
        time_s: f64,
        /// Its value.
        value: f64,
        /// Range.
        lower: f64,
        /// Range.
        upper: f64,
    },
    /// A joint moving faster than allowed.
    #[error("joint {joint} at t = {time_s:.3} s moves at {velocity:.3}/s, over its limit {limit:.3}/s ({fraction} of its maximum {max_velocity}/s); slow it down with --clamp, --speed or --duration, or change --velocity-fraction")]
    TooFast {
        /// Joint.
        joint: String,
        /// Start of the segment, s.
        time_s: f64,
        /// Its speed.
        velocity: f64,
        /// The allowed speed.
        limit: f64,
        /// Documented maximum.
        max_velocity: f64,
        /// Safety fraction.
        fraction: f64,
    },
    /// A trajectory joint without limits.
    #[error("joint `{joint}` has no limits in {source_name} (joints there: {}); export only the robot's joints, or give the robot's limits", known.join(", "))]
    UnknownJoint {
        /// The joint.
        joint: String,
        /// The limits' source.
        source_name: String,
        /// The joints it knows.
        known: Vec<String>,
    },
    /// A limits file (MJCF, velocity table) that cannot be used.
    #[error("{source_name}: {reason}")]
    Limits {
        /// The file.
        source_name: String,
        /// What is wrong.
        reason: String,
    },
    /// An option's value out of range.
    #[error("{option} {value}: expected {allowed}")]
    Option {
        /// The option.
        option: &'static str,
        /// Its value.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// Reading a CSV.
    #[error(transparent)]
    Demo(#[from] DemoError),
    /// Arguments that do not go together, or a value given on the command line that is not
    /// allowed (named in the message).
    #[error("{0}")]
    Usage(String),
    /// The simulated arm could not be loaded.
    #[cfg(feature = "sim")]
    #[error("loading the default arm model")]
    Arm {
        /// The simulator's error.
        source: crate::sim::SimError,
    },
    /// Writing the output.
    #[error("{path}: cannot write it: {source}")]
    Write {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// Writing or reading an MCAP file.
    #[error("{path}: {reason}")]
    Bag {
        /// The file.
        path: String,
        /// What is wrong.
        reason: String,
    },
}

/// A joint trajectory: named joints, positions at strictly increasing times from 0.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Trajectory {
    /// Joint names, one per position column.
    pub names: Vec<String>,
    /// Times, s, strictly increasing, the first 0.
    pub times: Vec<f64>,
    /// One posture per time.
    pub positions: Vec<Vec<f64>>,
}

fn invalid(reason: String) -> ExportError {
    ExportError::Invalid {
        source_name: "trajectory".into(),
        reason,
    }
}

impl Trajectory {
    /// A checked trajectory: at least one point, one name per column, finite values, times
    /// finite and strictly increasing (shifted so that the first is 0).
    pub fn new(
        names: Vec<String>,
        times: Vec<f64>,
        positions: Vec<Vec<f64>>,
    ) -> Result<Trajectory, ExportError> {
        if positions.is_empty() || names.is_empty() {
            return Err(invalid("no points or no joints".into()));
        }
        if times.len() != positions.len() {
            return Err(invalid(format!(
                "{} times for {} postures",
                times.len(),
                positions.len()
            )));
        }
        for (i, p) in positions.iter().enumerate() {
            if p.len() != names.len() || p.iter().any(|v| !v.is_finite()) {
                return Err(invalid(format!(
                    "posture {i} has {} values for {} joints, or a value that is not finite",
                    p.len(),
                    names.len()
                )));
            }
            if !times[i].is_finite() || (i > 0 && times[i] <= times[i - 1]) {
                return Err(invalid(format!(
                    "time {i} = {} s: times must be finite and strictly increasing",
                    times[i]
                )));
            }
        }
        let t0 = times[0];
        Ok(Trajectory {
            names,
            times: times.iter().map(|t| t - t0).collect(),
            positions,
        })
    }

    /// A demonstration or reproduction: its `time` column, or one sample every
    /// `1 / step_rate_hz` s without one (reproductions are one posture per tick of the
    /// demonstrations' clock, 40 Hz for the arm's encoders).
    pub fn from_demonstration(
        d: &Demonstration,
        step_rate_hz: f64,
    ) -> Result<Trajectory, ExportError> {
        check_rate("--step-rate", step_rate_hz)?;
        let times = match &d.time {
            Some(t) => t.clone(),
            None => (0..d.rows.len()).map(|i| i as f64 / step_rate_hz).collect(),
        };
        Trajectory::new(d.columns.clone(), times, d.rows.clone()).map_err(|e| match e {
            ExportError::Invalid { reason, .. } => ExportError::Invalid {
                source_name: d.source.clone(),
                reason,
            },
            e => e,
        })
    }

    /// As a demonstration with a `time` column.
    pub fn to_demonstration(&self, source: &str) -> Demonstration {
        Demonstration {
            source: source.into(),
            columns: self.names.clone(),
            time: Some(self.times.clone()),
            rows: self.positions.clone(),
        }
    }

    /// Last time, s.
    pub fn duration(&self) -> f64 {
        *self.times.last().unwrap_or(&0.0)
    }

    /// Every time multiplied by `factor` (> 0): 2 makes the motion last twice as long.
    pub fn scaled(&self, factor: f64) -> Result<Trajectory, ExportError> {
        if !(factor.is_finite() && factor > 0.0) {
            return Err(invalid(format!(
                "time scale {factor}: expected a finite factor > 0"
            )));
        }
        Trajectory::new(
            self.names.clone(),
            self.times.iter().map(|t| t * factor).collect(),
            self.positions.clone(),
        )
    }

    /// Joint velocities at each point: central differences inside, 0 at the first and the
    /// last point (the motion starts and ends at rest).
    pub fn velocities(&self) -> Vec<Vec<f64>> {
        let n = self.times.len();
        (0..n)
            .map(|i| {
                if i == 0 || i + 1 == n {
                    return vec![0.0; self.names.len()];
                }
                let dt = self.times[i + 1] - self.times[i - 1];
                (0..self.names.len())
                    .map(|k| (self.positions[i + 1][k] - self.positions[i - 1][k]) / dt)
                    .collect()
            })
            .collect()
    }

    /// Sampled every `1 / rate_hz` s from 0 to the last time (the last time included),
    /// by linear interpolation between the points (which keeps the path within the range
    /// of the points and adds no speed).
    pub fn at_rate(&self, rate_hz: f64) -> Result<Trajectory, ExportError> {
        check_rate("--rate", rate_hz)?;
        let d = self.duration();
        let n = (d * rate_hz + 1e-9).floor() as usize;
        let mut times: Vec<f64> = (0..=n).map(|i| i as f64 / rate_hz).collect();
        if d - times[n] > 1e-9 / rate_hz {
            times.push(d);
        }
        let positions = times.iter().map(|&t| self.position_at(t)).collect();
        Trajectory::new(self.names.clone(), times, positions)
    }

    /// The posture at time `t` (linear between points; the ends held outside).
    pub fn position_at(&self, t: f64) -> Vec<f64> {
        let n = self.times.len();
        if t <= self.times[0] {
            return self.positions[0].clone();
        }
        if t >= self.times[n - 1] {
            return self.positions[n - 1].clone();
        }
        let i = self.times.partition_point(|&x| x <= t) - 1;
        let u = (t - self.times[i]) / (self.times[i + 1] - self.times[i]);
        let (a, b) = (&self.positions[i], &self.positions[i + 1]);
        a.iter().zip(b).map(|(x, y)| x + u * (y - x)).collect()
    }
}

fn check_rate(option: &'static str, hz: f64) -> Result<(), ExportError> {
    if hz.is_finite() && hz > 0.0 && hz <= 10_000.0 {
        Ok(())
    } else {
        Err(ExportError::Option {
            option,
            value: format!("{hz}"),
            allowed: "a rate in (0, 10000] Hz",
        })
    }
}

/// Output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// JSON arguments of NAOqi's `ALMotion.angleInterpolation`.
    Naoqi,
    /// MCAP with a ROS 2 `trajectory_msgs/msg/JointTrajectory`.
    Ros2,
    /// CSV (`time`, then one column per joint) at a chosen rate.
    Csv,
}

impl std::str::FromStr for Format {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "naoqi" => Ok(Format::Naoqi),
            "ros2" => Ok(Format::Ros2),
            "csv" => Ok(Format::Csv),
            _ => Err(format!("`{s}`: expected naoqi, ros2 or csv")),
        }
    }
}

/// How to time the motion before the limits are checked.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Timing {
    /// As recorded.
    AsIs,
    /// Played `factor` times faster (2: twice as fast).
    Speed(f64),
    /// Stretched or squeezed to last this long, s.
    Duration(f64),
}

/// Everything `cosco export` decides besides the input and the output file.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    /// Output format.
    pub format: Format,
    /// Time scaling.
    pub timing: Timing,
    /// Safety fraction of each joint's maximum velocity.
    pub velocity_fraction: f64,
    /// Slow the timing down instead of refusing a too-fast trajectory.
    pub clamp: bool,
    /// Rate of the CSV output, Hz (`None`: the trajectory's own points).
    pub rate_hz: Option<f64>,
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

/// Time-scale, check against `limits` (or slow down with `clamp`): the trajectory to write
/// and the report.
pub fn prepare(
    t: &Trajectory,
    limits: &limits::RobotLimits,
    opts: &ExportOptions,
) -> Result<(Trajectory, ExportReport), ExportError> {
    let source_duration = t.duration();
    let timed = match opts.timing {
        Timing::AsIs => t.clone(),
        Timing::Speed(f) => {
            if !(f.is_finite() && f > 0.0) {
                return Err(ExportError::Option {
                    option: "--speed",
                    value: format!("{f}"),
                    allowed: "a finite factor > 0 (2: twice as fast)",
                });
            }
            t.scaled(1.0 / f)?
        }
        Timing::Duration(d) => {
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
    let (out, clamp) = if opts.clamp {
        let (s, r) = limits::slow_to_limits(limits, &timed, opts.velocity_fraction)?;
        (s, Some(r))
    } else {
        limits.check(&timed, opts.velocity_fraction)?;
        (timed, None)
    };
    let out = match (opts.format, opts.rate_hz) {
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

/// A way to execute the prepared trajectory and record the joints (the simulated arm:
/// `crate::export::executed` with the feature `sim`).
pub type Execute<'a> = &'a dyn Fn(&Trajectory) -> Result<Trajectory, ExportError>;

/// Prepare ([`prepare`]), execute when asked (its recording goes into the MCAP file), and
/// write atomically to `out`.
pub fn export_to(
    t: &Trajectory,
    limits: &limits::RobotLimits,
    opts: &ExportOptions,
    execute: Option<Execute<'_>>,
    out: &Path,
) -> Result<ExportReport, ExportError> {
    let (t, report) = prepare(t, limits, opts)?;
    let executed = execute.map(|f| f(&t)).transpose()?;
    let bytes = encode(&t, opts.format, executed.as_ref())?;
    crate::fsutil::write_atomic(out, &bytes).map_err(|source| ExportError::Write {
        path: out.display().to_string(),
        source,
    })?;
    Ok(report)
}

#[cfg(test)]
mod tests;
