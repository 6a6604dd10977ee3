//! `simulate --gesture all`: one hierarchy for every gesture on the simulated arm,
//! end to end: the files, the report's sections and numbers that agree with each other, the
//! saved model, and the refusals.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use assert_cmd::Command;
use cosco_hsom::gesture::Gesture;
use cosco_hsom::hsom::GestureModel;

/// The one run of `simulate --gesture all` the tests read (3 demonstrations of each gesture,
/// seed 11, `--recognize`, not rendered): its output directory and its standard output.
fn all_run() -> &'static (PathBuf, String) {
    static RUN: OnceLock<(PathBuf, String)> = OnceLock::new();
    RUN.get_or_init(|| {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("simulate_all");
        let _ = std::fs::remove_dir_all(&out);
        let assert = Command::cargo_bin("simulate")
            .unwrap()
            .args([
                "--gesture",
                "all",
                "--count",
                "3",
                "--seed",
                "11",
                "--no-render",
                "--recognize",
                "--out",
            ])
            .arg(&out)
            .assert()
            .success();
        let stdout = String::from_utf8_lossy(&assert.get_output().stdout).to_string();
        (out, stdout)
    })
}

#[test]
fn simulate_all_learns_every_gesture_in_one_model_and_reports_fidelity_and_recognition() {
    let (out, stdout) = all_run();
    // `--gesture all`: the gestures taught together (the pointing gestures stand apart)
    let names: Vec<&str> = (Gesture::all(cosco_hsom::robot::Robot::LeftArm).iter())
        .map(|g| g.name)
        .collect();
    for g in &names {
        assert!(
            stdout.contains(&format!("{g:<14} held-out joint DTW")),
            "{stdout}"
        );
        for k in 1..=3 {
            assert!(out.join(format!("demos/{g}/demo_{k:02}.csv")).is_file());
        }
        assert!(out.join(format!("reproduction_{g}.csv")).is_file());
    }
    assert!(
        stdout.contains("recognition of 12 held-out demonstrations"),
        "{stdout}"
    );
    for f in ["model.bin", "confusion.png", "report.md", "report.json"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    assert!(
        !out.join("clip.gif").exists(),
        "--no-render renders nothing"
    );
    // the model is one multi-gesture model holding every gesture
    let model = GestureModel::load(&out.join("model.bin")).unwrap();
    assert_eq!(
        model.labels(),
        names.iter().map(|n| n.to_string()).collect::<Vec<_>>()
    );
    // the report: both tables, and confusion counts that add up to the queries
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("| gesture | shared joint DTW (rad/step) | alone joint DTW | shared / alone |")
    );
    assert!(md.contains("| gesture | reading-watch | wave | reach-point | salute | unknown |"));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let total = |key: &str| -> u64 {
        json[key]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|r| r.as_array().unwrap().iter().map(|c| c.as_u64().unwrap()))
            .sum()
    };
    assert_eq!(total("confusion"), 12);
    assert_eq!(total("nn_confusion"), 12);
    assert_eq!(json["fidelity"].as_array().unwrap().len(), 4);
    for f in json["fidelity"].as_array().unwrap() {
        assert_eq!(f["folds"], 3);
        assert!(f["shared_joint_dtw"].as_f64().unwrap() > 0.0);
    }
}

#[test]
fn simulate_all_refuses_one_demonstration_per_gesture_and_recorded_files() {
    let tmp = tempfile::tempdir().unwrap();
    let err = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--gesture", "all", "--count", "1", "--no-render"])
        .arg("--out")
        .arg(tmp.path().join("a"))
        .assert()
        .failure();
    let e = String::from_utf8_lossy(&err.get_output().stderr).to_string();
    assert!(e.contains("at least 2 demonstrations per gesture"), "{e}");
    let err = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--gesture", "all", "--no-render", "--demos"])
        .arg(tmp.path())
        .arg("--out")
        .arg(tmp.path().join("b"))
        .assert()
        .failure();
    let e = String::from_utf8_lossy(&err.get_output().stderr).to_string();
    assert!(e.contains("cosco train --demos DIR"), "{e}");
    // the paper's algorithm has no branches to give each gesture: refused before recording
    let config = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/table1.xml");
    let err = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--gesture", "all", "--no-render", "--config"])
        .arg(&config)
        .arg("--out")
        .arg(tmp.path().join("c"))
        .assert()
        .failure();
    let e = String::from_utf8_lossy(&err.get_output().stderr).to_string();
    assert!(e.contains("need algorithm = events"), "{e}");
    assert!(
        !tmp.path().join("c").join("demos").exists(),
        "nothing recorded"
    );
}

/// `--recognize`: each gesture's last held-out demonstration streamed into the recogniser of
/// the fold that did not learn it; the report says what it committed to and when; without
/// `--gesture all` the flag is refused.
#[test]
fn simulate_all_recognize_streams_the_held_out_gestures() {
    let (out, _) = all_run();
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains("| gesture shown | committed to | at sample |"),
        "{report}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("report.json")).unwrap()).unwrap();
    let streamed = json["streamed"].as_array().unwrap();
    assert_eq!(streamed.len(), 4);
    // the taught gestures, held out, are committed to before their end
    let right = (streamed.iter())
        .filter(|s| {
            s["committed"] == s["gesture"] && s["at_sample"].as_u64() < s["samples"].as_u64()
        })
        .count();
    assert!(right >= 3, "{streamed:?}");
    let err = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--gesture", "wave", "--recognize", "--no-render", "--out"])
        .arg(out.join("refused"))
        .assert()
        .failure()
        .get_output()
        .stderr
        .clone();
    assert!(String::from_utf8_lossy(&err).contains("--gesture all"));
}
