//! The simulated Nao arm as an executor of the evaluator ([`crate::eval::Executor`]): a
//! method's postures clamped into the joint ranges, shaped by the transition (the hierarchy's
//! and the nearest sequence's; GMM/GMR's, ProMP's and the replay's go posture to posture), executed by
//! the position controller and recorded at the demonstration's rate (40 Hz), then scored
//! against the demonstration with the wrist paths.

use crate::demos::{sample_period, Demonstration};
use crate::eval::{Executed, Executor, Method};
use crate::metrics::MetricsParams;
use crate::sim::{NaoArm, Recording};

use super::baseline::LEAD_IN_PEAK_SPEED;
use super::pipeline::execute_and_score;
use super::Transition;

/// The simulated arm, with the transition of the hierarchy's postures.
#[derive(Clone, Copy)]
pub struct ArmExecutor<'a> {
    /// The arm.
    pub arm: &'a NaoArm,
    /// How the hierarchy's and the nearest sequence's postures become servo targets.
    pub transition: Transition,
}

impl Executor for ArmExecutor<'_> {
    type Trace = Recording;

    fn execute(
        &self,
        method: Method,
        postures: &[Vec<f64>],
        target: &Demonstration,
    ) -> Result<Executed<Recording>, String> {
        let metrics = MetricsParams {
            sample_period: sample_period(target),
            ..MetricsParams::default()
        };
        let transition = match method {
            Method::GmmGmr | Method::ProMP | Method::Replay => Transition::Linear,
            _ => self.transition,
        };
        let run = execute_and_score(
            self.arm,
            postures,
            transition,
            std::slice::from_ref(target),
            &metrics,
        )
        .map_err(|e| crate::app::error_line(&e))?;
        Ok(Executed {
            trace: run.executed,
            fidelity: run.fidelity,
            clamped_values: run.clamped_values,
            commanded: run.commanded,
        })
    }

    /// The encoders' record.
    fn motion<'a>(&self, executed: &'a Executed<Recording>) -> &'a [Vec<f64>] {
        &executed.trace.qpos
    }

    /// [`LEAD_IN_PEAK_SPEED`]: the arm's, whatever the demonstrations.
    fn gmr_lead_in_speed(&self, _train: &[Demonstration], _period: f64) -> f64 {
        LEAD_IN_PEAK_SPEED
    }
}
