//! The two arms of the upper body against each other: whether both move in a gesture, and the
//! lag between them, judged against the demonstrations' own lags (docs/METRICS.md, "The two
//! arms' lag").
//!
//! Rows are upper-body postures in NAOqi order ([`crate::robot::UPPER_BODY_JOINTS`]): HeadYaw,
//! HeadPitch, the left arm's six joints (columns 2..8), the right arm's six (8..14).

use serde::Serialize;

/// The mirrored joint pairs of the upper body: (left column, right column, sign); the right
/// joint times the sign moves as the left one does in a mirrored motion (the rolls and yaws
/// change sign between the arms, the pitches and the hands do not).
pub const UPPER_BODY_MIRROR: [(usize, usize, f64); 6] = [
    (2, 8, 1.0),   // ShoulderPitch
    (3, 9, -1.0),  // ShoulderRoll
    (4, 10, -1.0), // ElbowYaw
    (5, 11, -1.0), // ElbowRoll
    (6, 12, -1.0), // WristYaw
    (7, 13, 1.0),  // Hand
];

/// Both arms move in a trajectory when each arm's largest joint excursion from its first
/// sample is at least this fraction of the other arm's ([`both_arms_move`]) ...
pub const BOTH_ARMS_RATIO: f64 = 0.5;

/// ... and at least this many radians: the still arms of a one-arm or head gesture wobble and
/// drift by up to 0.18 rad in the recorded demonstrations, a moving arm's joints by 1.2 rad
/// or more.
pub const BOTH_ARMS_MIN_RAD: f64 = 0.5;

/// A lag lies within the demonstrations' spread when it is within this many samples of their
/// range ([`LagSpread::contains`]): the lag is measured in whole samples.
pub const LAG_TOLERANCE_SAMPLES: i64 = 1;

/// The largest excursion of `columns` from the first row: `max_k max_j |q_k[j] − q_0[j]|`.
fn excursion(rows: &[Vec<f64>], columns: impl Iterator<Item = usize> + Clone) -> f64 {
    let Some(first) = rows.first() else {
        return 0.0;
    };
    rows.iter()
        .flat_map(|r| columns.clone().map(move |j| (r[j] - first[j]).abs()))
        .fold(0.0, f64::max)
}

/// Rows that are upper-body postures with finite values (at least 14 columns).
fn usable(rows: &[Vec<f64>]) -> bool {
    let width = 1 + UPPER_BODY_MIRROR.iter().map(|p| p.1).max().unwrap_or(0);
    !rows.is_empty()
        && rows
            .iter()
            .all(|r| r.len() >= width && r.iter().all(|v| v.is_finite()))
}

/// Whether both arms move in `rows`: each arm's largest joint excursion from the first sample
/// is at least [`BOTH_ARMS_MIN_RAD`] and [`BOTH_ARMS_RATIO`] times the other arm's. False for
/// rows that are not upper-body postures or hold a non-finite value.
pub fn both_arms_move(rows: &[Vec<f64>]) -> bool {
    if !usable(rows) {
        return false;
    }
    let left = excursion(rows, UPPER_BODY_MIRROR.iter().map(|p| p.0));
    let right = excursion(rows, UPPER_BODY_MIRROR.iter().map(|p| p.1));
    left >= BOTH_ARMS_MIN_RAD
        && right >= BOTH_ARMS_MIN_RAD
        && left >= BOTH_ARMS_RATIO * right
        && right >= BOTH_ARMS_RATIO * left
}

/// The lag of the right arm behind the left in `rows`, whole samples (positive: the right arm
/// moves later): the shift `s`, `|s| <= n / 2`, that maximises the cross-covariance of the
/// mirrored joint pairs ([`UPPER_BODY_MIRROR`]) taken as excursions from the first sample,
/// `C(s) = Σ_pairs Σ_k (l(k) − l(0)) σ (r(k + s) − r(0)) / n` over the samples where both are
/// defined (from the first sample, so that the still stretches before and after the motion
/// count for nothing and the true delay of a copy is the maximum); of equal maxima the smallest
/// `|s|`, then the negative. `None` with fewer than 2 samples, rows that are not upper-body
/// postures, a non-finite value, or arms that do not move (`C` is 0 at every shift).
pub fn arm_lag(rows: &[Vec<f64>]) -> Option<i64> {
    let n = rows.len();
    if n < 2 || !usable(rows) {
        return None;
    }
    // each joint's excursion from its first sample: still stretches contribute nothing
    let centred = |j: usize, sign: f64| -> Vec<f64> {
        rows.iter().map(|r| sign * (r[j] - rows[0][j])).collect()
    };
    let pairs: Vec<(Vec<f64>, Vec<f64>)> = UPPER_BODY_MIRROR
        .iter()
        .map(|&(l, r, sign)| (centred(l, 1.0), centred(r, sign)))
        .collect();
    let max_shift = (n / 2) as i64;
    let covariance = |s: i64| -> f64 {
        // the samples k with k + s in 0..n
        let (from, to) = ((-s).max(0) as usize, (n as i64 - s).min(n as i64) as usize);
        let sum: f64 = (pairs.iter())
            .map(|(l, r)| {
                (from..to)
                    .map(|k| l[k] * r[(k as i64 + s) as usize])
                    .sum::<f64>()
            })
            .sum();
        sum / n as f64
    };
    let mut best: Option<(f64, i64)> = None;
    // in order of |s|, the negative first: a later shift replaces the best only when larger
    for s in (0..=max_shift).flat_map(|m| if m == 0 { vec![0] } else { vec![-m, m] }) {
        let c = covariance(s);
        if best.map_or(true, |(b, _)| c > b) {
            best = Some((c, s));
        }
    }
    best.filter(|(c, _)| *c > 0.0).map(|(_, s)| s)
}

/// The demonstrations' own spread of the lag: the smallest and largest of their lags, samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct LagSpread {
    /// The smallest lag.
    pub min: i64,
    /// The largest lag.
    pub max: i64,
}

impl LagSpread {
    /// The spread of `lags`; `None` when there is none.
    pub fn of(lags: &[i64]) -> Option<LagSpread> {
        Some(LagSpread {
            min: *lags.iter().min()?,
            max: *lags.iter().max()?,
        })
    }

    /// The spread of the lags of `demos` ([`arm_lag`]); `None` when a demonstration has none.
    pub fn of_demos<R: AsRef<[Vec<f64>]>>(demos: &[R]) -> Option<LagSpread> {
        let lags: Option<Vec<i64>> = demos.iter().map(|d| arm_lag(d.as_ref())).collect();
        Self::of(&lags?)
    }

    /// Whether `lag` lies within `[min − 1, max + 1]` ([`LAG_TOLERANCE_SAMPLES`]).
    pub fn contains(&self, lag: i64) -> bool {
        (self.min - LAG_TOLERANCE_SAMPLES..=self.max + LAG_TOLERANCE_SAMPLES).contains(&lag)
    }
}

#[cfg(test)]
mod tests;
