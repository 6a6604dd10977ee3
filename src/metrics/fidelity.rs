//! The fidelity report of one reproduction against a set of demonstrations.

use std::ops::Range;

use serde::Serialize;

use super::errors::MetricsError;
use super::smoothness::{apex_dwell, key_pose, smoothness, Smoothness};
use crate::dtw::{dtw_distance, euclidean, Band};
use crate::gmr::{active_range, IdleTrim};

/// One recorded or reproduced motion: joint positions (rad) at a fixed sample period, and
/// optionally the wrist position (m, world frame) at each sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// One row of joint angles per sample.
    pub joints: Vec<Vec<f64>>,
    /// Wrist position per sample, metres, when the simulator recorded it.
    pub wrist: Option<Vec<[f64; 3]>>,
}

impl From<&crate::demos::Demonstration> for Trajectory {
    /// The demonstration's rows as joint positions, without wrist positions (its `time`
    /// column is not used: metrics assume the fixed `MetricsParams::sample_period`).
    fn from(d: &crate::demos::Demonstration) -> Self {
        Trajectory::from_joints(d.rows.clone())
    }
}

impl Trajectory {
    /// A trajectory without wrist positions.
    pub fn from_joints(joints: Vec<Vec<f64>>) -> Self {
        Trajectory {
            joints,
            wrist: None,
        }
    }
}

/// Settings of the metrics. Defaults: 0.025 s sample period (40 Hz), the baseline's
/// [`IdleTrim::default`] (so "idle" means the same everywhere), a 0.25 rad/s deadband for
/// velocity reversals, no DTW band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MetricsParams {
    /// Seconds between samples.
    pub sample_period: f64,
    /// Idle trimming of start and end.
    pub trim: IdleTrim,
    /// Joint speeds at or below this (rad/s) do not count towards velocity reversals.
    pub reversal_deadband: f64,
    /// Sakoe-Chiba band of the DTW distances.
    #[serde(skip)]
    pub band: Band,
}

impl Default for MetricsParams {
    fn default() -> Self {
        MetricsParams {
            sample_period: 0.025,
            trim: IdleTrim::default(),
            reversal_deadband: 0.25,
            band: Band::None,
        }
    }
}

impl MetricsParams {
    /// Check the settings.
    pub fn check(&self) -> Result<(), MetricsError> {
        let bad = |name, value: &dyn ToString, reason| {
            let value = value.to_string();
            Err(MetricsError::InvalidParam {
                name,
                value,
                reason,
            })
        };
        let (period, deadband) = (self.sample_period, self.reversal_deadband);
        if !(period.is_finite() && period > 0.0) {
            return bad("sample_period", &period, "a finite time in seconds > 0");
        }
        if !(deadband.is_finite() && deadband >= 0.0) {
            return bad(
                "reversal_deadband",
                &deadband,
                "a finite speed in rad/s >= 0",
            );
        }
        if let Band::Fraction(f) = self.band {
            if !(0.0..=1.0).contains(&f) {
                return bad("band", &f, "a fraction within [0, 1]");
            }
        }
        match self.trim.check() {
            Ok(()) => Ok(()),
            Err((name, value, reason)) => bad(name, &value, reason),
        }
    }
}

/// Mean and worst of one metric over the demonstrations.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Stat {
    /// Arithmetic mean over the demonstrations.
    pub mean: f64,
    /// The worst value: the largest for errors and distances; for the duration ratio, the
    /// one farthest from 1 in ratio (largest `|ln r|`).
    pub worst: f64,
}

impl Stat {
    fn max_of(values: &[f64]) -> Stat {
        Stat {
            mean: values.iter().sum::<f64>() / values.len() as f64,
            worst: values.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        }
    }

    fn ratio_of(values: &[f64]) -> Stat {
        let worst = values
            .iter()
            .cloned()
            .max_by(|a, b| a.ln().abs().total_cmp(&b.ln().abs()))
            .unwrap_or(f64::NAN);
        Stat {
            mean: values.iter().sum::<f64>() / values.len() as f64,
            worst,
        }
    }
}

/// The reproduction scored against one demonstration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DemoScores {
    /// 0-based index of the demonstration.
    pub demo: usize,
    /// Per-step joint-space DTW distance between the trimmed trajectories, rad per step.
    pub joint_dtw_rad_per_step: f64,
    /// Per-step DTW distance between the trimmed wrist paths, millimetres per step (when
    /// both have wrist positions).
    pub wrist_dtw_mm: Option<f64>,
    /// Closest joint-space distance of the reproduction to the demonstration's key pose, rad.
    pub apex_error_rad: f64,
    /// Joint-space distance between the final postures, rad.
    pub final_error_rad: f64,
    /// Trimmed duration of the reproduction over that of the demonstration.
    pub duration_ratio: f64,
    /// Trimmed duration of the demonstration, seconds.
    pub demo_duration_s: f64,
    /// Kept sample range of the demonstration `[start, end)`.
    pub demo_active: [usize; 2],
}

/// Fidelity of one reproduction against a set of demonstrations (serialised into
/// `report.json`). Definitions in `docs/METRICS.md`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FidelityReport {
    /// Scores against each demonstration.
    pub per_demo: Vec<DemoScores>,
    /// Joint-space DTW, rad per step.
    pub joint_dtw_rad_per_step: Stat,
    /// Wrist-path DTW, mm per step, when every trajectory has wrist positions.
    pub wrist_dtw_mm: Option<Stat>,
    /// The right wrist's path DTW, mm per step, on a robot with two arms (the simulator's
    /// upper body, whose `wrist_dtw_mm` is then the left wrist's); none otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub right_wrist_dtw_mm: Option<Stat>,
    /// Apex (key-pose) error, rad.
    pub apex_error_rad: Stat,
    /// Final-posture error, rad.
    pub final_error_rad: Stat,
    /// Duration ratio (reproduction / demonstration, trimmed).
    pub duration_ratio: Stat,
    /// Trimmed duration of the reproduction, seconds (0 when it never moves).
    pub reproduction_duration_s: f64,
    /// Whether the reproduction ever moves faster than the idle threshold.
    pub reproduction_moves: bool,
    /// Smoothness of the reproduction.
    pub reproduction_smoothness: Smoothness,
    /// Smoothness of each demonstration, for comparison.
    pub demo_smoothness: Vec<Smoothness>,
    /// How long the trimmed reproduction stays at its apex, seconds
    /// ([`super::smoothness::apex_dwell`]; 0 when it never moves).
    pub reproduction_hold_s: f64,
    /// The same for each trimmed demonstration.
    pub demo_hold_s: Vec<f64>,
    /// The settings used.
    pub settings: MetricsParams,
}

/// The normalised jerk ([`super::normalized_jerk`]) of `rows` trimmed as a reproduction is
/// in [`fidelity`]: on its active range (`params.trim`, at `params.sample_period`), or on all
/// of it when it never moves.
pub fn trimmed_normalized_jerk<R: AsRef<[f64]>>(rows: &[R], params: &MetricsParams) -> Option<f64> {
    let dt = params.sample_period;
    let range = active_range(rows, None, dt, &params.trim).unwrap_or(0..rows.len());
    super::normalized_jerk(&rows[range], dt)
}

fn check_trajectory(t: &Trajectory, which: &str, width: usize) -> Result<(), MetricsError> {
    if t.joints.is_empty() || width == 0 {
        return Err(MetricsError::Empty {
            which: which.into(),
        });
    }
    for (sample, row) in t.joints.iter().enumerate() {
        if row.len() != width {
            return Err(MetricsError::Width {
                which: which.into(),
                sample,
                expected: width,
                found: row.len(),
            });
        }
        if let Some(&value) = row.iter().find(|v| !v.is_finite()) {
            return Err(MetricsError::NotFinite {
                which: which.into(),
                sample,
                value,
            });
        }
    }
    if let Some(w) = &t.wrist {
        if w.len() != t.joints.len() {
            return Err(MetricsError::WristLength {
                which: which.into(),
                wrist: w.len(),
                joints: t.joints.len(),
            });
        }
        for (sample, p) in w.iter().enumerate() {
            if let Some(&value) = p.iter().find(|v| !v.is_finite()) {
                return Err(MetricsError::NotFinite {
                    which: format!("{which} (wrist)"),
                    sample,
                    value,
                });
            }
        }
    }
    Ok(())
}

/// Score `reproduction` against each of `demos` (see `docs/METRICS.md`). Every trajectory
/// needs at least one sample, one joint width (the reproduction's), finite values and, if
/// it has wrist positions, one per sample. A demonstration that never moves is an error; a
/// reproduction that never moves is scored on all its samples with active duration 0.
pub fn fidelity(
    demos: &[Trajectory],
    reproduction: &Trajectory,
    params: &MetricsParams,
) -> Result<FidelityReport, MetricsError> {
    fidelity_named(demos, &[], reproduction, params)
}

/// The fidelity of `rows` against the demonstrations, named by their sources, in the data's
/// own variables: no wrist paths (those need the simulated arm's kinematics,
/// `sim::evaluate`).
pub fn fidelity_of_rows(
    demos: &[crate::demos::Demonstration],
    rows: &[Vec<f64>],
    params: &MetricsParams,
) -> Result<FidelityReport, MetricsError> {
    let trajs: Vec<Trajectory> = demos.iter().map(Trajectory::from).collect();
    let names: Vec<String> = demos.iter().map(|d| d.source.clone()).collect();
    fidelity_named(
        &trajs,
        &names,
        &Trajectory::from_joints(rows.to_vec()),
        params,
    )
}

/// [`fidelity`] with the demonstrations' names (their files) for the error messages; a
/// demonstration without one is `demonstration {i}`.
pub fn fidelity_named(
    demos: &[Trajectory],
    names: &[String],
    reproduction: &Trajectory,
    params: &MetricsParams,
) -> Result<FidelityReport, MetricsError> {
    params.check()?;
    if demos.is_empty() {
        return Err(MetricsError::NoDemonstrations);
    }
    let width = reproduction.joints.first().map_or(0, |r| r.len());
    check_trajectory(reproduction, "reproduction", width)?;
    let dt = params.sample_period;
    let names: Vec<String> = (0..demos.len())
        .map(|i| {
            names
                .get(i)
                .cloned()
                .unwrap_or_else(|| format!("demonstration {i}"))
        })
        .collect();
    let mut demo_ranges: Vec<Range<usize>> = Vec::with_capacity(demos.len());
    for (d, name) in demos.iter().zip(&names) {
        check_trajectory(d, name, width)?;
        let r = active_range(&d.joints, None, dt, &params.trim).ok_or_else(|| {
            MetricsError::NoMotion {
                which: name.clone(),
                threshold: params.trim.min_speed,
            }
        })?;
        demo_ranges.push(r);
    }
    let rep_active = active_range(&reproduction.joints, None, dt, &params.trim);
    let reproduction_moves = rep_active.is_some();
    let rep_range = rep_active.unwrap_or(0..reproduction.joints.len());
    let rep_duration = if reproduction_moves {
        (rep_range.len() - 1) as f64 * dt
    } else {
        0.0
    };
    let rep = &reproduction.joints[rep_range.clone()];
    let rep_last = &reproduction.joints[reproduction.joints.len() - 1];
    let all_wrist = reproduction.wrist.is_some() && demos.iter().all(|d| d.wrist.is_some());

    let mut per_demo = Vec::with_capacity(demos.len());
    for (i, (d, r)) in demos.iter().zip(&demo_ranges).enumerate() {
        let seg = &d.joints[r.clone()];
        let joint_dtw = dtw_distance(rep, seg, params.band)?.per_step();
        let wrist_dtw_mm = match (&reproduction.wrist, &d.wrist) {
            (Some(rw), Some(dw)) if all_wrist => Some(
                1000.0
                    * dtw_distance(&rw[rep_range.clone()], &dw[r.clone()], params.band)?.per_step(),
            ),
            _ => None,
        };
        let apex = &seg[key_pose(seg).unwrap_or(0)];
        let apex_error = reproduction
            .joints
            .iter()
            .map(|q| euclidean(q, apex))
            .fold(f64::INFINITY, f64::min);
        let final_error = euclidean(rep_last, &d.joints[d.joints.len() - 1]);
        let demo_duration = (r.len() - 1) as f64 * dt;
        per_demo.push(DemoScores {
            demo: i,
            joint_dtw_rad_per_step: joint_dtw,
            wrist_dtw_mm,
            apex_error_rad: apex_error,
            final_error_rad: final_error,
            duration_ratio: rep_duration / demo_duration,
            demo_duration_s: demo_duration,
            demo_active: [r.start, r.end],
        });
    }
    let collect = |f: &dyn Fn(&DemoScores) -> f64| per_demo.iter().map(f).collect::<Vec<f64>>();
    let wrist = if all_wrist {
        Some(Stat::max_of(&collect(&|s| {
            s.wrist_dtw_mm.unwrap_or(f64::NAN)
        })))
    } else {
        None
    };
    let deadband = params.reversal_deadband;
    // the time at the apex of the trimmed trajectory (docs/METRICS.md)
    let dwell = |rows: &[Vec<f64>]| apex_dwell(rows).map_or(0.0, |n| n as f64 * dt);
    Ok(FidelityReport {
        joint_dtw_rad_per_step: Stat::max_of(&collect(&|s| s.joint_dtw_rad_per_step)),
        wrist_dtw_mm: wrist,
        right_wrist_dtw_mm: None,
        apex_error_rad: Stat::max_of(&collect(&|s| s.apex_error_rad)),
        final_error_rad: Stat::max_of(&collect(&|s| s.final_error_rad)),
        duration_ratio: Stat::ratio_of(&collect(&|s| s.duration_ratio)),
        reproduction_duration_s: rep_duration,
        reproduction_moves,
        reproduction_smoothness: smoothness(&reproduction.joints, rep_range, dt, deadband),
        demo_smoothness: demos
            .iter()
            .zip(&demo_ranges)
            .map(|(d, r)| smoothness(&d.joints, r.clone(), dt, deadband))
            .collect(),
        reproduction_hold_s: if reproduction_moves { dwell(rep) } else { 0.0 },
        demo_hold_s: demos
            .iter()
            .zip(&demo_ranges)
            .map(|(d, r)| dwell(&d.joints[r.clone()]))
            .collect(),
        per_demo,
        settings: *params,
    })
}
