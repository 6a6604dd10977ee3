use super::limits::{self, nao_left_arm, RobotLimits};
use super::*;

#[allow(clippy::approx_constant)] // Stand's 1.4426 is NAOqi's angle, not log2(e)
fn arm_trajectory(duration: f64) -> Trajectory {
    // StandInit to Stand and back, 41 points
    let a = [1.4, 0.3, -1.39, -1.01, 0.0, 0.25];
    let b = [1.4426, 0.2245, -1.2023, -0.4173, 0.1, 0.3];
    let n = 41;
    let times: Vec<f64> = (0..n)
        .map(|i| duration * i as f64 / (n - 1) as f64)
        .collect();
    let positions = (0..n)
        .map(|i| {
            let u = (std::f64::consts::PI * i as f64 / (n - 1) as f64).sin();
            a.iter().zip(&b).map(|(x, y)| x + u * (y - x)).collect()
        })
        .collect();
    let names = nao_left_arm()
        .joints
        .iter()
        .map(|j| j.name.clone())
        .collect();
    Trajectory::new(names, times, positions).unwrap()
}

fn opts(format: Format) -> ExportRequest {
    ExportRequest {
        format,
        out: "unused".into(),
        speed: None,
        duration: None,
        velocity_fraction: limits::DEFAULT_VELOCITY_FRACTION,
        clamp: false,
        rate: None,
        step_rate: DEFAULT_STEP_RATE_HZ,
        mjcf: None,
        velocity_table: None,
        executed: false,
        robot: Some(crate::robot::Robot::LeftArm),
        allow_contact: false,
        own_contacts: Vec::new(),
    }
}

#[test]
fn a_sped_up_motion_is_refused_naming_the_joint_and_clamp_slows_it_to_the_limit() {
    let arm = nao_left_arm();
    let t = arm_trajectory(2.0);
    let (_, ok) = prepare(&t, &arm, &opts(Format::Naoqi)).unwrap();
    assert!(ok.peak_velocity_fraction < 0.5);
    // 40 times faster: the elbow roll (0.59 rad in 0.025 s at the steepest) is over the limit
    let fast = Some(40.0);
    let e = prepare(
        &t,
        &arm,
        &ExportRequest {
            speed: fast,
            ..opts(Format::Naoqi)
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("LElbowRoll") && e.contains("--clamp"), "{e}");
    let clamped = ExportRequest {
        speed: fast,
        clamp: true,
        ..opts(Format::Naoqi)
    };
    let (slow, r) = prepare(&t, &arm, &clamped).unwrap();
    let c = r.clamp.unwrap();
    assert!(c.factor > 1.0 && c.joint == "LElbowRoll");
    assert!((c.duration_before_s - 0.05).abs() < 1e-12);
    assert!(r.duration_s > c.duration_before_s);
    // at the limit, not below it: the slowest timing that passes
    assert!(
        (r.peak_velocity_fraction - 0.5).abs() < 1e-6,
        "{}",
        r.peak_velocity_fraction
    );
    arm.check(&slow, 0.5).unwrap();
    assert!(arm.check(&slow.scaled(0.99).unwrap(), 0.5).is_err());
}

#[test]
fn a_posture_out_of_range_is_refused_even_with_clamp() {
    let arm = nao_left_arm();
    let mut t = arm_trajectory(2.0);
    t.positions[20][3] = 0.1; // LElbowRoll's upper limit is -0.0349
    for clamp in [false, true] {
        let e = prepare(
            &t,
            &arm,
            &ExportRequest {
                clamp,
                ..opts(Format::Csv)
            },
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("LElbowRoll") && e.contains("outside its range") && e.contains("t = 1.000"),
            "{e}"
        );
    }
}

#[test]
fn naoqi_lists_have_equal_lengths_and_positive_increasing_times() {
    let t = arm_trajectory(2.0);
    let a = naoqi::arguments(&t);
    assert_eq!(a.names.len(), 6);
    assert_eq!(a.angleLists.len(), 6);
    assert_eq!(a.timeLists.len(), 6);
    for (angles, times) in a.angleLists.iter().zip(&a.timeLists) {
        assert_eq!(angles.len(), times.len());
        assert!(times[0] > 0.0 && times.windows(2).all(|w| w[1] > w[0]));
    }
    assert_eq!(a.angleLists[3][20], t.positions[20][3]);
    let v: serde_json::Value = serde_json::from_slice(&naoqi::to_json(&t)).unwrap();
    assert_eq!(v["isAbsolute"], serde_json::Value::Bool(true));
}

#[test]
fn duration_and_rate_retime_the_motion() {
    let arm = nao_left_arm();
    let t = arm_trajectory(2.0);
    let o = ExportRequest {
        duration: Some(4.0),
        rate: Some(10.0),
        ..opts(Format::Csv)
    };
    let (out, r) = prepare(&t, &arm, &o).unwrap();
    assert_eq!(out.times.len(), 41);
    assert!((r.duration_s - 4.0).abs() < 1e-9);
    assert!((out.times[1] - 0.1).abs() < 1e-12);
    // halfway: the apex (Stand), reached at 2 s
    assert!((out.position_at(2.0)[3] + 0.4173).abs() < 1e-9);
    let bad = ExportRequest {
        speed: Some(-1.0),
        ..opts(Format::Csv)
    };
    assert!(prepare(&t, &arm, &bad)
        .unwrap_err()
        .to_string()
        .contains("--speed"));
}

#[test]
fn limits_of_another_robot_come_from_its_mjcf_and_a_velocity_table() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("v.csv");
    std::fs::write(&table, "joint,max_velocity\nLElbowRoll,2.0\n").unwrap();
    let v = limits::read_velocity_table(&table).unwrap();
    let mjcf = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/nao_left_arm.xml");
    let l = limits::from_mjcf(&mjcf, &v).unwrap();
    // the MJCF's range is the documented one
    let nao = nao_left_arm();
    assert_eq!(l.joints[0].lower, nao.joints[3].lower);
    assert_eq!(l.joints[0].upper, nao.joints[3].upper);
    // a joint of the table missing from the model is named
    std::fs::write(&table, "joint,max_velocity\nRKnee,2.0\n").unwrap();
    let v = limits::read_velocity_table(&table).unwrap();
    let e = limits::from_mjcf(&mjcf, &v).unwrap_err().to_string();
    assert!(e.contains("RKnee") && e.contains("LShoulderPitch"), "{e}");
    std::fs::write(&table, "joint,max_velocity\nLElbowRoll,-2\n").unwrap();
    assert!(limits::read_velocity_table(&table).is_err());
    // a trajectory joint the limits do not know is named
    let one = RobotLimits {
        source: "t".into(),
        joints: l.joints.clone(),
    };
    let e = one
        .check(&arm_trajectory(2.0), 0.5)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("LShoulderPitch") && e.contains("no limits"),
        "{e}"
    );
}

#[cfg(feature = "sim")]
#[test]
fn nao_limits_agree_with_the_arm_model_and_its_joint_table() {
    let nao = nao_left_arm();
    for (j, s) in nao.joints.iter().zip(crate::sim::JOINT_SPECS.iter()) {
        assert_eq!(j.name, s.name);
        assert_eq!(
            (j.lower, j.upper, j.max_velocity),
            (s.range.0, s.range.1, s.max_velocity)
        );
    }
}

#[cfg(feature = "sim")]
#[test]
fn the_simulated_arm_executes_the_export_and_records_its_joints() {
    use crate::robot::Robot;
    let t = arm_trajectory(2.0);
    let done = executed::execute(Robot::LeftArm, &t, 40.0).unwrap();
    // the left arm's model is collision-free
    assert!(done.contacts.is_empty());
    let rec = done.encoders;
    assert_eq!(rec.names, t.names);
    // one sample per tick of the 40 Hz clock over the 2 s motion
    assert_eq!(rec.times.len(), 80);
    // the servos follow: the elbow roll within 0.05 rad of the plan at the apex
    let apex = rec.position_at(1.0)[3];
    assert!((apex - t.position_at(1.0)[3]).abs() < 0.05, "{apex}");
    // another robot's joints are refused by name
    let mut other = t.clone();
    other.names[0] = "RShoulderPitch".into();
    let e = executed::execute(Robot::LeftArm, &other, 40.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("RShoulderPitch"), "{e}");
}

#[test]
fn a_contact_shallower_than_a_tenth_of_a_millimetre_is_touching_not_0_0_mm_deep() {
    let refusal = |depth_m: f64| {
        ExportError::Contact {
            time_s: 0.76,
            parts: ["LHand_fingers".into(), "torso".into()],
            depth_m,
            robot: "upper body".into(),
        }
        .to_string()
    };
    let shallow = refusal(0.00002);
    assert!(
        shallow.contains("(touching on the simulated upper body)"),
        "{shallow}"
    );
    assert!(!shallow.contains("0.0 mm"), "{shallow}");
    assert!(refusal(0.0003).contains("(0.3 mm deep on the simulated upper body)"));
}
