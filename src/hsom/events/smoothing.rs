//! The smoothing of an executed curve: the curve nearest a sampled one whose jerk is least
//! (docs/ALGORITHM.md, section 3.8), by a banded factorisation built once for a length and a
//! weight and shared by every variable of a reproduction.

use std::cell::RefCell;
use std::rc::Rc;

/// The curve nearest `c` (sampled) whose jerk is least: `x` minimising
/// `Σ_{i≥1} (x_i − c_i)² + λ Σ_i (x_{i+3} − 3x_{i+2} + 3x_{i+1} − x_i)²` with `x_0 = c_0`
/// (Whittaker-Henderson smoothing with third differences), the third differences reaching
/// back before the start over [`BEFORE`] samples where the arm moved at `slope` per sample
/// (0: at rest), so the curve leaves `c_0` as the arm was moving, and `x_{n−1} = c_{n−1}`
/// with the arm at rest there after (the curve ends where and as it ends). Its normal equations are
/// banded (three diagonals each side), solved by a banded Cholesky factorisation in O(n).
pub(crate) fn jerk_smoothed(c: &[f64], lambda: f64, slope: f64) -> Vec<f64> {
    if c.len() < 5 || lambda <= 0.0 {
        return c.to_vec();
    }
    JerkFactor::new(c.len(), lambda)
        .solve_columns(&[c], &[slope])
        .remove(0)
}

/// [`jerk_smoothed`]'s normal matrix and its banded Cholesky factor for curves of one length
/// and one weight: they do not depend on the curve, so the columns of a reproduction share
/// them (the same operations on the same numbers: the same values).
pub(super) struct JerkFactor {
    /// a[i][k]: the normal matrix's entry (i, i - k) over every sample, k = 0..=3.
    a: Vec<[f64; 4]>,
    /// l[i][k] = L(i, i - k) of the unknowns' block.
    l: Vec<[f64; 4]>,
}

impl JerkFactor {
    /// For curves of `len` samples (at least 5) and weight `lambda` (above 0).
    pub(super) fn new(len: usize, lambda: f64) -> Self {
        let known = BEFORE + 1;
        let n = len + 2 * BEFORE;
        const D: [f64; 4] = [-1.0, 3.0, -3.0, 1.0];
        let mut a = vec![[0.0f64; 4]; n];
        for row in a.iter_mut() {
            row[0] = 1.0;
        }
        for j in 0..n - 3 {
            for p in 0..4 {
                for q in 0..=p {
                    a[j + p][p - q] += lambda * D[p] * D[q];
                }
            }
        }
        let m = n - 2 * known;
        // banded Cholesky of the unknowns' block: l[i][k] = L(i, i - k)
        let mut l = vec![[0.0f64; 4]; m];
        for i in 0..m {
            for k in (0..=3.min(i)).rev() {
                let j = i - k;
                let mut sum = a[i + known][k];
                for r in 1..=3usize {
                    // L(i, j - r) L(j, j - r)
                    if r + k <= 3 && r <= j {
                        sum -= l[i][k + r] * l[j][r];
                    }
                }
                if k == 0 {
                    l[i][0] = sum.max(f64::MIN_POSITIVE).sqrt();
                } else {
                    l[i][k] = sum / l[j][0];
                }
            }
        }
        JerkFactor { a, l }
    }

    /// The factor for `len` samples and weight `lambda`, built once and kept (per thread, the
    /// last [`KEPT_FACTORS`] made): reproductions of one length share it.
    pub(super) fn shared(len: usize, lambda: f64) -> Rc<JerkFactor> {
        FACTORS.with(|kept| {
            let mut kept = kept.borrow_mut();
            let key = (len, lambda.to_bits());
            if let Some((_, f)) = kept.iter().find(|(k, _)| *k == key) {
                return Rc::clone(f);
            }
            let f = Rc::new(JerkFactor::new(len, lambda));
            if kept.len() >= KEPT_FACTORS {
                kept.remove(0);
            }
            kept.push((key, Rc::clone(&f)));
            f
        })
    }

    /// [`jerk_smoothed`] of every column of `cols` (each of the factor's length, column
    /// `d` moving at `slopes[d]` before it; columns without a slope are left out), the
    /// columns' recurrences interleaved sample by sample: each column's values are computed
    /// by the same operations in the same order as alone, and the processor overlaps the
    /// columns' chains of divisions.
    pub(super) fn solve_columns<C: AsRef<[f64]>>(
        &self,
        cols: &[C],
        slopes: &[f64],
    ) -> Vec<Vec<f64>> {
        let (a, l) = (&self.a, &self.l);
        let w = cols.len().min(slopes.len());
        let Some(len) = cols.first().map(|c| c.as_ref().len()) else {
            return Vec::new();
        };
        // the samples before the curve and its first one, its last one and the samples at
        // rest after it: known values
        let known = BEFORE + 1;
        let n = len + 2 * BEFORE;
        let full = |d: usize, k: usize| {
            let c = cols[d].as_ref();
            if k < BEFORE {
                c[0] - (BEFORE - k) as f64 * slopes[d]
            } else if k < BEFORE + len {
                c[k - BEFORE]
            } else {
                c[len - 1]
            }
        };
        // the unknowns are x_known..n - known; their right-hand side without the known
        // values' terms (the normal matrix is symmetric: entry (i, i + k) is a[i + k][k]);
        // sample-major: entry u * w + d is column d's
        let m = n - 2 * known;
        let mut b = vec![0.0; m * w];
        for u in 0..m {
            let i = u + known;
            for d in 0..w {
                let mut bu = full(d, i);
                for k in 1..=3usize {
                    if i - k < known {
                        bu -= a[i][k] * full(d, i - k);
                    }
                    if i + k >= n - known {
                        bu -= a[i + k][k] * full(d, i + k);
                    }
                }
                b[u * w + d] = bu;
            }
        }
        // L y = b, then Lᵀ x = y
        let mut y = vec![0.0; m * w];
        for i in 0..m {
            let li = &l[i];
            for d in 0..w {
                let mut sum = b[i * w + d];
                for k in 1..=3.min(i) {
                    sum -= li[k] * y[(i - k) * w + d];
                }
                y[i * w + d] = sum / li[0];
            }
        }
        let mut x = vec![0.0; m * w];
        for i in (0..m).rev() {
            for d in 0..w {
                let mut sum = y[i * w + d];
                for k in 1..=3usize {
                    if i + k < m {
                        sum -= l[i + k][k] * x[(i + k) * w + d];
                    }
                }
                x[i * w + d] = sum / l[i][0];
            }
        }
        (0..w)
            .map(|d| {
                let c = cols[d].as_ref();
                std::iter::once(c[0])
                    .chain((0..m).map(|i| x[i * w + d]))
                    .chain(std::iter::once(c[len - 1]))
                    .collect()
            })
            .collect()
    }
}

/// Factors a thread keeps ([`JerkFactor::shared`]): every weight of [`super::curve`]'s
/// smoothing for several lengths (a few megabytes at most for gestures of a few hundred
/// samples).
const KEPT_FACTORS: usize = 64;

/// A factor kept, by its length and its weight's bits.
type Kept = ((usize, u64), Rc<JerkFactor>);

thread_local! {
    /// The factors kept, the oldest first.
    static FACTORS: RefCell<Vec<Kept>> = const { RefCell::new(Vec::new()) };
}

/// Samples before the curve (and after it) that [`jerk_smoothed`]'s third differences reach:
/// three, so the curve's first velocity and acceleration continue the arm's (and its last
/// come to rest).
const BEFORE: usize = 3;

#[cfg(test)]
mod tests;
