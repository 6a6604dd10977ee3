//! The learning part of the experiment in one call: train CoSCo-HSOM on demonstrations,
//! reproduce from the initial posture, execute on the simulated arm, score it.

use std::time::Instant;

use crate::config::HsomConfig;
use crate::demos::Demonstration;
use crate::hsom::{Hsom, Reproduction};
use crate::metrics::{FidelityReport, MetricsParams};
use crate::sim::{NaoArm, Recording};

use super::{clamp_to_ranges, evaluate, execute_postures, ExperimentError, Transition};

/// Whether the hierarchy learns (the real thing) or keeps its seeded initial weights (the
/// negative control of every fidelity check).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Training {
    /// Train as configured.
    Trained,
    /// Initial weights only.
    Untrained,
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
    /// Its fidelity against each demonstration.
    pub fidelity: FidelityReport,
    /// Training time, seconds.
    pub train_s: f64,
    /// Time to produce the postures, seconds.
    pub reproduce_s: f64,
}

/// Seconds between samples of a demonstration: from its `time` column, else 1/40 s.
pub fn sample_period(d: &Demonstration) -> f64 {
    match &d.time {
        Some(t) if t.len() >= 2 => (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64,
        _ => 0.025,
    }
}

/// Train on `demos` (or not), reproduce from the first demonstration's first posture, execute
/// on `arm` with `transition` and score against `demos`. `progress(done, total)` follows the
/// training.
pub fn learn_and_reproduce(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    training: Training,
    transition: Transition,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<Outcome, ExperimentError> {
    let first = demos
        .first()
        .ok_or_else(|| ExperimentError::Invalid("no demonstrations to learn from".into()))?;
    let initial = first
        .rows
        .first()
        .ok_or_else(|| ExperimentError::Invalid(format!("{}: no samples", first.source)))?
        .clone();
    let t = Instant::now();
    let model = match training {
        Training::Trained => config.fit_with_progress(demos, progress)?,
        Training::Untrained => config.initialise(demos)?,
    };
    let train_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let reproduction = model.reproduce(&initial)?;
    let reproduce_s = t.elapsed().as_secs_f64();
    let (postures, clamped_values) = clamp_to_ranges(&reproduction.postures)?;
    let postures = transition.shape(&postures);
    let dt = sample_period(first);
    let executed = execute_postures(arm, &postures, 1.0 / dt)?;
    let params = MetricsParams {
        sample_period: dt,
        ..MetricsParams::default()
    };
    let fidelity = evaluate(Some(arm), demos, &executed.qpos, &params)?;
    Ok(Outcome {
        model,
        reproduction,
        clamped_values,
        executed,
        fidelity,
        train_s,
        reproduce_s,
    })
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
    let first = demos
        .first()
        .ok_or_else(|| ExperimentError::Invalid("no demonstrations".into()))?;
    let initial = first
        .rows
        .first()
        .ok_or_else(|| ExperimentError::Invalid(format!("{}: no samples", first.source)))?;
    let t = Instant::now();
    let rep = model.reproduce_with(initial, reproduction)?;
    let reproduce_s = t.elapsed().as_secs_f64();
    let (postures, clamped) = clamp_to_ranges(&rep.postures)?;
    let dt = sample_period(first);
    let executed = execute_postures(arm, &transition.shape(&postures), 1.0 / dt)?;
    let params = MetricsParams {
        sample_period: dt,
        ..MetricsParams::default()
    };
    let fidelity = evaluate(Some(arm), demos, &executed.qpos, &params)?;
    Ok((rep, clamped, executed, fidelity, reproduce_s))
}
