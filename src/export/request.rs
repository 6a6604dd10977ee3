//! `cosco export` as one call once the trajectory is built (`app::export` builds it from a
//! reproduction file or a model reproduced from an initial posture): what it is asked
//! ([`ExportRequest`]), which robot's limits the trajectory is checked against, the time
//! scaling, the optional execution on the simulated arm, the file.

use std::path::PathBuf;

use super::{encode, limits, prepare, ExportError, Format, Trajectory};
use crate::robot::Robot;

/// Rate of a reproduction's `step` column when the file has no `time` column: the arm's
/// encoders' (the demonstrations' clock), Hz.
pub const DEFAULT_STEP_RATE_HZ: f64 = 40.0;

/// What `cosco export` is asked once the trajectory is built: the format and file, the
/// timing, the limits, the robot.
#[derive(Debug, Clone)]
pub struct ExportRequest {
    /// Output format.
    pub format: Format,
    /// Output file.
    pub out: PathBuf,
    /// Play the motion this many times faster (0.5: half as fast).
    pub speed: Option<f64>,
    /// Or stretch or squeeze the motion to last this many seconds.
    pub duration: Option<f64>,
    /// Fraction of each joint's documented maximum velocity the motion may reach
    /// ([`limits::DEFAULT_VELOCITY_FRACTION`] by default).
    pub velocity_fraction: f64,
    /// Slow the whole motion down to the velocity limit instead of refusing it (reported).
    pub clamp: bool,
    /// CSV output rate, Hz (`None`: the trajectory's own points).
    pub rate: Option<f64>,
    /// Rate of a `step` column (a reproduction without `time`), Hz
    /// ([`DEFAULT_STEP_RATE_HZ`] by default).
    pub step_rate: f64,
    /// The robot the motion is for: its joints' limits, and on the upper body (whose model has
    /// collision shapes) the contact check: the motion is executed on the simulated robot
    /// first, the joints not exported holding `StandInit` (feature `sim`). `None`: the robot
    /// whose joints the trajectory's columns are ([`Robot::of_columns`]), else the left arm.
    pub robot: Option<Robot>,
    /// Export a motion that brings two parts of the robot into contact anyway (reported).
    pub allow_contact: bool,
    /// The gesture's own contacts: pairs of limbs ([`crate::sim::Touch::limbs`]) that every
    /// demonstration of the gesture brings into contact (the clap's hands). A contact between
    /// them is exported and reported as the gesture's own; every other is refused.
    pub own_contacts: Vec<[String; 2]>,
    /// Another robot: the joint ranges from this MJCF file (with `velocity_table`).
    pub mjcf: Option<PathBuf>,
    /// Another robot: CSV `joint,max_velocity` of the joints to export (with `mjcf`).
    pub velocity_table: Option<PathBuf>,
    /// With the ROS 2 format: also execute the motion on the simulated arm and record its
    /// joints as sensor_msgs/msg/JointState on /joint_states at 40 Hz (feature `sim`).
    pub executed: bool,
}

/// `cosco export` once the output's place is checked and the trajectory `t` built
/// (`app::export`): check it against the robot's limits (`r.robot`'s, or `mjcf` with
/// `velocity_table`), scale its timing ([`prepare`]); execute it on the simulated robot when
/// asked or when the robot's model has collision shapes (with the feature `sim`; without it
/// nothing is executed), refusing a motion that brings two parts into contact unless
/// `r.allow_contact`; write it atomically (with `executed`, the recording goes into the MCAP
/// file). Returns the report's lines.
pub fn export_request(r: &ExportRequest, t: &Trajectory) -> Result<Vec<String>, ExportError> {
    let robot = (r.robot)
        .or_else(|| Robot::of_columns(&t.names))
        .unwrap_or(Robot::LeftArm);
    let limits = match (&r.mjcf, &r.velocity_table) {
        (Some(m), Some(v)) => limits::from_mjcf(m, &limits::read_velocity_table(v)?)?,
        _ => limits::RobotLimits::of(robot),
    };
    if r.executed && r.format != Format::Ros2 {
        return Err(ExportError::Usage(
            "--executed goes with --format ros2".into(),
        ));
    }
    let (t, report) = prepare(t, &limits, r)?;
    let mut lines = report.lines();
    let checks_contacts = robot.has_collision_shapes();
    #[cfg(feature = "sim")]
    let executed = match r.executed || checks_contacts {
        true => Some(super::executed::execute(
            robot,
            &t,
            crate::sim::DEFAULT_RECORD_RATE_HZ,
        )?),
        false => None,
    };
    #[cfg(feature = "sim")]
    if checks_contacts {
        let contacts = &executed.as_ref().map_or(&[][..], |e| &e.contacts[..]);
        lines.extend(contact_lines(r, robot, contacts)?);
    }
    #[cfg(feature = "sim")]
    let executed = executed.filter(|_| r.executed).map(|e| e.encoders);
    #[cfg(not(feature = "sim"))]
    let executed = None;
    #[cfg(not(feature = "sim"))]
    if checks_contacts {
        lines.push(format!(
            "contacts: not checked (this build has no simulator to execute the motion on the {})",
            robot.name()
        ));
    }
    let bytes = encode(&t, r.format, executed.as_ref())?;
    crate::fsutil::write_atomic(&r.out, &bytes).map_err(|source| ExportError::Write {
        path: r.out.display().to_string(),
        source,
    })?;
    lines.push(format!("written {}", r.out.display()));
    Ok(lines)
}

/// The report's lines on the contacts of the motion executed on the simulated robot, or the
/// refusal of the first one (unless `r.allow_contact`).
#[cfg(feature = "sim")]
fn contact_lines(
    r: &ExportRequest,
    robot: Robot,
    contacts: &[crate::sim::Touch],
) -> Result<Vec<String>, ExportError> {
    let robot = robot.name().replace('-', " ");
    let own = |c: &&crate::sim::Touch| r.own_contacts.contains(&c.limbs());
    let (mine, others): (Vec<_>, Vec<_>) = contacts.iter().partition(own);
    let mut lines: Vec<String> = Vec::new();
    if !mine.is_empty() {
        lines.push(format!(
            "contacts of the gesture's own (every demonstration makes them; {} contact(s)):",
            mine.len()
        ));
        lines.extend(mine.iter().map(|c| format!("  {}", c.describe())));
    }
    match others.first() {
        None if mine.is_empty() => Ok(vec![format!(
            "contacts: none (the motion executed on the simulated {robot})"
        )]),
        None => Ok(lines),
        Some(c) if !r.allow_contact => Err(ExportError::Contact {
            time_s: c.start_s,
            parts: c.parts.clone(),
            depth_m: c.depth_m,
            robot,
        }),
        Some(_) => {
            lines.push(format!(
                "--allow-contact: exported although the motion brings two parts of the simulated {robot} into contact ({} contact(s)):",
                others.len()
            ));
            lines.extend(others.iter().map(|c| format!("  {}", c.describe())));
            Ok(lines)
        }
    }
}
