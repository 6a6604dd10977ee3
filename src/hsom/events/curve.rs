//! The executed curve: knots at the placed, timed events and a monotone cubic through
//! them.

use super::encode::Step;
use super::traces::HALF_PLACES;
use crate::hsom::model::Hsom;
use crate::hsom::reproduction::{Reproduction, StopReason};

impl Hsom {
    /// Postures at every sample from the executed events: each event's node posture (its
    /// state half) is reached at the middle of the event, the initial posture is the first
    /// knot, and the last event ends where its node's learned action leads (its action half,
    /// the posture `actionHorizon` samples later, reached in proportion to the event's
    /// second half: a gesture that ends in motion is not cut at the middle of its last
    /// event; one that ends in a hold ends there, action and state being equal); in between a monotone cubic
    /// (Fritsch-Carlson) per variable, so holds are held and the motion starts and ends at
    /// rest; a knot at a turning point is moved so that the event's mean is its node's posture
    /// ([`turning_points_kept`]), the only place the curve goes beyond its knots.
    pub(super) fn timed_postures(
        &self,
        start: &[f64],
        y0: &[f64],
        executed: &[Step<usize>],
        stop: StopReason,
    ) -> Reproduction {
        let timed = self.timed_knots(start, y0, executed, stop);
        let samples = timed.total.floor() as usize + 1;
        self.curve(&timed, &vec![0.0; y0.len()], samples, stop)
    }

    /// The knots of [`Hsom::timed_postures`]: their times, their values per variable (turning
    /// points kept), the level that planned each, and the events' total duration.
    pub(super) fn timed_knots(
        &self,
        start: &[f64],
        y0: &[f64],
        executed: &[Step<usize>],
        stop: StopReason,
    ) -> Timed {
        let p = self.knot_places(start, y0, executed, stop);
        let values = (0..y0.len())
            .map(|d| {
                let target: Vec<f64> = p.v.iter().map(|r| r[d]).collect();
                let reach: Vec<Option<(f64, f64)>> = p
                    .reach
                    .iter()
                    .map(|r| r.as_ref().map(|(lo, hi)| (lo[d], hi[d])))
                    .collect();
                turning_points_kept(&p.t, &target, &p.spans, &p.traced_mean, &reach)
            })
            .collect();
        Timed {
            t: p.t,
            values,
            by: p.by,
            total: p.total,
        }
    }

    /// The knots of [`Hsom::timed_knots`] where the plan places them, before the turning
    /// points are kept.
    pub(super) fn knot_places(
        &self,
        start: &[f64],
        y0: &[f64],
        executed: &[Step<usize>],
        stop: StopReason,
    ) -> Places {
        let s = y0.len();
        let placed = self.placement(start);
        let knot = |n: usize| placed[n * s..(n + 1) * s].to_vec();
        // a traced event at its node's place plus its offset from it in the consensus
        let traced = |n: usize, at: &[f64]| -> Vec<f64> {
            (0..s).map(|j| placed[n * s + j] + at[j]).collect()
        };
        let mut t = vec![0.0];
        let mut v: Vec<Vec<f64>> = vec![y0.to_vec()];
        let mut by = vec![0usize];
        // per knot: its place is the mean of the span it stands for in the followed
        // demonstration's consensus (a traced event or half), a mean kept beside a turn
        let mut traced_mean = vec![false];
        // per knot of a traced half: its span's lowest and highest consensus values
        let mut reach: Vec<Option<(Vec<f64>, Vec<f64>)>> = vec![None];
        // the samples of each event (knot i + 1): ceil(start)..ceil(end), within the
        // floor(total) + 1 samples below
        let mut spans = Vec::with_capacity(executed.len());
        let mut now = 0.0;
        for &(n, d, l, ref at) in executed {
            match at {
                // a knot at the middle of each half, where that half lies
                // (a traced event's place is followed by its halves': trace_places)
                Some(a) if d >= 2.0 * HALF_SAMPLES => {
                    debug_assert_eq!(a.len(), HALF_PLACES * s);
                    let place = |i: usize| traced(n, &a[i * s..(i + 1) * s]);
                    for (half, (from, to)) in [(now, now + d / 2.0), (now + d / 2.0, now + d)]
                        .into_iter()
                        .enumerate()
                    {
                        t.push((from + to) / 2.0);
                        v.push(place(half + 1));
                        reach.push(Some((place(3 + 2 * half), place(4 + 2 * half))));
                        by.push(l);
                        traced_mean.push(true);
                        spans.push((from.ceil() as usize, to.ceil() as usize));
                    }
                }
                _ => {
                    t.push(now + d / 2.0);
                    v.push(at.as_ref().map_or_else(|| knot(n), |a| traced(n, a)));
                    reach.push(None);
                    by.push(l);
                    traced_mean.push(at.is_some());
                    spans.push((now.ceil() as usize, (now + d).ceil() as usize));
                }
            }
            now += d;
        }
        if let Some(&(n, d, l, ref at)) = executed.last() {
            t.push(now);
            // the last event's second half goes on along its node's learned action (the
            // posture actionHorizon samples later), as far as that half lasts; but a
            // reproduction that ends by its end event after a node no demonstration ended
            // after ends where they ended
            let ended = self.end_posture(n).filter(|_| stop == StopReason::EndEvent);
            let end = ended.unwrap_or_else(|| {
                let mut end = at.as_ref().map_or_else(|| knot(n), |a| traced(n, a));
                let w = self.maps[0].weights(n);
                let on = (d / 2.0 / self.config.params().action_horizon() as f64).min(1.0);
                for (j, e) in end.iter_mut().enumerate() {
                    *e += (w[s + j] - w[j]) * on;
                }
                end
            });
            v.push(end);
            reach.push(None);
            by.push(l);
            traced_mean.push(false);
        }
        Places {
            t,
            v,
            by,
            traced_mean,
            reach,
            spans,
            total: now,
        }
    }

    /// The postures at `samples` samples along the knots `timed`, the curve leaving the first
    /// knot at the slope `m0` per variable (within the monotone limits of
    /// [`monotone_cubic_from`]).
    pub(super) fn curve(
        &self,
        timed: &Timed,
        m0: &[f64],
        samples: usize,
        stop: StopReason,
    ) -> Reproduction {
        let s = timed.values.len();
        let mut out = vec![vec![0.0; s]; samples];
        for (d, knots) in timed.values.iter().enumerate() {
            for (row, y) in out
                .iter_mut()
                .zip(monotone_cubic_from(&timed.t, knots, samples, m0[d]))
            {
                row[d] = y;
            }
        }
        let (t, by) = (&timed.t, &timed.by);
        let k = t.len();
        let mut seg = 0;
        let out_by: Vec<usize> = (0..samples)
            .map(|i| {
                while seg + 2 < k && i as f64 > t[seg + 1] {
                    seg += 1;
                }
                by[(seg + 1).min(k - 1)]
            })
            .collect();
        let postures: Vec<Vec<f64>> = out.iter().map(|y| self.denormalise(y)).collect();
        Reproduction {
            steps: (0..postures.len()).collect(),
            postures,
            predicted_by: out_by,
            stop,
        }
    }
}

/// Knots where the plan places them ([`Hsom::knot_places`]).
pub(super) struct Places {
    /// Knot times, samples from the first.
    pub(super) t: Vec<f64>,
    /// Per knot, its place (`stateLength` values, normalised).
    pub(super) v: Vec<Vec<f64>>,
    /// Per knot, the level that planned its event.
    pub(super) by: Vec<usize>,
    /// Per knot, whether its place is the mean of the followed demonstration's consensus over
    /// its span (a traced event or half; [`turning_points_kept`]).
    pub(super) traced_mean: Vec<bool>,
    /// Per knot of a traced half, the lowest and highest values of the
    /// followed demonstration's consensus over its span (normalised): where a turn there
    /// reaches ([`turning_points_kept`]).
    pub(super) reach: Vec<Option<(Vec<f64>, Vec<f64>)>>,
    /// Per knot after the first, the samples of its event or half.
    pub(super) spans: Vec<(usize, usize)>,
    /// The events' total duration, samples.
    pub(super) total: f64,
}

/// Knots of a timed reproduction ([`Hsom::timed_knots`]).
pub(super) struct Timed {
    /// Knot times, samples from the first.
    pub(super) t: Vec<f64>,
    /// Per variable, the value at each knot.
    pub(super) values: Vec<Vec<f64>>,
    /// Per knot, the level that planned its event.
    pub(super) by: Vec<usize>,
    /// The events' total duration, samples.
    pub(super) total: f64,
}

impl Timed {
    /// The same curve from `now` samples on, starting at `from`: the knots after `now` (by
    /// half a sample at least), shifted to start there.
    pub(super) fn from(&self, now: f64, from: &[f64]) -> Timed {
        let keep: Vec<usize> = (1..self.t.len())
            .filter(|&i| self.t[i] - now >= 0.5)
            .collect();
        Timed {
            t: std::iter::once(0.0)
                .chain(keep.iter().map(|&i| self.t[i] - now))
                .collect(),
            values: self
                .values
                .iter()
                .zip(from)
                .map(|(v, &f)| {
                    std::iter::once(f)
                        .chain(keep.iter().map(|&i| v[i]))
                        .collect()
                })
                .collect(),
            by: std::iter::once(0)
                .chain(keep.iter().map(|&i| self.by[i]))
                .collect(),
            total: (self.total - now).max(0.0),
        }
    }
}

/// The monotone cubic through the knots (t, v) (Fritsch-Carlson tangents, zero at both
/// ends) at the samples 0..samples.
#[cfg(test)]
pub(super) fn monotone_cubic(t: &[f64], v: &[f64], samples: usize) -> Vec<f64> {
    monotone_cubic_from(t, v, samples, 0.0)
}

/// [`monotone_cubic`] with the tangent `m0` at the first knot: kept where it goes the way of
/// the first segment, at most 3x its secant (Fritsch-Carlson's bound: no overshoot); 0
/// otherwise.
fn monotone_cubic_from(t: &[f64], v: &[f64], samples: usize, m0: f64) -> Vec<f64> {
    let k = t.len();
    let mut m = monotone_tangents(t, v);
    if k >= 2 && t[1] > t[0] {
        let secant = (v[1] - v[0]) / (t[1] - t[0]);
        m[0] = if m0 * secant > 0.0 {
            m0.signum() * m0.abs().min(3.0 * secant.abs())
        } else {
            0.0
        };
    }
    let mut seg = 0;
    (0..samples)
        .map(|i| {
            let ti = i as f64;
            // a sweep: the segment only moves forward
            while seg + 2 < k && ti > t[seg + 1] {
                seg += 1;
            }
            on_segment(t, v, &m, seg, ti)
        })
        .collect()
}

/// The cubic through the knots (t, v) with tangents `m` at time `ti`, the segment found by
/// bisection (before the first knot and after the last: their values).
fn cubic_at(t: &[f64], v: &[f64], m: &[f64], ti: f64) -> f64 {
    let seg = t.partition_point(|&x| x < ti).clamp(1, t.len().max(2) - 1) - 1;
    on_segment(t, v, m, seg, ti)
}

/// The cubic on segment `seg` (knots seg and seg + 1) at time `ti`; a single knot's value.
fn on_segment(t: &[f64], v: &[f64], m: &[f64], seg: usize, ti: f64) -> f64 {
    if t.len() == 1 {
        return v[0];
    }
    hermite(
        t[seg],
        t[seg + 1],
        v[seg],
        v[seg + 1],
        m[seg],
        m[seg + 1],
        ti,
    )
}

/// The fewest samples each half of a traced event lasts for the event to pass through two
/// knots (`knots = halves`): a half of one sample puts its knot at one sample of the
/// consensus, whose unevenness from sample to sample then shows as speed (salute seed 2 at
/// 2.11x the demonstrations' jerk with halves from two samples); from two samples on, each
/// knot's place is a mean. docs/ALGORITHM.md, section 3.7.
const HALF_SAMPLES: f64 = 2.0;

/// Most corrections [`turning_points_kept`] makes (it converges in 3-4 on gestures; the cap
/// only bounds the work).
const TURNING_ITERATIONS: usize = 20;

/// One variable's knots with its *turning points kept*: a knot that is a strict local extremum
/// of its neighbours (the initial posture and the end are never moved) is moved until the
/// monotone cubic's mean over its event's samples (`spans[i - 1]` for knot i) equals the
/// node's posture (`target[i]`). A node's posture is the mean of the samples of its events
/// (the consensus, docs/ALGORITHM.md section 3.7); at a turning point those samples lie on both sides of the
/// turn, so their mean lies inside it, and a curve that merely passes through the mean turns
/// short (the wave's troughs 0.05-0.15 rad). Elsewhere the mean of a segment is its middle
/// value and the knot stays. A fixed point, reached in a few corrections; docs/ALGORITHM.md,
/// section 3.8.
///
/// Only the samples the knot moves count: those strictly between its neighbours' times. The
/// first event's first sample is the initial posture itself, which no knot moves; counting it
/// made each correction add the same step again, and a one-sample first event at a turn threw
/// its knot 20 gaps away (a start-up jump and back).
///
/// A traced knot (`traced_mean[i]`: a traced event or half, whose target is the mean of the
/// followed demonstration's consensus over exactly the span it stands for) beside a turning
/// point keeps its span's mean too: the turn's samples may lie in its span rather than in the
/// turning knot's (the wave's last trough fell at the start of the next event's first half,
/// whose mean the rise after it lifted above the turning knot's), and with only the turning
/// knot moved the curve stayed flat at the pair's means there (moved too, that trough came
/// 0.02 rad deeper and its return home counted as a swing). A decoded knot's target is its node's place, a mean
/// over every event of that node, not over this span, so only turning points move there.
/// Elsewhere a span's mean is its middle value: moving those knots too, measured, amplified
/// the unevenness between them (jerk; docs/ALGORITHM.md, section 3.7).
///
/// A turning knot of a traced half whose span's extremes are known (`reach[i]`: the lowest
/// and highest values of the followed demonstration's consensus over the span) is placed at
/// the extreme it turns at, the lowest for a trough, the highest for a peak (never inside
/// its mean), and not corrected further: the curve's turn, at the knot (its tangent is zero
/// there), then reaches where the demonstrations' consensus turns. A mean cannot find that
/// where the turn is a sample or two of a long half: where DTW aligns the other
/// demonstrations' deeper trough to one sample of the followed one, the consensus has a
/// one-sample tip that the half's mean, and the curve whose mean matches it, average away
/// (wave seed 13, fold 3: the last trough 0.11 rad short of the consensus and the rise after
/// it 0.28 rad, under the swing count's 0.3; docs/ALGORITHM.md, section
/// 3.8).
pub(super) fn turning_points_kept(
    t: &[f64],
    target: &[f64],
    spans: &[(usize, usize)],
    traced_mean: &[bool],
    reach: &[Option<(f64, f64)>],
) -> Vec<f64> {
    let k = target.len();
    // a strict local extremum of its neighbours
    let extremum = |i: usize| {
        i >= 1 && i + 1 < k && {
            let (p, q, r) = (target[i - 1], target[i], target[i + 1]);
            (q > p && q > r) || (q < p && q < r)
        }
    };
    let mut v = target.to_vec();
    // a traced half's turning knot at the extreme of its span it turns at
    let mut reached = vec![false; k];
    for i in (1..k.saturating_sub(1)).filter(|&i| extremum(i)) {
        if let Some(&Some((lo, hi))) = reach.get(i) {
            v[i] = if target[i] < target[i - 1] {
                lo.min(target[i])
            } else {
                hi.max(target[i])
            };
            reached[i] = true;
        }
    }
    let turning: Vec<(usize, usize, usize)> = (1..k.saturating_sub(1))
        .filter(|&i| !reached[i])
        .filter(|&i| {
            extremum(i)
                || (traced_mean.get(i) == Some(&true) && (extremum(i - 1) || extremum(i + 1)))
        })
        .filter_map(|i| {
            let &(a, b) = spans.get(i - 1)?;
            // samples j with t[i - 1] < j < t[i + 1]
            let a = a.max(t[i - 1].floor() as usize + 1);
            let b = b.min(t[i + 1].ceil() as usize);
            (b > a).then_some((i, a, b))
        })
        .collect();
    // only the turning events' samples are evaluated: the work per correction is the knots
    // plus those events
    for _ in 0..TURNING_ITERATIONS {
        if turning.is_empty() {
            break;
        }
        let m = monotone_tangents(t, &v);
        let mut moved = 0.0f64;
        for &(i, a, b) in &turning {
            let mean = (a..b).map(|j| cubic_at(t, &v, &m, j as f64)).sum::<f64>() / (b - a) as f64;
            let step = target[i] - mean;
            v[i] += step;
            moved = moved.max(step.abs());
        }
        if moved < 1e-9 {
            break;
        }
    }
    v
}

/// Fritsch-Carlson tangents of a monotone cubic through (t, v), zero at both ends.
pub(super) fn monotone_tangents(t: &[f64], v: &[f64]) -> Vec<f64> {
    let k = t.len();
    let mut m = vec![0.0; k];
    if k < 3 {
        return m;
    }
    let delta: Vec<f64> = (0..k - 1)
        .map(|i| (v[i + 1] - v[i]) / (t[i + 1] - t[i]))
        .collect();
    for i in 1..k - 1 {
        if delta[i - 1] * delta[i] > 0.0 {
            // weighted harmonic mean (Fritsch-Butland), never more than 3x either secant
            let (h0, h1) = (t[i] - t[i - 1], t[i + 1] - t[i]);
            let w1 = 2.0 * h1 + h0;
            let w2 = h1 + 2.0 * h0;
            m[i] = (w1 + w2) / (w1 / delta[i - 1] + w2 / delta[i]);
        }
    }
    m
}

/// Cubic Hermite between (t0, v0, m0) and (t1, v1, m1) at t (clamped to the segment).
fn hermite(t0: f64, t1: f64, v0: f64, v1: f64, m0: f64, m1: f64, t: f64) -> f64 {
    let h = t1 - t0;
    if h <= 0.0 {
        return v1;
    }
    let u = ((t - t0) / h).clamp(0.0, 1.0);
    let (u2, u3) = (u * u, u * u * u);
    (2.0 * u3 - 3.0 * u2 + 1.0) * v0
        + (u3 - 2.0 * u2 + u) * h * m0
        + (-2.0 * u3 + 3.0 * u2) * v1
        + (u3 - u2) * h * m1
}
