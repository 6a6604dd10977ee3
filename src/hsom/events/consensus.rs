//! Where bottom events are placed: the demonstrations' DTW alignment and consensus, the
//! nodes' postures and offsets.

use super::encode::bottom_events;
use super::traces::{trace_places, trace_postures_at, TRACE_HEAD};
use crate::hsom::model::{DemoSmoothness, EventsHsom, Model, Part, StartKnots};

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
/// ([`aligned_samples`] of `norm`). docs/ALGORITHM.md, section 3.7.
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
pub(super) fn aligned_samples(norm: &[Vec<Vec<f64>>], max_aligned: usize) -> Aligned {
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
/// of a few samples, would carry into its knots as uneven steps: docs/ALGORITHM.md, section
/// 3.7).
pub(crate) fn smooth_warp(warp: &[f64], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
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
    pub(super) fn of<A: Part>(
        model: &Model<A>,
        demo: &[Vec<f64>],
        events: &[(usize, f64)],
    ) -> Self {
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

    pub(super) fn add(&mut self, other: &NodeSums) {
        for (a, b) in self.count.iter_mut().zip(&other.count) {
            *a += b;
        }
        for (a, b) in self.sum.iter_mut().zip(&other.sum) {
            *a += b;
        }
    }
}

impl<A: Part> Model<A> {
    /// Where a reproduction that starts at `start` (normalised) places every bottom node's
    /// events, `stateLength` values per node: with `consensus = start` the training
    /// demonstrations' placements weighed by their starts ([`StartKnots`]); otherwise the
    /// branch's own postures ([`EventsHsom::fit_postures`]) when it has them, else the nodes'
    /// weights (state part).
    pub(super) fn placement(&self, start: &[f64]) -> Vec<f64> {
        let s = self.config.params().state_length;
        let e = self.part.events();
        if let Some(k) = e.and_then(|e| e.start_knots.as_ref()) {
            return k.placed(start);
        }
        match e.and_then(|e| e.knots.as_ref()) {
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
    /// keeps its weights. Flattened, `stateLength` values per node. [`EventsHsom::fit_postures`]
    /// gives it the demonstrations' consensus (docs/ALGORITHM.md, sections 3.7
    /// and 4).
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

    /// Per demonstration of `norm` (normalised), per bottom event, where that event lies in
    /// the demonstrations' consensus, as an offset from where its node is placed for a
    /// reproduction from that demonstration's start ([`Model::placement`]); state part. The
    /// consensus is the mean over the event's samples of every demonstration's samples
    /// aligned to them (its own for itself): with `consensus = start`, where the starts are
    /// used, weighed by that demonstration's start as [`StartKnots`] weighs them; otherwise
    /// all alike ([`consensus`]). A plan
    /// that follows a demonstration places its events at their node's place plus this offset
    /// (docs/ALGORITHM.md, section 3.7): the demonstrations' agreement at that
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
        let agreed: Vec<Vec<Vec<f64>>> =
            match self.part.events().and_then(|e| e.start_knots.as_ref()) {
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
}

impl EventsHsom {
    /// Where a reproduction places each bottom node's events, learned from `norm` (the
    /// normalised demonstrations this model or branch was trained on): the demonstrations'
    /// [`consensus`] over the samples of the node's events, smoothed by the map's
    /// neighbourhood at its final radius as the bottom's last training step would
    /// ([`Model::smoothed_postures`]). A reproduction follows one demonstrated sequence of
    /// nodes; placed at the consensus, each node's events land where the demonstrations
    /// agree, not where the one demonstration that visited it went, nor where the map's
    /// neighbourhood pulled its weights. With one demonstration there is nothing to agree
    /// on: the weights (and no stored postures).
    pub(crate) fn fit_postures(&mut self, norm: &[Vec<Vec<f64>>]) {
        let s = self.config.params().state_length;
        // the mean of one posture of each demonstration (state part)
        let mean = |at: fn(&Vec<Vec<f64>>) -> Option<&Vec<f64>>| {
            let rows: Vec<&Vec<f64>> = norm.iter().filter_map(at).collect();
            (!rows.is_empty())
                .then(|| StartKnots::mean(&rows, &vec![1.0; rows.len()])[..s].to_vec())
        };
        let (start, end) = (mean(|d| d.first()), mean(|d| d.last()));
        let fade = super::start::start_fade(norm, s);
        let smoothness = DemoSmoothness::of(norm, s);
        let e = &mut self.part;
        e.demo_smoothness = smoothness;
        e.start_fade = fade;
        e.knots = None;
        e.start_knots = None;
        e.start_posture = start;
        e.end_posture = end;
        let aligned = aligned_samples(norm, MAX_ALIGNED);
        self.fit_node_postures(norm, &aligned);
        self.place_traced_events(norm, &aligned);
    }

    /// The nodes' places of [`EventsHsom::fit_postures`] (`aligned`: [`aligned_samples`] of
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
        let mean = StartKnots::mean(&all, &vec![1.0; all.len()]);
        let starts = norm.iter().map(|d| d[0][..s].to_vec()).collect();
        let seed = self.config.params().seed;
        let weighed = StartKnots::fit(starts, knots, &count.count, seed);
        self.part.knots = Some(mean);
        // all alike is the mean already stored: nothing more to keep
        self.part.start_knots = weighed.width.is_finite().then_some(weighed);
    }

    /// The traced chunks' events placed ([`Traces`], [`Model::event_offsets`] of `norm`, the
    /// normalised demonstrations the traces were made from, once the nodes are placed): each
    /// traced event's offset from its node's place; where the demonstration's events do not
    /// match the traced ones (other demonstrations), none.
    fn place_traced_events(&mut self, norm: &[Vec<Vec<f64>>], aligned: &Aligned) {
        let Some(mut traces) = self.part.traces.take() else {
            return;
        };
        let own = self.event_offsets(norm, aligned);
        let (k, s) = (
            self.config.params().memory,
            trace_places(self.config.params()),
        );
        for (l, chunks) in traces.levels.iter_mut().enumerate().skip(1) {
            let span = k.pow(l as u32);
            let postures = trace_postures_at(k, l);
            for slot in chunks.iter_mut().map(|c| &mut c.words) {
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
        self.part.traces = Some(traces);
    }
}
