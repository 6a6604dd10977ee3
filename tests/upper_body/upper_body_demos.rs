//! The upper body's demonstrations, recorded from the simulated encoders: every gesture of the
//! robot, none with two parts in contact; the clap's hands meet; the arms of a symmetric
//! gesture move together within a person's variation.

#![cfg(feature = "sim")]

use cosco_hsom::experiment::demonstrate::{record_demonstrations, DemoSettings};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::robot::Robot;
use cosco_hsom::sim::{NaoArm, Recording};

fn record(arm: &NaoArm<14>, name: &str, count: usize, seed: u64) -> Vec<Recording> {
    let g = Gesture::by_name(Robot::UpperBody, name).unwrap();
    record_demonstrations(arm, &g, count, seed, &DemoSettings::default(), |_| {}).unwrap()
}

#[test]
fn the_upper_body_has_its_gestures_and_no_demonstration_touches() {
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
    for name in names {
        for r in record(&arm, name, 3, 21) {
            assert_eq!(r.joint_names.len(), 14);
            let touches: Vec<String> = r.contacts.iter().map(|t| t.describe()).collect();
            assert!(touches.is_empty(), "{name}: {touches:?}");
        }
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
