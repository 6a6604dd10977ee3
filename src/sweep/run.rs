//! One run of a sweep: the `simulate --no-render` pipeline for one point of the grid
//! (synthetic demonstrations, then the evaluator once: in-sample or leave-one-out,
//! CoSCo-HSOM, GMM/GMR or both, executed on the simulated arm or upper body), its metrics, and
//! the record it leaves in `DIR/runs/<run-id>.json`.

use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::demos::Demonstration;
use crate::eval::{
    diagonal, fold, Executor, FoldInput, FoldScores, HeldOutSummary, Method, Split, Training,
    SWING_MIN_AMPLITUDE_RAD,
};
use crate::experiment::{folds, synthetic_demonstrations, ArmExecutor, DemoSettings};
use crate::gesture::Gesture;
use crate::metrics::column_swings;
use crate::metrics::registry::{
    APEX_ERROR, DEMO_SWINGS, DEMO_VELOCITY_REVERSALS, DURATION_RATIO, FINAL_ERROR, JERK_RATIO,
    JOINT_DTW, SWINGS, VELOCITY_REVERSALS, WRIST_DTW,
};
use crate::robot::Robot;
use crate::sim::NaoArm;

use super::spec::{AxisValues, Evaluation, RunPlan, SweepSpec};
use super::{read_json, write_json, SweepError};

/// Version of the run-file format.
pub const RUN_FORMAT: u32 = 1;

/// One method's result in a run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MethodRecord {
    /// `cosco-hsom` or `gmr` ([`super::spec::method_name`]).
    #[serde(with = "super::spec::method_serde")]
    pub method: Method,
    /// Fidelity metrics (names in [`super::METRICS`]); a metric that is undefined for
    /// this run is absent.
    pub metrics: BTreeMap<String, f64>,
    /// Seconds: `train_s` and `reproduce_s` (means over folds for leave-one-out).
    pub timing: BTreeMap<String, f64>,
    /// Why the method could not run (then `metrics` is empty).
    pub error: Option<String>,
    /// Every number behind the metrics: the fidelity report (in-sample) or every fold
    /// (leave-one-out).
    pub detail: serde_json::Value,
}

/// What `DIR/runs/<run-id>.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// [`RUN_FORMAT`].
    pub format: u32,
    /// The run's id (its file name's stem).
    pub run_id: String,
    /// Position in the grid.
    pub index: usize,
    /// The sweep's identity hash (`SweepSpec::hash`).
    pub spec_hash: String,
    /// This crate's version.
    pub crate_version: String,
    /// The axes' values.
    pub axes: AxisValues,
    /// SHA-256 of the configuration file (as `sha256sum` prints it).
    pub config_sha256: String,
    /// Transition of CoSCo-HSOM's postures.
    pub transition: String,
    /// The shard that ran it, `I/N`.
    pub shard: String,
    /// Wall time of the run, seconds.
    pub wall_s: f64,
    /// Why the run failed as a whole (then `methods` is empty).
    pub error: Option<String>,
    /// One entry per method run.
    pub methods: Vec<MethodRecord>,
}

impl RunRecord {
    /// Whether the run or one of its methods failed.
    pub fn failed(&self) -> bool {
        self.error.is_some() || self.methods.iter().any(|m| m.error.is_some())
    }

    /// Read a run file.
    pub fn read(path: &Path) -> Result<RunRecord, SweepError> {
        let r: RunRecord = read_json(path, "read the run file", |e| {
            format!("not a run file of this version ({e}); delete it to run it again")
        })?;
        if r.format != RUN_FORMAT {
            return Err(SweepError::Record {
                path: path.to_path_buf(),
                message: format!(
                    "run-file format {}, this version reads {RUN_FORMAT}; delete it to run it again",
                    r.format
                ),
            });
        }
        Ok(r)
    }

    /// Write atomically (a killed sweep leaves the old file or none, never half a file).
    pub fn write(&self, path: &Path) -> Result<(), SweepError> {
        write_json(path, self, "write the run file")
    }
}

/// Run `plan` of `spec` (in shard `shard`) and record it. Never fails: an error, or a panic,
/// of the run is recorded in it.
pub fn execute_run(spec: &SweepSpec, plan: &RunPlan, spec_hash: &str, shard: &str) -> RunRecord {
    let t = Instant::now();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run_methods(spec, plan)))
        .unwrap_or_else(|panic| {
            let what = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "unknown panic".into());
            Err(format!("the run panicked: {what}"))
        });
    let (methods, error) = match result {
        Ok(m) => (m, None),
        Err(e) => (Vec::new(), Some(e)),
    };
    RunRecord {
        format: RUN_FORMAT,
        run_id: plan.id.clone(),
        index: plan.index,
        spec_hash: spec_hash.to_string(),
        crate_version: env!("CARGO_PKG_VERSION").to_string(),
        axes: plan.axes.clone(),
        config_sha256: spec
            .config_sha256(&plan.axes)
            .unwrap_or_default()
            .to_string(),
        transition: spec.transition.name(),
        shard: shard.to_string(),
        wall_s: t.elapsed().as_secs_f64(),
        error,
        methods,
    }
}

/// The run on its robot, `N` its joints (the robot is chosen here, once).
fn run_methods(spec: &SweepSpec, plan: &RunPlan) -> Result<Vec<MethodRecord>, String> {
    match plan.axes.robot {
        Robot::LeftArm => run_methods_on::<6>(spec, plan),
        Robot::UpperBody => run_methods_on::<14>(spec, plan),
    }
}

fn run_methods_on<const N: usize>(
    spec: &SweepSpec,
    plan: &RunPlan,
) -> Result<Vec<MethodRecord>, String> {
    let a = &plan.axes;
    // one simulator per run: nothing MuJoCo is shared between the pool's threads
    let arm = match &spec.model {
        Some(p) => NaoArm::<N>::load_robot(a.robot, p),
        None => NaoArm::<N>::load_shipped(a.robot),
    }
    .map_err(|e| format!("loading the arm model: {e}"))?;
    let gesture = Gesture::by_name(a.robot, &a.gesture)
        .ok_or_else(|| format!("unknown gesture '{}' of the {}", a.gesture, a.robot.name()))?;
    let config = spec.config_of(a).ok_or_else(|| {
        format!(
            "no configuration '{}' at height {}",
            a.config,
            a.height.name()
        )
    })?;
    let settings = DemoSettings {
        encoder_noise: a.noise,
        ..DemoSettings::default()
    };
    let demos = synthetic_demonstrations(&arm, &gesture, a.count, a.seed, &settings, |_| {})
        .map_err(|e| format!("recording the demonstrations: {e}"))?;
    let methods = a.method.singles();
    let executor = ArmExecutor {
        arm: &arm,
        transition: spec.transition,
    };
    // LElbowRoll on either robot
    let swing_joint = executor
        .swing_joint()
        .map(|(j, _)| j)
        .ok_or("the robot has no swing joint")?;
    // the evaluator, once: the in-sample split, or every held-out fold
    let folds = match a.evaluation {
        Evaluation::InSample => {
            let base = FoldInput {
                config: Some(config),
                ..FoldInput::new(&[], &[])
            };
            let diag = diagonal(&demos);
            vec![fold(
                methods,
                &base,
                &demos,
                Split::InSampleAll,
                diag,
                &executor,
            )]
        }
        Evaluation::LeaveOneOut => folds(
            &arm,
            &demos,
            methods,
            Some(config),
            Training::Trained,
            spec.transition,
        )
        .map_err(|e| e.to_string())?,
    };
    Ok(methods
        .iter()
        .map(|&method| {
            let ran: Vec<&FoldScores> = folds.iter().filter_map(|f| f.scores(method)).collect();
            let failed: Vec<String> = folds
                .iter()
                .filter_map(|f| f.error(method).map(str::to_string))
                .collect();
            let in_sample = (a.evaluation == Evaluation::InSample).then_some(&demos[..]);
            let r = if method == Method::GmmGmr && in_sample.is_none() {
                match ran.is_empty() {
                    true => Err(format!("GMM/GMR ran on no fold: {}", failed.join("; "))),
                    false => scored(method, &ran, failed, None, swing_joint),
                }
            } else if !failed.is_empty() {
                Err(failed.join("; "))
            } else {
                scored(method, &ran, failed, in_sample, swing_joint)
            };
            r.unwrap_or_else(|e| MethodRecord {
                method,
                metrics: BTreeMap::new(),
                timing: BTreeMap::new(),
                error: Some(e),
                detail: serde_json::Value::Null,
            })
        })
        .collect())
}

/// Insert the finite values of `pairs` (JSON has no NaN).
fn finite(pairs: impl IntoIterator<Item = (&'static str, Option<f64>)>) -> BTreeMap<String, f64> {
    pairs
        .into_iter()
        .filter_map(|(k, v)| v.filter(|v| v.is_finite()).map(|v| (k.to_string(), v)))
        .collect()
}

fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) if b != 0.0 => Some(a / b),
        _ => None,
    }
}

fn mean(v: impl Iterator<Item = f64>) -> Option<f64> {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    (n > 0).then(|| s / n as f64)
}

/// The record of `method` in a run: means over `folds` (those that ran; the in-sample split is
/// one fold scored against every demonstration of `in_sample`, whose swings are counted on
/// column `swing_joint`); `failed` lists the folds that did not.
fn scored(
    method: Method,
    folds: &[&FoldScores],
    failed: Vec<String>,
    in_sample: Option<&[Demonstration]>,
    swing_joint: usize,
) -> Result<MethodRecord, String> {
    let s = HeldOutSummary::of(folds).ok_or_else(|| "no folds".to_string())?;
    let demo_swings = match in_sample {
        Some(demos) => {
            let swings = |d: &Demonstration| {
                column_swings(&d.rows, swing_joint, SWING_MIN_AMPLITUDE_RAD).map(|s| s as f64)
            };
            let all = demos.iter().map(swings).collect::<Result<Vec<_>, _>>();
            mean(all.map_err(|e| e.to_string())?.into_iter())
        }
        None => Some(s.demo_swings),
    };
    let metrics = finite([
        (JOINT_DTW.key, Some(s.joint_dtw_rad_per_step)),
        (WRIST_DTW.key, s.wrist_dtw_mm),
        (APEX_ERROR.key, Some(s.apex_error_rad)),
        (FINAL_ERROR.key, Some(s.final_error_rad)),
        (DURATION_RATIO.key, Some(s.duration_ratio)),
        (VELOCITY_REVERSALS.key, Some(s.velocity_reversals)),
        (DEMO_VELOCITY_REVERSALS.key, Some(s.demo_velocity_reversals)),
        (
            JERK_RATIO.key,
            ratio(s.normalized_jerk, s.demo_normalized_jerk),
        ),
        (SWINGS.key, Some(s.swings)),
        (DEMO_SWINGS.key, demo_swings),
        ("folds", in_sample.is_none().then_some(s.folds as f64)),
    ]);
    let timing = finite([
        ("train_s", mean(folds.iter().map(|f| f.train_s))),
        ("reproduce_s", mean(folds.iter().map(|f| f.reproduce_s))),
    ]);
    let detail = match (in_sample, folds) {
        (Some(_), [one]) => serde_json::to_value(&one.fidelity).map_err(|e| e.to_string())?,
        _ => serde_json::json!({ "folds": folds, "failed_folds": failed }),
    };
    Ok(MethodRecord {
        method,
        metrics,
        timing,
        error: None,
        detail,
    })
}
