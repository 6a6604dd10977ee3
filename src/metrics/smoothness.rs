//! Smoothness and key-pose helpers of the fidelity metrics.

use serde::Serialize;

use super::errors::MetricsError;
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

/// Samples within this fraction of the gesture's amplitude (the key pose's distance from the
/// first sample) of the key pose count as at the apex ([`apex_dwell`]): wider than the
/// demonstrator's wobble in a hold, narrower than the strokes into and out of it.
pub const APEX_RADIUS: f64 = 0.1;

/// How long a trajectory stays at its apex, in samples: the run of consecutive samples
/// around its key pose ([`key_pose`]) that lie within [`APEX_RADIUS`] of the amplitude of
/// it. For a gesture that holds at its apex, its hold with the last stretch of the stroke in
/// and the first out; `None` for an empty trajectory.
pub fn apex_dwell<R: AsRef<[f64]>>(rows: &[R]) -> Option<usize> {
    let key = key_pose(rows)?;
    let apex = rows[key].as_ref();
    let radius = APEX_RADIUS * euclidean(apex, rows[0].as_ref());
    let near = |k: &usize| euclidean(rows[*k].as_ref(), apex) <= radius;
    let before = (0..key).rev().take_while(near).count();
    let after = (key + 1..rows.len()).take_while(near).count();
    Some(before + 1 + after)
}

/// Large swings of one signal (a joint's trajectory): the number of direction changes whose
/// excursions on both sides, between consecutive turning points, exceed `min_amplitude`
/// (hysteresis, as a zig-zag filter). The direction is set once the signal has moved more
/// than `min_amplitude` from its lowest (highest) value so far; from then on the running
/// extreme in that direction is tracked, and a move back from it by more than
/// `min_amplitude` confirms a turning point there and counts one swing. Wiggles, noise and
/// hesitations smaller than `min_amplitude` never count, however many sign changes of the
/// velocity they make; a sine of amplitude `a > min_amplitude / 2` over `k` whole periods,
/// starting and ending at its mean, counts `2k`. `min_amplitude` must be finite and > 0;
/// non-finite samples are skipped.
pub fn large_swings(values: &[f64], min_amplitude: f64) -> Result<usize, MetricsError> {
    if !(min_amplitude.is_finite() && min_amplitude > 0.0) {
        return Err(MetricsError::InvalidParam {
            name: "min_amplitude",
            value: min_amplitude.to_string(),
            reason: "a finite amplitude > 0",
        });
    }
    let mut finite = values.iter().copied().filter(|v| v.is_finite());
    let Some(first) = finite.next() else {
        return Ok(0);
    };
    // None: no direction yet (lowest and highest so far); Some(up): the running extreme.
    let (mut lo, mut hi) = (first, first);
    let mut rising: Option<bool> = None;
    let mut extreme = first;
    let mut count = 0;
    for v in finite {
        match rising {
            None => {
                lo = lo.min(v);
                hi = hi.max(v);
                if v - lo > min_amplitude {
                    rising = Some(true);
                    extreme = v;
                } else if hi - v > min_amplitude {
                    rising = Some(false);
                    extreme = v;
                }
            }
            Some(up) => {
                if (up && v > extreme) || (!up && v < extreme) {
                    extreme = v;
                } else if (extreme - v).abs() > min_amplitude {
                    // a move back from the running extreme: a turning point there
                    count += 1;
                    rising = Some(!up);
                    extreme = v;
                }
            }
        }
    }
    Ok(count)
}

/// [`large_swings`] of column `column` of `rows`; a column outside the rows is an error
/// naming it.
pub fn column_swings<R: AsRef<[f64]>>(
    rows: &[R],
    column: usize,
    min_amplitude: f64,
) -> Result<usize, MetricsError> {
    let mut values = Vec::with_capacity(rows.len());
    for (sample, r) in rows.iter().enumerate() {
        let r = r.as_ref();
        match r.get(column) {
            Some(&v) => values.push(v),
            None => {
                return Err(MetricsError::Width {
                    which: format!("column {column} for large swings"),
                    sample,
                    expected: column + 1,
                    found: r.len(),
                })
            }
        }
    }
    large_swings(&values, min_amplitude)
}

/// How smooth the training demonstrations are (normalised units, per sample).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct DemoSmoothness {
    /// Their median normalised jerk.
    pub(crate) jerk: f64,
    /// Their largest first step (the distance from the first posture to the second): how
    /// fast they leave their start.
    pub(crate) start_step: f64,
    /// Per variable, their largest step from one sample to the next: how fast they move.
    pub(crate) peak_step: Vec<f64>,
}

impl DemoSmoothness {
    /// Of the sequences `demos`, their first `s` variables; `None` where no normalised jerk
    /// is defined (no demonstration of 5 samples that moves).
    pub(crate) fn of(demos: &[Vec<Vec<f64>>], s: usize) -> Option<DemoSmoothness> {
        let jerk = crate::stats::median(demos.iter().filter_map(|d| {
            let state: Vec<&[f64]> = d.iter().map(|r| &r[..s]).collect();
            normalized_jerk(&state, 1.0)
        }))?;
        let start_step = demos
            .iter()
            .filter(|d| d.len() >= 2)
            .map(|d| euclidean(&d[1][..s], &d[0][..s]))
            .fold(0.0, f64::max);
        let peak_step = (0..s)
            .map(|j| {
                demos
                    .iter()
                    .flat_map(|d| d.windows(2).map(move |w| (w[1][j] - w[0][j]).abs()))
                    .fold(0.0, f64::max)
            })
            .collect();
        Some(DemoSmoothness {
            jerk,
            start_step,
            peak_step,
        })
    }
}

#[cfg(test)]
mod tests;
