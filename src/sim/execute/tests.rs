use super::*;
use crate::sim::JOINT_SPECS;

#[test]
fn min_jerk_keeps_length_endpoints_and_extremes_and_removes_jitter() {
    // a ramp up, a hold with +-5 mrad jitter, a ramp down
    let mut p: Vec<Vec<f64>> = Vec::new();
    for k in 0..40 {
        p.push(vec![k as f64 / 40.0]);
    }
    for k in 0..40 {
        p.push(vec![1.0 + if k % 2 == 0 { 0.005 } else { -0.005 }]);
    }
    for k in 0..41 {
        p.push(vec![1.0 - k as f64 / 40.0]);
    }
    let s = Transition::MinimumJerk { tolerance: 0.02 }.shape(&p);
    assert_eq!(s.len(), p.len());
    assert_eq!(s[0], p[0]);
    assert_eq!(s.last(), p.last());
    let max = s.iter().map(|r| r[0]).fold(f64::MIN, f64::max);
    assert!((max - 1.0).abs() < 0.02, "apex {max}");
    // jitter gone: no sign change of the step difference inside the hold
    let d: Vec<f64> = s[45..75].windows(2).map(|w| w[1][0] - w[0][0]).collect();
    let flips = d.windows(2).filter(|w| w[0] * w[1] < -1e-12).count();
    assert_eq!(flips, 0, "{d:?}");
    // linear is the identity
    assert_eq!(Transition::Linear.shape(&p), p);
}

#[test]
fn transition_parse_accepts_the_documented_forms_only() {
    assert_eq!(Transition::parse("linear").unwrap(), Transition::Linear);
    assert_eq!(
        Transition::parse("min-jerk").unwrap(),
        Transition::MinimumJerk { tolerance: 0.02 }
    );
    assert_eq!(
        Transition::parse("min-jerk:0.05").unwrap(),
        Transition::MinimumJerk { tolerance: 0.05 }
    );
    for bad in [
        "",
        "cubic",
        "min-jerk:0",
        "min-jerk:x",
        "min-jerk:-1",
        "linear:1",
    ] {
        let e = Transition::parse(bad).unwrap_err().to_string();
        assert!(e.contains("allowed"), "{bad}: {e}");
    }
}

#[test]
fn clamp_counts_values_outside_and_rejects_nan() {
    let ok = vec![1.4, 0.3, -1.39, -1.01, 0.0, 0.25];
    let mut bad = ok.clone();
    bad[1] = 2.0;
    let (out, n) = clamp_to_ranges(&[ok.clone(), bad]).unwrap();
    assert_eq!(n, 1);
    assert_eq!(out[1][1], JOINT_SPECS[1].range.1);
    let mut nan = ok;
    nan[0] = f64::NAN;
    assert!(clamp_to_ranges(&[nan]).is_err());
}
