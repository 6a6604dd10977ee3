//! Training the levels above the bottom, level by level, and the statistics the reproduction
//! uses.

use rand::{Rng, SeedableRng};

use super::encode::{
    b_part, bottom_events, chunks, dist2, end_content, event_content, summary, Chunk, DurationCode,
    Item,
};
use super::traces::{
    trace_bmus_at, trace_places, trace_width, trace_words, Decoder, TRACED_CHUNKS, TRACE_HEAD,
};
use super::END;
use crate::hsom::followers::{
    follower_positions, followers_table, fraction, lookup_accuracy, lookup_counts,
};
use crate::hsom::inputs::{node_means, spread, Layout};
use crate::hsom::model::{EventsHsom, TracedChunk, Traces};

/// What [`EventsHsom::replay_level`] measured.
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

/// Nodes of a level that some training entry selected (of the bottom: the nodes some
/// training event was on, those with a dwell time).
pub(in crate::hsom) fn used(model: &EventsHsom, level: usize) -> Vec<usize> {
    (0..model.maps[level].len())
        .filter(|&i| match level {
            0 => model.dwell[i] > 0.0,
            _ => model.hits[level][i] > 0,
        })
        .collect()
}

impl EventsHsom {
    /// Train the levels above the bottom on the events of `norm` (already normalised
    /// demonstrations; the bottom map is trained), level by level, and compute every
    /// statistic the events reproduction uses.
    pub(crate) fn fit_events<R: Rng>(&mut self, norm: &[Vec<Vec<f64>>], learn: bool, rng: &mut R) {
        self.fit_levels(norm, learn, rng);
        let (acc, lookup) = self.heldout_levels(norm, learn, rng.gen());
        self.part.heldout_accuracy = acc;
        self.part.heldout_lookup = lookup;
    }

    /// Each level's prediction accuracy and its lookup table's, held out: for every
    /// demonstration, the levels above the bottom trained again on the others (the bottom
    /// kept, fold seeds from `seed`) predict its entries, scored as in training
    /// ([`EventsHsom::replay_level`]); the counts are summed over the folds. With one
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
                    &fold.part.followers[l - 1],
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
        (
            counts.iter().map(|c| fraction(c[1], c[0])).collect(),
            counts.iter().map(|c| fraction(c[3], c[2])).collect(),
        )
    }

    /// [`EventsHsom::fit_events`] without the held-out figures.
    fn fit_levels<R: Rng>(&mut self, norm: &[Vec<Vec<f64>>], learn: bool, rng: &mut R) {
        let cfg = self.config.clone();
        let p = cfg.params();
        let lay = Layout::of(&cfg);
        let n0 = self.maps[0].len();
        // what a previous fit of the levels left (a held-out fold starts from a clone)
        self.hits[1..].iter_mut().for_each(|v| v.fill(0));
        self.part
            .exemplars
            .iter_mut()
            .for_each(|e| e.fill(u32::MAX));
        self.part
            .exemplar_phase
            .iter_mut()
            .for_each(|e| e.fill(0.0));
        self.part
            .followers
            .iter_mut()
            .for_each(|f| f.fill(u32::MAX));
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
        self.dwell = node_means(&dsum, &dn);
        let counts: Vec<f64> = events.iter().map(|e| e.len() as f64).collect();
        self.demo_runs = spread(&counts);
        let seqs0: Vec<Vec<u32>> = events
            .iter()
            .map(|e| e.iter().map(|&(n, _)| n as u32).chain([END]).collect())
            .collect();
        // the bottom's followers: its lookup table (the reflex at height 1) and the candidates
        // level 1 decodes among
        self.part.followers[0] = followers_table(n0, &seqs0);
        self.part.follower_at =
            follower_positions(n0, &seqs0, &self.part.followers[0], self.demo_runs[1]);
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
                self.part.followers[l - 1] = followers_table(nodes_below, &seqs);
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
                            self.part.exemplars[l][b * lay.k + j] =
                                items[di].get(ci * lay.k + j).map_or(END, |i| i.node);
                        }
                        self.part.exemplar_phase[l][b] = ch.phase;
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
            self.part.threshold[l] = r.threshold;
            self.accuracy[l] = fraction(r.correct, r.predicted);
            self.lookup[l] = lookup_accuracy(&self.part.followers[l - 1], nodes_below, &seqs);
            items = r.next_items;
            chunk_bmus.push(bmus);
        }
        self.part.traces = Some(self.traced_chunks(&seqs_by_level, chunk_bmus));
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
            levels.push(
                w.chunks_exact(width)
                    .enumerate()
                    .filter(|(_, slot)| slot[0] != u32::MAX)
                    .map(|(i, slot)| TracedChunk {
                        node: (i / TRACED_CHUNKS) as u32,
                        words: slot.to_vec(),
                    })
                    .collect(),
            );
        }
        Traces { levels }
    }

    /// A demonstration's bottom events as level 1's entries, ending with the end.
    pub(in crate::hsom) fn event_items(
        &self,
        events: &[(usize, f64)],
        code: DurationCode,
    ) -> Vec<Item> {
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
        let used_below = used(self, l - 1);
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
    pub(super) fn exemplar(&self, level: usize, n: usize, j: usize) -> u32 {
        let k = self.config.params().memory;
        self.part.exemplars[level]
            .get(n * k + j)
            .copied()
            .unwrap_or(u32::MAX)
    }
}
