//! Recognition with a multi-gesture hierarchy (docs/ALGORITHM.md, section 4): each label's
//! branch reproduces its gesture from the sequence's first posture, and the label's score is
//! the sequence's DTW distance per step from that reproduction (a prefix: with an open end).
//! The lowest score wins; above the label's threshold (what a new demonstration of it may
//! score, from its own demonstrations held out), the answer is `unknown`. The scores of the
//! levels' chunks and of the bottom's postures ([`Scoring`]) remain for comparison.

use rayon::iter::{IntoParallelRefIterator, ParallelIterator};

use crate::dtw::{argmin, dtw_distance, dtw_with_prefixes, open_end_cost, Band};

use super::errors::{GestureError, HsomError};
use super::events::{
    a_part, b_part, bottom_events, chunk_input, chunks, summary, used, DurationCode, Item,
};
use super::inputs::{check_series, Layout, Series};
use super::model::{Calibration, EventsHsom, GestureModel, Scoring};
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
/// (the branch's event durations say which nodes its gesture visited).
pub(crate) fn posture_distances(model: &EventsHsom, norm: &[Vec<f64>]) -> Vec<f64> {
    let map = &model.maps[0];
    let used = used(model, 0);
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

/// `model`'s gesture reproduced from the first posture of `norm` (normalised rows), normalised;
/// `None` when it cannot be reproduced from there.
pub(super) fn reproduction_from(model: &EventsHsom, norm: &[Vec<f64>]) -> Option<Vec<Vec<f64>>> {
    let rep = model.reproduce(&model.denormalise(norm.first()?)).ok()?;
    (!rep.postures.is_empty()).then(|| model.normalise_rows(&rep.postures))
}

/// Per variable, how much a gesture moves it: over its demonstrations `paths` (normalised,
/// `dim` variables), the mean of each one's standard deviation over time.
fn activity(paths: &[Vec<Vec<f64>>], dim: usize) -> Vec<f64> {
    let mut a = vec![0.0; dim];
    let paths: Vec<&Vec<Vec<f64>>> = paths.iter().filter(|p| p.len() >= 2).collect();
    for path in &paths {
        let n = path.len() as f64;
        for (v, a) in a.iter_mut().enumerate() {
            let mean = path.iter().map(|r| r[v]).sum::<f64>() / n;
            let var = path.iter().map(|r| (r[v] - mean).powi(2)).sum::<f64>() / n;
            *a += var.sqrt() / paths.len() as f64;
        }
    }
    a
}

/// A label's weights of the variables in its score (docs/ALGORITHM.md, section 4, item 3),
/// from its demonstrations `paths`: half 1, half the variable's activity over the mean
/// activity, so the weights average 1 and a variable the gesture holds still counts (a
/// sequence that moves it is not the gesture); every weight 1 when the gesture moves nothing.
pub(crate) fn weights(paths: &[Vec<Vec<f64>>], dim: usize) -> Vec<f64> {
    let a = activity(paths, dim);
    let mean = a.iter().sum::<f64>() / a.len().max(1) as f64;
    if !(mean > 0.0 && mean.is_finite()) {
        return vec![1.0; a.len()];
    }
    a.iter().map(|x| 0.5 * (1.0 + x / mean)).collect()
}

/// How a label weighs a sequence: each variable's value scaled by the square root of its
/// weight, then each variable's change over `span` samples (from the first sample before
/// that; 0 at the first) scaled by `rate`; Euclidean distances between such rows are the
/// weighted ones.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Weighing {
    pub(crate) w: Vec<f64>,
    pub(crate) rate: f64,
    pub(crate) span: usize,
}

impl Weighing {
    /// `model`'s weighing ([`Weighing::with`] its weights from the demonstrations it keeps,
    /// its changes over the bottom's `actionHorizon`).
    pub(crate) fn of(model: &EventsHsom, rep: &[Vec<f64>]) -> Self {
        let span = model.config.params().action_horizon();
        Self::with(weights(&model.paths, model.columns.len()), rep, span)
    }

    /// Weights `w`, and the scale of the changes that makes their spread over `rep` (the
    /// label's reproduction) the weighed values' spread, so the shape of the motion and where
    /// it goes count alike.
    pub(crate) fn with(w: Vec<f64>, rep: &[Vec<f64>], span: usize) -> Self {
        let span = span.max(1);
        let n = rep.len().max(1) as f64;
        let (mut values, mut changes) = (0.0, 0.0);
        for (v, w) in w.iter().enumerate() {
            let m = rep.iter().map(|r| r[v]).sum::<f64>() / n;
            values += w * rep.iter().map(|r| (r[v] - m).powi(2)).sum::<f64>() / n;
            changes += (rep.iter().zip(rep.iter().skip(span)))
                .map(|(a, b)| (b[v] - a[v]).powi(2))
                .sum::<f64>()
                / n;
        }
        let rate = if changes > 0.0 {
            (values / changes).sqrt()
        } else {
            0.0
        };
        Weighing { w, rate, span }
    }

    /// One row weighed, `prev` the sample `span` before it (the first one, closer to the
    /// start; `None` at the first).
    pub(crate) fn row(&self, x: &[f64], prev: Option<&[f64]>) -> Vec<f64> {
        let mut out: Vec<f64> = x.iter().zip(&self.w).map(|(x, w)| x * w.sqrt()).collect();
        out.extend(
            x.iter()
                .enumerate()
                .map(|(v, x)| prev.map_or(0.0, |p| self.rate * (x - p[v]))),
        );
        out
    }

    /// Rows weighed.
    pub(crate) fn rows(&self, rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
        (0..rows.len())
            .map(|t| {
                let prev = (t > 0).then(|| rows[t.saturating_sub(self.span)].as_slice());
                self.row(&rows[t], prev)
            })
            .collect()
    }
}

/// Rows of a sequence.
type Rows = Vec<Vec<f64>>;

/// `norm` (normalised rows) and `model`'s reproduction from its first posture, both weighed
/// by the label's weighing; `None` when it cannot be reproduced.
pub(super) fn weighed_pair(model: &EventsHsom, norm: &[Vec<f64>]) -> Option<(Rows, Rows)> {
    let rep = reproduction_from(model, norm)?;
    let k = Weighing::of(model, &rep);
    Some((k.rows(norm), k.rows(&rep)))
}

/// The weighted DTW distance per step between `norm` and `model`'s gesture reproduced from
/// its first posture (infinite when it cannot be reproduced).
fn reproduction_distance(model: &EventsHsom, norm: &[Vec<f64>]) -> f64 {
    weighed_pair(model, norm)
        .and_then(|(q, r)| dtw_distance(&q, &r, Band::None).ok())
        .map_or(f64::INFINITY, |c| c.per_step())
}

/// The mean of the first `n` values (`None` when there are none).
fn mean_of(v: &[f64], n: usize) -> Option<f64> {
    let n = n.min(v.len());
    (n > 0).then(|| v[..n].iter().sum::<f64>() / n as f64)
}

/// Level distances of a whole normalised sequence: the postures' at level 0, then the
/// levels' chunks ([`level_distances`]).
fn all_distances(
    model: &EventsHsom,
    norm: &[Vec<f64>],
    events: &[(usize, f64)],
) -> Vec<Option<f64>> {
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
    model: &EventsHsom,
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

/// The one-sided 99 % quantile of Student's t with `df` degrees of freedom (at least 1), to
/// three decimals as the printed tables give it (31.821 at 1, 2.423 at 40), which the
/// recognisers' bounds are calibrated with.
fn t99(df: usize) -> f64 {
    use statrs::distribution::{ContinuousCDF, StudentsT};
    // cannot fail: location 0, scale 1 and at least one degree of freedom are valid
    let t = StudentsT::new(0.0, 1.0, df.max(1) as f64).map_or(f64::NAN, |t| t.inverse_cdf(0.99));
    (t * 1e3).round() / 1e3
}

/// What a new demonstration of each gesture may score: from `own` (per label, its
/// demonstrations' held-out scores), the upper 99 % prediction bound of one more score. The scores are taken as log-normal (distances,
/// whose spread grows with their size), located at the label's median (one own score of a
/// branch that reproduced badly without it does not move the bound) with one spread pooled
/// over every label (how much one person's drawings of a gesture vary, estimated from all of
/// them rather than from a handful each). 99 %: the bound must let through more new
/// demonstrations than the acceptance gate asks (97 %). Without any spread to estimate (one
/// score per label), twice the worst.
pub(crate) fn new_demonstration_bounds(own: &[Vec<f64>]) -> Vec<f64> {
    let worst: Vec<f64> = own
        .iter()
        .map(|o| o.iter().cloned().fold(0.0, f64::max))
        .collect();
    // a score of 0 (a demonstration repeated exactly) would make the log spread infinite
    let logs: Vec<Vec<f64>> = own
        .iter()
        .zip(&worst)
        .map(|(o, w)| o.iter().map(|&s| s.max(w * 1e-6).ln()).collect())
        .collect();
    let means: Vec<f64> = logs
        .iter()
        .map(|l| l.iter().sum::<f64>() / l.len().max(1) as f64)
        .collect();
    let scores: usize = own.iter().map(Vec::len).sum();
    let labels = own.iter().filter(|o| !o.is_empty()).count();
    if scores <= labels {
        return worst.iter().map(|w| 2.0 * w).collect();
    }
    let df = scores - labels;
    let squares: f64 = logs
        .iter()
        .zip(&means)
        .flat_map(|(l, m)| l.iter().map(move |x| (x - m).powi(2)))
        .sum();
    let spread = (squares / df as f64).sqrt();
    let t = t99(df);
    logs.iter()
        .zip(&worst)
        .map(|(l, &w)| {
            let bound = (crate::stats::median(l.iter().copied()).unwrap_or(0.0)
                + t * spread * (1.0 + 1.0 / l.len().max(1) as f64).sqrt())
            .exp();
            if bound.is_finite() {
                bound
            } else {
                w
            }
        })
        .collect()
}

/// The calibration of every label: its held-out references (each own demonstration scored
/// by a branch trained without it: leave-one-out; in-sample for a label with one
/// demonstration), and its threshold: what a new demonstration of the gesture may score, from
/// those own held-out scores ([`new_demonstration_bounds`]).
pub(crate) fn calibrate(
    branches: &[EventsHsom],
    norm: &[Vec<Vec<Vec<f64>>>],
    learn: bool,
    seed: u64,
) -> Result<Vec<Calibration>, HsomError> {
    let h = branches[0].maps.len();
    let mut per: Vec<(Vec<f64>, Vec<f64>)> = Vec::with_capacity(branches.len());
    for g in 0..branches.len() {
        // each own demonstration's branch: trained without it, bottom level and all; with
        // one demonstration left, its levels on the label's own bottom (a bottom trained on
        // one demonstration replays it, a stand-in unlike a model that averages several);
        // with it, when alone
        let loo: Vec<EventsHsom> = match norm[g].len() {
            0 | 1 => vec![branches[g].clone()],
            n => (0..n)
                .map(|i| {
                    let rest: Vec<Vec<Vec<f64>>> = (norm[g].iter().enumerate())
                        .filter(|&(j, _)| j != i)
                        .map(|(_, d)| d.clone())
                        .collect();
                    let seed = branch_seed(seed, g, Some(i));
                    match n {
                        2 => Ok(branches[g].build_branch(&rest, learn, seed)),
                        _ => branches[g].without(&rest, learn, seed),
                    }
                })
                .collect::<Result<_, _>>()?,
        };
        let own: Vec<Vec<Option<f64>>> = (loo.iter().zip(&norm[g]))
            .map(|(b, n)| all_distances(b, n, &bottom_events(b, n)))
            .collect();
        let reference = level_means(&own, h);
        let scoring = Scoring::default();
        let own_scores: Vec<f64> = match scoring {
            Scoring::Reproduction => (loo.iter().zip(&norm[g]))
                .map(|(b, n)| reproduction_distance(b, n))
                .collect(),
            _ => own.iter().map(|d| scoring.score(d, &reference)).collect(),
        };
        let own_scores: Vec<f64> = own_scores.into_iter().filter(|v| v.is_finite()).collect();
        per.push((reference, own_scores));
    }
    let own: Vec<Vec<f64>> = per.iter().map(|p| p.1.clone()).collect();
    Ok(per
        .into_iter()
        .zip(new_demonstration_bounds(&own))
        .map(|((reference, _), threshold)| Calibration {
            reference,
            threshold,
        })
        .collect())
}

/// How many of a label's heaviest variables a [`Recognition`] names.
pub const WEIGHED_SHOWN: usize = 3;

/// `model`'s heaviest variables and their weights ([`Recognition::weighed`]).
fn weighed_most(model: &EventsHsom) -> Vec<(String, f64)> {
    let w = weights(&model.paths, model.columns.len());
    let mut w: Vec<(String, f64)> = model.columns.iter().cloned().zip(w).collect();
    w.sort_by(|a, b| b.1.total_cmp(&a.1));
    w.truncate(WEIGHED_SHOWN);
    w
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
    /// Per label (in the model's order): the variables its score weighs most, at most
    /// [`WEIGHED_SHOWN`], heaviest first, each with its weight (a label's weights average 1:
    /// what its gesture moves weighs more than what it holds).
    pub weighed: Vec<Vec<(String, f64)>>,
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

/// What a sequence is scored on against one label.
struct Evidence {
    /// Per sample, the distance to the nearest posture the gesture used (scoring by postures
    /// or levels).
    postures: Vec<f64>,
    /// The whole sequence's DTW distance per step from the reproduction (scoring by
    /// reproduction).
    whole: f64,
    /// Per prefix (index: its samples - 1), its open-ended DTW cost per sample against the
    /// reproduction (scoring by reproduction).
    prefix: Vec<f64>,
}

impl GestureModel {
    /// The branches of a model of several gestures: the events extension's (so trained, and
    /// checked on loading).
    pub(super) fn labelled(&self) -> Result<Vec<&EventsHsom>, GestureError> {
        if self.labels.is_empty() {
            return Err(GestureError::NoLabels);
        }
        if self.calibration.len() != self.labels.len() {
            return Err(GestureError::Recalibrate);
        }
        self.branches
            .iter()
            .map(|b| b.as_events().ok_or(GestureError::NeedsEvents))
            .collect()
    }

    /// The branches, the normalised rows (every branch has the same units) and their bottom
    /// events in each branch (none for the scores by reproduction), after checking the rows.
    #[allow(clippy::type_complexity)]
    fn checked_events(
        &self,
        rows: &[Vec<f64>],
    ) -> Result<(Vec<&EventsHsom>, Vec<Vec<f64>>, Vec<Vec<(usize, f64)>>), GestureError> {
        let branches = self.labelled()?;
        // a sequence of at least 2 samples (an action horizon of 1)
        let sequence = Series {
            source: "the sequence",
            rows,
        };
        check_series(&[sequence], branches[0].columns.len(), 1)?;
        let norm = branches[0].normalise_rows(rows);
        // the scores by reproduction read no events (recognize finds its decision points
        // in the named gesture's own)
        let ev = (branches.iter())
            .map(|b| match self.scoring {
                Scoring::Reproduction => Vec::new(),
                _ => bottom_events(b, &norm),
            })
            .collect();
        Ok((branches, norm, ev))
    }

    /// Per label, what a normalised sequence is scored on: its per-sample posture distances,
    /// or (scoring by reproduction) the gesture reproduced from its first posture.
    fn evidence_of(&self, branches: &[&EventsHsom], norm: &[Vec<f64>]) -> Vec<Evidence> {
        // the labels side by side (rayon: within a study's pool on its threads, elsewhere on
        // one a core); each label's evidence is its own, so the answers are the same
        branches
            .par_iter()
            .map(|b| match self.scoring {
                Scoring::Reproduction => {
                    let d = weighed_pair(b, norm).and_then(|(q, r)| dtw_with_prefixes(&q, &r).ok());
                    Evidence {
                        postures: Vec::new(),
                        whole: d.as_ref().map_or(f64::INFINITY, |(c, _)| c.per_step()),
                        prefix: d.map_or_else(|| vec![f64::INFINITY; norm.len()], |(_, p)| p),
                    }
                }
                _ => Evidence {
                    postures: posture_distances(b, norm),
                    whole: f64::INFINITY,
                    prefix: Vec::new(),
                },
            })
            .collect()
    }

    /// Per label, the score of the first `samples` samples (`evidence`) and of the bottom
    /// events in its branch (`events`) complete within them; `complete`: the sequence ends
    /// there.
    fn scores_of(
        &self,
        branches: &[&EventsHsom],
        evidence: &[Evidence],
        samples: usize,
        events: &[Vec<(usize, f64)>],
        complete: bool,
    ) -> Vec<f64> {
        branches
            .iter()
            .zip(&self.calibration)
            .zip(evidence)
            .zip(events)
            .map(|(((b, c), e), events)| match self.scoring {
                Scoring::Reproduction if complete => e.whole,
                Scoring::Reproduction => e.prefix[samples.clamp(1, e.prefix.len()) - 1],
                _ => {
                    let mut d = if self.scoring == Scoring::Postures {
                        vec![None; b.maps.len()]
                    } else {
                        level_distances(b, completed(events, samples), complete)
                    };
                    d[0] = mean_of(&e.postures, samples);
                    self.scoring.score(&d, &c.reference)
                }
            })
            .collect()
    }

    /// Per label (in the model's order), the score of a whole sequence (rows in the data's
    /// units): lower is closer (1 is as close as the label's training data only with
    /// [`Scoring::Relative`]; the default scores the distance from the reproduction).
    pub fn scores(&self, rows: &[Vec<f64>]) -> Result<Vec<f64>, GestureError> {
        let (branches, norm, ev) = self.checked_events(rows)?;
        let p = self.evidence_of(&branches, &norm);
        Ok(self.scores_of(&branches, &p, rows.len(), &ev, true))
    }

    /// Recognise a whole sequence: the best label or unknown, every score, and the earliest
    /// sample from which the best label stayed the same (each prefix scored on the bottom
    /// events it has completed, available `actionHorizon` samples after they end).
    pub fn recognize(&self, rows: &[Vec<f64>]) -> Result<Recognition, GestureError> {
        let (branches, norm, ev) = self.checked_events(rows)?;
        let post = self.evidence_of(&branches, &norm);
        let fin = self.scores_of(&branches, &post, rows.len(), &ev, true);
        let best = argmin(&fin);
        let horizon = branches[0].config.params().action_horizon();
        let mut decided_at = rows.len();
        // the prefixes ending with the named gesture's events
        let mut done = 0.0;
        let named = match ev[best].is_empty() {
            true => bottom_events(branches[best], &norm),
            false => ev[best].clone(),
        };
        let mut ends = Vec::with_capacity(named.len());
        for &(_, d) in &named {
            done += d;
            ends.push(done);
        }
        for &end in ends.iter().rev() {
            let at = ((end as usize) + horizon).min(rows.len());
            let prefix = self.scores_of(&branches, &post, end as usize, &ev, false);
            if argmin(&prefix) != best {
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
            weighed: branches.iter().map(|b| weighed_most(b)).collect(),
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
        let (branches, norm, ev) = self.checked_events(prefix)?;
        let post = self.evidence_of(&branches, &norm);
        let g = argmin(&self.scores_of(&branches, &post, prefix.len(), &ev, false));
        let rep = branches[g].reproduce(&prefix[0])?;
        // where the prefix ends along the reproduction: DTW with an open end in it
        let j = open_end_cost(prefix, &rep.postures).0;
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

/// The first of `events` (node, samples) complete within `samples` samples.
fn completed(events: &[(usize, f64)], samples: usize) -> &[(usize, f64)] {
    let mut done = 0.0;
    let n = (events.iter())
        .take_while(|(_, d)| {
            done += d;
            done as usize <= samples
        })
        .count();
    &events[..n]
}

/// Samples over which a continued prefix closes the gap to the reproduction (0.25 s at the
/// recordings' 40 Hz).
pub const PREFIX_BLEND: usize = 10;

#[cfg(test)]
mod tests;
