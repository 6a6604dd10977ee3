//! Pointing and gaze at a target (`cosco reproduce/export --point-at --look-at`): the
//! held part of a held-out reproduction points within 2 degrees of the target for 0.5 s, and
//! within 3 degrees once executed on the simulated upper body, with no contact and within the
//! joint ranges; the camera looks within 1 degree (2 executed); the unconditioned
//! reproduction, the negative control, misses both; `cosco export` of the aimed gesture.

use cosco_hsom::aim::{gaze_errors, longest_within, pointing_errors, Aim, Arm};
use cosco_hsom::condition::Conditions;
use cosco_hsom::config::load_config;
use cosco_hsom::experiment::{record_demonstrations, DemoSettings};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::robot::Robot;
use cosco_hsom::sim::{execute_postures, NaoArm};

use crate::common::cosco;

/// Rows of 0.5 s at 40 Hz.
const HALF_SECOND: usize = 20;

#[test]
fn the_right_arm_points_and_the_head_looks_at_a_target_no_demonstration_pointed_at() {
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let g = Gesture::by_name(Robot::UpperBody, "point-right").unwrap();
    let demos: Vec<_> = record_demonstrations(&arm, &g, 4, 51, &DemoSettings::default(), |_| {})
        .unwrap()
        .iter()
        .map(|r| r.to_demonstration(g.name))
        .collect();
    let cfg = load_config(std::path::Path::new("configs/nao-upper-body.xml")).unwrap();
    let model = cfg.fit(&demos[..3]).unwrap();
    let initial = &demos[3].rows[0];
    let plain = model.reproduce(initial).unwrap().postures;
    // ahead, to the right and up: 1.5 m from the right shoulder
    let target = [1.2, -0.85, 0.45];
    let aim = Aim {
        point_at: Some(target),
        look_at: Some(target),
    };
    let ranges = Robot::UpperBody.ranges();
    let (conditions, solved) =
        cosco_hsom::aim::aim_conditions(Robot::UpperBody, &plain, &Conditions::default(), &aim)
            .unwrap();
    assert_eq!(solved.arm, Some(Arm::Right));
    let aimed = (model.reproduce_conditioned(initial, &conditions, Some(&ranges)))
        .unwrap()
        .postures;
    let right = |rows: &[Vec<f64>]| pointing_errors(Robot::UpperBody, Arm::Right, rows, target);
    assert!(longest_within(&right(&aimed), 2.0) >= HALF_SECOND);
    assert!(longest_within(&gaze_errors(&aimed, target), 1.0) >= HALF_SECOND);
    for r in &aimed {
        for (v, (lo, hi)) in r.iter().zip(&ranges) {
            assert!((lo..=hi).contains(&v), "{v} outside [{lo}, {hi}]");
        }
    }
    let executed = execute_postures(&arm, &aimed, 40.0).unwrap();
    assert!(longest_within(&right(&executed.qpos), 3.0) >= HALF_SECOND);
    assert!(longest_within(&gaze_errors(&executed.qpos, target), 2.0) >= HALF_SECOND);
    assert!(executed.contacts.is_empty(), "{:?}", executed.contacts);
    // the negative control: unconditioned, neither the arm nor the head is aimed there
    assert!(longest_within(&right(&plain), 2.0) < HALF_SECOND);
    assert!(longest_within(&gaze_errors(&plain, target), 1.0) < HALF_SECOND);

    // the same through the command line: reproduce, and export for NAOqi
    let dir = tempfile::tempdir().unwrap();
    let mut files = Vec::new();
    for (k, d) in demos[..3].iter().enumerate() {
        let path = dir.path().join(format!("demo_{k}.csv"));
        cosco_hsom::demos::write_csv(&path, d).unwrap();
        files.push(path);
    }
    let m = dir.path().join("m.bin");
    let out = cosco()
        .arg("train")
        .arg("--demos")
        .args(&files)
        .arg("--out")
        .arg(&m)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let initial_text: Vec<String> = initial.iter().map(f64::to_string).collect();
    // `cosco <args> --model m.bin --initial ... --out <out>`
    let run = |args: &[&str], out: &std::path::Path| {
        let mut c = cosco();
        c.args(args).arg("--model").arg(&m);
        c.args(["--initial", &initial_text.join(",")])
            .arg("--out")
            .arg(out);
        c.output().unwrap()
    };
    let ok = |out: &std::process::Output| {
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    let rep = dir.path().join("aimed.csv");
    let t = "1.2,-0.85,0.45";
    let out = run(&["reproduce", "--point-at", t, "--look-at", t], &rep);
    ok(&out);
    // the line says how long it points and looks
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        said.contains("the right arm points within 1 deg of (1.2, -0.85, 0.45) m for"),
        "{said}"
    );
    assert!(
        said.contains("the top camera looks within 1 deg of"),
        "{said}"
    );
    // `step`, then the 14 joints
    let text = std::fs::read_to_string(&rep).unwrap();
    let rows: Vec<Vec<f64>> = (text.lines().skip(1))
        .map(|l| l.split(',').skip(1).map(|v| v.parse().unwrap()).collect())
        .collect();
    assert!(longest_within(&right(&rows), 2.0) >= HALF_SECOND);
    let json = dir.path().join("aimed.json");
    ok(&run(
        &["export", "--format", "naoqi", "--point-at", t],
        &json,
    ));
    assert!(json.exists());
    // a target the arm cannot point at: refused, naming the closest direction
    let out = run(
        &["reproduce", "--point-at", "-0.5,2,0.1"],
        &dir.path().join("no.csv"),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("the right arm cannot aim at") && err.contains("closest direction"),
        "{err}"
    );
    assert!(!dir.path().join("no.csv").exists());
}
