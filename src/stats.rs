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
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_even_non_finite_and_empty() {
        assert_eq!(median([3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median([4.0, 1.0, 2.0, 3.0]), Some(2.5));
        assert_eq!(median([f64::NAN, 5.0, f64::INFINITY]), Some(5.0));
        assert_eq!(median([f64::NAN]), None);
        assert_eq!(median([]), None);
    }

    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        let v = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(quantile(&v, 0.5), Some(2.5));
        assert_eq!(quantile(&v, 0.25), Some(1.75));
        assert_eq!(quantile(&v, 0.75), Some(3.25));
        assert_eq!(quantile(&v, 0.0), Some(1.0));
        assert_eq!(quantile(&v, 1.0), Some(4.0));
        assert_eq!(quantile(&[7.0], 0.25), Some(7.0));
        assert_eq!(quantile(&[], 0.5), None);
    }

    #[test]
    fn upper_median_is_a_value_of_the_sample() {
        assert_eq!(upper_median(&mut [3.0, 1.0, 2.0]), Some(2.0));
        // even count: the upper middle value, not the mean of the two (2.5)
        assert_eq!(upper_median(&mut [4.0, 1.0, 2.0, 3.0]), Some(3.0));
        assert_eq!(upper_median(&mut [0.025, 0.025, 0.026, 0.024]), Some(0.025));
        assert_eq!(upper_median(&mut []), None);
    }
}
