//! Upper-body demonstrations on the command line: their columns pick the robot's
//! configuration, limits and gestures without flags.

use predicates::prelude::*;

use crate::common::cosco;

/// Three nods of the upper body (its 14 joints from StandInit, the head pitching), 120
/// samples at 40 Hz each.
fn write_nods(dir: &std::path::Path) {
    use cosco_hsom::robot::Robot;
    std::fs::create_dir_all(dir).unwrap();
    let rest = Robot::UpperBody.posture("StandInit").unwrap();
    for k in 0..3 {
        let mut text = format!("time,{}\n", Robot::UpperBody.joint_names().join(","));
        for i in 0..120 {
            let s = i as f64 / 119.0;
            let mut q = rest.to_vec();
            q[1] += (0.3 + 0.01 * k as f64) * (std::f64::consts::PI * 2.0 * s).sin();
            q[0] += 0.05 * s;
            let values: Vec<String> = q.iter().map(f64::to_string).collect();
            text += &format!("{},{}\n", i as f64 * 0.025, values.join(","));
        }
        std::fs::write(dir.join(format!("demo_{:02}.csv", k + 1)), text).unwrap();
    }
}

#[test]
fn the_upper_bodys_demonstrations_take_its_configuration_and_its_limits_without_flags() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_nods(&d.join("ub"));
    let model = d.join("ub.bin");
    // the upper body's configuration (stateLength 14), not the left arm's 6
    cosco()
        .args(["train", "--demos"])
        .arg(d.join("ub"))
        .arg("--out")
        .arg(&model)
        .assert()
        .success()
        .stdout(predicate::str::contains("stateLength 14"));
    // the left arm's configuration, asked for, is still refused with the counts
    cosco()
        .args(["train", "--config", "configs/nao-gestures.xml", "--demos"])
        .arg(d.join("ub"))
        .arg("--out")
        .arg(d.join("arm.bin"))
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "14 state columns but the configured state length is 6",
        ));
    // exported without --robot: the upper body's limits, not "`HeadYaw` has no limits"
    let out = d.join("nod.csv");
    cosco()
        .args(["export", "--reproduction"])
        .arg(d.join("ub").join("demo_01.csv"))
        .args(["--format", "csv", "--out"])
        .arg(&out)
        .assert()
        .success()
        .stdout(predicate::str::contains(" of 14 joints"));
    assert!(out.exists());
}
