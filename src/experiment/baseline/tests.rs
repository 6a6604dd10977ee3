use super::*;
use crate::curve::minimum_jerk;
use crate::gmr::{lead_in_ticks_at, Gmm};
use crate::sim::JOINT_NAMES;
use nalgebra::{DMatrix, DVector};

#[test]
fn lead_in_respects_the_peak_speed_and_the_minimum() {
    let lead_in_ticks =
        |from: &[f64], to: &[f64]| lead_in_ticks_at(from, to, 40.0, LEAD_IN_PEAK_SPEED);
    // tiny distance: the minimum duration, 0.1 s at 40 Hz = 4 ticks
    assert_eq!(lead_in_ticks(&[0.0], &[1e-6]), 4);
    // 1 rad at 1 rad/s peak: 1.875 s = 75 ticks
    assert_eq!(lead_in_ticks(&[0.0, 0.0], &[0.2, -1.0]), 75);
    // the samples' peak speed stays under the limit
    let s = minimum_jerk(&[0.0], &[1.0], 75);
    let peak = s
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]) * 40.0)
        .fold(0.0, f64::max);
    assert!(peak <= LEAD_IN_PEAK_SPEED + 1e-9, "{peak}");
}

fn line_model() -> GmrModel {
    // one component: q = 0.5 + 0.25 t on 6 joints, duration 2 s
    let d = 7;
    let mut cov = DMatrix::identity(d, d) * 0.01;
    cov[(0, 0)] = 1.0;
    cov[(0, 1)] = 0.25;
    cov[(1, 0)] = 0.25;
    cov[(1, 1)] = 0.0625 + 0.01;
    let mut mean = DVector::from_element(d, 0.5);
    mean[0] = 1.0;
    mean[1] = 0.75;
    let gmm = Gmm::new(vec![1.0], vec![mean], vec![cov]).unwrap();
    GmrModel::new(
        JOINT_NAMES.iter().map(|s| s.to_string()).collect(),
        2.0,
        gmm,
    )
    .unwrap()
}

#[test]
fn plan_starts_at_the_initial_posture_then_follows_gmr() {
    let m = line_model();
    let initial = vec![0.0; 6];
    let p = plan(&m, &initial, 40.0).unwrap();
    assert_eq!(p.postures[0], initial);
    assert_eq!(p.predictions.len(), 81);
    assert_eq!(p.postures.len(), p.lead_in + 81);
    // after the lead-in: GMR's mean, q0 = 0.5 + 0.25 t
    let at = &p.postures[p.lead_in + 40];
    assert!((at[0] - 0.75).abs() < 1e-9, "{at:?}");
    // the lead-in respects the peak speed
    for w in p.postures[..=p.lead_in].windows(2) {
        for (a, b) in w[0].iter().zip(&w[1]) {
            assert!((b - a).abs() * 40.0 <= LEAD_IN_PEAK_SPEED + 1e-9);
        }
    }
}

#[test]
fn plan_rejects_bad_initial_posture_and_rate() {
    let m = line_model();
    let e = plan(&m, &[0.0; 5], 40.0).unwrap_err();
    assert!(e.to_string().contains("LShoulderPitch"), "{e}");
    let e = plan(&m, &[f64::NAN; 6], 40.0).unwrap_err();
    assert!(e.to_string().contains("finite"), "{e}");
    let e = plan(&m, &[0.0; 6], 0.0).unwrap_err();
    assert!(e.to_string().contains("rate_hz"), "{e}");
}
