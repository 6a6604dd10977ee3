use super::*;

#[test]
fn profiles_start_at_zero_end_at_one_and_peak_as_stated() {
    for i in [Interpolation::Linear, Interpolation::MinimumJerk] {
        assert_eq!(i.profile(0.0).0, 0.0);
        assert!((i.profile(1.0).0 - 1.0).abs() < 1e-12);
        let peak = (0..=1000)
            .map(|k| i.profile(k as f64 / 1000.0).1)
            .fold(0.0, f64::max);
        assert!(
            (peak - i.peak_velocity_factor()).abs() < 1e-6,
            "{i:?} {peak}"
        );
        // the derivative is the derivative
        let (a, _) = i.profile(0.3);
        let (b, _) = i.profile(0.3 + 1e-6);
        assert!(((b - a) / 1e-6 - i.profile(0.3).1).abs() < 1e-4);
    }
}
