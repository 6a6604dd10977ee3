//! The exported trajectory executed on the simulated robot: what its encoders read (for
//! `cosco export --format ros2 --executed`, `sensor_msgs/msg/JointState` on `/joint_states`)
//! and every contact between two of its parts (`cosco export --robot upper-body` refuses a
//! motion with one).

use crate::robot::Robot;
use crate::sim::{Controller, ControllerConfig, NaoArm, TargetTrajectory, Touch};
use crate::trajectory::{ExportError, Trajectory};

/// A trajectory executed on a simulated robot.
#[derive(Debug, Clone)]
pub struct Executed {
    /// What the encoders read: every joint of the robot, in its order.
    pub encoders: Trajectory,
    /// Every contact between two parts of the robot during the motion (none on a model
    /// without collision shapes, the left arm's).
    pub contacts: Vec<Touch>,
}

/// Follow `t` from its first posture on the simulated `robot` (its shipped model) and record
/// the encoders at `rate_hz`. The trajectory's joints are any of the robot's, in any order;
/// the robot's other joints hold their `StandInit` posture.
pub fn execute(robot: Robot, t: &Trajectory, rate_hz: f64) -> Result<Executed, ExportError> {
    match robot {
        Robot::LeftArm => execute_on::<6>(robot, t, rate_hz),
        Robot::UpperBody => execute_on::<14>(robot, t, rate_hz),
    }
}

fn execute_on<const N: usize>(
    robot: Robot,
    t: &Trajectory,
    rate_hz: f64,
) -> Result<Executed, ExportError> {
    let sim_err = |e: crate::sim::SimError| ExportError::Invalid {
        source_name: format!("simulated {}", robot.name()),
        reason: e.to_string(),
    };
    let names = robot.joint_names();
    let columns = t
        .names
        .iter()
        .map(|n| names.iter().position(|j| j == n))
        .collect::<Option<Vec<usize>>>()
        .ok_or_else(|| ExportError::Invalid {
            source_name: "--executed".into(),
            reason: format!(
                "the trajectory's joints are {}; the simulated {} executes {}",
                t.names.join(", "),
                robot.name(),
                names.join(", ")
            ),
        })?;
    let rest = robot
        .posture("StandInit")
        .ok_or_else(|| ExportError::Invalid {
            source_name: robot.model_path().into(),
            reason: "no StandInit keyframe: the posture the joints not exported hold".into(),
        })?;
    let targets: Vec<Vec<f64>> = (t.positions.iter())
        .map(|p| {
            let mut q = rest.to_vec();
            for (&k, &v) in columns.iter().zip(p) {
                q[k] = v;
            }
            q
        })
        .collect();
    let arm = NaoArm::<N>::load_shipped(robot).map_err(|e| ExportError::Arm(Box::new(e)))?;
    let start = targets[0].clone();
    let targets = TargetTrajectory::<N>::new_for(robot, &t.times, &targets).map_err(sim_err)?;
    let ctl = Controller::new(ControllerConfig {
        record_rate_hz: rate_hz,
        ..ControllerConfig::default()
    })
    .map_err(sim_err)?;
    let mut sim = arm.sim().map_err(sim_err)?;
    sim.reset_to(&start).map_err(sim_err)?;
    let rec = ctl.follow(&mut sim, &targets).map_err(sim_err)?;
    Ok(Executed {
        encoders: Trajectory::new(rec.joint_names.clone(), rec.time.clone(), rec.qpos.clone())?,
        contacts: rec.contacts,
    })
}
