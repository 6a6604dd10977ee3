//! Fidelity metrics on known cases, negative controls and bad inputs.

use crate::metrics::{
    fidelity, normalized_jerk, velocity_reversals, MetricsError, MetricsParams, Trajectory,
};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

const DT: f64 = 0.025;

/// A reading-watch-like 3-joint gesture at 40 Hz: idle, raise and return over `len`
/// samples (minimum-jerk bell), idle.
fn gesture(idle: usize, len: usize, idle_end: usize, amp: f64) -> Vec<Vec<f64>> {
    let rest = vec![1.5, 0.1, -0.4];
    let mut rows = vec![rest.clone(); idle];
    rows.extend((0..len).map(|i| {
        let s = (PI * i as f64 / (len - 1) as f64).sin().powi(2);
        vec![
            rest[0] - amp * s,
            rest[1] + 0.3 * amp * s,
            rest[2] - 0.5 * amp * s,
        ]
    }));
    rows.extend(vec![rest; idle_end]);
    rows
}

fn wrist_of(joints: &[Vec<f64>]) -> Vec<[f64; 3]> {
    // any smooth map from joints to a point, in metres
    joints
        .iter()
        .map(|q| {
            [
                0.1 * q[0].cos(),
                0.1 * q[0].sin() + 0.05 * q[1],
                0.05 * q[2],
            ]
        })
        .collect()
}

fn traj(joints: Vec<Vec<f64>>) -> Trajectory {
    Trajectory {
        wrist: Some(wrist_of(&joints)),
        joints,
    }
}

fn demos() -> Vec<Trajectory> {
    vec![
        traj(gesture(20, 120, 10, 1.2)),
        traj(gesture(5, 130, 30, 1.15)),
        traj(gesture(40, 110, 0, 1.25)),
    ]
}

#[test]
fn identical_trajectories_score_zero() {
    let d = traj(gesture(20, 120, 10, 1.2));
    let r = fidelity(std::slice::from_ref(&d), &d, &MetricsParams::default()).unwrap();
    assert_eq!(r.joint_dtw_rad_per_step.mean, 0.0);
    assert_eq!(r.wrist_dtw_mm.unwrap().worst, 0.0);
    assert_eq!(r.apex_error_rad.worst, 0.0);
    assert_eq!(r.final_error_rad.worst, 0.0);
    assert_eq!(r.duration_ratio.mean, 1.0);
    assert!(r.reproduction_moves);
    let a = r.per_demo[0].demo_active;
    assert!(
        a[0] >= 18 && a[0] <= 24 && a[1] >= 136 && a[1] <= 141,
        "{a:?}"
    );
}

#[test]
fn delayed_copy_scores_zero_after_trimming() {
    let d = traj(gesture(20, 120, 10, 1.2));
    let late = traj(gesture(70, 120, 10, 1.2));
    let r = fidelity(&[d], &late, &MetricsParams::default()).unwrap();
    assert!(r.joint_dtw_rad_per_step.worst < 1e-12);
    assert!((r.duration_ratio.mean - 1.0).abs() < 1e-12);
    assert_eq!(r.final_error_rad.worst, 0.0);
}

#[test]
fn shifted_copy_scores_its_offset() {
    let d = gesture(20, 120, 10, 1.2);
    let off = [0.03, -0.04, 0.0]; // norm 0.05 rad
    let shifted: Vec<Vec<f64>> = d
        .iter()
        .map(|q| q.iter().zip(off).map(|(a, b)| a + b).collect())
        .collect();
    let r = fidelity(
        &[Trajectory::from_joints(d)],
        &Trajectory::from_joints(shifted),
        &MetricsParams::default(),
    )
    .unwrap();
    assert!((r.final_error_rad.worst - 0.05).abs() < 1e-12);
    let j = r.joint_dtw_rad_per_step.mean;
    assert!(j > 0.02 && j <= 0.05 + 1e-12, "joint dtw {j}");
    assert!(r.apex_error_rad.worst <= 0.05 + 1e-12 && r.apex_error_rad.worst > 0.02);
    assert!(r.wrist_dtw_mm.is_none());
}

#[test]
fn slower_reproduction_shows_in_duration_ratio() {
    let r = fidelity(
        &[traj(gesture(20, 100, 10, 1.2))],
        &traj(gesture(20, 150, 10, 1.2)),
        &MetricsParams::default(),
    )
    .unwrap();
    let ratio = r.duration_ratio.mean;
    assert!((ratio - 1.5).abs() < 0.05, "ratio {ratio}");
}

#[test]
fn apex_error_measures_a_missed_key_pose() {
    // reaching only 70 % of the way misses the apex by 0.3 of its distance
    let d = gesture(10, 120, 10, 1.2);
    let short = gesture(10, 120, 10, 0.84);
    let r = fidelity(
        &[Trajectory::from_joints(d.clone())],
        &Trajectory::from_joints(short),
        &MetricsParams::default(),
    )
    .unwrap();
    let full = crate::dtw::euclidean(&d[0], &d[70]);
    let e = r.apex_error_rad.mean;
    assert!((e - 0.3 * full).abs() < 0.01, "{e} vs {}", 0.3 * full);
}

#[test]
fn oscillation_counts_reversals_and_deadband_hides_noise() {
    // 2 Hz sine for 2 s at 40 Hz: 8 extrema, 8 reversals
    let rows: Vec<Vec<f64>> = (0..=80)
        .map(|k| vec![0.3 * (2.0 * PI * 2.0 * k as f64 * DT).sin(), 0.0])
        .collect();
    assert_eq!(velocity_reversals(&rows, DT, 0.1), vec![8, 0]);
    // the same at 1 mrad amplitude (peak speed 0.0126 rad/s) is inside the deadband
    let tiny: Vec<Vec<f64>> = rows.iter().map(|r| vec![r[0] / 300.0, 0.0]).collect();
    assert_eq!(velocity_reversals(&tiny, DT, 0.1), vec![0, 0]);
}

#[test]
fn start_up_oscillation_shows_in_the_report() {
    let clean = gesture(10, 120, 10, 1.2);
    let mut wobbly = clean.clone();
    for (k, q) in wobbly.iter_mut().enumerate().skip(10).take(20) {
        q[0] += 0.04 * if k % 2 == 0 { 1.0 } else { -1.0 };
    }
    let p = MetricsParams::default();
    let d = [Trajectory::from_joints(clean.clone())];
    let a = fidelity(&d, &Trajectory::from_joints(clean), &p).unwrap();
    let b = fidelity(&d, &Trajectory::from_joints(wobbly), &p).unwrap();
    assert_eq!(a.reproduction_smoothness.reversals, vec![1, 1, 1]);
    assert!(b.reproduction_smoothness.reversals[0] >= 15);
    assert_eq!(b.reproduction_smoothness.reversals[1], 1);
    let (ja, jb) = (
        a.reproduction_smoothness.normalized_jerk.unwrap(),
        b.reproduction_smoothness.normalized_jerk.unwrap(),
    );
    assert!(jb > 5.0 * ja, "{jb} vs {ja}");
}

#[test]
fn minimum_jerk_motion_has_normalized_jerk_sqrt_360() {
    for (n, amp) in [(400, 1.0), (600, 0.2)] {
        let rows: Vec<Vec<f64>> = (0..n)
            .map(|k| {
                let s = k as f64 / (n - 1) as f64;
                vec![amp * (10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5))]
            })
            .collect();
        let nj = normalized_jerk(&rows, DT).unwrap();
        assert!((nj - 360f64.sqrt()).abs() / 360f64.sqrt() < 0.02, "{nj}");
    }
    assert_eq!(normalized_jerk(&vec![vec![0.0]; 10], DT), None);
    assert_eq!(normalized_jerk(&[vec![0.0], vec![1.0]], DT), None);
}

#[test]
fn shuffled_reproduction_scores_much_worse_negative_control() {
    let ds = demos();
    let good = traj(gesture(15, 125, 15, 1.18));
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut shuffled_joints = good.joints.clone();
    shuffled_joints[15..140].shuffle(&mut rng);
    let bad = traj(shuffled_joints);
    let p = MetricsParams::default();
    let g = fidelity(&ds, &good, &p).unwrap();
    let b = fidelity(&ds, &bad, &p).unwrap();
    assert!(
        b.joint_dtw_rad_per_step.mean > 3.0 * g.joint_dtw_rad_per_step.mean + 0.01,
        "{:?} vs {:?}",
        b.joint_dtw_rad_per_step,
        g.joint_dtw_rad_per_step
    );
    assert!(b.wrist_dtw_mm.unwrap().mean > 3.0 * g.wrist_dtw_mm.unwrap().mean);
    assert!(
        b.reproduction_smoothness.total_reversals > 10 * g.reproduction_smoothness.total_reversals
    );
    assert!(
        b.reproduction_smoothness.normalized_jerk.unwrap()
            > 10.0 * g.reproduction_smoothness.normalized_jerk.unwrap()
    );
    // and the good one is genuinely close
    assert!(g.joint_dtw_rad_per_step.worst < 0.05);
    assert!(g.apex_error_rad.worst < 0.1);
}

#[test]
fn worst_is_the_largest_error_and_the_most_distorted_ratio() {
    let ds = demos();
    let r = fidelity(&ds, &ds[0], &MetricsParams::default()).unwrap();
    let finals: Vec<f64> = r.per_demo.iter().map(|s| s.final_error_rad).collect();
    assert_eq!(
        r.final_error_rad.worst,
        finals.iter().cloned().fold(0.0, f64::max)
    );
    let ratios: Vec<f64> = r.per_demo.iter().map(|s| s.duration_ratio).collect();
    let far = ratios
        .iter()
        .cloned()
        .max_by(|a, b| a.ln().abs().total_cmp(&b.ln().abs()))
        .unwrap();
    assert_eq!(r.duration_ratio.worst, far);
    assert_eq!(r.per_demo[0].joint_dtw_rad_per_step, 0.0);
    assert!(r.per_demo[1].joint_dtw_rad_per_step > 0.0);
    assert_eq!(r.demo_smoothness.len(), 3);
}

#[test]
fn motionless_reproduction_is_scored_not_refused() {
    let still = traj(vec![vec![1.5, 0.1, -0.4]; 100]);
    let r = fidelity(&demos(), &still, &MetricsParams::default()).unwrap();
    assert!(!r.reproduction_moves);
    assert_eq!(r.duration_ratio.mean, 0.0);
    assert!(r.apex_error_rad.mean > 1.0);
    assert_eq!(r.reproduction_smoothness.normalized_jerk, None);
}

#[test]
fn report_serialises_to_json() {
    let ds = demos();
    let r = fidelity(&ds, &ds[1], &MetricsParams::default()).unwrap();
    let v = serde_json::to_value(&r).unwrap();
    for key in [
        "per_demo",
        "joint_dtw_rad_per_step",
        "wrist_dtw_mm",
        "apex_error_rad",
        "final_error_rad",
        "duration_ratio",
        "reproduction_smoothness",
        "settings",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert!(v["joint_dtw_rad_per_step"]["mean"].is_number());
    assert_eq!(v["per_demo"].as_array().unwrap().len(), 3);
}

#[test]
fn bad_inputs_are_clear_errors() {
    let p = MetricsParams::default();
    let ds = demos();
    let good = ds[0].clone();
    assert_eq!(
        fidelity(&[], &good, &p),
        Err(MetricsError::NoDemonstrations)
    );
    let empty = Trajectory::from_joints(vec![]);
    assert!(matches!(
        fidelity(&ds, &empty, &p),
        Err(MetricsError::Empty { .. })
    ));
    let mut narrow = ds.clone();
    narrow[2].joints[7].pop();
    match fidelity(&narrow, &good, &p) {
        Err(e @ MetricsError::Width { .. }) => {
            assert!(e.to_string().contains("demonstration 2, sample 7"), "{e}")
        }
        other => panic!("unexpected {other:?}"),
    }
    let mut nan = good.clone();
    nan.joints[3][1] = f64::NAN;
    assert!(matches!(
        fidelity(&ds, &nan, &p),
        Err(MetricsError::NotFinite { sample: 3, .. })
    ));
    let mut wrist = good.clone();
    wrist.wrist.as_mut().unwrap().pop();
    assert!(matches!(
        fidelity(&ds, &wrist, &p),
        Err(MetricsError::WristLength { .. })
    ));
    let still = traj(vec![vec![1.5, 0.1, -0.4]; 50]);
    assert!(matches!(
        fidelity(&[still], &good, &p),
        Err(MetricsError::NoMotion { .. })
    ));
    for bad in [
        MetricsParams {
            sample_period: 0.0,
            ..p
        },
        MetricsParams {
            reversal_deadband: -1.0,
            ..p
        },
        MetricsParams {
            band: crate::dtw::Band::Fraction(2.0),
            ..p
        },
    ] {
        assert!(matches!(
            fidelity(&ds, &good, &bad),
            Err(MetricsError::InvalidParam { .. })
        ));
    }
}

#[test]
fn demonstrations_convert_to_trajectories() {
    let d = crate::demos::Demonstration {
        source: "d".into(),
        columns: vec!["a".into(), "b".into(), "c".into()],
        time: None,
        rows: gesture(5, 60, 5, 1.0),
    };
    let t = Trajectory::from(&d);
    assert_eq!(t.joints, d.rows);
    assert!(t.wrist.is_none());
    let r = fidelity(std::slice::from_ref(&t), &t, &MetricsParams::default()).unwrap();
    assert_eq!(r.joint_dtw_rad_per_step.worst, 0.0);
}
