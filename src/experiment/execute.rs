//! Executing a learned gesture on the simulated arm: the predicted postures go to the position
//! controller, from the initial posture, and the executed trajectory is recorded at 40 Hz.

use crate::sim::{
    Controller, ControllerConfig, NaoArm, Recording, TargetTrajectory, JOINT_SPECS, NJ,
};

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

/// Clamp learned postures into the joint ranges before execution, counting the values that
/// were outside (the report shows the count: nothing is fixed silently). NaN is an error.
pub fn clamp_to_ranges(postures: &[Vec<f64>]) -> Result<(Vec<Vec<f64>>, usize), ExperimentError> {
    let mut clamped = 0;
    let mut out = Vec::with_capacity(postures.len());
    for (i, p) in postures.iter().enumerate() {
        if p.len() != NJ {
            return Err(ExperimentError::Invalid(format!(
                "posture {i} has {} values, the arm has {NJ} joints",
                p.len()
            )));
        }
        let mut row = Vec::with_capacity(NJ);
        for (spec, &v) in JOINT_SPECS.iter().zip(p) {
            let c = spec.clamp(v)?;
            if c != v {
                clamped += 1;
            }
            row.push(c);
        }
        out.push(row);
    }
    Ok((out, clamped))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp_counts_values_outside_and_rejects_nan() {
        let ok = vec![1.4, 0.3, -1.39, -1.01, 0.0, 0.25];
        let mut bad = ok.clone();
        bad[1] = 2.0;
        let (out, n) = clamp_to_ranges(&[ok.clone(), bad]).unwrap();
        assert_eq!(n, 1);
        assert_eq!(out[1][1], JOINT_SPECS[1].range.1);
        let mut nan = ok;
        nan[0] = f64::NAN;
        assert!(clamp_to_ranges(&[nan]).is_err());
    }
}
