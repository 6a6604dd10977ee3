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

use super::trajectory::{ExportError, Trajectory};

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
    let j = |name: &str, lower, upper, max_velocity| JointLimit {
        name: name.into(),
        lower,
        upper,
        max_velocity,
    };
    RobotLimits {
        source: "Nao H25 V5 left arm (nao_description naoV50 URDF; docs/EXPORT.md)".into(),
        joints: vec![
            j("LShoulderPitch", -2.08567, 2.08567, 8.26797),
            j("LShoulderRoll", -0.314159, 1.32645, 7.19407),
            j("LElbowYaw", -2.08567, 2.08567, 8.26797),
            j("LElbowRoll", -1.54462, -0.0349066, 7.19407),
            j("LWristYaw", -1.82387, 1.82387, 24.6229),
            j("LHand", 0.0, 1.0, 8.33),
        ],
    }
}

/// Whether `columns` are the Nao left arm's joints in NAOqi order (the simulated arm's
/// columns: then wrist paths exist and the joint ranges apply).
pub fn are_arm_joints(columns: &[String]) -> bool {
    let arm = nao_left_arm().joints;
    columns.len() == arm.len() && columns.iter().zip(&arm).all(|(c, j)| *c == j.name)
}

/// The Nao left arm's joint ranges, `(lower, upper)` in NAOqi order, when `columns` are its
/// joints ([`are_arm_joints`]); `None` otherwise.
pub fn arm_ranges(columns: &[String]) -> Option<Vec<(f64, f64)>> {
    are_arm_joints(columns).then(|| {
        let joints = nao_left_arm().joints;
        joints.iter().map(|j| (j.lower, j.upper)).collect()
    })
}

/// How far beyond a joint's range a recorded or reproduced value may lie and still be scored,
/// rad: encoders read a hair beyond a limit, and the simulated joints' soft limits let a
/// motion driven into a limit pass it by up to 0.07 rad (measured on the shuffled controls of
/// tests/gesture_fidelity.rs).
pub const RANGE_TOLERANCE_RAD: f64 = 0.25;

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
    let ranges = mjcf_ranges(&xml).map_err(bad)?;
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

/// `(name, lower, upper)` of every named `<joint>` with a `range` in an MJCF text.
fn mjcf_ranges(xml: &str) -> Result<Vec<(String, f64, f64)>, String> {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut out = Vec::new();
    loop {
        match reader.read_event() {
            Ok(Event::Start(e)) | Ok(Event::Empty(e)) if e.name().as_ref() == b"joint" => {
                let mut name = None;
                let mut range = None;
                for a in e.attributes().flatten() {
                    let v = String::from_utf8_lossy(&a.value).to_string();
                    match a.key.as_ref() {
                        b"name" => name = Some(v),
                        b"range" => range = Some(v),
                        _ => {}
                    }
                }
                if let (Some(n), Some(r)) = (name, range) {
                    let v: Vec<f64> = r
                        .split_whitespace()
                        .map(|x| x.parse::<f64>())
                        .collect::<Result<_, _>>()
                        .map_err(|_| format!("joint `{n}`: range `{r}` is not two numbers"))?;
                    match v.as_slice() {
                        [a, b] if a.is_finite() && b.is_finite() && a < b => out.push((n, *a, *b)),
                        _ => {
                            return Err(format!(
                                "joint `{n}`: range `{r}` is not `lower upper` with lower < upper"
                            ))
                        }
                    }
                }
            }
            Ok(Event::Eof) => break,
            Err(e) => return Err(format!("not well-formed XML: {e}")),
            _ => {}
        }
    }
    Ok(out)
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
