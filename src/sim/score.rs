//! Scoring on the arm: a reproduction's fidelity against demonstrations with wrist paths from
//! the arm's kinematics (see docs/METRICS.md for every definition).

use crate::demos::Demonstration;
use crate::metrics::{fidelity_named, FidelityReport, MetricsParams, Trajectory};
use crate::robot::{are_arm_joints, RANGE_TOLERANCE_RAD};

use super::{NaoArm, SimError, JOINT_SPECS};

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
