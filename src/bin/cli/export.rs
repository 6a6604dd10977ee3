//! `cosco export` and `cosco demos import`: the arguments, parsed and handed to
//! [`cosco_hsom::app`].

use std::path::PathBuf;

use anyhow::Result;
use cosco_hsom::app::{self, ExportFrom, ReproduceRequest};
use cosco_hsom::condition::{PostureArg, ViaPoint};
use cosco_hsom::export::{limits, ExportRequest, Format, DEFAULT_STEP_RATE_HZ};
use cosco_hsom::robot::Robot;

/// Everything `cosco export` is asked: its command line.
#[derive(Debug, Clone, clap::Args)]
pub struct ExportArgs {
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
    /// Point at X,Y,Z (with --model; metres, torso frame), as `cosco reproduce --point-at`.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = cosco_hsom::aim::parse_point, requires = "model")]
    pub point_at: Option<[f64; 3]>,
    /// Look at X,Y,Z (with --model; the upper body), as `cosco reproduce --look-at`.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = cosco_hsom::aim::parse_point, requires = "model")]
    pub look_at: Option<[f64; 3]>,
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
    /// The robot the motion is for: left-arm or upper-body (default: the robot whose joints
    /// the motion's columns are, else left-arm). Its joints' ranges and velocity limits apply;
    /// on the upper body the motion is first executed on the simulated robot (joints not
    /// exported hold StandInit) and refused if two parts come into contact.
    #[arg(long)]
    pub robot: Option<Robot>,
    /// Export a motion that brings two parts of the robot into contact anyway (said in the
    /// report, with every contact).
    #[arg(long)]
    pub allow_contact: bool,
    /// The demonstrations the motion was learned from (a directory of CSVs or files): a
    /// contact every one of them makes, executed on the simulated robot (the clap's hands), is
    /// the gesture's own and is exported, said so. Without it, a --model's kept demonstrations
    /// say it, and a --reproduction has no contact of its own.
    #[arg(long, num_args = 1..)]
    pub demos: Vec<PathBuf>,
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

/// `cosco export`: the report's lines.
pub fn export(a: ExportArgs) -> Result<Vec<String>> {
    let from = match (a.reproduction, a.model) {
        (Some(path), _) => ExportFrom::Reproduction(path),
        (None, Some(model)) => ExportFrom::Model(Box::new(ReproduceRequest {
            model,
            gesture: a.gesture,
            initial: a.initial,
            initial_from: a.initial_from,
            goal: a.goal,
            via: a.via,
            band: a.band,
            robot: None,
            duration: None,
            aim: cosco_hsom::aim::Aim {
                point_at: a.point_at,
                look_at: a.look_at,
            },
        })),
        (None, None) => anyhow::bail!("--reproduction: give --reproduction FILE or --model FILE"),
    };
    let request = ExportRequest {
        format: a.format,
        out: a.out,
        speed: a.speed,
        duration: a.duration,
        velocity_fraction: a.velocity_fraction,
        clamp: a.clamp,
        rate: a.rate,
        step_rate: a.step_rate,
        mjcf: a.mjcf,
        velocity_table: a.velocity_table,
        executed: a.executed,
        robot: a.robot,
        allow_contact: a.allow_contact,
        own_contacts: match a.demos.is_empty() {
            true => Vec::new(),
            false => {
                app::own_contacts(&app::files::read_demos(&a.demos, None, None)?, a.step_rate)?
            }
        },
    };
    Ok(app::export(&from, &request)?)
}

/// `cosco demos import`: what `cosco demos` does besides recording.
#[cfg(feature = "ros2")]
#[derive(clap::Subcommand)]
pub enum DemosAction {
    /// Demonstrations from a ROS 2 bag (MCAP): the sensor_msgs/msg/JointState messages of a
    /// topic, `time` from their stamps, one column per joint; one CSV per bag, or one per
    /// stretch of motion with --split-idle.
    Import {
        /// The bag: an MCAP file.
        #[arg(long)]
        bag: PathBuf,
        /// The topic of sensor_msgs/msg/JointState messages.
        #[arg(long, default_value = cosco_hsom::ros2::JOINT_STATES_TOPIC)]
        topic: String,
        /// Output directory (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Joints to keep, comma-separated, in this column order (default: the --robot's).
        #[arg(long, value_delimiter = ',', conflicts_with = "robot")]
        joints: Vec<String>,
        /// Keep this robot's joints, in NAOqi order: left-arm (6) or upper-body (14 of the
        /// whole Nao's JointState: the head and both arms).
        #[arg(long, default_value = "left-arm")]
        robot: Robot,
        /// Split at pauses of at least this many seconds (every joint below 0.05 rad/s).
        #[arg(long)]
        split_idle: Option<f64>,
    },
}

/// Run a `cosco demos` action: the lines to print.
#[cfg(feature = "ros2")]
pub fn demos_action(a: &DemosAction) -> Result<Vec<String>> {
    match a {
        DemosAction::Import {
            bag,
            topic,
            out,
            joints,
            robot,
            split_idle,
        } => {
            let joints = match joints.is_empty() {
                true => robot.joint_names().iter().map(|j| j.to_string()).collect(),
                false => joints.clone(),
            };
            Ok(app::import(bag, topic, &joints, *split_idle, out)?)
        }
    }
}
