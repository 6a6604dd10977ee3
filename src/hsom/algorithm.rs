//! Training a hierarchy (paper III-C.1): the bottom level and, with the paper's algorithm,
//! every level at once; the replay of the training data; the quality summary. The model it
//! makes is described in [`super::model`].

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::config::{HsomConfig, MemoryMode, Normalisation};
use crate::demos::Demonstration;
use crate::som::SelfOrganizingMap;

use super::errors::HsomError;
use super::followers::{followers_table, fraction, most_frequent};
use super::inputs::{
    bmu_known, check_series, demo_series, input_dim, level_buffers, node_means, spread, Series,
};
use super::kept::{kept, Warm};
use super::memory::{Activity, Stm};
use super::model::{EventsHsom, EventsModel, Hsom, Model, PaperModel, Part, MAX_NORMALISED};

fn demo_columns(demos: &[Demonstration]) -> Vec<String> {
    demos.first().map(|d| d.columns.clone()).unwrap_or_default()
}

/// How a model is fitted ([`HsomConfig::fit_model`]): the default trains quietly.
#[derive(Clone, Copy, Default)]
pub struct Fit<'a> {
    /// Called with `(done, total)` about a hundred times (for a progress bar).
    pub progress: Option<&'a dyn Fn(usize, usize)>,
    /// Leave the seeded initial weights (inside the data's bounding box) untrained, with the
    /// same statistics as a trained model: the negative control of fidelity and recognition.
    pub untrained: bool,
}

impl Fit<'_> {
    /// The untrained model, quietly.
    pub const UNTRAINED: Fit<'static> = Fit {
        progress: None,
        untrained: true,
    };
}

impl HsomConfig {
    /// Train a hierarchy on the demonstrations of one gesture (each `stateLength` columns
    /// wide, at least two samples), quietly: the branch of [`HsomConfig::fit_model`]'s model
    /// of one gesture.
    pub fn fit(&self, demos: &[Demonstration]) -> Result<Hsom, HsomError> {
        self.fit_one(demos, Fit::default())
    }

    /// One gesture's hierarchy as `how` says.
    pub(super) fn fit_one(&self, demos: &[Demonstration], how: Fit<'_>) -> Result<Hsom, HsomError> {
        self.fit_one_in(demos, how, None)
    }

    /// [`HsomConfig::fit_one`] in the units of `units` ([`Warm::units`]: a gesture of a model
    /// of several, in the units of all of them), else in its demonstrations' own.
    pub(super) fn fit_one_in(
        &self,
        demos: &[Demonstration],
        how: Fit<'_>,
        units: Option<&Warm<'_>>,
    ) -> Result<Hsom, HsomError> {
        let series = demo_series(demos);
        let learn = !how.untrained;
        let columns = demo_columns(demos);
        let mut model = self.fit_from(&series, how.progress, learn, columns, units)?;
        if learn {
            model.set_period(demos.first().and_then(crate::demos::median_interval));
            if let Hsom::Events(m) = &mut model {
                m.learn_postures(demos.iter().map(|d| d.rows.as_slice()));
            }
        }
        Ok(model)
    }

    /// The offset and scale of the bottom input for demonstrations `series` (what
    /// [`HsomConfig::fit_from`] normalises by without a [`Warm`] start).
    pub(super) fn units(&self, series: &[Series<'_>]) -> Result<(Vec<f64>, Vec<f64>), HsomError> {
        let p = self.params();
        check_series(series, p.state_length, p.action_horizon())?;
        let (lo, hi) = bounds(series, p.state_length)?;
        Ok(self.units_of(&lo, &hi))
    }

    fn units_of(&self, lo: &[f64], hi: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let range: Vec<f64> = lo.iter().zip(hi).map(|(a, b)| b - a).collect();
        match self.params().normalisation {
            Normalisation::None => (vec![0.0; lo.len()], vec![1.0; lo.len()]),
            Normalisation::Global => {
                let m = range.iter().cloned().fold(0.0, f64::max);
                (lo.to_vec(), vec![if m > 0.0 { m } else { 1.0 }; lo.len()])
            }
            Normalisation::PerDimension => (
                lo.to_vec(),
                range
                    .iter()
                    .map(|&r| if r > 0.0 { r } else { 1.0 })
                    .collect(),
            ),
        }
    }

    /// Fit `series` from the seeded initial weights (`warm` `None`) or going on from a
    /// trained model's maps and normalisation ([`Warm`]: an update); only the seeded weights
    /// and the statistics unless `learn`.
    pub(crate) fn fit_from(
        &self,
        series: &[Series<'_>],
        progress: Option<&dyn Fn(usize, usize)>,
        learn: bool,
        columns: Vec<String>,
        warm: Option<&Warm<'_>>,
    ) -> Result<Hsom, HsomError> {
        let p = self.params();
        let state = p.state_length;
        check_series(series, state, p.action_horizon())?;
        let columns = if columns.len() == state {
            columns
        } else {
            (0..state).map(|i| format!("x{i}")).collect()
        };
        let (lo, hi) = bounds(series, state)?;
        let (offset, scale) = match warm {
            // an update keeps the model's normalisation: the maps are in its units
            Some(w) => (w.offset.to_vec(), w.scale.to_vec()),
            None => self.units_of(&lo, &hi),
        };
        let norm: Vec<Vec<Vec<f64>>> = series
            .iter()
            .map(|s| {
                s.rows
                    .iter()
                    .map(|r| normalised(r, &offset, &scale))
                    .collect()
            })
            .collect();
        // what training cannot represent: squared distances of such values overflow
        for (s, rows) in series.iter().zip(&norm) {
            for (i, r) in rows.iter().enumerate() {
                if let Some(c) = r
                    .iter()
                    .position(|v| !v.is_finite() || v.abs() > MAX_NORMALISED)
                {
                    return Err(HsomError::OutOfScale {
                        demo: s.source.to_string(),
                        row: i,
                        column: c,
                        value: s.rows[i][c],
                        normalised: r[c],
                    });
                }
            }
        }
        // initial weights: inside the (normalised) data's bounding box, from the seed
        let mut rng = ChaCha8Rng::seed_from_u64(warm.map_or(p.seed, |w| w.seed));
        let mut maps = Vec::with_capacity(p.height);
        if let Some(w) = warm {
            maps = w.maps.to_vec();
        }
        for (l, lp) in p.levels.iter().enumerate().skip(maps.len()) {
            let dim = input_dim(self, l);
            let (blo, bhi): (Vec<f64>, Vec<f64>) = if l == 0 {
                let (a, b) = (
                    normalised(&lo, &offset, &scale),
                    normalised(&hi, &offset, &scale),
                );
                (
                    a.iter().chain(&a).cloned().collect(),
                    b.iter().chain(&b).cloned().collect(),
                )
            } else {
                let below = &p.levels[l - 1];
                match p.memory_mode() {
                    MemoryMode::Lists => (
                        vec![0.0; dim],
                        (0..dim)
                            .map(|i| if i % 2 == 0 { below.cols - 1 } else { below.rows - 1 } as f64)
                            .collect(),
                    ),
                    MemoryMode::Levels => (vec![0.0; dim], vec![1.0; dim]),
                }
            };
            maps.push(SelfOrganizingMap::new_random(
                lp.rows,
                lp.cols,
                dim,
                lp.topology,
                &blo,
                &bhi,
                &mut rng,
            ));
        }
        let mut stm = Stm::new(self);
        let (mut bufs, mut masks) = level_buffers(self);
        // an update goes on from the schedule's point `from` to its end: the steps and rates
        // of the share of the training data that is new
        let from = warm.map_or(0.0, |w| w.from);
        let total = match (learn, warm) {
            (false, _) => 0,
            (true, None) => p.training_steps,
            (true, Some(_)) => (p.training_steps as f64 * (1.0 - from)).ceil() as usize,
        };
        let at = |done: u64, expected: f64| from + (1.0 - from) * done as f64 / expected;
        let expected: Vec<f64> = (0..p.height)
            .map(|l| ((total as u64 / self.period(l)).max(2) - 1) as f64)
            .collect();
        let mut trained = vec![0u64; p.height];
        let (mut d, mut pos) = (0usize, 0usize);
        let horizon = p.action_horizon();
        let chunk = (total / 100).max(1);
        let events = p.kind() == crate::config::Algorithm::Events;
        for s in 1..=total as u64 {
            {
                let demo = &norm[d];
                let x = &mut bufs[0];
                x[..state].copy_from_slice(&demo[pos]);
                x[state..].copy_from_slice(&demo[(pos + horizon).min(demo.len() - 1)]);
                let lp = &p.levels[0];
                let prog = at(trained[0], expected[0]);
                let (b, _) = maps[0].bmu(x);
                stm.push_bottom(b, &maps[0]);
                maps[0].update(
                    x,
                    None,
                    b,
                    lp.learning_factor.at(prog),
                    lp.learning_radius.at(prog),
                    lp.neighbourhood,
                );
                trained[0] += 1;
            }
            for l in 1..p.height {
                if events || s % self.period(l) != 0 {
                    break;
                }
                let (x, mask) = (&mut bufs[l], &mut masks[l]);
                if !stm.input(l - 1, x, mask) {
                    continue;
                }
                let lp = &p.levels[l];
                let prog = at(trained[l], expected[l]);
                let (b, _, full) = bmu_known(&maps[l], x, mask);
                maps[l].update(
                    x,
                    if full { None } else { Some(mask) },
                    b,
                    lp.learning_factor.at(prog),
                    lp.learning_radius.at(prog),
                    lp.neighbourhood,
                );
                trained[l] += 1;
                stm.push(l, b, &maps[l]);
            }
            pos += 1;
            if pos + 1 >= norm[d].len() {
                stm.clear();
                d = (d + 1) % norm.len();
                pos = 0;
            }
            if let Some(cb) = progress {
                let done = s as usize;
                if done % chunk == 0 || done == total {
                    cb(done, total);
                }
            }
        }
        if let Some(w) = warm {
            trained
                .iter_mut()
                .zip(w.trained)
                .for_each(|(t, old)| *t += old);
        }
        let lens: Vec<f64> = series.iter().map(|s| s.rows.len() as f64).collect();
        let (paths, memory) = kept(&norm, series.iter().map(|s| s.rows.len()), p.seed);
        let model = Model {
            config: self.clone(),
            maps,
            offset,
            scale,
            trained,
            hits: p.levels.iter().map(|l| vec![0; l.rows * l.cols]).collect(),
            qe: vec![0.0; p.height],
            te: vec![0.0; p.height],
            demo_len: spread(&lens),
            demo_runs: [0.0; 3],
            dwell: vec![0.0; p.levels[0].rows * p.levels[0].cols],
            columns,
            accuracy: vec![0.0; p.height],
            lookup: vec![0.0; p.height],
            part: (),
            paths,
            kept: memory,
        };
        if events {
            let (mut m, ()) = model.with_part(EventsModel::untrained(p));
            m.replay(&norm);
            m.fit_events(&norm, learn, &mut rng);
            return Ok(Hsom::Events(Box::new(m)));
        }
        let end_hits = vec![0; p.levels[0].rows * p.levels[0].cols];
        let (mut m, ()) = model.with_part(PaperModel { end_hits });
        m.replay(&norm);
        Ok(Hsom::Paper(Box::new(m)))
    }
}

/// Per variable, the lowest and highest value of `series` (`state` variables); a variable
/// whose range overflows cannot be normalised.
fn bounds(series: &[Series<'_>], state: usize) -> Result<(Vec<f64>, Vec<f64>), HsomError> {
    let mut lo = vec![f64::INFINITY; state];
    let mut hi = vec![f64::NEG_INFINITY; state];
    for s in series {
        for r in s.rows {
            for d in 0..state {
                lo[d] = lo[d].min(r[d]);
                hi[d] = hi[d].max(r[d]);
            }
        }
    }
    if let Some(d) = (0..state).position(|d| !(hi[d] - lo[d]).is_finite()) {
        let (s, i) = series
            .iter()
            .flat_map(|s| (0..s.rows.len()).map(move |i| (s, i)))
            .find(|(s, i)| s.rows[*i][d] == hi[d])
            .expect("the maximum is a sample");
        return Err(HsomError::OutOfScale {
            demo: s.source.to_string(),
            row: i,
            column: d,
            value: hi[d],
            normalised: f64::INFINITY,
        });
    }
    Ok((lo, hi))
}

/// `x` as the bottom level sees it with `offset` and `scale`: (x - offset) / scale.
fn normalised(x: &[f64], offset: &[f64], scale: &[f64]) -> Vec<f64> {
    x.iter()
        .enumerate()
        .map(|(d, v)| (v - offset[d]) / scale[d])
        .collect()
}

impl EventsHsom {
    /// Where reproduction places each bottom node's events, learned from these (raw)
    /// demonstrations ([`EventsHsom::fit_postures`]).
    pub(super) fn learn_postures<'a>(&mut self, demos: impl Iterator<Item = &'a [Vec<f64>]>) {
        let norm: Vec<Vec<Vec<f64>>> = demos.map(|rows| self.normalise_rows(rows)).collect();
        self.fit_postures(&norm);
    }
}

impl<A: Part> Model<A> {
    /// Replay the (normalised) training data through the trained maps, without learning, with
    /// the training schedule restarted at every demonstration: node usage, end nodes, QE, TE.
    pub(super) fn replay(&mut self, norm: &[Vec<Vec<f64>>]) {
        let cfg = self.config.clone();
        let p = cfg.params();
        let state = p.state_length;
        let events = p.kind() == crate::config::Algorithm::Events;
        let mut stm = Stm::new(&cfg);
        let (mut bufs, mut masks) = level_buffers(&cfg);
        let mut qe_sum = vec![0.0; p.height];
        let mut te_bad = vec![0usize; p.height];
        let mut count = vec![0usize; p.height];
        let n0 = self.maps[0].len();
        let mut dwell_sum = vec![0.0f64; n0];
        let mut dwell_n = vec![0u32; n0];
        let mut runs_per_demo = Vec::with_capacity(norm.len());
        let horizon = p.action_horizon();
        let offset = p.offset();
        let (mut acc_n, mut acc_ok) = (vec![0u32; p.height], vec![0u32; p.height]);
        let mut pbuf = vec![0.0; 2 * p.memory];
        let mut pmask = vec![true; 2 * p.memory];
        // per level: the entries pushed in each demonstration, and the (previous, actual)
        // entries the level above predicted, to score the lookup table on the same entries
        let mut seqs: Vec<Vec<Vec<u32>>> = vec![Vec::new(); p.height];
        let mut scored: Vec<Vec<(u32, u32)>> = vec![Vec::new(); p.height];
        for demo in norm {
            stm.clear();
            seqs.iter_mut().for_each(|s| s.push(Vec::new()));
            let last = |seqs: &[Vec<Vec<u32>>], l: usize| {
                seqs[l]
                    .last()
                    .and_then(|s| s.last())
                    .copied()
                    .unwrap_or(u32::MAX)
            };
            let mut sc = 0u64;
            // runs of the same bottom BMU: (node, length)
            let mut runs: Vec<(usize, usize)> = Vec::new();
            for pos in 0..demo.len() - 1 {
                bufs[0][..state].copy_from_slice(&demo[pos]);
                bufs[0][state..].copy_from_slice(&demo[(pos + horizon).min(demo.len() - 1)]);
                let (a, b) = self.maps[0].best_two(&bufs[0]);
                let d2: f64 = self.maps[0]
                    .weights(a)
                    .iter()
                    .zip(&bufs[0])
                    .map(|(w, x)| (w - x) * (w - x))
                    .sum();
                qe_sum[0] += d2.sqrt();
                te_bad[0] +=
                    usize::from(self.maps[0].len() > 1 && !self.maps[0].are_neighbours(a, b));
                count[0] += 1;
                self.hits[0][a] = self.hits[0][a].saturating_add(1);
                if pos + 2 == demo.len() {
                    self.part.count_end(a);
                }
                let guess = if events {
                    None
                } else {
                    self.predict_next(&stm, 1, offset, &mut pbuf, &mut pmask)
                };
                stm.push_bottom(a, &self.maps[0]);
                if let Some(g) = guess {
                    acc_n[1] += 1;
                    acc_ok[1] += u32::from(g == a);
                    scored[1].push((last(&seqs, 0), a as u32));
                }
                if let Some(s0) = seqs[0].last_mut() {
                    s0.push(a as u32);
                }
                match runs.last_mut() {
                    Some((n, len)) if *n == a => *len += 1,
                    _ => runs.push((a, 1)),
                }
                sc += 1;
                for l in 1..p.height {
                    if events || sc % cfg.period(l) != 0 {
                        break;
                    }
                    let x = &mut bufs[l];
                    let mask = &mut masks[l];
                    if !stm.input(l - 1, x, mask) {
                        continue;
                    }
                    let (b, d2, full) = bmu_known(&self.maps[l], x, mask);
                    if full {
                        let (_, b2) = self.maps[l].best_two(x);
                        qe_sum[l] += d2.sqrt();
                        te_bad[l] += usize::from(
                            self.maps[l].len() > 1 && !self.maps[l].are_neighbours(b, b2),
                        );
                        count[l] += 1;
                    }
                    self.hits[l][b] = self.hits[l][b].saturating_add(1);
                    if l + 1 < p.height {
                        if let Some(g) =
                            self.predict_next(&stm, l + 1, offset, &mut pbuf, &mut pmask)
                        {
                            acc_n[l + 1] += 1;
                            acc_ok[l + 1] += u32::from(g == b);
                            scored[l + 1].push((last(&seqs, l), b as u32));
                        }
                    }
                    if let Some(sl) = seqs[l].last_mut() {
                        sl.push(b as u32);
                    }
                    stm.push(l, b, &self.maps[l]);
                }
            }
            let k = runs.len();
            for (i, &(n, len)) in runs.iter().enumerate() {
                if i > 0 && i + 1 < k {
                    dwell_sum[n] += len as f64;
                    dwell_n[n] += 1;
                }
            }
            runs_per_demo.push(k as f64);
        }
        self.dwell = node_means(&dwell_sum, &dwell_n);
        if !events {
            for l in 1..p.height {
                let nodes = self.maps[l - 1].len();
                let table = followers_table(nodes, &seqs[l - 1]);
                let ok = scored[l]
                    .iter()
                    .filter(|&&(prev, actual)| most_frequent(&table, nodes, prev) == actual)
                    .count();
                self.lookup[l] = if scored[l].is_empty() {
                    0.0
                } else {
                    ok as f64 / scored[l].len() as f64
                };
            }
        }
        self.accuracy = (0..p.height)
            .map(|l| fraction(acc_ok[l], acc_n[l]))
            .collect();
        self.demo_runs = spread(&runs_per_demo);
        for l in 0..p.height {
            let c = count[l].max(1) as f64;
            self.qe[l] = qe_sum[l] / c;
            self.te[l] = te_bad[l] as f64 / c;
        }
        if p.normalisation != Normalisation::PerDimension {
            self.qe[0] *= self.scale[0];
        }
    }

    /// A posture in the data's units as the bottom level sees it: (x - offset) / scale.
    pub(crate) fn normalise(&self, x: &[f64]) -> Vec<f64> {
        normalised(x, &self.offset, &self.scale)
    }

    /// Normalised rows.
    pub(crate) fn normalise_rows(&self, rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
        rows.iter().map(|r| self.normalise(r)).collect()
    }

    /// The central 95 % band about `rows` (a reproduction, in the data's units) from the
    /// training paths, pinned at its start and at `pinned` (phases;
    /// [`crate::condition::spread_band`], measured where the bottom level sees the data);
    /// `None` with fewer than 2 training paths.
    pub(crate) fn band(
        &self,
        rows: &[Vec<f64>],
        pinned: &[f64],
    ) -> Option<crate::condition::ConfidenceBand> {
        let b = crate::condition::spread_band(&self.normalise_rows(rows), &self.paths, pinned)?;
        let back = |side: &[Vec<f64>]| side.iter().map(|r| self.denormalise(r)).collect();
        Some(crate::condition::ConfidenceBand {
            lo: back(&b.lo),
            hi: back(&b.hi),
        })
    }

    /// Back to the data's units: y * scale + offset.
    pub(crate) fn denormalise(&self, y: &[f64]) -> Vec<f64> {
        y.iter()
            .enumerate()
            .map(|(d, v)| v * self.scale[d] + self.offset[d])
            .collect()
    }

    /// Level `level` (>= 1) predicts the next entry of the list of `level - 1` from its
    /// `offset` or more newest entries (as in reproduction: known entries in the oldest
    /// slots, rounded ID clamped to the grid); `None` with too little history or activity
    /// levels.
    pub(crate) fn predict_next(
        &self,
        stm: &Stm,
        level: usize,
        offset: usize,
        buf: &mut [f64],
        mask: &mut [bool],
    ) -> Option<usize> {
        let memory = stm.memory;
        if level == 0 || level >= self.maps.len() {
            return None;
        }
        let Activity::Lists(lists) = &stm.mem else {
            return None;
        };
        let list = &lists[level - 1];
        if memory < 2 || list.len() < offset.max(1) {
            return None;
        }
        let k = list.len().min(memory - 1);
        let shift = memory - k;
        list.encode(k, shift, buf, mask);
        let (b, _) = self.maps[level].bmu_masked(buf, mask);
        let w = self.maps[level].weights(b);
        let below = &self.maps[level - 1];
        let x = w[2 * (shift - 1)]
            .round()
            .clamp(0.0, below.cols() as f64 - 1.0) as u16;
        let y = w[2 * (shift - 1) + 1]
            .round()
            .clamp(0.0, below.rows() as f64 - 1.0) as u16;
        Some(below.index((x, y)))
    }
}
