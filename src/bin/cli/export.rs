//! `cosco export` and `cosco demos import`: the arguments, parsed and handed to
//! [`cosco_hsom::app`].

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use cosco_hsom::app;
use cosco_hsom::export::{limits, source, ExportRequest, Format};

/// `cosco export`.
#[derive(Args)]
pub struct ExportArgs {
    /// A reproduction CSV (`cosco reproduce`'s, GMM/GMR's, any CSV with `time` or `step`
    /// then one column per joint).
    #[arg(long, conflicts_with = "model", required_unless_present = "model")]
    reproduction: Option<PathBuf>,
    /// Or a model saved by `cosco train`, reproduced from --initial or --initial-from.
    #[arg(long)]
    model: Option<PathBuf>,
    /// The initial posture, comma-separated (with --model).
    #[arg(long, requires = "model", conflicts_with = "initial_from")]
    initial: Option<String>,
    /// Take the initial posture from the first row of this CSV (with --model).
    #[arg(long, requires = "model")]
    initial_from: Option<PathBuf>,
    /// The gesture to reproduce (a model of several gestures).
    #[arg(long, requires = "model")]
    gesture: Option<String>,
    /// Output format: naoqi (JSON for ALMotion.angleInterpolation), ros2 (MCAP with a
    /// trajectory_msgs/msg/JointTrajectory) or csv.
    #[arg(long)]
    format: Format,
    /// Output file.
    #[arg(long)]
    out: PathBuf,
    /// Play the motion this many times faster (0.5: half as fast).
    #[arg(long, conflicts_with = "duration")]
    speed: Option<f64>,
    /// Stretch or squeeze the motion to last this many seconds.
    #[arg(long)]
    duration: Option<f64>,
    /// Fraction of each joint's documented maximum velocity the motion may reach.
    #[arg(long, default_value_t = limits::DEFAULT_VELOCITY_FRACTION)]
    velocity_fraction: f64,
    /// Slow the whole motion down to the velocity limit instead of refusing it (reported).
    #[arg(long)]
    clamp: bool,
    /// CSV output rate, Hz (default: the trajectory's own points).
    #[arg(long)]
    rate: Option<f64>,
    /// Rate of a `step` column (a reproduction without `time`), Hz.
    #[arg(long, default_value_t = source::DEFAULT_STEP_RATE_HZ)]
    step_rate: f64,
    /// Another robot: the joint ranges from this MJCF file (with --velocity-table).
    #[arg(long, requires = "velocity_table")]
    mjcf: Option<PathBuf>,
    /// Another robot: CSV `joint,max_velocity` of the joints to export (with --mjcf).
    #[arg(long, requires = "mjcf")]
    velocity_table: Option<PathBuf>,
    /// With --format ros2: also execute the motion on the simulated arm and record its
    /// joints as sensor_msgs/msg/JointState on /joint_states at 40 Hz.
    #[cfg(feature = "sim")]
    #[arg(long)]
    executed: bool,
}

/// `cosco export`: the report's lines.
pub fn export(a: &ExportArgs) -> Result<Vec<String>> {
    let request = ExportRequest {
        reproduction: a.reproduction.clone(),
        model: a.model.clone(),
        initial: a.initial.clone(),
        initial_from: a.initial_from.clone(),
        gesture: a.gesture.clone(),
        format: a.format,
        out: a.out.clone(),
        speed: a.speed,
        duration: a.duration,
        velocity_fraction: a.velocity_fraction,
        clamp: a.clamp,
        rate: a.rate,
        step_rate: a.step_rate,
        mjcf: a.mjcf.clone(),
        velocity_table: a.velocity_table.clone(),
        #[cfg(feature = "sim")]
        executed: a.executed,
        #[cfg(not(feature = "sim"))]
        executed: false,
    };
    Ok(app::export(&request)?)
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
        /// Joints to keep, comma-separated, in this column order (default: the arm's six).
        #[arg(long, value_delimiter = ',')]
        joints: Vec<String>,
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
            split_idle,
        } => Ok(app::import(bag, topic, joints, *split_idle, out)?),
    }
}
