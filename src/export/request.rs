//! `cosco export` as one call once the trajectory is built (`app::export` builds it from a
//! reproduction file or a model reproduced from an initial posture): which robot's limits it
//! is checked against, the time scaling, and the optional execution on the simulated arm; the
//! binary only parses the arguments into an [`ExportRequest`].

use std::path::PathBuf;

use super::{export_to, limits, ExportError, ExportOptions, Format, Timing, Trajectory};

/// Everything `cosco export` is asked, as given on its command line.
#[derive(Debug, Clone)]
pub struct ExportRequest {
    /// A reproduction CSV (`time` or `step`, then one column per joint).
    pub reproduction: Option<PathBuf>,
    /// Or a model saved by `cosco train`, reproduced from `initial` or `initial_from`.
    pub model: Option<PathBuf>,
    /// The initial posture, comma-separated (with `model`).
    pub initial: Option<String>,
    /// A CSV whose first row is the initial posture (with `model`).
    pub initial_from: Option<PathBuf>,
    /// The gesture of a model of several gestures.
    pub gesture: Option<String>,
    /// Output format.
    pub format: Format,
    /// Output file.
    pub out: PathBuf,
    /// Play the motion this many times faster.
    pub speed: Option<f64>,
    /// Stretch or squeeze the motion to last this many seconds.
    pub duration: Option<f64>,
    /// Fraction of each joint's documented maximum velocity the motion may reach.
    pub velocity_fraction: f64,
    /// Slow the whole motion down to the velocity limit instead of refusing it.
    pub clamp: bool,
    /// CSV output rate, Hz (`None`: the trajectory's own points).
    pub rate: Option<f64>,
    /// Rate of a `step` column, Hz.
    pub step_rate: f64,
    /// Another robot's joint ranges: its MJCF file (with `velocity_table`).
    pub mjcf: Option<PathBuf>,
    /// Another robot's velocity limits: CSV `joint,max_velocity` (with `mjcf`).
    pub velocity_table: Option<PathBuf>,
    /// Also execute the motion on the simulated arm and record its joints (`Ros2` only;
    /// needs the feature `sim`).
    pub executed: bool,
}

/// `cosco export` once the output's place is checked and the trajectory `t` built
/// (`app::export`): check it against the robot's limits (the Nao left arm's, or `mjcf` with `velocity_table`), scale its timing,
/// execute it on the simulated arm when asked, and write it atomically. Returns the report's
/// lines.
pub fn export_request(r: &ExportRequest, t: &Trajectory) -> Result<Vec<String>, ExportError> {
    let robot = match (&r.mjcf, &r.velocity_table) {
        (Some(m), Some(v)) => limits::from_mjcf(m, &limits::read_velocity_table(v)?)?,
        _ => limits::nao_left_arm(),
    };
    let opts = ExportOptions {
        format: r.format,
        timing: match (r.speed, r.duration) {
            (Some(s), _) => Timing::Speed(s),
            (None, Some(d)) => Timing::Duration(d),
            (None, None) => Timing::AsIs,
        },
        velocity_fraction: r.velocity_fraction,
        clamp: r.clamp,
        rate_hz: r.rate,
    };
    if r.executed && r.format != Format::Ros2 {
        return Err(ExportError::Usage(
            "--executed goes with --format ros2".into(),
        ));
    }
    let report = export_executed(r, t, &robot, &opts)?;
    let mut lines = report.lines();
    lines.push(format!("written {}", r.out.display()));
    Ok(lines)
}

/// [`export_to`], executing on the simulated arm when `r.executed` (with the feature `sim`;
/// without it nothing is executed).
fn export_executed(
    r: &ExportRequest,
    t: &Trajectory,
    robot: &limits::RobotLimits,
    opts: &ExportOptions,
) -> Result<super::ExportReport, ExportError> {
    #[cfg(feature = "sim")]
    if r.executed {
        let arm =
            crate::sim::NaoArm::load_default().map_err(|source| ExportError::Arm { source })?;
        let run = |t: &Trajectory| {
            super::executed::execute_on_arm(&arm, t, crate::sim::DEFAULT_RECORD_RATE_HZ)
        };
        return export_to(t, robot, opts, Some(&run), &r.out);
    }
    export_to(t, robot, opts, None, &r.out)
}
