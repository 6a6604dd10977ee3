//! A robot's limits, checked before a trajectory leaves the testbed: every posture within
//! the joint ranges, every joint's speed within its documented maximum times a safety
//! fraction. A too-fast trajectory is refused, or slowed down uniformly ([`slow_to_limits`]).
//!
//! [`nao_left_arm`] is the Nao H25 V5 left arm. Its ranges and maximum velocities are those
//! of the `nao_robot` description of the ros-naoqi project (`nao_description/urdf/
//! naoV50_generated_urdf/nao.urdf`, robot "NaoH25V50", joint `<limit lower upper velocity>`),
//! which agree with Aldebaran's H25 joint documentation and with `models/nao_left_arm.xml`
//! (its joint `range` attributes); the reference table is in `docs/EXPORT.md`. Other robots:
//! [`from_mjcf`] takes the ranges from an MJCF file's hinge and slide joints and the
//! velocities from a user-given table.

use std::path::Path;

use serde::Serialize;

use crate::robot::{joint_ranges, Robot};
use crate::trajectory::{ExportError, Trajectory};

/// Default fraction of each joint's maximum velocity a trajectory may reach.
pub const DEFAULT_VELOCITY_FRACTION: f64 = 0.5;

/// One joint's limits.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointLimit {
    /// Joint name (as in the trajectory's columns).
    pub name: String,
    /// Lowest position (rad, or the joint's unit).
    pub lower: f64,
    /// Highest position.
    pub upper: f64,
    /// Documented maximum velocity (unit per second).
    pub max_velocity: f64,
}

/// The limits of a robot's joints, and where they come from (named in messages).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobotLimits {
    /// Where the figures come from.
    pub source: String,
    /// One entry per joint.
    pub joints: Vec<JointLimit>,
}

/// The Nao H25 V5 left arm, in NAOqi order (radians; `LHand` is the open fraction 0..1 and
/// its velocity the fraction per second). Sources: see the module documentation.
pub fn nao_left_arm() -> RobotLimits {
    RobotLimits::of(Robot::LeftArm)
}

impl RobotLimits {
    /// A robot of the description ([`crate::robot`]): its ranges and maximum velocities.
    pub fn of(robot: Robot) -> RobotLimits {
        let joints = robot.joints().iter().map(|j| JointLimit {
            name: j.name.into(),
            lower: j.range.0,
            upper: j.range.1,
            max_velocity: j.max_velocity,
        });
        RobotLimits {
            source: format!(
                "Nao H25 V5 {} (nao_description naoV50 URDF; docs/EXPORT.md)",
                robot.name().replace('-', " ")
            ),
            joints: joints.collect(),
        }
    }
}

pub use crate::robot::{are_arm_joints, arm_ranges, RANGE_TOLERANCE_RAD};

/// A velocity table: a CSV file with a header `joint,max_velocity` and one row per joint.
pub fn read_velocity_table(path: &Path) -> Result<Vec<(String, f64)>, ExportError> {
    let p = path.display().to_string();
    let bad = |reason: String| ExportError::Limits {
        source_name: p.clone(),
        reason,
    };
    let text = std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read it: {e}")))?;
    let mut lines = text.lines().filter(|l| !l.trim().is_empty());
    let header: Vec<String> = lines
        .next()
        .ok_or_else(|| bad("the file is empty; expected a header `joint,max_velocity`".into()))?
        .split(',')
        .map(|s| s.trim().to_ascii_lowercase())
        .collect();
    if header != ["joint", "max_velocity"] {
        return Err(bad(format!(
            "the header is {header:?}; expected `joint,max_velocity`"
        )));
    }
    let mut out: Vec<(String, f64)> = Vec::new();
    for (i, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let v = match cells.as_slice() {
            [name, v] if !name.is_empty() => v.parse::<f64>().ok().map(|v| (name, v)),
            _ => None,
        };
        match v {
            Some((name, v)) if v.is_finite() && v > 0.0 => {
                if out.iter().any(|(n, _)| n == name) {
                    return Err(bad(format!("joint `{name}` is listed twice")));
                }
                out.push((name.to_string(), v));
            }
            _ => {
                return Err(bad(format!(
                    "row {} `{line}`: expected a joint name and a finite velocity > 0",
                    i + 2
                )))
            }
        }
    }
    if out.is_empty() {
        return Err(bad("no joint listed below the header".into()));
    }
    Ok(out)
}

/// Limits of another robot: the ranges of the MJCF file's named, limited `hinge`/`slide`
/// joints (`range="lower upper"`), the maximum velocities from `velocities`
/// ([`read_velocity_table`]). Joints of the table missing from the model, or without a
/// range there, are refused by name.
pub fn from_mjcf(mjcf: &Path, velocities: &[(String, f64)]) -> Result<RobotLimits, ExportError> {
    let p = mjcf.display().to_string();
    let bad = |reason: String| ExportError::Limits {
        source_name: p.clone(),
        reason,
    };
    let xml = std::fs::read_to_string(mjcf).map_err(|e| bad(format!("cannot read it: {e}")))?;
    let ranges = joint_ranges(&xml).map_err(bad)?;
    let mut joints = Vec::new();
    for (name, v) in velocities {
        let (lower, upper) = ranges
            .iter()
            .find(|(n, _, _)| n == name)
            .map(|(_, a, b)| (*a, *b))
            .ok_or_else(|| {
                let names: Vec<&str> = ranges.iter().map(|(n, _, _)| n.as_str()).collect();
                bad(format!(
                    "joint `{name}` of the velocity table has no range in the model (joints with a range: {})",
                    names.join(", ")
                ))
            })?;
        joints.push(JointLimit {
            name: name.clone(),
            lower,
            upper,
            max_velocity: *v,
        });
    }
    Ok(RobotLimits { source: p, joints })
}

impl RobotLimits {
    fn joint(&self, name: &str) -> Result<&JointLimit, ExportError> {
        self.joints
            .iter()
            .find(|j| j.name == name)
            .ok_or_else(|| ExportError::UnknownJoint {
                joint: name.to_string(),
                source_name: self.source.clone(),
                known: self.joints.iter().map(|j| j.name.clone()).collect(),
            })
    }

    /// Every posture within range (a range error names the joint, the time and the value),
    /// then every joint's speed between consecutive points within `fraction` of its maximum
    /// (an error names the joint, the time, the speed and the limit).
    pub fn check(&self, t: &Trajectory, fraction: f64) -> Result<(), ExportError> {
        check_fraction(fraction)?;
        self.check_ranges(t)?;
        match self.fastest(t)? {
            Some(v) if v.ratio > fraction * (1.0 + 1e-12) => Err(ExportError::TooFast {
                joint: v.joint,
                time_s: v.time_s,
                velocity: v.velocity,
                limit: v.max_velocity * fraction,
                max_velocity: v.max_velocity,
                fraction,
            }),
            _ => Ok(()),
        }
    }

    /// Every posture within the joint ranges.
    pub fn check_ranges(&self, t: &Trajectory) -> Result<(), ExportError> {
        for (k, name) in t.names.iter().enumerate() {
            let j = self.joint(name)?;
            let tol = 1e-9 * (j.upper - j.lower).abs().max(1.0);
            for (i, p) in t.positions.iter().enumerate() {
                if p[k] < j.lower - tol || p[k] > j.upper + tol {
                    return Err(ExportError::OutOfRange {
                        joint: name.clone(),
                        time_s: t.times[i],
                        value: p[k],
                        lower: j.lower,
                        upper: j.upper,
                    });
                }
            }
        }
        Ok(())
    }

    /// The joint moving fastest relative to its maximum velocity (None for a single point).
    pub fn fastest(&self, t: &Trajectory) -> Result<Option<Fastest>, ExportError> {
        let mut best: Option<Fastest> = None;
        for (k, name) in t.names.iter().enumerate() {
            let j = self.joint(name)?;
            for i in 1..t.times.len() {
                let v = (t.positions[i][k] - t.positions[i - 1][k]).abs()
                    / (t.times[i] - t.times[i - 1]);
                let ratio = v / j.max_velocity;
                if best.as_ref().map_or(true, |b| ratio > b.ratio) {
                    best = Some(Fastest {
                        joint: name.clone(),
                        time_s: t.times[i - 1],
                        velocity: v,
                        max_velocity: j.max_velocity,
                        ratio,
                    });
                }
            }
        }
        Ok(best)
    }
}

/// The fastest joint of a trajectory, relative to its maximum velocity.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fastest {
    /// Joint name.
    pub joint: String,
    /// Start of the segment where it is fastest, s.
    pub time_s: f64,
    /// Its speed there.
    pub velocity: f64,
    /// Its documented maximum.
    pub max_velocity: f64,
    /// `velocity / max_velocity`.
    pub ratio: f64,
}

/// What [`slow_to_limits`] did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Slowdown {
    /// Duration before, s.
    pub duration_before_s: f64,
    /// Duration after, s.
    pub duration_after_s: f64,
    /// Factor the times were multiplied by (1: nothing to do).
    pub factor: f64,
    /// The joint that set the pace.
    pub joint: String,
}

fn check_fraction(fraction: f64) -> Result<(), ExportError> {
    if fraction.is_finite() && fraction > 0.0 && fraction <= 1.0 {
        Ok(())
    } else {
        Err(ExportError::Option {
            option: "--velocity-fraction",
            value: format!("{fraction}"),
            allowed: "a fraction of the maximum velocity in (0, 1]",
        })
    }
}

/// Slow the whole trajectory down uniformly (every time multiplied by one factor, so the
/// path and the relative timing are kept) until its fastest joint moves at `fraction` of its
/// maximum velocity; a trajectory already within the limits is returned unchanged. Ranges
/// are checked first: a posture out of range is refused, never slowed.
pub fn slow_to_limits(
    limits: &RobotLimits,
    t: &Trajectory,
    fraction: f64,
) -> Result<(Trajectory, Slowdown), ExportError> {
    check_fraction(fraction)?;
    limits.check_ranges(t)?;
    let before = t.duration();
    let (factor, joint) = match limits.fastest(t)? {
        Some(f) if f.ratio > fraction => (f.ratio / fraction * (1.0 + 1e-9), f.joint),
        Some(f) => (1.0, f.joint),
        None => (1.0, String::new()),
    };
    let slowed = if factor > 1.0 {
        t.scaled(factor)?
    } else {
        t.clone()
    };
    limits.check(&slowed, fraction)?;
    Ok((
        slowed.clone(),
        Slowdown {
            duration_before_s: before,
            duration_after_s: slowed.duration(),
            factor,
            joint,
        },
    ))
}

/// The longest duration [`at_duration`] takes, seconds (an hour).
const LONGEST_DURATION_S: f64 = 3600.0;

/// A duration [`at_duration`] takes at all: seconds above 0, at most an hour (checked before
/// any work, as `simulate --duration` does).
pub fn check_duration(duration_s: f64) -> Result<(), ExportError> {
    if duration_s.is_finite() && duration_s > 0.0 && duration_s <= LONGEST_DURATION_S {
        return Ok(());
    }
    Err(ExportError::Option {
        option: "--duration",
        value: format!("{duration_s}"),
        allowed: "seconds above 0 and at most 3600",
    })
}

/// `postures` (one every `1 / rate_hz` s) retimed to last `duration_s` seconds at the same
/// rate: the same path read at another pace (linearly between its postures, so nothing is
/// added to it), its shape kept and only its tempo changed. When `names` are a robot's joints,
/// a duration its servos cannot follow (a joint faster than its maximum velocity on the path)
/// is refused, naming the shortest they can.
pub fn at_duration(
    names: &[String],
    postures: &[Vec<f64>],
    rate_hz: f64,
    duration_s: f64,
) -> Result<Vec<Vec<f64>>, ExportError> {
    let bad = |allowed| ExportError::Option {
        option: "--duration",
        value: format!("{duration_s}"),
        allowed,
    };
    check_duration(duration_s)?;
    let n = (duration_s * rate_hz).round() as usize + 1;
    if n < 2 {
        return Err(bad(
            "at least one step of the reproduction (one sample period)",
        ));
    }
    let len = postures.len();
    if len < 2 {
        return Err(bad("a reproduction of more than one posture to retime"));
    }
    if let Some(robot) = Robot::of_columns(names) {
        // the joint fastest for its servo at the gesture's own tempo; retimed to n steps, the
        // path read linearly between its postures moves (len - 1) / (n - 1) times as fast, and
        // no two samples of it are farther apart than that
        let times = (0..len).map(|k| k as f64 / rate_hz).collect();
        let own = Trajectory::new(names.to_vec(), times, postures.to_vec())?;
        if let Some(f) = RobotLimits::of(robot).fastest(&own)? {
            let ratio = f.ratio * (len - 1) as f64 / (n - 1) as f64;
            if ratio > 1.0 {
                let steps = (f.ratio * (len - 1) as f64 - 1e-9).ceil().max(1.0);
                return Err(ExportError::TooShort {
                    duration_s,
                    robot: robot.name().into(),
                    joint: f.joint,
                    ratio,
                    max_velocity: f.max_velocity,
                    shortest_s: steps / rate_hz,
                });
            }
        }
    }
    Ok(crate::curve::resample_linear(postures, n))
}
