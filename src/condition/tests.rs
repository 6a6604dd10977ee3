use super::*;

/// 201 rows of (a swing out and back, a rise, a hold, a fall).
fn gesture() -> Vec<Vec<f64>> {
    (0..201)
        .map(|i| {
            let z = i as f64 / 200.0;
            let hold = if z < 0.3 {
                minimum_jerk_at(z / 0.3)
            } else if z < 0.6 {
                1.0
            } else {
                1.0 - minimum_jerk_at((z - 0.6) / 0.4)
            };
            vec![(2.0 * std::f64::consts::PI * z).sin(), hold]
        })
        .collect()
}

fn third_difference(rows: &[Vec<f64>], d: usize) -> f64 {
    rows.windows(4)
        .map(|w| (w[3][d] - 3.0 * w[2][d] + 3.0 * w[1][d] - w[0][d]).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_bent_trajectory_meets_its_goal_and_via_points_and_keeps_its_shape() {
    let original = gesture();
    let points = vec![
        (0.37, vec![0.65, 1.08]),
        (0.8133, vec![-0.85, 0.4]),
        (1.0, vec![0.1, 0.05]),
    ];
    let mut rows = original.clone();
    // negative control: the trajectory as it is misses them
    assert!(points
        .iter()
        .any(|(p, v)| (at_phase(&rows, *p)[0] - v[0]).abs() > 1e-3));
    bend(&mut rows, &points);
    assert_eq!(rows[0], original[0]);
    for (p, v) in &points {
        let got = at_phase(&rows, *p);
        for d in 0..2 {
            assert!((got[d] - v[d]).abs() < 1e-9, "phase {p}: {got:?} vs {v:?}");
        }
    }
    // the hold (0.3..0.6 of variable 1) stays nearly flat: it moves far less than the offsets
    let hold: Vec<f64> = rows[66..114].iter().map(|r| r[1]).collect();
    let spread = hold.iter().cloned().fold(f64::MIN, f64::max)
        - hold.iter().cloned().fold(f64::MAX, f64::min);
    assert!(spread < 0.015, "the hold spreads over {spread}");
    // its largest jerk grows by less than the offsets' share of its swing would allow twice
    for d in 0..2 {
        let (before, after) = (third_difference(&original, d), third_difference(&rows, d));
        assert!(
            after < 2.5 * before,
            "variable {d}: jerk {before} -> {after}"
        );
    }
}

#[test]
fn a_via_point_alone_fades_out_by_the_end() {
    let original = gesture();
    let mut rows = original.clone();
    bend(&mut rows, &[(0.5, vec![0.3, 1.2])]);
    assert!((at_phase(&rows, 0.5)[1] - 1.2).abs() < 1e-9);
    assert_eq!(rows.last(), original.last());
}

#[test]
fn conditions_are_checked_and_named() {
    let columns = vec!["a".to_string(), "b".to_string()];
    let initial = [0.0, 0.0];
    let check = |c: &Conditions| c.check(&columns, Some(&[(-1.0, 1.0), (-2.0, 2.0)]), &initial);
    let goal = |g: Vec<f64>| Conditions {
        goal: Some(g),
        via: vec![],
    };
    let via = |phase, posture: Vec<f64>| ViaPoint { phase, posture };
    assert!(check(&goal(vec![0.5, 0.5])).is_ok());
    let e = check(&goal(vec![0.5])).unwrap_err().to_string();
    assert!(
        e.contains("the goal has 1 values; the model has 2 variables (a, b)"),
        "{e}"
    );
    let e = check(&goal(vec![1.5, 0.0])).unwrap_err().to_string();
    assert!(e.contains("a = 1.5 is outside its range [-1, 1]"), "{e}");
    let e = check(&goal(vec![0.0, f64::NAN])).unwrap_err().to_string();
    assert!(e.contains("b is NaN"), "{e}");
    let c = Conditions {
        goal: None,
        via: vec![via(1.2, vec![0.0, 0.0])],
    };
    assert!(check(&c).unwrap_err().to_string().contains("phase is 1.2"));
    let c = Conditions {
        goal: None,
        via: vec![via(0.5, vec![0.0, 0.0]), via(0.5, vec![0.1, 0.0])],
    };
    assert!(matches!(check(&c), Err(ConditionError::Conflict { .. })));
    let c = Conditions {
        goal: Some(vec![0.2, 0.0]),
        via: vec![via(1.0, vec![0.1, 0.0])],
    };
    assert!(check(&c).unwrap_err().to_string().contains("the goal"));
    let c = Conditions {
        goal: None,
        via: vec![via(0.0, vec![0.1, 0.0])],
    };
    assert!(check(&c)
        .unwrap_err()
        .to_string()
        .contains("the initial posture"));
    // the same posture twice at one phase is one condition
    let c = Conditions {
        goal: Some(vec![0.1, 0.0]),
        via: vec![via(1.0, vec![0.1, 0.0]), via(0.0, vec![0.0, 0.0])],
    };
    assert!(check(&c).is_ok());
    assert_eq!(c.points(), vec![(1.0, vec![0.1, 0.0])]);
}

#[test]
fn via_points_and_goals_parse_or_say_what_is_wrong() {
    assert_eq!(
        "0.5:1,2.5".parse::<ViaPoint>().unwrap(),
        ViaPoint {
            phase: 0.5,
            posture: vec![1.0, 2.5]
        }
    );
    assert_eq!(
        "-0.2, 0.3".parse::<PostureArg>().unwrap(),
        PostureArg(vec![-0.2, 0.3])
    );
    for (bad, says) in [
        ("0.5", "need PHASE:V1,V2,..."),
        ("x:1,2", "the phase before ':'"),
        ("0.5:1,y", "value 2 is 'y'"),
    ] {
        let e = bad.parse::<ViaPoint>().unwrap_err();
        assert!(e.contains(says), "{e}");
    }
    for (bad, says) in [("1,inf", "value 2 is 'inf'"), ("", "value 1 is ''")] {
        let e = bad.parse::<PostureArg>().unwrap_err();
        assert!(e.contains(says), "{e}");
    }
}

#[test]
fn meeting_a_point_near_a_limit_stays_inside_the_range_where_a_plain_bend_leaves_it() {
    // the hold rises to 1.0, the range's upper limit; a via-point asking the rise to be
    // nearly there already pulls the hold that follows it up by the bend's blend
    let rows = gesture();
    let rising = at_phase(&rows, 0.2);
    assert!(rising[1] < 0.95, "{rising:?}");
    let points = vec![(0.2, vec![rising[0], 0.999]), (1.0, vec![0.05, 0.05])];
    let ranges = [(-1.5, 1.5), (0.0, 1.0)];
    let plain = meet(&rows, &points, None).unwrap();
    let ranged = meet(&rows, &points, Some(&ranges)).unwrap();
    let highest = |r: &[Vec<f64>]| r.iter().map(|r| r[1]).fold(f64::NEG_INFINITY, f64::max);
    // negative control: bent in the variable's own units, the hold overshoots the limit
    assert!(
        highest(&plain) > 1.0,
        "plain bend's highest {}",
        highest(&plain)
    );
    assert!(
        highest(&ranged) <= 1.0 + 1e-9,
        "ranged bend's highest {}",
        highest(&ranged)
    );
    for (phase, posture) in &points {
        let read = at_phase(&ranged, *phase);
        for (a, b) in read.iter().zip(posture) {
            assert!(
                (a - b).abs() < 1e-9,
                "phase {phase}: {read:?} vs {posture:?}"
            );
        }
    }
    // a variable already outside its range is bent no further out than it already is
    let ranged = meet(&rows, &points, Some(&[(-0.5, 0.5), (0.0, 1.0)])).unwrap();
    let lowest = ranged.iter().map(|r| r[0]).fold(f64::INFINITY, f64::min);
    assert!(lowest >= -1.0 - 1e-6, "lowest {lowest}");
}
