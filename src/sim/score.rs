//! Scoring on the arm: a reproduction's fidelity against demonstrations with wrist paths from
//! the arm's kinematics (see docs/METRICS.md for every definition).

use crate::demos::Demonstration;
use crate::metrics::{fidelity_named, FidelityReport, MetricsParams, Trajectory};
use crate::robot::{Robot, RANGE_TOLERANCE_RAD};

use super::{NaoArm, SimError};

/// Name of the site at the RWristYaw joint origin (the upper body's right wrist).
pub const RIGHT_WRIST_SITE: &str = "r_wrist";

/// The left arm's column whose large swings are counted ([`Robot::swing_joint`]).
///
/// [`Robot::swing_joint`]: crate::robot::Robot::swing_joint
pub const SWING_JOINT: usize = crate::robot::Robot::LeftArm.swing_joint().0;

/// Peak joint speed of GMM/GMR's lead-in from the initial posture to its first point on the
/// arm, rad/s.
pub const LEAD_IN_PEAK_SPEED: f64 = 1.0;

/// The `l_wrist` position (m, torso frame) at each posture, from the simulated arm's kinematics.
/// Postures are clamped into the joint ranges first: encoders (and their simulated noise) can
/// read a hair beyond a limit the joint itself cannot pass; NaN is still an error.
pub fn wrist_path<const N: usize>(
    arm: &NaoArm<N>,
    postures: &[Vec<f64>],
) -> Result<Vec<[f64; 3]>, SimError> {
    let mut sim = arm.sim()?;
    postures
        .iter()
        .map(|q| {
            sim.set_posture_clamped(q)?;
            Ok(sim.wrist_position())
        })
        .collect()
}

/// The position (m, torso frame) of the model's site `site` at each posture, clamped into the
/// joint ranges as in [`wrist_path`]; a model without that site is [`SimError::Missing`].
pub fn site_path<const N: usize>(
    arm: &NaoArm<N>,
    site: &str,
    postures: &[Vec<f64>],
) -> Result<Vec<[f64; 3]>, SimError> {
    let id = arm.model().site_id(site).ok_or_else(|| SimError::Missing {
        kind: "site",
        name: site.to_string(),
    })?;
    let mut sim = arm.sim()?;
    postures
        .iter()
        .map(|q| {
            sim.set_posture_clamped(q)?;
            Ok(sim.data().site_xpos(id))
        })
        .collect()
}

/// The `l_wrist` path of every demonstration (see [`wrist_path`]).
pub fn demo_wrist_paths<const N: usize>(
    arm: &NaoArm<N>,
    demos: &[Demonstration],
) -> Result<Vec<Vec<[f64; 3]>>, SimError> {
    demos.iter().map(|d| wrist_path(arm, &d.rows)).collect()
}

/// Whether `columns` are the joints of `arm`'s robot (then its kinematics give wrist paths).
fn of_arm<const N: usize>(arm: &NaoArm<N>, columns: &[String]) -> bool {
    Robot::of_columns(columns) == Some(arm.robot())
}

/// A metrics trajectory from joint rows, with the wrist path when the columns are the arm's
/// joints and an arm is given.
pub fn trajectory<const N: usize>(
    arm: Option<&NaoArm<N>>,
    columns: &[String],
    rows: &[Vec<f64>],
) -> Result<Trajectory, SimError> {
    let wrist = match arm {
        Some(arm) if of_arm(arm, columns) => Some(wrist_path(arm, rows)?),
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
    check_reachable_of(Robot::LeftArm, rows, which)
}

/// [`check_reachable`] against `robot`'s joint ranges.
pub fn check_reachable_of(robot: Robot, rows: &[Vec<f64>], which: &str) -> Result<(), SimError> {
    for (i, r) in rows.iter().enumerate() {
        for (v, spec) in r.iter().zip(robot.joints()) {
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
/// demonstrations' rate) against each demonstration. On the upper body the wrist path is the
/// left wrist's (`l_wrist`) and the right wrist's (`r_wrist`) is scored beside it
/// ([`FidelityReport::right_wrist_dtw_mm`]).
pub fn evaluate<const N: usize>(
    arm: Option<&NaoArm<N>>,
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
    let arm = arm.filter(|a| of_arm(a, &first.columns));
    if let Some(arm) = arm {
        check_reachable_of(arm.robot(), rows, "reproduction")?;
        for d in demos {
            check_reachable_of(arm.robot(), &d.rows, &d.source)?;
        }
    }
    let demo_trajs = demos
        .iter()
        .map(|d| trajectory(arm, &d.columns, &d.rows))
        .collect::<Result<Vec<_>, _>>()?;
    let rep = trajectory(arm, &first.columns, rows)?;
    let names: Vec<String> = demos.iter().map(|d| d.source.clone()).collect();
    let mut report = fidelity_named(&demo_trajs, &names, &rep, params)?;
    if let Some(arm) = arm.filter(|a| a.robot() == Robot::UpperBody) {
        // the same measure on the right wrist's path: only its wrist figure is kept
        let right = |t: Trajectory, rows: &[Vec<f64>]| -> Result<Trajectory, SimError> {
            let wrist = Some(site_path(arm, RIGHT_WRIST_SITE, rows)?);
            Ok(Trajectory { wrist, ..t })
        };
        let demo_right = demo_trajs
            .into_iter()
            .zip(demos)
            .map(|(t, d)| right(t, &d.rows))
            .collect::<Result<Vec<_>, _>>()?;
        let rep_right = right(rep, rows)?;
        let r = fidelity_named(&demo_right, &names, &rep_right, params)?;
        report.right_wrist_dtw_mm = r.wrist_dtw_mm;
    }
    Ok(report)
}
