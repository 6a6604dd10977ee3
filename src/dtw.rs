//! Dynamic time warping between two multivariate sequences.
//!
//! Local cost: the Euclidean distance between two samples, `c(i, j) = ‖a_i − b_j‖₂`.
//! Recursion (steps (1,1), (1,0), (0,1)):
//! `D(i, j) = c(i, j) + min(D(i−1, j−1), D(i−1, j), D(i, j−1))`, `D(0, 0) = c(0, 0)`.
//! The DTW distance is `D(n−1, m−1)`: the summed local cost along the cheapest monotone path
//! from `(0, 0)` to `(n−1, m−1)`. The *per-step* (normalised) distance divides it by the
//! number of cells on that path (between `max(n, m)` and `n + m − 1`), so it is in the
//! units of the samples (for joint angles: radians per step) and comparable across lengths.
//!
//! Ties between predecessors are broken in a fixed order (diagonal, then `(i−1, j)`, then
//! `(i, j−1)`), so results are deterministic.
//!
//! An optional Sakoe-Chiba band restricts the path to cells with `|i − j| ≤ w`. The width
//! is widened to at least `|n − m|` so that a path always exists.
//!
//! ```
//! use cosco_hsom::dtw::{dtw, Band};
//! let a = vec![vec![0.0], vec![1.0], vec![2.0]];
//! let b = vec![vec![0.0], vec![1.0], vec![1.0], vec![2.0]];
//! let al = dtw(&a, &b, Band::None).unwrap();
//! assert_eq!(al.distance, 0.0);
//! assert_eq!(al.path, vec![(0, 0), (1, 1), (1, 2), (2, 3)]);
//! ```

/// Errors of the DTW functions.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DtwError {
    /// One of the sequences has no sample.
    #[error("DTW needs two non-empty sequences (got {len_a} and {len_b} samples)")]
    Empty {
        /// Samples in the first sequence.
        len_a: usize,
        /// Samples in the second sequence.
        len_b: usize,
    },
    /// A sample's width differs from the first sample of the first sequence.
    #[error("DTW needs samples of one width: {which} sequence, sample {index} has {found} values, expected {expected}")]
    Width {
        /// `"first"` or `"second"`.
        which: &'static str,
        /// 0-based sample index.
        index: usize,
        /// Width of the first sample of the first sequence.
        expected: usize,
        /// Width found.
        found: usize,
    },
    /// A value is NaN or infinite.
    #[error("DTW needs finite values: {which} sequence, sample {index} holds {value}")]
    NotFinite {
        /// `"first"` or `"second"`.
        which: &'static str,
        /// 0-based sample index.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A band fraction outside `[0, 1]` or not finite.
    #[error("Sakoe-Chiba band fraction must be within [0, 1], got {fraction}")]
    BandFraction {
        /// The rejected fraction.
        fraction: f64,
    },
}

/// Sakoe-Chiba band: which cells `(i, j)` the warping path may visit.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Band {
    /// No constraint: every cell.
    #[default]
    None,
    /// Cells with `|i − j| ≤ w`, `w` in samples (widened to at least `|n − m|`).
    Samples(usize),
    /// Cells with `|i − j| ≤ ceil(f · max(n, m))`, `f` in `[0, 1]` (widened to at least
    /// `|n − m|`).
    Fraction(f64),
}

impl Band {
    /// The half-width in samples for sequences of `n` and `m` samples, after widening to
    /// `|n − m|`; `None` means unconstrained.
    pub fn width(&self, n: usize, m: usize) -> Result<Option<usize>, DtwError> {
        let min_w = n.abs_diff(m);
        match *self {
            Band::None => Ok(None),
            Band::Samples(w) => Ok(Some(w.max(min_w))),
            Band::Fraction(f) => {
                if !(0.0..=1.0).contains(&f) {
                    return Err(DtwError::BandFraction { fraction: f });
                }
                let w = (f * n.max(m) as f64).ceil() as usize;
                Ok(Some(w.max(min_w)))
            }
        }
    }
}

/// Cost of the cheapest warping path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DtwCost {
    /// Summed Euclidean local cost along the path (units of the samples).
    pub distance: f64,
    /// Number of cells on the path (≥ `max(n, m)`).
    pub steps: usize,
}

impl DtwCost {
    /// Normalised distance: `distance / steps`, the mean local cost per path step.
    pub fn per_step(&self) -> f64 {
        self.distance / self.steps as f64
    }
}

/// A DTW alignment: the cost and the warping path.
#[derive(Debug, Clone, PartialEq)]
pub struct Alignment {
    /// Summed Euclidean local cost along the path.
    pub distance: f64,
    /// Normalised distance: `distance / path.len()` (per step).
    pub normalized: f64,
    /// The warping path, pairs `(i, j)` from `(0, 0)` to `(n−1, m−1)`, each step
    /// increasing `i`, `j` or both by one.
    pub path: Vec<(usize, usize)>,
}

fn check<R: AsRef<[f64]>>(a: &[R], b: &[R]) -> Result<usize, DtwError> {
    if a.is_empty() || b.is_empty() {
        return Err(DtwError::Empty {
            len_a: a.len(),
            len_b: b.len(),
        });
    }
    let width = a[0].as_ref().len();
    for (which, seq) in [("first", a), ("second", b)] {
        for (index, row) in seq.iter().enumerate() {
            let row = row.as_ref();
            if row.len() != width {
                return Err(DtwError::Width {
                    which,
                    index,
                    expected: width,
                    found: row.len(),
                });
            }
            if let Some(&value) = row.iter().find(|v| !v.is_finite()) {
                return Err(DtwError::NotFinite {
                    which,
                    index,
                    value,
                });
            }
        }
    }
    Ok(width)
}

/// Euclidean distance between two samples of equal width.
pub fn euclidean(x: &[f64], y: &[f64]) -> f64 {
    x.iter()
        .zip(y)
        .map(|(p, q)| (p - q) * (p - q))
        .sum::<f64>()
        .sqrt()
}

/// Columns `lo..hi` of row `i` inside the band (all `0..m` without one).
#[inline]
fn band_columns(i: usize, m: usize, w: Option<usize>) -> (usize, usize) {
    match w {
        None => (0, m),
        Some(w) => (i.saturating_sub(w), (i + w + 1).min(m)),
    }
}

/// Choose the predecessor of cell (i, j) among diagonal, up (i−1, j), left (i, j−1):
/// returns (cost, steps, direction) with direction 0 = diagonal, 1 = up, 2 = left.
#[inline]
fn best(diag: (f64, usize), up: (f64, usize), left: (f64, usize)) -> ((f64, usize), u8) {
    let mut b = (diag, 0u8);
    if up.0 < b.0 .0 {
        b = (up, 1);
    }
    if left.0 < b.0 .0 {
        b = (left, 2);
    }
    b
}

const INF: (f64, usize) = (f64::INFINITY, 0);

/// DTW distance only, with `O(m)` memory (two rows of the cost matrix). Gives the same
/// distance and step count as [`dtw`].
pub fn dtw_distance<R: AsRef<[f64]>>(a: &[R], b: &[R], band: Band) -> Result<DtwCost, DtwError> {
    check(a, b)?;
    let w = band.width(a.len(), b.len())?;
    Ok(by_rows(a, b, w, |_, _| {}))
}

/// The DTW cost row by row in two rows of memory, inside the band of half-width `w`;
/// `row(i, costs)` sees each row's accumulated (cost, steps) once it is complete.
fn by_rows<R: AsRef<[f64]>>(
    a: &[R],
    b: &[R],
    w: Option<usize>,
    mut row: impl FnMut(usize, &[(f64, usize)]),
) -> DtwCost {
    let m = b.len();
    let mut prev = vec![INF; m];
    let mut cur = vec![INF; m];
    for (i, ai) in a.iter().enumerate() {
        let ai = ai.as_ref();
        let (lo, hi) = band_columns(i, m, w);
        cur.fill(INF);
        for (j, bj) in b.iter().enumerate().take(hi).skip(lo) {
            let c = euclidean(ai, bj.as_ref());
            if i == 0 && j == 0 {
                cur[j] = (c, 1);
                continue;
            }
            let diag = if i > 0 && j > 0 { prev[j - 1] } else { INF };
            let up = if i > 0 { prev[j] } else { INF };
            let left = if j > 0 { cur[j - 1] } else { INF };
            let ((d, s), _) = best(diag, up, left);
            cur[j] = (d + c, s + 1);
        }
        std::mem::swap(&mut prev, &mut cur);
        row(i, &prev);
    }
    let (distance, steps) = prev[m - 1];
    DtwCost { distance, steps }
}

/// DTW with the warping path, `O(n·m)` memory.
pub fn dtw<R: AsRef<[f64]>>(a: &[R], b: &[R], band: Band) -> Result<Alignment, DtwError> {
    check(a, b)?;
    let (n, m) = (a.len(), b.len());
    let w = band.width(n, m)?;
    let (acc, dir) = fill(a, b, w);
    Ok(backtrack(&acc, &dir, m, (n - 1, m - 1)))
}

/// DTW with an open end in `b`: the cheapest warping path that starts at both starts and
/// covers all of `a`, ending at whichever sample of `b` makes it cheapest (the first such
/// one), with its path from `(0, 0)` to `(n−1, end)`; `O(n·m)` memory, no band. Where `a` is
/// the first part of something like `b`, the path's last column says how far along `b` it
/// got.
pub fn dtw_open_end<R: AsRef<[f64]>>(a: &[R], b: &[R]) -> Result<Alignment, DtwError> {
    check(a, b)?;
    let (n, m) = (a.len(), b.len());
    let (acc, dir) = fill(a, b, None);
    let last = &acc[(n - 1) * m..];
    let end = (0..m).fold(0, |e, j| if last[j].0 < last[e].0 { j } else { e });
    Ok(backtrack(&acc, &dir, m, (n - 1, end)))
}

/// The accumulated costs (cost, steps) and the predecessor directions of every cell of the
/// `a` x `b` matrix (row-major), inside the band of half-width `w`.
fn fill<R: AsRef<[f64]>>(a: &[R], b: &[R], w: Option<usize>) -> (Vec<(f64, usize)>, Vec<u8>) {
    let m = b.len();
    let mut acc = vec![INF; a.len() * m];
    let mut dir = vec![0u8; a.len() * m];
    for (i, ai) in a.iter().enumerate() {
        let ai = ai.as_ref();
        let (lo, hi) = band_columns(i, m, w);
        for (j, bj) in b.iter().enumerate().take(hi).skip(lo) {
            let c = euclidean(ai, bj.as_ref());
            let k = i * m + j;
            if i == 0 && j == 0 {
                acc[k] = (c, 1);
                continue;
            }
            let diag = if i > 0 && j > 0 { acc[k - m - 1] } else { INF };
            let up = if i > 0 { acc[k - m] } else { INF };
            let left = if j > 0 { acc[k - 1] } else { INF };
            let ((d, s), d_ir) = best(diag, up, left);
            acc[k] = (d + c, s + 1);
            dir[k] = d_ir;
        }
    }
    (acc, dir)
}

/// The warping path ending at cell `(i, j)` of a filled matrix of `m` columns.
fn backtrack(acc: &[(f64, usize)], dir: &[u8], m: usize, (i, j): (usize, usize)) -> Alignment {
    let (distance, steps) = acc[i * m + j];
    let mut path = Vec::with_capacity(steps);
    let (mut i, mut j) = (i, j);
    path.push((i, j));
    while i > 0 || j > 0 {
        match dir[i * m + j] {
            0 => {
                i -= 1;
                j -= 1;
            }
            1 => i -= 1,
            _ => j -= 1,
        }
        path.push((i, j));
    }
    path.reverse();
    Alignment {
        distance,
        normalized: distance / path.len() as f64,
        path,
    }
}

/// The index of the lowest value (the first among equals; NaN never wins).
pub(crate) fn argmin(v: &[f64]) -> usize {
    let mut best = 0;
    for (i, x) in v.iter().enumerate() {
        if *x < v[best] || v[best].is_nan() {
            best = i;
        }
    }
    best
}

/// DTW of `a` against `b` ([`dtw_distance`], unconstrained), and on the way, for every prefix
/// of `a` (its first `i + 1` samples, at index `i`), the cost per sample of the cheapest
/// warping path that starts at both starts, covers the prefix and ends anywhere in `b` (an
/// open end): how well each part of `a` seen so far follows the start of `b`.
pub(crate) fn dtw_with_prefixes(
    a: &[Vec<f64>],
    b: &[Vec<f64>],
) -> Result<(DtwCost, Vec<f64>), DtwError> {
    check(a, b)?;
    let p = pruned::prefixes(a, &pruned::Reference::new(b));
    Ok((p.whole, p.prefix))
}

/// [`dtw_with_prefixes`] computed over every cell (what the pruned computation must equal),
/// and the share of the cells the pruned one skips.
#[cfg(test)]
pub(crate) fn dtw_with_prefixes_full(
    a: &[Vec<f64>],
    b: &[Vec<f64>],
) -> Result<(DtwCost, Vec<f64>), DtwError> {
    check(a, b)?;
    let mut prefixes = Vec::with_capacity(a.len());
    let whole = by_rows(a, b, None, |i, costs| {
        let open = costs.iter().map(|c| c.0).fold(f64::INFINITY, f64::min);
        prefixes.push(open / (i + 1) as f64);
    });
    Ok((whole, prefixes))
}

/// The share of the cells of the DTW of `a` against `b` that [`dtw_with_prefixes`] skips
/// (docs/BENCHMARKS.md); `None` when the sequences are refused.
pub fn prefix_pruning_rate<R: AsRef<[f64]>>(a: &[R], b: &[R]) -> Option<f64> {
    let rows = |s: &[R]| -> Vec<Vec<f64>> { s.iter().map(|r| r.as_ref().to_vec()).collect() };
    let (a, b) = (rows(a), rows(b));
    check(&a, &b).ok()?;
    let p = pruned::prefixes(&a, &pruned::Reference::new(&b));
    Some(1.0 - p.computed as f64 / (a.len() * b.len()) as f64)
}

/// Where along `b` the sequence `a` ends (the column of the cheapest warping path that starts
/// at both starts and covers all of `a`, open end in `b`) and that path's cost per sample of
/// `a`.
pub(crate) fn open_end_cost(a: &[Vec<f64>], b: &[Vec<f64>]) -> (usize, f64) {
    let m = b.len();
    let mut prev = vec![f64::INFINITY; m];
    let mut cur = vec![f64::INFINITY; m];
    for (i, ai) in a.iter().enumerate() {
        for j in 0..m {
            let c = euclidean(ai, &b[j]);
            let best = if i == 0 && j == 0 {
                0.0
            } else {
                let diag = if i > 0 && j > 0 {
                    prev[j - 1]
                } else {
                    f64::INFINITY
                };
                let up = if i > 0 { prev[j] } else { f64::INFINITY };
                let left = if j > 0 { cur[j - 1] } else { f64::INFINITY };
                diag.min(up).min(left)
            };
            cur[j] = best + c;
        }
        std::mem::swap(&mut prev, &mut cur);
    }
    let end = argmin(&prev);
    (end, prev[end] / a.len().max(1) as f64)
}

pub(crate) mod pruned;
#[cfg(test)]
mod tests;
