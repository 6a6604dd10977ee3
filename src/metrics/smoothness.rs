//! Smoothness and key-pose helpers of the fidelity metrics.

use serde::Serialize;

use crate::dtw::euclidean;

/// Smoothness of one trajectory.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Smoothness {
    /// Normalised jerk of the active (trimmed) part, dimensionless; `None` when it has
    /// fewer than 4 samples or no path length (it does not move).
    pub normalized_jerk: Option<f64>,
    /// Velocity sign reversals per joint over the whole trajectory (deadband applied).
    pub reversals: Vec<usize>,
    /// Sum of `reversals`.
    pub total_reversals: usize,
}

/// Normalised jerk of evenly sampled joint positions (period `dt` seconds):
/// `NJ = sqrt( T⁵ / (2 L²) · Σ_k ‖j_k‖² dt )`, with `j_k = (q_{k+3} − 3q_{k+2} + 3q_{k+1} −
/// q_k) / dt³` the third finite difference, `T = (n−1) dt` the duration and
/// `L = Σ_k ‖q_{k+1} − q_k‖` the joint-space path length. Dimensionless: a minimum-jerk
/// point-to-point motion scores `√360 ≈ 18.97` whatever its amplitude and duration; noise,
/// oscillation and sharp edges raise it. `None` with fewer than 4 samples or `L = 0`.
pub fn normalized_jerk<R: AsRef<[f64]>>(rows: &[R], dt: f64) -> Option<f64> {
    let n = rows.len();
    if n < 4 {
        return None;
    }
    let length: f64 = rows
        .windows(2)
        .map(|w| euclidean(w[1].as_ref(), w[0].as_ref()))
        .sum();
    if length <= 0.0 {
        return None;
    }
    let dt3 = dt * dt * dt;
    let sum_sq: f64 = rows
        .windows(4)
        .map(|w| {
            let (a, b, c, d) = (w[0].as_ref(), w[1].as_ref(), w[2].as_ref(), w[3].as_ref());
            (0..a.len())
                .map(|i| {
                    let j = (d[i] - 3.0 * c[i] + 3.0 * b[i] - a[i]) / dt3;
                    j * j
                })
                .sum::<f64>()
        })
        .sum();
    let t = (n - 1) as f64 * dt;
    Some((t.powi(5) / (2.0 * length * length) * sum_sq * dt).sqrt())
}

/// Velocity sign reversals per joint: with `v_k = (q_{k+1} − q_k) / dt`, the samples with
/// `|v_k| > deadband` (rad/s) keep their sign, the rest are ignored, and every change of
/// sign between consecutive kept samples counts one reversal.
pub fn velocity_reversals<R: AsRef<[f64]>>(rows: &[R], dt: f64, deadband: f64) -> Vec<usize> {
    let width = rows.first().map_or(0, |r| r.as_ref().len());
    (0..width)
        .map(|i| {
            let mut last: Option<bool> = None;
            let mut count = 0;
            for w in rows.windows(2) {
                let v = (w[1].as_ref()[i] - w[0].as_ref()[i]) / dt;
                if v.abs() > deadband {
                    let positive = v > 0.0;
                    if last.is_some_and(|l| l != positive) {
                        count += 1;
                    }
                    last = Some(positive);
                }
            }
            count
        })
        .collect()
}

/// Smoothness of a trajectory: normalised jerk of `rows[active]`, reversals over all rows.
pub fn smoothness<R: AsRef<[f64]>>(
    rows: &[R],
    active: std::ops::Range<usize>,
    dt: f64,
    deadband: f64,
) -> Smoothness {
    let reversals = velocity_reversals(rows, dt, deadband);
    Smoothness {
        normalized_jerk: normalized_jerk(&rows[active], dt),
        total_reversals: reversals.iter().sum(),
        reversals,
    }
}

/// The key pose of a (trimmed) demonstration: the index of the sample farthest, in
/// joint-space Euclidean distance, from its first sample (ties to the earliest). `None`
/// for an empty sequence.
pub fn key_pose<R: AsRef<[f64]>>(rows: &[R]) -> Option<usize> {
    let first = rows.first()?.as_ref();
    let mut best = (0, 0.0);
    for (k, r) in rows.iter().enumerate() {
        let d = euclidean(r.as_ref(), first);
        if d > best.1 {
            best = (k, d);
        }
    }
    Some(best.0)
}
