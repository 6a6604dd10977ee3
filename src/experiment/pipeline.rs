//! The learning part of the experiment in one call: train CoSCo-HSOM on demonstrations,
//! reproduce from the initial posture, execute on the simulated arm, score it.
//!
//! In-sample ([`learn_and_reproduce`]) and held-out (`heldout::leave_one_out`) runs are the
//! same [`learn_and_score`] on different [`Split`]s.

use std::time::Instant;

use crate::config::HsomConfig;
use crate::demos::Demonstration;
use crate::hsom::{Hsom, Reproduction};
use crate::metrics::{FidelityReport, MetricsParams};
use crate::sim::{NaoArm, Recording};

use super::report::MethodResult;
use super::{clamp_to_ranges, evaluate, execute_postures, ExperimentError, Transition};

/// What CoSCo-HSOM needs as input (the report's "needs as input" row).
pub const HSOM_NEEDS: &str = "raw demonstrations; the initial posture";

pub use crate::eval::Training;

/// Which demonstrations a run learns from and which it is scored against. The reproduction
/// starts from the first posture of `test[0]`.
#[derive(Debug, Clone, Copy)]
pub struct Split<'a> {
    /// Demonstrations to learn from.
    pub train: &'a [Demonstration],
    /// Demonstrations to score against; the first one gives the initial posture and the
    /// sample period.
    pub test: &'a [Demonstration],
}

impl<'a> Split<'a> {
    /// Learn from `demos` and score against the same `demos` (the in-sample result).
    pub fn in_sample(demos: &'a [Demonstration]) -> Split<'a> {
        Split {
            train: demos,
            test: demos,
        }
    }

    /// The first test demonstration (an error when there is none).
    pub fn first_test(&self) -> Result<&'a Demonstration, ExperimentError> {
        self.test
            .first()
            .ok_or_else(|| ExperimentError::Invalid("no demonstrations to score against".into()))
    }

    /// The initial posture: the first row of the first test demonstration.
    pub fn initial(&self) -> Result<&'a [f64], ExperimentError> {
        let first = self.first_test()?;
        first
            .rows
            .first()
            .map(Vec::as_slice)
            .ok_or_else(|| ExperimentError::Invalid(format!("{}: no samples", first.source)))
    }

    /// The metrics settings: the sample period of the first test demonstration.
    pub fn metrics(&self) -> Result<MetricsParams, ExperimentError> {
        Ok(MetricsParams {
            sample_period: sample_period(self.first_test()?),
            ..MetricsParams::default()
        })
    }
}

/// What one run produced.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The model.
    pub model: Hsom,
    /// The learned postures, before clamping.
    pub reproduction: Reproduction,
    /// Values that were outside a joint's range and were clamped before execution.
    pub clamped_values: usize,
    /// The trajectory executed by the simulated arm, recorded at the demonstrations' rate.
    pub executed: Recording,
    /// Its fidelity against each test demonstration.
    pub fidelity: FidelityReport,
    /// Training time, seconds.
    pub train_s: f64,
    /// Time to produce the postures, seconds.
    pub reproduce_s: f64,
}

impl Outcome {
    /// CoSCo-HSOM's column of a comparison table (no held-out figures: see
    /// `heldout::leave_one_out`); `model_bytes` is the size of the saved model.
    pub fn method_result(&self, name: &str, model_bytes: u64, notes: Vec<String>) -> MethodResult {
        MethodResult {
            name: name.into(),
            needs: HSOM_NEEDS.into(),
            fidelity: self.fidelity.clone(),
            train_s: self.train_s,
            reproduce_s: self.reproduce_s,
            model_bytes,
            postures: self.reproduction.postures.len(),
            clamped_values: self.clamped_values,
            notes,
            heldout: None,
        }
    }
}

use crate::demos::sample_period;

/// An executed and scored posture sequence.
#[derive(Debug, Clone)]
pub struct Executed {
    /// Values outside a joint's range, clamped before execution.
    pub clamped_values: usize,
    /// The trajectory executed by the simulated arm.
    pub executed: Recording,
    /// Its fidelity against the test demonstrations.
    pub fidelity: FidelityReport,
    /// The servo targets, one per tick: the postures clamped and shaped by the transition.
    pub commanded: Vec<Vec<f64>>,
}

/// Clamp `postures` into the joint ranges, shape them with `transition`, execute them on
/// `arm` at the rate of `metrics.sample_period` and score the executed trajectory against
/// `test` (the step shared by CoSCo-HSOM, its variants and the GMM/GMR baseline).
pub fn execute_and_score(
    arm: &NaoArm,
    postures: &[Vec<f64>],
    transition: Transition,
    test: &[Demonstration],
    metrics: &MetricsParams,
) -> Result<Executed, ExperimentError> {
    if !(metrics.sample_period.is_finite() && metrics.sample_period > 0.0) {
        return Err(ExperimentError::Invalid(format!(
            "metrics sample_period = {}: needs a finite period > 0",
            metrics.sample_period
        )));
    }
    let (postures, clamped_values) = clamp_to_ranges(postures)?;
    let commanded = transition.shape(&postures);
    let executed = execute_postures(arm, &commanded, 1.0 / metrics.sample_period)?;
    let fidelity = evaluate(Some(arm), test, &executed.qpos, metrics)?;
    Ok(Executed {
        clamped_values,
        executed,
        fidelity,
        commanded,
    })
}

/// Train on `split.train` (or not), reproduce from the first posture of `split.test[0]`,
/// execute on `arm` with `transition` and score against `split.test`. `progress(done,
/// total)` follows the training.
pub fn learn_and_score(
    arm: &NaoArm,
    config: &HsomConfig,
    split: Split<'_>,
    training: Training,
    transition: Transition,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<Outcome, ExperimentError> {
    let initial = split.initial()?;
    let metrics = split.metrics()?;
    if split.train.is_empty() {
        return Err(ExperimentError::Invalid(
            "no demonstrations to learn from".into(),
        ));
    }
    let t = Instant::now();
    let model = match training {
        Training::Trained => config.fit_with_progress(split.train, progress)?,
        Training::Untrained => config.initialise(split.train)?,
    };
    let train_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let reproduction = model.reproduce(initial)?;
    let reproduce_s = t.elapsed().as_secs_f64();
    let run = execute_and_score(
        arm,
        &reproduction.postures,
        transition,
        split.test,
        &metrics,
    )?;
    Ok(Outcome {
        model,
        reproduction,
        clamped_values: run.clamped_values,
        executed: run.executed,
        fidelity: run.fidelity,
        train_s,
        reproduce_s,
    })
}

/// Train on `demos` (or not), reproduce from the first demonstration's first posture, execute
/// on `arm` with `transition` and score against `demos` (the in-sample result:
/// [`learn_and_score`] with [`Split::in_sample`]). `progress(done, total)` follows the
/// training.
pub fn learn_and_reproduce(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    training: Training,
    transition: Transition,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<Outcome, ExperimentError> {
    if demos.is_empty() {
        return Err(ExperimentError::Invalid(
            "no demonstrations to learn from".into(),
        ));
    }
    learn_and_score(
        arm,
        config,
        Split::in_sample(demos),
        training,
        transition,
        progress,
    )
}

/// Execute and score another reproduction of an already trained model (a variant of the
/// reproduction settings or of the transition), for before/after comparisons. Returns the
/// reproduction, the number of clamped values, the executed trajectory, its fidelity and the
/// time taken to produce the postures.
pub fn reproduce_variant(
    arm: &NaoArm,
    model: &Hsom,
    reproduction: &crate::config::ReproductionParams,
    demos: &[Demonstration],
    transition: Transition,
) -> Result<(Reproduction, usize, Recording, FidelityReport, f64), ExperimentError> {
    let split = Split::in_sample(demos);
    let initial = split.initial()?;
    let t = Instant::now();
    let rep = model.reproduce_with(initial, reproduction)?;
    let reproduce_s = t.elapsed().as_secs_f64();
    let run = execute_and_score(arm, &rep.postures, transition, demos, &split.metrics()?)?;
    Ok((
        rep,
        run.clamped_values,
        run.executed,
        run.fidelity,
        reproduce_s,
    ))
}
