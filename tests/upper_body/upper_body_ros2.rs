//! ROS 2 and the whole upper body: a bag of the whole Nao's `sensor_msgs/msg/JointState` (26
//! joints, legs included, in the driver's order) imports to the upper body's 14 columns in
//! NAOqi order (`cosco demos import --robot upper-body`); an upper-body reproduction exports
//! as one JointTrajectory of its 14 joints, and with `--executed` the simulated upper body's
//! encoders come back in as the same 14 columns.

#![cfg(feature = "ros2")]

use cosco_hsom::export::Trajectory;
use cosco_hsom::robot::Robot;

use crate::common::cosco;

/// The whole Nao H25's joints as its ROS driver publishes them: legs and arms interleaved.
const WHOLE_NAO: [&str; 26] = [
    "HeadYaw",
    "HeadPitch",
    "LHipYawPitch",
    "LHipRoll",
    "LHipPitch",
    "LKneePitch",
    "LAnklePitch",
    "LAnkleRoll",
    "RHipYawPitch",
    "RHipRoll",
    "RHipPitch",
    "RKneePitch",
    "RAnklePitch",
    "RAnkleRoll",
    "LShoulderPitch",
    "LShoulderRoll",
    "LElbowYaw",
    "LElbowRoll",
    "LWristYaw",
    "RShoulderPitch",
    "RShoulderRoll",
    "RElbowYaw",
    "RElbowRoll",
    "RWristYaw",
    "LHand",
    "RHand",
];

/// The value joint `j` of the whole robot reads at sample `k`: distinct for every joint.
fn value(j: usize, k: usize) -> f64 {
    0.01 * j as f64 + 0.001 * k as f64
}

fn csv_rows(path: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

/// `cosco demos import --bag BAG --out OUT` with `extra` flags, which must succeed.
fn import(bag: &std::path::Path, out: &std::path::Path, extra: &[&str]) {
    cosco()
        .args(["demos", "import"])
        .args(extra)
        .arg("--bag")
        .arg(bag)
        .arg("--out")
        .arg(out)
        .assert()
        .success();
}

#[test]
fn a_whole_nao_joint_state_bag_imports_to_the_upper_bodys_14_columns() {
    let dir = tempfile::tempdir().unwrap();
    let names: Vec<String> = WHOLE_NAO.iter().map(|s| s.to_string()).collect();
    let times: Vec<f64> = (0..20).map(|k| k as f64 / 40.0).collect();
    let positions: Vec<Vec<f64>> = (0..20)
        .map(|k| (0..26).map(|j| value(j, k)).collect())
        .collect();
    let whole = Trajectory::new(names, times, positions).unwrap();
    let bag = dir.path().join("nao.mcap");
    std::fs::write(
        &bag,
        cosco_hsom::ros2::trajectory_mcap(&whole, Some(&whole)).unwrap(),
    )
    .unwrap();
    let out = dir.path().join("imported");
    import(&bag, &out, &["--robot", "upper-body"]);
    let (header, rows) = csv_rows(&out.join("nao.csv"));
    let upper = Robot::UpperBody.joint_names();
    assert_eq!(header[0], "time");
    assert_eq!(&header[1..], upper);
    assert_eq!(rows.len(), 20);
    for (c, name) in upper.iter().enumerate() {
        let j = WHOLE_NAO.iter().position(|n| n == name).unwrap();
        assert!((rows[7][1 + c] - value(j, 7)).abs() < 1e-12, "{name}");
    }
    // the default stays the left arm's six
    let six = dir.path().join("six");
    import(&bag, &six, &[]);
    let (header, _) = csv_rows(&six.join("nao.csv"));
    assert_eq!(&header[1..], Robot::LeftArm.joint_names());
}

#[cfg(feature = "sim")]
#[test]
fn an_upper_body_reproduction_exports_and_its_execution_imports_as_14_columns() {
    let dir = tempfile::tempdir().unwrap();
    let robot = Robot::UpperBody;
    let rest = robot.posture("StandInit").unwrap();
    let mut csv = format!("step,{}\n", robot.joint_names().join(","));
    for k in 0..60 {
        let mut p = rest.to_vec();
        p[1] = 0.2 * (k as f64 / 59.0 * std::f64::consts::PI).sin(); // a nod
        let row: Vec<String> = p.iter().map(|v| v.to_string()).collect();
        csv += &format!("{k},{}\n", row.join(","));
    }
    let rep = dir.path().join("nod.csv");
    std::fs::write(&rep, csv).unwrap();
    let bag = dir.path().join("nod.mcap");
    cosco()
        .args([
            "export",
            "--robot",
            "upper-body",
            "--format",
            "ros2",
            "--executed",
        ])
        .arg("--reproduction")
        .arg(&rep)
        .arg("--out")
        .arg(&bag)
        .assert()
        .success();
    let out = dir.path().join("back");
    import(&bag, &out, &["--robot", "upper-body"]);
    let (header, rows) = csv_rows(&out.join("nod.csv"));
    assert_eq!(&header[1..], robot.joint_names());
    // the executed nod: HeadPitch rises to about 0.2 rad and the arms hold StandInit
    let peak = rows.iter().map(|r| r[2]).fold(f64::MIN, f64::max);
    assert!((peak - 0.2).abs() < 0.05, "{peak}");
    let last = rows.last().unwrap();
    assert!((last[3] - rest[2]).abs() < 0.05, "{}", last[3]);
}
