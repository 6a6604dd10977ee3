//! Held-out evaluation (leave-one-out): for each demonstration `i`, learn from all the others,
//! reproduce from demonstration `i`'s first posture, execute on the simulated arm and score
//! against demonstration `i` only, for CoSCo-HSOM and the GMM/GMR and ProMP baselines alike. The
//! in-sample result (learn from all, score against all) says how well a method reproduces
//! what it saw; this says how well it reproduces the gesture from a start it has not seen.

use crate::config::HsomConfig;
use crate::demos::{sample_period, Demonstration};
use crate::dtw::euclidean;
use crate::eval::{all_but, diagonal, run_fold, Commanded, FoldInput, Method, MethodRun};
pub use crate::eval::{ArmFold as Fold, FoldScores, HeldOut, HeldOutSummary, Swings};
use crate::gmr::MIN_DEMONSTRATIONS;
use crate::metrics::{column_swings, trimmed_normalized_jerk, MetricsParams, StartEndReference};
use crate::sim::{NaoArm, Recording, JOINT_NAMES};

use super::pipeline::Training;
use super::{are_arm_joints, ArmExecutor, ExperimentError, Transition};

pub use super::evaluate::{SWING_JOINT, SWING_MIN_AMPLITUDE_RAD};

impl FoldScores {
    /// A method's run on the arm ([`run_fold`] with [`ArmExecutor`]) on fold `i` of `demos`
    /// as its scores against the held-out demonstration `demos[i]`: the executed motion's and
    /// the commanded postures' start and end against the other demonstrations (docs/METRICS.md,
    /// "Start and end"), in the diagonal of all of them.
    pub fn of(
        run: MethodRun<Recording>,
        demos: &[Demonstration],
        i: usize,
    ) -> Result<FoldScores, ExperimentError> {
        let held = demos.get(i).ok_or_else(|| {
            ExperimentError::Invalid(format!(
                "fold {}: no such demonstration (there are {})",
                i + 1,
                demos.len()
            ))
        })?;
        let others = demos.iter().enumerate().filter(|&(j, _)| j != i);
        let reference = StartEndReference::of(others.map(|(_, d)| d), diagonal(demos));
        let metrics = MetricsParams {
            sample_period: sample_period(held),
            ..MetricsParams::default()
        };
        let dt = metrics.sample_period;
        let executed = &run.executed;
        let start_end = reference.judge(
            &executed.trace.qpos,
            dt,
            executed.fidelity.final_error_rad.mean,
        );
        let commanded = match (executed.commanded.last(), held.rows.last()) {
            (Some(c), Some(h)) => Some(Commanded {
                postures: executed.commanded.len(),
                normalized_jerk: trimmed_normalized_jerk(&executed.commanded, &metrics),
                start_end: reference.judge(&executed.commanded, dt, euclidean(c, h)),
            }),
            _ => None,
        };
        Ok(FoldScores {
            swings: swings(&executed.trace, held)?,
            postures: run.postures.len(),
            clamped_values: executed.clamped_values,
            train_s: run.train_s,
            reproduce_s: run.reproduce_s,
            start_end: Some(start_end),
            commanded,
            fidelity: run.executed.fidelity,
        })
    }
}

/// Check that leave-one-out can run on `demos`: at least 2, the arm's joints.
pub fn check_demos(demos: &[Demonstration]) -> Result<(), ExperimentError> {
    if demos.len() < 2 {
        return Err(ExperimentError::Invalid(format!(
            "leave-one-out needs at least 2 demonstrations (one to hold out, one to learn \
             from), got {}",
            demos.len()
        )));
    }
    for d in demos {
        if !are_arm_joints(&d.columns) {
            return Err(ExperimentError::Invalid(format!(
                "{}: columns {:?}; executing on the simulated arm needs exactly {:?}",
                d.source, d.columns, JOINT_NAMES
            )));
        }
    }
    Ok(())
}

/// The large swings of [`SWING_JOINT`] in an executed reproduction and in the held-out
/// demonstration it is scored against.
pub fn swings(executed: &Recording, held_out: &Demonstration) -> Result<Swings, ExperimentError> {
    Ok(Swings {
        joint: JOINT_NAMES[SWING_JOINT].to_string(),
        min_amplitude_rad: SWING_MIN_AMPLITUDE_RAD,
        reproduction: column_swings(&executed.qpos, SWING_JOINT, SWING_MIN_AMPLITUDE_RAD)?,
        demo: column_swings(&held_out.rows, SWING_JOINT, SWING_MIN_AMPLITUDE_RAD)?,
    })
}

/// Fold `i` of `demos` on the arm ([`run_fold`] with [`ArmExecutor`]): `methods` learn from
/// every demonstration but `demos[i]` (the hierarchy with `config` and `training`), start from
/// its first posture, are executed and scored against it alone; each method's run, in
/// `methods`' order.
pub fn arm_fold(
    executor: &ArmExecutor<'_>,
    methods: &[Method],
    config: Option<&HsomConfig>,
    training: Training,
    demos: &[Demonstration],
    i: usize,
) -> Vec<Result<MethodRun<Recording>, String>> {
    let train = all_but(demos, i);
    let input = FoldInput {
        config,
        height_1: None,
        train: &train,
        target: &demos[i],
        training,
    };
    run_fold(methods, &input, executor)
        .into_iter()
        .map(|(_, run)| run)
        .collect()
}

/// The run of the one method asked of [`arm_fold`].
fn only(runs: Vec<Result<MethodRun<Recording>, String>>) -> Result<MethodRun<Recording>, String> {
    runs.into_iter().next().unwrap_or_else(|| Err(no_run()))
}

/// The hierarchy on every fold: `result[i]` learned from all demonstrations but `demos[i]`
/// (with `training`), reproduced from `demos[i]`'s first posture, executed with `transition`
/// and scored against `demos[i]` only (the evaluator's [`run_fold`] on the arm's executor).
pub fn hierarchy_runs(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    training: Training,
    transition: Transition,
) -> Result<Vec<MethodRun<Recording>>, ExperimentError> {
    check_demos(demos)?;
    let executor = ArmExecutor { arm, transition };
    (0..demos.len())
        .map(|i| {
            only(arm_fold(
                &executor,
                &[Method::Hierarchy],
                Some(config),
                training,
                demos,
                i,
            ))
            .map_err(ExperimentError::Invalid)
        })
        .collect()
}

/// CoSCo-HSOM's scores on every fold ([`hierarchy_runs`]).
pub fn hsom_folds(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    training: Training,
    transition: Transition,
) -> Result<Vec<FoldScores>, ExperimentError> {
    hierarchy_runs(arm, config, demos, training, transition)?
        .into_iter()
        .enumerate()
        .map(|(i, run)| FoldScores::of(run, demos, i))
        .collect()
}

/// CoSCo-HSOM's folds as [`hsom_folds`] (trained), and on each fold, from the same trained
/// model, the *nearest-sequence* baseline: instead of the levels' plan, the bottom events of
/// the training demonstration whose first posture is nearest `demos[i]`'s
/// ([`Hsom::follow_nearest`](crate::hsom::Hsom::follow_nearest)), executed with
/// `transition` and scored against `demos[i]` only: what the upper levels add over following
/// one whole demonstrated sequence through the same bottom code. Returns (CoSCo-HSOM's
/// folds, the baseline's), one per demonstration each.
pub fn hsom_and_sequence_folds(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    transition: Transition,
) -> Result<(Vec<FoldScores>, Vec<FoldScores>), ExperimentError> {
    check_demos(demos)?;
    let executor = ArmExecutor { arm, transition };
    let methods = [Method::Hierarchy, Method::NearestSequence];
    (0..demos.len())
        .map(|i| {
            let runs = arm_fold(
                &executor,
                &methods,
                Some(config),
                Training::Trained,
                demos,
                i,
            );
            let mut scores = runs
                .into_iter()
                .map(|run| FoldScores::of(run.map_err(ExperimentError::Invalid)?, demos, i));
            let no_run = || Err(ExperimentError::Invalid(no_run()));
            let hsom = scores.next().unwrap_or_else(no_run)?;
            let sequence = scores.next().unwrap_or_else(no_run)?;
            Ok((hsom, sequence))
        })
        .collect::<Result<Vec<_>, ExperimentError>>()
        .map(|v| v.into_iter().unzip())
}

/// A method asked of [`run_fold`] that it did not answer (cannot happen: it answers each).
fn no_run() -> String {
    "the evaluator returned no run for a method".into()
}

/// GMM/GMR ([`DEFAULT_COMPONENTS`](super::baseline::DEFAULT_COMPONENTS)) on every fold, as [`hsom_folds`] (the evaluator's
/// [`run_fold`] on the arm's executor: posture to posture, the lead-in at the arm's speed); a
/// fold where it cannot run (fewer than [`MIN_DEMONSTRATIONS`] to learn from, a failed fit)
/// gives the reason. Errors only when `demos` cannot be used at all.
pub fn gmr_folds(
    arm: &NaoArm,
    demos: &[Demonstration],
) -> Result<Vec<Result<FoldScores, String>>, ExperimentError> {
    baseline_folds(arm, demos, Method::GmmGmr)
}

/// ProMP conditioned on the initial posture ([`Method::ProMP`]) on every fold, as
/// [`gmr_folds`]: posture to posture; a fold where it cannot run (fewer than
/// [`MIN_DEMONSTRATIONS`] to learn from, a failed fit) gives the reason.
pub fn promp_folds(
    arm: &NaoArm,
    demos: &[Demonstration],
) -> Result<Vec<Result<FoldScores, String>>, ExperimentError> {
    baseline_folds(arm, demos, Method::ProMP)
}

/// A baseline `method` that learns from demonstrations alone on every fold (the evaluator's
/// [`run_fold`] on the arm's executor, posture to posture), or the fold's reason.
fn baseline_folds(
    arm: &NaoArm,
    demos: &[Demonstration],
    method: Method,
) -> Result<Vec<Result<FoldScores, String>>, ExperimentError> {
    check_demos(demos)?;
    let executor = ArmExecutor {
        arm,
        transition: Transition::Linear,
    };
    Ok((0..demos.len())
        .map(|i| {
            let learn_from = demos.len() - 1;
            if learn_from < MIN_DEMONSTRATIONS {
                return Err(format!(
                    "fold {}: {} needs at least {MIN_DEMONSTRATIONS} demonstrations to \
                     learn from, this fold has {learn_from}",
                    i + 1,
                    method.name(),
                ));
            }
            let run = only(arm_fold(
                &executor,
                &[method],
                None,
                Training::Trained,
                demos,
                i,
            ))
            .and_then(|run| FoldScores::of(run, demos, i).map_err(|e| e.to_string()));
            run.map_err(|e| format!("fold {}: {}: {e}", i + 1, method.name()))
        })
        .collect())
}

/// Leave-one-out for CoSCo-HSOM (trained with `config`, executed with `transition`),
/// GMM/GMR, ProMP and the nearest-sequence baseline ([`hsom_and_sequence_folds`]): fold `i`
/// learns from every demonstration but `demos[i]`, reproduces from `demos[i]`'s first posture,
/// executes on `arm` and is scored against `demos[i]` only. Needs at least 2 demonstrations of
/// the arm's joints; GMM/GMR and ProMP need 2 to learn from, so with 2 demonstrations their
/// folds hold the reason instead.
pub fn leave_one_out(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    transition: Transition,
) -> Result<HeldOut, ExperimentError> {
    let (hsom, sequence) = hsom_and_sequence_folds(arm, config, demos, transition)?;
    let gmr = gmr_folds(arm, demos)?;
    let promp = promp_folds(arm, demos)?;
    Ok(HeldOut::new(demos, hsom, gmr)?
        .with_sequence(sequence)?
        .with_promp(promp)?)
}

/// `(time s, value rad)` of [`SWING_JOINT`] in an executed recording.
pub fn joint_trace(rec: &Recording) -> Vec<(f64, f64)> {
    rec.time
        .iter()
        .zip(&rec.qpos)
        .map(|(&t, q)| (t, q[SWING_JOINT]))
        .collect()
}

/// `(time s, value rad)` of [`SWING_JOINT`] in a demonstration (its own times, or its rows at
/// its sample period).
pub fn demo_trace(demo: &Demonstration) -> Vec<(f64, f64)> {
    let period = sample_period(demo);
    demo.rows
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let t = demo
                .time
                .as_ref()
                .and_then(|t| t.get(k).copied())
                .unwrap_or(k as f64 * period);
            (t, r[SWING_JOINT])
        })
        .collect()
}
