use super::*;

// ---------- minimum jerk ----------

#[test]
fn minimum_jerk_goes_from_0_to_1_at_rest_and_without_acceleration_at_both_ends() {
    assert_eq!(minimum_jerk_at(0.0), 0.0);
    assert_eq!(minimum_jerk_at(1.0), 1.0);
    // clamped outside [0, 1]
    assert_eq!((minimum_jerk_at(-0.5), minimum_jerk_at(1.5)), (0.0, 1.0));
    // symmetric about the middle
    assert!((minimum_jerk_at(0.5) - 0.5).abs() < 1e-15);
    assert_eq!(minimum_jerk_velocity(0.0), 0.0);
    assert_eq!(minimum_jerk_velocity(1.0), 0.0);
    // the acceleration (the velocity's slope) is 0 at both ends: the velocity grows
    // quadratically there; a parabola's (the control) grows linearly
    let e = 1e-4;
    for (end, inward) in [(0.0, e), (1.0, 1.0 - e)] {
        let a = (minimum_jerk_velocity(inward) - minimum_jerk_velocity(end)) / e;
        assert!(a.abs() < 1e-2, "acceleration {a} at {end}");
    }
    let ramp = |s: f64| s * (1.0 - s);
    assert!(((ramp(e) - ramp(0.0)) / e).abs() > 0.9, "the control");
}

#[test]
fn minimum_jerk_velocity_is_the_profile_s_slope_and_peaks_as_stated() {
    for k in 1..100 {
        let s = k as f64 / 100.0;
        let e = 1e-6;
        let slope = (minimum_jerk_at(s + e) - minimum_jerk_at(s - e)) / (2.0 * e);
        assert!((slope - minimum_jerk_velocity(s)).abs() < 1e-6, "{s}");
    }
    let peak = (0..=1000)
        .map(|k| minimum_jerk_velocity(k as f64 / 1000.0))
        .fold(0.0, f64::max);
    assert_eq!(peak, MINIMUM_JERK_PEAK);
}

#[test]
fn minimum_jerk_samples_start_at_from_and_approach_to_monotonically() {
    let s = minimum_jerk(&[0.0, 1.0], &[1.0, 1.0], 10);
    assert_eq!(s.len(), 10);
    assert_eq!(s[0], vec![0.0, 1.0]);
    for w in s.windows(2) {
        assert!(w[1][0] > w[0][0]);
        assert_eq!(w[1][1], 1.0);
    }
    // symmetric about the middle: h(1/2) = 1/2
    assert!((s[5][0] - 0.5).abs() < 1e-12);
    assert!(minimum_jerk(&[0.0], &[1.0], 0).is_empty());
}

// ---------- PCHIP ----------

#[test]
fn pchip_is_exact_at_its_knots() {
    let x: Vec<f64> = (0..40)
        .map(|i| i as f64 * 0.1 + 0.01 * (i % 3) as f64)
        .collect();
    let y: Vec<f64> = x.iter().map(|t| t.sin()).collect();
    assert_eq!(pchip(&x, &y, &x), y);
    assert_eq!(pchip(&[2.0], &[7.0], &[2.0, 2.0]), vec![7.0, 7.0]);
}

#[test]
fn pchip_keeps_monotone_data_monotone_and_holds_held() {
    // a step: a natural cubic spline through it overshoots (the slopes a plain three-point
    // difference gives, the control below, leave the range)
    let x = [0.0, 1.0, 2.0, 3.0, 4.0];
    let y = [0.0, 0.0, 1.0, 1.0, 1.0];
    let at: Vec<f64> = (0..=40).map(|i| i as f64 / 10.0).collect();
    for ends in [PchipEnds::ThreePoint, PchipEnds::AtRest] {
        let d = pchip_slopes(&x, &y, ends);
        // the holds' knots have no slope
        assert_eq!((d[1], d[3]), (0.0, 0.0), "{ends:?}");
        let v: Vec<f64> = at
            .iter()
            .map(|&t| hermite(&x, &y, &d, (t as usize).min(3), t))
            .collect();
        assert!(v.windows(2).all(|w| w[1] >= w[0]), "{ends:?}");
        assert!(v.iter().all(|x| (0.0..=1.0).contains(x)), "{ends:?}");
    }
    let central = [0.0, 0.5, 0.5, 0.0, 0.0];
    let overshoot = at
        .iter()
        .map(|&t| hermite(&x, &y, &central, (t as usize).min(3), t))
        .any(|v| !(0.0..=1.0).contains(&v));
    assert!(overshoot, "the control stays in range");
}

#[test]
fn pchip_ends_are_three_point_or_at_rest() {
    let x = [0.0, 1.0, 2.0, 3.0];
    let y = [0.0, 1.0, 2.0, 3.0];
    assert_eq!(pchip_slopes(&x, &y, PchipEnds::ThreePoint), vec![1.0; 4]);
    assert_eq!(
        pchip_slopes(&x, &y, PchipEnds::AtRest),
        vec![0.0, 1.0, 1.0, 0.0]
    );
    // two knots: the secant, or at rest
    assert_eq!(
        pchip_slopes(&[0.0, 2.0], &[1.0, 2.0], PchipEnds::ThreePoint),
        vec![0.5; 2]
    );
    assert_eq!(
        pchip_slopes(&[0.0, 2.0], &[1.0, 2.0], PchipEnds::AtRest),
        vec![0.0; 2]
    );
}

// ---------- reading between rows ----------

#[test]
fn reads_rows_at_their_phases_and_between_them_linearly() {
    let rows = vec![vec![0.0], vec![1.0], vec![3.0]];
    assert_eq!(at_phase(&rows, 0.0), rows[0]);
    assert_eq!(at_phase(&rows, 1.0), rows[2]);
    assert_eq!(at_phase(&rows, 0.5), vec![1.0]);
    assert_eq!(at_phase(&rows, 0.75), vec![2.0]);
    // clamped outside [0, 1]; one row is every phase's
    assert_eq!(at_phase(&rows, 1.5), rows[2]);
    assert_eq!(at_phase(&[vec![4.0]], 0.3), vec![4.0]);
    assert_eq!(split_phase(3, 0.75), (1, 0.5));
    assert_eq!(split_row(3, 2.0), (1, 1.0));
}

#[test]
fn resample_is_exact_on_lines_and_keeps_ends() {
    let seq: Vec<Vec<f64>> = (0..7).map(|i| vec![i as f64, 2.0 * i as f64]).collect();
    let r = resample_linear(&seq, 13);
    assert_eq!(r.len(), 13);
    for (k, p) in r.iter().enumerate() {
        assert!((p[0] - k as f64 * 0.5).abs() < 1e-12);
        assert!((p[1] - k as f64).abs() < 1e-12);
    }
    assert_eq!(
        resample_linear(&seq, 2),
        vec![seq[0].clone(), seq[6].clone()]
    );
    assert_eq!(resample_linear(&seq[..1], 3), vec![seq[0].clone(); 3]);
    assert!(resample_linear(&seq, 0).is_empty());
    assert!(resample_linear::<Vec<f64>>(&[], 4).is_empty());
}
