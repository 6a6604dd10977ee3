//! The DTW of a sequence against a reference with every prefix's open-ended cost
//! ([`super::dtw_with_prefixes`]), computed only where it can matter: a cell whose accumulated
//! cost is above an upper bound of the whole path's cost (the cost of one valid path, the
//! diagonal's) lies on no cheapest path and is the minimum of no row, so it is skipped, as
//! PrunedDTW (Silva and Batista, SDM 2016) prunes. Every cell that is not skipped holds
//! exactly what the full computation holds, and so do the whole cost, its steps and every
//! prefix's cost: the answers are identical, the work smaller. A row's distances are
//! computed a coordinate at a time over the reference stored by columns, which the compiler
//! vectorises; the sums are taken in the same order as [`super::euclidean`]'s.

use super::DtwCost;

/// A reference sequence stored by coordinate (`cols[k * m + j]`: coordinate `k` of row `j`).
pub(crate) struct Reference {
    width: usize,
    m: usize,
    cols: Vec<f64>,
}

impl Reference {
    /// `b` (rows of one width, at least one row) stored by coordinate.
    pub(crate) fn new(b: &[Vec<f64>]) -> Self {
        let (m, width) = (b.len(), b.first().map_or(0, Vec::len));
        let mut cols = vec![0.0; width * m];
        for (j, row) in b.iter().enumerate() {
            for (k, v) in row.iter().enumerate() {
                cols[k * m + j] = *v;
            }
        }
        Reference { width, m, cols }
    }

    /// Rows of the reference.
    pub(crate) fn len(&self) -> usize {
        self.m
    }

    /// `out[j - lo] = euclidean(x, b[j])` for `j` in `lo..hi`: the squares summed in the
    /// coordinates' order, as [`super::euclidean`] sums them, so the values are the same.
    pub(crate) fn distances(&self, x: &[f64], lo: usize, hi: usize, out: &mut [f64]) {
        let out = &mut out[..hi - lo];
        out.fill(0.0);
        for (k, &a) in x.iter().enumerate().take(self.width) {
            let col = &self.cols[k * self.m + lo..k * self.m + hi];
            for (o, &b) in out.iter_mut().zip(col) {
                let t = a - b;
                *o += t * t;
            }
        }
        for o in out.iter_mut() {
            *o = o.sqrt();
        }
    }

    /// [`super::euclidean`] of `x` and row `j` (the squares summed in the same order).
    pub(crate) fn distance(&self, x: &[f64], j: usize) -> f64 {
        let mut s = 0.0;
        for (k, &a) in x.iter().enumerate().take(self.width) {
            let t = a - self.cols[k * self.m + j];
            s += t * t;
        }
        s.sqrt()
    }
}

/// The cost of the diagonal path from `(0, 0)` to `(n - 1, m - 1)` (a valid warping path:
/// each step moves down, right or both), summed along the path: the accumulated cost of the
/// cheapest path is never above it, in floating point too (adding the same local costs in
/// the same order to something no larger gives something no larger).
fn diagonal_bound(a: &[Vec<f64>], b: &Reference) -> f64 {
    let (n, m) = (a.len(), b.len());
    let target = |i: usize| {
        if n == 1 {
            m - 1
        } else {
            (i * (m - 1)) / (n - 1)
        }
    };
    let mut cost = b.distance(&a[0], 0);
    let mut j = 0;
    for (i, ai) in a.iter().enumerate() {
        let t = target(i);
        if i > 0 {
            // down, or down and right at once
            if t > j {
                j += 1;
            }
            cost += b.distance(ai, j);
        }
        while j < t {
            j += 1;
            cost += b.distance(ai, j);
        }
    }
    cost
}

/// What [`prefixes`] computed.
pub(crate) struct Prefixes {
    /// The whole sequence's DTW cost against the reference.
    pub(crate) whole: DtwCost,
    /// Per prefix (index: its samples - 1), its open-ended cost per sample.
    pub(crate) prefix: Vec<f64>,
    /// Cells computed, of `n * m`.
    pub(crate) computed: usize,
}

/// [`super::dtw_with_prefixes`] of `a` against `b` (both checked: non-empty, one width,
/// finite), pruned: the same whole cost, steps and prefix costs.
pub(crate) fn prefixes(a: &[Vec<f64>], b: &Reference) -> Prefixes {
    let (n, m) = (a.len(), b.len());
    let ub = diagonal_bound(a, b);
    const INF: f64 = f64::INFINITY;
    let (mut pc, mut ps) = (vec![INF; m], vec![0usize; m]);
    let (mut cc, mut cs) = (vec![INF; m], vec![0usize; m]);
    let mut dist = vec![0.0; m];
    // the columns computed in the previous row and in the row before it (the buffer `cc`
    // still holds them), and the previous row's columns within the bound
    let (mut old, mut prev_range) = ((0, 0), (0, 0));
    let (mut keep_lo, mut keep_hi) = (0usize, 0usize);
    let mut prefix = Vec::with_capacity(n);
    let mut computed = 0;
    for (i, ai) in a.iter().enumerate() {
        cc[old.0..old.1].fill(INF);
        // predecessors within the bound above (columns keep_lo..=keep_hi) reach columns
        // keep_lo..=keep_hi + 1 by a step down or diagonal
        let lo = if i == 0 { 0 } else { keep_lo };
        let batch_hi = if i == 0 { 1 } else { (keep_hi + 2).min(m) };
        b.distances(ai, lo, batch_hi, &mut dist);
        let mut j = lo;
        let mut open = INF;
        let mut last_within = None;
        let mut first_within = None;
        while j < m {
            let c = if j < batch_hi {
                dist[j - lo]
            } else {
                // beyond the previous row's reach: only the left neighbour leads here
                if cc[j - 1] > ub {
                    break;
                }
                b.distance(ai, j)
            };
            let (v, s) = if i == 0 && j == 0 {
                (c, 1)
            } else {
                let (mut bc, mut bs) = if i > 0 && j > 0 {
                    (pc[j - 1], ps[j - 1])
                } else {
                    (INF, 0)
                };
                if i > 0 && pc[j] < bc {
                    (bc, bs) = (pc[j], ps[j]);
                }
                if j > 0 && cc[j - 1] < bc {
                    (bc, bs) = (cc[j - 1], cs[j - 1]);
                }
                (bc + c, bs + 1)
            };
            cc[j] = v;
            cs[j] = s;
            if v <= ub {
                first_within.get_or_insert(j);
                last_within = Some(j);
            }
            open = open.min(v);
            j += 1;
        }
        computed += j - lo;
        old = prev_range;
        prev_range = (lo, j);
        (keep_lo, keep_hi) = match (first_within, last_within) {
            (Some(f), Some(l)) => (f, l),
            // nothing within the bound (only when the bound is not finite): keep all
            _ => (lo, j.saturating_sub(1)),
        };
        prefix.push(open / (i + 1) as f64);
        std::mem::swap(&mut pc, &mut cc);
        std::mem::swap(&mut ps, &mut cs);
    }
    Prefixes {
        whole: DtwCost {
            distance: pc[m - 1],
            steps: ps[m - 1],
        },
        prefix,
        computed,
    }
}
