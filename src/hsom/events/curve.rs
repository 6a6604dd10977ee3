//! The executed curve: knots at the placed, timed events, a monotone cubic through them,
//! the given initial posture joined to it, and the whole made as smooth as the
//! demonstrations (docs/ALGORITHM.md, section 3.8).

use super::encode::Step;
use super::smoothing::{jerk_smoothed, JerkFactor};
use super::traces::HALF_PLACES;
use crate::curve::{hermite, minimum_jerk_at, pchip_slopes, PchipEnds, MINIMUM_JERK_PEAK};
use crate::hsom::model::{DemoSmoothness, Model, Part};
use crate::hsom::reproduction::{Reproduction, StopReason};

impl<A: Part> Model<A> {
    /// Postures at every sample from the executed events ([`Model::curve`] of
    /// [`Model::timed_knots`]): each event's place is reached at the middle of the event; the
    /// first knot is where the plan begins and the last where it ends ([`Model::knot_places`]).
    ///
    /// A reproduction from its own start (`start` is `y0`) begins where the training
    /// demonstrations weighed by that start began ([`Model::plan_start`]), the mean their
    /// placements are weighed with, and the given posture's offset from there is joined to the
    /// plan ([`Timed::joined_from`]): a start away from every demonstration's is neither
    /// snapped to the plan in its first steps nor kept to the end. A continuation (`y0` the
    /// posture reached) starts at `y0`.
    pub(super) fn timed_postures(
        &self,
        start: &[f64],
        y0: &[f64],
        executed: &[Step<usize>],
        stop: StopReason,
        timing: Timing,
    ) -> Reproduction {
        let begun = (start == y0).then(|| self.plan_start(start)).flatten();
        let first = begun.as_deref().unwrap_or(y0);
        let mut timed = self.timed_knots(start, first, executed, stop);
        timed.timing = timing;
        let samples = timed.total.floor() as usize + 1;
        timed.joined_from = begun.map(|_| y0.to_vec());
        self.curve(&timed, &vec![0.0; y0.len()], samples, stop)
    }

    /// Where the training demonstrations weighed by `start` began (normalised, state part): the
    /// mean of their first postures weighed as their placements (`StartKnots`); `None` without.
    fn plan_start(&self, start: &[f64]) -> Option<Vec<f64>> {
        let e = self.part.events()?;
        e.start_knots
            .as_ref()
            .map_or(e.start_posture.clone(), |k| Some(k.placed_start(start)))
    }

    /// The knots of [`Model::timed_postures`]: their times, their values per variable (turning
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
            joined_from: None,
            timing: Timing::Planned,
        }
    }

    /// How smooth and how fast the training demonstrations were (`None` before
    /// [`Model::fit_postures`] or for the paper's model).
    fn smoothness(&self) -> Option<&DemoSmoothness> {
        self.part.events().and_then(|e| e.demo_smoothness.as_ref())
    }

    /// `timed` (a plan's knots, from rest) retimed where its curve moves faster than the
    /// demonstrations ever did ([`no_faster_than`]), marked so that its curve keeps them.
    pub(super) fn retimed(&self, timed: Timed) -> Timed {
        let mut out = match self.smoothness() {
            Some(d) => {
                let samples = timed.total.floor() as usize + 1;
                no_faster_than(
                    &timed,
                    &vec![0.0; timed.values.len()],
                    samples,
                    &d.peak_step,
                )
                .0
            }
            None => timed,
        };
        out.timing = Timing::Kept;
        out
    }

    /// The knots of [`Model::timed_knots`] where the plan places them, before the turning
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
            // a reproduction that ends by its end event ends where the demonstrations ended;
            // one cut short goes on along its last node's learned action (the posture
            // actionHorizon samples later), as far as that event's second half lasts
            let ended = self
                .part
                .events()
                .and_then(|e| e.end_posture.clone())
                .filter(|_| stop == StopReason::EndEvent);
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

    /// The postures at `samples` samples along the knots `timed`: per variable the monotone
    /// cubic through them ([`monotone_cubic_from`]: holds are held, turns are at knots), the
    /// knots retimed where it moves faster than the demonstrations ever did
    /// ([`no_faster_than`]; the samples grow by what they gained), leaving the first knot at
    /// the slope `m0` (within its monotone limits); plus the offset of the given posture from
    /// the first knot ([`Timed::joined_from`]) fading from 1 to 0 along a minimum-jerk profile
    /// over the samples; then smoothed as the training demonstrations are smooth
    /// ([`as_smooth_as`]): the cubic is continuous in velocity only, and its steps of
    /// acceleration at the knots are what the smoothing takes away.
    pub(super) fn curve(
        &self,
        timed: &Timed,
        m0: &[f64],
        samples: usize,
        stop: StopReason,
    ) -> Reproduction {
        let slowed = self
            .smoothness()
            .filter(|_| timed.timing == Timing::Planned)
            .map(|d| no_faster_than(timed, m0, samples, &d.peak_step));
        let (timed, samples) = match &slowed {
            Some((t, n)) => (t, *n),
            None => (timed, samples),
        };
        let s = timed.values.len();
        let mut out = vec![vec![0.0; s]; samples];
        // the offset fades to nothing, at rest at both ends of the fade
        let whole = (samples.max(2) - 1) as f64;
        // as long as the demonstrations' own offsets lasted, and no faster than they move (a
        // minimum-jerk move of d in H samples peaks at 1.875 d / H)
        let e = self.part.events();
        let offset: Option<Vec<f64>> = timed.joined_from.as_ref().map(|from| {
            from.iter()
                .zip(&timed.values)
                .map(|(f, v)| f - v[0])
                .collect()
        });
        let horizon = match (&offset, self.smoothness()) {
            (Some(off), Some(d)) => off
                .iter()
                .zip(&d.peak_step)
                .map(|(o, p)| {
                    if *p > 0.0 {
                        MINIMUM_JERK_PEAK * o.abs() / p
                    } else {
                        whole
                    }
                })
                .fold(
                    e.and_then(|e| e.start_fade).unwrap_or(1.0) * whole,
                    f64::max,
                )
                .clamp(1.0, whole),
            _ => whole,
        };
        let columns: Vec<Vec<f64>> = timed
            .values
            .iter()
            .enumerate()
            .map(|(d, knots)| {
                let mut y = monotone_cubic_from(&timed.t, knots, samples, m0[d]);
                if let (Some(off), Some(from)) = (&offset, &timed.joined_from) {
                    for (i, v) in y.iter_mut().enumerate() {
                        *v += off[d] * (1.0 - minimum_jerk_at(i as f64 / horizon));
                    }
                    // exactly the given posture, not the first knot plus its offset
                    y[0] = from[d];
                }
                y
            })
            .collect();
        // a reproduction from its start leaves it no faster than the demonstrations left theirs
        let target = self.smoothness().cloned().map(|d| DemoSmoothness {
            start_step: if timed.joined_from.is_some() {
                d.start_step
            } else {
                f64::INFINITY
            },
            ..d
        });
        for (d, y) in as_smooth_as(&columns, m0, target).into_iter().enumerate() {
            for (row, v) in out.iter_mut().zip(y) {
                row[d] = v;
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

/// Knots where the plan places them ([`Model::knot_places`]).
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

/// Knots of a timed reproduction ([`Model::timed_knots`]).
pub(super) struct Timed {
    /// Knot times, samples from the first.
    pub(super) t: Vec<f64>,
    /// Per variable, the value at each knot.
    pub(super) values: Vec<Vec<f64>>,
    /// Per knot, the level that planned its event.
    pub(super) by: Vec<usize>,
    /// The events' total duration, samples.
    pub(super) total: f64,
    /// The given initial posture (normalised) the curve starts at: its offset from the first
    /// knot fades along the reproduction ([`Model::curve`]); `None`: the curve starts at its
    /// first knot.
    pub(super) joined_from: Option<Vec<f64>>,
    /// Whose the events' durations are.
    pub(super) timing: Timing,
}

/// Whose the events' durations are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Timing {
    /// A plan's (its nodes' mean durations): where the curve moves faster than the
    /// demonstrations ever did, the knots are retimed ([`no_faster_than`]).
    Planned,
    /// Kept as they are: a demonstration's own (re-encoding it, sample for sample), or knots
    /// already retimed (the rest of a resumed plan, [`Model::retimed`]).
    Kept,
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
            joined_from: None,
            timing: self.timing,
        }
    }
}

/// Rounds of [`no_faster_than`]: each stretches every segment still too fast by its excess;
/// the tangents change with the times, so a segment may need another.
const RETIME_ROUNDS: usize = 4;

/// The knots `timed` (sampled over `samples`, leaving the first at slopes `m0`) retimed so
/// that between no two knots does the cubic move a variable faster than `peak` (per
/// variable, the training demonstrations' largest step, normalised): each segment whose
/// samples step further than that, in any variable, lasts longer by the ratio, and the
/// knots after it come later; the knots' values stay. A plan whose events are shorter than
/// the demonstrations' is slowed where it is too fast, not flattened; the samples grow by
/// what the segments gained.
pub(super) fn no_faster_than(
    timed: &Timed,
    m0: &[f64],
    samples: usize,
    peak: &[f64],
) -> (Timed, usize) {
    let mut t = timed.t.clone();
    let mut n = samples;
    for _ in 0..RETIME_ROUNDS {
        // per segment, how much faster than the demonstrations its fastest step is
        let mut excess = vec![1.0f64; t.len().saturating_sub(1)];
        for ((v, &m), &p) in timed.values.iter().zip(m0).zip(peak) {
            if p <= 0.0 {
                continue;
            }
            // the arm's own motion at the start is not the plan's to slow
            let y = monotone_cubic_from(&t, v, n, m.clamp(-p, p));
            // a step counts against every segment it spans (a knot between two samples:
            // both sides' lengths set its speed)
            let (mut lo, mut hi) = (0, 0);
            for (i, w) in y.windows(2).enumerate() {
                while lo + 2 < t.len() && i as f64 >= t[lo + 1] {
                    lo += 1;
                }
                while hi + 2 < t.len() && (i + 1) as f64 > t[hi + 1] {
                    hi += 1;
                }
                let r = (w[1] - w[0]).abs() / p;
                for e in excess.iter_mut().take(hi + 1).skip(lo) {
                    *e = e.max(r);
                }
            }
        }
        if excess.iter().all(|&e| e <= 1.0 + 1e-6) {
            break;
        }
        let mut shift = 0.0;
        let old = t.clone();
        for k in 1..t.len() {
            shift += (old[k] - old[k - 1]) * (excess[k - 1].max(1.0) - 1.0);
            t[k] = old[k] + shift;
        }
        n = samples + (t[t.len() - 1] - timed.t[timed.t.len() - 1]).ceil() as usize;
    }
    let gained = t.last().copied().unwrap_or(0.0) - timed.t.last().copied().unwrap_or(0.0);
    let slowed = Timed {
        t,
        values: timed.values.clone(),
        by: timed.by.clone(),
        total: timed.total + gained,
        joined_from: timed.joined_from.clone(),
        timing: timed.timing,
    };
    (slowed, n)
}

/// The monotone cubic through the knots (t, v) (PCHIP slopes, [`pchip_slopes`], at rest at
/// both ends) at the samples 0..samples.
#[cfg(test)]
pub(super) fn monotone_cubic(t: &[f64], v: &[f64], samples: usize) -> Vec<f64> {
    monotone_cubic_from(t, v, samples, 0.0)
}

/// [`monotone_cubic`] with the tangent `m0` at the first knot: kept where it goes the way of
/// the first segment, at most 3x its secant (Fritsch-Carlson's bound: no overshoot); 0
/// otherwise.
fn monotone_cubic_from(t: &[f64], v: &[f64], samples: usize, m0: f64) -> Vec<f64> {
    let k = t.len();
    let mut m = pchip_slopes(t, v, PchipEnds::AtRest);
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
            hermite(t, v, &m, seg, ti)
        })
        .collect()
}

/// The cubic through the knots (t, v) with tangents `m` at time `ti`, the segment found by
/// bisection (at a knot, the segment that ends there; before the first knot and after the
/// last: their values).
fn cubic_at(t: &[f64], v: &[f64], m: &[f64], ti: f64) -> f64 {
    let seg = t.partition_point(|&x| x < ti).clamp(1, t.len().max(2) - 1) - 1;
    hermite(t, v, m, seg, ti)
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
        let m = pchip_slopes(t, &v, PchipEnds::AtRest);
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

/// The smoothing weights [`as_smooth_as`] tries, least first: the cut-off period of
/// [`jerk_smoothed`] (`2π λ^(1/6)` samples) goes from 6 to 20 samples.
const SMOOTHING: [f64; 7] = [1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0];

/// The columns `y` (one variable each, sampled, moving at `slope` per sample before their
/// first sample), smoothed by [`jerk_smoothed`] with the least weight of [`SMOOTHING`] that
/// makes them as smooth as `target` (the training demonstrations'): their normalised jerk
/// at most the demonstrations', their first step at most the largest of theirs, and no
/// variable moving faster than in any of them. Where no weight slows a variable down
/// enough (a plan whose events are shorter than the demonstrations'), the least weight that
/// meets the rest: smoothing more would flatten the motion, not slow it. As they are where
/// they already are (or without a target), the most smoothed where none does.
pub(crate) fn as_smooth_as(
    y: &[Vec<f64>],
    slope: &[f64],
    target: Option<DemoSmoothness>,
) -> Vec<Vec<f64>> {
    let Some(target) = target else {
        return y.to_vec();
    };
    // (smooth and slow enough, smooth enough); whether smooth enough is told only when
    // `need_smooth` or when slow enough (else false)
    let judge = |cols: &[Vec<f64>], need_smooth: bool| {
        let slow = cols
            .iter()
            .zip(&target.peak_step)
            .all(|(c, &peak)| c.windows(2).all(|w| (w[1] - w[0]).abs() <= peak));
        if !slow && !need_smooth {
            return (false, false);
        }
        let n = cols.first().map_or(0, Vec::len);
        let flat: Vec<f64> = (0..n)
            .flat_map(|i| cols.iter().map(move |c| c[i]))
            .collect();
        let rows: Vec<&[f64]> = flat.chunks(cols.len().max(1)).collect();
        let first = rows
            .get(1)
            .map_or(0.0, |r| crate::dtw::euclidean(r, rows[0]));
        let smooth = crate::metrics::normalized_jerk(&rows, 1.0).map_or(true, |j| j <= target.jerk)
            && first <= target.start_step;
        (smooth && slow, smooth)
    };
    // every column has one length: one factor per weight serves them all
    let len = y.first().map_or(0, Vec::len);
    let candidates = std::iter::once(y.to_vec()).chain(SMOOTHING.iter().map(|&lambda| {
        if len >= 5 && y.iter().all(|c| c.len() == len) {
            JerkFactor::shared(len, lambda).solve_columns(y, slope)
        } else {
            y.iter()
                .zip(slope)
                .map(|(c, &m)| jerk_smoothed(c, lambda, m))
                .collect::<Vec<_>>()
        }
    }));
    let mut smooth_only: Option<Vec<Vec<f64>>> = None;
    let mut last = Vec::new();
    for c in candidates {
        let (all, smooth) = judge(&c, smooth_only.is_none());
        if all {
            return c;
        }
        if smooth && smooth_only.is_none() {
            smooth_only = Some(c.clone());
        }
        last = c;
    }
    smooth_only.unwrap_or(last)
}
