//! The exported trajectory executed on the simulated arm: what its encoders read, for
//! `cosco export --format ros2 --executed` (`sensor_msgs/msg/JointState` on `/joint_states`).

use super::trajectory::{ExportError, Trajectory};
use crate::sim::{Controller, ControllerConfig, NaoArm, TargetTrajectory, JOINT_NAMES};

/// Follow `t` (the arm's six joints, in [`JOINT_NAMES`] order) from its first posture on
/// `arm` and record the encoders at `rate_hz`.
pub fn execute_on_arm(
    arm: &NaoArm,
    t: &Trajectory,
    rate_hz: f64,
) -> Result<Trajectory, ExportError> {
    let sim_err = |e: crate::sim::SimError| ExportError::Invalid {
        source_name: "simulated arm".into(),
        reason: e.to_string(),
    };
    if t.names.iter().map(String::as_str).ne(JOINT_NAMES) {
        return Err(ExportError::Invalid {
            source_name: "--executed".into(),
            reason: format!(
                "the trajectory's joints are {}; the simulated arm executes {} in that order",
                t.names.join(", "),
                JOINT_NAMES.join(", ")
            ),
        });
    }
    let targets = TargetTrajectory::new(&t.times, &t.positions).map_err(sim_err)?;
    let ctl = Controller::new(ControllerConfig {
        record_rate_hz: rate_hz,
        ..ControllerConfig::default()
    })
    .map_err(sim_err)?;
    let mut sim = arm.sim().map_err(sim_err)?;
    sim.reset_to(&t.positions[0]).map_err(sim_err)?;
    let rec = ctl.follow(&mut sim, &targets).map_err(sim_err)?;
    Trajectory::new(rec.joint_names.clone(), rec.time.clone(), rec.qpos.clone())
}
