//! The paper's reproduction from an initial posture (paper III-C.2, Table I): the levels'
//! predictions through activity lists (or, as the baseline, activity levels), decoded to the
//! bottom's next posture. [`Model::reproduce`] starts here for both algorithms and hands the
//! events extension's models to [`super::events`]. See docs/ALGORITHM.md for every choice the
//! paper leaves open.

use crate::config::{
    ConfigError, HsomParams, IdDecoding, MemoryMode, PaperParams, ReproductionParams, StopRule,
    PAPER_MIN_LENGTH_FRACTION, PAPER_STATIONARY_STEPS, PAPER_STATIONARY_TOLERANCE,
};

use super::errors::HsomError;
use super::inputs::{bmu_known, level_buffers};
use super::memory::{Activity, Stm};
use super::model::{Model, PaperHsom, Part};
use super::reproduction::{Reproduction, StopReason};

struct Gen<'a> {
    m: &'a PaperHsom,
    /// Per bottom node, how many demonstrations end on it ([`PaperModel`]).
    ends: &'a [u32],
    r: &'a ReproductionParams,
    q: &'a PaperParams,
    stm: Stm,
    s: u64,
    out: Vec<Vec<f64>>,
    by: Vec<usize>,
    last_node: usize,
    bufs: Vec<Vec<f64>>,
    masks: Vec<Vec<bool>>,
    min_len: usize,
    /// Bottom quantization error in normalised units.
    qe0: f64,
}

impl Gen<'_> {
    /// Turn a predicted (real-valued) ID into a node index of `level`.
    fn decode(&self, level: usize, wx: f64, wy: f64) -> usize {
        let map = &self.m.maps[level];
        let (cols, rows) = (map.cols() as f64, map.rows() as f64);
        let hits = &self.m.hits[level];
        let any_used = hits.iter().any(|&h| h > 0);
        let nearest_used = |x: f64, y: f64| -> usize {
            let mut best = (0usize, f64::INFINITY);
            for (i, &h) in hits.iter().enumerate() {
                if any_used && h == 0 {
                    continue;
                }
                let (ix, iy) = map.id(i);
                let d = (ix as f64 - x).powi(2) + (iy as f64 - y).powi(2);
                if d < best.1 {
                    best = (i, d);
                }
            }
            best.0
        };
        let wx = if wx.is_finite() { wx } else { 0.0 };
        let wy = if wy.is_finite() { wy } else { 0.0 };
        let idx = match self.q.id_decoding {
            IdDecoding::Nearest => return nearest_used(wx, wy),
            IdDecoding::Round => {
                let x = wx.round().clamp(0.0, cols - 1.0) as u16;
                let y = wy.round().clamp(0.0, rows - 1.0) as u16;
                map.index((x, y))
            }
            IdDecoding::Floor => {
                let x = (wx + 1e-9).floor().clamp(0.0, cols - 1.0) as u16;
                let y = (wy + 1e-9).floor().clamp(0.0, rows - 1.0) as u16;
                map.index((x, y))
            }
        };
        // a node the training data never used is replaced by the nearest used one
        if any_used && hits[idx] == 0 {
            nearest_used(wx, wy)
        } else {
            idx
        }
    }

    /// Children of node `node` of `level` (>= 1) in the level below, oldest first.
    fn children(&self, level: usize, node: usize) -> Vec<usize> {
        let w = self.m.maps[level].weights(node);
        match self.stm.mem {
            Activity::Lists(_) => {
                let slots = w.len() / 2;
                (0..slots)
                    .rev()
                    .map(|k| self.decode(level - 1, w[2 * k], w[2 * k + 1]))
                    .collect()
            }
            Activity::Levels(_) => {
                let memory = self.stm.memory;
                let thr = 0.5 / memory as f64;
                let mut idx: Vec<usize> = (0..w.len()).filter(|&j| w[j] > thr).collect();
                idx.sort_by(|&a, &b| w[b].total_cmp(&w[a]).then(a.cmp(&b)));
                idx.truncate(memory);
                if idx.is_empty() {
                    let best = (0..w.len())
                        .max_by(|&a, &b| w[a].total_cmp(&w[b]))
                        .unwrap_or(0);
                    idx.push(best);
                }
                idx.reverse();
                idx
            }
        }
    }

    /// Depth-first expansion of a node of `level` into bottom nodes, oldest first. With
    /// `strided` (activity levels, whose nodes stand for overlapping windows), every child
    /// after the first adds only the bottom steps it covers beyond its predecessor (its newest
    /// updatePeriod^(level-1) steps). At most `cap` nodes.
    fn expand(&self, level: usize, node: usize, strided: bool, cap: usize, out: &mut Vec<usize>) {
        if level == 0 {
            out.push(node);
            return;
        }
        let period = self.m.config.period(level - 1) as usize;
        for (i, c) in self.children(level, node).into_iter().enumerate() {
            if out.len() >= cap {
                return;
            }
            if strided && i > 0 {
                let mut e = Vec::new();
                self.expand(level - 1, c, strided, cap, &mut e);
                let k = e.len().saturating_sub(period);
                out.extend_from_slice(&e[k..]);
            } else {
                self.expand(level - 1, c, strided, cap, out);
            }
        }
        out.truncate(cap);
    }

    /// Level `level` (>= 1) predicts the next entries of the memory of `level - 1`, oldest
    /// first, or `None` when it has too little history or is confused.
    fn predict(&mut self, level: usize) -> Option<Vec<usize>> {
        let below = level - 1;
        let n = self.stm.pushes[below];
        if n < self.q.offset {
            return None;
        }
        let memory = self.stm.memory;
        if memory < 2 {
            return None;
        }
        let map = &self.m.maps[level];
        match &self.stm.mem {
            Activity::Lists(lists) => {
                let k = lists[below].len().min(memory - 1);
                if k == 0 {
                    return None;
                }
                let shift = memory - k;
                let (x, mask) = (&mut self.bufs[level], &mut self.masks[level]);
                lists[below].encode(k, shift, x, mask);
                let (b, _) = map.bmu_masked(x, mask);
                let w = map.weights(b);
                Some(
                    (0..shift)
                        .rev()
                        .map(|s| self.decode(below, w[2 * s], w[2 * s + 1]))
                        .collect(),
                )
            }
            Activity::Levels(levels) => {
                let a = levels[below].levels();
                let dec = levels[below].decrement();
                let x = &mut self.bufs[level];
                for (xi, ai) in x.iter_mut().zip(a) {
                    *xi = (ai - dec).max(0.0);
                }
                let (b, _) = map.bmu(x);
                let w = map.weights(b);
                let next = (0..w.len())
                    .max_by(|&i, &j| (w[i] - x[i]).total_cmp(&(w[j] - x[j])).then(j.cmp(&i)))
                    .unwrap_or(0);
                Some(vec![next])
            }
        }
    }

    /// Execute bottom node `node`: its action half is the next posture; push it and climb
    /// the schedule.
    fn emit(
        &mut self,
        node: usize,
        by: usize,
        skip: Option<usize>,
        pending: Option<(usize, usize)>,
    ) {
        let p = self.m.config.params();
        let state = p.state_length;
        let w = self.m.maps[0].weights(node);
        // the node's action half, reached from the current posture in one step
        let cur = self.out.last().cloned().unwrap_or_default();
        let y = cur
            .iter()
            .zip(&w[state..2 * state])
            .map(|(a, b)| a + (b - a));
        self.out.push(y.collect());
        self.by.push(by);
        self.stm.push_bottom(node, &self.m.maps[0]);
        self.s += 1;
        self.last_node = node;
        for l in 1..p.height {
            if let Some((pl, pn)) = pending {
                if pl == l {
                    self.stm.push(l, pn, &self.m.maps[l]);
                    continue;
                }
            }
            if skip == Some(l) || self.s % self.m.config.period(l) != 0 {
                continue;
            }
            let (x, mask) = (&mut self.bufs[l], &mut self.masks[l]);
            if !self.stm.input(l - 1, x, mask) {
                continue;
            }
            let (b, _, _) = bmu_known(&self.m.maps[l], x, mask);
            self.stm.push(l, b, &self.m.maps[l]);
        }
    }

    fn stop(&self) -> Option<StopReason> {
        let t = self.out.len();
        if t >= self.r.max_length {
            return Some(StopReason::MaxLength);
        }
        if self.q.stop == StopRule::Learned && t >= self.min_len {
            let state = self.m.config.params().state_length;
            let y = &self.out[t - 1];
            let (near, _) = self.m.maps[0].bmu_range(y, state..2 * state);
            if self.ends[self.last_node] > 0 || self.ends[near] > 0 {
                return Some(StopReason::EndNode);
            }
            let k = PAPER_STATIONARY_STEPS;
            if t > k {
                let win = &self.out[t - k - 1..];
                let tol = PAPER_STATIONARY_TOLERANCE * self.qe0;
                let still = if tol <= 0.0 {
                    win.windows(2).all(|w| w[0] == w[1])
                } else {
                    let n = win.len() as f64;
                    let mean: Vec<f64> = (0..state)
                        .map(|d| win.iter().map(|y| y[d]).sum::<f64>() / n)
                        .collect();
                    win.iter().all(|y| {
                        y.iter()
                            .zip(&mean)
                            .map(|(a, b)| (a - b) * (a - b))
                            .sum::<f64>()
                            <= tol * tol
                    })
                };
                if still {
                    return Some(StopReason::Stationary);
                }
            }
            if t as f64 >= self.r.length_factor * self.m.demo_len[2] {
                return Some(StopReason::LearnedLength);
            }
        }
        None
    }
}

impl<A: Part> Model<A> {
    /// An initial posture a reproduction can start from: `stateLength` finite values.
    pub(crate) fn check_initial(&self, initial: &[f64]) -> Result<(), HsomError> {
        let state = self.config.params().state_length;
        if initial.len() != state {
            return Err(HsomError::DimensionMismatch {
                demo: "initial posture".into(),
                row: 0,
                expected: state,
                found: initial.len(),
            });
        }
        if let Some(c) = initial.iter().position(|v| !v.is_finite()) {
            return Err(HsomError::NonFinite {
                demo: "initial posture".into(),
                row: 0,
                column: c,
            });
        }
        Ok(())
    }

    /// Reproduce the learned gesture from `initial` (a posture of `stateLength` values, in the
    /// data's units) with the configuration's reproduction settings: the paper's reproduction
    /// ([`PaperHsom::reproduce_paper`]) or the events extension's.
    pub(crate) fn reproduce(&self, initial: &[f64]) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        self.check_initial(initial)?;
        let y0 = self.normalise(initial);
        let mut rep = A::reproduce(self, y0, p)?;
        rep.truncate(p.reproduction.max_length);
        Ok(rep)
    }
}

impl PaperHsom {
    /// The paper's reproduction from the normalised posture `y0` with the settings `p`.
    pub(crate) fn reproduce_paper(
        &self,
        y0: Vec<f64>,
        p: &HsomParams,
    ) -> Result<Reproduction, HsomError> {
        let state = p.state_length;
        let r = &p.reproduction;
        // a paper model's configuration is the paper's: so trained, and checked on loading
        let Some(q) = p.paper() else {
            return Err(HsomError::Config(ConfigError::Invalid {
                file: self.config.source().to_string(),
                field: "algorithm".into(),
                value: p.kind().name(),
                reason: "the model holds the paper's algorithm's part".into(),
            }));
        };
        let ends = &self.part.end_hits;
        let (bufs, masks) = level_buffers(&self.config);
        let mut g = Gen {
            m: self,
            ends,
            r,
            q,
            stm: Stm::new(&self.config),
            s: 0,
            out: vec![y0],
            by: vec![0],
            last_node: 0,
            bufs,
            masks,
            qe0: if p.normalisation == crate::config::Normalisation::PerDimension {
                self.qe[0]
            } else {
                self.qe[0] / self.scale[0]
            },
            min_len: (PAPER_MIN_LENGTH_FRACTION * self.demo_len[0])
                .ceil()
                .max(2.0) as usize,
        };
        let strided = q.memory_mode == MemoryMode::Levels;
        let top = r.max_level.unwrap_or(p.height - 1).min(p.height - 1);
        let reason = 'outer: loop {
            if g.out.len() > 1 {
                if let Some(reason) = g.stop() {
                    break reason;
                }
            } else if r.max_length <= 1 {
                break StopReason::MaxLength;
            }
            let before = g.s;
            let mut done = false;
            for l in (1..=top).rev() {
                let period = self.config.period(l - 1);
                if strided && g.s % period != 0 {
                    continue;
                }
                let Some(preds) = g.predict(l) else { continue };
                for pred in preds {
                    let cap = r.max_length.saturating_sub(g.out.len()).max(1);
                    let mut bottom = Vec::new();
                    g.expand(
                        l - 1,
                        pred,
                        strided,
                        if strided { usize::MAX } else { cap },
                        &mut bottom,
                    );
                    if strided {
                        let k = bottom.len().saturating_sub(period as usize);
                        bottom.drain(..k);
                    }
                    let n = bottom.len();
                    for (j, node) in bottom.into_iter().enumerate() {
                        let below = l - 1;
                        let pending = (j + 1 == n && below >= 1).then_some((below, pred));
                        g.emit(node, l, (below >= 1).then_some(below), pending);
                        if g.out.len() > 1 {
                            if let Some(reason) = g.stop() {
                                break 'outer reason;
                            }
                        }
                    }
                }
                done = true;
                break;
            }
            // no level could predict (or its prediction expanded to nothing): the reflex
            // executes the BMU of the current posture
            if !done || g.s == before {
                let y = g.out.last().cloned().unwrap_or_default();
                let (b, _) = self.maps[0].bmu_range(&y, 0..state);
                g.emit(b, 0, None, None);
            }
        };
        g.out.truncate(r.max_length);
        g.by.truncate(r.max_length);
        let postures: Vec<Vec<f64>> = g.out.iter().map(|y| self.denormalise(y)).collect();
        Ok(Reproduction {
            steps: (0..postures.len()).collect(),
            postures,
            predicted_by: g.by,
            stop: reason,
        })
    }
}
