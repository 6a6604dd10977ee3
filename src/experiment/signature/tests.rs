use super::*;
use crate::sim::{own_contacts, Touch};

/// Rows of one column following `f` at 40 Hz for `seconds`.
fn rows(seconds: f64, f: impl Fn(f64) -> f64) -> Vec<Vec<f64>> {
    let n = (seconds * 40.0) as usize;
    (0..=n).map(|k| vec![f(k as f64 / 40.0)]).collect()
}

#[test]
fn reversals_count_the_turns_of_a_swing_and_not_its_wobble() {
    // three periods of a 0.3 rad swing: six extremes, each followed by a move of 0.3 rad or
    // more back
    let swing = rows(3.0, |t| 0.3 * (std::f64::consts::TAU * t).sin());
    assert_eq!(reversals(&swing, 0, 0.2), 6);
    // the same swing is wobble at a larger bound
    assert_eq!(reversals(&swing, 0, 0.7), 0);
    // a still joint with 0.01 rad of noise turns nowhere
    let still = rows(3.0, |t| 0.01 * (37.0 * t).sin());
    assert_eq!(reversals(&still, 0, 0.2), 0);
}

#[test]
fn meetings_count_each_approach_once_until_the_hands_part() {
    // 10 cm, then 3 cm three times with 8 cm between: three meetings
    let apart = [0.1, 0.03, 0.035, 0.08, 0.03, 0.08, 0.02, 0.1];
    assert_eq!(meetings(apart.into_iter()), 3);
    // hands that come within 4 cm but never part beyond 7 cm meet once
    let close = [0.1, 0.03, 0.05, 0.03, 0.06, 0.03];
    assert_eq!(meetings(close.into_iter()), 1);
    // the clap's threshold: 4.1 cm is no meeting
    assert_eq!(meetings([0.1, 0.041, 0.1].into_iter()), 0);
}

fn touch(a: &str, b: &str) -> Touch {
    Touch {
        parts: [a.into(), b.into()],
        start_s: 1.0,
        end_s: 1.1,
        depth_m: 0.0005,
    }
}

#[test]
fn a_gestures_own_contacts_are_the_limbs_every_demonstration_brings_together() {
    let hands = ["left hand".to_string(), "right hand".to_string()];
    // the palm of one and the fingers of the other are the two hands
    let runs = vec![
        vec![touch("LHand_fingers", "RHand_fingers")],
        vec![touch("l_wrist", "RHand_fingers"), touch("LBicep", "torso")],
        vec![touch("r_wrist", "LHand_fingers")],
    ];
    assert_eq!(own_contacts(&runs), vec![hands.clone()]);
    // a contact that one demonstration does not make is not the gesture's own
    let mut one_without = runs.clone();
    one_without.push(Vec::new());
    assert!(own_contacts(&one_without).is_empty());
    assert!(own_contacts(&[]).is_empty());
}
