//! What the export writes and reads, and what can go wrong: a room below the two that write
//! it, `export` and `ros2` (re-exported as `export::Trajectory` and `export::ExportError`).

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
    /// A duration the robot's servos cannot follow.
    #[error("--duration {duration_s} is too fast for the {robot}'s servos: {joint} would move at {ratio:.2} times its maximum velocity ({max_velocity}/s); the shortest this gesture can take is {shortest_s} s")]
    TooShort {
        /// The duration asked, s.
        duration_s: f64,
        /// The robot.
        robot: String,
        /// The joint fastest for its servo.
        joint: String,
        /// Its speed over its maximum at that duration.
        ratio: f64,
        /// Its documented maximum.
        max_velocity: f64,
        /// The shortest duration the servos follow, s.
        shortest_s: f64,
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
    /// A motion that brings two parts of the robot into contact (seen on the simulated robot).
    #[error("the motion brings {} and {} into contact at t = {time_s:.2} s ({} on the simulated {robot}); the robot's motors do not stop for it: change the reproduction (a goal, via-points), give the demonstrations it was learned from with --demos when every one of them makes this contact (the gesture's own, as the clap's hands), or export it anyway with --allow-contact", parts[0], parts[1], contact_depth(*depth_m))]
    Contact {
        /// When the contact begins, s from the start of the exported motion.
        time_s: f64,
        /// The two parts (the model's body names).
        parts: [String; 2],
        /// The deepest penetration, m.
        depth_m: f64,
        /// The robot it was executed on.
        robot: String,
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
    #[error("loading the default arm model: {0}")]
    Arm(Box<crate::sim::SimError>),
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

/// How deep a contact is, for people: "1.8 mm deep", or "touching" when it rounds to 0.0 mm
/// (the shapes meet, or penetrate by less than 0.05 mm).
pub fn contact_depth(depth_m: f64) -> String {
    match depth_m * 1e3 {
        mm if mm < 0.05 => "touching".into(),
        mm => format!("{mm:.1} mm deep"),
    }
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
