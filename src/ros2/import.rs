//! Demonstrations from a ROS 2 bag: the `sensor_msgs/msg/JointState` messages of one topic,
//! the chosen joints picked by name (the messages may list more, in any order), `time`
//! from the header stamps (from 0 at the first message), one demonstration per bag or one
//! per stretch of motion between pauses.

use std::path::Path;

use super::{read_joint_states, StampedJoints};
use crate::demos::Demonstration;
use crate::trajectory::ExportError;

/// Below this speed (rad/s, every joint) a sample is idle for `--split-idle`.
pub const IDLE_SPEED: f64 = 0.05;

/// Read `topic` of the bag at `path` into demonstrations of the `joints` (the arm's six when
/// empty): one, or with `split_idle` one per stretch of motion separated by pauses of at
/// least that many seconds (every joint slower than [`IDLE_SPEED`]). Refused with the file
/// named: a joint absent from a message (the names it has listed), stamps that do not
/// strictly increase, and what [`read_joint_states`] refuses.
pub fn import_bag(
    path: &Path,
    topic: &str,
    joints: &[String],
    split_idle: Option<f64>,
) -> Result<Vec<Demonstration>, ExportError> {
    let p = path.display().to_string();
    let bad = |reason: String| ExportError::Bag {
        path: p.clone(),
        reason,
    };
    if let Some(s) = split_idle {
        if !(s.is_finite() && s > 0.0) {
            return Err(ExportError::Option {
                option: "--split-idle",
                value: format!("{s}"),
                allowed: "a pause length in seconds, finite and > 0",
            });
        }
    }
    let joints: Vec<String> = if joints.is_empty() {
        // the arm's six joints
        crate::robot::Robot::LeftArm
            .joint_names()
            .iter()
            .map(|j| j.to_string())
            .collect()
    } else {
        joints.to_vec()
    };
    let msgs = read_joint_states(path, topic)?;
    let mut times = Vec::with_capacity(msgs.len());
    let mut rows = Vec::with_capacity(msgs.len());
    for (i, m) in msgs.iter().enumerate() {
        rows.push(pick(m, &joints).map_err(|missing| {
            bad(format!(
                "message {i} on {topic} has no joint `{missing}` (it has: {}); choose joints with --joints",
                m.names.join(", ")
            ))
        })?);
        if let Some(&prev) = times.last() {
            if m.stamp_ns <= prev {
                return Err(bad(format!(
                    "message {i} on {topic}: stamp {} s is not after the previous message's {} s; the stamps must strictly increase",
                    m.stamp_ns as f64 * 1e-9,
                    prev as f64 * 1e-9
                )));
            }
        }
        times.push(m.stamp_ns);
    }
    // from the first stamp, in whole nanoseconds before the conversion to seconds
    let t0 = times[0];
    let times: Vec<f64> = times.iter().map(|t| (t - t0) as f64 / 1e9).collect();
    let segments = match split_idle {
        None => vec![(0, times.len())],
        Some(s) => moving_segments(&times, &rows, s),
    };
    if segments.is_empty() {
        return Err(bad(format!(
            "no motion on {topic}: every joint stays below {IDLE_SPEED} rad/s throughout"
        )));
    }
    Ok(segments
        .iter()
        .map(|&(a, b)| {
            let s0 = times[a];
            Demonstration {
                source: format!("{p} [{:.3} s, {:.3} s]", times[a], times[b - 1]),
                columns: joints.clone(),
                time: Some(times[a..b].iter().map(|t| t - s0).collect()),
                rows: rows[a..b].to_vec(),
            }
        })
        .collect())
}

/// [`import_bag`], written into `out` (created if missing): `<bag name>.csv`, or with
/// `split_idle` `<bag name>_01.csv`, `<bag name>_02.csv`, ... (atomically). Returns the
/// files and their demonstrations.
pub fn import_to_dir(
    path: &Path,
    topic: &str,
    joints: &[String],
    split_idle: Option<f64>,
    out: &Path,
) -> Result<Vec<(std::path::PathBuf, Demonstration)>, ExportError> {
    let demos = import_bag(path, topic, joints, split_idle)?;
    std::fs::create_dir_all(out).map_err(|source| ExportError::Write {
        path: out.display().to_string(),
        source,
    })?;
    let stem = path
        .file_stem()
        .map_or_else(|| "bag".to_string(), |s| s.to_string_lossy().to_string());
    let mut files = Vec::new();
    for (i, d) in demos.into_iter().enumerate() {
        let name = match split_idle {
            None => format!("{stem}.csv"),
            Some(_) => format!("{stem}_{:02}.csv", i + 1),
        };
        let f = out.join(name);
        crate::demos::write_csv(&f, &d)?;
        files.push((f, d));
    }
    Ok(files)
}

fn pick(m: &StampedJoints, joints: &[String]) -> Result<Vec<f64>, String> {
    joints
        .iter()
        .map(|j| {
            m.names
                .iter()
                .position(|n| n == j)
                .map(|k| m.positions[k])
                .ok_or_else(|| j.clone())
        })
        .collect()
}

/// `[start, end)` sample ranges of motion: runs of idle intervals lasting at least `pause`
/// s cut the recording; a range keeps the idle sample on each side of its motion, and
/// ranges of fewer than two samples are dropped.
fn moving_segments(times: &[f64], rows: &[Vec<f64>], pause: f64) -> Vec<(usize, usize)> {
    let n = times.len();
    // idle[i]: the interval from sample i to i + 1 is idle
    let idle: Vec<bool> = (0..n.saturating_sub(1))
        .map(|i| {
            let dt = times[i + 1] - times[i];
            rows[i]
                .iter()
                .zip(&rows[i + 1])
                .all(|(a, b)| (b - a).abs() / dt < IDLE_SPEED)
        })
        .collect();
    let mut cuts: Vec<(usize, usize)> = Vec::new(); // idle runs [a, b] in samples
    let mut i = 0;
    while i < idle.len() {
        if idle[i] {
            let a = i;
            while i < idle.len() && idle[i] {
                i += 1;
            }
            let long = times[i] - times[a] >= pause;
            let at_edge = a == 0 || i == idle.len();
            if long || at_edge {
                cuts.push((a, i));
            }
        } else {
            i += 1;
        }
    }
    let mut out = Vec::new();
    let mut start = 0;
    for (a, b) in cuts {
        if a + 1 > start + 1 {
            out.push((start, a + 1));
        }
        start = b;
    }
    if start + 1 < n {
        out.push((start, n));
    }
    out.retain(|&(a, b)| b >= a + 2);
    out
}

#[cfg(test)]
mod tests;
