use super::*;

fn sine(periods: f64, amplitude: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|k| amplitude * (std::f64::consts::TAU * periods * k as f64 / n as f64).sin())
        .collect()
}

#[test]
fn a_sine_counts_two_swings_per_period() {
    assert_eq!(large_swings(&sine(3.0, 0.5, 600), 0.3).unwrap(), 6);
    assert_eq!(large_swings(&sine(1.0, 0.5, 200), 0.3).unwrap(), 2);
    // peak-to-peak 1.0 is below 1.2: nothing counts
    assert_eq!(large_swings(&sine(3.0, 0.5, 600), 1.2).unwrap(), 0);
}

#[test]
fn small_wiggles_do_not_count_however_many_sign_changes() {
    let wiggle: Vec<f64> = (0..400)
        .map(|k| if k % 2 == 0 { 0.1 } else { -0.1 })
        .collect();
    assert_eq!(large_swings(&wiggle, 0.3).unwrap(), 0);
    // a raise and return counts one turning point
    let mut up_down: Vec<f64> = (0..50).map(|k| k as f64 / 50.0).collect();
    up_down.extend((0..=50).map(|k| 1.0 - k as f64 / 50.0));
    assert_eq!(large_swings(&up_down, 0.3).unwrap(), 1);
    // the return stops short of the amplitude: no swing
    let mut short: Vec<f64> = (0..50).map(|k| k as f64 / 50.0).collect();
    short.extend((0..=10).map(|k| 1.0 - k as f64 / 50.0));
    assert_eq!(large_swings(&short, 0.3).unwrap(), 0);
    assert_eq!(large_swings(&[], 0.3).unwrap(), 0);
}

#[test]
fn bad_amplitude_and_column_are_named_errors() {
    let e = large_swings(&[0.0, 1.0], 0.0).unwrap_err().to_string();
    assert!(e.contains("min_amplitude") && e.contains('0'), "{e}");
    let e = large_swings(&[0.0], f64::NAN).unwrap_err().to_string();
    assert!(e.contains("NaN"), "{e}");
    let e = column_swings(&[vec![0.0, 1.0]], 3, 0.3)
        .unwrap_err()
        .to_string();
    assert!(e.contains("column 3"), "{e}");
    assert_eq!(
        column_swings(&[[0.0, 0.0], [0.0, 1.0], [0.0, 0.0]], 1, 0.3).unwrap(),
        1
    );
}

/// The time at the apex counts the hold and the last and first samples of the strokes
/// within a tenth of the amplitude; a wobble in the hold smaller than that does not
/// break it, and a stroke that only passes through its apex (the control) stays there
/// a few samples.
#[test]
fn the_time_at_the_apex_counts_the_hold_through_its_wobble() {
    // a stroke of 20 samples from 0 to 1, a hold of 40 with a 0.03 wobble, back in 20
    let mut rows: Vec<[f64; 2]> = (0..20).map(|k| [k as f64 / 20.0, 0.0]).collect();
    rows.extend((0..40).map(|k| [1.0 + 0.03 * (k as f64 * 0.7).sin(), 0.0]));
    rows.extend((0..=20).map(|k| [1.0 - k as f64 / 20.0, 0.0]));
    let dwell = apex_dwell(&rows).unwrap();
    // the 40 held samples and the strokes' last and first two (within 0.1 of the apex)
    assert!((42..=46).contains(&dwell), "{dwell}");
    let through: Vec<[f64; 2]> = (0..=40)
        .map(|k| [1.0 - (k as f64 - 20.0).abs() / 20.0, 0.0])
        .collect();
    assert!(apex_dwell(&through).unwrap() <= 5);
    assert_eq!(apex_dwell::<[f64; 2]>(&[]), None);
}
