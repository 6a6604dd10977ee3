//! `cosco export` as one call once the trajectory is built (`app::export` builds it from a
//! reproduction file or a model reproduced from an initial posture): its arguments
//! ([`ExportRequest`], which the binary parses), which robot's limits the trajectory is
//! checked against, the time scaling, the optional execution on the simulated arm, the file.

use std::path::PathBuf;

use clap::Args;

use crate::condition::{PostureArg, ViaPoint};

use super::{encode, limits, prepare, ExportError, Format, Trajectory};

/// Rate of a reproduction's `step` column when the file has no `time` column: the arm's
/// encoders' (the demonstrations' clock), Hz.
pub const DEFAULT_STEP_RATE_HZ: f64 = 40.0;

/// Everything `cosco export` is asked: its command line.
#[derive(Debug, Clone, Args)]
pub struct ExportRequest {
    /// A reproduction CSV (`cosco reproduce`'s, GMM/GMR's, any CSV with `time` or `step`
    /// then one column per joint).
    #[arg(long, conflicts_with = "model", required_unless_present = "model")]
    pub reproduction: Option<PathBuf>,
    /// Or a model saved by `cosco train`, reproduced from --initial or --initial-from.
    #[arg(long)]
    pub model: Option<PathBuf>,
    /// The initial posture, comma-separated (with --model).
    #[arg(
        long,
        allow_hyphen_values = true,
        requires = "model",
        conflicts_with = "initial_from"
    )]
    pub initial: Option<PostureArg>,
    /// Take the initial posture from the first row of this CSV (with --model).
    #[arg(long, requires = "model")]
    pub initial_from: Option<PathBuf>,
    /// The gesture to reproduce (a model of several gestures).
    #[arg(long, requires = "model")]
    pub gesture: Option<String>,
    /// The last posture, comma-separated (with --model): the reproduction ends exactly there.
    #[arg(long, allow_hyphen_values = true, requires = "model")]
    pub goal: Option<PostureArg>,
    /// A posture to pass at a phase (with --model): `PHASE:V1,V2,...`; repeatable.
    #[arg(long, allow_hyphen_values = true, requires = "model")]
    pub via: Vec<ViaPoint>,
    /// Also write the reproduction's 95 % confidence band to this CSV (with --model), as
    /// `cosco reproduce --band` does.
    #[arg(long, requires = "model")]
    pub band: Option<PathBuf>,
    /// Output format: naoqi (JSON for ALMotion.angleInterpolation), ros2 (MCAP with a
    /// trajectory_msgs/msg/JointTrajectory) or csv.
    #[arg(long)]
    pub format: Format,
    /// Output file.
    #[arg(long)]
    pub out: PathBuf,
    /// Play the motion this many times faster (0.5: half as fast).
    #[arg(long, conflicts_with = "duration")]
    pub speed: Option<f64>,
    /// Stretch or squeeze the motion to last this many seconds.
    #[arg(long)]
    pub duration: Option<f64>,
    /// Fraction of each joint's documented maximum velocity the motion may reach.
    #[arg(long, default_value_t = limits::DEFAULT_VELOCITY_FRACTION)]
    pub velocity_fraction: f64,
    /// Slow the whole motion down to the velocity limit instead of refusing it (reported).
    #[arg(long)]
    pub clamp: bool,
    /// CSV output rate, Hz (default: the trajectory's own points).
    #[arg(long)]
    pub rate: Option<f64>,
    /// Rate of a `step` column (a reproduction without `time`), Hz.
    #[arg(long, default_value_t = DEFAULT_STEP_RATE_HZ)]
    pub step_rate: f64,
    /// Another robot: the joint ranges from this MJCF file (with --velocity-table).
    #[arg(long, requires = "velocity_table")]
    pub mjcf: Option<PathBuf>,
    /// Another robot: CSV `joint,max_velocity` of the joints to export (with --mjcf).
    #[arg(long, requires = "mjcf")]
    pub velocity_table: Option<PathBuf>,
    /// With --format ros2: also execute the motion on the simulated arm and record its
    /// joints as sensor_msgs/msg/JointState on /joint_states at 40 Hz.
    #[cfg_attr(feature = "sim", arg(long))]
    #[cfg_attr(not(feature = "sim"), arg(skip))]
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
