//! The central 95 % band about a reproduction (docs/METRICS.md, "Confidence band"): how far
//! the demonstrations it learned from lie from it where DTW aligns them to it, widened for
//! their small number and narrowed where the reproduction is pinned (its start, its goal, its
//! via-points).

use nalgebra::{DMatrix, DVector};
use statrs::distribution::{ContinuousCDF, StudentsT};

use crate::dtw::{dtw, Band};

/// A central band about a trajectory: per row, per variable, the lowest and the highest value
/// (a 95 % band: where 95 % of the gesture's demonstrations are expected, docs/METRICS.md).
#[derive(Debug, Clone, PartialEq)]
pub struct ConfidenceBand {
    /// Per row, the lower ends.
    pub lo: Vec<Vec<f64>>,
    /// Per row, the upper ends.
    pub hi: Vec<Vec<f64>>,
}

impl ConfidenceBand {
    /// `rows` minus and plus `half` (per row, per variable, >= 0).
    pub fn around(rows: &[Vec<f64>], half: &[Vec<f64>]) -> Self {
        let side = |sign: f64| -> Vec<Vec<f64>> {
            rows.iter()
                .zip(half)
                .map(|(r, h)| r.iter().zip(h).map(|(v, h)| v + sign * h).collect())
                .collect()
        };
        ConfidenceBand {
            lo: side(-1.0),
            hi: side(1.0),
        }
    }

    /// Rows of the band.
    pub fn len(&self) -> usize {
        self.lo.len()
    }

    /// Whether the band has no rows.
    pub fn is_empty(&self) -> bool {
        self.lo.is_empty()
    }

    /// The share of `other`'s values inside the band, `other`'s rows aligned to the band's by
    /// `path` (pairs `(band row, other's row)`, as DTW aligns them): each of `other`'s rows
    /// counts once, by the share of the band rows aligned to it that hold it, and each
    /// variable counts once. 0 for an empty path.
    pub fn coverage(&self, other: &[Vec<f64>], path: &[(usize, usize)]) -> f64 {
        // per row of `other`: (inside, pairs) summed over its pairs and variables
        let mut per_row = vec![(0usize, 0usize); other.len()];
        for &(i, j) in path {
            for (d, v) in other[j].iter().enumerate() {
                per_row[j].1 += 1;
                per_row[j].0 += usize::from((self.lo[i][d]..=self.hi[i][d]).contains(v));
            }
        }
        let shares: Vec<f64> = per_row
            .iter()
            .filter(|(_, n)| *n > 0)
            .map(|&(k, n)| k as f64 / n as f64)
            .collect();
        shares.iter().sum::<f64>() / shares.len().max(1) as f64
    }

    /// The band as CSV (`cosco reproduce --band`): `step` (the trajectory's own, one per
    /// row), then `<variable>_lo` and `<variable>_hi` for each of `columns`, one row per row
    /// of the trajectory.
    pub fn csv(&self, columns: &[String], steps: &[usize]) -> csv::Result<Vec<u8>> {
        let mut w = csv::Writer::from_writer(Vec::new());
        let header = columns
            .iter()
            .flat_map(|c| [format!("{c}_lo"), format!("{c}_hi")]);
        w.write_record(std::iter::once("step".to_string()).chain(header))?;
        for (step, (lo, hi)) in steps.iter().zip(self.lo.iter().zip(&self.hi)) {
            let values = lo
                .iter()
                .zip(hi)
                .flat_map(|(l, h)| [l.to_string(), h.to_string()]);
            w.write_record(std::iter::once(step.to_string()).chain(values))?;
        }
        w.into_inner().map_err(|e| e.into_error().into())
    }
}

/// The central 95 % band about `rows` (a reproduction) from `demos` (the demonstrations it
/// learned from, at least 2, each as wide as `rows`), pinned at the phases `pinned` (0..1:
/// where the reproduction is conditioned, its start at 0 always included); `None` with fewer
/// than 2 demonstrations or rows, or rows of another width.
///
/// 1. Each demonstration is aligned to `rows` by DTW; at each row, its values are the mean of
///    its samples aligned there. `s` is, per row and variable, the root mean square of their
///    deviations from the row: how far the demonstrations lie from this reproduction (not
///    from their mean, which the reproduction need not follow).
/// 2. The half-width is `t(0.975, n - 1) sqrt(1 + 1/n) s`: the prediction interval of one
///    more demonstration from `n`.
/// 3. It is narrowed where the reproduction is pinned by the factor
///    `sqrt(1 - k' K⁻¹ k)` of a Gaussian process of squared-exponential covariance over the
///    rows, `k` its covariances with the pinned rows and `K` theirs: 0 at a pinned row,
///    back to 1 a few length scales away. The length scale is the deviations' own: the
///    first lag (in rows) at which their pooled autocorrelation falls below `exp(-1/2)`, the
///    squared exponential's value at one length scale.
pub fn spread_band(
    rows: &[Vec<f64>],
    demos: &[Vec<Vec<f64>>],
    pinned: &[f64],
) -> Option<ConfidenceBand> {
    let (n, len) = (demos.len(), rows.len());
    let width = rows.first()?.len();
    if n < 2 || len < 2 || demos.iter().flatten().any(|r| r.len() != width) {
        return None;
    }
    // deviations[k][i][d]: demonstration k's mean aligned value at row i, minus the row
    let mut deviations = Vec::with_capacity(n);
    for demo in demos {
        let path = dtw(rows, demo, Band::None).ok()?.path;
        let mut sum = vec![vec![0.0; width]; len];
        let mut count = vec![0usize; len];
        for &(i, j) in &path {
            count[i] += 1;
            sum[i].iter_mut().zip(&demo[j]).for_each(|(s, v)| *s += v);
        }
        let dev: Vec<Vec<f64>> = (0..len)
            .map(|i| {
                let c = count[i].max(1) as f64;
                (0..width).map(|d| sum[i][d] / c - rows[i][d]).collect()
            })
            .collect();
        deviations.push(dev);
    }
    let t = StudentsT::new(0.0, 1.0, (n - 1) as f64)
        .ok()?
        .inverse_cdf(0.975);
    let widen = t * (1.0 + 1.0 / n as f64).sqrt();
    let scale = length_scale(&deviations);
    let pinned_rows: Vec<f64> = std::iter::once(0.0)
        .chain(pinned.iter().copied())
        .map(|p| p.clamp(0.0, 1.0) * (len - 1) as f64)
        .collect();
    let narrow = pinned_factor(len, &pinned_rows, scale);
    let half: Vec<Vec<f64>> = (0..len)
        .map(|i| {
            (0..width)
                .map(|d| {
                    let ms = deviations.iter().map(|k| k[i][d].powi(2)).sum::<f64>() / n as f64;
                    widen * ms.sqrt() * narrow[i]
                })
                .collect()
        })
        .collect();
    Some(ConfidenceBand::around(rows, &half))
}

/// The first lag, in rows, at which the pooled autocorrelation of the deviations (over
/// demonstrations and variables, about 0) falls below `exp(-1/2)`; the number of rows when it
/// never does, and 1 at least.
fn length_scale(deviations: &[Vec<Vec<f64>>]) -> f64 {
    let len = deviations.first().map_or(0, Vec::len);
    let lagged = |lag: usize| -> f64 {
        let s: f64 = (deviations.iter())
            .flat_map(|k| k.iter().zip(&k[lag..]))
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>())
            .sum();
        s / (len - lag) as f64
    };
    let zero = lagged(0);
    if zero <= 0.0 {
        return len as f64;
    }
    let threshold = (-0.5f64).exp();
    (1..len)
        .find(|&lag| lagged(lag) / zero < threshold)
        .unwrap_or(len) as f64
}

/// Per row of `len`, `sqrt(1 - k' K⁻¹ k)` for a squared-exponential covariance of length
/// `scale` rows, observed without noise at the (fractional) rows `pinned` (a tiny nugget
/// keeps `K` invertible when two are close).
fn pinned_factor(len: usize, pinned: &[f64], scale: f64) -> Vec<f64> {
    let kernel = |a: f64, b: f64| (-(a - b).powi(2) / (2.0 * scale * scale)).exp();
    let m = pinned.len();
    let mut big_k = DMatrix::from_fn(m, m, |a, b| kernel(pinned[a], pinned[b]));
    for a in 0..m {
        big_k[(a, a)] += 1e-9;
    }
    let Some(chol) = big_k.cholesky() else {
        return vec![1.0; len];
    };
    (0..len)
        .map(|i| {
            let k = DVector::from_fn(m, |a, _| kernel(i as f64, pinned[a]));
            let explained = k.dot(&chol.solve(&k));
            (1.0 - explained).max(0.0).sqrt()
        })
        .collect()
}
