//! `cosco export` as one call once the trajectory is built (`app::export` builds it from a
//! reproduction file or a model reproduced from an initial posture): what it is asked
//! ([`ExportRequest`]), which robot's limits the trajectory is checked against, the time
//! scaling, the optional execution on the simulated arm, the file.

use std::path::PathBuf;

use super::{encode, limits, prepare, ExportError, Format, Trajectory};

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
    /// Another robot: the joint ranges from this MJCF file (with `velocity_table`).
    pub mjcf: Option<PathBuf>,
    /// Another robot: CSV `joint,max_velocity` of the joints to export (with `mjcf`).
    pub velocity_table: Option<PathBuf>,
    /// With the ROS 2 format: also execute the motion on the simulated arm and record its
    /// joints as sensor_msgs/msg/JointState on /joint_states at 40 Hz (feature `sim`).
    pub executed: bool,
}

/// `cosco export` once the output's place is checked and the trajectory `t` built
/// (`app::export`): check it against the robot's limits (the Nao left arm's, or `mjcf` with
/// `velocity_table`), scale its timing ([`prepare`]), execute it on the simulated arm when
/// asked (with the feature `sim`; without it nothing is executed; the recording goes into the
/// MCAP file), and write it atomically. Returns the report's lines.
pub fn export_request(r: &ExportRequest, t: &Trajectory) -> Result<Vec<String>, ExportError> {
    let robot = match (&r.mjcf, &r.velocity_table) {
        (Some(m), Some(v)) => limits::from_mjcf(m, &limits::read_velocity_table(v)?)?,
        _ => limits::nao_left_arm(),
    };
    if r.executed && r.format != Format::Ros2 {
        return Err(ExportError::Usage(
            "--executed goes with --format ros2".into(),
        ));
    }
    #[cfg(feature = "sim")]
    let arm = match r.executed {
        true => {
            Some(crate::sim::NaoArm::load_default().map_err(|e| ExportError::Arm(Box::new(e)))?)
        }
        false => None,
    };
    let (t, report) = prepare(t, &robot, r)?;
    #[cfg(feature = "sim")]
    let executed = match &arm {
        Some(arm) => Some(super::executed::execute_on_arm(
            arm,
            &t,
            crate::sim::DEFAULT_RECORD_RATE_HZ,
        )?),
        None => None,
    };
    #[cfg(not(feature = "sim"))]
    let executed = None;
    let bytes = encode(&t, r.format, executed.as_ref())?;
    crate::fsutil::write_atomic(&r.out, &bytes).map_err(|source| ExportError::Write {
        path: r.out.display().to_string(),
        source,
    })?;
    let mut lines = report.lines();
    lines.push(format!("written {}", r.out.display()));
    Ok(lines)
}
