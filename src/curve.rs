//! Curve maths every method and the simulator share, on plain slices: the minimum-jerk
//! profile, the shape-preserving piecewise cubic Hermite curve (PCHIP), and reading a
//! trajectory between its rows (at a phase, at a fractional row, resampled to `n` rows).
//! It imports nothing of the crate: the rooms above it (the methods, conditioning, the
//! gesture demonstrator, the evaluation, the simulator) import their curves from here.
//!
//! ```
//! use cosco_hsom::curve::{at_phase, minimum_jerk_at, pchip};
//! assert_eq!((minimum_jerk_at(0.0), minimum_jerk_at(1.0)), (0.0, 1.0));
//! let rows = vec![vec![0.0], vec![1.0], vec![3.0]];
//! assert_eq!(at_phase(&rows, 0.75), vec![2.0]);
//! // monotone data stay monotone and within their range
//! let y = pchip(&[0.0, 1.0, 2.0, 3.0], &[0.0, 0.0, 1.0, 1.0], &[0.5, 1.5, 2.5]);
//! assert!(y.windows(2).all(|w| w[1] >= w[0]) && y.iter().all(|v| (0.0..=1.0).contains(v)));
//! ```

// ---------- minimum jerk ----------

/// The minimum-jerk profile's steepest slope, at `s = 1/2`: 15/8 times its mean. A move of
/// `d` over a time `T` peaks at `1.875 d / T`.
pub const MINIMUM_JERK_PEAK: f64 = 1.875;

/// The minimum-jerk profile from 0 to 1 at `s` (clamped to [0, 1]): `10s³ − 15s⁴ + 6s⁵`
/// (Flash & Hogan), at rest and without acceleration at both ends.
pub fn minimum_jerk_at(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    s * s * s * (10.0 - 15.0 * s + 6.0 * s * s)
}

/// The slope of [`minimum_jerk_at`] at `s` (clamped to [0, 1]): `30s²(1 − s)²`, 0 at both
/// ends, [`MINIMUM_JERK_PEAK`] at `s = 1/2`.
pub fn minimum_jerk_velocity(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    30.0 * (s * s) * (1.0 - s) * (1.0 - s)
}

/// Minimum-jerk samples from `from` to `to` at `s = k / n`, `k = 0 … n−1` (`to` itself is
/// not included: it is the next posture of the caller's path). `n = 0` gives nothing.
pub fn minimum_jerk(from: &[f64], to: &[f64], n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|k| {
            let h = minimum_jerk_at(k as f64 / n as f64);
            from.iter().zip(to).map(|(a, b)| a + (b - a) * h).collect()
        })
        .collect()
}

// ---------- the shape-preserving piecewise cubic (PCHIP) ----------

/// The slopes [`pchip_slopes`] gives the first and the last knot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PchipEnds {
    /// Fritsch–Carlson's three-point formulas, kept within the monotone limits (0 where the
    /// formula turns against the first secant, at most 3 times it where the data turn); two
    /// knots: the secant at both.
    ThreePoint,
    /// 0: the curve leaves its first knot and reaches its last at rest; two knots or fewer:
    /// 0 everywhere.
    AtRest,
}

/// PCHIP slopes at the knots `(x, y)` (`x` increasing; Fritsch & Carlson 1980): at an inner
/// knot between two secants of one sign, their weighted harmonic mean (Fritsch–Butland,
/// never more than 3 times either); 0 where the secants change sign or one is 0 (a turn or
/// a hold stays at the knot); at the ends as `ends` says.
pub fn pchip_slopes(x: &[f64], y: &[f64], ends: PchipEnds) -> Vec<f64> {
    let n = x.len();
    let mut d = vec![0.0; n];
    if n < 2 {
        return d;
    }
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let delta: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    if n == 2 {
        if ends == PchipEnds::ThreePoint {
            d = vec![delta[0]; 2];
        }
        return d;
    }
    for i in 1..n - 1 {
        if delta[i - 1] * delta[i] > 0.0 {
            let (w1, w2) = (2.0 * h[i] + h[i - 1], h[i] + 2.0 * h[i - 1]);
            d[i] = (w1 + w2) / (w1 / delta[i - 1] + w2 / delta[i]);
        }
    }
    if ends == PchipEnds::ThreePoint {
        let end = |h0: f64, h1: f64, d0: f64, d1: f64| {
            let s = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
            if s * d0 <= 0.0 {
                0.0
            } else if d0 * d1 <= 0.0 && s.abs() > 3.0 * d0.abs() {
                3.0 * d0
            } else {
                s
            }
        };
        d[0] = end(h[0], h[1], delta[0], delta[1]);
        d[n - 1] = end(h[n - 2], h[n - 3], delta[n - 2], delta[n - 3]);
    }
    d
}

/// The cubic Hermite curve through the knots `(x, y)` with slopes `d` on segment `seg`
/// (knots `seg` and `seg + 1`) at `t`, clamped to the segment; a single knot's value; the
/// second knot's value on a segment of no length.
pub fn hermite(x: &[f64], y: &[f64], d: &[f64], seg: usize, t: f64) -> f64 {
    if x.len() == 1 {
        return y[0];
    }
    let (x0, y0, d0) = (x[seg], y[seg], d[seg]);
    let (y1, d1) = (y[seg + 1], d[seg + 1]);
    let h = x[seg + 1] - x0;
    if h <= 0.0 {
        return y1;
    }
    let s = ((t - x0) / h).clamp(0.0, 1.0);
    let (s2, s3) = (s * s, s * s * s);
    (2.0 * s3 - 3.0 * s2 + 1.0) * y0
        + (s3 - 2.0 * s2 + s) * h * d0
        + (-2.0 * s3 + 3.0 * s2) * y1
        + (s3 - s2) * h * d1
}

/// Values at `at` (within `x`'s span) of the PCHIP curve through `(x, y)` (`x` strictly
/// increasing, at least one knot) with the three-point end slopes: monotone between knots,
/// never beyond its neighbouring knots' values. A time at a knot is read on the segment that
/// starts there.
pub fn pchip(x: &[f64], y: &[f64], at: &[f64]) -> Vec<f64> {
    if x.len() == 1 {
        return vec![y[0]; at.len()];
    }
    let d = pchip_slopes(x, y, PchipEnds::ThreePoint);
    at.iter()
        .map(|&t| {
            let seg = (x.partition_point(|&v| v <= t).max(1) - 1).min(x.len() - 2);
            hermite(x, y, &d, seg, t)
        })
        .collect()
}

// ---------- reading a trajectory between its rows ----------

/// The row before the fractional row `x` of `n` rows (at most the last but one) and how far
/// past it `x` lies (0..1 within the rows).
pub fn split_row(n: usize, x: f64) -> (usize, f64) {
    let i = (x.floor() as usize).min(n.saturating_sub(2));
    (i, x - i as f64)
}

/// [`split_row`] at the fractional row of `phase` (clamped to [0, 1]) in `n` rows:
/// `phase (n − 1)`.
pub fn split_phase(n: usize, phase: f64) -> (usize, f64) {
    split_row(n, phase.clamp(0.0, 1.0) * (n.max(1) - 1) as f64)
}

/// The posture of `rows` (at least one) at the fractional row `x`: linear between the two
/// rows about it ([`split_row`]), `a + f (b − a)`.
pub fn at_row<R: AsRef<[f64]>>(rows: &[R], x: f64) -> Vec<f64> {
    let (i, f) = split_row(rows.len(), x);
    let next = rows[(i + 1).min(rows.len() - 1)].as_ref();
    rows[i]
        .as_ref()
        .iter()
        .zip(next)
        .map(|(p, q)| p + f * (q - p))
        .collect()
}

/// The posture of `rows` (at least one) at `phase` (0..1 of its duration): [`at_row`] at the
/// fractional row `phase (n − 1)`. A conditioned reproduction's rows are checked so.
pub fn at_phase(rows: &[Vec<f64>], phase: f64) -> Vec<f64> {
    at_row(rows, phase.clamp(0.0, 1.0) * (rows.len().max(1) - 1) as f64)
}

/// A sequence resampled to `n` rows by [`at_row`] at the fractional rows `k (L−1)/(n−1)`.
/// An empty sequence or `n == 0` gives an empty result; a single row is repeated; `n == 1`
/// gives the first row.
pub fn resample_linear<R: AsRef<[f64]>>(seq: &[R], n: usize) -> Vec<Vec<f64>> {
    if seq.is_empty() || n == 0 {
        return Vec::new();
    }
    let len = seq.len();
    if len == 1 || n == 1 {
        return vec![seq[0].as_ref().to_vec(); n];
    }
    (0..n)
        .map(|k| at_row(seq, k as f64 * (len - 1) as f64 / (n - 1) as f64))
        .collect()
}

#[cfg(test)]
mod tests;
