//! `cosco reproduce`: its arguments, handed to [`cosco_hsom::app::reproduce_file`] as a
//! [`ReproduceFile`].

use std::path::PathBuf;

use cosco_hsom::app::{ReproduceFile, ReproduceRequest};
use cosco_hsom::condition::{PostureArg, ViaPoint};

/// What `cosco reproduce` is asked, as given on its command line.
#[derive(Debug, Clone, clap::Args)]
pub struct ReproduceArgs {
    /// A model saved by `cosco train` (.bin or .txt).
    #[arg(long)]
    pub model: PathBuf,
    /// The initial posture, comma-separated, one value per state variable.
    #[arg(
        long,
        allow_hyphen_values = true,
        conflicts_with_all = ["initial_from", "prefix_from"],
        required_unless_present_any = ["initial_from", "prefix_from"]
    )]
    pub initial: Option<PostureArg>,
    /// Take the initial posture from the first row of this demonstration CSV.
    #[arg(long, conflicts_with = "prefix_from")]
    pub initial_from: Option<PathBuf>,
    /// The gesture to reproduce (required with a model of several gestures).
    #[arg(long, conflicts_with = "prefix_from")]
    pub gesture: Option<String>,
    /// Continue the gesture begun in this demonstration CSV's first --prefix samples; the
    /// hierarchy decides which gesture it is.
    #[arg(long, requires = "prefix")]
    pub prefix_from: Option<PathBuf>,
    /// Samples of --prefix-from to continue from.
    #[arg(long, requires = "prefix_from")]
    pub prefix: Option<usize>,
    /// Resume the reproduction from the initial posture after part of it was executed:
    /// this CSV (the model's columns) is what the encoders read meanwhile, possibly
    /// disturbed; writes the rest, from the reading's last posture (`algorithm = events`).
    #[arg(long, conflicts_with = "prefix_from")]
    pub resume_from: Option<PathBuf>,
    /// The last posture, comma-separated: the reproduction ends exactly there.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["prefix_from", "resume_from"])]
    pub goal: Option<PostureArg>,
    /// A posture to pass at a phase of the reproduction (0 the start, 1 the end):
    /// `PHASE:V1,V2,...`; repeatable.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["prefix_from", "resume_from"])]
    pub via: Vec<ViaPoint>,
    /// Also write the central 95 % confidence band about the reproduction to this CSV: one
    /// row per reproduction row, `step` then `<variable>_lo` and `<variable>_hi`.
    #[arg(long, conflicts_with_all = ["prefix_from", "resume_from"])]
    pub band: Option<PathBuf>,
    /// The robot the model must be of: `left-arm` (6 joints) or `upper-body` (14: the head
    /// and both arms); its joint ranges bound the initial posture, the goal and via-points.
    /// Default: whichever robot's joints the model's variables are (none for other data).
    #[arg(long)]
    pub robot: Option<cosco_hsom::robot::Robot>,
    /// Reproduce the gesture in this many seconds, its shape kept (the tempo changes, not
    /// the path); a duration the robot's servos cannot follow is refused, naming the shortest.
    #[arg(long, value_name = "SECONDS", conflicts_with_all = ["prefix_from", "resume_from"])]
    pub duration: Option<f64>,
    /// Point at X,Y,Z (metres, in the torso frame: x forward, y to the robot's left, z up):
    /// during the held part, the ray from the pointing arm's shoulder through its gripper
    /// passes through it; a target the arm cannot point at is refused, naming the closest
    /// direction it can.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = cosco_hsom::aim::parse_point, conflicts_with_all = ["prefix_from", "resume_from"])]
    pub point_at: Option<[f64; 3]>,
    /// Look at X,Y,Z (the upper body; metres, torso frame): during the held part the top
    /// camera's optical axis passes through it.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = cosco_hsom::aim::parse_point, conflicts_with_all = ["prefix_from", "resume_from"])]
    pub look_at: Option<[f64; 3]>,
    /// Output CSV.
    #[arg(long)]
    pub out: PathBuf,
}

impl From<ReproduceArgs> for ReproduceFile {
    fn from(a: ReproduceArgs) -> Self {
        ReproduceFile {
            request: ReproduceRequest {
                model: a.model,
                gesture: a.gesture,
                initial: a.initial,
                initial_from: a.initial_from,
                goal: a.goal,
                via: a.via,
                band: a.band,
                robot: a.robot,
                duration: a.duration,
                aim: cosco_hsom::aim::Aim {
                    point_at: a.point_at,
                    look_at: a.look_at,
                },
            },
            prefix_from: a.prefix_from,
            prefix: a.prefix,
            resume_from: a.resume_from,
            out: a.out,
        }
    }
}
