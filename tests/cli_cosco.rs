//! The `cosco` tool end to end: demos -> train -> inspect -> reproduce -> evaluate, and the
//! errors a user sees for bad input (named file, field or value; exit code 1, no panic).

use assert_cmd::Command;
use predicates::prelude::*;

fn cosco() -> Command {
    Command::cargo_bin("cosco").unwrap()
}

#[test]
fn demos_train_inspect_reproduce_evaluate() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let demos = d.join("demos");
    cosco()
        .args([
            "demos",
            "--gesture",
            "reach-point",
            "--count",
            "3",
            "--seed",
            "2",
            "--out",
        ])
        .arg(&demos)
        .assert()
        .success()
        .stdout(predicate::str::contains("demo_03.csv"));
    let model = d.join("model.txt");
    cosco()
        .arg("train")
        .arg("--demos")
        .arg(&demos)
        .arg("--out")
        .arg(&model)
        .assert()
        .success()
        .stdout(predicate::str::contains("16x16"));
    cosco()
        .arg("inspect")
        .arg(&model)
        .assert()
        .success()
        .stdout(
            predicate::str::contains("4 levels")
                .and(predicate::str::contains("QE"))
                .and(predicate::str::contains("lookup")),
        );
    let rep = d.join("rep.csv");
    cosco()
        .arg("reproduce")
        .arg("--model")
        .arg(&model)
        .arg("--initial-from")
        .arg(demos.join("demo_01.csv"))
        .arg("--out")
        .arg(&rep)
        .assert()
        .success();
    let text = std::fs::read_to_string(&rep).unwrap();
    assert!(text
        .starts_with("step,LShoulderPitch,LShoulderRoll,LElbowYaw,LElbowRoll,LWristYaw,LHand\n0,"));
    assert!(text.lines().count() > 20);
    let json = d.join("scores.json");
    cosco()
        .arg("evaluate")
        .arg("--reproduction")
        .arg(&rep)
        .arg("--demos")
        .arg(&demos)
        .arg("--json")
        .arg(&json)
        .assert()
        .success()
        .stdout(predicate::str::contains("wrist-path DTW (mm/step)"));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(v["joint_dtw_rad_per_step"]["mean"].as_f64().unwrap() < 0.2);
    // the same model from --initial
    cosco()
        .arg("reproduce")
        .arg("--model")
        .arg(&model)
        .args(["--initial", "1.4,0.3,-1.39,-1.01,0,0.25", "--out"])
        .arg(d.join("rep2.csv"))
        .assert()
        .success();
}

#[test]
fn bad_input_is_a_named_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("ragged.csv"), "a,b\n1,2\n3\n").unwrap();
    cosco()
        .arg("train")
        .arg("--demos")
        .arg(d.join("ragged.csv"))
        .arg("--out")
        .arg(d.join("m.bin"))
        .assert()
        .failure()
        .code(1)
        .stderr(
            predicate::str::contains("ragged.csv").and(predicate::str::contains("panicked").not()),
        );
    cosco()
        .arg("train")
        .arg("--demos")
        .arg(d.join("ragged.csv"))
        .arg("--out")
        .arg(d.join("m.json"))
        .assert()
        .failure()
        .stderr(predicate::str::contains(".bin (binary) or .txt"));
    std::fs::write(d.join("m.bin"), b"not a model").unwrap();
    cosco()
        .arg("inspect")
        .arg(d.join("m.bin"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("m.bin"));
    cosco()
        .args(["demos", "--gesture", "moonwalk", "--out"])
        .arg(d.join("x"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("reading-watch"));
    std::fs::write(d.join("bad.xml"), "<hsom><height>6</height>").unwrap();
    cosco()
        .arg("train")
        .arg("--config")
        .arg(d.join("bad.xml"))
        .arg("--demos")
        .arg(d.join("ragged.csv"))
        .arg("--out")
        .arg(d.join("m2.bin"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("bad.xml"));
}
