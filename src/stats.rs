//! Order statistics of a sample: the median, a quantile, and the upper median.
//!
//! Two conventions, each on purpose:
//! - [`median`] and [`quantile`] interpolate between the two middle (neighbouring) order
//!   statistics (Hyndman & Fan's type 7, the default of R and numpy): what the reports, studies
//!   and sweeps summarise results with. [`median`] takes the mean of the two middle values,
//!   which is [`quantile`] at 0.5 up to rounding in the last bit.
//! - [`upper_median`] is one of the values itself (the upper of the two middle ones of an even
//!   count), found by selection without sorting: what the algorithms estimate a scale with (a
//!   recording's sample interval, the noise of a sequence, the spread of start postures), where
//!   a value that occurred is wanted and the call is in a loop.

/// The median of the finite values (`None` when there are none): the middle one, or the mean
/// of the two middle ones.
pub fn median(values: impl IntoIterator<Item = f64>) -> Option<f64> {
    let mut v: Vec<f64> = values.into_iter().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    })
}

/// The `p`-quantile (0 <= p <= 1) of `sorted` (ascending, finite), interpolating linearly
/// between order statistics (type 7); `None` when empty.
pub fn quantile(sorted: &[f64], p: f64) -> Option<f64> {
    let n = sorted.len();
    if n == 0 {
        return None;
    }
    let h = (n - 1) as f64 * p.clamp(0.0, 1.0);
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    Some(sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo]))
}

/// The value of rank `n / 2` (from 0) of `values` in ascending order ([`f64::total_cmp`]): the
/// median of an odd count, the upper of the two middle values of an even one; `None` when
/// empty. Reorders `values` (selection, linear time).
pub fn upper_median(values: &mut [f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let mid = values.len() / 2;
    let (_, m, _) = values.select_nth_unstable_by(mid, f64::total_cmp);
    Some(*m)
}

#[cfg(test)]
mod tests;
