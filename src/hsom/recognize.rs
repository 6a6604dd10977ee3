//! Recognition with a multi-gesture hierarchy (docs/ALGORITHM.md, section
//! 4): a sequence's bottom events are pushed up every label's branch exactly as in
//! training; at each level above the bottom, each chunk is matched by the branch's map and
//! its RMS distance (per coordinate) taken. A label's score is the mean over levels of the
//! level's mean distance divided by the same mean on the branch's own training data: 1 is
//! "as close as what it learned", larger is farther. The lowest score wins; above the
//! label's threshold, calibrated on the training data alone (leave-one-out), the answer is
//! `unknown`.

use crate::dtw::{argmin, open_end_cost};

use super::errors::GestureError;
use super::errors::HsomError;
use super::events::{
    a_part, b_part, bottom_events, chunk_input, chunks, summary, DurationCode, Item,
};
use super::model::{Calibration, GestureModel, Hsom, Layout, Scoring};
use super::reproduction::Reproduction;

/// The seed of branch `g` (`held_out`: of its leave-one-out variant without that
/// demonstration).
pub(crate) fn branch_seed(seed: u64, g: usize, held_out: Option<usize>) -> u64 {
    let h = held_out.map_or(0, |i| i as u64 + 1);
    seed.wrapping_add(0x9e37_79b9_7f4a_7c15u64.wrapping_mul(g as u64 + 1))
        .wrapping_add(h.wrapping_mul(0x2545_f491_4f6c_dd1d))
}

/// Per sample of `norm` (normalised rows; its bottom inputs: the posture and the posture
/// `actionHorizon` later), the RMS distance to the nearest bottom node `model`'s gesture used
/// (the bottom is shared; the branch's event durations say which nodes its gesture visited).
pub(crate) fn posture_distances(model: &Hsom, norm: &[Vec<f64>]) -> Vec<f64> {
    let map = &model.maps[0];
    let used: Vec<usize> = (0..map.len()).filter(|&n| model.dwell[n] > 0.0).collect();
    let s = model.config.params().state_length;
    let h = model.config.params().action_horizon().max(1);
    let mut x = vec![0.0; 2 * s];
    (0..norm.len().saturating_sub(1))
        .map(|pos| {
            x[..s].copy_from_slice(&norm[pos]);
            x[s..].copy_from_slice(&norm[(pos + h).min(norm.len() - 1)]);
            let d2 = used
                .iter()
                .map(|&n| map.distance2(n, &x, 0..2 * s))
                .fold(f64::INFINITY, f64::min);
            (d2 / (2 * s) as f64).sqrt()
        })
        .collect()
}

/// The mean of the first `n` values (`None` when there are none).
fn mean_of(v: &[f64], n: usize) -> Option<f64> {
    let n = n.min(v.len());
    (n > 0).then(|| v[..n].iter().sum::<f64>() / n as f64)
}

/// Level distances of a whole normalised sequence: the postures' at level 0, then the
/// levels' chunks ([`level_distances`]).
fn all_distances(model: &Hsom, norm: &[Vec<f64>], events: &[(usize, f64)]) -> Vec<Option<f64>> {
    let mut d = level_distances(model, events, true);
    let p = posture_distances(model, norm);
    d[0] = mean_of(&p, p.len());
    d
}

/// Per level, the mean RMS distance per known coordinate between the
/// chunks of `events` (bottom events: node, samples) and their best nodes in `model`'s maps.
/// With `complete`, the sequence ends after its events (the end is appended, as in training);
/// otherwise it is a prefix: only the chunks it completes count, plus the chunk in progress
/// at level 1, matched on what it holds. Level 0 is left to [`posture_distances`].
pub(crate) fn level_distances(
    model: &Hsom,
    events: &[(usize, f64)],
    complete: bool,
) -> Vec<Option<f64>> {
    let lay = Layout::of(&model.config);
    let h = model.maps.len();
    let code = DurationCode::from_dwell(&model.dwell);
    let mean_events = model.demo_runs[1];
    let mut out = vec![None; h];
    // the events as level 1's entries; the end only once the gesture is complete
    let mut items: Vec<Item> = model.event_items(events, code);
    if !complete || events.is_empty() {
        items.pop();
    }
    let mut x = vec![0.0; lay.dim()];
    let mut mask = vec![true; lay.dim()];
    for (l, slot) in out.iter_mut().enumerate().skip(1) {
        if items.is_empty() {
            break;
        }
        let per_item = (lay.k as f64).powi(l as i32 - 1);
        let full = if complete {
            items.len()
        } else {
            items.len() / lay.k * lay.k
        };
        let (mut sum, mut n) = (0.0, 0usize);
        let mut next = Vec::new();
        for ch in chunks(lay, &items[..full], per_item, mean_events) {
            ch.input(lay, lay.k, &mut x, &mut mask);
            let (b, d2) = model.maps[l].bmu(&x);
            sum += (d2 / lay.dim() as f64).sqrt();
            n += 1;
            next.push(Item {
                node: b as u32,
                content: summary(lay, &model.maps[l].weights(b), code),
            });
        }
        if l == 1 && full < items.len() {
            let rest: Vec<&[f64]> = items[full..].iter().map(|i| i.content.as_slice()).collect();
            let prev = if full == 0 {
                a_part(lay, &items[0].content).to_vec()
            } else {
                b_part(lay, &items[full - 1].content).to_vec()
            };
            let phase = full as f64 * per_item / mean_events.max(1.0);
            let known = chunk_input(lay, &prev, full == 0, phase, &rest, &mut x, &mut mask);
            let (_, d2) = model.maps[l].bmu_masked(&x, &mask);
            sum += (d2 / known as f64).sqrt();
            n += 1;
        }
        if n > 0 {
            *slot = Some(sum / n as f64);
        }
        items = next;
    }
    out
}

impl Scoring {
    /// The score of per-level distances against per-level references (levels without either
    /// left out; infinite when none is left).
    fn score(self, dist: &[Option<f64>], reference: &[f64]) -> f64 {
        let (mut s, mut n) = (0.0, 0usize);
        for (l, (d, r)) in dist.iter().zip(reference).enumerate() {
            let counted = match self {
                Scoring::Level1 => l == 1,
                Scoring::Postures => l == 0,
                _ => true,
            };
            if !counted {
                continue;
            }
            if let Some(d) = d {
                match self {
                    Scoring::Relative if *r > 0.0 => s += d / r,
                    Scoring::Relative => continue,
                    _ => s += d,
                }
                n += 1;
            }
        }
        if n > 0 {
            s / n as f64
        } else {
            f64::INFINITY
        }
    }
}

/// Per level, the mean of distance vectors (0 where none).
fn level_means(dists: &[Vec<Option<f64>>], h: usize) -> Vec<f64> {
    let (mut sum, mut n) = (vec![0.0; h], vec![0usize; h]);
    for d in dists {
        for (l, v) in d.iter().enumerate() {
            if let Some(v) = v {
                sum[l] += v;
                n[l] += 1;
            }
        }
    }
    sum.iter()
        .zip(&n)
        .map(|(s, &n)| if n > 0 { s / n as f64 } else { 0.0 })
        .collect()
}

/// The one-sided 95 % quantile of Student's t with `df` degrees of freedom (a table to 30,
/// the Cornish-Fisher expansion beyond, within 1e-3 of the exact value there).
fn t95(df: usize) -> f64 {
    const TABLE: [f64; 30] = [
        6.314, 2.920, 2.353, 2.132, 2.015, 1.943, 1.895, 1.860, 1.833, 1.812, 1.796, 1.782, 1.771,
        1.761, 1.753, 1.746, 1.740, 1.734, 1.729, 1.725, 1.721, 1.717, 1.714, 1.711, 1.708, 1.706,
        1.703, 1.701, 1.699, 1.697,
    ];
    if (1..=30).contains(&df) {
        return TABLE[df - 1];
    }
    let (z, v) = (1.644_853_6_f64, df.max(1) as f64);
    z + (z.powi(3) + z) / (4.0 * v)
        + (5.0 * z.powi(5) + 16.0 * z.powi(3) + 3.0 * z) / (96.0 * v * v)
}

/// What a new demonstration of a gesture may score: the upper 95 % prediction bound of one
/// more score from `own` (its demonstrations' held-out scores), the scores taken as
/// log-normal (distances, whose spread grows with their size), and never below
/// the worst of them. With one score there is no spread to estimate: twice it.
pub(crate) fn new_demonstration_bound(own: &[f64]) -> f64 {
    let worst = own.iter().cloned().fold(0.0, f64::max);
    let n = own.len();
    if n < 2 {
        return 2.0 * worst;
    }
    // a score of 0 (a demonstration repeated exactly) would make the log spread infinite
    let floor = worst * 1e-6;
    let logs: Vec<f64> = own.iter().map(|&s| s.max(floor).ln()).collect();
    let mean = logs.iter().sum::<f64>() / n as f64;
    let var = logs.iter().map(|l| (l - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    let bound = (mean + t95(n - 1) * (var * (1.0 + 1.0 / n as f64)).sqrt()).exp();
    if bound.is_finite() {
        bound.max(worst)
    } else {
        worst
    }
}

/// The calibration of every label: its held-out references (each own demonstration scored
/// by a branch trained without it: leave-one-out; in-sample for a label with one
/// demonstration), and its threshold from those own held-out scores (what a new
/// demonstration of the gesture scores, [`new_demonstration_bound`]) and the scores the other
/// labels' training demonstrations get from it: the geometric midpoint of the bound and the
/// best other score when every other scores above the bound (the widest margin in log score),
/// else the bound itself (a new demonstration of the gesture accepted before another gesture
/// is refused); with a single label, the bound.
pub(crate) fn calibrate(
    shared: &Hsom,
    branches: &[Hsom],
    norm: &[Vec<Vec<Vec<f64>>>],
    learn: bool,
    seed: u64,
) -> Vec<Calibration> {
    let h = shared.maps.len();
    let events: Vec<Vec<Vec<(usize, f64)>>> = norm
        .iter()
        .map(|n| n.iter().map(|d| bottom_events(shared, d)).collect())
        .collect();
    (0..branches.len())
        .map(|g| {
            let own: Vec<Vec<Option<f64>>> = if norm[g].len() >= 2 {
                (0..norm[g].len())
                    .map(|i| {
                        let rest: Vec<Vec<Vec<f64>>> = norm[g]
                            .iter()
                            .enumerate()
                            .filter(|&(j, _)| j != i)
                            .map(|(_, d)| d.clone())
                            .collect();
                        let loo = shared.branch(&rest, learn, branch_seed(seed, g, Some(i)));
                        all_distances(&loo, &norm[g][i], &events[g][i])
                    })
                    .collect()
            } else {
                vec![all_distances(&branches[g], &norm[g][0], &events[g][0])]
            };
            let reference = level_means(&own, h);
            let scoring = Scoring::default();
            let own_scores: Vec<f64> = own
                .iter()
                .map(|d| scoring.score(d, &reference))
                .filter(|v| v.is_finite())
                .collect();
            let bound = new_demonstration_bound(&own_scores);
            let best_other = (0..branches.len())
                .filter(|&o| o != g)
                .flat_map(|o| norm[o].iter().zip(&events[o]))
                .map(|(n, ev)| scoring.score(&all_distances(&branches[g], n, ev), &reference))
                .fold(f64::INFINITY, f64::min);
            let threshold = if best_other > bound && best_other.is_finite() {
                (bound * best_other).sqrt()
            } else {
                bound
            };
            Calibration {
                reference,
                threshold,
            }
        })
        .collect()
}

/// The answer of recognition for one sequence.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Recognition {
    /// The recognised label, or `None` (unknown) when the best score is above its threshold.
    pub label: Option<String>,
    /// The label with the lowest score (whether or not it is below its threshold).
    pub best: String,
    /// Per label (in the model's order): its score (lower is closer; recognised when at
    /// most its threshold; 1 is as close as its training data only with [`Scoring::Relative`]).
    pub scores: Vec<(String, f64)>,
    /// Per label: its threshold.
    pub thresholds: Vec<f64>,
    /// The earliest sample from which the best label stayed the same to the end (early
    /// recognition).
    pub decided_at: usize,
    /// Samples in the sequence.
    pub samples: usize,
}

impl Recognition {
    /// `decided_at / samples`: the fraction of the gesture seen before the decision was
    /// final.
    pub fn decided_fraction(&self) -> f64 {
        self.decided_at as f64 / self.samples.max(1) as f64
    }
}

impl GestureModel {
    /// The normalised rows and their bottom events, after checking the rows.
    #[allow(clippy::type_complexity)]
    fn checked_events(
        &self,
        rows: &[Vec<f64>],
    ) -> Result<(Vec<Vec<f64>>, Vec<(usize, f64)>), GestureError> {
        if self.labels.is_empty() {
            return Err(GestureError::NoLabels);
        }
        let shared = &self.branches[0];
        let width = shared.columns.len();
        if rows.len() < 2 {
            return Err(HsomError::TooShort {
                demo: "the sequence".into(),
                rows: rows.len(),
                needed: 2,
            }
            .into());
        }
        for (i, r) in rows.iter().enumerate() {
            if r.len() != width {
                return Err(HsomError::DimensionMismatch {
                    demo: "the sequence".into(),
                    row: i,
                    expected: width,
                    found: r.len(),
                }
                .into());
            }
            if let Some(c) = r.iter().position(|v| !v.is_finite()) {
                return Err(HsomError::NonFinite {
                    demo: "the sequence".into(),
                    row: i,
                    column: c,
                }
                .into());
            }
        }
        let norm = shared.normalise_rows(rows);
        let ev = bottom_events(shared, &norm);
        Ok((norm, ev))
    }

    /// Per label, the per-sample posture distances of a normalised sequence.
    fn postures_of(&self, norm: &[Vec<f64>]) -> Vec<Vec<f64>> {
        self.branches
            .iter()
            .map(|b| posture_distances(b, norm))
            .collect()
    }

    /// Per label, the score of the first `samples` samples (their posture distances
    /// `postures`) and the bottom events `events`; `complete`: the sequence ends there.
    fn scores_of(
        &self,
        postures: &[Vec<f64>],
        samples: usize,
        events: &[(usize, f64)],
        complete: bool,
    ) -> Vec<f64> {
        self.branches
            .iter()
            .zip(&self.calibration)
            .zip(postures)
            .map(|((b, c), p)| {
                let mut d = if self.scoring == Scoring::Postures {
                    vec![None; b.maps.len()]
                } else {
                    level_distances(b, events, complete)
                };
                d[0] = mean_of(p, samples);
                self.scoring.score(&d, &c.reference)
            })
            .collect()
    }

    /// Per label (in the model's order), the score of a whole sequence (rows in the data's
    /// units): lower is closer (1 is as close as the label's training data only with
    /// [`Scoring::Relative`]; the default scores postures' distances).
    pub fn scores(&self, rows: &[Vec<f64>]) -> Result<Vec<f64>, GestureError> {
        let (norm, ev) = self.checked_events(rows)?;
        let p = self.postures_of(&norm);
        Ok(self.scores_of(&p, rows.len(), &ev, true))
    }

    /// Recognise a whole sequence: the best label or unknown, every score, and the earliest
    /// sample from which the best label stayed the same (each prefix scored on the bottom
    /// events it has completed, available `actionHorizon` samples after they end).
    pub fn recognize(&self, rows: &[Vec<f64>]) -> Result<Recognition, GestureError> {
        let (norm, ev) = self.checked_events(rows)?;
        let post = self.postures_of(&norm);
        let fin = self.scores_of(&post, rows.len(), &ev, true);
        let best = argmin(&fin);
        let horizon = self.branches[0].config.params().action_horizon();
        let mut decided_at = rows.len();
        let mut done = 0.0;
        let mut ends = Vec::with_capacity(ev.len());
        for &(_, d) in &ev {
            done += d;
            ends.push(done);
        }
        for p in (1..=ev.len()).rev() {
            let at = ((ends[p - 1] as usize) + horizon).min(rows.len());
            if argmin(&self.scores_of(&post, ends[p - 1] as usize, &ev[..p], false)) != best {
                break;
            }
            decided_at = at;
        }
        let threshold = self.calibration[best].threshold;
        Ok(Recognition {
            label: (fin[best] <= threshold).then(|| self.labels[best].clone()),
            best: self.labels[best].clone(),
            scores: self.labels.iter().cloned().zip(fin).collect(),
            thresholds: self.calibration.iter().map(|c| c.threshold).collect(),
            decided_at,
            samples: rows.len(),
        })
    }

    /// Continue a gesture from its first samples (`prefix`, in the data's units): the
    /// hierarchy decides which gesture it is (the lowest prefix score), reproduces it from
    /// the prefix's first posture, finds where the prefix ends along that reproduction (DTW
    /// with an open end) and continues from there, the gap between the prefix's last posture
    /// and the reproduction closed over [`PREFIX_BLEND`] samples. Returns the label and the
    /// postures (the prefix first).
    pub fn continue_prefix(
        &self,
        prefix: &[Vec<f64>],
    ) -> Result<(String, Reproduction), GestureError> {
        let (norm, ev) = self.checked_events(prefix)?;
        let post = self.postures_of(&norm);
        let g = argmin(&self.scores_of(&post, prefix.len(), &ev, false));
        let rep = self.branches[g].reproduce(&prefix[0])?;
        let j = open_end(prefix, &rep.postures);
        let last = &prefix[prefix.len() - 1];
        let gap: Vec<f64> = last
            .iter()
            .zip(&rep.postures[j])
            .map(|(a, b)| a - b)
            .collect();
        let mut postures = prefix.to_vec();
        let mut by = vec![0; prefix.len()];
        for (t, (row, &l)) in rep.postures[j + 1..]
            .iter()
            .zip(&rep.predicted_by[j + 1..])
            .enumerate()
        {
            let w = (1.0 - (t + 1) as f64 / PREFIX_BLEND as f64).max(0.0);
            postures.push(row.iter().zip(&gap).map(|(v, d)| v + w * d).collect());
            by.push(l);
        }
        Ok((
            self.labels[g].clone(),
            Reproduction {
                steps: (0..postures.len()).collect(),
                postures,
                predicted_by: by,
                stop: rep.stop,
            },
        ))
    }
}

/// Samples over which a continued prefix closes the gap to the reproduction (0.25 s at the
/// recordings' 40 Hz).
pub const PREFIX_BLEND: usize = 10;

/// Where along `b` the sequence `a` ends: the column of the cheapest warping path that
/// starts at both starts and covers all of `a` (open end in `b`).
fn open_end(a: &[Vec<f64>], b: &[Vec<f64>]) -> usize {
    open_end_cost(a, b).0
}

#[cfg(test)]
mod tests {
    use super::{new_demonstration_bound, t95};

    #[test]
    fn the_bound_of_a_new_demonstration_widens_with_the_spread_and_the_fewness_of_scores() {
        // Student's t: the table, and the expansion beyond it (exact: 1.6839 at 40)
        assert_eq!(t95(1), 6.314);
        assert_eq!(t95(6), 1.943);
        assert!((t95(40) - 1.6839).abs() < 1e-3, "{}", t95(40));
        assert!(t95(31) < t95(30) && t95(31) > t95(40));
        // equal scores: no spread, the bound is the score
        assert!((new_demonstration_bound(&[0.2; 6]) - 0.2).abs() < 1e-12);
        // never below the worst own score; above it when the scores spread
        let own = [0.02, 0.025, 0.03, 0.022, 0.028, 0.035];
        let b = new_demonstration_bound(&own);
        assert!(b > 0.035 && b < 0.06, "{b}");
        // fewer scores of the same spread: a wider bound
        assert!(new_demonstration_bound(&own[..3]) > new_demonstration_bound(&own[..3].repeat(2)));
        // one score: twice it; none: 0; a zero score: finite
        assert_eq!(new_demonstration_bound(&[0.1]), 0.2);
        assert_eq!(new_demonstration_bound(&[]), 0.0);
        assert!(new_demonstration_bound(&[0.0, 0.1, 0.12]).is_finite());
    }
}
