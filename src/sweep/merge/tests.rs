use super::*;

#[test]
fn stats_median_mean_and_quartiles() {
    let s = Stats::of([4.0, 1.0, 3.0, 2.0, f64::NAN]).unwrap();
    assert_eq!(s.n, 4);
    assert_eq!((s.median, s.mean, s.q1, s.q3), (2.5, 2.5, 1.75, 3.25));
    assert!(Stats::of([f64::NAN]).is_none());
}
