//! Where a reproduction starts and ends against the demonstrations it learned from: its first
//! step's speed against theirs, its final error against the spread of their ends
//! (docs/METRICS.md, "Start and end").

use serde::Serialize;

use crate::demos::{sample_period, Demonstration};
use crate::dtw::euclidean;

/// A reproduction ends within the demonstrations' spread when its final error is at most this
/// many times their end spread ([`end_tolerance`]).
pub const END_SPREAD_FACTOR: f64 = 2.0;

/// ... or at most this fraction of the gesture's bounding-box diagonal, whichever is larger
/// (demonstrations that all end at one point, as LASA's at the attractor, have no spread).
pub const END_DIAGONAL_FRACTION: f64 = 0.01;

/// A start speed counts as at most the demonstrations' largest up to this relative rounding:
/// periods computed from `time` columns (span / intervals) differ in the last bit between
/// recordings at one rate, so a training demonstration replayed at the held-out one's period
/// can start one unit in the last place faster than itself.
pub const START_SPEED_RTOL: f64 = 1e-9;

/// The start speed of evenly sampled positions (period `dt` seconds): the first step's
/// Euclidean speed `‖q₁ − q₀‖ / dt`, data units per second. `None` with fewer than 2 samples
/// (no step).
pub fn start_speed<R: AsRef<[f64]>>(rows: &[R], dt: f64) -> Option<f64> {
    match rows {
        [q0, q1, ..] => Some(euclidean(q1.as_ref(), q0.as_ref()) / dt),
        _ => None,
    }
}

/// The end spread of trajectories whose last samples are `ends`: the mean Euclidean distance
/// over every pair of them, data units; 0 for fewer than two.
pub fn end_spread<R: AsRef<[f64]>>(ends: &[R]) -> f64 {
    let (mut sum, mut pairs) = (0.0, 0usize);
    for (i, a) in ends.iter().enumerate() {
        for b in &ends[i + 1..] {
            sum += euclidean(a.as_ref(), b.as_ref());
            pairs += 1;
        }
    }
    if pairs == 0 {
        0.0
    } else {
        sum / pairs as f64
    }
}

/// The largest final error that still ends within the demonstrations' spread:
/// `max(END_SPREAD_FACTOR · end_spread, END_DIAGONAL_FRACTION · diagonal)`.
pub fn end_tolerance(end_spread: f64, diagonal: f64) -> f64 {
    (END_SPREAD_FACTOR * end_spread).max(END_DIAGONAL_FRACTION * diagonal)
}

/// The diagonal of the bounding box of every sample of `demos`.
pub fn diagonal(demos: &[Demonstration]) -> f64 {
    let width = demos.first().map_or(0, |d| d.width());
    let mut lo = vec![f64::INFINITY; width];
    let mut hi = vec![f64::NEG_INFINITY; width];
    for row in demos.iter().flat_map(|d| &d.rows) {
        for (k, &v) in row.iter().enumerate() {
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
        }
    }
    lo.iter()
        .zip(&hi)
        .map(|(a, b)| (b - a).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The demonstrations a reproduction's start and end are judged against (a held-out fold's
/// training demonstrations; `cosco evaluate`'s demonstrations).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StartEndReference {
    /// The largest start speed ([`start_speed`], each at its own sample period) of the
    /// demonstrations, data units/s; `None` when none has two samples.
    pub demo_start_speed_max: Option<f64>,
    /// The [`end_spread`] of their last samples, data units.
    pub end_spread: f64,
    /// The gesture's bounding-box diagonal, data units.
    pub diagonal: f64,
}

impl StartEndReference {
    /// The reference of `demos` in a gesture whose bounding box has the diagonal `diagonal`.
    pub fn of<'a>(
        demos: impl IntoIterator<Item = &'a Demonstration>,
        diagonal: f64,
    ) -> StartEndReference {
        let mut max: Option<f64> = None;
        let mut ends: Vec<&[f64]> = Vec::new();
        for d in demos {
            if let Some(s) = start_speed(&d.rows, sample_period(d)) {
                max = Some(max.map_or(s, |m| m.max(s)));
            }
            if let Some(last) = d.rows.last() {
                ends.push(last);
            }
        }
        StartEndReference {
            demo_start_speed_max: max,
            end_spread: end_spread(&ends),
            diagonal,
        }
    }

    /// A reproduction's start and end: `rows` sampled every `dt` seconds, `final_error` the
    /// distance of its last sample from the demonstration it is scored against.
    pub fn judge<R: AsRef<[f64]>>(&self, rows: &[R], dt: f64, final_error: f64) -> StartEnd {
        let speed = start_speed(rows, dt);
        let tolerance = end_tolerance(self.end_spread, self.diagonal);
        StartEnd {
            start_speed: speed,
            demo_start_speed_max: self.demo_start_speed_max,
            start_in_range: matches!(
                (speed, self.demo_start_speed_max),
                (Some(s), Some(m)) if s <= m * (1.0 + START_SPEED_RTOL)
            ),
            end_spread: self.end_spread,
            final_error,
            end_tolerance: tolerance,
            end_within_spread: final_error <= tolerance,
        }
    }
}

/// A reproduction's start and end against a [`StartEndReference`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StartEnd {
    /// Its [`start_speed`], data units/s (`None` with one sample).
    pub start_speed: Option<f64>,
    /// The demonstrations' largest start speed, data units/s.
    pub demo_start_speed_max: Option<f64>,
    /// Whether its start speed is at most theirs (slower than the slowest counts as in range:
    /// it is no jump).
    pub start_in_range: bool,
    /// The demonstrations' [`end_spread`], data units.
    pub end_spread: f64,
    /// The distance of its last sample from the scored demonstration's last, data units.
    pub final_error: f64,
    /// [`end_tolerance`] of the spread and the gesture's diagonal, data units.
    pub end_tolerance: f64,
    /// Whether `final_error <= end_tolerance`.
    pub end_within_spread: bool,
}

#[cfg(test)]
mod tests;
