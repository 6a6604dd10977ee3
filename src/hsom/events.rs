//! The events extension (`algorithm = events`, docs/ALGORITHM.md "The hierarchy as the sequence
//! model"): activity lists of events (a bottom node and how long it was held), levels whose
//! nodes tile `memory` consecutive entries of the level below, lists encoded by content, a
//! learned begin and end, and a reproduction that climbs while the levels' matches lie within
//! what they saw in training, expands the highest confident level's prediction down to timed
//! bottom events, and re-plans when what was executed is not what the plan expected.
//!
//! Layout of a level-l input (l >= 1), all in the bottom level's normalised units:
//! `[context | slot 0 | ... | slot memory-1]`, context = `[previous posture (S), begin, phase]`,
//! slot = `[a (S), b (S), duration, end]`. At level 1 a slot is a bottom event: a and b are
//! its node's state and action halves, duration its encoded length in samples. Higher up a
//! slot summarises a node of the level below: a = its first posture, b = its last, duration
//! the encoded sum of its slots' durations, end the largest of their end flags.

use std::collections::{BTreeMap, VecDeque};

use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::config::{HsomConfig, ReproductionParams};
use crate::demos::Demonstration;
use crate::som::SelfOrganizingMap;

use super::algorithm::{check_series, demo_series, Hsom};
use super::errors::HsomError;
use super::reproduce::{Reproduction, StopReason};

/// A node index that stands for the end of the gesture in item sequences and successors.
pub(crate) const END: u32 = u32::MAX - 1;

/// Sizes of the event encoding.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Layout {
    /// stateLength.
    pub(crate) s: usize,
    /// memory: entries per chunk.
    pub(crate) k: usize,
}

impl Layout {
    pub(crate) fn of(config: &HsomConfig) -> Self {
        let p = config.params();
        Layout {
            s: p.state_length,
            k: p.memory,
        }
    }
    /// Values of one slot.
    pub(crate) fn slot(&self) -> usize {
        2 * self.s + 2
    }
    /// Values of the context.
    pub(crate) fn ctx(&self) -> usize {
        self.s + 2
    }
    /// Input length of a level above the bottom.
    pub(crate) fn dim(&self) -> usize {
        self.ctx() + self.k * self.slot()
    }
    fn slot_range(&self, j: usize) -> std::ops::Range<usize> {
        let o = self.ctx() + j * self.slot();
        o..o + self.slot()
    }
}

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
    fn decode(&self, v: f64) -> f64 {
        ((v.max(0.0) / self.scale).min(30.0)).exp() - 1.0
    }
}

/// One entry of an activity list: the node (or [`END`]) and its content (a slot).
#[derive(Debug, Clone)]
pub(super) struct Item {
    pub(super) node: u32,
    pub(super) content: Vec<f64>,
}

/// Longest sequence [`aligned_samples`] aligns sample by sample: a longer demonstration is aligned
/// in blocks of consecutive samples (their means), so that an alignment never takes more
/// than this squared cells whatever the data (64 MB, tens of milliseconds). Demonstrations of
/// gestures (the Nao's 250-400 samples, handwriting's 100) are aligned sample by sample.
pub(crate) const MAX_ALIGNED: usize = 2000;

/// The demonstrations' *consensus* (normalised, state part): per demonstration and sample,
/// the mean over all the demonstrations of the samples aligned to it by DTW (its own sample
/// for itself; the mean of several aligned samples for another). Where the demonstrations
/// agree it is each one's own path; where they differ (an apex a little higher in one, a
/// lane a little to the side) it is their average at that point of the gesture, as
/// GMM/GMR's regression is, with no time axis: a wave's turning points are aligned with
/// each other whatever their tempo. `aligned`: the demonstrations' alignments
/// ([`aligned_samples`] of `norm`). docs/ALGORITHM.md, passage 6 of the events extension.
pub(crate) fn consensus(norm: &[Vec<Vec<f64>>], aligned: &Aligned) -> Vec<Vec<Vec<f64>>> {
    let n = norm.len();
    let mut out: Vec<Vec<Vec<f64>>> = norm.to_vec();
    for a in 0..n {
        for (t, row) in out[a].iter_mut().enumerate() {
            let others: Vec<&Vec<f64>> = (0..n)
                .filter(|&b| b != a)
                .filter_map(|b| aligned[a][b].as_ref().map(|al| &al[t]))
                .collect();
            let mut total = 1.0;
            let mut acc = norm[a][t].clone();
            for m in &others {
                acc.iter_mut().zip(m.iter()).for_each(|(s, v)| *s += v);
                total += 1.0;
            }
            row.iter_mut().zip(&acc).for_each(|(r, v)| *r = v / total);
        }
    }
    out
}

/// Per pair of demonstrations (`[a][b]`), per sample of `a`, the mean of `b`'s samples aligned
/// to it ([`aligned_samples`]).
type Aligned = Vec<Vec<Option<Vec<Vec<f64>>>>>;

/// `aligned[a][b]`: per sample of the normalised demonstration `a`, the mean of the samples
/// of `b` aligned to it by DTW (`None` for `b == a`, and where an alignment failed), `b` read
/// along the warp without its stairs ([`smooth_warp`]).
/// Sequences longer than `max_aligned` are aligned in blocks of `ceil(len / max_aligned)`
/// samples (their means), every sample of a block taking the block's value.
fn aligned_samples(norm: &[Vec<Vec<f64>>], max_aligned: usize) -> Aligned {
    let block = |d: &[Vec<f64>]| d.len().div_ceil(max_aligned.max(1)).max(1);
    let blocks: Vec<Vec<Vec<f64>>> = norm
        .iter()
        .map(|d| {
            d.chunks(block(d))
                .map(|c| {
                    let mut m = vec![0.0; c[0].len()];
                    for r in c {
                        m.iter_mut()
                            .zip(r)
                            .for_each(|(a, v)| *a += v / c.len() as f64);
                    }
                    m
                })
                .collect()
        })
        .collect();
    let n = norm.len();
    let mut aligned: Vec<Vec<Option<Vec<Vec<f64>>>>> = vec![vec![None; n]; n];
    for j in 0..n {
        for k in j + 1..n {
            // cannot fail: the training series were checked (rows non-empty, of stateLength
            // finite values, at magnitudes the normalisation keeps below 1e100)
            let Ok(al) = crate::dtw::dtw(&blocks[j], &blocks[k], crate::dtw::Band::None) else {
                continue;
            };
            for (a, b) in [(j, k), (k, j)] {
                // per block of a: the sum of the indices of b's blocks aligned to it, and their
                // count
                let mut acc = vec![(0.0, 0.0); blocks[a].len()];
                for &(x, y) in &al.path {
                    let (x, y) = if a == j { (x, y) } else { (y, x) };
                    acc[x].0 += y as f64;
                    acc[x].1 += 1.0;
                }
                let warp: Vec<f64> = acc.iter().map(|(y, c)| y / c).collect();
                let per_block = smooth_warp(&warp, &blocks[b]);
                let size = block(&norm[a]);
                aligned[a][b] = Some(
                    (0..norm[a].len())
                        .map(|t| per_block[t / size].clone())
                        .collect(),
                );
            }
        }
    }
    aligned
}

/// `b` read along `warp` (per sample of another sequence, the mean index of the samples of `b`
/// DTW aligned to it: non-decreasing, from 0 to `b`'s last), the warp's stairs replaced by
/// lines: each run of equal values (samples aligned to one sample of `b`) becomes the point
/// at its middle, the warp is the line through those points (and through its first and last
/// values at the ends), and `b` is read there, linearly between its samples. Where the other
/// sequence is slower than `b`, its samples then move on through `b` at an even pace instead
/// of all taking one sample of `b` (a stair that a traced plan's short events, each the mean
/// of a few samples, would carry into its knots as uneven steps: docs/ALGORITHM.md, passage
/// 6, "A consensus without stairs").
fn smooth_warp(warp: &[f64], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let n = warp.len();
    if n == 0 || b.is_empty() {
        return Vec::new();
    }
    // the points: (sample, index into b), by increasing sample
    let mut points: Vec<(f64, f64)> = vec![(0.0, warp[0])];
    let mut run = 0;
    for x in 1..=n {
        if x == n || warp[x] != warp[run] {
            let mid = (run + x - 1) as f64 / 2.0;
            if mid > points[points.len() - 1].0 {
                points.push((mid, warp[run]));
            }
            run = x;
        }
    }
    let last = (n - 1) as f64;
    if last > points[points.len() - 1].0 {
        points.push((last, warp[n - 1]));
    }
    let top = b.len() - 1;
    let mut seg = 0;
    (0..n)
        .map(|x| {
            let xf = x as f64;
            while seg + 2 < points.len() && xf > points[seg + 1].0 {
                seg += 1;
            }
            let y = match points.get(seg + 1) {
                Some(&(x1, y1)) => {
                    let (x0, y0) = points[seg];
                    y0 + (y1 - y0) * ((xf - x0) / (x1 - x0)).clamp(0.0, 1.0)
                }
                None => points[seg].1,
            }
            .clamp(0.0, top as f64);
            let i = (y.floor() as usize).min(top);
            let (f, k) = (y - i as f64, (i + 1).min(top));
            b[i].iter()
                .zip(&b[k])
                .map(|(p, q)| p + f * (q - p))
                .collect()
        })
        .collect()
}

/// The consensus weighed by the starts (docs/ALGORITHM.md, passage 6): where each training
/// demonstration places every bottom node's events (the node's samples, of every
/// demonstration, replaced by that demonstration's samples aligned to them, smoothed as
/// [`Hsom::fit_postures`] smooths the consensus), and where each started. A reproduction
/// weighs the demonstrations by a Gaussian of the distance between their start and its own,
/// of the width that best predicted each training demonstration's placement from the others'
/// (leave-one-out); all alike (`width` infinite) is a candidate, and is the plain
/// [`consensus`].
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct StartKnots {
    /// Per training demonstration, its first posture (state part, normalised).
    pub(crate) starts: Vec<Vec<f64>>,
    /// Per training demonstration, its placement of every bottom node (`stateLength` values
    /// per node).
    pub(crate) knots: Vec<Vec<f64>>,
    /// The Gaussian's width (normalised units); infinite: all alike.
    pub(crate) width: f64,
}

/// Widths [`StartKnots`] chooses among, in units of the median distance between two
/// training demonstrations' starts; all alike (infinite) is tried first and kept on a tie.
const START_WIDTHS: [f64; 5] = [2.0, 1.0, 0.5, 0.25, 0.125];

/// Every order of `0..n` (`n!` of them, the identity first).
fn all_orders(n: usize) -> Vec<Vec<usize>> {
    let mut out = vec![Vec::new()];
    for k in 0..n {
        out = out
            .into_iter()
            .flat_map(|o: Vec<usize>| {
                (0..=k).map(move |i| {
                    let mut o = o.clone();
                    o.insert(i, k);
                    o
                })
            })
            .collect();
    }
    out.sort();
    out
}

/// Shuffles of the starts [`StartKnots::fit`] compares the starts' own gain with.
const START_SHUFFLES: usize = 199;

/// The permutation test's level: the starts are used where at most this fraction of
/// shuffles (their own order included) predict the placements as well.
const START_SIGNIFICANCE: f64 = 0.05;

impl StartKnots {
    /// The weights of demonstrations starting at `starts` for a reproduction starting at
    /// `x`: `exp(-(d² - d_min²) / (2 width²))` (the nearest counts 1, so some always count);
    /// all 1 for an infinite width.
    fn weights(starts: &[&Vec<f64>], x: &[f64], width: f64) -> Vec<f64> {
        if !width.is_finite() {
            return vec![1.0; starts.len()];
        }
        let d2: Vec<f64> = starts.iter().map(|s| dist2(s, x)).collect();
        let min = d2.iter().cloned().fold(f64::INFINITY, f64::min);
        d2.iter()
            .map(|d| (-(d - min) / (2.0 * width * width)).exp())
            .collect()
    }

    /// The weighted mean of `knots` (flattened placements) with `weights`.
    fn mean(knots: &[&Vec<f64>], weights: &[f64]) -> Vec<f64> {
        let total: f64 = weights.iter().sum();
        let mut out = vec![0.0; knots[0].len()];
        for (k, w) in knots.iter().zip(weights) {
            out.iter_mut()
                .zip(k.iter())
                .for_each(|(o, v)| *o += w / total * v);
        }
        out
    }

    /// The placement for a reproduction starting at `x` (normalised, state part).
    pub(crate) fn placed(&self, x: &[f64]) -> Vec<f64> {
        let starts: Vec<&Vec<f64>> = self.starts.iter().collect();
        let knots: Vec<&Vec<f64>> = self.knots.iter().collect();
        Self::mean(
            &knots,
            &Self::weights(&starts, &x[..starts[0].len()], self.width),
        )
    }

    /// The width that predicts each demonstration's placement best from the others' (the
    /// squared error per node weighted by the samples on the node, `count`, summed over the
    /// demonstrations), kept only where the starts are evidence: its gain over all alike must
    /// be larger than that of the best width for the starts shuffled among the
    /// demonstrations, in all but [`START_SIGNIFICANCE`] of the orders (a permutation test:
    /// every order up to 6 demonstrations, else [`START_SHUFFLES`] shuffles drawn from
    /// `seed`). Infinite (all alike) otherwise, and with identical starts. With three
    /// demonstrations (six orders) it cannot be.
    fn fit(starts: Vec<Vec<f64>>, knots: Vec<Vec<f64>>, count: &[f64], seed: u64) -> Self {
        let n = starts.len();
        let s = knots[0].len() / count.len().max(1);
        let mut dist: Vec<f64> = (0..n)
            .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
            .map(|(a, b)| dist2(&starts[a], &starts[b]).sqrt())
            .filter(|d| *d > 0.0)
            .collect();
        dist.sort_by(f64::total_cmp);
        let Some(&median) = dist.get(dist.len() / 2) else {
            return StartKnots {
                starts,
                knots,
                width: f64::INFINITY,
            };
        };
        // gram[e][f]: the placements' inner product, each node weighted by its samples, so
        // that an error below costs n^2 per demonstration whatever the map's size
        let mut gram = vec![vec![0.0; n]; n];
        for e in 0..n {
            for f in e..n {
                let g: f64 = count
                    .iter()
                    .enumerate()
                    .map(|(j, c)| {
                        let (x, y) = (&knots[e][j * s..(j + 1) * s], &knots[f][j * s..(j + 1) * s]);
                        c * x.iter().zip(y).map(|(u, v)| u * v).sum::<f64>()
                    })
                    .sum();
                (gram[e][f], gram[f][e]) = (g, g);
            }
        }
        // the error of predicting each demonstration's placement from the others' weighed
        // by the starts in the order `order` (demonstration d started at starts[order[d]]):
        // |sum_e w_e K_e / W - K_d|^2, expanded over `gram`
        let error = |order: &[usize], width: f64| -> f64 {
            (0..n)
                .map(|d| {
                    let others: Vec<usize> = (0..n).filter(|&o| o != d).collect();
                    let st: Vec<&Vec<f64>> = others.iter().map(|&o| &starts[order[o]]).collect();
                    let w = Self::weights(&st, &starts[order[d]], width);
                    let total: f64 = w.iter().sum();
                    let mut e = gram[d][d];
                    for (i, &a) in others.iter().enumerate() {
                        e -= 2.0 * w[i] / total * gram[a][d];
                        for (k, &b) in others.iter().enumerate() {
                            e += w[i] * w[k] / (total * total) * gram[a][b];
                        }
                    }
                    e
                })
                .sum()
        };
        let alike = error(&(0..n).collect::<Vec<_>>(), f64::INFINITY);
        let best = |order: &[usize]| -> (f64, f64) {
            START_WIDTHS
                .iter()
                .map(|f| (alike - error(order, f * median), f * median))
                .fold((0.0, f64::INFINITY), |b, g| if g.0 > b.0 { g } else { b })
        };
        let (gain, width) = best(&(0..n).collect::<Vec<_>>());
        if gain <= 0.0 {
            return StartKnots {
                starts,
                knots,
                width: f64::INFINITY,
            };
        }
        // every other order where there are at most 720 (exact), else shuffles from the seed
        let orders: Vec<Vec<usize>> = if n <= 6 {
            all_orders(n)
        } else {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let mut order: Vec<usize> = (0..n).collect();
            std::iter::once(order.clone())
                .chain((0..START_SHUFFLES).map(|_| {
                    order.shuffle(&mut rng);
                    order.clone()
                }))
                .collect()
        };
        // the starts' own order counts itself (its gain is `gain`)
        let as_good = orders.iter().filter(|o| best(o).0 >= gain).count();
        let p = as_good as f64 / orders.len() as f64;
        let width = if p <= START_SIGNIFICANCE {
            width
        } else {
            f64::INFINITY
        };
        StartKnots {
            starts,
            knots,
            width,
        }
    }
}

/// Per bottom node, how many samples its events hold and the sum of the values given for
/// those samples (state part; the samples themselves or their [`consensus`]): additive over
/// demonstrations.
struct NodeSums {
    count: Vec<f64>,
    sum: Vec<f64>,
}

impl NodeSums {
    fn new(nodes: usize, state: usize) -> Self {
        NodeSums {
            count: vec![0.0; nodes],
            sum: vec![0.0; nodes * state],
        }
    }

    /// The samples of `demo` (normalised) on the nodes of its `events`.
    fn of(model: &Hsom, demo: &[Vec<f64>], events: &[(usize, f64)]) -> Self {
        let s = model.config.params().state_length;
        let mut out = NodeSums::new(model.maps[0].len(), s);
        let mut pos = 0usize;
        for &(node, d) in events {
            for x in demo.iter().skip(pos).take(d as usize) {
                out.count[node] += 1.0;
                for (acc, v) in out.sum[node * s..(node + 1) * s].iter_mut().zip(x) {
                    *acc += v;
                }
            }
            pos += d as usize;
        }
        out
    }

    fn add(&mut self, other: &NodeSums) {
        for (a, b) in self.count.iter_mut().zip(&other.count) {
            *a += b;
        }
        for (a, b) in self.sum.iter_mut().zip(&other.sum) {
            *a += b;
        }
    }
}

/// The events of one demonstration: runs of the bottom BMU with hysteresis (`changeRatio`),
/// as (node, length in samples). Constant work per sample.
pub(crate) fn bottom_events(model: &Hsom, demo: &[Vec<f64>]) -> Vec<(usize, f64)> {
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
/// [`Hsom::placement`]).
type Step<N> = (N, f64, usize, Option<Vec<f64>>);

/// How far a `reading` of a plan's execution has got along the plan, event by event: the
/// events of the plan (`events`: node, duration in samples, level) begun by the reading's
/// end, each with its duration as executed (its planned duration, longer or shorter by the
/// reading samples more or fewer than the plan samples aligned with it: a hold of 40
/// samples adds 40 to the event held), and the share of the last one still to come (plan
/// samples). `reading` and the plan's samples `plan` (both normalised) are aligned by DTW with
/// an open end in the plan ([`crate::dtw::dtw_open_end`]); each sample counts for the event whose span holds it, a reading
/// sample for the last plan sample it is aligned with. Read back exactly, every event is as
/// planned.
fn observed_durations(
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

fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Content of a bottom event.
pub(super) fn event_content(
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
pub(super) fn end_content(lay: Layout, b: &[f64]) -> Vec<f64> {
    let mut c = Vec::with_capacity(lay.slot());
    c.extend_from_slice(b);
    c.extend_from_slice(b);
    c.push(0.0);
    c.push(1.0);
    c
}

/// The summary of a node of level >= 1 (its slot form one level up).
pub(super) fn summary(lay: Layout, w: &[f64], code: DurationCode) -> Vec<f64> {
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

pub(super) fn a_part(lay: Layout, c: &[f64]) -> &[f64] {
    &c[..lay.s]
}
pub(super) fn b_part(lay: Layout, c: &[f64]) -> &[f64] {
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
pub(super) fn chunk_input(
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
pub(super) struct Chunk {
    /// The last posture before the chunk (the first posture for the first chunk).
    prev: Vec<f64>,
    /// The first chunk of a demonstration.
    begin: bool,
    /// Bottom events before the chunk / the mean number of events per demonstration.
    phase: f64,
    /// The entries' contents, padded with the end.
    slots: Vec<Vec<f64>>,
}

impl Chunk {
    /// Its input with the first `known` slots known (the rest masked out); returns the
    /// number of known values.
    pub(super) fn input(
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
pub(super) fn chunks(lay: Layout, items: &[Item], per_item: f64, mean_events: f64) -> Vec<Chunk> {
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

/// The row of the follower table for the entry `prev` (`u32::MAX` or [`END`]: the begin row,
/// `nodes`).
fn follower_row(nodes: usize, prev: u32) -> usize {
    if prev == u32::MAX || prev == END {
        nodes
    } else {
        prev as usize
    }
}

/// The lookup table's prediction: the most frequent follower of `prev` in a follower table of
/// a level with `nodes` nodes (`u32::MAX`: none recorded).
pub(crate) fn most_frequent(table: &[u32], nodes: usize, prev: u32) -> u32 {
    table[follower_row(nodes, prev) * FOLLOWERS]
}

/// The fraction of the entries of `seqs` (each sequence starting after the begin) that the
/// lookup table of "next entry given the last one" of `table` predicts.
pub(crate) fn lookup_accuracy(table: &[u32], nodes: usize, seqs: &[Vec<u32>]) -> f64 {
    let (n, ok) = lookup_counts(table, nodes, seqs);
    if n > 0 {
        ok as f64 / n as f64
    } else {
        0.0
    }
}

/// The entries of `seqs` the lookup table of `table` was asked for and how many it predicted
/// ([`lookup_accuracy`]).
fn lookup_counts(table: &[u32], nodes: usize, seqs: &[Vec<u32>]) -> (u32, u32) {
    let (mut n, mut ok) = (0u32, 0u32);
    for sq in seqs {
        let mut prev = u32::MAX;
        for &x in sq {
            n += 1;
            ok += u32::from(most_frequent(table, nodes, prev) == x);
            prev = x;
        }
    }
    (n, ok)
}

/// What [`Hsom::replay_level`] measured.
struct LevelReplay {
    /// Per sequence, the level's BMU of each chunk: the next level's entries.
    next_items: Vec<Vec<Item>>,
    /// Entries predicted and predicted right.
    predicted: u32,
    correct: u32,
    /// The largest partial-match distance (RMS per known coordinate).
    threshold: f64,
    /// Sum of the complete chunks' BMU distances, chunks whose two best nodes are not
    /// neighbours, and chunks.
    qe: f64,
    te: usize,
    chunks: usize,
}

/// Nodes of a level that some training entry selected.
fn used(model: &Hsom, level: usize) -> Vec<usize> {
    (0..model.maps[level].len())
        .filter(|&i| model.hits[level][i] > 0)
        .collect()
}

/// Followers kept per entry (fixed, so the model's size does not depend on the data).
pub(crate) const FOLLOWERS: usize = 4;

/// The content of entry `m` of level `level` as a slot of the level above.
fn entry_content(
    model: &Hsom,
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

/// How many of the training chunks a node was the BMU of it keeps for traced plans (those
/// nearest its weights first): a bound on the model's size, not a tuned value.
pub(crate) const TRACED_CHUNKS: usize = 8;
/// The most words a level's traced chunks may take (16 MiB); a level whose nodes x
/// [`TRACED_CHUNKS`] x chunk width would take more keeps none, and its plans are decoded.
const TRACE_BUDGET: usize = 1 << 22;

/// Words before a traced chunk's bottom events: its index, the bottom node before it, its
/// demonstration.
const TRACE_HEAD: usize = 3;

/// Words of one traced chunk of level `l` (memory `k`, `stateLength` `s`): its index in its
/// demonstration, the bottom node before it (its first, for a demonstration's first chunk),
/// the demonstration (its index among the training demonstrations), its `k^l` bottom
/// events, where each of them lies in the demonstrations' consensus (`s` values per event,
/// as `f32` bits, from [`Hsom::fit_postures`]; all `u32::MAX`: none), then for each level
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
const HALF_PLACES: usize = 7;

/// Where the postures of a traced chunk of level `l` (memory `k`) begin in its words: after
/// its head and bottom events.
fn trace_postures_at(k: usize, l: usize) -> usize {
    TRACE_HEAD + k.pow(l as u32)
}

/// Where the lower levels' BMUs of a traced chunk of level `l` (memory `k`, `stateLength`
/// `s`) begin in its words: after its events' postures.
fn trace_bmus_at(k: usize, l: usize, s: usize) -> usize {
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

/// What the levels were trained on, kept so a plan can replay it (`plan = traced`; a fixed
/// size, set by the configuration alone): per level l >= 1, per node, up to
/// [`TRACED_CHUNKS`] of the training chunks it was the BMU of, nearest its weights first (the
/// exemplar first), each as [`trace_width`] words; `u32::MAX` pads what is not there. Level
/// 0, and a level over [`TRACE_BUDGET`], keeps none.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Traces {
    pub(crate) levels: Vec<Vec<u32>>,
}

impl Traces {
    /// Flat form for the model file: the number of levels, then per level its word count and
    /// words.
    pub(crate) fn to_words(&self) -> Vec<u32> {
        let mut w = vec![self.levels.len() as u32];
        for l in &self.levels {
            w.push(l.len() as u32);
            w.extend_from_slice(l);
        }
        w
    }

    /// The traces of a model with memory `k` and `s` values placing each event
    /// ([`trace_places`]) whose levels have `nodes` nodes each, from [`Traces::to_words`]
    /// (loaded, untrusted): every level sized as the configuration sizes it
    /// ([`trace_words`]), every bottom node before a chunk a node, every bottom event a node
    /// or the end, every upper entry a node of its level (or the padding), every event's
    /// place `s` finite values (or all padding); otherwise what is wrong.
    pub(crate) fn from_words(
        w: &[u32],
        k: usize,
        s: usize,
        nodes: &[usize],
    ) -> Result<Traces, String> {
        let mut it = w.iter().copied();
        let mut next = |what: &str| it.next().ok_or_else(|| format!("traces end before {what}"));
        let levels = next("the level count")? as usize;
        if levels != nodes.len() {
            return Err(format!(
                "traces of {levels} levels, the model has {}",
                nodes.len()
            ));
        }
        let n0 = nodes[0];
        let mut out = Vec::with_capacity(levels);
        for (l, &n) in nodes.iter().enumerate() {
            let len = next("a level's length")? as usize;
            let want = if l == 0 { 0 } else { trace_words(k, l, s, n) };
            if len != want {
                return Err(format!("level {l} holds {len} words, {want} expected"));
            }
            let words = (0..len)
                .map(|_| next("a word"))
                .collect::<Result<Vec<u32>, String>>()?;
            if len > 0 {
                let width = trace_width(k, l, s).unwrap_or(usize::MAX);
                let span = k.pow(l as u32);
                let postures = trace_postures_at(k, l);
                for (i, slot) in words.chunks(width).enumerate() {
                    let bad = |what: &str, v: u32| {
                        format!(
                            "level {l} node {} chunk {}: {what} {v}",
                            i / TRACED_CHUNKS,
                            i % TRACED_CHUNKS
                        )
                    };
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
                        if let Some(&v) =
                            p.iter().find(|&&v| !none && !f32::from_bits(v).is_finite())
                        {
                            return Err(bad(&format!("event {j}'s posture value"), v));
                        }
                    }
                }
            }
            out.push(words);
        }
        if it.next().is_some() {
            return Err("traces go on past their last level".into());
        }
        Ok(Traces { levels: out })
    }
}

/// What decoding needs: the model and its encoding.
struct Decoder<'a> {
    model: &'a Hsom,
    lay: Layout,
    code: DurationCode,
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
    fn decode(
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
        let table = &model.followers[below];
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
                .then(|| (position - model.follower_at[row * FOLLOWERS + k]).abs())
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

/// Per entry of the follower table `table` of a level with `nodes` nodes, the mean position
/// at which that follower came after its row's entry in `seqs` (entries before it / `mean`,
/// the mean number of entries per sequence: the phase of a chunk's context, in its units);
/// 0 where the table holds none.
pub(crate) fn follower_positions(
    nodes: usize,
    seqs: &[Vec<u32>],
    table: &[u32],
    mean: f64,
) -> Vec<f64> {
    let mut sums: BTreeMap<(u32, u32), (f64, f64)> = BTreeMap::new();
    for sq in seqs {
        let mut prev = nodes as u32;
        for (i, &x) in sq.iter().enumerate() {
            let e = sums.entry((prev, x)).or_insert((0.0, 0.0));
            e.0 += i as f64 / mean.max(1.0);
            e.1 += 1.0;
            if x == END {
                break;
            }
            prev = x;
        }
    }
    table
        .iter()
        .enumerate()
        .map(|(k, &f)| {
            sums.get(&((k / FOLLOWERS) as u32, f))
                .map_or(0.0, |&(sum, count)| sum / count)
        })
        .collect()
}

/// The table of up to [`FOLLOWERS`] most frequent followers of every entry of a level (row
/// `nodes` is the begin of a demonstration; ties to the smaller index), from its entry
/// sequences. Its first column is the lookup table every level must beat.
pub(crate) fn followers_table(nodes: usize, seqs: &[Vec<u32>]) -> Vec<u32> {
    let mut counts: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for sq in seqs {
        let mut prev = nodes as u32;
        for &x in sq {
            *counts.entry((prev, x)).or_insert(0) += 1;
            if x == END {
                break;
            }
            prev = x;
        }
    }
    let mut rows: Vec<Vec<(u32, u32)>> = vec![Vec::new(); nodes + 1];
    for (&(a, b), &c) in &counts {
        rows[a as usize].push((c, b));
    }
    let mut t = vec![u32::MAX; (nodes + 1) * FOLLOWERS];
    for (i, r) in rows.iter_mut().enumerate() {
        r.sort_by(|x, y| y.0.cmp(&x.0).then(x.1.cmp(&y.1)));
        for (j, &(_, b)) in r.iter().take(FOLLOWERS).enumerate() {
            t[i * FOLLOWERS + j] = b;
        }
    }
    t
}

impl Hsom {
    /// Train the levels above the bottom on the events of `norm` (already normalised
    /// demonstrations; the bottom map is trained), level by level, and compute every
    /// statistic the events reproduction uses.
    pub(crate) fn fit_events<R: Rng>(&mut self, norm: &[Vec<Vec<f64>>], learn: bool, rng: &mut R) {
        self.fit_levels(norm, learn, rng);
        let (acc, lookup) = self.heldout_levels(norm, learn, rng.gen());
        self.heldout_accuracy = acc;
        self.heldout_lookup = lookup;
    }

    /// Each level's prediction accuracy and its lookup table's, held out: for every
    /// demonstration, the levels above the bottom trained again on the others (the bottom
    /// kept, fold seeds from `seed`) predict its entries, scored as in training
    /// ([`Hsom::replay_level`]); the counts are summed over the folds. With one
    /// demonstration nothing can be held out: the in-sample figures.
    fn heldout_levels(
        &self,
        norm: &[Vec<Vec<f64>>],
        learn: bool,
        seed: u64,
    ) -> (Vec<f64>, Vec<f64>) {
        let h = self.config.params().height;
        if norm.len() < 2 {
            return (self.accuracy.clone(), self.lookup.clone());
        }
        let lay = Layout::of(&self.config);
        // per level: predicted, right, looked up, right
        let mut counts = vec![[0u32; 4]; h];
        for j in 0..norm.len() {
            let train: Vec<Vec<Vec<f64>>> = norm
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != j)
                .map(|(_, d)| d.clone())
                .collect();
            let mut fold = self.clone();
            let mut frng = rand_chacha::ChaCha8Rng::seed_from_u64(seed.wrapping_add(j as u64));
            fold.fit_levels(&train, learn, &mut frng);
            let code = DurationCode::from_dwell(&fold.dwell);
            let mut items = fold.event_items(&bottom_events(&fold, &norm[j]), code);
            for (l, c) in counts.iter_mut().enumerate().skip(1) {
                let seq: Vec<u32> = items.iter().map(|i| i.node).collect();
                let (n, ok) = lookup_counts(
                    &fold.followers[l - 1],
                    fold.maps[l - 1].len(),
                    std::slice::from_ref(&seq),
                );
                let per_item = (lay.k as f64).powi(l as i32 - 1);
                let demo_chunks = vec![chunks(lay, &items, per_item, fold.demo_runs[1])];
                let mut r = fold.replay_level(l, std::slice::from_ref(&items), &demo_chunks, code);
                c[0] += r.predicted;
                c[1] += r.correct;
                c[2] += n;
                c[3] += ok;
                items = r.next_items.pop().unwrap_or_default();
                if items.is_empty() {
                    break;
                }
            }
        }
        let frac = |ok: u32, n: u32| if n > 0 { ok as f64 / n as f64 } else { 0.0 };
        (
            counts.iter().map(|c| frac(c[1], c[0])).collect(),
            counts.iter().map(|c| frac(c[3], c[2])).collect(),
        )
    }

    /// [`Hsom::fit_events`] without the held-out figures.
    fn fit_levels<R: Rng>(&mut self, norm: &[Vec<Vec<f64>>], learn: bool, rng: &mut R) {
        let cfg = self.config.clone();
        let p = cfg.params();
        let lay = Layout::of(&cfg);
        let n0 = self.maps[0].len();
        // what a previous fit of the levels left (a held-out fold starts from a clone)
        self.hits[1..].iter_mut().for_each(|v| v.fill(0));
        self.exemplars.iter_mut().for_each(|e| e.fill(u32::MAX));
        self.exemplar_phase.iter_mut().for_each(|e| e.fill(0.0));
        self.followers.iter_mut().for_each(|f| f.fill(u32::MAX));
        // 1. bottom events, their durations and the bottom's own lookup table
        let events: Vec<Vec<(usize, f64)>> = norm.iter().map(|d| bottom_events(self, d)).collect();
        let mut dsum = vec![0.0; n0];
        let mut dn = vec![0u32; n0];
        for ev in &events {
            for &(n, d) in ev {
                dsum[n] += d;
                dn[n] += 1;
            }
        }
        for i in 0..n0 {
            self.dwell[i] = if dn[i] > 0 {
                dsum[i] / dn[i] as f64
            } else {
                0.0
            };
        }
        let counts: Vec<f64> = events.iter().map(|e| e.len() as f64).collect();
        let nd = counts.len().max(1) as f64;
        self.demo_runs = [
            counts.iter().cloned().fold(f64::INFINITY, f64::min),
            counts.iter().sum::<f64>() / nd,
            counts.iter().cloned().fold(0.0, f64::max),
        ];
        let seqs0: Vec<Vec<u32>> = events
            .iter()
            .map(|e| e.iter().map(|&(n, _)| n as u32).chain([END]).collect())
            .collect();
        // the bottom's followers: its lookup table (the reflex at height 1) and the candidates
        // level 1 decodes among
        self.followers[0] = followers_table(n0, &seqs0);
        self.follower_at = follower_positions(n0, &seqs0, &self.followers[0], self.demo_runs[1]);
        let code = DurationCode::from_dwell(&self.dwell);
        let mean_events = self.demo_runs[1];
        // 2. level by level
        let mut items: Vec<Vec<Item>> =
            events.iter().map(|ev| self.event_items(ev, code)).collect();
        // every level's entries per demonstration, and per level every training chunk's
        // BMU and distance (for the traced chunks)
        let mut seqs_by_level: Vec<Vec<Vec<u32>>> = Vec::new();
        let mut chunk_bmus: Vec<Vec<(usize, f64, usize, usize)>> = vec![Vec::new()];
        let mut x = vec![0.0; lay.dim()];
        let mut mask = vec![true; lay.dim()];
        for l in 1..p.height {
            let seqs: Vec<Vec<u32>> = items
                .iter()
                .map(|it| it.iter().map(|i| i.node).collect())
                .collect();
            seqs_by_level.push(seqs.clone());
            let nodes_below = self.maps[l - 1].len();
            if l > 1 {
                self.followers[l - 1] = followers_table(nodes_below, &seqs);
            }
            let per_item = (lay.k as f64).powi(l as i32 - 1);
            let demo_chunks: Vec<_> = items
                .iter()
                .map(|it| chunks(lay, it, per_item, mean_events))
                .collect();
            let inputs: Vec<Vec<f64>> = demo_chunks
                .iter()
                .flatten()
                .map(|ch| {
                    ch.input(lay, lay.k, &mut x, &mut mask);
                    x.clone()
                })
                .collect();
            if inputs.is_empty() {
                break;
            }
            // initial weights: randomly chosen training inputs (from the seed)
            let map = &mut self.maps[l];
            for i in 0..map.len() {
                let pick = &inputs[rng.gen_range(0..inputs.len())];
                map.set_weights(i, pick);
            }
            let lp = &p.levels[l];
            let steps = if learn {
                (p.training_steps / lay.k.pow(l as u32)).max(20 * inputs.len())
            } else {
                0
            };
            for t in 0..steps {
                let prog = t as f64 / steps.max(1) as f64;
                let xi = &inputs[t % inputs.len()];
                let (b, _) = map.bmu(xi);
                map.update(
                    xi,
                    None,
                    b,
                    lp.learning_factor.at(prog),
                    lp.learning_radius.at(prog),
                    lp.neighbourhood,
                );
            }
            self.trained[l] = steps as u64;
            // every node's exemplar: the entries of its nearest training chunk among those
            // it is the BMU of
            let mut best = vec![f64::INFINITY; self.maps[l].len()];
            let mut bmus = Vec::new();
            for (di, dc) in demo_chunks.iter().enumerate() {
                for (ci, ch) in dc.iter().enumerate() {
                    ch.input(lay, lay.k, &mut x, &mut mask);
                    let (b, d2) = self.maps[l].bmu(&x);
                    bmus.push((b, d2, di, ci));
                    if d2 < best[b] {
                        best[b] = d2;
                        for j in 0..lay.k {
                            self.exemplars[l][b * lay.k + j] =
                                items[di].get(ci * lay.k + j).map_or(END, |i| i.node);
                        }
                        self.exemplar_phase[l][b] = ch.phase;
                    }
                }
            }
            // 3. replay: BMUs (the next level's entries), QE/TE, the match threshold, and the
            // prediction accuracy of this level against the lookup table of the level below
            let r = self.replay_level(l, &items, &demo_chunks, code);
            for it in r.next_items.iter().flatten() {
                self.hits[l][it.node as usize] = self.hits[l][it.node as usize].saturating_add(1);
            }
            let chunks = r.chunks.max(1) as f64;
            self.qe[l] = r.qe / chunks;
            self.te[l] = r.te as f64 / chunks;
            self.threshold[l] = r.threshold;
            self.accuracy[l] = if r.predicted > 0 {
                r.correct as f64 / r.predicted as f64
            } else {
                0.0
            };
            self.lookup[l] = lookup_accuracy(&self.followers[l - 1], nodes_below, &seqs);
            items = r.next_items;
            chunk_bmus.push(bmus);
        }
        self.traces = Some(self.traced_chunks(&seqs_by_level, chunk_bmus));
    }

    /// The traced chunks ([`Traces`]) from the entries per demonstration of every level below
    /// the top (`seqs[0]`: the bottom events' nodes, then the end) and every training chunk's
    /// (BMU, distance, demonstration, index) per level.
    fn traced_chunks(
        &self,
        seqs: &[Vec<Vec<u32>>],
        mut chunk_bmus: Vec<Vec<(usize, f64, usize, usize)>>,
    ) -> Traces {
        let (k, s) = (
            self.config.params().memory,
            trace_places(self.config.params()),
        );
        let mut levels = vec![Vec::new()];
        for l in 1..self.maps.len() {
            let nodes = self.maps[l].len();
            let words = trace_words(k, l, s, nodes);
            let Some(width) = trace_width(k, l, s).filter(|_| words > 0) else {
                levels.push(Vec::new());
                continue;
            };
            let mut w = vec![u32::MAX; words];
            let mut kept = vec![0usize; nodes];
            let mut mine = chunk_bmus
                .get_mut(l)
                .map(std::mem::take)
                .unwrap_or_default();
            mine.sort_by(|a, b| a.1.total_cmp(&b.1).then((a.2, a.3).cmp(&(b.2, b.3))));
            let span = k.pow(l as u32);
            for (b, _, d, q) in mine {
                if kept[b] == TRACED_CHUNKS {
                    continue;
                }
                let slot = &mut w[(b * TRACED_CHUNKS + kept[b]) * width..][..width];
                kept[b] += 1;
                let bottom = &seqs[0][d];
                let first = q * span;
                slot[0] = q as u32;
                slot[1] = bottom
                    .get(first.saturating_sub(1))
                    .copied()
                    .filter(|&e| e != END)
                    .unwrap_or(u32::MAX);
                slot[2] = d as u32;
                for (i, v) in slot[TRACE_HEAD..TRACE_HEAD + span].iter_mut().enumerate() {
                    *v = bottom.get(first + i).copied().unwrap_or(u32::MAX);
                }
                let mut at = trace_bmus_at(k, l, s);
                for (m, level) in seqs.iter().enumerate().take(l).skip(1) {
                    let count = k.pow((l - m) as u32);
                    for (i, v) in slot[at..at + count].iter_mut().enumerate() {
                        *v = level[d].get(q * count + i).copied().unwrap_or(u32::MAX);
                    }
                    at += count;
                }
            }
            levels.push(w);
        }
        Traces { levels }
    }

    /// A demonstration's bottom events as level 1's entries, ending with the end.
    pub(super) fn event_items(&self, events: &[(usize, f64)], code: DurationCode) -> Vec<Item> {
        let lay = Layout::of(&self.config);
        let mut v: Vec<Item> = events
            .iter()
            .map(|&(n, d)| Item {
                node: n as u32,
                content: event_content(&self.maps[0], n, d, code),
            })
            .collect();
        let last_b = v
            .last()
            .map_or_else(|| vec![0.0; lay.s], |it| b_part(lay, &it.content).to_vec());
        v.push(Item {
            node: END,
            content: end_content(lay, &last_b),
        });
        v
    }

    /// Replay the chunks of level `l` (trained) over `items`, the entries of the level below
    /// (`demo_chunks`: their chunks): at every slot the level's partial match predicts the
    /// entry, decoded as in reproduction, and is scored against the entry that came; each
    /// complete chunk's BMU is the next level's entry.
    fn replay_level(
        &self,
        l: usize,
        items: &[Vec<Item>],
        demo_chunks: &[Vec<Chunk>],
        code: DurationCode,
    ) -> LevelReplay {
        let lay = Layout::of(&self.config);
        let mut x = vec![0.0; lay.dim()];
        let mut mask = vec![true; lay.dim()];
        let used_below: Vec<usize> = if l == 1 {
            (0..self.maps[0].len())
                .filter(|&i| self.dwell[i] > 0.0)
                .collect()
        } else {
            used(self, l - 1)
        };
        let dec = Decoder {
            model: self,
            lay,
            code,
        };
        let mut r = LevelReplay {
            next_items: Vec::with_capacity(items.len()),
            predicted: 0,
            correct: 0,
            threshold: 0.0,
            qe: 0.0,
            te: 0,
            chunks: 0,
        };
        for (di, dc) in demo_chunks.iter().enumerate() {
            let mut v = Vec::with_capacity(dc.len());
            for (ci, ch) in dc.iter().enumerate() {
                for j in 0..lay.k {
                    let known = ch.input(lay, j, &mut x, &mut mask);
                    let (b, d2) = self.maps[l].bmu_masked(&x, &mask);
                    r.threshold = r.threshold.max((d2 / known as f64).sqrt());
                    let at = ci * lay.k + j;
                    if let Some(actual) = items[di].get(at).map(|i| i.node) {
                        let prev = if at == 0 {
                            u32::MAX
                        } else {
                            items[di][at - 1].node
                        };
                        let c = &self.maps[l].weights(b)[lay.slot_range(j)];
                        r.predicted += 1;
                        let hint = self.exemplar(l, b, j);
                        r.correct += u32::from(
                            dec.decode(l, c, &used_below, prev, at as f64, f64::NAN, hint)
                                == actual,
                        );
                    }
                }
                ch.input(lay, lay.k, &mut x, &mut mask);
                let (b, b2) = self.maps[l].best_two(&x);
                r.qe += dist2(&self.maps[l].weights(b), &x).sqrt();
                r.te += usize::from(self.maps[l].len() > 1 && !self.maps[l].are_neighbours(b, b2));
                r.chunks += 1;
                v.push(Item {
                    node: b as u32,
                    content: summary(lay, &self.maps[l].weights(b), code),
                });
            }
            r.next_items.push(v);
        }
        r
    }

    /// Entry `j` of the exemplar of node `n` of `level` (`u32::MAX`: none).
    fn exemplar(&self, level: usize, n: usize, j: usize) -> u32 {
        let k = self.config.params().memory;
        self.exemplars[level]
            .get(n * k + j)
            .copied()
            .unwrap_or(u32::MAX)
    }

    /// Reproduce with the events extension from the normalised initial posture `y0`.
    /// Whether reproduction may plan from level `l` (`algorithm = events`): level 1 always
    /// (the lowest level with a sequence); a level above only if it and every level between
    /// it and level 1, on their own training data, predicted the next entry of the level
    /// below more often than the lookup table of "next entry given the last one" counted on
    /// the same data (docs/ALGORITHM.md, passage 5). Always true with the paper's algorithm
    /// and for the bottom.
    pub fn level_trusted(&self, l: usize) -> bool {
        if self.config.params().kind() != crate::config::Algorithm::Events {
            return true;
        }
        (2..=l).all(|k| {
            self.accuracy.get(k).copied().unwrap_or(0.0)
                > self.lookup.get(k).copied().unwrap_or(0.0)
        })
    }

    pub(crate) fn reproduce_events(&self, y0: &[f64], r: &ReproductionParams) -> Reproduction {
        self.plan_events(y0, y0, &[], r)
    }

    /// The events reproduction after `prefix`, bottom events already executed from the
    /// normalised posture `start` (none: a reproduction from `start`): they are pushed up the
    /// lists exactly as executed events are, so every level's context and completed entries
    /// are theirs, and the plan continues from there. The postures returned start at `from`
    /// (the prefix's last posture) and hold only the continuation's events.
    fn plan_events(
        &self,
        start: &[f64],
        from: &[f64],
        prefix: &[(usize, f64)],
        r: &ReproductionParams,
    ) -> Reproduction {
        let (executed, stop) = self.plan_event_list(start, prefix, &[], r);
        self.timed_postures(start, from, &executed[prefix.len()..], stop)
    }

    /// The events of [`Hsom::plan_events`]: the prefix's, then the planned ones, each (node,
    /// duration in samples, level that planned it), and why the plan ended. The first
    /// planned events are `executed` where given (what was executed of an earlier plan: its
    /// nodes, for the durations observed): each is pushed up the lists in the plan's place,
    /// and where it surprises the levels the rest of the plan is made anew, as for any
    /// executed event.
    fn plan_event_list(
        &self,
        start: &[f64],
        prefix: &[(usize, f64)],
        observed: &[(usize, f64)],
        r: &ReproductionParams,
    ) -> (Vec<Step<usize>>, StopReason) {
        let cfg = &self.config;
        let p = cfg.params();
        let max_len = r.max_length;
        let lay = Layout::of(cfg);
        let s = lay.s;
        let h = p.height;
        let code = DurationCode::from_dwell(&self.dwell);
        let mean_events = self.demo_runs[1].max(1.0);
        let cap = ((self.demo_len[2] * r.length_factor).ceil() as usize).clamp(2, max_len.max(2));
        let used_levels: Vec<Vec<usize>> = (0..h)
            .map(|l| {
                if l == 0 {
                    (0..self.maps[0].len())
                        .filter(|&i| self.dwell[i] > 0.0)
                        .collect()
                } else {
                    used(self, l)
                }
            })
            .collect();
        let top = r.max_level.unwrap_or(h - 1).min(h - 1);
        // the initial event: the bottom node nearest to the initial posture (state half)
        let (n_init, _) = self.maps[0].bmu_range(start, 0..s);
        let init_content = event_content(&self.maps[0], n_init, 0.0, code);
        let mut lists = Lists::new(h, a_part(lay, &init_content));
        let mut plan: VecDeque<Step<u32>> = VecDeque::new();
        // the training demonstration the last traced plan came from
        let mut follow: Option<u32> = None;
        let mut executed: Vec<Step<usize>> = Vec::new();
        let mut x = vec![0.0; lay.dim()];
        let mut mask = vec![true; lay.dim()];
        let mut total = 0.0;
        let mut stop = StopReason::LearnedLength;
        let mut first = prefix.is_empty();
        for &(node, dur) in prefix {
            executed.push((node, dur, 0, None));
            total += dur;
            lists.push_event(self, lay, code, mean_events, node, dur);
        }
        'run: loop {
            if plan.is_empty() {
                lists.expected.iter_mut().for_each(|e| e.clear());
                // climb while the match lies within what the level saw in training
                let mut matched: Vec<usize> = vec![0; h];
                let mut level = 0;
                for (l, slot) in matched.iter_mut().enumerate().take(top + 1).skip(1) {
                    let known = lists.input(lay, l, mean_events, &mut x, &mut mask);
                    let (b, d2) = self.maps[l].bmu_masked(&x, &mask);
                    // level 1 always predicts (the lowest level with a sequence and a
                    // context); higher levels only while they are not confused
                    if l > 1
                        && (!self.level_trusted(l)
                            || (d2 / known as f64).sqrt()
                                > self.threshold[l] * (1.0 + 1e-9) + 1e-12)
                    {
                        break;
                    }
                    *slot = b;
                    level = l;
                }
                if level == 0 {
                    // confused everywhere: the bottom's lookup table (its reflex)
                    let last = executed.last().map_or(n_init, |e| e.0);
                    let next = if first {
                        n_init as u32
                    } else {
                        most_frequent(&self.followers[0], self.maps[0].len(), last as u32)
                    };
                    if next == u32::MAX || next == END {
                        stop = StopReason::EndEvent;
                        break 'run;
                    }
                    plan.push_back((next, self.dwell[next as usize].max(1.0), 0, None));
                } else {
                    let done: Vec<usize> = lists.chunk.iter().map(|c| c.len()).collect();
                    let here: Vec<f64> = match executed.last() {
                        Some(e) => self.maps[0].weights(e.0)[..s].to_vec(),
                        None => start[..s].to_vec(),
                    };
                    let ctx = Planner {
                        lay,
                        code,
                        matched: &matched,
                        done: &done,
                        used: &used_levels,
                        by: level,
                        executed: executed.len(),
                        here: &here,
                        index: &lists.index,
                    };
                    // the chunk in progress at the top level used is its own match
                    let mut tail = lists.tail.clone();
                    // where the plan is in the gesture: its top node's exemplar position
                    // (none for a node no training chunk chose)
                    let pos = if self.exemplar(level, matched[level], 0) == u32::MAX {
                        f64::NAN
                    } else {
                        self.exemplar_phase[level][matched[level]]
                    };
                    let traced =
                        self.traced_plan(&ctx, level, &mut follow, &mut plan, &mut lists.expected);
                    if !traced {
                        self.expand(
                            &ctx,
                            level,
                            matched[level],
                            done[level],
                            true,
                            pos,
                            &mut plan,
                            &mut lists.expected,
                            &mut tail,
                        );
                    }
                }
            }
            let planned = plan.pop_front();
            let (node, dur, by, at) = match (observed.get(executed.len() - prefix.len()), planned) {
                // an observed event keeps the planned one's place only where it is that event
                (Some(&(n, d)), planned) => match planned {
                    Some((m, _, by, at)) => (n as u32, d, by, at.filter(|_| m == n as u32)),
                    None => (n as u32, d, 0, None),
                },
                (None, Some(e)) => e,
                (None, None) => break,
            };
            first = false;
            if node == END {
                stop = StopReason::EndEvent;
                break;
            }
            let node = node as usize;
            // never past the cap, whatever a (loaded, untrusted) duration says
            let dur = dur.min(cap as f64 - total).max(1.0);
            executed.push((node, dur, by, at));
            total += dur;
            if total >= cap as f64 {
                stop = StopReason::LearnedLength;
                break;
            }
            // push the executed event up the lists, as in training; re-plan on surprise
            let surprise = lists.push_event(self, lay, code, mean_events, node, dur);
            if surprise {
                plan.clear();
            }
        }
        (executed, stop)
    }

    /// The plan of the demonstrated stretch node `matched[level]` stands for, from where the
    /// reproduction is in its chunk (docs/ALGORITHM.md, passage 5, `plan = traced`): of the
    /// training chunks the node keeps ([`Traces`]) at the reproduction's place in the gesture
    /// (the same chunk index), the one whose bottom event before it was nearest where the
    /// reproduction is (`ctx.here`: the last executed event's node, or the start; for a
    /// demonstration's first chunk its first event; ties to the one nearest the node's
    /// weights): the chunk that goes on from the event just executed. Its bottom events go to
    /// `plan` (at their nodes' learned durations), and the entries of every level below it
    /// completes to `expected` (the chunk's; the partial match for a chunk already begun).
    /// False where the node keeps no such chunk: the plan is then decoded.
    fn traced_plan(
        &self,
        ctx: &Planner<'_>,
        level: usize,
        follow: &mut Option<u32>,
        plan: &mut VecDeque<Step<u32>>,
        expected: &mut [VecDeque<u32>],
    ) -> bool {
        let Some(words) = self
            .traces
            .as_ref()
            .and_then(|t| t.levels.get(level))
            .filter(|w| !w.is_empty())
        else {
            return false;
        };
        let (k, s, pw) = (ctx.lay.k, ctx.lay.s, trace_places(self.config.params()));
        let n0 = self.maps[0].len();
        let Some(width) = trace_width(k, level, pw) else {
            return false;
        };
        let postures = trace_postures_at(k, level);
        let span = k.pow(level as u32);
        let n = ctx.matched[level];
        // bottom events the reproduction has completed in its current chunk of this level
        let off: usize = (1..=level).map(|m| ctx.done[m] * k.pow(m as u32 - 1)).sum();
        let index = ctx.index[level];
        let followed = *follow;
        // the demonstration followed goes on; otherwise the node matched, otherwise any;
        // nearest first, then nearest the node's weights (the first of equals)
        let best = words
            .chunks_exact(width)
            .enumerate()
            .filter(|(_, slot)| {
                slot[0] as usize == index
                    && off < span
                    && slot[TRACE_HEAD + off] != u32::MAX
                    && (slot[1] as usize) < n0
            })
            .map(|(i, slot)| {
                let d = dist2(&self.maps[0].weights(slot[1] as usize)[..s], ctx.here);
                (slot, Some(slot[2]) != followed, i / TRACED_CHUNKS != n, d)
            })
            .min_by(|a, b| a.1.cmp(&b.1).then(a.2.cmp(&b.2)).then(a.3.total_cmp(&b.3)));
        let Some((slot, ..)) = best else {
            *follow = None;
            return false;
        };
        *follow = Some(slot[2]);
        let mut end = off;
        for &e in &slot[TRACE_HEAD + off..TRACE_HEAD + span] {
            if e == u32::MAX || (e != END && e as usize >= n0) {
                break;
            }
            end += 1;
            if e == END {
                plan.push_back((END, 0.0, ctx.by, None));
                break;
            }
            // where this event of that demonstration lies in the consensus (none stored:
            // where its node is placed)
            let at = &slot[postures + (end - 1) * pw..postures + end * pw];
            let at =
                (at[0] != u32::MAX).then(|| at.iter().map(|&v| f32::from_bits(v) as f64).collect());
            plan.push_back((e, self.dwell[e as usize].max(1.0), ctx.by, at));
        }
        let mut at = trace_bmus_at(k, level, pw);
        for (m, exp) in expected.iter_mut().enumerate().take(level).skip(1) {
            let count = k.pow((level - m) as u32);
            let sm = k.pow(m as u32);
            let mut q = off / sm;
            while (q + 1) * sm <= end {
                let e = if q == off / sm && off % sm != 0 {
                    ctx.matched[m] as u32
                } else {
                    slot[at + q]
                };
                if e == u32::MAX {
                    break;
                }
                exp.push_back(e);
                q += 1;
            }
            at += count;
        }
        true
    }

    /// Expand the prediction of node `n` of `level` from slot `from` into timed bottom
    /// events (`plan`), and the entries of every level it expects (`expected`). With
    /// `in_progress`, the slot `from` is the chunk being executed below: it is the lower
    /// level's own match (`matched`), expanded from what that chunk has completed (`done`).
    #[allow(clippy::too_many_arguments)]
    fn expand(
        &self,
        ctx: &Planner<'_>,
        level: usize,
        n: usize,
        from: usize,
        in_progress: bool,
        pos: f64,
        plan: &mut VecDeque<Step<u32>>,
        expected: &mut [VecDeque<u32>],
        tail: &mut [u32],
    ) -> bool {
        let lay = ctx.lay;
        let w = self.maps[level].weights(n);
        let mean_events = self.demo_runs[1].max(1.0);
        for j in from..lay.k {
            let c = &w[lay.slot_range(j)];
            let slot_pos = pos + (j * lay.k.pow(level as u32 - 1)) as f64 / mean_events;
            if level == 1 {
                let before = (ctx.executed + plan.len()) as f64;
                let e = ctx.decoder(self).decode(
                    1,
                    c,
                    &ctx.used[0],
                    tail[0],
                    before,
                    slot_pos,
                    self.exemplar(1, n, j),
                );
                tail[0] = e;
                if e == END {
                    plan.push_back((END, 0.0, ctx.by, None));
                    return true;
                }
                plan.push_back((e, self.dwell[e as usize].max(1.0), ctx.by, None));
            } else {
                let (m, sub_from, sub_prog) = if in_progress && j == from {
                    (ctx.matched[level - 1] as u32, ctx.done[level - 1], true)
                } else {
                    let prev = tail[level - 1];
                    let dec = ctx.decoder(self);
                    (
                        dec.decode(
                            level,
                            c,
                            &ctx.used[level - 1],
                            prev,
                            0.0,
                            f64::NAN,
                            self.exemplar(level, n, j),
                        ),
                        0,
                        false,
                    )
                };
                tail[level - 1] = m;
                if m == END {
                    plan.push_back((END, 0.0, ctx.by, None));
                    return true;
                }
                expected[level - 1].push_back(m);
                if self.expand(
                    ctx,
                    level - 1,
                    m as usize,
                    sub_from,
                    sub_prog,
                    slot_pos,
                    plan,
                    expected,
                    tail,
                ) {
                    return true;
                }
            }
        }
        false
    }
}

impl Hsom {
    /// Where a reproduction that starts at `start` (normalised) places every bottom node's
    /// events, `stateLength` values per node: with `consensus = start` the training
    /// demonstrations' placements weighed by their starts ([`StartKnots`]); otherwise the
    /// branch's own postures ([`Hsom::fit_postures`]) when it has them, else the nodes'
    /// weights (state part).
    fn placement(&self, start: &[f64]) -> Vec<f64> {
        let s = self.config.params().state_length;
        if let Some(k) = &self.start_knots {
            return k.placed(start);
        }
        match &self.knots {
            Some(k) => k.clone(),
            None => (0..self.maps[0].len())
                .flat_map(|n| self.maps[0].weights(n)[..s].to_vec())
                .collect(),
        }
    }

    /// The *own postures* of `norm` (normalised demonstrations): each node at its own
    /// samples' mean, with no consensus between the demonstrations (a test's control).
    #[cfg(test)]
    pub(crate) fn own_postures(&self, norm: &[Vec<Vec<f64>>]) -> Vec<f64> {
        let mut total = NodeSums::new(self.maps[0].len(), self.config.params().state_length);
        for demo in norm {
            total.add(&NodeSums::of(self, demo, &bottom_events(self, demo)));
        }
        self.smoothed_postures(&total)
    }

    /// The postures (state part, normalised) of every bottom node as the values in `sums`
    /// realise it: the bottom map's last training step done in batch on these values alone,
    /// i.e. per node the mean of the values of the events on it, weighted by the map's
    /// neighbourhood at its final radius around each event's node. A node no event is on
    /// keeps its weights. Flattened, `stateLength` values per node. [`Hsom::fit_postures`]
    /// gives it the demonstrations' consensus (docs/ALGORITHM.md, passage 6 of the events
    /// extension, and "Several gestures").
    fn smoothed_postures(&self, sums: &NodeSums) -> Vec<f64> {
        let p = self.config.params();
        let s = p.state_length;
        let map = &self.maps[0];
        let n = map.len();
        let (h, r) = (p.levels[0].neighbourhood, p.levels[0].learning_radius.last);
        let mut out = vec![0.0; n * s];
        for j in 0..n {
            let row = &mut out[j * s..(j + 1) * s];
            if sums.count[j] == 0.0 {
                row.copy_from_slice(&map.weights(j)[..s]);
                continue;
            }
            let mut w_sum = 0.0;
            for i in (0..n).filter(|&i| sums.count[i] > 0.0) {
                let w = h.weight(map.grid_distance2(i, j), r);
                w_sum += w * sums.count[i];
                for (acc, v) in row.iter_mut().zip(&sums.sum[i * s..(i + 1) * s]) {
                    *acc += w * v;
                }
            }
            row.iter_mut().for_each(|v| *v /= w_sum);
        }
        out
    }

    /// Where a reproduction places each bottom node's events, learned from `norm` (the
    /// normalised demonstrations this model or branch was trained on): the demonstrations'
    /// [`consensus`] over the samples of the node's events, smoothed by the map's
    /// neighbourhood at its final radius as the bottom's last training step would
    /// ([`Hsom::smoothed_postures`]). A reproduction follows one demonstrated sequence of
    /// nodes; placed at the consensus, each node's events land where the demonstrations
    /// agree, not where the one demonstration that visited it went, nor where the map's
    /// neighbourhood pulled its weights. With one demonstration there is nothing to agree
    /// on: the weights (and no stored postures).
    pub(crate) fn fit_postures(&mut self, norm: &[Vec<Vec<f64>>]) {
        self.knots = None;
        self.start_knots = None;
        self.end_postures = Some(self.ends(norm));
        let aligned = aligned_samples(norm, MAX_ALIGNED);
        self.fit_node_postures(norm, &aligned);
        self.place_traced_events(norm, &aligned);
    }

    /// The nodes' places of [`Hsom::fit_postures`] (`aligned`: [`aligned_samples`] of
    /// `norm`).
    fn fit_node_postures(&mut self, norm: &[Vec<Vec<f64>>], aligned: &Aligned) {
        if norm.len() < 2 {
            return;
        }
        let s = self.config.params().state_length;
        let events: Vec<Vec<(usize, f64)>> = norm.iter().map(|d| bottom_events(self, d)).collect();
        let mut count = NodeSums::new(self.maps[0].len(), s);
        for (demo, ev) in norm.iter().zip(&events) {
            count.add(&NodeSums::of(self, demo, ev));
        }
        let knots: Vec<Vec<f64>> = (0..norm.len())
            .map(|d| {
                let mut sums = NodeSums::new(self.maps[0].len(), s);
                for (a, ev) in events.iter().enumerate() {
                    let values = aligned[a][d].as_ref().unwrap_or(&norm[a]);
                    sums.add(&NodeSums::of(self, values, ev));
                }
                self.smoothed_postures(&sums)
            })
            .collect();
        let all: Vec<&Vec<f64>> = knots.iter().collect();
        self.knots = Some(StartKnots::mean(&all, &vec![1.0; all.len()]));
        let starts = norm.iter().map(|d| d[0][..s].to_vec()).collect();
        let seed = self.config.params().seed;
        let weighed = StartKnots::fit(starts, knots, &count.count, seed);
        // all alike is the mean already stored: nothing more to keep
        self.start_knots = weighed.width.is_finite().then_some(weighed);
    }

    /// Per demonstration of `norm` (normalised), per bottom event, where that event lies in
    /// the demonstrations' consensus, as an offset from where its node is placed for a
    /// reproduction from that demonstration's start ([`Hsom::placement`]); state part. The
    /// consensus is the mean over the event's samples of every demonstration's samples
    /// aligned to them (its own for itself): with `consensus = start`, where the starts are
    /// used, weighed by that demonstration's start as [`StartKnots`] weighs them; otherwise
    /// all alike ([`consensus`]). A plan
    /// that follows a demonstration places its events at their node's place plus this offset
    /// (docs/ALGORITHM.md, passage 6, "Traced events"): the demonstrations' agreement at that
    /// event of that demonstration, where a node's place pools every visit to the node, from
    /// wherever in the gesture it came. Per event the model keeps, in the traced chunks, this
    /// offset, each half's, and each half's lowest and highest consensus values per variable
    /// (as offsets from the same place; [`trace_places`]).
    pub(crate) fn event_offsets(
        &self,
        norm: &[Vec<Vec<f64>>],
        aligned: &Aligned,
    ) -> Vec<Vec<(usize, Vec<f64>)>> {
        let s = self.config.params().state_length;
        let agreed: Vec<Vec<Vec<f64>>> = match &self.start_knots {
            Some(k) => {
                let starts: Vec<Vec<f64>> = norm.iter().map(|d| d[0][..s].to_vec()).collect();
                let refs: Vec<&Vec<f64>> = starts.iter().collect();
                (0..norm.len())
                    .map(|d| {
                        let w = StartKnots::weights(&refs, &starts[d], k.width);
                        let total: f64 = w.iter().sum();
                        (0..norm[d].len())
                            .map(|t| {
                                let mut m = vec![0.0; s];
                                for (a, wa) in w.iter().enumerate() {
                                    let x = match &aligned[d][a] {
                                        Some(al) if a != d => &al[t],
                                        _ => &norm[d][t],
                                    };
                                    m.iter_mut().zip(x).for_each(|(v, x)| *v += wa / total * x);
                                }
                                m
                            })
                            .collect()
                    })
                    .collect()
            }
            None => consensus(norm, aligned),
        };
        norm.iter()
            .zip(&agreed)
            .map(|(demo, values)| {
                let placed = self.placement(&demo[0]);
                let mut pos = 0usize;
                bottom_events(self, demo)
                    .into_iter()
                    .map(|(n, len)| {
                        let rows = &values[pos..pos + len as usize];
                        pos += len as usize;
                        let offset = |rows: &[Vec<f64>]| {
                            let mut m: Vec<f64> =
                                placed[n * s..(n + 1) * s].iter().map(|v| -v).collect();
                            for r in rows {
                                m.iter_mut()
                                    .zip(r.iter())
                                    .for_each(|(a, v)| *a += v / rows.len() as f64);
                            }
                            m
                        };
                        let mut m = offset(rows);
                        // the first half the first len / 2 samples (at least one), the
                        // second the rest (the whole event where it has one sample)
                        let h = (rows.len() / 2).max(1);
                        let parts = [&rows[..h], if h < rows.len() { &rows[h..] } else { rows }];
                        for part in parts {
                            m.extend(offset(part));
                        }
                        // where a turn in each half reaches: its extremes per variable
                        for part in parts {
                            for pick in [f64::min, f64::max] {
                                m.extend((0..s).map(|j| {
                                    let e = part.iter().map(|r| r[j]).reduce(pick);
                                    e.unwrap_or(placed[n * s + j]) - placed[n * s + j]
                                }));
                            }
                        }
                        (n, m)
                    })
                    .collect()
            })
            .collect()
    }

    /// The traced chunks' events placed ([`Traces`], [`Hsom::event_offsets`] of `norm`, the
    /// normalised demonstrations the traces were made from, once the nodes are placed): each
    /// traced event's offset from its node's place; where the demonstration's events do not
    /// match the traced ones (other demonstrations), none.
    fn place_traced_events(&mut self, norm: &[Vec<Vec<f64>>], aligned: &Aligned) {
        let Some(mut traces) = self.traces.take() else {
            return;
        };
        let own = self.event_offsets(norm, aligned);
        let (k, s) = (
            self.config.params().memory,
            trace_places(self.config.params()),
        );
        for (l, words) in traces.levels.iter_mut().enumerate().skip(1) {
            let Some(width) = trace_width(k, l, s).filter(|_| !words.is_empty()) else {
                continue;
            };
            let span = k.pow(l as u32);
            let postures = trace_postures_at(k, l);
            for slot in words.chunks_exact_mut(width).filter(|w| w[0] != u32::MAX) {
                let (q, d) = (slot[0] as usize, slot[2] as usize);
                for i in 0..span {
                    let e = slot[TRACE_HEAD + i];
                    let at = &mut slot[postures + i * s..postures + (i + 1) * s];
                    at.fill(u32::MAX);
                    let Some((n, offset)) = own.get(d).and_then(|o| o.get(q * span + i)) else {
                        continue;
                    };
                    if *n as u32 == e {
                        for (w, v) in at.iter_mut().zip(offset) {
                            *w = (*v as f32).to_bits();
                        }
                    }
                }
            }
        }
        self.traces = Some(traces);
    }

    /// Where the demonstrations `norm` (normalised) ended: per bottom node, how many had
    /// their last event on it, then the mean of their last postures (`stateLength` values;
    /// [`Hsom::end_postures`](super::algorithm::Hsom)).
    fn ends(&self, norm: &[Vec<Vec<f64>>]) -> Vec<f64> {
        let (n0, s) = (self.maps[0].len(), self.config.params().state_length);
        let mut out = vec![0.0; n0 + s];
        let mut k = 0.0;
        for demo in norm {
            let (Some(&(node, _)), Some(last)) = (bottom_events(self, demo).last(), demo.last())
            else {
                continue;
            };
            out[node] += 1.0;
            k += 1.0;
            for (m, v) in out[n0..].iter_mut().zip(last) {
                *m += (v - *m) / k;
            }
        }
        out
    }

    /// Where a reproduction whose last event is on node `n` ends by its end event, when no
    /// demonstration ended after `n` (the end decoded by content after another node): where
    /// all of them ended. `None` after a node one ended after (its last event's learned
    /// action leads there, from the mean of many samples) and without end postures.
    fn end_posture(&self, n: usize) -> Option<Vec<f64>> {
        let ends = self.end_postures.as_ref()?;
        let n0 = self.maps[0].len();
        (ends[n] == 0.0 && ends[..n0].iter().any(|&c| c > 0.0)).then(|| ends[n0..].to_vec())
    }

    /// Postures at every sample from the executed events: each event's node posture (its
    /// state half) is reached at the middle of the event, the initial posture is the first
    /// knot, and the last event ends where its node's learned action leads (its action half,
    /// the posture `actionHorizon` samples later, reached in proportion to the event's
    /// second half: a gesture that ends in motion is not cut at the middle of its last
    /// event; one that ends in a hold ends there, action and state being equal); in between a monotone cubic
    /// (Fritsch-Carlson) per variable, so holds are held and the motion starts and ends at
    /// rest; a knot at a turning point is moved so that the event's mean is its node's posture
    /// ([`turning_points_kept`]), the only place the curve goes beyond its knots.
    fn timed_postures(
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
    fn timed_knots(
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
    fn knot_places(
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
    fn curve(&self, timed: &Timed, m0: &[f64], samples: usize, stop: StopReason) -> Reproduction {
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
struct Places {
    /// Knot times, samples from the first.
    t: Vec<f64>,
    /// Per knot, its place (`stateLength` values, normalised).
    v: Vec<Vec<f64>>,
    /// Per knot, the level that planned its event.
    by: Vec<usize>,
    /// Per knot, whether its place is the mean of the followed demonstration's consensus over
    /// its span (a traced event or half; [`turning_points_kept`]).
    traced_mean: Vec<bool>,
    /// Per knot of a traced half, the lowest and highest values of the
    /// followed demonstration's consensus over its span (normalised): where a turn there
    /// reaches ([`turning_points_kept`]).
    reach: Vec<Option<(Vec<f64>, Vec<f64>)>>,
    /// Per knot after the first, the samples of its event or half.
    spans: Vec<(usize, usize)>,
    /// The events' total duration, samples.
    total: f64,
}

/// Knots of a timed reproduction ([`Hsom::timed_knots`]).
struct Timed {
    /// Knot times, samples from the first.
    t: Vec<f64>,
    /// Per variable, the value at each knot.
    values: Vec<Vec<f64>>,
    /// Per knot, the level that planned its event.
    by: Vec<usize>,
    /// The events' total duration, samples.
    total: f64,
}

impl Timed {
    /// The same curve from `now` samples on, starting at `from`: the knots after `now` (by
    /// half a sample at least), shifted to start there.
    fn from(&self, now: f64, from: &[f64]) -> Timed {
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
fn monotone_cubic(t: &[f64], v: &[f64], samples: usize) -> Vec<f64> {
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
/// knot's place is a mean. Measured: docs/ALGORITHM.md, passage 6, "Two knots per event".
const HALF_SAMPLES: f64 = 2.0;

/// Most corrections [`turning_points_kept`] makes (it converges in 3-4 on gestures; the cap
/// only bounds the work).
const TURNING_ITERATIONS: usize = 20;

/// One variable's knots with its *turning points kept*: a knot that is a strict local extremum
/// of its neighbours (the initial posture and the end are never moved) is moved until the
/// monotone cubic's mean over its event's samples (`spans[i - 1]` for knot i) equals the
/// node's posture (`target[i]`). A node's posture is the mean of the samples of its events
/// (the consensus, passage 6); at a turning point those samples lie on both sides of the
/// turn, so their mean lies inside it, and a curve that merely passes through the mean turns
/// short (the wave's troughs 0.05-0.15 rad). Elsewhere the mean of a segment is its middle
/// value and the knot stays. A fixed point, reached in a few corrections; docs/ALGORITHM.md,
/// passage 6 of the events extension.
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
/// the unevenness between them (jerk; docs/ALGORITHM.md, passage 6).
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
/// it 0.28 rad, under the swing count's 0.3; docs/ALGORITHM.md, passage 6, "Where a turn
/// reaches").
fn turning_points_kept(
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
fn monotone_tangents(t: &[f64], v: &[f64]) -> Vec<f64> {
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

/// The reproduction's short-term memory, as in training: per level l >= 1 the entries of
/// level l-1 completed in its current chunk, the chunk's context and index; per level its
/// last completed entry; and the entries the current plan expects each level to complete.
#[derive(Debug, Clone)]
struct Lists {
    chunk: Vec<Vec<Item>>,
    prev: Vec<Vec<f64>>,
    index: Vec<usize>,
    /// Last completed entry per level (`u32::MAX`: the begin).
    tail: Vec<u32>,
    expected: Vec<VecDeque<u32>>,
}

impl Lists {
    fn new(height: usize, start: &[f64]) -> Self {
        Lists {
            chunk: vec![Vec::new(); height],
            prev: vec![start.to_vec(); height],
            index: vec![0; height],
            tail: vec![u32::MAX; height],
            expected: vec![VecDeque::new(); height],
        }
    }

    /// The input of level `l`'s current chunk (completed slots known); the known count.
    fn input(
        &self,
        lay: Layout,
        l: usize,
        mean_events: f64,
        x: &mut [f64],
        mask: &mut [bool],
    ) -> usize {
        let refs: Vec<&[f64]> = self.chunk[l].iter().map(|i| i.content.as_slice()).collect();
        let phase = (self.index[l] * lay.k.pow(l as u32)) as f64 / mean_events;
        chunk_input(
            lay,
            &self.prev[l],
            self.index[l] == 0,
            phase,
            &refs,
            x,
            mask,
        )
    }

    /// Push an executed bottom event up the lists exactly as in training: every chunk it
    /// completes is matched by its level and pushed one level up. True when a completed
    /// chunk's node is not the one the plan expected there (a surprise).
    fn push_event(
        &mut self,
        model: &Hsom,
        lay: Layout,
        code: DurationCode,
        mean_events: f64,
        node: usize,
        dur: f64,
    ) -> bool {
        let mut x = vec![0.0; lay.dim()];
        let mut mask = vec![true; lay.dim()];
        self.tail[0] = node as u32;
        let mut item = Item {
            node: node as u32,
            content: event_content(&model.maps[0], node, dur, code),
        };
        let mut surprise = false;
        for l in 1..self.chunk.len() {
            self.chunk[l].push(item);
            if self.chunk[l].len() < lay.k {
                break;
            }
            self.input(lay, l, mean_events, &mut x, &mut mask);
            let (b, _) = model.maps[l].bmu(&x);
            self.prev[l] = b_part(lay, &self.chunk[l][lay.k - 1].content).to_vec();
            self.chunk[l].clear();
            self.index[l] += 1;
            self.tail[l] = b as u32;
            if let Some(e) = self.expected[l].pop_front() {
                surprise |= e != b as u32;
            }
            item = Item {
                node: b as u32,
                content: summary(lay, &model.maps[l].weights(b), code),
            };
        }
        surprise
    }
}

impl Planner<'_> {
    fn decoder<'m>(&self, model: &'m Hsom) -> Decoder<'m> {
        Decoder {
            model,
            lay: self.lay,
            code: self.code,
        }
    }
}

/// What a plan is made from.
struct Planner<'a> {
    lay: Layout,
    code: DurationCode,
    /// Per level, the partial match of its current chunk.
    matched: &'a [usize],
    /// Per level, the entries its current chunk has completed.
    done: &'a [usize],
    /// Per level, its used nodes.
    used: &'a [Vec<usize>],
    /// The level the plan comes from.
    by: usize,
    /// Bottom events executed before the plan.
    executed: usize,
    /// Where the reproduction is: the last executed event's node's posture (the start
    /// posture before any).
    here: &'a [f64],
    /// Per level, the index of its current chunk.
    index: &'a [usize],
}

impl Hsom {
    /// The demonstration through the bottom level's own code and back: its events (the
    /// bottom node of each run of samples and the run's length, as in training) turned into
    /// postures exactly as a reproduction's planned events are. No upper level is involved,
    /// so this is the ceiling of what the hierarchy can reproduce of that demonstration:
    /// whatever is lost here (a swing's amplitude, a short hold) the levels above cannot
    /// bring back. `predicted_by` is 0 throughout.
    pub fn reencode(&self, demo: &Demonstration) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        check_series(
            &demo_series(std::slice::from_ref(demo)),
            p.state_length,
            p.action_horizon(),
        )?;
        let norm: Vec<Vec<f64>> = demo.rows.iter().map(|r| self.normalise(r)).collect();
        let executed: Vec<Step<usize>> = bottom_events(self, &norm)
            .into_iter()
            .map(|(n, d)| (n, d, 0, None))
            .collect();
        Ok(self.timed_postures(&norm[0], &norm[0], &executed, StopReason::EndEvent))
    }

    /// The *nearest-sequence* baseline (docs/ALGORITHM.md, "A simpler thing"): of the
    /// demonstrations `demos` (a model's training demonstrations), the one whose first
    /// posture is nearest `initial` (in the model's normalised units), its bottom events
    /// executed from `initial` exactly as a reproduction's planned events are: each event's
    /// node at the posture where the model places it, for the node's learned mean duration
    /// (its own length where the node has none). No level above the bottom is involved:
    /// this is a reproduction whose plan is one whole demonstrated sequence of bottom nodes,
    /// the one that starts nearest, where the levels' plan is built chunk by chunk.
    /// `predicted_by` is 0 throughout.
    pub fn follow_nearest(
        &self,
        demos: &[Demonstration],
        initial: &[f64],
    ) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        check_series(&demo_series(demos), p.state_length, p.action_horizon())?;
        self.check_initial(initial)?;
        let y0 = self.normalise(initial);
        let nearest = demos
            .iter()
            .map(|d| dist2(&self.normalise(&d.rows[0]), &y0))
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
            .ok_or(HsomError::NoDemonstrations)?;
        let all: Vec<Vec<Vec<f64>>> = demos.iter().map(|d| self.normalise_rows(&d.rows)).collect();
        let executed = self.followed(&all, nearest, None);
        Ok(self.timed_postures(&y0, &y0, &executed, StopReason::EndEvent))
    }

    /// The bottom events of `norm[d]` (normalised demonstrations) that begin after sample
    /// `after` (all of them for `None`), as planned ones, as a reproduction whose plan follows
    /// that demonstration executes them: each for its node's learned mean duration (its own
    /// length where the node has none); with `plan = traced`, each at that event's place in
    /// the consensus of `norm` ([`Hsom::event_postures`]), as a traced plan places it.
    fn followed(&self, norm: &[Vec<Vec<f64>>], d: usize, after: Option<f64>) -> Vec<Step<usize>> {
        let own = self
            .traces
            .is_some()
            .then(|| self.event_offsets(norm, &aligned_samples(norm, MAX_ALIGNED)));
        let mut begun = 0.0;
        bottom_events(self, &norm[d])
            .into_iter()
            .enumerate()
            .filter(|&(_, (_, len))| {
                let keep = after.map_or(true, |a| begun > a);
                begun += len;
                keep
            })
            .map(|(i, (n, len))| {
                let learned = self.dwell.get(n).copied().unwrap_or(0.0);
                let at = own.as_ref().map(|o| o[d][i].1.clone());
                (n, if learned > 0.0 { learned } else { len }, 0, at)
            })
            .collect()
    }

    /// The normalised rows of `prefix` (the first samples of a gesture, in the data's units;
    /// `source` names it in errors), once checked as a demonstration is.
    fn normalised_prefix(
        &self,
        source: &'static str,
        prefix: &[Vec<f64>],
    ) -> Result<Vec<Vec<f64>>, HsomError> {
        let p = self.config.params();
        check_series(
            &[super::algorithm::Series {
                source,
                rows: prefix,
            }],
            p.state_length,
            p.action_horizon(),
        )?;
        Ok(self.normalise_rows(prefix))
    }

    /// Continue a gesture from its first samples (`prefix`, in the data's units; at least
    /// `actionHorizon + 1` of them) with the events extension's own machinery: the prefix's
    /// bottom events are pushed up the lists exactly as executed events are (each level's
    /// context, phase and completed entries become the prefix's), and the levels plan the rest
    /// from there (docs/ALGORITHM.md, "Continuing a prefix"). The postures start at the
    /// prefix's last posture and hold only the continuation. Needs `algorithm = events`.
    pub fn continue_events(&self, prefix: &[Vec<f64>]) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        if p.kind() != crate::config::Algorithm::Events {
            return Err(HsomError::NeedsEvents {
                what: "continuing a prefix".into(),
                algorithm: format!("{:?}", p.algorithm).to_lowercase(),
            });
        }
        let norm = self.normalised_prefix("prefix", prefix)?;
        let events = bottom_events(self, &norm);
        let last = &norm[norm.len() - 1];
        let r = &p.reproduction;
        let mut rep = self.plan_events(&norm[0], last, &events, r);
        rep.truncate(r.max_length);
        Ok(rep)
    }

    /// Resume this model's own reproduction from `initial` after part of it was executed:
    /// `reading` is what the encoders read meanwhile (in the data's units, from `initial`; at
    /// least `actionHorizon + 1` samples), possibly disturbed (held still, slowed, pushed).
    /// The closed loop of passage 5 on the plan's own events (docs/ALGORITHM.md, "In a closed
    /// loop"): the reproduction is planned again from `initial` (it is deterministic), the
    /// reading is aligned with its postures by DTW (open end, the model's normalised units),
    /// so each planned event begun by the reading's end has an observed duration (the reading
    /// samples aligned with it); the plan is then made again with those events executed for
    /// those durations, each pushed up the lists, and where one surprises the levels (a chunk
    /// completed otherwise than expected) the rest is planned anew; the event in progress goes
    /// on for what is left of it. Read back without a disturbance this is the plan itself.
    /// The events are the plan's own, not the reading encoded again: a reproduction's reading
    /// encodes into more bottom events than were planned, and the lists' phase counts events.
    /// The postures start at the reading's last posture and hold only the continuation.
    /// Needs `algorithm = events`.
    pub fn resume(&self, initial: &[f64], reading: &[Vec<f64>]) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        if p.kind() != crate::config::Algorithm::Events {
            return Err(HsomError::NeedsEvents {
                what: "resuming a reproduction".into(),
                algorithm: format!("{:?}", p.algorithm).to_lowercase(),
            });
        }
        self.check_initial(initial)?;
        let norm = self.normalised_prefix("reading", reading)?;
        let y0 = self.normalise(initial);
        let r = &p.reproduction;
        let (events, stop) = self.plan_event_list(&y0, &[], &[], r);
        let plan = self.normalise_rows(&self.timed_postures(&y0, &y0, &events, stop).postures);
        // the alignment keeps a cell per (reading, plan) sample pair: bounded as the
        // consensus's alignments are
        let most = MAX_ALIGNED * MAX_ALIGNED / plan.len().max(1);
        if norm.len() > most {
            return Err(HsomError::ReadingTooLong {
                rows: norm.len(),
                most,
                plan: plan.len(),
            });
        }
        let (executed, left) = observed_durations(&norm, &plan, &events);
        let from = &norm[norm.len() - 1];
        if executed.is_empty() {
            return Ok(self.plan_events(&y0, from, &[], r));
        }
        // the events begun are executed as observed (the one in progress as it will have
        // lasted), and the plan is made again from there; the one in progress goes on first
        let (all, stop) = self.plan_event_list(&y0, &[], &executed, r);
        // the continuation is the whole plan's curve (the events executed as observed, then
        // the rest), from where the reading is along it: it starts at the reading's last
        // posture, moving as the encoders read, and goes on through the plan's knots after
        // that time (each turning point kept as in the whole plan)
        let timed = self.timed_knots(&y0, &y0, &all, stop);
        let now = executed.iter().map(|e| e.1).sum::<f64>() - left;
        let rest = timed.from(now, from);
        let v0: Vec<f64> = from
            .iter()
            .zip(&norm[norm.len() - 2])
            .map(|(a, b)| a - b)
            .collect();
        let samples = rest.total.floor() as usize + 1;
        let mut rep = self.curve(&rest, &v0, samples, stop);
        rep.truncate(r.max_length);
        Ok(rep)
    }

    /// The nearest-sequence baseline for a prefix: of `demos`, the one along which `prefix`
    /// runs closest (open-end DTW in the model's normalised units, per prefix sample), its
    /// bottom events after the sample where the prefix ends along it, executed from the
    /// prefix's last posture as [`Hsom::follow_nearest`] executes them. The postures start
    /// at the prefix's last posture and hold only the continuation.
    pub fn follow_nearest_from(
        &self,
        demos: &[Demonstration],
        prefix: &[Vec<f64>],
    ) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        check_series(&demo_series(demos), p.state_length, p.action_horizon())?;
        let norm = self.normalised_prefix("prefix", prefix)?;
        let all: Vec<Vec<Vec<f64>>> = demos.iter().map(|d| self.normalise_rows(&d.rows)).collect();
        let (d, end, _) = all
            .iter()
            .enumerate()
            .map(|(d, rows)| {
                let (end, cost) = super::recognize::open_end_cost(&norm, rows);
                (d, end, cost)
            })
            .min_by(|a, b| a.2.total_cmp(&b.2))
            .ok_or(HsomError::NoDemonstrations)?;
        // the events the prefix has reached (begun at or before its end) are skipped, as
        // `continue_events` takes the prefix's last event as done
        let executed = self.followed(&all, d, Some(end as f64));
        Ok(self.timed_postures(
            &norm[0],
            &norm[norm.len() - 1],
            &executed,
            StopReason::EndEvent,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::HsomParams;

    /// A 2-D gesture: hold at the origin, go to (1, 0), hold, come back, hold.
    fn gesture(hold: usize, noise_seed: u64) -> Vec<Vec<f64>> {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(noise_seed);
        let mut rows = Vec::new();
        let mut push = |x: f64, rng: &mut rand_chacha::ChaCha8Rng| {
            rows.push(vec![x + 0.002 * rng.gen::<f64>(), 0.5 * x]);
        };
        for _ in 0..hold {
            push(0.0, &mut rng);
        }
        for i in 0..40 {
            push(i as f64 / 40.0, &mut rng);
        }
        for _ in 0..hold {
            push(1.0, &mut rng);
        }
        for i in 0..40 {
            push(1.0 - i as f64 / 40.0, &mut rng);
        }
        for _ in 0..hold {
            push(0.0, &mut rng);
        }
        rows
    }

    fn config(height: usize) -> HsomConfig {
        let mut p = HsomParams::table1();
        p.algorithm = crate::config::AlgorithmParams::Events(crate::config::EventsParams {
            change_ratio: 0.6,
            action_horizon: 5,
        });
        p.state_length = 2;
        p.action_length = 2;
        p.height = height;
        p.levels.truncate(height);
        p.levels[0] = crate::config::LevelParams::new(8, 8, crate::som::Topology::Orthogonal, 0.1);
        for l in 1..height {
            p.levels[l] =
                crate::config::LevelParams::new(6, 6, crate::som::Topology::Orthogonal, 0.5);
        }
        p.training_steps = 3000;
        p.check("test").unwrap()
    }

    fn trained(height: usize) -> Hsom {
        let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        config(height).fit_series(&series).unwrap()
    }

    /// Mean distance of `rows` (with their postures `horizon` samples later, as the bottom is
    /// trained) to the bottom map: its quantization error on them.
    fn bottom_error(m: &Hsom, rows: &[Vec<f64>], horizon: usize) -> f64 {
        let norm = m.normalise_rows(rows);
        let n = norm.len() - 1;
        let inputs: Vec<Vec<f64>> = (0..n)
            .map(|i| [norm[i].as_slice(), &norm[(i + horizon).min(n)]].concat())
            .collect();
        m.maps[0].quantization_error(&inputs)
    }

    #[test]
    fn a_shared_bottom_drawn_at_random_keeps_the_first_gesture() {
        use crate::hsom::algorithm::{Presentation, Series};
        // two gestures in different places, presented first one, then the other
        let a: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        let b: Vec<Vec<Vec<f64>>> = (0..3)
            .map(|i| {
                gesture(30 + 5 * i, 10 + i as u64)
                    .into_iter()
                    .map(|r| vec![-r[0], 1.0 - 2.0 * r[1]])
                    .collect()
            })
            .collect();
        let name = "demo";
        let series: Vec<Series<'_>> = a
            .iter()
            .chain(&b)
            .map(|rows| Series { source: name, rows })
            .collect();
        let cfg = config(2);
        let fit = |order| {
            cfg.fit_inner(&series, None, true, vec!["x".into(), "y".into()], order)
                .unwrap()
        };
        let (in_order, drawn) = (fit(Presentation::InOrder), fit(Presentation::Shuffled));
        let h = cfg.params().action_horizon();
        let err = |m: &Hsom, set: &[Vec<Vec<f64>>]| {
            set.iter().map(|r| bottom_error(m, r, h)).sum::<f64>() / set.len() as f64
        };
        let (ea_order, ea_drawn) = (err(&in_order, &a), err(&drawn, &a));
        let (eb_order, eb_drawn) = (err(&in_order, &b), err(&drawn, &b));
        // in order, the gesture presented first loses its nodes to the one after it (0.064
        // against 0.045 when written); drawn at random it keeps them, and the worse-coded
        // gesture is coded better than in order
        assert!(
            ea_drawn < 0.7 * ea_order,
            "first gesture: drawn {ea_drawn} vs in order {ea_order}"
        );
        assert!(
            ea_drawn.max(eb_drawn) < ea_order.max(eb_order),
            "worse gesture: drawn {ea_drawn}/{eb_drawn} vs in order {ea_order}/{eb_order}"
        );
        assert!(
            ea_order > eb_order,
            "in order, the first gesture is the worse coded"
        );
    }

    #[test]
    fn each_branch_executes_its_own_gesture_on_the_shared_nodes() {
        // two gestures from the same rest posture along nearby paths, on a bottom too small
        // to give each its own nodes: the nodes they share sit between them (written:
        // own 0.025, weights 0.061, the other gesture's 0.078)
        let a: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        let b: Vec<Vec<Vec<f64>>> = a
            .iter()
            .map(|d| d.iter().map(|r| vec![r[0], 1.6 * r[1]]).collect())
            .collect();
        let demos = |set: &[Vec<Vec<f64>>]| -> Vec<Demonstration> {
            set.iter()
                .map(|rows| Demonstration {
                    source: "demo".into(),
                    columns: vec!["x".into(), "y".into()],
                    time: None,
                    rows: rows.clone(),
                })
                .collect()
        };
        let mut p = config(2).params().clone();
        p.levels[0] = crate::config::LevelParams::new(4, 4, crate::som::Topology::Orthogonal, 0.1);
        let cfg = p.check("test").unwrap();
        let sets = vec![("a".to_string(), demos(&a)), ("b".to_string(), demos(&b))];
        let m = cfg.fit_gestures(&sets, None).unwrap();
        // mean distance between a demonstration and its re-encoding by a branch
        let err = |br: &Hsom, set: &[Demonstration]| {
            let mut e = 0.0;
            for d in set {
                let r = br.reencode(d).unwrap();
                assert_eq!(r.postures.len(), d.rows.len());
                e += r
                    .postures
                    .iter()
                    .zip(&d.rows)
                    .map(|(x, y)| dist2(x, y).sqrt())
                    .sum::<f64>()
                    / d.rows.len() as f64;
            }
            e / set.len() as f64
        };
        let (ba, bb) = (&m.branches[0], &m.branches[1]);
        assert!(ba.knots.is_some() && bb.knots.is_some());
        let weights_only = |br: &Hsom| Hsom {
            knots: None,
            ..br.clone()
        };
        let other = Hsom {
            knots: bb.knots.clone(),
            ..ba.clone()
        };
        let (own, plain, wrong) = (
            err(ba, &sets[0].1),
            err(&weights_only(ba), &sets[0].1),
            err(&other, &sets[0].1),
        );
        // its own gesture's postures: closer than the shared nodes' weights; the other's: farther
        assert!(own < 0.7 * plain, "own {own} vs weights {plain}");
        assert!(
            wrong > plain,
            "the other gesture's postures {wrong} vs weights {plain}"
        );
        // one gesture through fit_gestures places them as fit does; an untrained model, or one
        // demonstration (nothing to agree on), executes the nodes' weights
        let alone = cfg.fit_gestures(&sets[..1], None).unwrap();
        assert_eq!(alone.branches[0].knots, cfg.fit(&sets[0].1).unwrap().knots);
        assert!(cfg.initialise_gestures(&sets).unwrap().branches[0]
            .knots
            .is_none());
        assert!(cfg.fit(&sets[0].1[..1]).unwrap().knots.is_none());
    }

    #[test]
    fn the_consensus_averages_aligned_samples_whatever_their_tempo() {
        // two bumps from rest: one to 1 early and quickly, one to 2 late and slowly
        let bump = |start: usize, rise: usize, peak: f64| -> Vec<Vec<f64>> {
            let mut d = vec![vec![0.0, 0.0]; start];
            d.extend((0..=rise).map(|i| vec![peak * i as f64 / rise as f64, 1.0]));
            d.extend((0..=rise).map(|i| vec![peak * (1.0 - i as f64 / rise as f64), 1.0]));
            d.extend(vec![vec![0.0, 0.0]; 10]);
            d
        };
        let (a, b) = (bump(5, 10, 1.0), bump(20, 25, 2.0));
        let top = |d: &[Vec<f64>]| d.iter().map(|r| r[0]).fold(f64::MIN, f64::max);
        for max_aligned in [MAX_ALIGNED, 16] {
            let c = consensus(
                &[a.clone(), b.clone()],
                &aligned_samples(&[a.clone(), b.clone()], max_aligned),
            );
            assert_eq!((c[0].len(), c[1].len()), (a.len(), b.len()));
            // each consensus path's apex lies between the two apexes (1 and 2), toward the
            // other's: the higher apex aligned to the lower one's single top sample gives
            // their mean, 1.5; the lower one's top, aligned to the higher one's whole crest,
            // the crest's mean (written: 1.25 and 1.5; in blocks of 3 and 6 samples 1.27 and
            // 1.48); the rest stays at rest
            for cd in &c {
                assert!(
                    (1.1..=1.55).contains(&top(cd)),
                    "{max_aligned}: {}",
                    top(cd)
                );
                assert!(cd[0].iter().all(|v| v.abs() < 1e-12), "{:?}", cd[0]);
            }
        }
        // one demonstration is its own consensus
        assert_eq!(
            consensus(
                std::slice::from_ref(&a),
                &aligned_samples(std::slice::from_ref(&a), MAX_ALIGNED),
            ),
            vec![a]
        );
    }

    #[test]
    fn the_starts_weigh_the_placements_only_where_they_predict_them() {
        // six demonstrations whose placements of two nodes follow their starts (nested
        // curves: where a drawing starts tells where it goes)
        let starts: Vec<Vec<f64>> = (0..6).map(|i| vec![i as f64, 0.0]).collect();
        let knots: Vec<Vec<f64>> = (0..6)
            .map(|i| vec![i as f64, 1.0, 2.0 * i as f64, -1.0])
            .collect();
        let count = [3.0, 1.0];
        let fitted = StartKnots::fit(starts.clone(), knots.clone(), &count, 1);
        assert!(fitted.width.is_finite(), "{}", fitted.width);
        // a reproduction that starts where the last one did is placed where it was, not at
        // the mean of all (2.5, 5)
        let p = fitted.placed(&[5.0, 0.0]);
        assert!(
            (p[0] - 5.0).abs() < 0.1 && (p[2] - 10.0).abs() < 0.2,
            "{p:?}"
        );
        // the same seed, the same width
        assert_eq!(
            StartKnots::fit(starts.clone(), knots.clone(), &count, 1),
            fitted
        );
        // the control: the same placements in an order the starts do not predict
        let shuffled: Vec<Vec<f64>> = [3, 0, 5, 1, 4, 2]
            .iter()
            .map(|&i| knots[i].clone())
            .collect();
        let control = StartKnots::fit(starts.clone(), shuffled, &count, 1);
        assert!(!control.width.is_finite(), "{}", control.width);
        let mean = control.placed(&[5.0, 0.0]);
        assert!(
            (mean[0] - 2.5).abs() < 1e-12 && (mean[2] - 5.0).abs() < 1e-12,
            "{mean:?}"
        );
        // three demonstrations cannot show it (6 orders: the starts' own is 1 in 6), nor
        // identical starts
        let three = StartKnots::fit(starts[..3].to_vec(), knots[..3].to_vec(), &count, 1);
        assert!(!three.width.is_finite());
        let same = StartKnots::fit(vec![vec![0.0, 0.0]; 6], knots.clone(), &count, 1);
        assert!(!same.width.is_finite());
        // more than six demonstrations: shuffles from the seed
        let starts9: Vec<Vec<f64>> = (0..9).map(|i| vec![i as f64, 0.0]).collect();
        let knots9: Vec<Vec<f64>> = (0..9).map(|i| vec![i as f64, 0.0, 0.0, 0.0]).collect();
        assert!(StartKnots::fit(starts9, knots9, &count, 7)
            .width
            .is_finite());
        assert_eq!(all_orders(3).len(), 6);
        assert_eq!(all_orders(3)[0], vec![0, 1, 2]);
    }

    #[test]
    fn each_node_is_placed_where_the_demonstrations_agree() {
        // the same gesture at three amplitudes: each demonstration's apex has its own
        // nodes, and a reproduction along any of them should reach the mean apex (1.0)
        let series: Vec<Vec<Vec<f64>>> = [0.8, 1.0, 1.2]
            .iter()
            .enumerate()
            .map(|(i, &k)| {
                gesture(30 + 5 * i, 100 + i as u64)
                    .into_iter()
                    .map(|r| vec![k * r[0], k * r[1]])
                    .collect()
            })
            .collect();
        let m = config(2).fit_series(&series).unwrap();
        // where each demonstration's apex events are placed, raw units
        let apex = |h: &Hsom, d: &[Vec<f64>]| {
            let y = m.normalise_rows(d);
            let ev = bottom_events(h, &y);
            let node = ev.iter().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap().0;
            let node = if node == ev[0].0 {
                // the longest event is the rest; the apex is the longest other one
                ev.iter()
                    .filter(|e| e.0 != ev[0].0)
                    .max_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap()
                    .0
            } else {
                node
            };
            let s = m.config.params().state_length;
            h.denormalise(&h.placement(&[])[node * s..(node + 1) * s])[0]
        };
        // the control: each node at its own samples' mean, each demonstration its own apex
        let norm: Vec<Vec<Vec<f64>>> = series.iter().map(|d| m.normalise_rows(d)).collect();
        let own = Hsom {
            knots: Some(m.own_postures(&norm)),
            ..m.clone()
        };
        for d in &series {
            let amplitude = d.iter().map(|r| r[0]).fold(f64::MIN, f64::max);
            let toward_mean = |h: &Hsom| (apex(h, d) - 1.0).abs() < 0.7 * (amplitude - 1.0).abs();
            if (amplitude - 1.0).abs() < 0.1 {
                assert!((apex(&m, d) - 1.0).abs() < 0.05, "{}", apex(&m, d));
                continue;
            }
            // moved toward the mean apex (written: 0.80 -> 0.87, 1.20 -> 0.99), where the
            // demonstration's own samples leave it
            assert!(
                toward_mean(&m),
                "{amplitude}: consensus apex {}",
                apex(&m, d)
            );
            assert!(
                !toward_mean(&own),
                "{amplitude}: own apex {}",
                apex(&own, d)
            );
        }
    }

    #[test]
    fn events_tile_the_demonstration_and_hold_their_durations() {
        let m = trained(3);
        let demo = gesture(30, 9);
        let y: Vec<Vec<f64>> = demo.iter().map(|r| m.normalise(r)).collect();
        let ev = bottom_events(&m, &y);
        // every sample but the last belongs to exactly one event
        let total: f64 = ev.iter().map(|e| e.1).sum();
        assert_eq!(total as usize, y.len() - 1);
        // consecutive events are different nodes (an event ends when the BMU changes)
        assert!(ev.windows(2).all(|w| w[0].0 != w[1].0));
        // the holds are single long events, not flicker from the noise
        assert!(ev.first().unwrap().1 >= 25.0, "{ev:?}");
        assert!(ev.iter().any(|e| e.1 >= 25.0 && e.0 != ev[0].0), "{ev:?}");
        assert!(ev.len() < 40, "{} events for {} samples", ev.len(), y.len());
    }

    #[test]
    fn chunks_tile_without_overlap_and_end_with_the_end() {
        let lay = Layout { s: 1, k: 4 };
        let items: Vec<Item> = (0..9)
            .map(|i| Item {
                node: i,
                content: vec![i as f64, i as f64 + 0.5, 0.1, 0.0],
            })
            .collect();
        let c = chunks(lay, &items, 1.0, 9.0);
        assert_eq!(c.len(), 3);
        assert!(
            c[0].begin && !c[1].begin && !c[2].begin,
            "only the first chunk is the begin"
        );
        assert_eq!(c[1].prev, vec![3.5], "context: the last posture before");
        assert_eq!(c[2].slots[0], items[8].content);
        // slots after the last entry are the end, holding the last posture
        for j in 1..4 {
            assert_eq!(c[2].slots[j], vec![8.5, 8.5, 0.0, 1.0]);
        }
        let phases: Vec<f64> = c.iter().map(|x| x.phase).collect();
        assert_eq!(phases, vec![0.0, 4.0 / 9.0, 8.0 / 9.0]);
    }

    #[test]
    fn followers_count_the_begin_and_the_most_frequent_first() {
        let seqs = vec![
            vec![1, 2, 3, END],
            vec![1, 2, 4, END],
            vec![1, 3, 2, 4, END],
        ];
        let t = followers_table(5, &seqs);
        let row = |n: usize| t[n * FOLLOWERS..(n + 1) * FOLLOWERS].to_vec();
        assert_eq!(row(5)[0], 1, "the begin is followed by 1");
        assert_eq!(row(2)[0], 4, "2 -> 4 twice, 2 -> 3 once");
        assert_eq!(row(2)[1], 3);
        assert_eq!(row(4), vec![END, u32::MAX, u32::MAX, u32::MAX]);
    }

    #[test]
    fn decoding_by_content_picks_the_nearest_follower() {
        let m = trained(3);
        let lay = Layout::of(&m.config);
        let code = DurationCode::from_dwell(&m.dwell);
        // the first follower of the begin, decoded from its own content
        let first = m.followers[0][m.maps[0].len() * FOLLOWERS];
        assert_ne!(first, u32::MAX);
        let c = entry_content(&m, lay, 0, first as usize, code);
        let dec = Decoder {
            model: &m,
            lay,
            code,
        };
        assert_eq!(
            dec.decode(1, &c, &[], u32::MAX, 0.0, f64::NAN, u32::MAX),
            first
        );
        // a slot whose end flag is set decodes to the end
        let mut e = c.clone();
        e[2 * lay.s + 1] = 1.0;
        assert_eq!(
            dec.decode(1, &e, &[], u32::MAX, 0.0, f64::NAN, u32::MAX),
            END
        );
        // an exemplar entry that followed the previous one wins over content; one that never
        // followed it is ignored
        let row = &m.followers[0][m.maps[0].len() * FOLLOWERS..][..FOLLOWERS];
        let never = (0..m.maps[0].len() as u32)
            .find(|n| !row.contains(n))
            .unwrap();
        assert_eq!(
            dec.decode(1, &c, &[], u32::MAX, 0.0, f64::NAN, never),
            first
        );
        if let Some(&other) = row
            .iter()
            .find(|&&f| f != first && f != u32::MAX && f != END)
        {
            assert_eq!(
                dec.decode(1, &c, &[], u32::MAX, 0.0, f64::NAN, other),
                other
            );
        }
    }

    /// A node passed more than once leads on to different followers at different positions:
    /// the follower table keeps where each transition came, and level 1 decodes among
    /// followers equally near by content by where the plan places the entry.
    #[test]
    fn decoding_prefers_the_follower_seen_at_the_planned_position() {
        // node 2 is followed by 3 early and by 4 late
        let seqs = vec![vec![1, 2, 3, 2, 4, END]];
        let table = followers_table(5, &seqs);
        let at = follower_positions(5, &seqs, &table, 6.0);
        let row = &table[2 * FOLLOWERS..3 * FOLLOWERS];
        let pos = |f: u32| at[2 * FOLLOWERS + row.iter().position(|&x| x == f).unwrap()];
        assert!((pos(3) - 2.0 / 6.0).abs() < 1e-12 && (pos(4) - 4.0 / 6.0).abs() < 1e-12);
        assert_eq!(at[5 * FOLLOWERS], 0.0, "the begin row: node 1 at 0");

        let mut m = trained(3);
        let lay = Layout::of(&m.config);
        let code = DurationCode::from_dwell(&m.dwell);
        let (p, a, b) = (0usize, 1u32, 2u32);
        m.followers[0][p * FOLLOWERS..(p + 1) * FOLLOWERS].copy_from_slice(&[
            a,
            b,
            u32::MAX,
            u32::MAX,
        ]);
        m.follower_at[p * FOLLOWERS] = 0.1;
        m.follower_at[p * FOLLOWERS + 1] = 0.9;
        // a slot halfway between a and b: content alone cannot choose
        let ca = entry_content(&m, lay, 0, a as usize, code);
        let cb = entry_content(&m, lay, 0, b as usize, code);
        let mut c: Vec<f64> = ca.iter().zip(&cb).map(|(x, y)| 0.5 * (x + y)).collect();
        c[2 * lay.s + 1] = 0.0;
        let dec = Decoder {
            model: &m,
            lay,
            code,
        };
        assert_eq!(dec.decode(1, &c, &[], p as u32, 0.0, 0.1, u32::MAX), a);
        assert_eq!(dec.decode(1, &c, &[], p as u32, 0.0, 0.9, u32::MAX), b);
        // no position (the training replay): the first of equals
        assert_eq!(dec.decode(1, &c, &[], p as u32, 0.0, f64::NAN, u32::MAX), a);
    }

    /// Home is followed by the start of the gesture (at its begin) and by the end (at its
    /// end): a plan that comes home early, before the shortest demonstration's number of
    /// events, ends where its position is nearer the end's, and starts again where it is
    /// nearer the start's (the paper's replication, which the count alone let through).
    /// Two demonstrations of a 2-D gesture from different starts: out along x and back once
    /// from (0, 0), twice from (0, 0.3); and the model `config(2)` trained on them.
    fn once_and_twice() -> ([Demonstration; 2], Hsom) {
        let demo = |source: &str, rows: Vec<Vec<f64>>, y: f64| Demonstration {
            source: source.into(),
            columns: vec!["x".into(), "y".into()],
            time: None,
            rows: rows.into_iter().map(|r| vec![r[0], r[1] + y]).collect(),
        };
        let demos = [
            demo("once", gesture(30, 1), 0.0),
            demo("twice", [gesture(30, 2), gesture(30, 3)].concat(), 0.3),
        ];
        let m = config(2).fit(&demos).unwrap();
        (demos, m)
    }

    /// The same model with the traces' stored places cleared: each event at its node's place.
    fn at_nodes(m: &Hsom) -> Hsom {
        let mut cleared = m.clone();
        let (k, s) = (m.config.params().memory, trace_places(m.config.params()));
        let at = trace_postures_at(k, 1);
        let width = trace_width(k, 1, s).unwrap();
        for slot in cleared.traces.as_mut().unwrap().levels[1].chunks_exact_mut(width) {
            slot[at..trace_bmus_at(k, 1, s)].fill(u32::MAX);
        }
        cleared
    }

    /// Turning points of x larger than 0.5 (out and back once: 1; twice: 3).
    fn excursions(rows: &[Vec<f64>]) -> usize {
        crate::metrics::column_swings(rows, 0, 0.5).unwrap()
    }

    /// The nearest-sequence baseline follows the training demonstration that starts nearest
    /// the initial posture: from each demonstration's start, its events at their nodes make
    /// that one's number of excursions (one, or two), where the other has the other number;
    /// bad input is refused with the error naming it. (At the consensus places, two
    /// demonstrations of different structure are averaged: "twice"'s second excursion stays
    /// under the 0.5 the count needs.)
    #[test]
    fn following_the_nearest_demonstration_keeps_its_number_of_excursions() {
        let (demos, m) = once_and_twice();
        assert_ne!(excursions(&demos[0].rows), excursions(&demos[1].rows));
        // without traces, the followed events are placed at their nodes
        let mut nodes = m.clone();
        nodes.traces = None;
        for d in &demos {
            let r = nodes.follow_nearest(&demos, &d.rows[0]).unwrap();
            assert_eq!(excursions(&r.postures), excursions(&d.rows), "{}", d.source);
            assert!(r.predicted_by.iter().all(|&l| l == 0));
        }
        let e = m.follow_nearest(&[], &[0.0, 0.0]).unwrap_err();
        assert!(matches!(e, HsomError::NoDemonstrations), "{e}");
        let e = m.follow_nearest(&demos, &[0.0]).unwrap_err().to_string();
        assert!(e.contains("initial posture") && e.contains('2'), "{e}");
    }

    /// A traced plan replays the demonstrated stretch its node stands for and goes on along
    /// the same demonstration across chunks: from each demonstration's start the hierarchy
    /// executes exactly that demonstration's bottom events (one excursion, or two, counted
    /// with each event at its node), at its nodes' learned durations. The traces have a size
    /// set by the configuration alone. The control: with every traced chunk of the first
    /// demonstration marked as the second's and its events made the second's, its start makes
    /// the second's number of excursions, so the plan is the traces' and not the levels'
    /// decoding.
    #[test]
    fn a_traced_plan_replays_the_demonstration_its_node_stands_for() {
        let (demos, _) = once_and_twice();
        let m = config(2).fit(&demos).unwrap();
        let r = &m.config.params().reproduction;
        let tr = m.traces.as_ref().unwrap();
        let (k, s) = (m.config.params().memory, trace_places(m.config.params()));
        assert_eq!(tr.levels[1].len(), trace_words(k, 1, s, m.maps[1].len()));
        for d in &demos {
            let y0 = m.normalise(&d.rows[0]);
            let (executed, stop) = m.plan_event_list(&y0, &[], &[], r);
            assert_eq!(stop, StopReason::EndEvent);
            let demonstrated: Vec<usize> = bottom_events(&m, &m.normalise_rows(&d.rows))
                .iter()
                .map(|e| e.0)
                .collect();
            let nodes: Vec<usize> = executed.iter().map(|e| e.0).collect();
            assert_eq!(nodes, demonstrated, "{}", d.source);
            assert!(executed.iter().all(|e| e.1 == m.dwell[e.0].max(1.0)));
            let rep = at_nodes(&m).reproduce(&d.rows[0]).unwrap();
            assert_eq!(
                excursions(&rep.postures),
                excursions(&d.rows),
                "{}",
                d.source
            );
        }
        // the control: the first demonstration's traced chunks replaced by the second's
        let mut other = m.clone();
        let width = trace_width(k, 1, s).unwrap();
        let words = &mut other.traces.as_mut().unwrap().levels[1];
        let second: Vec<Vec<u32>> = words
            .chunks_exact(width)
            .filter(|c| c[2] == 1)
            .map(|c| c.to_vec())
            .collect();
        for slot in words.chunks_exact_mut(width).filter(|c| c[2] == 0) {
            if let Some(theirs) = second.iter().find(|c| c[0] == slot[0]) {
                slot[TRACE_HEAD..].copy_from_slice(&theirs[TRACE_HEAD..]);
            }
            slot[2] = 1;
        }
        let rep = at_nodes(&other).reproduce(&demos[0].rows[0]).unwrap();
        assert_eq!(excursions(&rep.postures), excursions(&demos[1].rows));
    }

    /// Strokes of a family (a bent line, drawn with varying bend, tempo and length; 2-D,
    /// without holds): demonstration `i` of 5.
    fn stroke(i: usize) -> Vec<Vec<f64>> {
        let n = 80 + 7 * i;
        let bend = 0.3 * (1.0 + 0.15 * (i as f64 - 2.0));
        let warp = 0.8 + 0.1 * i as f64;
        (0..n)
            .map(|j| {
                let t = (j as f64 / (n - 1) as f64).powf(warp);
                vec![t, bend * (std::f64::consts::PI * t).sin()]
            })
            .collect()
    }

    /// A traced plan places each event where the demonstrations agree at that event of the
    /// demonstration it follows (`Hsom::event_postures`), not where its node pools every visit
    /// from wherever in the gesture: held out on a family of strokes, the reproduction is
    /// smoother on every fold (twice as smooth over the folds together), and no farther from
    /// the held-out stroke. The control: the same model with the stored places cleared (each
    /// event at its node's place) is jerkier.
    #[test]
    fn traced_events_at_their_place_in_the_consensus_are_smoother_than_at_their_nodes() {
        let all: Vec<Vec<Vec<f64>>> = (0..5).map(stroke).collect();
        let mut placed = Vec::new();
        let mut nodes = Vec::new();
        let mut dtw_placed = Vec::new();
        let mut dtw_nodes = Vec::new();
        for out in 0..5 {
            let train: Vec<Vec<Vec<f64>>> = (0..5)
                .filter(|&i| i != out)
                .map(|i| all[i].clone())
                .collect();
            let m = config(2).fit_series(&train).unwrap();
            let cleared = at_nodes(&m);
            let y0 = &all[out][0];
            let a = m.reproduce(y0).unwrap().postures;
            let b = cleared.reproduce(y0).unwrap().postures;
            placed.push(crate::metrics::normalized_jerk(&a, 0.025).unwrap());
            nodes.push(crate::metrics::normalized_jerk(&b, 0.025).unwrap());
            let d = |r: &[Vec<f64>]| {
                crate::dtw::dtw_distance(r, &all[out], crate::dtw::Band::None)
                    .unwrap()
                    .per_step()
            };
            dtw_placed.push(d(&a));
            dtw_nodes.push(d(&b));
        }
        // smoother on every fold, and at least twice as smooth over the folds together
        // (measured: 4 of 5 folds at least twice as smooth, the fifth 540 against 948)
        for (a, b) in placed.iter().zip(&nodes) {
            assert!(
                a < b,
                "jerk at the places {placed:?}, at the nodes {nodes:?}"
            );
        }
        let (a, b): (f64, f64) = (placed.iter().sum(), nodes.iter().sum());
        assert!(
            2.0 * a < b,
            "jerk at the places {placed:?}, at the nodes {nodes:?}"
        );
        let (a, b): (f64, f64) = (dtw_placed.iter().sum(), dtw_nodes.iter().sum());
        assert!(a < 1.05 * b, "DTW {dtw_placed:?} against {dtw_nodes:?}");
    }

    /// A warp with stairs (runs of three samples aligned to one sample of `b`) is read at an
    /// even pace: every step a third of `b`'s, from `b`'s first sample to its last; the
    /// stepped mean of the same alignment jumps a whole sample of `b` at each stair. A warp
    /// without stairs reads `b` as it is.
    #[test]
    fn a_smooth_warp_moves_on_evenly_through_the_stairs() {
        let b: Vec<Vec<f64>> = (0..4).map(|i| vec![i as f64, -2.0 * i as f64]).collect();
        let stairs: Vec<f64> = (0..12).map(|x| (x / 3) as f64).collect();
        let read = smooth_warp(&stairs, &b);
        assert_eq!(read.len(), 12);
        assert_eq!((read[0][0], read[11][0]), (0.0, 3.0));
        let steps: Vec<f64> = read.windows(2).map(|w| w[1][0] - w[0][0]).collect();
        // the middles 1, 4, 7, 10 are a third of a sample of b apart, after the first run
        // and before the last
        for (x, d) in steps.iter().enumerate().skip(1).take(9) {
            assert!((d - 1.0 / 3.0).abs() < 1e-12, "step {x}: {d}");
        }
        assert!(
            steps.iter().all(|&d| (-1e-12..=0.5).contains(&d)),
            "{steps:?}"
        );
        // both variables read at the same place
        assert!(read.iter().all(|r| (r[1] + 2.0 * r[0]).abs() < 1e-12));
        let stepped: Vec<f64> = stairs.iter().map(|&y| b[y as usize][0]).collect();
        assert!(stepped.windows(2).any(|w| w[1] - w[0] == 1.0));
        let identity: Vec<f64> = (0..4).map(|x| x as f64).collect();
        assert_eq!(smooth_warp(&identity, &b), b);
        assert!(smooth_warp(&[], &b).is_empty());
    }

    /// Two knots per event (passage 6, "Two knots per event"): a traced event of four samples
    /// or more passes through two knots, at a quarter and three quarters of its duration, at
    /// its halves' places. On a family whose swings are about as short as its events (a wave
    /// from a hold, three half-swings of 9-13 samples, 8 bottom nodes), held out, the
    /// executed curve keeps the three swings on every fold; the control, every traced place
    /// cleared (each event at its node's place), loses a turn on some fold.
    #[test]
    fn two_knots_per_event_keep_the_swings() {
        let wave = |i: usize| -> Vec<Vec<f64>> {
            let (hold, per) = (10 + 2 * i, 9 + i);
            let swings = 3.0 * per as f64;
            (0..2 * hold + swings as usize)
                .map(|j| {
                    let u = (j as f64 - hold as f64).clamp(0.0, swings) / per as f64;
                    let x = (std::f64::consts::PI * u).sin();
                    vec![
                        0.5 * x,
                        0.2 * (1.0 - (std::f64::consts::PI * u / 3.0).cos()),
                    ]
                })
                .collect()
        };
        let all: Vec<Vec<Vec<f64>>> = (0..5).map(wave).collect();
        let swings = |rows: &[Vec<f64>]| crate::metrics::column_swings(rows, 0, 0.3).unwrap();
        assert!(all.iter().all(|d| swings(d) == swings(&all[0])));
        let mut kept = [0, 0];
        for out in 0..5 {
            let train: Vec<Vec<Vec<f64>>> = (0..5)
                .filter(|&i| i != out)
                .map(|i| all[i].clone())
                .collect();
            let mut p = config(2).into_params();
            p.levels[0] =
                crate::config::LevelParams::new(4, 2, crate::som::Topology::Orthogonal, 0.1);
            let m = p.check("test").unwrap().fit_series(&train).unwrap();
            let mut cleared = m.clone();
            let (k, pw) = (m.config.params().memory, trace_places(m.config.params()));
            let at = trace_postures_at(k, 1);
            let width = trace_width(k, 1, pw).unwrap();
            for slot in cleared.traces.as_mut().unwrap().levels[1].chunks_exact_mut(width) {
                slot[at..trace_bmus_at(k, 1, pw)].fill(u32::MAX);
            }
            for (i, model) in [&m, &cleared].into_iter().enumerate() {
                let r = model.reproduce(&all[out][0]).unwrap().postures;
                kept[i] += usize::from(swings(&r) == swings(&all[out]));
            }
        }
        assert_eq!(kept[0], 5, "two knots per event {kept:?}");
        assert!(kept[1] < 5, "at the nodes' places {kept:?}");
        // an event passes through two knots only where each half lasts two samples: one
        // of 3.5 samples keeps one knot at its middle, one of 4 two, at its quarters, each
        // at its half's place
        let m = config(2).fit_series(&all[..4]).unwrap();
        let y0 = m.normalise(&all[0][0]);
        // the event, its halves, then each half's lowest and highest values (s = 2)
        let at: Vec<f64> = vec![
            0.0, 0.0, 0.1, 0.1, 0.2, 0.2, -0.3, -0.3, 0.4, 0.4, -0.5, -0.5, 0.6, 0.6,
        ];
        let n = m.dwell.iter().position(|&d| d > 0.0).unwrap();
        let executed: Vec<Step<usize>> = vec![(n, 3.5, 1, Some(at.clone())), (n, 4.0, 1, Some(at))];
        let places = m.knot_places(&y0, &y0, &executed, StopReason::LearnedLength);
        assert_eq!(places.t, vec![0.0, 1.75, 4.5, 6.5, 7.5]);
        let placed = m.placement(&y0);
        assert_eq!(places.by, vec![0, 1, 1, 1, 1]);
        assert_eq!(places.traced_mean, vec![false, true, true, true, false]);
        // the whole event at its place, the first half of the next at that half's, the
        // second at the second's
        for (k, off) in [(1, 0.0), (2, 0.1), (3, 0.2)] {
            assert!(
                (places.v[k][0] - (placed[2 * n] + off)).abs() < 1e-12,
                "knot {k}"
            );
        }
        // and the knots the curve passes through are those places, turning points kept
        let timed = m.timed_knots(&y0, &y0, &executed, StopReason::LearnedLength);
        assert_eq!(timed.t, places.t);
        let target: Vec<f64> = places.v.iter().map(|r| r[0]).collect();
        // each half's extremes go with its knot; the whole event and the end have none
        let reach: Vec<Option<(f64, f64)>> = places
            .reach
            .iter()
            .map(|r| r.as_ref().map(|(lo, hi)| (lo[0], hi[0])))
            .collect();
        let at = |off: f64| placed[2 * n] + off;
        assert_eq!(
            reach,
            vec![
                None,
                None,
                Some((at(-0.3), at(0.4))),
                Some((at(-0.5), at(0.6))),
                None
            ]
        );
        assert_eq!(
            timed.values[0],
            turning_points_kept(
                &places.t,
                &target,
                &places.spans,
                &places.traced_mean,
                &reach
            )
        );
    }

    /// Continued after a prefix, the nearest sequence goes on along the demonstration the
    /// prefix ran along, from where it ended: half of "twice" (its first excursion) is
    /// completed with the second, the prefix of "once" up to its far hold with the way back
    /// only.
    #[test]
    fn the_nearest_sequence_continues_the_demonstration_the_prefix_ran_along() {
        let (demos, m) = once_and_twice();
        for d in &demos {
            let prefix = &d.rows[..d.rows.len() / 2];
            let r = m.follow_nearest_from(&demos, prefix).unwrap();
            assert_eq!(&r.postures[0], prefix.last().unwrap());
            let whole: Vec<Vec<f64>> = prefix
                .iter()
                .chain(r.postures.iter().skip(1))
                .cloned()
                .collect();
            assert_eq!(excursions(&whole), excursions(&d.rows), "{}", d.source);
        }
        let e = m
            .follow_nearest_from(&demos, &demos[0].rows[..1])
            .unwrap_err();
        assert!(e.to_string().contains("prefix"), "{e}");
    }

    /// Resuming its own reproduction: read back at any point of it (the reading is the
    /// reproduction's first samples), the hierarchy goes on as planned, so reading and
    /// continuation are the whole reproduction again (within 0.02, as long to a sample);
    /// held still on the way out for 30 samples, it then goes on with the rest (out, hold,
    /// back: one excursion, ending at home). Continuing the same readings as a new
    /// demonstration's prefix (the reading encoded again by the bottom) does not give the
    /// plan back (the control); a paper-algorithm model, a wrong initial posture and a
    /// too-short reading are refused.
    #[test]
    fn resuming_its_own_reproduction_goes_on_as_planned() {
        let m = trained(3);
        let initial = gesture(30, 7)[0].clone();
        let whole = m.reproduce(&initial).unwrap().postures;
        let n = whole.len();
        let joined = |reading: &[Vec<f64>], rest: &[Vec<f64>]| -> Vec<Vec<f64>> {
            reading.iter().chain(rest.iter().skip(1)).cloned().collect()
        };
        let gap = |a: &[Vec<f64>], b: &[Vec<f64>]| {
            a.iter()
                .zip(b)
                .flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| (p - q).abs()))
                .fold(0.0, f64::max)
        };
        let mut control = Vec::new();
        for k in [n / 4, n / 2, 3 * n / 4] {
            let reading = &whole[..k];
            let rest = m.resume(&initial, reading).unwrap().postures;
            assert_eq!(&rest[0], reading.last().unwrap());
            let again = joined(reading, &rest);
            assert!(
                again.len().abs_diff(n) <= 1,
                "at {k}: {} of {n}",
                again.len()
            );
            assert!(
                gap(&again, &whole) < 0.02,
                "at {k}: {}",
                gap(&again, &whole)
            );
            let reencoded = joined(reading, &m.continue_events(reading).unwrap().postures);
            control.push(gap(&reencoded, &whole));
        }
        // the control: the reading encoded again does not give the plan back (0.08, 0.51 and
        // 0.08 measured)
        assert!(control.iter().any(|&g| g > 0.05), "{control:?}");
        // held still for 30 samples on the way out: then out, held, back, home
        let out = whole.iter().position(|p| p[0] > 0.5).unwrap();
        let mut reading = whole[..out].to_vec();
        reading.extend(std::iter::repeat(whole[out - 1].clone()).take(30));
        let after = joined(&reading, &m.resume(&initial, &reading).unwrap().postures);
        assert_eq!(excursions(&after), 1, "{after:?}");
        assert!(after.last().unwrap()[0].abs() < 0.15);
        assert!(
            after.len().abs_diff(n + 30) <= 10,
            "{} against {}",
            after.len(),
            n + 30
        );
        let e = m.resume(&[0.0], &reading).unwrap_err().to_string();
        assert!(e.contains("initial posture"), "{e}");
        let e = m.resume(&initial, &reading[..2]).unwrap_err().to_string();
        assert!(e.contains("reading") && e.contains("2 sample"), "{e}");
        let endless = vec![initial.clone(); MAX_ALIGNED * MAX_ALIGNED / n + 1];
        let e = m.resume(&initial, &endless).unwrap_err().to_string();
        assert!(
            e.contains("at most") && e.contains(&format!("plan of {n}")),
            "{e}"
        );
        let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        let mut p = HsomParams::table1();
        p.state_length = 2;
        p.action_length = 2;
        let paper = p.check("paper").unwrap().fit_series(&series).unwrap();
        let e = paper.resume(&initial, &reading).unwrap_err().to_string();
        assert!(e.contains("algorithm = events"), "{e}");
    }

    /// Continuing a prefix with the hierarchy: the prefix's events are pushed up the lists
    /// and the levels plan the rest. Shown the way out and part of the far hold, the
    /// reproduction holds, comes back and ends by itself, without going out again; an
    /// untrained hierarchy does not. A paper-algorithm model and a too-short prefix are
    /// refused with named errors.
    #[test]
    fn continuing_a_prefix_plans_the_rest_from_the_lists() {
        let prefix: Vec<Vec<f64>> = gesture(35, 9).into_iter().take(35 + 40 + 15).collect();
        let goes_home = |m: &Hsom| {
            let r = m.continue_events(&prefix).unwrap();
            let xs: Vec<f64> = r.postures.iter().map(|p| p[0]).collect();
            let back = xs.iter().position(|&x| x < 0.5);
            let out_again = back.is_some_and(|b| xs[b..].iter().any(|&x| x > 0.6));
            let held = xs.iter().take_while(|&&x| x > 0.9).count();
            (
                r.postures[0] == prefix[prefix.len() - 1]
                    && r.stop == StopReason::EndEvent
                    && xs.last().unwrap().abs() < 0.15
                    && !out_again
                    && (5..=45).contains(&held),
                format!("{xs:?}"),
            )
        };
        let (ok, xs) = goes_home(&trained(3));
        assert!(ok, "trained: {xs}");
        let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        let (ok, xs) = goes_home(&config(3).initialise_series(&series).unwrap());
        assert!(!ok, "untrained: {xs}");
        let mut p = HsomParams::table1();
        p.state_length = 2;
        p.action_length = 2;
        let paper = p.check("paper").unwrap().fit_series(&series).unwrap();
        let e = paper.continue_events(&prefix).unwrap_err().to_string();
        assert!(e.contains("algorithm = events"), "{e}");
        let e = trained(3)
            .continue_events(&prefix[..2])
            .unwrap_err()
            .to_string();
        assert!(e.contains("prefix") && e.contains("2 sample"), "{e}");
    }

    #[test]
    fn a_plan_ends_at_home_where_its_position_is_nearer_the_end() {
        let mut m = trained(3);
        let lay = Layout::of(&m.config);
        let code = DurationCode::from_dwell(&m.dwell);
        let (home, start) = (0usize, 1u32);
        m.followers[0][home * FOLLOWERS..(home + 1) * FOLLOWERS].copy_from_slice(&[
            start,
            END,
            u32::MAX,
            u32::MAX,
        ]);
        m.follower_at[home * FOLLOWERS] = 0.0;
        m.follower_at[home * FOLLOWERS + 1] = 1.0;
        // a slot that reads as the start of the gesture: content says "start again"
        let mut c = entry_content(&m, lay, 0, start as usize, code);
        c[2 * lay.s + 1] = 0.0;
        let dec = Decoder {
            model: &m,
            lay,
            code,
        };
        let early = m.demo_runs[0] - 10.0;
        assert_eq!(
            dec.decode(1, &c, &[], home as u32, early, 0.7, u32::MAX),
            END
        );
        // the controls: the plan at the begin, and no position (only the count decides)
        assert_eq!(
            dec.decode(1, &c, &[], home as u32, early, 0.2, u32::MAX),
            start
        );
        assert_eq!(
            dec.decode(1, &c, &[], home as u32, early, f64::NAN, u32::MAX),
            start
        );
        assert_eq!(
            dec.decode(1, &c, &[], home as u32, m.demo_runs[0], f64::NAN, u32::MAX),
            END
        );
    }

    /// Every used node of a level above the bottom has an exemplar's position: the phase of
    /// a training chunk it is the BMU of.
    #[test]
    fn exemplar_positions_are_phases_of_training_chunks() {
        let m = trained(3);
        for l in 1..m.maps.len() {
            for n in (0..m.maps[l].len()).filter(|&n| m.hits[l][n] > 0) {
                let p = m.exemplar_phase[l][n];
                assert!(
                    p.is_finite() && (0.0..=2.0).contains(&p),
                    "level {l} node {n}: {p}"
                );
            }
        }
        // the begin chunk's node is at 0
        assert!((1..m.maps.len()).all(|l| m.exemplar_phase[l].contains(&0.0)));
    }

    /// Every used node of a level above the bottom has an exemplar: the entries below of a
    /// training chunk it is the BMU of, so expanding it replays a demonstrated sequence.
    #[test]
    fn exemplars_are_training_chunks_of_their_node() {
        let m = trained(3);
        let k = m.config.params().memory;
        let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        let norm: Vec<Vec<Vec<f64>>> = series
            .iter()
            .map(|d| d.iter().map(|r| m.normalise(r)).collect())
            .collect();
        let seqs: Vec<Vec<u32>> = norm
            .iter()
            .map(|d| {
                bottom_events(&m, d)
                    .iter()
                    .map(|e| e.0 as u32)
                    .chain([END])
                    .collect()
            })
            .collect();
        let windows: Vec<Vec<u32>> = seqs
            .iter()
            .flat_map(|s| {
                s.chunks(k)
                    .map(|c| {
                        let mut c = c.to_vec();
                        c.resize(k, END);
                        c
                    })
                    .collect::<Vec<_>>()
            })
            .collect();
        let used1 = used(&m, 1);
        assert!(!used1.is_empty());
        for &n in &used1 {
            let ex: Vec<u32> = (0..k).map(|j| m.exemplar(1, n, j)).collect();
            assert!(
                windows.contains(&ex),
                "node {n}: {ex:?} is no training chunk"
            );
        }
        // unused nodes have none
        for n in (0..m.maps[1].len()).filter(|n| !used1.contains(n)) {
            assert_eq!(m.exemplar(1, n, 0), u32::MAX);
        }
    }

    #[test]
    fn reproduction_goes_there_and_back_at_the_learned_tempo_and_ends_by_itself() {
        let m = trained(3);
        let rep = m.reproduce(&[0.0, 0.0]).unwrap();
        assert_eq!(rep.stop, StopReason::EndEvent);
        let xs: Vec<f64> = rep.postures.iter().map(|p| p[0]).collect();
        let top = xs.iter().cloned().fold(f64::MIN, f64::max);
        assert!(top > 0.85, "reaches the far posture: {top}");
        assert!(xs.last().unwrap().abs() < 0.15, "comes back: {xs:?}");
        // the hold at the far posture lasts about as long as demonstrated (30-40 samples)
        let held = xs.iter().filter(|&&x| x > 0.9).count();
        assert!((20..=60).contains(&held), "held {held} samples");
        let n = rep.postures.len() as f64;
        assert!((0.7 * 150.0..=1.3 * 200.0).contains(&n), "length {n}");
        // the levels above the bottom carried it, each only where it beats its lookup table
        assert!(rep.predicted_by.iter().any(|&l| l >= 1));
        assert!(rep.predicted_by.iter().all(|&l| m.level_trusted(l)));
        // deterministic
        assert_eq!(rep, m.reproduce(&[0.0, 0.0]).unwrap());
    }

    #[test]
    fn a_plan_that_ends_after_a_node_no_demonstration_ended_after_ends_where_they_ended() {
        // three strokes from rest to (1, 0.5) that end in motion, at the far end
        let stroke = |hold: usize, seed: u64| -> Vec<Vec<f64>> {
            let mut rows = gesture(hold, seed);
            rows.truncate(hold + 40);
            rows
        };
        let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| stroke(30 + 5 * i, i as u64)).collect();
        let m = config(3).fit_series(&series).unwrap();
        let ends = m.end_postures.as_ref().unwrap();
        assert_eq!(ends[..m.maps[0].len()].iter().sum::<f64>(), 3.0);
        let end_node = bottom_events(&m, &m.normalise_rows(&series[0]))
            .last()
            .unwrap()
            .0;
        assert!(m.end_posture(end_node).is_none());
        let rep = m.reproduce(&[0.0, 0.0]).unwrap();
        assert_eq!(rep.stop, StopReason::EndEvent);
        // after the node the demonstrations ended after, where its learned action leads
        let last = rep.postures.last().unwrap();
        assert!(
            (last[0] - 0.975).abs() < 0.05 && (last[1] - 0.4875).abs() < 0.025,
            "{last:?}"
        );
        // a plan that ends two events early (the end decoded by content after a node no
        // demonstration ended after) still ends where they ended; the control: the same
        // events cut by a length cap stop where the last one's action leads, short of it
        let norm = m.normalise_rows(&series[0]);
        let mut executed: Vec<Step<usize>> = bottom_events(&m, &norm)
            .into_iter()
            .map(|(n, d)| (n, d, 0, None))
            .collect();
        executed.truncate(executed.len() - 2);
        let early = m.timed_postures(&norm[0], &norm[0], &executed, StopReason::EndEvent);
        let capped = m.timed_postures(&norm[0], &norm[0], &executed, StopReason::LearnedLength);
        let (e, c) = (
            early.postures.last().unwrap(),
            capped.postures.last().unwrap(),
        );
        assert!((e[0] - 0.975).abs() < 0.02, "{e:?}");
        assert!(c[0] < 0.9, "{c:?} (the control)");
    }

    #[test]
    fn a_level_plans_only_where_it_and_the_levels_below_beat_their_lookup_tables() {
        let mut m = trained(4);
        m.accuracy = vec![0.0, 0.5, 0.9, 0.9];
        m.lookup = vec![0.0, 0.9, 0.8, 0.8];
        // level 1 always (the lowest level with a sequence), whatever its table
        assert!(m.level_trusted(0) && m.level_trusted(1));
        assert!(m.level_trusted(2) && m.level_trusted(3));
        // a tie is not better; a level above an untrusted one is not reached
        m.accuracy[2] = 0.8;
        assert!(!m.level_trusted(2) && !m.level_trusted(3));
        m.accuracy[2] = 0.9;
        m.accuracy[3] = 0.7;
        assert!(m.level_trusted(2) && !m.level_trusted(3));
        let rep = m.reproduce(&[0.0, 0.0]).unwrap();
        assert!(
            rep.predicted_by.iter().all(|&l| l <= 2),
            "{:?}",
            rep.predicted_by
        );
        // the summary says which levels plan
        let used: Vec<bool> = m
            .summary()
            .levels
            .iter()
            .map(|l| l.used_in_reproduction)
            .collect();
        assert_eq!(used, vec![true, true, true, false]);
    }

    #[test]
    fn reencoding_keeps_what_the_bottom_code_keeps_and_an_untrained_code_loses_it() {
        let rows = gesture(30, 0);
        let demo = Demonstration {
            source: "g".into(),
            columns: vec!["x".into(), "y".into()],
            time: None,
            rows: rows.clone(),
        };
        let err = |m: &Hsom| {
            let r = m.reencode(&demo).unwrap();
            assert!(r.predicted_by.iter().all(|&l| l == 0));
            crate::dtw::dtw_distance(&r.postures, &rows, crate::dtw::Band::None)
                .unwrap()
                .per_step()
        };
        let model = trained(3);
        let good = err(&model);
        assert!(good < 0.05, "trained: {good}");
        // negative control: the initial (random) bottom map
        let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        let untrained = err(&config(3).initialise_series(&series).unwrap());
        // it fails the gate the trained code passes, by an order of magnitude
        assert!(
            untrained > 0.05 && untrained > 10.0 * good,
            "untrained: {untrained}, trained: {good}"
        );
        // a demonstration of another width is refused, not re-encoded
        let mut bad = demo.clone();
        bad.rows[3] = vec![0.0];
        assert!(matches!(
            model.reencode(&bad),
            Err(HsomError::DimensionMismatch { row: 3, .. })
        ));
    }

    #[test]
    fn an_untrained_hierarchy_does_not_reproduce_the_gesture() {
        let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
        let m = config(3).initialise_series(&series).unwrap();
        let rep = m.reproduce(&[0.0, 0.0]).unwrap();
        let xs: Vec<f64> = rep.postures.iter().map(|p| p[0]).collect();
        let held = xs.iter().filter(|&&x| x > 0.9).count();
        let top = xs.iter().cloned().fold(f64::MIN, f64::max);
        assert!(
            !(top > 0.85 && (20..=60).contains(&held) && xs.last().unwrap().abs() < 0.15),
            "untrained: top {top}, held {held}"
        );
    }

    /// The events of a training demonstration, pushed up the lists, complete chunks whose
    /// nodes are the training replay's; a plan that expected another node there is surprised.
    #[test]
    fn executed_events_climb_the_lists_and_a_wrong_expectation_is_a_surprise() {
        let m = trained(3);
        let lay = Layout::of(&m.config);
        let code = DurationCode::from_dwell(&m.dwell);
        let mean = m.demo_runs[1];
        let demo = gesture(35, 1);
        let y: Vec<Vec<f64>> = demo.iter().map(|r| m.normalise(r)).collect();
        let ev = bottom_events(&m, &y);
        assert!(ev.len() >= 2 * lay.k);
        let start = m.maps[0].weights(ev[0].0)[..lay.s].to_vec();
        // expecting exactly what the lists will find: no surprise
        let mut probe = Lists::new(m.height(), &start);
        for &(n, d) in &ev[..lay.k] {
            probe.push_event(&m, lay, code, mean, n, d);
        }
        let first_chunk = probe.tail[1];
        assert_ne!(first_chunk, u32::MAX, "a full chunk reaches level 1");
        let mut lists = Lists::new(m.height(), &start);
        lists.expected[1].push_back(first_chunk);
        let mut surprised = false;
        for &(n, d) in &ev[..lay.k] {
            surprised |= lists.push_event(&m, lay, code, mean, n, d);
        }
        assert!(!surprised);
        assert_eq!(lists.index[1], 1, "one chunk completed at level 1");
        assert!(lists.chunk[1].is_empty());
        assert!(lists.expected[1].is_empty(), "the expectation was consumed");
        // expecting another node: surprise, at the event that completes the chunk only
        let mut lists = Lists::new(m.height(), &start);
        let other = (first_chunk + 1) % m.maps[1].len() as u32;
        lists.expected[1].push_back(other);
        let flags: Vec<bool> = ev[..lay.k]
            .iter()
            .map(|&(n, d)| lists.push_event(&m, lay, code, mean, n, d))
            .collect();
        assert_eq!(flags.iter().filter(|&&f| f).count(), 1);
        assert!(flags[lay.k - 1], "{flags:?}");
    }

    /// A model file's durations are untrusted: an absurd learned duration cannot make the
    /// reproduction longer than its cap (nor allocate without bound).
    #[test]
    fn absurd_durations_are_capped_by_the_length_cap() {
        let mut m = trained(3);
        m.dwell.iter_mut().for_each(|d| {
            if *d > 0.0 {
                *d = 1e300
            }
        });
        let rep = m.reproduce(&[0.0, 0.0]).unwrap();
        let cap = (m.demo_len[2] * m.config.params().reproduction.length_factor).ceil();
        assert!(
            rep.postures.len() as f64 <= cap + 1.0,
            "{}",
            rep.postures.len()
        );
    }

    #[test]
    fn turning_points_are_kept_and_holds_are_not_moved() {
        // four events of 5 samples: knots at their middles, the initial posture and the end
        let t = [0.0, 2.5, 7.5, 12.5, 17.5, 20.0];
        let spans = [(0, 5), (5, 10), (10, 15), (15, 20)];
        let mean = |c: &[f64], (a, b): (usize, usize)| c[a..b].iter().sum::<f64>() / (b - a) as f64;
        let peak = [0.0, 0.3, 1.0, 0.3, 0.0, 0.0];
        let kept = turning_points_kept(&t, &peak, &spans, &[], &[]);
        let c = monotone_cubic(&t, &kept, 21);
        // the turn's event has the node's posture as its mean, so the curve turns beyond it
        assert!(
            (mean(&c, spans[1]) - 1.0).abs() < 1e-6,
            "{}",
            mean(&c, spans[1])
        );
        assert!(c.iter().cloned().fold(f64::MIN, f64::max) > 1.0);
        // only the turning point moved
        assert!(kept[2] > 1.0);
        assert_eq!((kept[0], kept[1], kept[3], kept[4]), (0.0, 0.3, 0.3, 0.0));
        // the control: through the knots alone, the turn's mean falls short of the posture
        let plain = monotone_cubic(&t, &peak, 21);
        assert!(mean(&plain, spans[1]) < 0.97, "{}", mean(&plain, spans[1]));
        // a hold (no strict extremum) is held where it is: nothing moves
        let hold = [0.0, 1.0, 1.0, 1.0, 0.0, 0.0];
        assert_eq!(
            turning_points_kept(&t, &hold, &spans, &[], &[]),
            hold.to_vec()
        );
    }

    /// A traced half whose consensus dips for a sample or two (DTW's pile-up of the other
    /// demonstrations' deeper trough): its turning knot goes to that dip, so the curve turns
    /// there; matching the half's mean instead (the control, no extremes known) turns well
    /// inside it. A peak goes to its highest value, a knot that is no turning point stays,
    /// and an extreme inside the knot's own place never pulls it back.
    #[test]
    fn a_traced_turn_reaches_the_extreme_of_its_span() {
        let t = [0.0, 5.0, 15.0, 25.0, 30.0];
        let spans = [(0, 10), (10, 20), (20, 30)];
        let traced = [false, true, true, true, false];
        let trough = [0.0, -0.3, -0.6, -0.3, 0.0];
        let reach = [
            None,
            Some((-0.5, -0.1)),
            Some((-1.0, -0.4)),
            Some((-0.5, -0.1)),
            None,
        ];
        let min = |v: &[f64]| {
            monotone_cubic(&t, v, 31)
                .into_iter()
                .fold(f64::MAX, f64::min)
        };
        let kept = turning_points_kept(&t, &trough, &spans, &traced, &reach);
        assert_eq!(kept[2], -1.0);
        assert!((min(&kept) + 1.0).abs() < 1e-9, "{}", min(&kept));
        // the control: the mean matched, the curve turns 0.2 rad inside the dip
        let mean_kept = turning_points_kept(&t, &trough, &spans, &traced, &[]);
        assert!(min(&mean_kept) > -0.8, "{}", min(&mean_kept));
        // a peak reaches its highest value
        let peak: Vec<f64> = trough.iter().map(|v| -v).collect();
        let up = [None, None, Some((0.4, 1.0)), None, None];
        assert_eq!(turning_points_kept(&t, &peak, &spans, &traced, &up)[2], 1.0);
        // knots that are no turning point ignore their extremes
        let slope = [0.0, -0.3, -0.6, -0.9, -1.0];
        let kept = turning_points_kept(&t, &slope, &spans, &traced, &reach);
        assert_eq!(kept, slope.to_vec());
        // an extreme inside the knot's place (not one of the span's samples) never moves
        // the turn inward
        let inside = [None, None, Some((-0.5, -0.4)), None, None];
        assert_eq!(
            turning_points_kept(&t, &trough, &spans, &traced, &inside)[2],
            -0.6
        );
    }

    #[test]
    fn a_turn_at_the_first_sample_is_not_thrown_away_from_the_start() {
        // a first event of one sample at a turn: its only sample is the initial posture,
        // which no knot moves, so the knot stays at the node's posture
        let t = [0.0, 0.5, 5.0, 10.0];
        let spans = [(0, 1), (1, 9)];
        let v = [0.0, 0.01, -0.5, -0.5];
        let kept = turning_points_kept(&t, &v, &spans, &[], &[]);
        assert_eq!(kept, v.to_vec());
        let c = monotone_cubic(&t, &kept, 11);
        assert!(c.iter().all(|&x| x <= 0.01), "{c:?}");
        // a longer first event at a turn is still kept, on its samples after the start
        let t = [0.0, 2.5, 7.5, 10.0];
        let spans = [(0, 5), (5, 10)];
        let v = [0.0, 0.3, 0.0, 0.0];
        let kept = turning_points_kept(&t, &v, &spans, &[], &[]);
        let c = monotone_cubic(&t, &kept, 11);
        let mean = c[1..5].iter().sum::<f64>() / 4.0;
        assert!(
            (mean - 0.3).abs() < 1e-6 && kept[1] < 0.6,
            "{mean} {kept:?}"
        );
    }

    #[test]
    fn a_turn_in_the_span_beside_its_turning_knot_is_kept_by_both() {
        // a slow descent to a trough at 20.3 samples, a fast rise, a hold: the trough lies at
        // the start of the span 20..25, whose mean the rise lifts above the mean of 15..20,
        // so the knot of 15..20 is the turning point and the one holding the trough is not
        let c0 = 20.3;
        let y = |j: f64| {
            use std::f64::consts::PI;
            if j < c0 {
                (PI * (j - (c0 - 20.0)) / 20.0).cos()
            } else if j < c0 + 12.0 {
                -(PI * (j - c0) / 12.0).cos()
            } else {
                1.0
            }
        };
        let spans: Vec<(usize, usize)> = (0..8).map(|i| (5 * i, 5 * i + 5)).collect();
        let mut t = vec![0.0];
        let mut v = vec![y(0.0)];
        for &(a, b) in &spans {
            t.push((a + b) as f64 / 2.0);
            v.push((a..b).map(|j| y(j as f64)).sum::<f64>() / (b - a) as f64);
        }
        t.push(40.0);
        v.push(y(40.0));
        let n = t.len();
        assert!(v[4] < v[5] && v[5] < v[6] && v[4] < v[3], "{v:?}");
        let mean = |c: &[f64], (a, b): (usize, usize)| c[a..b].iter().sum::<f64>() / (b - a) as f64;
        // the control, decoded knots: only the turning point moves; the span holding the
        // trough keeps its knot at its mean, and the curve's mean over it is off
        let plain = turning_points_kept(&t, &v, &spans, &vec![false; n], &[]);
        assert_eq!(plain[5], v[5]);
        let c = monotone_cubic(&t, &plain, 41);
        assert!(mean(&c, spans[4]) > v[5] + 0.01, "{}", mean(&c, spans[4]));
        // traced knots: the turning point's neighbours keep their spans' means too
        let mut traced = vec![true; n];
        (traced[0], traced[n - 1]) = (false, false);
        let kept = turning_points_kept(&t, &v, &spans, &traced, &[]);
        let c = monotone_cubic(&t, &kept, 41);
        for i in [3, 4, 5] {
            assert!((mean(&c, spans[i - 1]) - v[i]).abs() < 1e-3, "knot {i}");
        }
        // and the curve is nearer the one the means were taken from around the turn
        let off = |c: &[f64]| {
            let e2: f64 = (10..30).map(|j| (c[j] - y(j as f64)).powi(2)).sum();
            (e2 / 20.0).sqrt()
        };
        let plain_curve = monotone_cubic(&t, &plain, 41);
        assert!(
            off(&c) < off(&plain_curve),
            "{} against {}",
            off(&c),
            off(&plain_curve)
        );
        // knots away from the turn stay where they are (the ends, the slopes, the hold)
        for i in [0, 1, 2, 6, 7, 8, 9] {
            assert_eq!(kept[i], v[i], "knot {i}");
        }
        // one trough, no new turn
        let turns = c
            .windows(3)
            .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
            .count();
        assert_eq!(turns, 1, "{c:?}");
    }

    #[test]
    fn monotone_cubic_holds_and_does_not_overshoot() {
        let t = [0.0, 10.0, 20.0, 30.0];
        let v = [0.0, 1.0, 1.0, 0.0];
        let m = monotone_tangents(&t, &v);
        assert_eq!(m[1], 0.0);
        assert_eq!(m[2], 0.0);
        for (i, x) in monotone_cubic(&t, &v, 31).into_iter().enumerate() {
            assert!((0.0..=1.0).contains(&x), "{i}: {x}");
            if (10..=20).contains(&i) {
                assert!((x - 1.0).abs() < 1e-12, "the hold is held");
            }
        }
    }
}
