//! Scoring on the arm: a reproduction's fidelity against demonstrations with wrist paths from
//! the arm's kinematics (see docs/METRICS.md for every definition), and the arm as an
//! executor of the evaluator ([`ArmExecutor`]): a method's postures clamped into the joint
//! ranges, shaped by the transition (the hierarchy's and the nearest sequence's; GMM/GMR's,
//! ProMP's and the replay's go posture to posture), executed by the position controller and
//! recorded at the demonstration's rate (40 Hz), then scored with the wrist paths.

use crate::demos::{sample_period, Demonstration};
use crate::eval::{Executed, Executor, Method};
use crate::metrics::{fidelity_named, FidelityReport, MetricsParams, Trajectory};
use crate::robot::{are_arm_joints, RANGE_TOLERANCE_RAD};

use super::execute::{clamp_to_ranges, execute_postures, Transition};
use super::{NaoArm, Recording, SimError, JOINT_NAMES, JOINT_SPECS};

/// The joint whose large swings are counted (column 3, `LElbowRoll`: the wave's joint).
pub const SWING_JOINT: usize = 3;

/// Peak joint speed of GMM/GMR's lead-in from the initial posture to its first point on the
/// arm, rad/s.
pub const LEAD_IN_PEAK_SPEED: f64 = 1.0;

/// The `l_wrist` position (m, torso frame) at each posture, from the simulated arm's kinematics.
/// Postures are clamped into the joint ranges first: encoders (and their simulated noise) can
/// read a hair beyond a limit the joint itself cannot pass; NaN is still an error.
pub fn wrist_path(arm: &NaoArm, postures: &[Vec<f64>]) -> Result<Vec<[f64; 3]>, SimError> {
    let mut sim = arm.sim()?;
    postures
        .iter()
        .map(|q| {
            sim.set_posture_clamped(q)?;
            Ok(sim.wrist_position())
        })
        .collect()
}

/// The `l_wrist` path of every demonstration (see [`wrist_path`]).
pub fn demo_wrist_paths(
    arm: &NaoArm,
    demos: &[Demonstration],
) -> Result<Vec<Vec<[f64; 3]>>, SimError> {
    demos.iter().map(|d| wrist_path(arm, &d.rows)).collect()
}

/// A metrics trajectory from joint rows, with the wrist path when the columns are the arm's
/// joints and an arm is given.
pub fn trajectory(
    arm: Option<&NaoArm>,
    columns: &[String],
    rows: &[Vec<f64>],
) -> Result<Trajectory, SimError> {
    let wrist = match arm {
        Some(arm) if are_arm_joints(columns) => Some(wrist_path(arm, rows)?),
        _ => None,
    };
    Ok(Trajectory {
        joints: rows.to_vec(),
        wrist,
    })
}

/// Every posture of `rows` within the arm's joint ranges give or take
/// [`RANGE_TOLERANCE_RAD`]: a posture farther out is none the arm can take, and scoring it
/// (with kinematics that clamp it) would hide that.
pub fn check_reachable(rows: &[Vec<f64>], which: &str) -> Result<(), SimError> {
    for (i, r) in rows.iter().enumerate() {
        for (v, spec) in r.iter().zip(JOINT_SPECS.iter()) {
            let (lo, hi) = spec.range;
            if !(v.is_finite() && *v >= lo - RANGE_TOLERANCE_RAD && *v <= hi + RANGE_TOLERANCE_RAD)
            {
                return Err(SimError::Invalid(format!(
                    "{which}, sample {i}: {} = {v} is outside its range [{lo}, {hi}] by more \
                     than {RANGE_TOLERANCE_RAD} rad: not a posture the arm can take",
                    spec.name
                )));
            }
        }
    }
    Ok(())
}

/// Score the reproduction `rows` (columns as in the demonstrations, sampled at the
/// demonstrations' rate) against each demonstration.
pub fn evaluate(
    arm: Option<&NaoArm>,
    demos: &[Demonstration],
    rows: &[Vec<f64>],
    params: &MetricsParams,
) -> Result<FidelityReport, SimError> {
    let Some(first) = demos.first() else {
        return Err(SimError::Invalid(
            "no demonstrations to evaluate against".into(),
        ));
    };
    if rows.len() < 2 {
        return Err(SimError::Invalid(format!(
            "the reproduction has {} sample(s); at least 2 are needed to compare it with \
             demonstrations",
            rows.len()
        )));
    }
    if arm.is_some() && are_arm_joints(&first.columns) {
        check_reachable(rows, "reproduction")?;
        for d in demos {
            check_reachable(&d.rows, &d.source)?;
        }
    }
    let demo_trajs = demos
        .iter()
        .map(|d| trajectory(arm, &d.columns, &d.rows))
        .collect::<Result<Vec<_>, _>>()?;
    let rep = trajectory(arm, &first.columns, rows)?;
    let names: Vec<String> = demos.iter().map(|d| d.source.clone()).collect();
    Ok(fidelity_named(&demo_trajs, &names, &rep, params)?)
}

/// Clamp `postures` into the joint ranges, shape them with `transition`, execute them on
/// `arm` at the rate of `metrics.sample_period` and score the executed trajectory against
/// `test`: what [`ArmExecutor`] does, for callers that produce postures themselves.
pub fn execute_and_score(
    arm: &NaoArm,
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
    let (postures, clamped_values) = clamp_to_ranges(postures)?;
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

/// The simulated arm as the evaluator's executor, with the transition of the hierarchy's
/// postures.
#[derive(Clone, Copy)]
pub struct ArmExecutor<'a> {
    /// The arm.
    pub arm: &'a NaoArm,
    /// How the hierarchy's and the nearest sequence's postures become servo targets.
    pub transition: Transition,
}

impl Executor for ArmExecutor<'_> {
    type Trace = Recording;

    /// Refuses targets whose columns are not the arm's joints.
    fn execute(
        &self,
        method: Method,
        postures: &[Vec<f64>],
        targets: &[Demonstration],
    ) -> Result<Executed<Recording>, String> {
        if let Some(d) = targets.iter().find(|d| !are_arm_joints(&d.columns)) {
            return Err(format!(
                "the demonstrations' columns are {:?}; executing on the simulated arm needs \
                 exactly {:?}",
                d.columns, JOINT_NAMES
            ));
        }
        let metrics = MetricsParams {
            sample_period: targets.first().map_or(f64::NAN, sample_period),
            ..MetricsParams::default()
        };
        let transition = match method {
            Method::GmmGmr | Method::ProMP | Method::Dmp | Method::Replay => Transition::Linear,
            _ => self.transition,
        };
        execute_and_score(self.arm, postures, transition, targets, &metrics)
            .map_err(|e| crate::app::error_line(&e))
    }

    /// The encoders' record.
    fn motion<'a>(&self, executed: &'a Executed<Recording>) -> &'a [Vec<f64>] {
        &executed.trace.qpos
    }

    /// [`LEAD_IN_PEAK_SPEED`]: the arm's, whatever the demonstrations.
    fn gmr_lead_in_speed(&self, _train: &[Demonstration], _period: f64) -> f64 {
        LEAD_IN_PEAK_SPEED
    }

    /// [`SWING_JOINT`].
    fn swing_joint(&self) -> Option<(usize, &'static str)> {
        Some((SWING_JOINT, JOINT_NAMES[SWING_JOINT]))
    }
}

#[cfg(test)]
mod tests;
