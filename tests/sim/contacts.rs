//! Contacts between two parts of the robot. `cosco export --robot upper-body` executes the
//! motion on the simulated upper body first: a reproduction that brings the left hand into
//! the chest is refused, naming the time and the two parts; the same path with the hand kept
//! out exports (the negative control); `--allow-contact` exports the first anyway and says
//! so. `cosco evaluate` of an upper-body reproduction reports its contacts. `cosco reproduce`
//! keeps an initial posture within the robot's joint ranges, and `--robot` refuses a model of
//! another robot.

#![cfg(feature = "sim")]

use std::path::Path;

use predicates::prelude::*;

use crate::common::cosco;

use cosco_hsom::curve::minimum_jerk_at;
use cosco_hsom::robot::Robot;

/// The left arm from StandInit to `apex` at 1 s and back at 2 s, at 40 Hz, each leg a
/// minimum-jerk curve; the other joints of `robot` hold StandInit. Written as a CSV of `time`
/// then the robot's joints.
fn write_motion(path: &Path, robot: Robot, apex: [f64; 6]) {
    let rest = robot.posture("StandInit").unwrap();
    let arm = robot
        .joint_names()
        .iter()
        .position(|j| *j == "LShoulderPitch")
        .unwrap();
    let mut csv = format!("time,{}\n", robot.joint_names().join(","));
    for k in 0..=80 {
        let t = k as f64 / 40.0;
        let w = minimum_jerk_at(if t <= 1.0 { t } else { 2.0 - t });
        let mut p = rest.to_vec();
        for (j, b) in apex.iter().enumerate() {
            p[arm + j] = rest[arm + j] + w * (b - rest[arm + j]);
        }
        let row: Vec<String> = p.iter().map(|v| v.to_string()).collect();
        csv += &format!("{t},{}\n", row.join(","));
    }
    std::fs::write(path, csv).unwrap();
}

/// A left-arm reproduction CSV ([`write_motion`] of the left arm's six joints).
fn write_reproduction(path: &Path, apex: [f64; 6]) {
    write_motion(path, Robot::LeftArm, apex);
}

/// The hand pressed into the chest: the arm forward, rolled in across the torso, the elbow
/// bent fully.
const INTO_CHEST: [f64; 6] = [0.6, -0.314159, 0.0, -1.54, 0.0, 0.0];
/// The same motion with the hand kept out: the arm rolled outwards, the elbow half bent.
const KEPT_OUT: [f64; 6] = [0.6, 0.3, 0.0, -1.0, 0.0, 0.0];

fn export(rep: &Path, out: &Path, extra: &[&str]) -> assert_cmd::assert::Assert {
    cosco()
        .args(["export", "--format", "naoqi", "--robot", "upper-body"])
        .arg("--reproduction")
        .arg(rep)
        .arg("--out")
        .arg(out)
        .args(extra)
        .assert()
}

#[test]
fn a_hand_into_the_chest_is_refused_naming_the_time_and_the_parts() {
    let dir = tempfile::tempdir().unwrap();
    let rep = dir.path().join("chest.csv");
    let out = dir.path().join("chest.json");
    write_reproduction(&rep, INTO_CHEST);
    let e = export(&rep, &out, &[]).failure().code(1);
    let text = String::from_utf8_lossy(&e.get_output().stderr).to_string();
    assert!(text.contains("into contact at t = "), "{text}");
    assert!(text.contains("torso"), "{text}");
    assert!(text.contains("--allow-contact"), "{text}");
    // the time lies within the motion, before the apex is held back out
    let t: f64 = text
        .split("at t = ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap();
    assert!((0.1..1.9).contains(&t), "{t}: {text}");
    assert!(!out.exists(), "a refused motion is not written");
}

#[test]
fn the_same_path_with_the_hand_kept_out_exports() {
    let dir = tempfile::tempdir().unwrap();
    let rep = dir.path().join("out.csv");
    let out = dir.path().join("out.json");
    write_reproduction(&rep, KEPT_OUT);
    export(&rep, &out, &[])
        .success()
        .stdout(predicate::str::contains("contacts: none"));
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!(json["names"].as_array().unwrap().len(), 6);
}

#[test]
fn allow_contact_exports_it_anyway_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let rep = dir.path().join("chest.csv");
    let out = dir.path().join("chest.json");
    write_reproduction(&rep, INTO_CHEST);
    export(&rep, &out, &["--allow-contact"])
        .success()
        .stdout(predicate::str::contains("--allow-contact: exported"))
        .stdout(predicate::str::contains("torso"));
    assert!(out.exists());
}

#[test]
fn the_left_arm_model_exports_the_same_motion_unchecked_as_before() {
    // the left arm's model is collision-free: its export is what it always was
    let dir = tempfile::tempdir().unwrap();
    let rep = dir.path().join("chest.csv");
    let out = dir.path().join("chest.json");
    write_reproduction(&rep, INTO_CHEST);
    cosco()
        .args(["export", "--format", "naoqi", "--reproduction"])
        .arg(&rep)
        .arg("--out")
        .arg(&out)
        .assert()
        .success()
        .stdout(predicate::str::contains("contacts").not());
}

#[test]
fn every_upper_body_joint_goes_in_one_angle_interpolation_call() {
    let dir = tempfile::tempdir().unwrap();
    let rep = dir.path().join("both.csv");
    let out = dir.path().join("both.json");
    let names = Robot::UpperBody.joint_names();
    let rest = Robot::UpperBody.posture("StandInit").unwrap();
    let mut csv = format!("time,{}\n", names.join(","));
    for k in 0..=40 {
        let t = k as f64 / 40.0;
        let mut p = rest.to_vec();
        p[0] = 0.3 * (std::f64::consts::PI * t).sin(); // HeadYaw turns and back
        let row: Vec<String> = p.iter().map(|v| v.to_string()).collect();
        csv += &format!("{t},{}\n", row.join(","));
    }
    std::fs::write(&rep, csv).unwrap();
    export(&rep, &out, &[])
        .success()
        .stdout(predicate::str::contains("contacts: none"));
    let json: serde_json::Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
    let got: Vec<&str> = (json["names"].as_array().unwrap().iter())
        .map(|v| v.as_str().unwrap())
        .collect();
    assert_eq!(got, names);
    assert_eq!(json["angleLists"].as_array().unwrap().len(), 14);
}

/// An upper-body CSV ([`write_motion`] of the 14 joints).
fn write_upper_body(path: &Path, apex: [f64; 6]) {
    write_motion(path, Robot::UpperBody, apex);
}

#[test]
fn evaluate_reports_the_contacts_of_an_upper_body_reproduction() {
    let dir = tempfile::tempdir().unwrap();
    let demo = dir.path().join("demo.csv");
    write_upper_body(&demo, KEPT_OUT);
    let evaluate = |rep: &Path| {
        let out = cosco()
            .arg("evaluate")
            .arg("--reproduction")
            .arg(rep)
            .arg("--demos")
            .arg(&demo)
            .assert()
            .success();
        String::from_utf8_lossy(&out.get_output().stdout).to_string()
    };
    let chest = dir.path().join("chest.csv");
    write_upper_body(&chest, INTO_CHEST);
    let text = evaluate(&chest);
    let row = text
        .lines()
        .find(|l| l.starts_with("contacts (simulated upper body):"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(row.contains("torso"), "{row}");
    // the negative control: the demonstration itself touches nothing
    let text = evaluate(&demo);
    assert!(
        text.lines()
            .any(|l| l.starts_with("contacts (simulated upper body):") && l.ends_with("none")),
        "{text}"
    );
}

/// `reproduce --initial` with an arm posture far outside a joint's range is refused, naming
/// the joint and its range.
#[test]
fn reproduce_refuses_an_initial_posture_far_outside_the_joint_ranges() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    cosco()
        .args(["demos", "--count", "2", "--out"])
        .arg(d.join("demos"))
        .assert()
        .success();
    cosco()
        .args(["train", "--demos"])
        .arg(d.join("demos"))
        .arg("--out")
        .arg(d.join("m.bin"))
        .assert()
        .success();
    let run = |initial: &str| {
        let mut c = cosco();
        c.args(["reproduce", "--model"])
            .arg(d.join("m.bin"))
            .args(["--initial", initial, "--out"])
            .arg(d.join("r.csv"));
        c.assert()
    };
    run("1.4,0.3,-1.39,8.0,0,0.25").failure().stderr(
        predicate::str::contains("LElbowRoll")
            .and(predicate::str::contains("8"))
            .and(predicate::str::contains("range")),
    );
    run("1.4,0.3,-1.39,-1.01,0,0.25").success();
    // --robot: the model must be of that robot
    let on = |robot: &str| {
        let mut c = cosco();
        c.args(["reproduce", "--model"])
            .arg(d.join("m.bin"))
            .args([
                "--initial",
                "1.4,0.3,-1.39,-1.01,0,0.25",
                "--robot",
                robot,
                "--out",
            ])
            .arg(d.join("r.csv"));
        c.assert()
    };
    on("left-arm").success();
    on("upper-body").failure().stderr(
        predicate::str::contains("--robot upper-body")
            .and(predicate::str::contains("m.bin learned 6 variables"))
            .and(predicate::str::contains("HeadYaw")),
    );
    on("biped")
        .failure()
        .stderr(predicate::str::contains("left-arm, upper-body"));
}

#[test]
fn the_claps_hands_are_its_own_contact_and_export_while_a_hand_in_the_chest_is_still_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = |name: &str| dir.path().join(name);
    cosco()
        .args([
            "demos",
            "--robot",
            "upper-body",
            "--gesture",
            "clap",
            "--count",
            "3",
        ])
        .args(["--seed", "41", "--out"])
        .arg(d("demos"))
        .assert()
        .success();
    let config = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/nao-upper-body.xml");
    cosco()
        .args(["train", "--config", config, "--demos"])
        .arg(d("demos"))
        .arg("--out")
        .arg(d("m.bin"))
        .assert()
        .success();
    let initial = d("demos").join("demo_01.csv");
    cosco()
        .args(["reproduce", "--model"])
        .arg(d("m.bin"))
        .arg("--initial-from")
        .arg(&initial)
        .arg("--out")
        .arg(d("rep.csv"))
        .assert()
        .success();
    // from the model: its kept demonstrations say the hands' contact is the clap's own
    cosco()
        .args(["export", "--format", "naoqi", "--model"])
        .arg(d("m.bin"))
        .arg("--initial-from")
        .arg(&initial)
        .arg("--out")
        .arg(d("m.json"))
        .assert()
        .success()
        .stdout(predicate::str::contains("contacts of the gesture's own"))
        .stdout(predicate::str::contains("LHand_fingers and RHand_fingers"));
    // the reproduction alone: nothing says whose the contact is, so it is refused ...
    export(&d("rep.csv"), &d("r.json"), &[])
        .failure()
        .stderr(predicate::str::contains("into contact"));
    // ... and exported with the demonstrations it was learned from
    let demos = d("demos").display().to_string();
    export(&d("rep.csv"), &d("r.json"), &["--demos", &demos])
        .success()
        .stdout(predicate::str::contains("contacts of the gesture's own"));
    // the clap's own contact allows no other: the hand in the chest is refused as before
    write_motion(&d("chest.csv"), Robot::UpperBody, INTO_CHEST);
    export(&d("chest.csv"), &d("c.json"), &["--demos", &demos])
        .failure()
        .stderr(predicate::str::contains("torso"));
}
