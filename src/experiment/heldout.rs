//! Held-out evaluation (leave-one-out): for each demonstration `i`, learn from all the others,
//! reproduce from demonstration `i`'s first posture, execute on the simulated arm and score
//! against demonstration `i` only, for CoSCo-HSOM and the GMM/GMR baseline alike. The
//! in-sample result (learn from all, score against all) says how well a method reproduces
//! what it saw; this says how well it reproduces the gesture from a start it has not seen.

use serde::Serialize;

use crate::config::HsomConfig;
use crate::demos::{sample_period, Demonstration};
use crate::eval::{all_but, run_fold, FoldInput, Method, MethodRun};
use crate::gmr::MIN_DEMONSTRATIONS;
use crate::metrics::{column_swings, FidelityReport};
use crate::sim::{NaoArm, Recording, JOINT_NAMES};

use super::pipeline::Training;
use super::{are_arm_joints, ArmExecutor, ExperimentError, Transition};

/// The joint whose large swings are counted (column 3, `LElbowRoll`: the wave's joint).
pub const SWING_JOINT: usize = 3;
/// Smallest excursion between turning points that counts as a swing, rad.
pub const SWING_MIN_AMPLITUDE_RAD: f64 = 0.3;

/// Large swings of [`SWING_JOINT`] (see [`crate::metrics::large_swings`]): the reproduction's
/// and the held-out demonstration's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Swings {
    /// Joint name.
    pub joint: String,
    /// Smallest excursion counted, rad.
    pub min_amplitude_rad: f64,
    /// Swings of the executed reproduction.
    pub reproduction: usize,
    /// Swings of the held-out demonstration.
    pub demo: usize,
}

/// One method on one fold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FoldScores {
    /// Fidelity of the executed trajectory against the held-out demonstration only.
    pub fidelity: FidelityReport,
    /// Large swings of [`SWING_JOINT`].
    pub swings: Swings,
    /// Postures the method produced.
    pub postures: usize,
    /// Posture values clamped into the joint ranges before execution.
    pub clamped_values: usize,
    /// Training time, seconds.
    pub train_s: f64,
    /// Time to produce the postures, seconds.
    pub reproduce_s: f64,
}

impl FoldScores {
    /// A method's run on the arm ([`run_fold`] with [`ArmExecutor`]) as its scores against
    /// the held-out demonstration `held`.
    pub fn of(
        run: MethodRun<Recording>,
        held: &Demonstration,
    ) -> Result<FoldScores, ExperimentError> {
        Ok(FoldScores {
            swings: swings(&run.executed.trace, held)?,
            postures: run.postures.len(),
            clamped_values: run.executed.clamped_values,
            train_s: run.train_s,
            reproduce_s: run.reproduce_s,
            fidelity: run.executed.fidelity,
        })
    }
}

/// One fold: a demonstration held out.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fold {
    /// 0-based index of the held-out demonstration.
    pub held_out: usize,
    /// Its source (file name or description).
    pub source: String,
    /// CoSCo-HSOM trained on the other demonstrations.
    pub hsom: FoldScores,
    /// GMM/GMR trained on the other demonstrations, when it could run.
    pub gmr: Option<FoldScores>,
    /// Why GMM/GMR did not run on this fold.
    pub gmr_error: Option<String>,
    /// The nearest-sequence baseline on the same fold ([`hsom_and_sequence_folds`]), when it
    /// was run.
    pub sequence: Option<FoldScores>,
}

/// Means over folds of one method.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeldOutSummary {
    /// Folds averaged.
    pub folds: usize,
    /// Joint-space DTW, rad per step.
    pub joint_dtw_rad_per_step: f64,
    /// Wrist-path DTW, mm per step (when every fold has wrist paths).
    pub wrist_dtw_mm: Option<f64>,
    /// Apex (key-pose) error, rad.
    pub apex_error_rad: f64,
    /// Final-posture error, rad.
    pub final_error_rad: f64,
    /// Duration ratio, reproduction / held-out demonstration (trimmed).
    pub duration_ratio: f64,
    /// Normalized jerk of the reproductions (mean over the folds where it is defined).
    pub normalized_jerk: Option<f64>,
    /// Velocity reversals of the reproductions, all joints.
    pub velocity_reversals: f64,
    /// Normalized jerk of the held-out demonstrations (mean where defined).
    pub demo_normalized_jerk: Option<f64>,
    /// Velocity reversals of the held-out demonstrations, all joints.
    pub demo_velocity_reversals: f64,
    /// Large swings of [`SWING_JOINT`] of the reproductions.
    pub swings: f64,
    /// Large swings of [`SWING_JOINT`] of the held-out demonstrations.
    pub demo_swings: f64,
    /// How long the reproductions stay at their apex, seconds (docs/METRICS.md,
    /// `apex_dwell`).
    pub hold_s: f64,
    /// The same for the held-out demonstrations.
    pub demo_hold_s: f64,
}

fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

impl HeldOutSummary {
    /// Means over `folds`; `None` when there are none.
    pub fn of(folds: &[&FoldScores]) -> Option<HeldOutSummary> {
        let m = |f: &dyn Fn(&FoldScores) -> f64| mean(folds.iter().map(|s| f(s)));
        let demo_smoothness = |s: &FoldScores| s.fidelity.demo_smoothness.first().cloned();
        Some(HeldOutSummary {
            folds: folds.len(),
            joint_dtw_rad_per_step: m(&|s| s.fidelity.joint_dtw_rad_per_step.mean)?,
            wrist_dtw_mm: folds
                .iter()
                .map(|s| s.fidelity.wrist_dtw_mm.map(|w| w.mean))
                .collect::<Option<Vec<f64>>>()
                .and_then(|v| mean(v.into_iter())),
            apex_error_rad: m(&|s| s.fidelity.apex_error_rad.mean)?,
            final_error_rad: m(&|s| s.fidelity.final_error_rad.mean)?,
            duration_ratio: m(&|s| s.fidelity.duration_ratio.mean)?,
            normalized_jerk: mean(
                folds
                    .iter()
                    .filter_map(|s| s.fidelity.reproduction_smoothness.normalized_jerk),
            ),
            velocity_reversals: m(&|s| s.fidelity.reproduction_smoothness.total_reversals as f64)?,
            demo_normalized_jerk: mean(
                folds
                    .iter()
                    .filter_map(|s| demo_smoothness(s).and_then(|d| d.normalized_jerk)),
            ),
            demo_velocity_reversals: m(&|s| {
                demo_smoothness(s).map_or(f64::NAN, |d| d.total_reversals as f64)
            })?,
            swings: m(&|s| s.swings.reproduction as f64)?,
            demo_swings: m(&|s| s.swings.demo as f64)?,
            hold_s: m(&|s| s.fidelity.reproduction_hold_s)?,
            demo_hold_s: m(&|s| s.fidelity.demo_hold_s.first().copied().unwrap_or(f64::NAN))?,
        })
    }
}

/// The held-out evaluation of CoSCo-HSOM and GMM/GMR on one set of demonstrations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeldOut {
    /// One fold per demonstration, in order.
    pub folds: Vec<Fold>,
    /// CoSCo-HSOM: means over all folds.
    pub hsom: HeldOutSummary,
    /// GMM/GMR: means over the folds where it ran (`None` when it ran on none).
    pub gmr: Option<HeldOutSummary>,
    /// The nearest-sequence baseline: means over all folds (`None` when it was not run:
    /// [`HeldOut::with_sequence`]).
    pub sequence: Option<HeldOutSummary>,
}

impl HeldOut {
    /// Put per-fold results together: `hsom[i]` and `gmr[i]` are the results of fold `i`
    /// (demonstration `i` held out); `gmr[i]` is the reason when GMM/GMR did not run.
    pub fn new(
        demos: &[Demonstration],
        hsom: Vec<FoldScores>,
        gmr: Vec<Result<FoldScores, String>>,
    ) -> Result<HeldOut, ExperimentError> {
        if hsom.len() != demos.len() || gmr.len() != demos.len() {
            return Err(ExperimentError::Invalid(format!(
                "held-out results: {} CoSCo-HSOM and {} GMM/GMR folds for {} demonstrations; \
                 need one per demonstration",
                hsom.len(),
                gmr.len(),
                demos.len()
            )));
        }
        let folds: Vec<Fold> = demos
            .iter()
            .zip(hsom.into_iter().zip(gmr))
            .enumerate()
            .map(|(i, (d, (h, g)))| {
                let (gmr, gmr_error) = match g {
                    Ok(s) => (Some(s), None),
                    Err(e) => (None, Some(e)),
                };
                Fold {
                    held_out: i,
                    source: d.source.clone(),
                    hsom: h,
                    gmr,
                    gmr_error,
                    sequence: None,
                }
            })
            .collect();
        let all: Vec<&FoldScores> = folds.iter().map(|f| &f.hsom).collect();
        let hsom = HeldOutSummary::of(&all).ok_or_else(|| {
            ExperimentError::Invalid("held-out results: no folds (no demonstrations)".into())
        })?;
        let ran: Vec<&FoldScores> = folds.iter().filter_map(|f| f.gmr.as_ref()).collect();
        Ok(HeldOut {
            gmr: HeldOutSummary::of(&ran),
            hsom,
            folds,
            sequence: None,
        })
    }

    /// Add the nearest-sequence baseline's folds ([`hsom_and_sequence_folds`]): `sequence[i]` is fold
    /// `i`'s, one per fold.
    pub fn with_sequence(mut self, sequence: Vec<FoldScores>) -> Result<HeldOut, ExperimentError> {
        if sequence.len() != self.folds.len() {
            return Err(ExperimentError::Invalid(format!(
                "held-out results: {} nearest-sequence folds for {} folds; need one per fold",
                sequence.len(),
                self.folds.len()
            )));
        }
        for (f, s) in self.folds.iter_mut().zip(sequence) {
            f.sequence = Some(s);
        }
        let all: Vec<&FoldScores> = self
            .folds
            .iter()
            .filter_map(|f| f.sequence.as_ref())
            .collect();
        self.sequence = HeldOutSummary::of(&all);
        Ok(self)
    }

    /// Both methods averaged over the same folds (those where GMM/GMR ran): (CoSCo-HSOM,
    /// GMM/GMR); `None` when GMM/GMR ran on none.
    pub fn paired(&self) -> Option<(HeldOutSummary, HeldOutSummary)> {
        let (h, g): (Vec<&FoldScores>, Vec<&FoldScores>) = self
            .folds
            .iter()
            .filter_map(|f| f.gmr.as_ref().map(|g| (&f.hsom, g)))
            .unzip();
        Some((HeldOutSummary::of(&h)?, HeldOutSummary::of(&g)?))
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
        .zip(demos)
        .map(|(run, held)| FoldScores::of(run, held))
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
                .map(|run| FoldScores::of(run.map_err(ExperimentError::Invalid)?, &demos[i]));
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
                    "fold {}: GMM/GMR needs at least {MIN_DEMONSTRATIONS} demonstrations to \
                     learn from, this fold has {learn_from}",
                    i + 1,
                ));
            }
            let run = only(arm_fold(
                &executor,
                &[Method::GmmGmr],
                None,
                Training::Trained,
                demos,
                i,
            ))
            .and_then(|run| FoldScores::of(run, &demos[i]).map_err(|e| e.to_string()));
            run.map_err(|e| format!("fold {}: GMM/GMR: {e}", i + 1))
        })
        .collect())
}

/// Leave-one-out for CoSCo-HSOM (trained with `config`, executed with `transition`),
/// GMM/GMR and the nearest-sequence baseline ([`hsom_and_sequence_folds`]): fold `i` learns from
/// every demonstration but `demos[i]`, reproduces from `demos[i]`'s first posture, executes
/// on `arm` and is scored against `demos[i]` only. Needs at least 2 demonstrations of the
/// arm's joints; GMM/GMR needs 2 to learn from, so with 2 demonstrations its folds hold the
/// reason instead.
pub fn leave_one_out(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    transition: Transition,
) -> Result<HeldOut, ExperimentError> {
    let (hsom, sequence) = hsom_and_sequence_folds(arm, config, demos, transition)?;
    let gmr = gmr_folds(arm, demos)?;
    HeldOut::new(demos, hsom, gmr)?.with_sequence(sequence)
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
