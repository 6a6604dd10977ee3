//! The command line of `cosco` (clap definitions only).

use std::path::PathBuf;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(
    name = "cosco",
    version,
    about = "CoSCo-HSOM: learn a gesture from raw demonstrations, reproduce it from the initial posture"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    #[cfg(feature = "sim")]
    /// Record synthetic, human-like demonstrations of a gesture on the simulated arm (40 Hz
    /// encoders); `demos import`: from a ROS 2 bag.
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Demos {
        #[cfg(feature = "ros2")]
        #[command(subcommand)]
        action: Option<super::export::DemosAction>,
        /// The robot: `left-arm` (the paper's experiment) or `upper-body` (the head and both
        /// arms, 14 joints).
        #[arg(long, default_value = "left-arm")]
        robot: cosco_hsom::robot::Robot,
        /// Gesture name (left arm: reading-watch, wave, reach-point, salute; upper body:
        /// wave-right, clap, welcome, shrug, nod, shake-head, reading-watch, salute), or `all`:
        /// every gesture of the robot, each in its own labelled subdirectory of --out
        /// (OUT/<gesture>/demo_01.csv, ...).
        #[arg(long, default_value = "reading-watch")]
        gesture: String,
        /// Number of demonstrations.
        #[arg(long, default_value_t = 3, allow_negative_numbers = true, value_parser = super::parse_count)]
        count: usize,
        /// Seed of every random choice.
        #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = super::parse_seed)]
        seed: u64,
        /// Output directory (created if missing); files demo_01.csv, demo_02.csv, ...
        #[arg(long, required = true)]
        out: Option<PathBuf>,
        /// Standard deviation of the encoder noise, rad: 0 to 0.1 (a real encoder's noise is
        /// far below 0.1 rad, about 6 degrees; more would hide the gesture).
        #[arg(long, default_value_t = cosco_hsom::experiment::job::DEFAULT_ENCODER_NOISE, allow_negative_numbers = true, value_parser = super::parse_noise)]
        noise: f64,
        /// MJCF model of the robot (default: its shipped model under models/).
        #[arg(long)]
        model: Option<PathBuf>,
    },
    #[cfg(all(feature = "ros2", not(feature = "sim")))]
    /// `demos import`: demonstrations from a ROS 2 bag.
    Demos {
        #[command(subcommand)]
        action: super::export::DemosAction,
    },
    /// Export a reproduction for a real robot: NAOqi JSON, ROS 2 MCAP or CSV, time-scaled
    /// and checked against the robot's joint ranges and velocity limits.
    Export(super::export::ExportArgs),
    /// Train a CoSCo-HSOM hierarchy on demonstration CSV files and save it (.bin or .txt).
    Train {
        /// XML configuration (default: the built-in configs/nao-upper-body.xml for demonstrations
        /// of the upper body's joints, else configs/nao-gestures.xml, the recommended events
        /// extension).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Demonstrations: a directory of *.csv files, or files (one gesture); or directories
        /// whose subdirectories are gesture labels (DIR/<label>/*.csv: several gestures in one
        /// hierarchy).
        #[arg(long, num_args = 1.., required = true)]
        demos: Vec<PathBuf>,
        /// Where to save the model: `.bin` (binary) or `.txt` (plain text).
        #[arg(long)]
        out: PathBuf,
        /// Take stateLength and actionLength from the demonstrations' columns.
        #[arg(long)]
        state_length_from_data: bool,
        /// Resample demonstrations with `time` columns to this rate, Hz (shape-preserving).
        #[arg(long)]
        resample: Option<f64>,
        /// Teach this saved model the demonstrations (more of its gesture; with labelled
        /// directories, more of its gestures or new ones) instead of training a new one, from
        /// the model and the new files alone; --out gets the updated model.
        #[arg(long, conflicts_with = "state_length_from_data")]
        from: Option<PathBuf>,
    },
    /// Reproduce a gesture from an initial posture with a saved model; writes `step` then the
    /// demonstrations' columns.
    Reproduce(super::reproduce::ReproduceArgs),
    /// Recognise demonstrations with a model of several gestures: per file the label (or
    /// `unknown`), a score per label and the earliest sample from which the decision held.
    Recognize {
        /// A model trained on labelled directories (`cosco train --demos DIR`, DIR/<label>/*.csv).
        #[arg(long)]
        model: PathBuf,
        /// A demonstration CSV, a directory of them, or a directory of label subdirectories.
        #[arg(long, required_unless_present = "stream")]
        demos: Option<PathBuf>,
        /// Also write every answer as JSON here.
        #[arg(long, conflicts_with = "stream")]
        json: Option<PathBuf>,
        /// Recognise in the loop: CSV rows from standard input as they come (a header of the
        /// model's columns, an optional first `time` column); a line when the recogniser
        /// commits to a label or to unknown, the whole sequence's answer at the end.
        #[arg(long, conflicts_with = "demos")]
        stream: bool,
    },
    /// `cosco heldout --recognition` as a hidden alias, for scripts that call it by this name.
    #[command(hide = true, group = clap::ArgGroup::new("taught_given").args(["taught"]).required(true))]
    Recognition {
        #[command(flatten)]
        study: RecognitionArgs,
        #[command(flatten)]
        common: StudyArgs,
    },
    /// Held out on your own demonstrations, without the simulator. With --demos: for each
    /// demonstration, learn from the others, reproduce from its first sample, score against
    /// it; the hierarchy beside the nearest sequence, height 1, GMM/GMR, ProMP and a replay, on
    /// the same folds. With --recognition: for each taught demonstration, one hierarchy learns
    /// every other taught one and recognises it (accepted: its own label); every untaught
    /// demonstration is recognised by the hierarchy taught all (right: `unknown`); the
    /// untrained hierarchy beside it as the control. Markdown on stdout.
    #[command(group = clap::ArgGroup::new("recognition_study")
        .args(["taught", "untaught", "no_control", "one_at_a_time", "stream"]).multiple(true).requires("recognition"))]
    Heldout {
        /// Demonstrations: a directory of *.csv files or files (one gesture), or directories of
        /// gesture subdirectories (DIR/<gesture>/*.csv, each gesture on its own); at least 3
        /// per gesture.
        #[arg(long, num_args = 1.., required_unless_present = "recognition")]
        demos: Vec<PathBuf>,
        /// The recognition study (with --taught and --untaught) instead of reproduction.
        #[arg(long, requires = "taught", conflicts_with_all = ["demos", "no_height_1", "no_gmr", "no_promp", "no_dmp", "no_dba", "no_in_sample", "condition", "far", "sittings"])]
        recognition: bool,
        #[command(flatten)]
        study: Option<RecognitionArgs>,
        #[command(flatten)]
        common: StudyArgs,
        /// Leave out the configuration at height 1.
        #[arg(long)]
        no_height_1: bool,
        /// Leave out GMM/GMR.
        #[arg(long)]
        no_gmr: bool,
        /// Leave out ProMP.
        #[arg(long)]
        no_promp: bool,
        /// Leave out the DMP.
        #[arg(long)]
        no_dmp: bool,
        /// Leave out the DTW mean (DBA).
        #[arg(long)]
        no_dba: bool,
        /// Also run every fold conditioned on the held-out demonstration's last posture
        /// (`end`), or on it and its posture at phase 0.5 (`end+mid`), beside the
        /// unconditioned run.
        #[arg(long, value_name = "end|end+mid")]
        condition: Option<Condition>,
        /// Also run every fold with its goal moved K times the training demonstrations' end
        /// spread away from their mean end (extrapolation), scored against the held-out
        /// demonstration shifted as far; repeatable.
        #[arg(long, value_name = "K")]
        far: Vec<f64>,
        /// Also teach every fold in two sittings (half its training demonstrations, then an
        /// update with the rest) beside the model taught at once.
        #[arg(long)]
        sittings: bool,
        /// Leave out the in-sample result (learned from all).
        #[arg(long)]
        no_in_sample: bool,
        /// Also run every fold in the loop (each method's stepper, the arm going where it is
        /// commanded) disturbed: `hold:P:D` (held from phase P for D of the duration) or
        /// `move:P:D:K` (moved K x the diagonal at phase P and held for D); repeatable.
        #[arg(long, value_name = "hold:P:D|move:P:D:K", value_parser = cosco_hsom::stepper::Disturbance::kinematic)]
        disturb: Vec<cosco_hsom::stepper::Disturbance>,
        /// Also run every fold in the loop with its goal moved K x the diagonal at phase P.
        #[arg(long, value_name = "P:K", value_parser = cosco_hsom::stepper::Disturbance::goal_moves)]
        goal_moves: Vec<cosco_hsom::stepper::Disturbance>,
        /// Also draw one fold per gesture (the first sample's plane) as a PNG here.
        #[cfg(feature = "plot")]
        #[arg(long)]
        png: Option<PathBuf>,
    },
    /// Print a saved model's levels, sizes and quality measures.
    Inspect {
        /// A model saved by `cosco train` (.bin or .txt).
        model: PathBuf,
    },
    /// Fidelity metrics of a reproduction CSV against demonstrations (docs/METRICS.md).
    Evaluate {
        /// Reproduction CSV (`time` or `step` column, then the demonstrations' columns).
        #[arg(long)]
        reproduction: PathBuf,
        /// Demonstrations: a directory of *.csv files, or files.
        #[arg(long, num_args = 1.., required = true)]
        demos: Vec<PathBuf>,
        /// Also write the full report as JSON here.
        #[arg(long)]
        json: Option<PathBuf>,
        /// MJCF model of the arm, for wrist paths (default: the crate's model).
        #[cfg(feature = "sim")]
        #[arg(long)]
        model: Option<PathBuf>,
    },
    #[cfg(feature = "sim")]
    /// Compare CoSCo-HSOM with the paper's GMM/GMR baseline on the same demonstrations, both
    /// executed on the simulated arm from the same initial posture (report, csvs, plots).
    Compare {
        /// Directory of demonstration CSVs (columns: time, then the arm's six joints).
        #[arg(long)]
        demos: PathBuf,
        /// CoSCo-HSOM configuration (XML); default: the built-in configs/nao-gestures.xml.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Output directory (created if missing).
        #[arg(long, default_value = "out-compare")]
        out: PathBuf,
        /// GMM components: a number K >= 1, or `bic` (lowest BIC over 1..=16).
        #[arg(long, default_value = "bic", value_parser = cosco_hsom::experiment::compare::parse_components)]
        components: cosco_hsom::gmr::ComponentChoice,
        /// How CoSCo-HSOM's postures become servo targets: `linear` (the paper) or
        /// `min-jerk[:TOL]` (as for `simulate`).
        #[arg(long, default_value = "linear")]
        transition: String,
        /// MJCF model of the arm.
        #[arg(long)]
        model: Option<PathBuf>,
        /// Resample demonstrations with `time` columns to this rate, Hz (shape-preserving).
        #[arg(long)]
        resample: Option<f64>,
    },
    #[cfg(feature = "sim")]
    /// Run a sweep: every combination of the axes of a TOML spec (docs/SWEEPS.md), one JSON
    /// file per run in DIR/runs, finished runs skipped; `merge` makes the tables and plots.
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Sweep(super::sweep::SweepArgs),
}

/// `--condition`: what every fold is also conditioned on ([`cosco_hsom::eval::Conditioning`]).
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum Condition {
    /// Also the held-out demonstration's last posture, as the goal.
    #[value(name = "end")]
    End,
    /// Also its last posture and its posture at phase 0.5, as a via-point.
    #[value(name = "end+mid")]
    EndMid,
}

impl From<Condition> for cosco_hsom::eval::Conditioning {
    fn from(c: Condition) -> Self {
        match c {
            Condition::End => cosco_hsom::eval::Conditioning::End,
            Condition::EndMid => cosco_hsom::eval::Conditioning::EndMid,
        }
    }
}

/// The recognition study's demonstrations (`cosco heldout --recognition`).
#[derive(clap::Args)]
pub struct RecognitionArgs {
    /// Taught gestures: directories of *.csv files (one gesture each, named after the
    /// directory) or of gesture subdirectories (DIR/<gesture>/*.csv); at least 3
    /// demonstrations per gesture.
    #[arg(long, num_args = 1..)]
    pub taught: Vec<PathBuf>,
    /// Untaught gestures, given the same way (each should be called `unknown`).
    #[arg(long, num_args = 1..)]
    pub untaught: Vec<PathBuf>,
    /// Leave out the untrained hierarchy (the negative control).
    #[arg(long)]
    pub no_control: bool,
    /// Teach every hierarchy one gesture after another (an update per gesture, with its
    /// demonstrations alone), and reproduce each held-out demonstration's gesture with it, with
    /// the hierarchy taught at once and with the one right after its gesture was taught.
    #[arg(long)]
    pub one_at_a_time: bool,
    /// Also stream every demonstration, a sample at a time, into the recogniser of the
    /// hierarchy that answers it (as `cosco recognize --stream`): what it committed to and
    /// when, against the gates, beside a recogniser that commits at the first sample.
    #[arg(long)]
    pub stream: bool,
}

/// What both held-out studies share: how they read demonstrations, their threads, their JSON.
#[derive(clap::Args)]
pub struct StudyArgs {
    #[command(flatten)]
    pub data: DataArgs,
    /// Worker threads (default: every core).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
    pub threads: Option<u64>,
    /// Also write every fold's scores or every answer as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// How a held-out study reads demonstrations: the configuration and its fit to the data.
#[derive(clap::Args)]
pub struct DataArgs {
    /// XML configuration (default: the built-in configs/nao-gestures.xml; `heldout` of the upper
    /// body's joints: configs/nao-upper-body.xml).
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Take stateLength and actionLength from the demonstrations' columns.
    #[arg(long)]
    pub state_length_from_data: bool,
    /// Resample demonstrations with `time` columns to this rate, Hz (shape-preserving).
    #[arg(long)]
    pub resample: Option<f64>,
}
