use super::*;

/// An upper-body trajectory of `n` samples: both arms raise and lower their shoulders
/// mirrored (pitch down, rolls out) and clap their elbows twice; the right arm `delay` samples
/// behind the left, holding its first posture meanwhile.
fn gesture(n: usize, delay: usize, right_moves: bool) -> Vec<Vec<f64>> {
    let left = |k: f64| -> [f64; 6] {
        let phase = (k / (n as f64 - 1.0)).clamp(0.0, 1.0);
        let envelope = (std::f64::consts::PI * phase).sin().powi(2);
        let clap = 0.3 * (4.0 * std::f64::consts::TAU * phase).sin() * envelope;
        [
            1.4 - 0.8 * envelope,
            0.3 - 0.4 * envelope,
            -1.2,
            -0.4 - 0.6 * envelope + clap,
            0.0,
            0.3,
        ]
    };
    (0..n)
        .map(|k| {
            let l = left(k as f64);
            let r = match right_moves {
                true => left(k as f64 - delay as f64),
                false => left(0.0),
            };
            let mut row = vec![0.01 * k as f64 / n as f64, 0.0];
            row.extend(l);
            row.extend(
                UPPER_BODY_MIRROR
                    .iter()
                    .enumerate()
                    .map(|(j, p)| p.2 * r[j]),
            );
            row
        })
        .collect()
}

#[test]
fn a_mirrored_motion_has_no_lag_and_a_delayed_arm_its_delay() {
    assert_eq!(arm_lag(&gesture(200, 0, true)), Some(0));
    assert_eq!(arm_lag(&gesture(200, 7, true)), Some(7));
    // the left arm later: a negative lag
    let mut swapped = gesture(200, 12, true);
    for row in &mut swapped {
        for &(l, r, sign) in &UPPER_BODY_MIRROR {
            let (a, b) = (row[l], row[r]);
            row[l] = sign * b;
            row[r] = sign * a;
        }
    }
    assert_eq!(arm_lag(&swapped), Some(-12));
}

#[test]
fn demonstrations_spread_admits_a_synchronous_reproduction_and_refuses_a_delayed_arm() {
    // the demonstrations: lags 0, 1 and 2 samples
    let demos: Vec<Vec<Vec<f64>>> = (0..3).map(|d| gesture(180 + 10 * d, d, true)).collect();
    let spread = LagSpread::of_demos(&demos).unwrap();
    assert_eq!(spread, LagSpread { min: 0, max: 2 });
    let reproduction = gesture(190, 1, true);
    assert!(spread.contains(arm_lag(&reproduction).unwrap()));
    // within one sample of the range still counts; the negative control, one arm delayed
    // by 20 samples (0.5 s at 40 Hz), does not
    assert!(spread.contains(3) && spread.contains(-1));
    let delayed = gesture(190, 20, true);
    let lag = arm_lag(&delayed).unwrap();
    assert_eq!(lag, 20);
    assert!(!spread.contains(lag));
}

#[test]
fn one_arm_still_is_not_a_two_arm_gesture_and_a_still_trajectory_has_no_lag() {
    assert!(both_arms_move(&gesture(100, 0, true)));
    assert!(both_arms_move(&gesture(100, 5, true)));
    assert!(!both_arms_move(&gesture(100, 0, false)));
    // arms that only wobble (a tenth of the motion, both alike) do not count
    let wobble: Vec<Vec<f64>> = (gesture(100, 0, true).iter())
        .map(|r| {
            (r.iter().enumerate())
                .map(|(j, v)| if j < 2 { *v } else { 0.1 * v })
                .collect()
        })
        .collect();
    assert!(!both_arms_move(&wobble));
    let still = vec![gesture(100, 0, true)[0].clone(); 50];
    assert!(!both_arms_move(&still));
    assert_eq!(arm_lag(&still), None);
}

#[test]
fn rows_that_are_not_upper_body_postures_have_no_lag() {
    let narrow: Vec<Vec<f64>> = (0..50).map(|k| vec![k as f64; 6]).collect();
    assert_eq!(arm_lag(&narrow), None);
    assert!(!both_arms_move(&narrow));
    let mut bad = gesture(100, 0, true);
    bad[10][3] = f64::NAN;
    assert_eq!(arm_lag(&bad), None);
    assert_eq!(arm_lag(&gesture(1, 0, true)), None);
    assert_eq!(LagSpread::of(&[]), None);
}
