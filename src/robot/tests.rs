use super::*;

/// The published left arm (docs: nao-left-arm.md): name, range, max velocity, max torque.
const PUBLISHED_LEFT_ARM: [(&str, f64, f64, f64, f64); 6] = [
    ("LShoulderPitch", -2.08567, 2.08567, 8.26797, 1.329),
    ("LShoulderRoll", -0.314159, 1.32645, 7.19407, 1.7835),
    ("LElbowYaw", -2.08567, 2.08567, 8.26797, 1.547),
    ("LElbowRoll", -1.54462, -0.0349066, 7.19407, 1.532),
    ("LWristYaw", -1.82387, 1.82387, 24.6229, 0.4075),
    ("LHand", 0.0, 1.0, 8.33, 0.292),
];

#[test]
fn the_left_arm_is_the_published_one() {
    let joints = Robot::LeftArm.joints();
    assert_eq!(joints.len(), PUBLISHED_LEFT_ARM.len());
    for (j, (name, lo, hi, v, tau)) in joints.iter().zip(PUBLISHED_LEFT_ARM) {
        assert_eq!(
            (j.name, j.range, j.max_velocity, j.max_torque),
            (name, (lo, hi), v, tau)
        );
    }
}

/// The published upper body (docs: nao-upper-body.md, the left arm as above).
const PUBLISHED_HEAD_AND_RIGHT_ARM: [(&str, f64, f64, f64, f64); 8] = [
    ("HeadYaw", -2.08567, 2.08567, 8.26797, 1.547),
    ("HeadPitch", -0.671952, 0.514872, 7.19407, 1.532),
    ("RShoulderPitch", -2.08567, 2.08567, 8.26797, 1.329),
    ("RShoulderRoll", -1.32645, 0.314159, 7.19407, 1.783),
    ("RElbowYaw", -2.08567, 2.08567, 8.26797, 1.547),
    ("RElbowRoll", 0.0349066, 1.54462, 7.19407, 1.532),
    ("RWristYaw", -1.82387, 1.82387, 24.6229, 0.4075),
    ("RHand", 0.0, 1.0, 8.33, 0.292),
];

#[test]
fn the_upper_body_is_the_published_one() {
    let joints = Robot::UpperBody.joints();
    let published: Vec<_> = PUBLISHED_HEAD_AND_RIGHT_ARM[..2]
        .iter()
        .chain(&PUBLISHED_LEFT_ARM)
        .chain(&PUBLISHED_HEAD_AND_RIGHT_ARM[2..])
        .collect();
    assert_eq!(joints.len(), 14);
    for (j, &&(name, lo, hi, v, tau)) in joints.iter().zip(&published) {
        assert_eq!(
            (j.name, j.range, j.max_velocity, j.max_torque),
            (name, (lo, hi), v, tau)
        );
    }
    let rest = Robot::UpperBody.posture("StandInit").unwrap();
    assert_eq!(&rest[2..8], Robot::LeftArm.posture("StandInit").unwrap());
}

#[test]
fn named_postures_come_from_the_keyframes_within_range() {
    let r = Robot::LeftArm;
    assert_eq!(
        r.posture("StandInit"),
        Some(&[1.4, 0.3, -1.39, -1.01, 0.0, 0.25][..])
    );
    assert_eq!(r.posture("NoSuchPosture"), None);
    for name in ["StandInit", "Stand", "Crouch", "StandZero", "ReadingWatch"] {
        let p = r.posture(name).unwrap();
        for (v, j) in p.iter().zip(r.joints()) {
            assert!((j.range.0..=j.range.1).contains(v), "{name} {}", j.name);
        }
    }
}

#[test]
fn a_robot_is_known_by_its_columns_and_its_name() {
    let cols = |names: &[&str]| names.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    assert_eq!(
        Robot::of_columns(&cols(&LEFT_ARM_JOINTS)),
        Some(Robot::LeftArm)
    );
    let mut swapped = LEFT_ARM_JOINTS;
    swapped.swap(0, 1);
    assert_eq!(Robot::of_columns(&cols(&swapped)), None);
    assert_eq!(Robot::of_columns(&cols(&["x", "y"])), None);
    assert_eq!(Robot::from_name("left-arm"), Ok(Robot::LeftArm));
    let e = Robot::from_name("torso").unwrap_err();
    assert!(e.contains("torso") && e.contains("left-arm"), "{e}");
}

#[test]
fn a_malformed_model_is_named() {
    let e = joint_ranges(r#"<mujoco><joint name="a" range="1 0"/></mujoco>"#).unwrap_err();
    assert!(e.contains("`a`") && e.contains("lower < upper"), "{e}");
    let e = joint_ranges(r#"<mujoco><joint name="a" range="x 0"/></mujoco>"#).unwrap_err();
    assert!(e.contains("two numbers"), "{e}");
    let e = read(r#"<mujoco><joint name="a"/><key name="k" qpos="1 2"/></mujoco>"#)
        .err()
        .unwrap();
    assert!(e.contains("`k`") && e.contains("2 joint positions"), "{e}");
}

#[test]
fn each_robot_is_described_once() {
    for r in Robot::ALL {
        // one spelling: the command line's, serde's and clap's
        let json = serde_json::to_string(&r).unwrap();
        assert_eq!(json, format!("\"{}\"", r.name()));
        assert_eq!(serde_json::from_str::<Robot>(&json).unwrap(), r);
        let value = clap::ValueEnum::to_possible_value(&r).unwrap();
        assert_eq!(value.get_name(), r.name());
        // the swing joint by its column
        let (j, name) = r.swing_joint();
        assert_eq!(r.joint_names()[j], name);
        // its configuration reads the robot's joints
        let (file, xml) = r.config();
        let cfg = crate::config::parse_config(xml, file).unwrap();
        assert_eq!(cfg.params().state_length, r.joint_names().len());
        // its default gesture is one of its own
        assert!(crate::gesture::Gesture::by_name(r, r.default_gesture()).is_some());
    }
    let fig4: Vec<&str> = Robot::LeftArm.plot_panels().iter().map(|p| p.1).collect();
    assert_eq!(fig4, LEFT_ARM_JOINTS[..4]);
    assert_eq!(Robot::UpperBody.plot_panels().len(), 14);
}

#[test]
fn a_hand_is_plotted_as_an_open_fraction() {
    assert_eq!(axis_label("LHand"), "LHand (open fraction)");
    assert_eq!(axis_label("RHand"), "RHand (open fraction)");
    assert_eq!(axis_label("LElbowRoll"), "LElbowRoll (rad)");
}
