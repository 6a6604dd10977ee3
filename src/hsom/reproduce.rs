//! Reproduction from an initial posture (paper III-C.2). See docs/ALGORITHM.md for every
//! choice the paper leaves open.

use crate::config::{
    IdDecoding, MemoryMode, Reflex, ReproductionMode, ReproductionParams, StopRule, Timing,
};

use super::algorithm::{input_dim, Hsom, Memory, Stm};
use super::errors::HsomError;

/// Why a reproduction ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// `maxLength` postures were produced.
    MaxLength,
    /// A bottom node on which training demonstrations ended was reached.
    EndNode,
    /// The posture stopped changing for `stationarySteps` steps.
    Stationary,
    /// `lengthFactor` times the longest demonstration was reached.
    LearnedLength,
    /// The hierarchy predicted the end of the gesture (`algorithm = events`).
    EndEvent,
}

/// A reproduced gesture: postures (in the data's units) with their step index.
#[derive(Debug, Clone, PartialEq)]
pub struct Reproduction {
    /// Step index of each posture (0 = the initial posture).
    pub steps: Vec<usize>,
    /// One posture per step, `stateLength` values each.
    pub postures: Vec<Vec<f64>>,
    /// Level whose prediction produced each posture (0 = the bottom level's reflex; the
    /// initial posture counts as 0).
    pub predicted_by: Vec<usize>,
    /// Why it ended.
    pub stop: StopReason,
}

impl Reproduction {
    /// Keep the first `n` steps (at least one: the initial posture).
    pub(crate) fn truncate(&mut self, n: usize) {
        let n = n.max(1);
        self.postures.truncate(n);
        self.steps.truncate(n);
        self.predicted_by.truncate(n);
    }
}

struct Gen<'a> {
    m: &'a Hsom,
    r: &'a ReproductionParams,
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
    /// Node executed before `last_node` (None at the start).
    prev_node: Option<usize>,
    /// Fractional postures carried over (`timing = dwell`).
    acc: f64,
    /// Length of the stationarity window (postures).
    still_window: usize,
    /// Longest learned dwell (steps).
    max_dwell: f64,
    /// Bottom nodes pushed so far, oldest first (`loopVisits`).
    recent: Vec<usize>,
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
        let idx = match self.r.id_decoding {
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
        if self.r.unseen_fallback && any_used && hits[idx] == 0 {
            nearest_used(wx, wy)
        } else {
            idx
        }
    }

    /// Children of node `node` of `level` (>= 1) in the level below, oldest first.
    fn children(&self, level: usize, node: usize) -> Vec<usize> {
        let w = self.m.maps[level].weights(node);
        match self.stm.mem {
            Memory::Lists(_) => {
                let slots = w.len() / 2;
                (0..slots)
                    .rev()
                    .map(|k| self.decode(level - 1, w[2 * k], w[2 * k + 1]))
                    .collect()
            }
            Memory::Levels(_) => {
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
    /// `strided`, every child after the first adds only the bottom steps it covers beyond its
    /// predecessor (its newest updatePeriod^(level-1) steps). At most `cap` nodes.
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
        if n < self.r.offset {
            return None;
        }
        let memory = self.stm.memory;
        if memory < 2 {
            return None;
        }
        let map = &self.m.maps[level];
        match &self.stm.mem {
            Memory::Lists(lists) => {
                let k = lists[below].len().min(memory - 1);
                if k == 0 {
                    return None;
                }
                let shift = memory - k;
                let (x, mask) = (&mut self.bufs[level], &mut self.masks[level]);
                lists[below].encode(k, shift, x, mask);
                let (b, d2) = map.bmu_masked(x, mask);
                let rms = (d2 / (2 * k) as f64).sqrt();
                if self.r.confusion_threshold > 0.0 && rms > self.r.confusion_threshold {
                    return None;
                }
                let w = map.weights(b);
                let slots: Vec<usize> = match self.r.mode {
                    ReproductionMode::Strided => vec![shift - 1],
                    ReproductionMode::Literal => (0..shift).rev().collect(),
                };
                Some(
                    slots
                        .into_iter()
                        .map(|s| self.decode(below, w[2 * s], w[2 * s + 1]))
                        .collect(),
                )
            }
            Memory::Levels(levels) => {
                let a = levels[below].levels();
                let dec = levels[below].decrement();
                let x = &mut self.bufs[level];
                for (xi, ai) in x.iter_mut().zip(a) {
                    *xi = (ai - dec).max(0.0);
                }
                let (b, d2) = map.bmu(x);
                let rms = (d2 / x.len() as f64).sqrt();
                if self.r.confusion_threshold > 0.0 && rms > self.r.confusion_threshold {
                    return None;
                }
                let w = map.weights(b);
                let next = (0..w.len())
                    .max_by(|&i, &j| (w[i] - x[i]).total_cmp(&(w[j] - x[j])).then(j.cmp(&i)))
                    .unwrap_or(0);
                Some(vec![next])
            }
        }
    }

    /// The bottom node nearest to posture `y` (state half) that has a learned successor,
    /// other than `except`.
    fn nearest_with_successor(&self, y: &[f64], except: usize) -> Option<usize> {
        let map = &self.m.maps[0];
        let state = y.len();
        let mut best: Option<(usize, f64)> = None;
        for i in 0..map.len() {
            if i == except || self.m.successor[i] == u32::MAX {
                continue;
            }
            let d = map.distance2(i, y, 0..state);
            if best.map_or(true, |(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        best.map(|(i, _)| i)
    }

    /// Learned dwell of a bottom node (1 when unknown).
    fn dwell(&self, node: usize) -> f64 {
        let d = self.m.dwell.get(node).copied().unwrap_or(0.0);
        if d > 0.0 {
            d
        } else {
            1.0
        }
    }

    /// `loopVisits`: when `node` is already `loop_visits` times among the last `loop_window`
    /// executed bottom nodes, the reproduction is cycling; the learned successor of the
    /// newest recent node whose successor is not among them (the way out of the cycle) is
    /// returned instead; with `revisitSuccessors`, failing that, the latest learned transition
    /// (`last_successor`) of the newest recent node that leaves them. Otherwise `node`.
    fn break_loop(&self, node: usize) -> usize {
        let v = self.r.loop_visits;
        if v == 0 {
            return node;
        }
        let n = self.recent.len();
        let win = &self.recent[n.saturating_sub(self.r.loop_window.max(1))..];
        if win.iter().filter(|&&x| x == node).count() < v {
            return node;
        }
        for &x in win.iter().rev() {
            let s = self.m.successor[x];
            if s != u32::MAX && !win.contains(&(s as usize)) {
                return s as usize;
            }
        }
        if self.r.revisit_successors {
            for &x in win.iter().rev() {
                let s = self.m.last_successor[x];
                if s != u32::MAX && !win.contains(&(s as usize)) {
                    return s as usize;
                }
            }
        }
        node
    }

    /// Execute bottom node `node`: its action half is the next posture (reached over the
    /// node's dwell with `timing = dwell`); push it and climb the schedule. With
    /// `listUpdate = onChange` a node equal to the newest bottom entry is not executed.
    fn emit(
        &mut self,
        node: usize,
        by: usize,
        skip: Option<usize>,
        pending: Option<(usize, usize)>,
    ) {
        let node = self.break_loop(node);
        if self.stm.on_change && self.stm.last0 == Some(node) {
            return;
        }
        let p = self.m.config.params();
        let state = p.state_length;
        let w = self.m.maps[0].weights(node);
        let cur = self.out.last().cloned().unwrap_or_default();
        let lambda = self.r.continuity;
        let h = p.action_horizon.max(1) as f64;
        // the node's one-step action: S_t + (S_t+h - S_t) / h (its action half when h = 1)
        let y: Vec<f64> = (0..state)
            .map(|d| {
                let a = if h == 1.0 {
                    w[state + d]
                } else {
                    w[d] + (w[state + d] - w[d]) / h
                };
                a + lambda * (cur[d] - w[d])
            })
            .collect();
        let k = match self.r.timing {
            Timing::Step => 1,
            Timing::Dwell => {
                let d = self.dwell(node);
                let dp = self.prev_node.map_or(d, |n| self.dwell(n));
                self.acc += 0.5 * (d + dp);
                let k = self.acc.floor();
                self.acc -= k;
                k as usize
            }
            Timing::Speed => {
                let v = self.m.speed.get(node).copied().unwrap_or(0.0);
                let steps = if v > 0.0 {
                    let dist = cur
                        .iter()
                        .zip(&y)
                        .map(|(a, b)| (a - b) * (a - b))
                        .sum::<f64>()
                        .sqrt();
                    // never slower than the slowest learned dwell allows
                    (dist / v).min(self.max_dwell.max(1.0))
                } else {
                    self.dwell(node)
                };
                self.acc += steps;
                let k = self.acc.floor();
                self.acc -= k;
                k as usize
            }
        };
        let pushed = if self.r.closed_loop && !self.stm.on_change && k > 0 {
            let x = &mut self.bufs[0];
            let last = if k == 1 {
                cur.clone()
            } else {
                (0..state)
                    .map(|d| cur[d] + (y[d] - cur[d]) * (k - 1) as f64 / k as f64)
                    .collect()
            };
            x[..state].copy_from_slice(&last);
            if h == 1.0 {
                x[state..].copy_from_slice(&y);
            } else {
                for d in 0..state {
                    x[state + d] = last[d] + h * (y[d] - last[d]);
                }
            }
            self.m.maps[0].bmu(x).0
        } else {
            node
        };
        if !self.stm.push_bottom(pushed, &self.m.maps[0]) {
            // closed loop found the node just executed: the list does not change
            self.emit_postures(&cur, &y, k, by);
            return;
        }
        self.s += 1;
        self.recent.push(pushed);
        self.emit_postures(&cur, &y, k, by);
        self.prev_node = (self.s > 1).then_some(self.last_node);
        self.last_node = pushed;
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
            if !self.stm.input(l - 1, p.partial_training, x, mask) {
                continue;
            }
            let full = mask.iter().all(|&m| m);
            let (b, _) = if full {
                self.m.maps[l].bmu(x)
            } else {
                self.m.maps[l].bmu_masked(x, mask)
            };
            self.stm.push(l, b, &self.m.maps[l]);
        }
    }

    /// Append `k` postures moving linearly from `cur` to `y` (just `y` when k = 1).
    fn emit_postures(&mut self, cur: &[f64], y: &[f64], k: usize, by: usize) {
        for j in 1..=k {
            let f = j as f64 / k as f64;
            self.out
                .push(cur.iter().zip(y).map(|(a, b)| a + f * (b - a)).collect());
            self.by.push(by);
        }
    }

    fn stop(&self) -> Option<StopReason> {
        let t = self.out.len();
        if t >= self.r.max_length {
            return Some(StopReason::MaxLength);
        }
        let long_enough = if self.stm.on_change {
            self.s as f64 >= self.r.min_length_fraction * self.m.demo_runs[0]
        } else {
            t >= self.min_len
        };
        if self.r.stop == StopRule::Learned && long_enough {
            let state = self.m.config.params().state_length;
            let y = &self.out[t - 1];
            let (near, _) = self.m.maps[0].bmu_range(y, state..2 * state);
            let tol = self.r.end_tolerance * self.qe0;
            let close = tol > 0.0
                && self.m.end_hits.iter().enumerate().any(|(i, &h)| {
                    h > 0
                        && self.m.maps[0].distance2(i, y, state..self.m.maps[0].dim()) <= tol * tol
                });
            if close || self.m.end_hits[self.last_node] > 0 || self.m.end_hits[near] > 0 {
                return Some(StopReason::EndNode);
            }
            let k = self.still_window;
            if t > k {
                let win = &self.out[t - k - 1..];
                let tol = self.r.stationary_tolerance * self.qe0;
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

impl Hsom {
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
    /// data's units) with the configuration's reproduction settings.
    pub fn reproduce(&self, initial: &[f64]) -> Result<Reproduction, HsomError> {
        self.reproduce_with(initial, &self.config.params().reproduction)
    }

    /// Reproduce with other reproduction settings (validate them with
    /// [`HsomConfig::with_reproduction`](crate::config::HsomConfig::with_reproduction) first;
    /// out-of-range values are clamped here).
    pub fn reproduce_with(
        &self,
        initial: &[f64],
        r: &ReproductionParams,
    ) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        self.check_initial(initial)?;
        let state = p.state_length;
        let mut r = r.clone();
        r.offset = r.offset.clamp(1, p.memory);
        r.max_length = r.max_length.max(1);
        let y0 = self.normalise(initial);
        if p.algorithm == crate::config::Algorithm::Events {
            let mut rep = self.reproduce_events(&y0, &r);
            rep.truncate(r.max_length);
            return Ok(rep);
        }
        let mut g = Gen {
            m: self,
            r: &r,
            stm: Stm::new(&self.config),
            s: 0,
            out: vec![y0],
            by: vec![0],
            last_node: 0,
            bufs: (0..p.height)
                .map(|l| vec![0.0; input_dim(&self.config, l)])
                .collect(),
            masks: (0..p.height)
                .map(|l| vec![true; input_dim(&self.config, l)])
                .collect(),
            qe0: if p.normalisation == crate::config::Normalisation::PerDimension {
                self.qe[0]
            } else {
                self.qe[0] / self.scale[0]
            },
            min_len: (r.min_length_fraction * self.demo_len[0]).ceil().max(2.0) as usize,
            prev_node: None,
            acc: 0.0,
            recent: Vec::new(),
            max_dwell: self.dwell.iter().cloned().fold(1.0, f64::max),
            still_window: if r.timing != Timing::Step {
                let dmax = self.dwell.iter().cloned().fold(1.0, f64::max);
                r.stationary_steps.max((2.0 * dmax).ceil() as usize)
            } else {
                r.stationary_steps
            },
        };
        let mut stalls = 0usize;
        // Guards against a reproduction that keeps stepping without producing postures (e.g.
        // `timing = speed` on a node whose output equals the current posture: zero distance,
        // zero postures, forever): `STILL_ITERATIONS` steps without a new posture end it as
        // stationary, and the loop never runs more than `ITERATION_CAP_FACTOR * maxLength`.
        const STILL_ITERATIONS: usize = 1000;
        const ITERATION_CAP_FACTOR: usize = 20;
        let mut iterations = 0usize;
        let mut no_output = 0usize;
        let strided = r.mode == ReproductionMode::Strided || p.memory_mode == MemoryMode::Levels;
        let top = r.max_level.unwrap_or(p.height - 1).min(p.height - 1);
        let reason = 'outer: loop {
            if g.out.len() > 1 {
                if let Some(reason) = g.stop() {
                    break reason;
                }
            } else if r.max_length <= 1 {
                break StopReason::MaxLength;
            }
            let before = (g.s, g.out.len());
            let mut done = false;
            for l in (1..=top).rev() {
                let period = self.config.period(l - 1);
                if strided && g.s % period != 0 {
                    continue;
                }
                if r.min_accuracy > 0.0
                    && self.accuracy.get(l).copied().unwrap_or(0.0) < r.min_accuracy
                {
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
            // no level could predict, or (onChange) it predicted only the node just executed
            if !done || g.s == before.0 {
                let y = g.out.last().cloned().unwrap_or_default();
                let (b, _) = self.maps[0].bmu_range(&y, 0..state);
                let stationary = g.s > 0 && b == g.last_node;
                // revisitSuccessors: the first execution of a node follows the transition the
                // demonstrations took first from it (e.g. into an oscillation, not out of it)
                let first_visit = r.revisit_successors
                    && g.recent.iter().filter(|&&x| x == g.last_node).count() <= 1;
                let succ = if first_visit {
                    &self.first_successor
                } else {
                    &self.successor
                };
                let learned = succ
                    .get(g.last_node)
                    .copied()
                    .filter(|&n| g.s > 0 && n != u32::MAX);
                let node = match (r.reflex, learned) {
                    (Reflex::Successor, Some(n)) => n as usize,
                    (Reflex::Successor, None) if stationary => {
                        // never left in training: the nearest node that was
                        match g.nearest_with_successor(&y, b) {
                            Some(n) => n,
                            None => break StopReason::EndNode,
                        }
                    }
                    _ => b,
                };
                g.emit(node, 0, None, None);
            }
            iterations += 1;
            no_output = if g.out.len() == before.1 {
                no_output + 1
            } else {
                0
            };
            if no_output >= STILL_ITERATIONS {
                break StopReason::Stationary;
            }
            if iterations >= ITERATION_CAP_FACTOR * r.max_length.max(1) + STILL_ITERATIONS {
                break StopReason::MaxLength;
            }
            if (g.s, g.out.len()) == before {
                // nothing executed: the reproduction cannot move any more
                stalls += 1;
                if stalls >= 3 {
                    break StopReason::Stationary;
                }
            } else {
                stalls = 0;
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
