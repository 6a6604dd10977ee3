//! A reproduction to a robot (`cosco export`: the trajectory from a reproduction file or a
//! model reproduced on the spot, then [`crate::export`]), and demonstrations from a ROS 2 bag
//! (`cosco demos import`, [`crate::ros2`]).

use super::files::{self, read_reproduction};
use super::reproduce::{conditions, initial_posture, reproduce_conditioned, write_band};
use super::{Error, Result};
use crate::demos::Demonstration;
use crate::export::{export_request, ExportRequest, Trajectory};

/// `cosco export`: check where the output goes, build the trajectory (the reproduction file's,
/// or gesture `r.gesture` of the model reproduced from exactly one of `r.initial` and
/// `r.initial_from`, through `r.goal` and `r.via`, its band written to `r.band` when asked),
/// then check, scale, execute when asked and write it
/// ([`export_request`]). Returns the report's lines.
pub fn export(r: &ExportRequest) -> Result<Vec<String>> {
    files::check_output(&r.out)?;
    if let Some(b) = &r.band {
        files::check_output(b)?;
    }
    let conditions = conditions(r.goal.as_ref(), &r.via);
    let mut band = None;
    let d = match (&r.reproduction, &r.model) {
        (Some(path), _) => read_reproduction(path)?,
        (None, Some(model)) => {
            let m = files::load_gesture_model(model)?;
            let branch = m.branch(r.gesture.as_deref())?;
            let initial = initial_posture(branch, r.initial.as_ref(), r.initial_from.as_deref())?;
            let name = model.display().to_string();
            let rep = reproduce_conditioned(branch, &name, &initial, &conditions)?;
            band = Some((branch.clone(), rep.clone()));
            Demonstration {
                rows: rep.postures,
                source: name,
                columns: m.columns().to_vec(),
                time: None,
            }
        }
        (None, None) => {
            return Err(Error::value(
                "--reproduction:",
                "give --reproduction FILE or --model FILE",
            ))
        }
    };
    let t = Trajectory::from_demonstration(&d, r.step_rate)?;
    let lines = export_request(r, &t)?;
    // the band once the trajectory is written
    if let (Some(path), Some((model, rep))) = (&r.band, &band) {
        write_band(model, rep, &conditions, path)?;
    }
    Ok(lines)
}

/// `cosco demos import`: the sensor_msgs/msg/JointState messages of `topic` in the bag,
/// `joints` kept (the arm's six when empty), one CSV per bag or per stretch of motion
/// (`split_idle`: pauses of at least this many seconds), written into `out`. Returns a line
/// per file.
#[cfg(feature = "ros2")]
pub fn import(
    bag: &std::path::Path,
    topic: &str,
    joints: &[String],
    split_idle: Option<f64>,
    out: &std::path::Path,
) -> Result<Vec<String>> {
    let files = crate::ros2::import::import_to_dir(bag, topic, joints, split_idle, out)?;
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
