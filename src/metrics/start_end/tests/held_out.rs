//! Where a reproduction starts and ends against the demonstrations it learned from, scored as
//! `cosco heldout` scores a fold (`eval::Kinematic`, `metrics::StartEndReference`,
//! `eval::Score`): the held-out demonstration itself starts in range, ends within the spread
//! and has a jerk ratio of 1; the controls, the same motion with a step injected at its start
//! and the same motion ending away, fail. Needs no simulator: runs in both builds.

use crate::demos::{sample_period, Demonstration};
use crate::eval::{all_but, diagonal, Executor, Kinematic, Method, Score};
use crate::metrics::{start_speed, StartEndReference};

/// Samples of each demonstration (2 s at 40 Hz).
const N: usize = 81;
/// The demonstration held out, in the middle of the others' amplitudes.
const HELD: usize = 2;

/// The minimum-jerk profile from 0 to 1.
fn min_jerk(u: f64) -> f64 {
    u * u * u * (10.0 - 15.0 * u + 6.0 * u * u)
}

/// Five smooth 2-D strokes at rest at both ends, amplitudes 0.8 to 1.2: a gesture whose
/// demonstrations differ in size, so their first steps and their ends differ.
fn demos() -> Vec<Demonstration> {
    (0..5)
        .map(|i| {
            let a = 0.8 + 0.1 * i as f64;
            let rows = (0..N)
                .map(|k| {
                    let s = min_jerk(k as f64 / (N - 1) as f64);
                    vec![a * s, 0.5 * a * (std::f64::consts::PI * s).sin()]
                })
                .collect();
            Demonstration {
                source: format!("stroke{i}.csv"),
                columns: vec!["x".into(), "y".into()],
                time: Some((0..N).map(|k| k as f64 * 0.025).collect()),
                rows,
            }
        })
        .collect()
}

/// `rows` scored as fold [`HELD`] of [`demos`] is scored by `cosco heldout`.
fn score(rows: &[Vec<f64>]) -> Score {
    let demos = demos();
    let held = &demos[HELD];
    let executed = Kinematic
        .execute(Method::Hierarchy, rows, std::slice::from_ref(held))
        .unwrap();
    let diag = diagonal(&demos);
    let reference = StartEndReference::of(&all_but(&demos, HELD), diag);
    let f = &executed.fidelity;
    let start_end = reference.judge(
        Kinematic.motion(&executed),
        sample_period(held),
        f.final_error_rad.mean,
    );
    Score::of(f, diag, &start_end)
}

#[test]
fn the_held_out_demonstration_itself_starts_in_range_ends_within_and_has_jerk_ratio_1() {
    let held = demos()[HELD].rows.clone();
    let s = score(&held);
    assert!(s.start_in_range, "{s:?}");
    assert!(s.end_within_spread, "{s:?}");
    assert_eq!(s.final_error, 0.0);
    let ratio = s.jerk_ratio.unwrap();
    assert!((ratio - 1.0).abs() < 1e-12, "{ratio}");
    // the reference is the training demonstrations': amplitudes 0.8, 0.9, 1.1, 1.2 end
    // 0.1, 0.3, 0.4, 0.2, 0.3, 0.1 apart, 1.4 / 6 on average; the fastest start is 1.2's
    assert!((s.end_spread - 1.4 / 6.0).abs() < 1e-12, "{}", s.end_spread);
    let fastest = start_speed(&demos()[4].rows, 0.025).unwrap();
    assert!((s.demo_start_speed_max.unwrap() - fastest).abs() < 1e-12);
    assert!(s.start_speed.unwrap() < fastest);
}

#[test]
fn a_step_injected_at_the_start_fails_start_in_range_and_the_jerk_gate() {
    // the reproduction snaps from the given initial posture onto the path: its first sample
    // is 0.05 away in each variable from where the motion goes on
    let mut stepped = demos()[HELD].rows.clone();
    stepped[0][0] -= 0.05;
    stepped[0][1] -= 0.05;
    let s = score(&stepped);
    assert!(!s.start_in_range, "{s:?}");
    assert!(
        s.start_speed.unwrap() > 10.0 * s.demo_start_speed_max.unwrap(),
        "{s:?}"
    );
    let ratio = s.jerk_ratio.unwrap();
    assert!(ratio > 2.0, "jerk ratio of the injected step: {ratio}");
    // it still ends where the held-out demonstration does
    assert!(s.end_within_spread, "{s:?}");
}

#[test]
fn a_reproduction_ending_away_fails_end_within_spread() {
    // the last quarter drifts smoothly 0.6 away in x (the tolerance is 2 x 1.4 / 6 = 0.47)
    let mut away = demos()[HELD].rows.clone();
    let from = 3 * N / 4;
    for (k, r) in away.iter_mut().enumerate().skip(from) {
        r[0] += 0.6 * min_jerk((k - from) as f64 / (N - 1 - from) as f64);
    }
    let s = score(&away);
    assert!(!s.end_within_spread, "{s:?}");
    assert!((s.final_error - 0.6).abs() < 1e-9, "{}", s.final_error);
    // the start is untouched
    assert!(s.start_in_range, "{s:?}");
    // a drift that stays within the tolerance passes
    let mut near = demos()[HELD].rows.clone();
    for (k, r) in near.iter_mut().enumerate().skip(from) {
        r[0] += 0.3 * min_jerk((k - from) as f64 / (N - 1 - from) as f64);
    }
    assert!(score(&near).end_within_spread);
}
