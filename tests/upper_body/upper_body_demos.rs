//! The upper body's demonstrations, recorded from the simulated encoders: every gesture of the
//! robot, none with two parts in contact but the gesture's own (the clap's hands, in every
//! demonstration); each gesture's signature holds on its own demonstrations and on the
//! hierarchy's reproductions, and not on the other gestures'; the arms of a symmetric gesture
//! move together within a person's variation.

#![cfg(feature = "sim")]

use cosco_hsom::experiment::demonstrate::{record_demonstrations, DemoSettings};
use cosco_hsom::experiment::signature::signature;
use cosco_hsom::gesture::Gesture;
use cosco_hsom::gesture::{mirror, upper, Segment};
use cosco_hsom::robot::Robot;
use cosco_hsom::sim::{own_contacts, NaoArm, Recording};

fn record(arm: &NaoArm<14>, name: &str, count: usize, seed: u64) -> Vec<Recording> {
    let g = Gesture::by_name(Robot::UpperBody, name).unwrap();
    record_demonstrations(arm, &g, count, seed, &DemoSettings::default(), |_| {}).unwrap()
}

#[test]
fn the_upper_body_has_its_gestures_and_only_the_clap_touches_its_own_hands() {
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let names = Gesture::names(Robot::UpperBody);
    assert!(names.len() >= 8, "{names:?}");
    for name in [
        "wave-right",
        "clap",
        "welcome",
        "shrug",
        "nod",
        "shake-head",
    ] {
        assert!(names.contains(&name), "{name}");
    }
    let hands = [["left hand".to_string(), "right hand".to_string()]];
    for name in names {
        let recs = record(&arm, name, 3, 21);
        let contacts: Vec<_> = recs.iter().map(|r| r.contacts.clone()).collect();
        let own = own_contacts(&contacts);
        assert_eq!(own, if name == "clap" { &hands[..] } else { &[] }, "{name}");
        for r in &recs {
            assert_eq!(r.joint_names.len(), 14);
            let others: Vec<String> = (r.contacts.iter())
                .filter(|t| !own.contains(&t.limbs()))
                .map(|t| t.describe())
                .collect();
            assert!(others.is_empty(), "{name}: {others:?}");
        }
    }
}

/// The demonstrations of every upper-body gesture, seed `seed`, `count` each.
fn every_gesture(arm: &NaoArm<14>, count: usize, seed: u64) -> Vec<(&'static str, Vec<Recording>)> {
    (Gesture::names(Robot::UpperBody).into_iter())
        .map(|name| (name, record(arm, name, count, seed)))
        .collect()
}

#[test]
fn each_gesture_has_its_signature_and_the_others_do_not() {
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let all = every_gesture(&arm, 3, 23);
    for (name, recs) in &all {
        for (other, theirs) in &all {
            for r in theirs {
                let s = signature(&arm, name, &r.qpos).unwrap().unwrap();
                // its own demonstrations hold it; every other gesture's miss it (the
                // negative control of each signature)
                assert_eq!(
                    s.holds,
                    name == other,
                    "{name}'s signature on {other}: {s:?}"
                );
            }
        }
        assert!(!recs.is_empty());
    }
}

#[test]
fn a_clap_with_the_hands_kept_apart_fails_the_clap_signature() {
    // the negative control of the clap's: the hands 12 cm apart at their closest
    const APART: cosco_hsom::gesture::ArmPose = [1.0, 0.06, -1.04, -1.26, -1.23, 0.5];
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let mut clap = Gesture::by_name(Robot::UpperBody, "clap").unwrap();
    for seg in clap.segments.iter_mut().take(7) {
        if let Segment::Move { to, .. } = seg {
            *to = upper([0.0, 0.1], APART, mirror(APART));
        }
    }
    let recs = record_demonstrations(&arm, &clap, 2, 23, &DemoSettings::default(), |_| {}).unwrap();
    for r in recs {
        let s = signature(&arm, "clap", &r.qpos).unwrap().unwrap();
        assert!(!s.holds && s.measured == 0.0, "{s:?}");
        assert!(r.contacts.is_empty(), "{:?}", r.contacts);
    }
}

#[test]
fn a_posture_of_the_hand_in_the_chest_is_a_recorded_contact() {
    // the negative control of the test above: the same recording path reports a contact
    use cosco_hsom::sim::{Controller, ControllerConfig, TargetTrajectory};
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let rest = Robot::UpperBody.posture("StandInit").unwrap().to_vec();
    let mut chest = rest.clone();
    chest[2..8].copy_from_slice(&[0.6, -0.314159, 0.0, -1.54, 0.0, 0.0]);
    let targets = vec![rest.clone(), chest, rest];
    let t = TargetTrajectory::<14>::new_for(Robot::UpperBody, &[0.0, 1.0, 2.0], &targets).unwrap();
    let mut sim = arm.sim().unwrap();
    let rec = Controller::new(ControllerConfig::default())
        .unwrap()
        .follow(&mut sim, &t)
        .unwrap();
    assert!(
        rec.contacts
            .iter()
            .any(|c| c.parts.iter().any(|p| p == "torso")),
        "{:?}",
        rec.contacts
    );
}
