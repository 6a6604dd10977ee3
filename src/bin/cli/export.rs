//! `cosco export` and `cosco demos import`: the arguments, parsed and handed to the library
//! ([`cosco_hsom::export`], [`cosco_hsom::ros2`]).

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;
use cosco_hsom::export::{self, limits, source, ExportOptions, Format, Timing};

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
    cosco_hsom::steps::check_output(&a.out)?;
    let t = match (&a.reproduction, &a.model) {
        (Some(r), _) => source::from_reproduction_file(r, a.step_rate)?,
        (None, Some(m)) => {
            let values;
            let initial = match (&a.initial, &a.initial_from) {
                (Some(text), None) => {
                    values = cosco_hsom::commands::parse_posture(text)?;
                    source::Initial::Values(&values)
                }
                (None, Some(p)) => source::Initial::From(p),
                _ => bail!("with --model, give exactly one of --initial and --initial-from"),
            };
            source::from_model(m, a.gesture.as_deref(), initial, a.step_rate)?
        }
        (None, None) => bail!("give --reproduction FILE or --model FILE"),
    };
    let robot = match (&a.mjcf, &a.velocity_table) {
        (Some(m), Some(v)) => limits::from_mjcf(m, &limits::read_velocity_table(v)?)?,
        _ => limits::nao_left_arm(),
    };
    let opts = ExportOptions {
        format: a.format,
        timing: match (a.speed, a.duration) {
            (Some(s), _) => Timing::Speed(s),
            (None, Some(d)) => Timing::Duration(d),
            (None, None) => Timing::AsIs,
        },
        velocity_fraction: a.velocity_fraction,
        clamp: a.clamp,
        rate_hz: a.rate,
    };
    #[cfg(feature = "sim")]
    let arm = if a.executed {
        if a.format != Format::Ros2 {
            bail!("--executed goes with --format ros2");
        }
        Some(cosco_hsom::experiment::job::load_arm(None)?)
    } else {
        None
    };
    #[cfg(feature = "sim")]
    let run = arm.as_ref().map(|arm| {
        move |t: &export::Trajectory| {
            export::executed::execute_on_arm(arm, t, cosco_hsom::sim::DEFAULT_RECORD_RATE_HZ)
        }
    });
    #[cfg(feature = "sim")]
    let execute = run.as_ref().map(|f| f as export::Execute<'_>);
    #[cfg(not(feature = "sim"))]
    let execute = None;
    let report = export::export_to(&t, &robot, &opts, execute, &a.out)?;
    let mut lines = report.lines();
    lines.push(format!("written {}", a.out.display()));
    Ok(lines)
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
        } => {
            let files =
                cosco_hsom::ros2::import::import_to_dir(bag, topic, joints, *split_idle, out)?;
            Ok(files
                .iter()
                .map(|(f, d)| {
                    format!(
                        "{} ({} samples, {:.3} s)",
                        f.display(),
                        d.len(),
                        d.time.as_ref().map_or(0.0, |t| t[t.len() - 1])
                    )
                })
                .collect())
        }
    }
}
