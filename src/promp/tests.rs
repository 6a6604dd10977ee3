use super::*;

/// A demonstration of `samples` rows: (a sin 2πz + offset, a cos 2πz).
fn sine(a: f64, offset: f64, samples: usize) -> Demonstration {
    let rows = (0..samples)
        .map(|t| {
            let z = t as f64 / (samples - 1) as f64;
            let p = 2.0 * std::f64::consts::PI * z;
            vec![a * p.sin() + offset, a * p.cos()]
        })
        .collect();
    Demonstration {
        source: format!("sine {a}"),
        columns: vec!["x".into(), "y".into()],
        time: None,
        rows,
    }
}

fn family() -> Vec<Demonstration> {
    [
        (0.9, 0.0, 96),
        (1.0, 0.05, 100),
        (1.1, -0.05, 104),
        (1.05, 0.02, 100),
    ]
    .iter()
    .map(|&(a, o, n)| sine(a, o, n))
    .collect()
}

fn max_error(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn basis_functions_add_up_to_one_and_peak_in_order() {
    for z in [0.0, 0.3, 1.0] {
        let row = basis_row(z, 7);
        assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }
    let peak = |z| {
        let row = basis_row(z, 7);
        (0..7).max_by(|&i, &j| row[i].total_cmp(&row[j])).unwrap()
    };
    assert_eq!(peak(0.0), 0);
    assert_eq!(peak(1.0), 6);
}

#[test]
fn reproduces_a_held_out_member_of_a_sine_family_closely_and_not_another_family() {
    let held = sine(0.95, 0.03, 100);
    let model = PrompSettings::default().fit(&family()).unwrap();
    assert_eq!(model.samples(), 100);
    let rep = model.reproduce(&held.rows[0]).unwrap();
    let err = max_error(&rep, &held.rows);
    assert!(err < 0.06, "max error {err}");
    // negative control: a family of opposite phase, conditioned on the same start, is far
    let other: Vec<Demonstration> = family()
        .iter()
        .map(|d| Demonstration {
            rows: d.rows.iter().map(|r| vec![-r[0], r[1]]).collect(),
            ..d.clone()
        })
        .collect();
    let wrong = PrompSettings::default().fit(&other).unwrap();
    let err = max_error(&wrong.reproduce(&held.rows[0]).unwrap(), &held.rows);
    assert!(err > 1.0, "max error of the other family {err}");
}

#[test]
fn conditioning_moves_the_start_to_the_given_posture_and_the_mean_does_not() {
    let model = PrompSettings::default().fit(&family()).unwrap();
    let mean = model.mean_trajectory();
    let initial = vec![mean[0][0] + 0.4, mean[0][1] - 0.3];
    let rep = model.reproduce(&initial).unwrap();
    let start = max_error(&rep[..1], std::slice::from_ref(&initial));
    assert!(start < 1e-3, "start off by {start}");
    let unconditioned = max_error(&mean[..1], std::slice::from_ref(&initial));
    assert!(unconditioned > 0.29, "the mean starts {unconditioned} away");
}

#[test]
fn fitting_and_reproducing_are_deterministic() {
    let a = PrompSettings::default().fit(&family()).unwrap();
    let b = PrompSettings::default().fit(&family()).unwrap();
    let x0 = [0.1, 0.9];
    assert_eq!(a.reproduce(&x0).unwrap(), b.reproduce(&x0).unwrap());
}

#[test]
fn bad_settings_name_the_field_and_the_range() {
    let s = PrompSettings::default();
    for (bad, field) in [
        (PrompSettings { basis: 1, ..s }, "basis"),
        (PrompSettings { basis: 101, ..s }, "basis"),
        (PrompSettings { ridge: 0.0, ..s }, "ridge"),
        (
            PrompSettings {
                regulariser: f64::NAN,
                ..s
            },
            "regulariser",
        ),
        (
            PrompSettings {
                observation_noise: -1.0,
                ..s
            },
            "observation_noise",
        ),
    ] {
        let e = bad.check().unwrap_err().to_string();
        assert!(
            e.contains(&format!("`{field}`")) && e.contains("allowed"),
            "{e}"
        );
        assert!(bad.fit(&family()).is_err());
    }
}

#[test]
fn bad_demonstrations_give_named_errors() {
    let fit = |d: Vec<Demonstration>| PrompSettings::default().fit(&d).unwrap_err();
    assert!(matches!(
        fit(vec![]),
        PrompError::TooFewDemonstrations { found: 0 }
    ));
    assert!(matches!(
        fit(vec![sine(1.0, 0.0, 50)]),
        PrompError::TooFewDemonstrations { found: 1 }
    ));
    let mut short = sine(1.0, 0.0, 50);
    short.rows.truncate(1);
    let e = fit(vec![sine(1.0, 0.0, 50), short]);
    assert!(matches!(e, PrompError::TooShort { len: 1, .. }), "{e}");
    let mut narrow = sine(1.0, 0.0, 50);
    narrow.rows[3].pop();
    let e = fit(vec![sine(1.0, 0.0, 50), narrow]);
    assert!(
        matches!(
            e,
            PrompError::Width {
                row: 3,
                found: 1,
                expected: 2,
                ..
            }
        ),
        "{e}"
    );
    let mut nan = sine(1.0, 0.0, 50);
    nan.rows[4][1] = f64::INFINITY;
    let e = fit(vec![sine(1.0, 0.0, 50), nan]);
    assert!(
        matches!(
            e,
            PrompError::NonFinite {
                row: 4,
                column: 1,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("sine 1"), "{e}");
    // 300 variables x 20 basis functions: refused before any covariance is allocated; at the
    // bound it fits
    let wide = |cols: usize| Demonstration {
        source: format!("wide {cols}"),
        columns: (0..cols).map(|c| format!("x{c}")).collect(),
        time: None,
        rows: (0..10).map(|i| vec![i as f64; cols]).collect(),
    };
    let e = fit(vec![wide(300), wide(300)]);
    assert!(
        matches!(
            e,
            PrompError::TooManyWeights {
                weights: 6000,
                max: MAX_WEIGHTS,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("6000 weights"), "{e}");
    assert!(PrompSettings::default().fit(&[wide(2), wide(2)]).is_ok());
    let model = PrompSettings::default().fit(&family()).unwrap();
    for bad in [vec![0.0], vec![0.0, f64::NAN], vec![0.0; 3]] {
        assert!(matches!(
            model.reproduce(&bad),
            Err(PrompError::BadInitial { .. })
        ));
    }
}

#[test]
fn the_stepper_re_conditions_on_the_posture_read_at_its_phase() {
    let demos = family();
    let p = PrompSettings::default().fit(&demos).unwrap();
    let start = demos[0].rows[0].clone();
    // conditioned from the start, the mean from sample 0 is `conditioned`'s
    let (rows, _) = p.conditioned(&start, &[]).unwrap();
    let from = p.conditioned_from(&[(0.0, &start)], 0).unwrap();
    assert!(max_error(&rows, &from) < 1e-9);
    // the stepper: undisturbed its plan; a reading off the plan at mid-way re-conditions it
    use crate::condition::Conditions;
    use crate::stepper::Stepper;
    let mut s = PrompStepper::new(&p, &start, &Conditions::default(), None).unwrap();
    let mut arm = start.clone();
    for row in &rows[1..rows.len() / 2] {
        arm = s.step(&arm).unwrap();
        assert_eq!(&arm, row);
    }
    let pushed: Vec<f64> = arm.iter().map(|v| v + 0.2).collect();
    let next = s.step(&pushed).unwrap();
    assert_eq!(s.replans(), 1);
    // the next command is a step from the posture read, not from the plan
    let step = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    };
    assert!(step(&next, &pushed) < 0.1, "{next:?} {pushed:?}");
}
