//! `cosco export` and `cosco demos import`: the arguments, parsed and handed to
//! [`cosco_hsom::app`].

#[cfg(feature = "ros2")]
use std::path::PathBuf;

use anyhow::Result;
use cosco_hsom::app;
use cosco_hsom::export::ExportRequest;

/// `cosco export`: the report's lines.
pub fn export(a: &ExportRequest) -> Result<Vec<String>> {
    Ok(app::export(a)?)
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
