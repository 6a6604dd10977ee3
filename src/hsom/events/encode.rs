//! Events and their encoding: the bottom level's runs of BMUs, and the slots, chunks and
//! summaries every level above reads.

use crate::som::SelfOrganizingMap;

use crate::hsom::inputs::Layout;
use crate::hsom::model::{Model, Part};

/// Encoded durations: `scale * ln(1 + samples)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct DurationCode {
    scale: f64,
}

impl DurationCode {
    /// The scale that maps the longest mean event duration to 0.5 (half the posture range of
    /// the global normalisation), derived from the stored per-node durations so that a loaded
    /// model decodes as the trained one did.
    pub(crate) fn from_dwell(dwell: &[f64]) -> Self {
        let longest = dwell.iter().cloned().fold(1.0, f64::max);
        DurationCode {
            scale: 0.5 / (1.0 + longest).ln(),
        }
    }
    fn encode(&self, samples: f64) -> f64 {
        self.scale * (1.0 + samples.max(0.0)).ln()
    }
    pub(super) fn decode(&self, v: f64) -> f64 {
        ((v.max(0.0) / self.scale).min(30.0)).exp() - 1.0
    }
}

/// One entry of an activity list: the node (or [`END`]) and its content (a slot).
#[derive(Debug, Clone)]
pub(in crate::hsom) struct Item {
    pub(in crate::hsom) node: u32,
    pub(in crate::hsom) content: Vec<f64>,
}

/// The events of one demonstration: runs of the bottom BMU with hysteresis (`changeRatio`),
/// as (node, length in samples). Constant work per sample.
pub(crate) fn bottom_events<A: Part>(model: &Model<A>, demo: &[Vec<f64>]) -> Vec<(usize, f64)> {
    let p = model.config.params();
    let s = p.state_length;
    let h = p.action_horizon().max(1);
    let map = &model.maps[0];
    let mut x = vec![0.0; 2 * s];
    let mut out: Vec<(usize, f64)> = Vec::new();
    let mut cur: Option<usize> = None;
    for pos in 0..demo.len().saturating_sub(1) {
        x[..s].copy_from_slice(&demo[pos]);
        x[s..].copy_from_slice(&demo[(pos + h).min(demo.len() - 1)]);
        let (b, d2) = map.bmu(&x);
        let switch = match cur {
            None => true,
            Some(c) if c == b => false,
            Some(c) => {
                let dc = dist2(&map.weights(c), &x);
                d2.sqrt() < p.change_ratio() * dc.sqrt()
            }
        };
        if switch {
            out.push((b, 1.0));
            cur = Some(b);
        } else if let Some(last) = out.last_mut() {
            last.1 += 1.0;
        }
    }
    out
}

/// A bottom event of a plan, planned or executed: its node (`u32` with [`END`] while
/// planned), its duration in samples, the level that planned it, and where a traced plan
/// places it (`plan = traced`: that demonstrated event's place in the demonstrations'
/// consensus, normalised, state part; `None`: where its node is placed,
/// [`Model::placement`]).
pub(super) type Step<N> = (N, f64, usize, Option<Vec<f64>>);

/// How far a `reading` of a plan's execution has got along the plan, event by event: the
/// events of the plan (`events`: node, duration in samples, level) begun by the reading's
/// end, each with its duration as executed (its planned duration, longer or shorter by the
/// reading samples more or fewer than the plan samples aligned with it: a hold of 40
/// samples adds 40 to the event held), and the share of the last one still to come (plan
/// samples). `reading` and the plan's samples `plan` (both normalised) are aligned by DTW with
/// an open end in the plan ([`crate::dtw::dtw_open_end`]); each sample counts for the event whose span holds it, a reading
/// sample for the last plan sample it is aligned with. Read back exactly, every event is as
/// planned.
pub(super) fn observed_durations(
    reading: &[Vec<f64>],
    plan: &[Vec<f64>],
    events: &[Step<usize>],
) -> (Vec<(usize, f64)>, f64) {
    if reading.is_empty() || plan.is_empty() || events.is_empty() {
        return (Vec::new(), 0.0);
    }
    let Ok(al) = crate::dtw::dtw_open_end(reading, plan) else {
        return (Vec::new(), 0.0);
    };
    let end = al.path.last().map_or(0, |p| p.1);
    // the plan sample each reading sample reached last
    let mut last = vec![0usize; reading.len()];
    for &(i, j) in &al.path {
        last[i] = last[i].max(j);
    }
    // sample j of the plan belongs to the event whose span [start, start + duration) holds it
    let mut starts = Vec::with_capacity(events.len());
    let mut t = 0.0;
    for e in events {
        starts.push(t);
        t += e.1;
    }
    let event_of = |j: usize| starts.partition_point(|&s| s <= j as f64).saturating_sub(1);
    let begun = event_of(end) + 1;
    let mut stretch = vec![0.0f64; begun];
    // every j here is at most `end`, so its event is one of those begun
    for &j in &last {
        stretch[event_of(j)] += 1.0;
    }
    for j in 0..=end {
        stretch[event_of(j)] -= 1.0;
    }
    let executed = events[..begun]
        .iter()
        .zip(stretch)
        .map(|(e, s)| (e.0, (e.1 + s).max(1.0)))
        .collect();
    // the continuation's first posture is the reading's last, plan sample `end`
    let left = (starts[begun - 1] + events[begun - 1].1 - end as f64).max(0.0);
    (executed, left)
}

pub(super) fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Content of a bottom event.
pub(in crate::hsom) fn event_content(
    map: &SelfOrganizingMap,
    node: usize,
    samples: f64,
    code: DurationCode,
) -> Vec<f64> {
    let mut c = map.weights(node).to_vec();
    c.push(code.encode(samples));
    c.push(0.0);
    c
}

/// Content of the end of the gesture after an item whose last posture is `b`.
pub(in crate::hsom) fn end_content(lay: Layout, b: &[f64]) -> Vec<f64> {
    let mut c = Vec::with_capacity(lay.slot());
    c.extend_from_slice(b);
    c.extend_from_slice(b);
    c.push(0.0);
    c.push(1.0);
    c
}

/// The summary of a node of level >= 1 (its slot form one level up).
pub(in crate::hsom) fn summary(lay: Layout, w: &[f64], code: DurationCode) -> Vec<f64> {
    let s = lay.s;
    let first = &w[lay.slot_range(0)];
    let last = &w[lay.slot_range(lay.k - 1)];
    let mut c = Vec::with_capacity(lay.slot());
    c.extend_from_slice(&first[..s]);
    c.extend_from_slice(&last[s..2 * s]);
    let mut total = 0.0;
    let mut end = 0.0f64;
    for j in 0..lay.k {
        let sl = &w[lay.slot_range(j)];
        total += code.decode(sl[2 * s]);
        end = end.max(sl[2 * s + 1]);
    }
    c.push(code.encode(total));
    c.push(end);
    c
}

pub(in crate::hsom) fn a_part(lay: Layout, c: &[f64]) -> &[f64] {
    &c[..lay.s]
}
pub(in crate::hsom) fn b_part(lay: Layout, c: &[f64]) -> &[f64] {
    &c[lay.s..2 * lay.s]
}

/// Write the context of a chunk into `x` (and mark it known).
fn write_ctx(lay: Layout, prev: &[f64], begin: bool, phase: f64, x: &mut [f64], mask: &mut [bool]) {
    x[..lay.s].copy_from_slice(prev);
    x[lay.s] = if begin { 1.0 } else { 0.0 };
    x[lay.s + 1] = phase;
    mask[..lay.ctx()].iter_mut().for_each(|m| *m = true);
}

/// Build the input of a chunk with `known` slots (the rest masked out).
pub(in crate::hsom) fn chunk_input(
    lay: Layout,
    prev: &[f64],
    begin: bool,
    phase: f64,
    slots: &[&[f64]],
    x: &mut [f64],
    mask: &mut [bool],
) -> usize {
    mask.iter_mut().for_each(|m| *m = false);
    write_ctx(lay, prev, begin, phase, x, mask);
    for (j, c) in slots.iter().enumerate() {
        let r = lay.slot_range(j);
        x[r.clone()].copy_from_slice(c);
        mask[r].iter_mut().for_each(|m| *m = true);
    }
    lay.ctx() + slots.len() * lay.slot()
}

/// One chunk of entries as the level above sees it.
#[derive(Debug, Clone, PartialEq)]
pub(in crate::hsom) struct Chunk {
    /// The last posture before the chunk (the first posture for the first chunk).
    pub(super) prev: Vec<f64>,
    /// The first chunk of a demonstration.
    pub(super) begin: bool,
    /// Bottom events before the chunk / the mean number of events per demonstration.
    pub(super) phase: f64,
    /// The entries' contents, padded with the end.
    pub(super) slots: Vec<Vec<f64>>,
}

impl Chunk {
    /// Its input with the first `known` slots known (the rest masked out); returns the
    /// number of known values.
    pub(in crate::hsom) fn input(
        &self,
        lay: Layout,
        known: usize,
        x: &mut [f64],
        mask: &mut [bool],
    ) -> usize {
        let refs: Vec<&[f64]> = self.slots[..known].iter().map(|v| v.as_slice()).collect();
        chunk_input(lay, &self.prev, self.begin, self.phase, &refs, x, mask)
    }
}

/// The chunks of one item sequence at the level above.
pub(in crate::hsom) fn chunks(
    lay: Layout,
    items: &[Item],
    per_item: f64,
    mean_events: f64,
) -> Vec<Chunk> {
    let mut out = Vec::new();
    if items.is_empty() {
        return out;
    }
    let last_b = b_part(lay, &items[items.len() - 1].content).to_vec();
    let mut k = 0;
    while k * lay.k < items.len() {
        let start = k * lay.k;
        let prev = if start == 0 {
            a_part(lay, &items[0].content).to_vec()
        } else {
            b_part(lay, &items[start - 1].content).to_vec()
        };
        let slots: Vec<Vec<f64>> = (start..start + lay.k)
            .map(|i| match items.get(i) {
                Some(it) => it.content.clone(),
                None => end_content(lay, &last_b),
            })
            .collect();
        let phase = start as f64 * per_item / mean_events.max(1.0);
        out.push(Chunk {
            prev,
            begin: k == 0,
            phase,
            slots,
        });
        k += 1;
    }
    out
}

/// The content of entry `m` of level `level` as a slot of the level above.
pub(super) fn entry_content<A: Part>(
    model: &Model<A>,
    lay: Layout,
    level: usize,
    m: usize,
    code: DurationCode,
) -> Vec<f64> {
    if level == 0 {
        event_content(&model.maps[0], m, model.dwell[m], code)
    } else {
        summary(lay, &model.maps[level].weights(m), code)
    }
}
