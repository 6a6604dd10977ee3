use super::*;

fn demo(t: Vec<f64>, y: Vec<f64>) -> Demonstration {
    Demonstration {
        source: "mem".into(),
        columns: vec!["q".into()],
        time: Some(t),
        rows: y.into_iter().map(|v| vec![v]).collect(),
    }
}

#[test]
fn reproduces_a_smooth_curve_and_keeps_monotone_data_monotone() {
    // a sine sampled at 250 Hz, resampled to 40 Hz: within 1e-5 of the sine
    let t: Vec<f64> = (0..1000).map(|i| i as f64 / 250.0).collect();
    let y: Vec<f64> = t.iter().map(|x| x.sin()).collect();
    let r = resample(&demo(t, y), 40.0).unwrap();
    assert_eq!(r.len(), (3.996f64 * 40.0).floor() as usize + 1);
    for (ti, yi) in r.time.as_ref().unwrap().iter().zip(&r.rows) {
        assert!((yi[0] - ti.sin()).abs() < 1e-5, "{ti}");
    }
    // a step: monotone data stays monotone and within its range (a natural cubic
    // spline would overshoot; the control below shows the data invite it)
    let t = vec![0.0, 1.0, 2.0, 3.0, 4.0];
    let y = vec![0.0, 0.0, 1.0, 1.0, 1.0];
    let r = resample(&demo(t, y), 10.0).unwrap();
    let v: Vec<f64> = r.rows.iter().map(|x| x[0]).collect();
    assert!(v.windows(2).all(|w| w[1] >= w[0] - 1e-15));
    assert!(v.iter().all(|x| (0.0..=1.0).contains(x)));
}

#[test]
fn refuses_a_demonstration_without_time_and_a_bad_rate() {
    let mut d = demo(vec![0.0, 1.0], vec![0.0, 1.0]);
    assert!(matches!(
        resample(&d, 0.0),
        Err(DemoError::ResampleRate { .. })
    ));
    d.time = None;
    let e = resample(&d, 40.0).unwrap_err().to_string();
    assert!(e.contains("mem") && e.contains("time"), "{e}");
}
