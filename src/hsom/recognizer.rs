//! Recognition in the loop (docs/ALGORITHM.md, section 4, item 7): a [`Recognizer`] takes a
//! sequence one sample at a time, commits to a label or to unknown as soon as the rule below
//! allows, never changes a committed answer, and at the end gives what
//! [`GestureModel::recognize`] gives on every sample pushed.
//!
//! Each label's score of the prefix pushed so far is the one recognition's early decision
//! reads: the open-ended DTW cost per sample against the label's reproduction from the first
//! posture, one row of the DTW per sample (O(reproduction length) a label a push). The rule
//! eliminates labels: a label is out once its prefix score passes its ceiling, the label's
//! threshold (what a whole new demonstration of it may score) times the model's rise (how far
//! above its whole score a prefix of one of the model's own kept demonstrations ever scored,
//! [`StreamCalibration`]). When one label is left, past its hold, and its prefix scores within
//! its threshold and within its own demonstrations' held-out prefixes that far into the
//! gesture, the recogniser commits to it; when none is left, to unknown.

use std::borrow::Borrow;

use crate::dtw::dtw_with_prefixes;
use crate::dtw::pruned::Reference;

use super::errors::{GestureError, HsomError};
use super::model::{EventsHsom, GestureModel, Scoring};
use super::recognize::{reproduction_from, weighed_pair, Recognition, Weighing};

/// What a [`Recognizer`] committed to.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Commit {
    /// The label, or `None` for unknown.
    pub label: Option<String>,
    /// The samples pushed when it committed (the sample it committed on, counted from 1).
    pub samples: usize,
}

/// What the model's own kept demonstrations say about prefixes (docs/ALGORITHM.md, section 4,
/// item 7). The **rise**: per stretch of the reproduction covered (one of [`RISE_BINS`]), the
/// largest ratio of a prefix's score (open-ended DTW per sample against the reproduction) to
/// the whole sequence's score (DTW per step), over every prefix ending in that stretch or
/// later of every kept demonstration of every label, each against its own label's
/// reproduction from its first posture; infinite (no label is ever ruled out early) when the
/// model keeps no demonstration to measure it on. The **holds**: per label, how far into its
/// reproduction a stream must be before the recogniser may commit to it, from the other
/// labels' kept demonstrations standing in for a gesture it never saw. The **envelope**: per
/// label, how far from its reproduction a prefix of a new demonstration of it may be that far
/// into the gesture, from its own kept demonstrations each scored by the label learned again
/// without it (a one-class check: a prefix farther than every held-out one is not this label
/// yet, whatever the other labels say).
#[derive(Debug, Clone, PartialEq)]
pub struct StreamCalibration {
    /// Per stretch of the reproduction covered, the largest prefix score over whole score.
    pub rise: Vec<f64>,
    /// Per label (in the model's order): the largest fraction of its reproduction at which a
    /// stand-in stream met the rule for committing to it.
    pub holds: Vec<f64>,
    /// Per label (in the model's order), per stretch of its reproduction covered (one of
    /// [`RISE_BINS`]): the largest prefix score of one of its kept demonstrations, each against
    /// the reproduction of the label learned again without it, over the prefixes ending in
    /// that stretch or later; infinite (no bound) where none was measured.
    pub envelope: Vec<Vec<f64>>,
}

/// The stretches of a reproduction the rise is measured on (twentieths: its resolution).
pub const RISE_BINS: usize = 20;

impl StreamCalibration {
    /// The prefix score above which label `g` (`threshold`) is out after `samples` samples
    /// against a reproduction of `m` samples (0 for a threshold of 0: out at the first miss).
    fn ceiling(&self, threshold: f64, samples: usize, m: usize) -> f64 {
        match threshold == 0.0 {
            true => 0.0,
            false => {
                threshold
                    * self
                        .rise
                        .get(bin(samples, m))
                        .copied()
                        .unwrap_or(f64::INFINITY)
            }
        }
    }

    /// The largest prefix score label `g`'s own held-out demonstrations reached after
    /// `samples` samples against a reproduction of `m` samples, or later.
    fn envelope(&self, g: usize, samples: usize, m: usize) -> f64 {
        (self.envelope.get(g))
            .and_then(|e| e.get(bin(samples, m)))
            .copied()
            .unwrap_or(f64::INFINITY)
    }
}

/// The stretch of a reproduction of `m` samples that `samples` samples cover.
fn bin(samples: usize, m: usize) -> usize {
    (samples * RISE_BINS / m.max(1)).min(RISE_BINS - 1)
}

/// Per stretch, the largest of `per` (a score per stretch a prefix ended in; NaN: none) over
/// that stretch and every later one; a stretch with no prefix takes the one before it, and
/// infinite where nothing was measured from there on.
fn from_here_on(mut per: Vec<f64>) -> Vec<f64> {
    for b in 1..per.len() {
        if per[b].is_nan() {
            per[b] = per[b - 1];
        }
    }
    let mut top = f64::NAN;
    for r in per.iter_mut().rev() {
        top = f64::max(top, *r);
        *r = if top.is_nan() { f64::INFINITY } else { top };
    }
    per
}

/// One label's open-ended DTW against its reproduction, a row per sample pushed.
struct Track {
    /// The reproduction from the first posture, normalised, stored for a row's distances
    /// (`None`: it could not be made).
    rep: Option<Reference>,
    /// The last row of accumulated costs, the row being filled, and its distances.
    prev: Vec<f64>,
    cur: Vec<f64>,
    dist: Vec<f64>,
    /// The prefix's cost per sample (infinite without a reproduction).
    score: f64,
    /// The prefix score passed the label's ceiling.
    out: bool,
    /// The label's weighing of a sample.
    k: Weighing,
}

impl Track {
    fn new(b: &EventsHsom, first: &[Vec<f64>]) -> Self {
        let rep = reproduction_from(b, first);
        let m = rep.as_ref().map_or(0, Vec::len);
        let k = rep.as_ref().map_or(
            Weighing {
                w: Vec::new(),
                rate: 0.0,
                span: 1,
            },
            |r| Weighing::of(b, r),
        );
        Track {
            rep: rep.map(|r| Reference::new(&k.rows(&r))),
            k,
            prev: vec![f64::INFINITY; m],
            cur: vec![f64::INFINITY; m],
            dist: vec![0.0; m],
            score: f64::INFINITY,
            out: false,
        }
    }

    /// The DTW's row for the last of the normalised samples pushed, `seen` (row `i`, the
    /// sample the weighing's span before it giving its change): the recurrence of
    /// [`dtw_with_prefixes`], so each prefix's score is the one it gives.
    fn step(&mut self, seen: &[Vec<f64>]) {
        let Some(rep) = &self.rep else { return };
        let m = rep.len();
        let i = seen.len() - 1;
        let prev = (i > 0).then(|| seen[i.saturating_sub(self.k.span)].as_slice());
        let y = self.k.row(&seen[i], prev);
        rep.distances(&y, 0, m, &mut self.dist);
        for (j, &c) in self.dist.iter().enumerate() {
            if i == 0 && j == 0 {
                self.cur[0] = c;
                continue;
            }
            let mut b = if i > 0 && j > 0 {
                self.prev[j - 1]
            } else {
                f64::INFINITY
            };
            let up = if i > 0 { self.prev[j] } else { f64::INFINITY };
            if up < b {
                b = up;
            }
            let left = if j > 0 {
                self.cur[j - 1]
            } else {
                f64::INFINITY
            };
            if left < b {
                b = left;
            }
            self.cur[j] = b + c;
        }
        std::mem::swap(&mut self.prev, &mut self.cur);
        let open = self.prev.iter().copied().fold(f64::INFINITY, f64::min);
        self.score = open / (i + 1) as f64;
    }
}

/// Recognition in the loop: push samples one at a time ([`Recognizer::push`]); the answer
/// once committed ([`Recognizer::commit`]) never changes; [`Recognizer::finish`] is
/// [`GestureModel::recognize`] on every sample pushed. `M` is the model or what holds it
/// (a reference, an `Arc`).
pub struct Recognizer<M: Borrow<GestureModel>> {
    model: M,
    /// When a label is out, and when one left may be committed to.
    calibration: StreamCalibration,
    rows: Vec<Vec<f64>>,
    /// The same samples normalised, which every label's track reads.
    norm: Vec<Vec<f64>>,
    tracks: Vec<Track>,
    commit: Option<Commit>,
}

impl GestureModel {
    /// [`StreamCalibration`] of this model, measured on the demonstrations it keeps.
    pub fn stream_calibration(&self) -> Result<StreamCalibration, GestureError> {
        let branches = self.labelled()?;
        // per label k, per kept demonstration of k, per label g: the demonstration against
        // g's reproduction from its first posture
        let scored: Vec<Vec<Vec<Option<Scored>>>> = branches
            .iter()
            .map(|b| {
                (kept_rows(b).iter())
                    .map(|rows| branches.iter().map(|g| Scored::of(g, rows)).collect())
                    .collect()
            })
            .collect();
        let mut rise = vec![f64::NAN; RISE_BINS];
        for (k, demos) in scored.iter().enumerate() {
            for s in demos.iter().filter_map(|d| d[k].as_ref()) {
                if !(s.whole > 0.0 && s.whole.is_finite()) {
                    continue;
                }
                for (i, p) in s.prefix.iter().enumerate() {
                    let b = bin(i + 1, s.reproduction);
                    rise[b] = f64::max(rise[b], p / s.whole);
                }
            }
        }
        let envelope = (branches.iter())
            .map(|b| held_out_envelope(b))
            .collect::<Result<_, _>>()?;
        let c = StreamCalibration {
            rise: from_here_on(rise),
            holds: Vec::new(),
            envelope,
        };
        let thresholds = self.thresholds();
        let mut holds = vec![0.0; branches.len()];
        for (k, demos) in scored.iter().enumerate() {
            for d in demos {
                // a stand-in for a gesture never seen: k's demonstration, k untaught
                let samples = d
                    .iter()
                    .flatten()
                    .map(|s| s.prefix.len())
                    .max()
                    .unwrap_or(0);
                let mut out: Vec<bool> = (0..d.len()).map(|g| g == k || d[g].is_none()).collect();
                for i in 0..samples {
                    let at = |g: usize| d[g].as_ref().map_or(f64::INFINITY, |s| s.prefix[i]);
                    let m = |g: usize| d[g].as_ref().map_or(1, |s| s.reproduction);
                    for (g, out) in out.iter_mut().enumerate() {
                        *out |= at(g).is_nan() || at(g) > c.ceiling(thresholds[g], i + 1, m(g));
                    }
                    let mut left = (0..d.len()).filter(|&g| !out[g]);
                    if let (Some(g), None) = (left.next(), left.next()) {
                        if at(g) <= thresholds[g] {
                            holds[g] = f64::max(holds[g], (i + 1) as f64 / m(g).max(1) as f64);
                        }
                    }
                }
            }
        }
        Ok(StreamCalibration { holds, ..c })
    }

    /// Per label (in the model's order), its threshold: the score above which a sequence is
    /// not that gesture.
    pub fn thresholds(&self) -> Vec<f64> {
        self.calibration.iter().map(|c| c.threshold).collect()
    }

    /// Per label (in the model's order), the share of the DTW's cells that recognition of
    /// `rows` skips (its exact pruning, [`crate::dtw::prefix_pruning_rate`]; docs/BENCHMARKS.md);
    /// `None` for a label whose gesture cannot be reproduced from the first posture.
    pub fn pruning_rates(&self, rows: &[Vec<f64>]) -> Result<Vec<Option<f64>>, GestureError> {
        let branches = self.labelled()?;
        let norm = branches[0].normalise_rows(rows);
        Ok(branches
            .iter()
            .map(|b| {
                reproduction_from(b, &norm).and_then(|r| crate::dtw::prefix_pruning_rate(&norm, &r))
            })
            .collect())
    }

    /// A recogniser in the loop on this model ([`Recognizer`]), calibrated on the
    /// demonstrations the model keeps ([`GestureModel::stream_calibration`]).
    pub fn recognizer(&self) -> Result<Recognizer<&GestureModel>, GestureError> {
        let c = self.stream_calibration()?;
        Recognizer::new(self, c)
    }
}

/// Rule out every label whose prefix score passed its ceiling (its threshold times the rise
/// at the stretch of its reproduction covered: for good, no recognisable demonstration of it
/// scored a prefix that high), then commit (after `samples` samples) when one label is left,
/// past its hold, within its threshold and within its envelope, or none is left (unknown).
fn decide(
    tracks: &mut [Track],
    c: &StreamCalibration,
    m: &GestureModel,
    samples: usize,
) -> Option<Commit> {
    let length = |t: &Track| t.rep.as_ref().map_or(1, |r| r.len());
    for (t, cal) in tracks.iter_mut().zip(&m.calibration) {
        if t.score.is_nan() || t.score > c.ceiling(cal.threshold, samples, length(t)) {
            t.out = true;
        }
    }
    let mut left = tracks.iter().enumerate().filter(|(_, t)| !t.out);
    let past = |k: usize, t: &Track| {
        samples as f64 / length(t).max(1) as f64 > c.holds.get(k).copied().unwrap_or(0.0)
    };
    match (left.next(), left.next()) {
        (None, _) => Some(Commit {
            label: None,
            samples,
        }),
        (Some((k, t)), None)
            if t.score <= m.calibration[k].threshold
                && t.score <= c.envelope(k, samples, length(t))
                && past(k, t) =>
        {
            Some(Commit {
                label: Some(m.labels[k].clone()),
                samples,
            })
        }
        _ => None,
    }
}

/// A sequence against one label's reproduction from its first posture.
struct Scored {
    /// Per prefix (index: its samples - 1), its open-ended score.
    prefix: Vec<f64>,
    /// The whole sequence's score.
    whole: f64,
    /// The reproduction's samples.
    reproduction: usize,
}

impl Scored {
    /// `rows` (normalised) against `b`'s reproduction; `None` when it cannot be made.
    fn of(b: &EventsHsom, rows: &[Vec<f64>]) -> Option<Self> {
        let (q, rep) = weighed_pair(b, rows)?;
        let (whole, prefix) = dtw_with_prefixes(&q, &rep).ok()?;
        Some(Scored {
            prefix,
            whole: whole.per_step(),
            reproduction: rep.len(),
        })
    }
}

/// [`StreamCalibration::envelope`] of one label's branch `b`: each kept demonstration's
/// prefixes against the reproduction of `b` learned again without it (as the label's
/// threshold is calibrated: bottom level and all; with two, on `b`'s own bottom, since a
/// bottom of one demonstration replays it); no bound with fewer than two.
fn held_out_envelope(b: &EventsHsom) -> Result<Vec<f64>, GestureError> {
    let kept = kept_rows(b);
    let learn = b.trained.first().is_some_and(|&t| t > 0);
    let seed = b.config.params().seed;
    let mut per = vec![f64::NAN; RISE_BINS];
    if kept.len() < 2 {
        return Ok(from_here_on(per));
    }
    for (i, own) in kept.iter().enumerate() {
        let rest: Vec<Vec<Vec<f64>>> = (kept.iter().enumerate())
            .filter(|&(j, _)| j != i)
            .map(|(_, d)| d.clone())
            .collect();
        let seed = super::recognize::branch_seed(seed, 0, Some(i));
        let without = match rest.len() {
            1 => b.build_branch(&rest, learn, seed),
            _ => b.without(&rest, learn, seed)?,
        };
        let Some(s) = Scored::of(&without, own) else {
            continue;
        };
        for (j, p) in s.prefix.iter().enumerate() {
            let k = bin(j + 1, s.reproduction);
            per[k] = f64::max(per[k], *p);
        }
    }
    Ok(from_here_on(per))
}

/// The kept demonstrations of `b` (normalised), each at its own length.
fn kept_rows(b: &EventsHsom) -> Vec<Vec<Vec<f64>>> {
    b.paths
        .iter()
        .zip(&b.kept.lengths)
        .filter(|(_, &n)| n >= 2)
        .map(|(path, &n)| {
            let n = n as usize;
            (0..n)
                .map(|k| crate::curve::at_phase(path, k as f64 / (n - 1) as f64))
                .collect()
        })
        .collect()
}

impl<M: Borrow<GestureModel>> Recognizer<M> {
    /// A recogniser on `model` with `calibration` (its own, [`GestureModel::stream_calibration`],
    /// measured once for many streams).
    pub fn new(model: M, calibration: StreamCalibration) -> Result<Self, GestureError> {
        let m = model.borrow();
        m.labelled()?;
        Ok(Recognizer {
            model,
            calibration,
            rows: Vec::new(),
            norm: Vec::new(),
            tracks: Vec::new(),
            commit: None,
        })
    }

    /// Push the next sample (in the data's units, the model's columns): the commitment once
    /// made (from the sample it was made on), `None` before. A sample of the wrong width or
    /// with a value that is not finite is refused and leaves the recogniser as it was.
    pub fn push(&mut self, sample: &[f64]) -> Result<Option<Commit>, GestureError> {
        let m = self.model.borrow();
        let branches = m.labelled()?;
        let shared = branches[0];
        let i = self.rows.len();
        let width = shared.columns.len();
        if sample.len() != width {
            return Err(HsomError::DimensionMismatch {
                demo: "the stream".into(),
                row: i,
                expected: width,
                found: sample.len(),
            }
            .into());
        }
        if let Some(c) = sample.iter().position(|v| !v.is_finite()) {
            return Err(HsomError::NonFinite {
                demo: "the stream".into(),
                row: i,
                column: c,
            }
            .into());
        }
        let x = shared.normalise(sample);
        if i == 0 {
            let first = std::slice::from_ref(&x);
            self.tracks = branches.iter().map(|b| Track::new(b, first)).collect();
        }
        self.rows.push(sample.to_vec());
        self.norm.push(x);
        for t in &mut self.tracks {
            t.step(&self.norm);
        }
        if self.commit.is_none() && m.scoring == Scoring::Reproduction {
            self.commit = decide(&mut self.tracks, &self.calibration, m, self.rows.len());
        }
        Ok(self.commit.clone())
    }

    /// The commitment, once made.
    pub fn commit(&self) -> Option<&Commit> {
        self.commit.as_ref()
    }

    /// Whether the recogniser has committed (to a label or to unknown).
    pub fn decided(&self) -> bool {
        self.commit.is_some()
    }

    /// Per label (in the model's order), the score of the prefix pushed so far (empty before
    /// the first sample).
    pub fn prefix_scores(&self) -> Vec<f64> {
        self.tracks.iter().map(|t| t.score).collect()
    }

    /// The samples pushed so far.
    pub fn samples(&self) -> usize {
        self.rows.len()
    }

    /// The whole sequence's answer: [`GestureModel::recognize`] on every sample pushed
    /// (refused, as it refuses, with fewer than 2).
    pub fn finish(&self) -> Result<Recognition, GestureError> {
        self.model.borrow().recognize(&self.rows)
    }
}
