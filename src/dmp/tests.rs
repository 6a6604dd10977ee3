use super::*;

/// A gesture that swings out and comes back: (a sin πz² + offset, a (1 - cos 2πz)) over
/// `samples` rows, ending near where it starts.
fn swing(a: f64, offset: f64, samples: usize) -> Demonstration {
    let rows = (0..samples)
        .map(|t| {
            let z = t as f64 / (samples - 1) as f64;
            let p = std::f64::consts::PI * z;
            vec![a * (p * z).sin() + offset, a * (1.0 - (2.0 * p).cos())]
        })
        .collect();
    Demonstration {
        source: format!("swing {a}"),
        columns: vec!["x".into(), "y".into()],
        time: None,
        rows,
    }
}

fn max_error(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max)
}

#[test]
fn reproduces_its_one_demonstration_from_its_start_to_its_goal() {
    let demo = swing(1.0, 0.2, 120);
    let dmp = DmpSettings::default()
        .fit(std::slice::from_ref(&demo))
        .unwrap();
    assert_eq!(dmp.samples(), 120);
    let rep = dmp.reproduce(&demo.rows[0], None).unwrap();
    assert_eq!(rep[0], demo.rows[0]);
    let err = max_error(&rep, &demo.rows);
    assert!(err < 0.03, "max error {err} over a range of 2");
    // negative control: two basis functions cannot hold the swing
    let coarse = DmpSettings {
        basis: 2,
        ..DmpSettings::default()
    }
    .fit(std::slice::from_ref(&demo))
    .unwrap();
    let err = max_error(&coarse.reproduce(&demo.rows[0], None).unwrap(), &demo.rows);
    assert!(err > 0.1, "two basis functions reproduced it within {err}");
}

#[test]
fn a_moved_goal_is_approached_and_the_swing_kept() {
    let demos: Vec<_> = [(0.9, 0.0, 110), (1.0, 0.05, 120), (1.1, -0.05, 130)]
        .iter()
        .map(|&(a, o, n)| swing(a, o, n))
        .collect();
    let dmp = DmpSettings::default().fit(&demos).unwrap();
    assert_eq!(dmp.samples(), 120);
    let goal = vec![dmp.mean_goal()[0] + 0.5, dmp.mean_goal()[1] - 0.3];
    let rep = dmp.reproduce(&[0.1, 0.0], Some(&goal)).unwrap();
    assert_eq!(rep[0], vec![0.1, 0.0]);
    let end = rep.last().unwrap();
    for j in 0..2 {
        assert!(
            (end[j] - goal[j]).abs() < 0.05,
            "end {end:?}, goal {goal:?}"
        );
    }
    // the y swing (up to about 2 in the middle) is still there
    let peak = rep.iter().map(|r| r[1]).fold(f64::MIN, f64::max);
    assert!(peak > 1.6, "peak {peak}");
}

#[test]
fn bad_settings_demonstrations_and_postures_are_named() {
    let e = DmpSettings {
        basis: 1,
        ..DmpSettings::default()
    }
    .check()
    .unwrap_err();
    assert!(e.to_string().contains("`basis` = 1"), "{e}");
    let e = DmpSettings {
        overlap: 1.0,
        ..DmpSettings::default()
    }
    .check()
    .unwrap_err();
    assert!(e.to_string().contains("overlap"), "{e}");
    assert!(DmpSettings::default().fit(&[]).is_err());
    let mut short = swing(1.0, 0.0, 2);
    assert!(DmpSettings::default()
        .fit(std::slice::from_ref(&short))
        .unwrap_err()
        .to_string()
        .contains("swing 1: 2 sample(s)"));
    short = swing(1.0, 0.0, 50);
    short.rows[7][1] = f64::NAN;
    let e = DmpSettings::default().fit(&[short]).unwrap_err();
    assert!(e.to_string().contains("row 7"), "{e}");
    let dmp = DmpSettings::default().fit(&[swing(1.0, 0.0, 50)]).unwrap();
    let e = dmp.reproduce(&[0.0], None).unwrap_err();
    assert!(e.to_string().contains("start"), "{e}");
    let e = dmp
        .reproduce(&[0.0, 0.0], Some(&[0.0, f64::INFINITY]))
        .unwrap_err();
    assert!(e.to_string().contains("goal"), "{e}");
}

#[test]
fn the_stepper_is_the_reproduction_undisturbed_and_slows_its_phase_when_held() {
    use crate::condition::Conditions;
    use crate::stepper::Stepper;
    let demos: Vec<Demonstration> = [(1.0, 0.0, 100), (1.1, 0.05, 110)]
        .iter()
        .map(|&(a, o, n)| swing(a, o, n))
        .collect();
    let dmp = DmpSettings::default().fit(&demos).unwrap();
    let start = demos[0].rows[0].clone();
    let rows = dmp.reproduce(&start, None).unwrap();
    let mut s = DmpStepper::new(&dmp, &start, &Conditions::default(), None).unwrap();
    let mut arm = start.clone();
    for row in &rows[1..] {
        arm = s.step(&arm).unwrap();
        assert_eq!(&arm, row);
    }
    assert!(s.done());
    // held at the start: the phase advances far slower than the clock
    let mut s = DmpStepper::new(&dmp, &start, &Conditions::default(), None).unwrap();
    for _ in 0..30 {
        s.step(&start).unwrap();
    }
    let clock = 30.0 / (rows.len() - 1) as f64;
    assert!(s.phase() < 0.5 * clock, "{} {clock}", s.phase());
    let bad = DmpLoop {
        coupling: 2.0,
        phase_stop: 1.0,
    };
    let e = s.with_loop(bad).unwrap_err().to_string();
    assert!(e.contains("coupling is 2; allowed 0 to 1"), "{e}");
}
