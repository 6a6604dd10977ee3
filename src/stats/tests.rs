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
