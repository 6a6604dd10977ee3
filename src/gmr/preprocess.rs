//! Pre-processing of the baseline (the paper's Section V): trim the idle start and end of
//! every demonstration, align the trimmed demonstrations to a reference with DTW, and
//! resample each to a fixed number of points. [`active_range`] is reused by the fidelity
//! metrics, so both use one definition of "idle".
//!
//! **Idle trimming.** With `q_k` the samples (`n` of them) and `t_k` their times, the smoothed
//! joint-space speed of step `k` (between samples `k` and `k+1`, `k = 0 … n−2`) is the speed
//! over a centred window of `2·half_window + 1` steps (clipped at the ends):
//! `s_k = ‖q_b − q_a‖₂ / (t_b − t_a)` (rad/s) with `a = max(k − half_window, 0)` and
//! `b = min(k + half_window + 1, n − 1)`. Differencing across the window, rather than
//! averaging the per-step speeds, keeps encoder noise from looking like motion: with
//! independent noise of σ rad on each of `J` joints the per-step speeds of a still arm
//! average `≈ σ·√(2J)/Δt` (0.14 rad/s for σ = 1 mrad, six joints, 40 Hz, as much as 5 % of a
//! gesture's peak speed), the windowed difference only `1/(2·half_window + 1)` of that. The
//! threshold is `θ = max(min_speed, relative · max_k s_k)`. The active part runs
//! from sample `first k with s_k > θ` to sample `(last k with s_k > θ) + 1`, inclusive.
//! If `max_k s_k < min_speed` the sequence never moves and has no active part.
//! Defaults: `min_speed` 0.02 rad/s, `relative` 0.05, `half_window` 2 (5 samples,
//! 125 ms at 40 Hz).
//!
//! **Reference.** The reference is the medoid: the trimmed demonstration whose summed
//! per-step DTW distance to the others is smallest (ties to the lower index). It is
//! typical of the set, not an outlier, and its trimmed duration becomes the duration of
//! the model.
//!
//! **Alignment.** Each demonstration is warped onto the reference's time line: for each
//! reference index `r`, the aligned sample is the mean of the demonstration's samples that
//! the DTW path pairs with `r`. Every aligned demonstration has the reference's length.
//!
//! **Resampling.** Each sequence of `L` samples becomes `n` samples by linear
//! interpolation at the fractional indices `u_k = k (L−1)/(n−1)`
//! ([`crate::curve::resample_linear`]). Samples are assumed
//! evenly spaced (the recordings are at a fixed rate); a `time` column only sets speeds
//! and durations.

use std::ops::Range;

use super::errors::GmrError;
use super::hyperparams::{GmrValidParams, IdleTrim, MIN_DEMONSTRATIONS};
use crate::curve::resample_linear;
use crate::demos::{validate_set, Demonstration};
use crate::dtw::{dtw, dtw_distance, Band, DtwError};
use crate::stats::upper_median;

/// Smoothed joint-space speeds `s_k` (rad/s), `k = 0..n−1` for `n + 1` samples (see the
/// module documentation), of evenly or explicitly timed samples: `times` when given (one per
/// sample), else `period` seconds apart. Empty for fewer than two samples.
pub fn smoothed_speeds<R: AsRef<[f64]>>(
    rows: &[R],
    times: Option<&[f64]>,
    period: f64,
    half_window: usize,
) -> Vec<f64> {
    if rows.len() < 2 {
        return Vec::new();
    }
    let n = rows.len() - 1;
    (0..n)
        .map(|k| {
            let a = k.saturating_sub(half_window);
            let b = (k + half_window + 1).min(n);
            let dt = times.map_or((b - a) as f64 * period, |t| t[b] - t[a]);
            crate::dtw::euclidean(rows[b].as_ref(), rows[a].as_ref()) / dt
        })
        .collect()
}

/// The active (non-idle) part of a sequence as a range of sample indices, or `None` when
/// it never moves faster than `trim.min_speed` (or has fewer than two samples). Rows must
/// share one width and `times`, when given, must hold one increasing time per row.
pub fn active_range<R: AsRef<[f64]>>(
    rows: &[R],
    times: Option<&[f64]>,
    period: f64,
    trim: &IdleTrim,
) -> Option<Range<usize>> {
    let s = smoothed_speeds(rows, times, period, trim.half_window);
    let peak = s.iter().cloned().fold(0.0, f64::max);
    if peak < trim.min_speed {
        return None;
    }
    let theta = trim.min_speed.max(trim.relative * peak);
    // a step also needs a displacement across its window that encoder noise alone would
    // not reach anywhere in the sequence (see `noise_displacement`)
    let floor = noise_displacement(rows);
    let n = s.len();
    let moving = |k: usize| {
        let a = k.saturating_sub(trim.half_window);
        let b = (k + trim.half_window + 1).min(n);
        s[k] > theta && crate::dtw::euclidean(rows[b].as_ref(), rows[a].as_ref()) > floor
    };
    let first = (0..n).find(|&k| moving(k))?;
    let last = (0..n).rev().find(|&k| moving(k))?;
    Some(first..last + 2)
}

/// Probability that encoder noise alone moves a sequence across one smoothing window by
/// more than [`noise_displacement`] anywhere in it.
pub const NOISE_FALSE_ALARM: f64 = 1e-3;

/// The displacement between two samples that white encoder noise alone exceeds somewhere in
/// the sequence with probability at most [`NOISE_FALSE_ALARM`]. Each column's noise `σ_j` is
/// estimated from the sequence itself, robustly, as the median absolute second difference /
/// (0.6745 √6) (white noise of deviation σ has second differences of deviation √6 σ; the
/// smooth motion adds little at 40 Hz, and only raises the estimate). The difference of two
/// noisy samples is then `Σ_j a_j Z_j²` in squared norm with `a_j = 2 σ_j²`, bounded with
/// the Laurent-Massart inequality: `P(X ≥ Σa + 2 √(Σa² t) + 2 max(a) t) ≤ e^(-t)`, with
/// `t = ln(steps / NOISE_FALSE_ALARM)`. 0 for fewer than 3 samples.
pub fn noise_displacement<R: AsRef<[f64]>>(rows: &[R]) -> f64 {
    if rows.len() < 3 {
        return 0.0;
    }
    let width = rows[0].as_ref().len();
    let mut a = Vec::with_capacity(width);
    let mut d2: Vec<f64> = Vec::with_capacity(rows.len() - 2);
    for j in 0..width {
        d2.clear();
        d2.extend(
            rows.windows(3)
                .map(|w| (w[2].as_ref()[j] - 2.0 * w[1].as_ref()[j] + w[0].as_ref()[j]).abs()),
        );
        // at least one second difference: 3 rows or more
        let m = upper_median(&mut d2).unwrap_or(0.0);
        let sigma = m / (0.6745 * 6f64.sqrt());
        a.push(2.0 * sigma * sigma);
    }
    let t = ((rows.len() - 1) as f64 / NOISE_FALSE_ALARM).ln();
    let sum: f64 = a.iter().sum();
    let sum2: f64 = a.iter().map(|x| x * x).sum();
    let max = a.iter().cloned().fold(0.0, f64::max);
    let bound = sum + 2.0 * (sum2 * t).sqrt() + 2.0 * max * t;
    if bound.is_finite() {
        bound.sqrt()
    } else {
        f64::INFINITY
    }
}

/// The baseline's training data: every demonstration trimmed, aligned and resampled to the
/// same time line.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainingSet {
    /// Column names of the state variables.
    pub columns: Vec<String>,
    /// The shared time line, seconds from the start of the motion: `n_points` values from
    /// 0 to `duration`.
    pub times: Vec<f64>,
    /// One resampled sequence per demonstration, each `times.len()` samples.
    pub demos: Vec<Vec<Vec<f64>>>,
    /// Index of the reference demonstration (`None` when alignment is off).
    pub reference: Option<usize>,
    /// Duration of the motion in seconds: the reference's trimmed duration, or the mean
    /// trimmed duration when alignment is off.
    pub duration: f64,
    /// The kept (active) sample range of each demonstration.
    pub kept: Vec<Range<usize>>,
}

impl TrainingSet {
    /// The GMM's data: one point `[t, q_1 … q_D]` per sample of every demonstration.
    pub fn points(&self) -> Vec<Vec<f64>> {
        self.demos
            .iter()
            .flat_map(|d| {
                d.iter().zip(&self.times).map(|(q, &t)| {
                    let mut p = Vec::with_capacity(q.len() + 1);
                    p.push(t);
                    p.extend_from_slice(q);
                    p
                })
            })
            .collect()
    }
}

/// The medoid of a set of sequences under per-step DTW distance (ties to the lower index).
pub fn choose_reference(seqs: &[Vec<Vec<f64>>], band: Band) -> Result<usize, DtwError> {
    let n = seqs.len();
    let mut total = vec![0.0; n];
    for i in 0..n {
        for j in i + 1..n {
            let d = dtw_distance(&seqs[i], &seqs[j], band)?.per_step();
            total[i] += d;
            total[j] += d;
        }
    }
    let mut best = 0;
    for (i, &t) in total.iter().enumerate() {
        if t < total[best] {
            best = i;
        }
    }
    Ok(best)
}

/// Warp `seq` onto `reference`'s time line: for each reference index, the mean of the
/// samples of `seq` that the DTW path pairs with it. The result has `reference.len()`
/// samples.
pub fn align_to(
    reference: &[Vec<f64>],
    seq: &[Vec<f64>],
    band: Band,
) -> Result<Vec<Vec<f64>>, DtwError> {
    let al = dtw(reference, seq, band)?;
    let width = reference[0].len();
    let mut sum = vec![vec![0.0; width]; reference.len()];
    let mut count = vec![0usize; reference.len()];
    for &(r, s) in &al.path {
        for (acc, v) in sum[r].iter_mut().zip(&seq[s]) {
            *acc += v;
        }
        count[r] += 1;
    }
    for (row, c) in sum.iter_mut().zip(&count) {
        for v in row.iter_mut() {
            *v /= *c as f64;
        }
    }
    Ok(sum)
}

fn duration_of(demo: &Demonstration, range: &Range<usize>, period: f64) -> f64 {
    match &demo.time {
        Some(t) => t[range.end - 1] - t[range.start],
        None => (range.len() - 1) as f64 * period,
    }
}

/// The whole pre-processing: validate the set (same columns), require at least
/// [`MIN_DEMONSTRATIONS`], trim each, align to the medoid (when alignment is on), resample.
pub fn preprocess(
    demos: &[Demonstration],
    params: &GmrValidParams,
) -> Result<TrainingSet, GmrError> {
    let p = params.params();
    if demos.len() < MIN_DEMONSTRATIONS {
        return Err(GmrError::TooFewDemonstrations {
            found: demos.len(),
            required: MIN_DEMONSTRATIONS,
        });
    }
    validate_set(demos, None)?;
    let trim = p.trim;
    let period = p.sample_period;
    let mut kept = Vec::with_capacity(demos.len());
    let mut trimmed: Vec<Vec<Vec<f64>>> = Vec::with_capacity(demos.len());
    for d in demos {
        let range = active_range(&d.rows, d.time.as_deref(), period, &trim).ok_or_else(|| {
            GmrError::NoMotion {
                source_name: d.source.clone(),
                threshold: trim.min_speed,
            }
        })?;
        trimmed.push(d.rows[range.clone()].to_vec());
        kept.push(range);
    }
    let n = p.n_points;
    let (reference, duration, demos_out) = if p.align {
        let r = choose_reference(&trimmed, p.band)?;
        let duration = duration_of(&demos[r], &kept[r], period);
        let mut out = Vec::with_capacity(trimmed.len());
        for t in &trimmed {
            let aligned = align_to(&trimmed[r], t, p.band)?;
            out.push(resample_linear(&aligned, n));
        }
        (Some(r), duration, out)
    } else {
        let duration = demos
            .iter()
            .zip(&kept)
            .map(|(d, k)| duration_of(d, k, period))
            .sum::<f64>()
            / demos.len() as f64;
        let out = trimmed.iter().map(|t| resample_linear(t, n)).collect();
        (None, duration, out)
    };
    let times = (0..n)
        .map(|k| duration * k as f64 / (n - 1) as f64)
        .collect();
    Ok(TrainingSet {
        columns: demos[0].columns.clone(),
        times,
        demos: demos_out,
        reference,
        duration,
        kept,
    })
}

#[cfg(test)]
mod tests;
