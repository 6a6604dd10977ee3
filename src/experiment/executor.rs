//! The simulated arm as the evaluator's executor ([`ArmExecutor`]): a method's postures
//! clamped into the joint ranges, shaped by the transition (the hierarchy's and the nearest
//! sequence's; GMM/GMR's, ProMP's, the DMP's and the replay's go posture to posture),
//! executed by the position controller and recorded at the demonstration's rate (40 Hz), then
//! scored with the wrist paths ([`crate::sim::evaluate`]).

use crate::demos::{sample_period, Demonstration};
use crate::eval::{Executed, Executor, Method};
use crate::metrics::MetricsParams;
use crate::robot::Robot;
use crate::sim::{
    clamp_to_ranges_of, evaluate, execute_postures, NaoArm, Recording, SimError, Transition,
    LEAD_IN_PEAK_SPEED, NJ,
};

/// Clamp `postures` into the joint ranges, shape them with `transition`, execute them on
/// `arm` at the rate of `metrics.sample_period` and score the executed trajectory against
/// `test`: what [`ArmExecutor`] does, for callers that produce postures themselves.
pub fn execute_and_score<const N: usize>(
    arm: &NaoArm<N>,
    postures: &[Vec<f64>],
    transition: Transition,
    test: &[Demonstration],
    metrics: &MetricsParams,
) -> Result<Executed<Recording>, SimError> {
    if !(metrics.sample_period.is_finite() && metrics.sample_period > 0.0) {
        return Err(SimError::Invalid(format!(
            "metrics sample_period = {}: needs a finite period > 0",
            metrics.sample_period
        )));
    }
    let (postures, clamped_values) = clamp_to_ranges_of(arm.robot(), postures)?;
    let commanded = transition.shape(&postures);
    let trace = execute_postures(arm, &commanded, 1.0 / metrics.sample_period)?;
    let fidelity = evaluate(Some(arm), test, &trace.qpos, metrics)?;
    Ok(Executed {
        trace,
        fidelity,
        clamped_values,
        commanded,
    })
}

/// The simulated arm (or upper body, `N` its joints) as the evaluator's executor, with the
/// transition of the hierarchy's postures.
#[derive(Clone, Copy)]
pub struct ArmExecutor<'a, const N: usize = NJ> {
    /// The arm.
    pub arm: &'a NaoArm<N>,
    /// How the hierarchy's and the nearest sequence's postures become servo targets.
    pub transition: Transition,
}

impl<const N: usize> Executor for ArmExecutor<'_, N> {
    type Trace = Recording;

    /// Refuses targets whose columns are not the arm's joints.
    fn execute(
        &self,
        method: Method,
        postures: &[Vec<f64>],
        targets: &[Demonstration],
    ) -> Result<Executed<Recording>, String> {
        let robot = self.arm.robot();
        if let Some(d) = targets
            .iter()
            .find(|d| Robot::of_columns(&d.columns) != Some(robot))
        {
            return Err(format!(
                "the demonstrations' columns are {:?}; executing on the simulated arm needs \
                 exactly {:?}",
                d.columns,
                robot.joint_names()
            ));
        }
        let metrics = MetricsParams {
            sample_period: targets.first().map_or(f64::NAN, sample_period),
            ..MetricsParams::default()
        };
        let transition = match method {
            Method::GmmGmr | Method::ProMP | Method::Dmp | Method::Dba | Method::Replay => {
                Transition::Linear
            }
            _ => self.transition,
        };
        execute_and_score(self.arm, postures, transition, targets, &metrics)
            .map_err(|e| crate::errors::error_line(&e))
    }

    /// The encoders' record.
    fn motion<'a>(&self, executed: &'a Executed<Recording>) -> &'a [Vec<f64>] {
        &executed.trace.qpos
    }

    /// [`LEAD_IN_PEAK_SPEED`]: the arm's, whatever the demonstrations.
    fn gmr_lead_in_speed(&self, _train: &[Demonstration], _period: f64) -> f64 {
        LEAD_IN_PEAK_SPEED
    }

    /// The robot's ([`Robot::swing_joint`]).
    fn swing_joint(&self) -> Option<(usize, &'static str)> {
        Some(self.arm.robot().swing_joint())
    }
}

#[cfg(test)]
mod tests;
