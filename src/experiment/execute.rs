//! Executing a learned gesture on the simulated arm: the predicted postures go to the position
//! controller, from the initial posture, and the executed trajectory is recorded at 40 Hz.

use crate::sim::{Controller, ControllerConfig, NaoArm, Recording, TargetTrajectory, NJ};

use super::ExperimentError;

/// How predicted postures become servo targets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Transition {
    /// One predicted posture per recording tick, linear in between (the paper: "execute the
    /// transition from posture to posture").
    #[default]
    Linear,
}

/// Execute `postures` (one per tick of `rate_hz`, the first being the initial posture) on the
/// simulated arm, starting at the first posture, and record the encoders at `rate_hz`.
/// Postures outside the joint ranges are an error naming the joint (no silent clamping).
pub fn execute_postures(
    arm: &NaoArm,
    postures: &[Vec<f64>],
    rate_hz: f64,
) -> Result<Recording, ExperimentError> {
    let Some(first) = postures.first() else {
        return Err(ExperimentError::Invalid("no postures to execute".into()));
    };
    if first.len() != NJ {
        return Err(ExperimentError::Invalid(format!(
            "postures have {} values, the arm has {NJ} joints",
            first.len()
        )));
    }
    let controller = Controller::new(ControllerConfig {
        record_rate_hz: rate_hz,
        ..ControllerConfig::default()
    })?;
    let trajectory = TargetTrajectory::at_rate(rate_hz, postures)?;
    let mut sim = arm.sim()?;
    sim.set_posture(first)?;
    Ok(controller.follow(&mut sim, &trajectory)?)
}
