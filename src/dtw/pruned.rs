//! The DTW of a sequence against a reference with every prefix's open-ended cost
//! ([`super::dtw_with_prefixes`]), computed only where it can matter. An upper bound of the
//! whole path's cost is the cost of a valid path (the cheaper of the diagonal's and the
//! cheapest within a narrow band around it); what the rows after row `i` still add is at
//! least the sum of their lower bounds (each row's distance to the nearest bounding box of
//! a few consecutive reference rows). A cell of row `i` whose accumulated cost is above the
//! upper bound less that sum lies on no cheapest path and is the minimum of no row, so it is
//! skipped: PrunedDTW (Silva and Batista, SDM 2016) with the UCR suite's cumulative lower
//! bounds (Rakthanmanon et al., KDD 2012). Every cell a cheapest path or a row's minimum
//! needs holds exactly what the full computation holds, and so do the whole cost, its steps
//! and every prefix's cost: the answers are identical, the work smaller. A row's distances
//! are computed a coordinate at a time over the reference stored by columns, which the
//! compiler vectorises; the sums are taken in the same order as [`super::euclidean`]'s.

use super::DtwCost;

/// A reference sequence stored by coordinate (`cols[k * m + j]`: coordinate `k` of row `j`).
pub(crate) struct Reference {
    width: usize,
    m: usize,
    cols: Vec<f64>,
    /// The bounding boxes of blocks of [`BLOCK`] consecutive rows, by coordinate:
    /// `lows[k * blocks + q]` the lowest value of coordinate `k` in block `q`, `highs` the
    /// highest.
    blocks: usize,
    lows: Vec<f64>,
    highs: Vec<f64>,
}

/// Columns either side of the diagonal path that the upper bound's path may take
/// ([`band_bound`]).
const BAND: usize = 8;

/// Rows of the reference per bounding box of [`Reference::nearest_bound`].
const BLOCK: usize = 8;

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
        let blocks = m.div_ceil(BLOCK);
        let (mut lows, mut highs) = (vec![0.0; width * blocks], vec![0.0; width * blocks]);
        for (q, block) in b.chunks(BLOCK).enumerate() {
            for k in 0..width {
                let (lo, hi) = block[1..]
                    .iter()
                    .fold((block[0][k], block[0][k]), |(l, h), r| {
                        (l.min(r[k]), h.max(r[k]))
                    });
                lows[k * blocks + q] = lo;
                highs[k * blocks + q] = hi;
            }
        }
        Reference {
            width,
            m,
            cols,
            blocks,
            lows,
            highs,
        }
    }

    /// A lower bound of `euclidean(x, b[j])` over every row `j`: the distance from `x` to the
    /// nearest of the blocks' bounding boxes. Never above any of those distances as computed
    /// in floating point: per coordinate the gap to the box is no larger than the gap to any
    /// row in it (a difference rounds monotonically), and the squares are summed in the
    /// same order.
    pub(crate) fn nearest_bound(&self, x: &[f64], sums: &mut Vec<f64>) -> f64 {
        let q = self.blocks;
        sums.clear();
        sums.resize(q, 0.0);
        for (k, &a) in x.iter().enumerate().take(self.width) {
            let (lo, hi) = (
                &self.lows[k * q..(k + 1) * q],
                &self.highs[k * q..(k + 1) * q],
            );
            for ((s, &l), &h) in sums.iter_mut().zip(lo).zip(hi) {
                // the gap below the box, above it, or none (the others are negative)
                let t = (l - a).max(a - h).max(0.0);
                *s += t * t;
            }
        }
        sums.iter().copied().fold(f64::INFINITY, f64::min).sqrt()
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

/// The cost of the cheapest warping path from `(0, 0)` to `(n - 1, m - 1)` through cells at
/// most `w` columns from the diagonal path's ([`diagonal_bound`]'s) in their row: a valid
/// path, so the cheapest path over every cell costs no more, in floating point too (each
/// cell's cost is the same local cost added to the least of predecessors no cheaper than
/// the full computation's); infinite where the cells do not connect. Its cells computed are
/// added to `computed`.
fn band_bound(a: &[Vec<f64>], b: &Reference, w: usize, computed: &mut usize) -> f64 {
    let (n, m) = (a.len(), b.len());
    let target = |i: usize| {
        if n == 1 {
            m - 1
        } else {
            (i * (m - 1)) / (n - 1)
        }
    };
    const INF: f64 = f64::INFINITY;
    let mut prev = vec![INF; m];
    let mut cur = vec![INF; m];
    let mut dist = vec![0.0; m];
    // the columns set in the rows `prev` and `cur` hold
    let (mut in_prev, mut in_cur) = ((0, 0), (0, 0));
    for (i, ai) in a.iter().enumerate() {
        let t = target(i);
        let (lo, hi) = (t.saturating_sub(w), (t + w + 1).min(m));
        cur[in_cur.0..in_cur.1].fill(INF);
        b.distances(ai, lo, hi, &mut dist);
        let mut left = INF;
        for j in lo..hi {
            let c = dist[j - lo];
            let v = if i == 0 && j == 0 {
                c
            } else {
                let mut best = if j > 0 { prev[j - 1] } else { INF };
                if prev[j] < best {
                    best = prev[j];
                }
                if left < best {
                    best = left;
                }
                best + c
            };
            cur[j] = v;
            left = v;
        }
        *computed += hi - lo;
        std::mem::swap(&mut prev, &mut cur);
        (in_prev, in_cur) = ((lo, hi), in_prev);
    }
    prev[m - 1]
}

/// Per row `i` of `a`, the accumulated cost above which a cell of that row lies on no cheapest
/// path and is no row's minimum: the upper bound `ub` of the whole path's cost less a lower
/// bound of what the rows after it still add (each row's [`Reference::nearest_bound`]), as
/// the UCR suite's cumulative lower bounds abandon early (Rakthanmanon et al., KDD 2012).
/// A cell on the cheapest path, or on the cheapest path to a row's minimum, has a cost of at
/// most `ub` less what the rest of that path adds, hence at most the threshold; the
/// threshold is raised by a billionth of `ub`, far more than the rounding of sums of a few
/// thousand terms, so that this holds in floating point too. Without a finite bound: no
/// threshold.
fn thresholds(a: &[Vec<f64>], b: &Reference, ub: f64) -> Vec<f64> {
    if !ub.is_finite() {
        return vec![f64::INFINITY; a.len()];
    }
    let mut out = vec![0.0; a.len()];
    let mut rest = 0.0;
    let mut sums = Vec::new();
    for (i, ai) in a.iter().enumerate().rev() {
        out[i] = ub - rest + 1e-9 * ub;
        rest += b.nearest_bound(ai, &mut sums);
    }
    out
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
    let mut computed = 0;
    let ub = diagonal_bound(a, b).min(band_bound(a, b, BAND, &mut computed));
    let within = thresholds(a, b, ub);
    const INF: f64 = f64::INFINITY;
    // a row's accumulated costs and steps, column j at index j + 1 (index 0: none, before
    // the first column)
    let (mut pc, mut ps) = (vec![INF; m + 1], vec![0usize; m + 1]);
    let (mut cc, mut cs) = (vec![INF; m + 1], vec![0usize; m + 1]);
    let mut dist = vec![0.0; m];
    // the columns computed in the previous row and in the row before it (the buffer `cc`
    // still holds them), and the previous row's columns within the bound
    let (mut old, mut prev_range) = ((0, 0), (0, 0));
    let (mut keep_lo, mut keep_hi) = (0usize, 0usize);
    let mut prefix = Vec::with_capacity(n);
    for (i, ai) in a.iter().enumerate() {
        let ub = within[i];
        cc[old.0 + 1..old.1 + 1].fill(INF);
        // predecessors within the bound above (columns keep_lo..=keep_hi) reach columns
        // keep_lo..=keep_hi + 1 by a step down or diagonal
        let lo = if i == 0 { 0 } else { keep_lo };
        let batch_hi = if i == 0 { 1 } else { (keep_hi + 2).min(m) };
        b.distances(ai, lo, batch_hi, &mut dist);
        // the left neighbour's cost and steps; the first cell starts from nothing
        let (mut lc, mut ls) = if i == 0 { (0.0, 0) } else { (INF, 0) };
        let mut open = INF;
        let (mut first_within, mut last_within) = (usize::MAX, usize::MAX);
        // cell (i, j) from the diagonal (index j), from above (j + 1) and from the left, ties
        // in that order
        macro_rules! relax {
            ($j:expr, $c:expr) => {{
                let (j, c) = ($j, $c);
                let (mut bc, mut bs) = (pc[j], ps[j]);
                if pc[j + 1] < bc {
                    (bc, bs) = (pc[j + 1], ps[j + 1]);
                }
                if lc < bc {
                    (bc, bs) = (lc, ls);
                }
                (lc, ls) = (bc + c, bs + 1);
                cc[j + 1] = lc;
                cs[j + 1] = ls;
                if lc <= ub {
                    if first_within == usize::MAX {
                        first_within = j;
                    }
                    last_within = j;
                }
                if lc < open {
                    open = lc;
                }
            }};
        }
        for (j, &c) in (lo..batch_hi).zip(&dist) {
            relax!(j, c);
        }
        let mut j = batch_hi;
        // beyond the previous row's reach: only the left neighbour leads here
        while j < m && lc <= ub {
            relax!(j, b.distance(ai, j));
            j += 1;
        }
        computed += j - lo;
        old = prev_range;
        prev_range = (lo, j);
        (keep_lo, keep_hi) = match first_within {
            // nothing within the bound (only when the bound is not finite): keep all
            usize::MAX => (lo, j.saturating_sub(1)),
            f => (f, last_within),
        };
        prefix.push(open / (i + 1) as f64);
        std::mem::swap(&mut pc, &mut cc);
        std::mem::swap(&mut ps, &mut cs);
    }
    Prefixes {
        whole: DtwCost {
            distance: pc[m],
            steps: ps[m],
        },
        prefix,
        computed,
    }
}
