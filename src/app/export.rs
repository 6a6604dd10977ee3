//! A reproduction to a robot (`cosco export`: the trajectory from a reproduction file or a
//! model reproduced on the spot, then [`crate::export`]), and demonstrations from a ROS 2 bag
//! (`cosco demos import`, [`crate::ros2`]).

use std::path::PathBuf;

use super::files::{self, read_reproduction};
use super::reproduce::{conditions, ReproduceRequest};
use super::Result;
use crate::demos::Demonstration;
use crate::export::{export_request, ExportRequest, Trajectory};

/// Where `cosco export`'s trajectory comes from.
#[derive(Debug, Clone)]
pub enum ExportFrom {
    /// A reproduction CSV (`cosco reproduce`'s, GMM/GMR's, any CSV with `time` or `step` then
    /// one column per joint).
    Reproduction(PathBuf),
    /// A gesture of a saved model reproduced on the spot, as `cosco reproduce` does.
    Model(Box<ReproduceRequest>),
}

/// `cosco export`: check where the output goes, build the trajectory (the reproduction file's,
/// or the model's gesture reproduced as `cosco reproduce` does, [`ReproduceRequest`]), then
/// check, scale, execute when asked and write it ([`export_request`]), and the band last,
/// when asked. Returns the report's lines.
pub fn export(from: &ExportFrom, r: &ExportRequest) -> Result<Vec<String>> {
    crate::fsutil::check_output(&r.out)?;
    let mut r = r.clone();
    let (d, band) = match from {
        ExportFrom::Reproduction(path) => (read_reproduction(path)?, None),
        ExportFrom::Model(q) => {
            if let Some(b) = &q.band {
                crate::fsutil::check_output(b)?;
            }
            let conditions = conditions(q.goal.as_ref(), &q.via);
            let done = q.run(&conditions, None)?;
            if r.own_contacts.is_empty() {
                let (kept, period) = &done.kept;
                let kept: Vec<Demonstration> = (kept.iter())
                    .map(|rows| Demonstration {
                        rows: rows.clone(),
                        source: q.model.display().to_string(),
                        columns: done.columns.clone(),
                        time: None,
                    })
                    .collect();
                r.own_contacts = own_contacts(&kept, 1.0 / period.unwrap_or(1.0 / r.step_rate))?;
            }
            let d = Demonstration {
                rows: done.rep.postures,
                source: q.model.display().to_string(),
                columns: done.columns,
                time: None,
            };
            (d, done.band)
        }
    };
    let t = Trajectory::from_demonstration(&d, r.step_rate)?;
    let lines = export_request(&r, &t)?;
    // the band once the trajectory is written
    if let Some((path, bytes)) = band {
        files::write(&path, &bytes?)?;
    }
    Ok(lines)
}

/// The contacts every one of `demos` makes ([`crate::sim::own_contacts`]), each executed on
/// the simulated upper body when its columns are the upper body's joints (values held within
/// the joint ranges; `rate_hz`: the rows' rate when a demonstration has no `time`); none for
/// any other robot, or without the simulator.
pub fn own_contacts(demos: &[Demonstration], rate_hz: f64) -> Result<Vec<[String; 2]>> {
    #[cfg(feature = "sim")]
    {
        use crate::robot::Robot;
        let upper = |d: &Demonstration| Robot::of_columns(&d.columns) == Some(Robot::UpperBody);
        if demos.is_empty() || !demos.iter().all(upper) {
            return Ok(Vec::new());
        }
        let sim = |e: crate::sim::SimError| crate::export::ExportError::Invalid {
            source_name: "the demonstrations on the simulated upper-body".into(),
            reason: e.to_string(),
        };
        let arm = crate::sim::NaoArm::<14>::load_shipped(Robot::UpperBody).map_err(sim)?;
        let executions = (demos.iter())
            .map(|d| {
                let period = d
                    .time
                    .as_ref()
                    .map_or(1.0 / rate_hz, |_| crate::demos::sample_period(d));
                crate::experiment::upper_body::execute_contacts(&arm, &d.rows, period).map_err(sim)
            })
            .collect::<std::result::Result<Vec<_>, _>>()?;
        Ok(crate::sim::own_contacts(&executions))
    }
    #[cfg(not(feature = "sim"))]
    {
        let _ = (demos, rate_hz);
        Ok(Vec::new())
    }
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
