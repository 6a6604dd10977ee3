use super::*;

fn demo(rows: Vec<Vec<f64>>, period: f64) -> Demonstration {
    Demonstration {
        source: "d.csv".into(),
        columns: (0..rows[0].len()).map(|k| format!("q{k}")).collect(),
        time: Some((0..rows.len()).map(|k| k as f64 * period).collect()),
        rows,
    }
}

#[test]
fn start_speed_is_the_first_steps_euclidean_speed() {
    let rows = [vec![0.0, 0.0], vec![0.3, 0.4], vec![5.0, 5.0]];
    assert_eq!(start_speed(&rows, 0.1), Some(5.0));
    assert_eq!(start_speed(&rows[..1], 0.1), None);
    let none: [Vec<f64>; 0] = [];
    assert_eq!(start_speed(&none, 0.1), None);
}

#[test]
fn end_spread_is_the_mean_pairwise_distance() {
    // a 3-4-5 triangle: (3 + 4 + 5) / 3
    let ends = [vec![0.0, 0.0], vec![3.0, 0.0], vec![0.0, 4.0]];
    assert!((end_spread(&ends) - 4.0).abs() < 1e-12);
    assert_eq!(end_spread(&ends[..1]), 0.0);
    assert_eq!(end_tolerance(4.0, 100.0), 8.0);
    // no spread: 1 % of the diagonal
    assert_eq!(end_tolerance(0.0, 100.0), 1.0);
}

#[test]
fn the_reference_takes_each_demonstrations_own_period() {
    // 0.1 per step at 10 Hz is 1 unit/s; 0.1 per step at 40 Hz is 4 units/s
    let slow = demo(vec![vec![0.0], vec![0.1], vec![1.0]], 0.1);
    let fast = demo(vec![vec![0.0], vec![0.1], vec![2.0]], 0.025);
    let r = StartEndReference::of([&slow, &fast], 10.0);
    assert!((r.demo_start_speed_max.unwrap() - 4.0).abs() < 1e-9);
    assert!((r.end_spread - 1.0).abs() < 1e-12);
    let one = StartEndReference::of([&slow], 10.0);
    assert_eq!(one.end_spread, 0.0);
}

#[test]
fn a_slower_start_is_in_range_a_faster_one_is_not() {
    let r = StartEndReference {
        demo_start_speed_max: Some(2.0),
        end_spread: 0.5,
        diagonal: 10.0,
    };
    let judge = |first_step: f64| r.judge(&[vec![0.0], vec![first_step]], 0.1, 0.0);
    assert!(judge(0.2).start_in_range); // 2 units/s: the largest itself
    assert!(judge(0.0).start_in_range); // at rest: slower than the slowest
    assert!(!judge(0.21).start_in_range);
    // the rounding of a period computed from a time column is no jump; a millionth is
    let ulp = r.judge(&[vec![0.0], vec![0.2]], 0.1 * (1.0 - f64::EPSILON), 0.0);
    assert!(ulp.start_speed.unwrap() > 2.0 && ulp.start_in_range);
    assert!(!judge(0.2 * (1.0 + 1e-6)).start_in_range);
    assert!(!r.judge(&[vec![0.0]], 0.1, 0.0).start_in_range); // no step to judge
                                                              // end: within 2 x 0.5 = 1.0 (1 % of the diagonal is 0.1)
    assert!(r.judge(&[vec![0.0]], 0.1, 1.0).end_within_spread);
    assert!(!r.judge(&[vec![0.0]], 0.1, 1.01).end_within_spread);
    assert_eq!(r.judge(&[vec![0.0]], 0.1, 0.3).end_tolerance, 1.0);
}

mod held_out;
