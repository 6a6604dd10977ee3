//! Held-out evaluation (leave-one-out) on the simulated arm: for each demonstration `i`,
//! learn from all the others, reproduce from demonstration `i`'s first posture, execute on the
//! arm and score against demonstration `i` only, for CoSCo-HSOM and the GMM/GMR and ProMP
//! baselines alike (the evaluator's [`fold`] with [`ArmExecutor`]). The in-sample result
//! (learn from all, score against all) says how well a method reproduces what it saw; this
//! says how well it reproduces the gesture from a start it has not seen.

use crate::config::HsomConfig;
use crate::demos::{sample_period, Demonstration};
use crate::eval::{
    diagonal, loo_folds, run_fold, Fold, FoldInput, HeldOut, HeldOutSummary, Method, MethodRun,
    Pool, Training,
};
use crate::sim::{NaoArm, Recording, Transition, SWING_JOINT};

use super::executor::ArmExecutor;
use super::ExperimentError;
use crate::robot::Robot;

/// Check that leave-one-out can run on `demos`: at least 2, the arm's joints.
pub fn check_demos(demos: &[Demonstration]) -> Result<(), ExperimentError> {
    check_demos_of(Robot::LeftArm, demos)
}

/// [`check_demos`] for `robot`'s joints.
fn check_demos_of(robot: Robot, demos: &[Demonstration]) -> Result<(), ExperimentError> {
    if demos.len() < 2 {
        return Err(ExperimentError::Invalid(format!(
            "leave-one-out needs at least 2 demonstrations (one to hold out, one to learn \
             from), got {}",
            demos.len()
        )));
    }
    for d in demos {
        if Robot::of_columns(&d.columns) != Some(robot) {
            return Err(ExperimentError::Invalid(format!(
                "{}: columns {:?}; executing on the simulated arm needs exactly {:?}",
                d.source,
                d.columns,
                robot.joint_names()
            )));
        }
    }
    Ok(())
}

/// `methods` on every fold of `demos` on the arm ([`loo_folds`], one thread): fold `i` learns
/// from every demonstration but `demos[i]` (the hierarchy with `config` and `training`,
/// executed with `transition`), starts from its first posture and is scored against it alone.
/// A baseline that cannot run on a fold holds the reason, `fold N: method: why`.
pub fn folds<const N: usize>(
    arm: &NaoArm<N>,
    demos: &[Demonstration],
    methods: &[Method],
    config: Option<&HsomConfig>,
    training: Training,
    transition: Transition,
) -> Result<Vec<Fold>, ExperimentError> {
    check_demos_of(arm.robot(), demos)?;
    let executor = ArmExecutor { arm, transition };
    let base = FoldInput {
        config,
        training,
        ..FoldInput::new(&[], &[])
    };
    let pool = Pool::new(1).map_err(ExperimentError::Invalid)?;
    let sets = [(demos, diagonal(demos))];
    let mut folds = loo_folds(&sets, methods, None, &base, &executor, &pool, None)
        .pop()
        .map(|(held_out, _)| held_out)
        .unwrap_or_default();
    // a baseline's failed fit named with its fold, as a skipped baseline's reason is
    let baseline = |m: &Method| matches!(m, Method::GmmGmr | Method::ProMP);
    for (i, f) in folds.iter_mut().enumerate() {
        for r in f.runs.iter_mut().filter(|r| baseline(&r.method)) {
            match &mut r.error {
                Some(e) if !e.starts_with("fold ") => {
                    *e = format!("fold {}: {}: {e}", i + 1, r.method.name())
                }
                _ => {}
            }
        }
    }
    Ok(folds)
}

/// Leave-one-out for CoSCo-HSOM (trained with `config`, executed with `transition`), the
/// nearest sequence (the same model following the bottom events of the training
/// demonstration that starts nearest), GMM/GMR and ProMP ([`folds`]). Needs at least 2
/// demonstrations of the arm's joints; GMM/GMR and ProMP need 2 to learn from, so with 2
/// demonstrations their folds hold the reason instead.
pub fn leave_one_out<const N: usize>(
    arm: &NaoArm<N>,
    config: &HsomConfig,
    demos: &[Demonstration],
    transition: Transition,
) -> Result<HeldOut, ExperimentError> {
    let methods = [
        Method::Hierarchy,
        Method::NearestSequence,
        Method::GmmGmr,
        Method::ProMP,
        Method::Dmp,
        Method::Dba,
    ];
    let all = folds(
        arm,
        demos,
        &methods,
        Some(config),
        Training::Trained,
        transition,
    )?;
    Ok(HeldOut::of(all)?)
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

/// CoSCo-HSOM alone on every fold ([`folds`]): the means over them.
pub fn hierarchy_held_out<const N: usize>(
    arm: &NaoArm<N>,
    config: &HsomConfig,
    demos: &[Demonstration],
    training: Training,
    transition: Transition,
) -> Result<HeldOutSummary, ExperimentError> {
    let all = folds(
        arm,
        demos,
        &[Method::Hierarchy],
        Some(config),
        training,
        transition,
    )?;
    Ok(HeldOut::of(all)?.hsom)
}

/// `method` as `input` says (configuration, training progress, GMM/GMR's components) on its
/// split, executed on the arm with `transition`: in the reports, learned from all
/// demonstrations and scored against all ([`Split::InSampleAll`]).
pub fn on_arm<const N: usize>(
    arm: &NaoArm<N>,
    transition: Transition,
    method: Method,
    input: &FoldInput<'_>,
) -> Result<MethodRun<Recording>, ExperimentError> {
    if input.train.is_empty() {
        return Err(ExperimentError::Invalid(
            "no demonstrations to learn from".into(),
        ));
    }
    let executor = ArmExecutor { arm, transition };
    match run_fold(&[method], input, &executor).pop() {
        Some((_, run)) => run.map_err(ExperimentError::Invalid),
        None => Err(ExperimentError::Invalid(format!(
            "{} did not run",
            method.name()
        ))),
    }
}
