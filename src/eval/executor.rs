//! Where a method's postures are carried out before they are scored: the executor. The
//! kinematic one ([`Kinematic`]) takes the postures as they are, with no simulator; the
//! simulated Nao arm's is `experiment::ArmExecutor` (feature `sim`), recording the executed motion
//! at the demonstration's rate. Both produce an [`Executed`].

use crate::demos::{sample_period, Demonstration};
use crate::metrics::{FidelityReport, MetricsParams};

use super::method::{peak_speed, Method};

/// What an executor made of a method's postures, scored against the demonstrations.
#[derive(Debug, Clone)]
pub struct Executed<T> {
    /// The executed motion (the executor's own record of it).
    pub trace: T,
    /// Its fidelity against the demonstrations.
    pub fidelity: FidelityReport,
    /// Posture values moved into the executor's ranges before execution.
    pub clamped_values: usize,
    /// What the executor handed its actuators, one posture per sample period of the
    /// demonstration (the method's postures as they are, or moved into the ranges and
    /// shaped for the servos).
    pub commanded: Vec<Vec<f64>>,
}

/// Carries out a method's postures and scores what was carried out against a demonstration.
pub trait Executor: Sync {
    /// The executor's record of an executed motion.
    type Trace;

    /// Execute `postures` produced by `method` and score the motion against each of
    /// `targets`, at the first one's sample period. The reason as a line when it cannot.
    fn execute(
        &self,
        method: Method,
        postures: &[Vec<f64>],
        targets: &[Demonstration],
    ) -> Result<Executed<Self::Trace>, String>;

    /// The executed motion of `executed`, one row per sample period of the demonstration it
    /// was scored against (what its fidelity was computed on).
    fn motion<'a>(&self, executed: &'a Executed<Self::Trace>) -> &'a [Vec<f64>];

    /// The peak speed of GMM/GMR's lead-in from the initial posture to its first point, units
    /// per second, for training demonstrations sampled every `period` seconds.
    fn gmr_lead_in_speed(&self, train: &[Demonstration], period: f64) -> f64;

    /// The column whose large swings are counted, and its name (`None`: none is).
    fn swing_joint(&self) -> Option<(usize, &'static str)> {
        None
    }
}

/// The postures as they are: no simulator, no ranges, scored in the data's own units. GMM/GMR's
/// lead-in moves at the training demonstrations' own peak speed ([`peak_speed`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct Kinematic;

impl Executor for Kinematic {
    type Trace = ();

    fn execute(
        &self,
        _method: Method,
        postures: &[Vec<f64>],
        targets: &[Demonstration],
    ) -> Result<Executed<()>, String> {
        let params = MetricsParams {
            sample_period: targets.first().map_or(f64::NAN, sample_period),
            ..MetricsParams::default()
        };
        let fidelity = crate::metrics::fidelity_of_rows(targets, postures, &params)
            .map_err(|e| crate::errors::error_line(&e))?;
        Ok(Executed {
            trace: (),
            fidelity,
            clamped_values: 0,
            commanded: postures.to_vec(),
        })
    }

    /// The postures themselves.
    fn motion<'a>(&self, executed: &'a Executed<()>) -> &'a [Vec<f64>] {
        &executed.commanded
    }

    fn gmr_lead_in_speed(&self, train: &[Demonstration], period: f64) -> f64 {
        peak_speed(train, period)
    }
}
