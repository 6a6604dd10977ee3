//! The consensus weighed by the starts: per training demonstration, its placements and how
//! much its start counts.

use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::encode::dist2;
use crate::hsom::model::StartKnots;
use crate::stats::upper_median;

/// Widths [`StartKnots`] chooses among, in units of the median distance between two
/// training demonstrations' starts; all alike (infinite) is tried first and kept on a tie.
const START_WIDTHS: [f64; 5] = [2.0, 1.0, 0.5, 0.25, 0.125];

/// Every order of `0..n` (`n!` of them, the identity first).
pub(super) fn all_orders(n: usize) -> Vec<Vec<usize>> {
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
    pub(super) fn weights(starts: &[&Vec<f64>], x: &[f64], width: f64) -> Vec<f64> {
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
    pub(super) fn mean(knots: &[&Vec<f64>], weights: &[f64]) -> Vec<f64> {
        let total: f64 = weights.iter().sum();
        let mut out = vec![0.0; knots[0].len()];
        for (k, w) in knots.iter().zip(weights) {
            out.iter_mut()
                .zip(k.iter())
                .for_each(|(o, v)| *o += w / total * v);
        }
        out
    }

    /// The demonstrations' weights for a reproduction starting at `x` (normalised).
    fn weights_at(&self, x: &[f64]) -> Vec<f64> {
        let starts: Vec<&Vec<f64>> = self.starts.iter().collect();
        Self::weights(&starts, &x[..starts[0].len()], self.width)
    }

    /// The placement for a reproduction starting at `x` (normalised, state part).
    pub(crate) fn placed(&self, x: &[f64]) -> Vec<f64> {
        let knots: Vec<&Vec<f64>> = self.knots.iter().collect();
        Self::mean(&knots, &self.weights_at(x))
    }

    /// Where the demonstrations weighed by a reproduction starting at `x` began: the mean of
    /// their first postures with [`StartKnots::placed`]'s weights (normalised, state part).
    pub(crate) fn placed_start(&self, x: &[f64]) -> Vec<f64> {
        let starts: Vec<&Vec<f64>> = self.starts.iter().collect();
        Self::mean(&starts, &self.weights_at(x))
    }

    /// The width that predicts each demonstration's placement best from the others' (the
    /// squared error per node weighted by the samples on the node, `count`, summed over the
    /// demonstrations), kept only where the starts are evidence: its gain over all alike must
    /// be larger than that of the best width for the starts shuffled among the
    /// demonstrations, in all but [`START_SIGNIFICANCE`] of the orders (a permutation test:
    /// every order up to 6 demonstrations, else [`START_SHUFFLES`] shuffles drawn from
    /// `seed`). Infinite (all alike) otherwise, and with identical starts. With three
    /// demonstrations (six orders) it cannot be.
    pub(super) fn fit(
        starts: Vec<Vec<f64>>,
        knots: Vec<Vec<f64>>,
        count: &[f64],
        seed: u64,
    ) -> Self {
        let width = Self::fitted_width(&starts, &knots, count, seed);
        // the width is fitted on every demonstration; the model keeps the placements of the
        // sample of them it keeps (crate::hsom::KEPT_DEMONSTRATIONS): its size never grows
        // with their number
        let kept = crate::hsom::kept::kept_indices(starts.len(), seed);
        let pick = |v: Vec<Vec<f64>>| {
            let mut v: Vec<Option<Vec<f64>>> = v.into_iter().map(Some).collect();
            kept.iter().filter_map(|&i| v[i].take()).collect()
        };
        StartKnots {
            starts: pick(starts),
            knots: pick(knots),
            width,
        }
    }

    /// The width of [`StartKnots::fit`].
    fn fitted_width(starts: &[Vec<f64>], knots: &[Vec<f64>], count: &[f64], seed: u64) -> f64 {
        let n = starts.len();
        let s = knots[0].len() / count.len().max(1);
        let mut dist: Vec<f64> = (0..n)
            .flat_map(|a| (a + 1..n).map(move |b| (a, b)))
            .map(|(a, b)| dist2(&starts[a], &starts[b]).sqrt())
            .filter(|d| *d > 0.0)
            .collect();
        let Some(median) = upper_median(&mut dist) else {
            return f64::INFINITY;
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
            return f64::INFINITY;
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
        if p <= START_SIGNIFICANCE {
            width
        } else {
            f64::INFINITY
        }
    }
}

/// Fractions of the gesture [`start_fade`] chooses among.
const START_FADES: [f64; 5] = [0.0, 0.125, 0.25, 0.5, 1.0];

/// Phases at which [`start_fade`] compares the demonstrations.
const FADE_PHASES: usize = 50;

/// How long a start's offset lasts, as a fraction of the gesture: of [`START_FADES`], the
/// minimum-jerk fade `1 - s(u / f)` (`s` the minimum-jerk profile, `u` the phase) that best
/// predicts each training demonstration's offset from their mean at every phase from its
/// offset at the start (least squares over `norm`'s demonstrations, each read at
/// [`FADE_PHASES`] phases, state part `s`). Drawings of nested curves keep their offset to the
/// end (1); demonstrations that start apart by chance meet at once (0). `None` with fewer
/// than two demonstrations.
pub(crate) fn start_fade(norm: &[Vec<Vec<f64>>], s: usize) -> Option<f64> {
    if norm.len() < 2 || norm.iter().any(|d| d.is_empty()) {
        return None;
    }
    let at = |d: &[Vec<f64>], u: f64, j: usize| {
        let x = u * (d.len() - 1) as f64;
        let (i, w) = (x.floor() as usize, x.fract());
        let next = (i + 1).min(d.len() - 1);
        d[i][j] * (1.0 - w) + d[next][j] * w
    };
    let phases: Vec<f64> = (0..FADE_PHASES)
        .map(|k| k as f64 / (FADE_PHASES - 1) as f64)
        .collect();
    // mean[k][j]: the demonstrations' mean at phase k; offsets[d][k][j]: demonstration d's
    // offset from it
    let n = norm.len() as f64;
    let mean: Vec<Vec<f64>> = phases
        .iter()
        .map(|&u| {
            (0..s)
                .map(|j| norm.iter().map(|e| at(e, u, j)).sum::<f64>() / n)
                .collect()
        })
        .collect();
    let offsets: Vec<Vec<Vec<f64>>> = norm
        .iter()
        .map(|d| {
            phases
                .iter()
                .zip(&mean)
                .map(|(&u, m)| (0..s).map(|j| at(d, u, j) - m[j]).collect())
                .collect()
        })
        .collect();
    let error = |f: f64| -> f64 {
        offsets
            .iter()
            .map(|o| {
                phases
                    .iter()
                    .zip(o)
                    .map(|(&u, x)| {
                        let keep = if u >= f {
                            0.0
                        } else {
                            1.0 - crate::curve::minimum_jerk_at(u / f)
                        };
                        x.iter()
                            .zip(&o[0])
                            .map(|(v, v0)| (v - v0 * keep).powi(2))
                            .sum::<f64>()
                    })
                    .sum::<f64>()
            })
            .sum()
    };
    START_FADES
        .iter()
        .map(|&f| (error(f), f))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, f)| f)
}
