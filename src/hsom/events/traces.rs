//! Traces: the training chunks a node keeps for traced plans, and the decoder of a node's
//! content.

use super::encode::{b_part, dist2, entry_content, DurationCode};
use super::END;
use crate::hsom::followers::{follower_row, FOLLOWERS};
use crate::hsom::inputs::Layout;
use crate::hsom::model::{EventsHsom, Traces};

/// How many of the training chunks a node was the BMU of it keeps for traced plans (those
/// nearest its weights first): a bound on the model's size, not a tuned value.
pub(crate) const TRACED_CHUNKS: usize = 8;
/// The most words a level's traced chunks may take (16 MiB); a level whose nodes x
/// [`TRACED_CHUNKS`] x chunk width would take more keeps none, and its plans are decoded.
const TRACE_BUDGET: usize = 1 << 22;

/// Words before a traced chunk's bottom events: its index, the bottom node before it, its
/// demonstration.
pub(super) const TRACE_HEAD: usize = 3;

/// Words of one traced chunk of level `l` (memory `k`, `stateLength` `s`): its index in its
/// demonstration, the bottom node before it (its first, for a demonstration's first chunk),
/// the demonstration (its index among the training demonstrations), its `k^l` bottom
/// events, where each of them lies in the demonstrations' consensus (`s` values per event,
/// as `f32` bits, from [`EventsHsom::fit_postures`]; all `u32::MAX`: none), then for each level
/// `m` from 1 to `l - 1` the BMUs of its `k^(l-m)` chunks of level `m`; `None` where that
/// does not fit in `usize`. `s` is [`trace_places`]: each event's place, then its two
/// halves'.
pub(crate) fn trace_width(k: usize, l: usize, s: usize) -> Option<usize> {
    let head = (0..=l).try_fold(TRACE_HEAD, |w, m| {
        let span = k.checked_pow((l - m) as u32)?;
        // m = 0: the bottom events (k^l); 1..l: the BMUs of level m (k^(l-m)); not level l
        if m == l {
            Some(w)
        } else {
            w.checked_add(span)
        }
    })?;
    head.checked_add(k.checked_pow(l as u32)?.checked_mul(s)?)
}

/// The values that place each traced event of a model configured by `p` (the `s` of
/// [`trace_width`] and the rest): seven times `stateLength` (the event, its first and second
/// half, then the first half's lowest and highest values and the second's: where a turn in
/// that half reaches, [`turning_points_kept`]).
pub(crate) fn trace_places(p: &crate::config::HsomParams) -> usize {
    HALF_PLACES * p.state_length
}

/// Places per traced event ([`trace_places`]), each `stateLength` values.
pub(super) const HALF_PLACES: usize = 7;

/// Where the postures of a traced chunk of level `l` (memory `k`) begin in its words: after
/// its head and bottom events.
pub(super) fn trace_postures_at(k: usize, l: usize) -> usize {
    TRACE_HEAD + k.pow(l as u32)
}

/// Where the lower levels' BMUs of a traced chunk of level `l` (memory `k`, `stateLength`
/// `s`) begin in its words: after its events' postures.
pub(super) fn trace_bmus_at(k: usize, l: usize, s: usize) -> usize {
    trace_postures_at(k, l) + k.pow(l as u32) * s
}

/// The words of level `l` (nodes `nodes`, memory `k`, `stateLength` `s`) when it keeps
/// traced chunks: 0 where they would not fit [`TRACE_BUDGET`].
pub(crate) fn trace_words(k: usize, l: usize, s: usize, nodes: usize) -> usize {
    trace_width(k, l, s)
        .and_then(|w| w.checked_mul(nodes * TRACED_CHUNKS))
        .filter(|&n| n <= TRACE_BUDGET)
        .unwrap_or(0)
}

impl Traces {
    /// Check traces loaded from a file (untrusted) for a model with memory `k` and `s`
    /// values placing each event ([`trace_places`]) whose levels have `nodes` nodes each:
    /// chunks only where the configuration keeps them ([`trace_words`]), by node, at most
    /// [`TRACED_CHUNKS`] a node, each [`trace_width`] words; every bottom node before a chunk
    /// a node, every bottom event a node or the end, every upper entry a node of its level
    /// (or the padding), every event's place `s` finite values (or all padding); otherwise
    /// what is wrong.
    pub(crate) fn check(&self, k: usize, s: usize, nodes: &[usize]) -> Result<(), String> {
        if self.levels.len() != nodes.len() {
            return Err(format!(
                "traces of {} levels, the model has {}",
                self.levels.len(),
                nodes.len()
            ));
        }
        let n0 = nodes[0];
        for (l, (chunks, &n)) in self.levels.iter().zip(nodes).enumerate() {
            let kept = l > 0 && trace_words(k, l, s, n) > 0;
            if !kept && !chunks.is_empty() {
                return Err(format!("level {l} holds traced chunks, none expected"));
            }
            let (Some(width), true) = (trace_width(k, l, s), kept) else {
                continue;
            };
            let span = k.pow(l as u32);
            let postures = trace_postures_at(k, l);
            for (i, c) in chunks.iter().enumerate() {
                let bad =
                    |what: &str, v: u32| format!("level {l} node {} chunk {i}: {what} {v}", c.node);
                let slot = &c.words;
                if slot.len() < width {
                    return Err(format!(
                        "traces end before a word: level {l} chunk {i} holds {} words, {width} expected",
                        slot.len()
                    ));
                }
                if slot.len() > width {
                    return Err(bad("words beyond its width", slot.len() as u32));
                }
                let earlier = chunks[..i]
                    .iter()
                    .rev()
                    .take_while(|e| e.node == c.node)
                    .count();
                if c.node as usize >= n
                    || chunks[..i].last().is_some_and(|e| e.node > c.node)
                    || earlier >= TRACED_CHUNKS
                {
                    return Err(bad(
                        "node out of order, outside its map or over its chunks",
                        c.node,
                    ));
                }
                if slot[0] == u32::MAX {
                    return Err(bad("chunk index", slot[0]));
                }
                if slot[1] != u32::MAX && slot[1] as usize >= n0 {
                    return Err(bad("bottom node before it", slot[1]));
                }
                if let Some(&e) = slot[TRACE_HEAD..TRACE_HEAD + span]
                    .iter()
                    .find(|&&e| e != u32::MAX && e != END && e as usize >= n0)
                {
                    return Err(bad("bottom event", e));
                }
                let mut at = trace_bmus_at(k, l, s);
                for (m, &nm) in nodes.iter().enumerate().take(l).skip(1) {
                    let count = k.pow((l - m) as u32);
                    if let Some(&e) = slot[at..at + count]
                        .iter()
                        .find(|&&e| e != u32::MAX && e as usize >= nm)
                    {
                        return Err(bad(&format!("level {m} entry"), e));
                    }
                    at += count;
                }
                let places = &slot[postures..trace_bmus_at(k, l, s)];
                for (j, p) in places.chunks(s.max(1)).enumerate() {
                    let none = p.iter().all(|&v| v == u32::MAX);
                    if let Some(&v) = p.iter().find(|&&v| !none && !f32::from_bits(v).is_finite()) {
                        return Err(bad(&format!("event {j}'s posture value"), v));
                    }
                }
            }
        }
        Ok(())
    }
}

/// What decoding needs: the model and its encoding.
pub(super) struct Decoder<'a> {
    pub(super) model: &'a EventsHsom,
    pub(super) lay: Layout,
    pub(super) code: DurationCode,
}

impl Decoder<'_> {
    /// Decode a predicted slot of level `level`'s input into an entry of the level below:
    /// the predicting node's exemplar entry `hint` (what its nearest training chunk held in
    /// this slot) when it followed `prev` in training; otherwise, among the entries that
    /// followed `prev` (the end included; all used entries when `prev` has no recorded
    /// follower), the one whose content is nearest; at level 1 with a finite `position`
    /// (where the plan places this entry, in the units of a chunk's phase), the squared
    /// distance between it and the position at which each follower came in training is
    /// added to the content distance (same units as the context). At level 1
    /// the end is taken when a demonstration ended after `prev` and either the slot is mostly
    /// the end, or `events_before` (bottom events so far) has reached the shortest
    /// demonstration's count, or `position` is nearer where the demonstrations ended after
    /// `prev` than where any other follower came: where a gesture starts
    /// and ends in the same posture, content alone cannot tell "end here" from "start
    /// again" (the paper's replication).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn decode(
        &self,
        level: usize,
        c: &[f64],
        used_below: &[usize],
        prev: u32,
        events_before: f64,
        position: f64,
        hint: u32,
    ) -> u32 {
        let (model, lay, code) = (self.model, self.lay, self.code);
        let s = lay.s;
        let below = level - 1;
        let n = model.maps[below].len();
        let row = follower_row(n, prev);
        let table = &model.part.followers[below];
        let cands: Vec<u32> = table[row * FOLLOWERS..(row + 1) * FOLLOWERS]
            .iter()
            .copied()
            .filter(|&f| f != u32::MAX)
            .collect();
        // at level 1, how far each follower's position in the demonstrations is from where
        // the plan places this entry (`None`: not a follower, or no position)
        let gap = |m: u32| -> Option<f64> {
            let k = table[row * FOLLOWERS..(row + 1) * FOLLOWERS]
                .iter()
                .position(|&f| f == m)?;
            (level == 1 && position.is_finite())
                .then(|| (position - model.part.follower_at[row * FOLLOWERS + k]).abs())
        };
        // the plan nearer where the demonstrations ended after `prev` than where any other
        // follower came: "end here", not "start again", even when the reproduction came home
        // in fewer events than the shortest demonstration
        let end_nearest = || {
            gap(END).is_some_and(|e| {
                cands
                    .iter()
                    .filter(|&&m| m != END)
                    .all(|&m| gap(m).is_some_and(|g| e < g))
            })
        };
        if level == 1
            && (c[2 * s + 1] > 0.5
                || (cands.contains(&END) && (events_before >= model.demo_runs[0] || end_nearest())))
        {
            return END;
        }
        if hint != u32::MAX && hint != END && (cands.is_empty() || cands.contains(&hint)) {
            return hint;
        }
        let all: Vec<u32>;
        let cands = if cands.is_empty() {
            all = used_below.iter().map(|&m| m as u32).collect();
            &all
        } else {
            &cands
        };
        let prev_b: Vec<f64> = if (prev as usize) < n {
            b_part(lay, &entry_content(model, lay, below, prev as usize, code)).to_vec()
        } else {
            c[s..2 * s].to_vec()
        };
        // a node every swing passes through leads on to the next swing early and home late,
        // which content cannot tell apart: the follower's position gap is added
        let position_cost = |m: u32| gap(m).map_or(0.0, |g| g * g);
        let mut best = (END, f64::INFINITY);
        for &m in cands {
            let d = if m == END {
                dist2(&prev_b, &c[..s])
                    + dist2(&prev_b, &c[s..2 * s])
                    + (c[2 * s + 1] - 1.0).powi(2)
            } else {
                let e = entry_content(model, lay, below, m as usize, code);
                dist2(&e[..2 * s], &c[..2 * s]) + (c[2 * s + 1] - e[2 * s + 1]).powi(2)
            } + position_cost(m);
            if d < best.1 {
                best = (m, d);
            }
        }
        best.0
    }
}
