//! The `cosco` tool end to end: demos -> train -> inspect -> reproduce -> evaluate, and the
//! errors a user sees for bad input (named file, field or value; exit code 1, no panic).
//! Recording demonstrations needs the simulator (feature `sim`); training, reproducing,
//! inspecting and evaluating 2-D data does not, and is tested in both builds.

use predicates::prelude::*;

use crate::common::cosco;

#[cfg(feature = "sim")]
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
                .and(predicate::str::contains("lookup"))
                .and(predicate::str::contains("binary model file by part"))
                .and(predicate::str::contains("traced chunks")),
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
    // the start and end against the demonstrations given
    let start_end = &v["start_end"];
    assert!(start_end["start_in_range"].is_boolean(), "{start_end}");
    assert!(
        start_end["end_spread"].as_f64().unwrap() > 0.0,
        "{start_end}"
    );
    assert_eq!(
        start_end["final_error"].as_f64(),
        v["final_error_rad"]["mean"].as_f64()
    );
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
    #[cfg(feature = "sim")]
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

/// The rows of a reproduction (or band) CSV after its `step` column.
fn postures(path: &std::path::Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').skip(1).map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// Three noisy strokes of a 2-D "S" (columns x, y), 60 samples each, no `time` column.
fn write_strokes(dir: &std::path::Path) {
    std::fs::create_dir_all(dir).unwrap();
    for k in 0..3 {
        let mut text = String::from("x,y\n");
        for i in 0..60 {
            let s = i as f64 / 59.0;
            let a = std::f64::consts::PI * (2.0 * s - 0.5);
            let x = a.cos() * (1.0 - 2.0 * s) + 0.01 * k as f64;
            let y = 2.0 * s + 0.02 * (k as f64 * s).sin();
            text += &format!("{x},{y}\n");
        }
        std::fs::write(dir.join(format!("s{k}.csv")), text).unwrap();
    }
}

/// The recommended configuration for the 2-D strokes of [`write_strokes`], quick to train.
fn strokes_config() -> String {
    std::fs::read_to_string("configs/nao-gestures.xml")
        .unwrap()
        .replace(
            "<stateLength>6</stateLength>",
            "<stateLength>2</stateLength>",
        )
        .replace(
            "<actionLength>6</actionLength>",
            "<actionLength>2</actionLength>",
        )
        .replace(
            "<trainingSteps>5000</trainingSteps>",
            "<trainingSteps>1500</trainingSteps>",
        )
}

#[test]
fn train_reproduce_inspect_evaluate_2d_data_in_either_build() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_strokes(&d.join("demos"));
    std::fs::write(d.join("c.xml"), strokes_config()).unwrap();
    let model = d.join("m.txt");
    cosco()
        .arg("train")
        .arg("--config")
        .arg(d.join("c.xml"))
        .arg("--demos")
        .arg(d.join("demos"))
        .arg("--out")
        .arg(&model)
        .assert()
        .success();
    cosco()
        .arg("inspect")
        .arg(&model)
        .assert()
        .success()
        .stdout(predicate::str::contains("stateLength 2"));
    let rep = d.join("rep.csv");
    cosco()
        .arg("reproduce")
        .arg("--model")
        .arg(&model)
        .arg("--initial-from")
        .arg(d.join("demos/s0.csv"))
        .arg("--out")
        .arg(&rep)
        .assert()
        .success();
    assert!(std::fs::read_to_string(&rep)
        .unwrap()
        .starts_with("step,x,y\n"));
    // resuming after the first half was executed (read back as x,y): the rest of it
    let rows = postures(&rep);
    let half = rows.len() / 2;
    let mut reading = String::from("x,y\n");
    for r in &rows[..half] {
        reading += &format!("{},{}\n", r[0], r[1]);
    }
    std::fs::write(d.join("reading.csv"), reading).unwrap();
    let rest = d.join("rest.csv");
    let resume = |out: &std::path::Path| {
        let mut c = cosco();
        c.arg("reproduce")
            .arg("--model")
            .arg(&model)
            .arg("--initial-from")
            .arg(d.join("demos/s0.csv"))
            .arg("--resume-from")
            .arg(d.join("reading.csv"))
            .arg("--out")
            .arg(out);
        c
    };
    resume(&rest).assert().success();
    let tail = postures(&rest);
    assert!(
        (half + tail.len() - 1).abs_diff(rows.len()) <= 1,
        "{half} + {} against {}",
        tail.len(),
        rows.len()
    );
    let (a, b) = (tail.last().unwrap(), rows.last().unwrap());
    assert!(
        (a[0] - b[0]).abs() + (a[1] - b[1]).abs() < 0.05,
        "{a:?} against {b:?}"
    );
    // a reading of other columns is named
    std::fs::write(d.join("reading.csv"), "x,z\n0,0\n1,1\n2,2\n").unwrap();
    resume(&rest)
        .assert()
        .failure()
        .stderr(predicate::str::contains("reading.csv").and(predicate::str::contains("columns")));
    let eval = cosco()
        .arg("evaluate")
        .arg("--reproduction")
        .arg(&rep)
        .arg("--demos")
        .arg(d.join("demos"))
        .assert()
        .success()
        .stdout(predicate::str::contains("joint DTW (data units/step):"));
    let out = String::from_utf8_lossy(&eval.get_output().stdout).to_string();
    assert!(out.contains("start speed (data units/s):"), "{out}");
    assert!(out.contains("demonstrations' end spread"), "{out}");
    // Without the arm's kinematics the wrist path is said to be missing, not silently dropped.
    assert_eq!(
        out.contains("wrist-path DTW (mm/step):"),
        cfg!(not(feature = "sim")),
        "{out}"
    );
}

/// Negative or impossible numbers for `--count`, `--noise`, `--seed` are answered with what is
/// allowed (not clap's "unexpected argument '-1'"), naming the option and the value (a noise
/// no encoder has is refused at `--noise`, not blamed on the demonstration it would spoil);
/// nothing is recorded.
#[cfg(feature = "sim")]
#[test]
fn negative_numbers_are_named_with_what_is_allowed() {
    let dir = tempfile::tempdir().unwrap();
    for (flag, value, allowed) in [
        ("--count", "-1", "at least 1"),
        ("--count", "0", "at least 1"),
        ("--noise", "-0.1", ">= 0"),
        ("--noise", "nan", ">= 0"),
        ("--noise", "5", "<= 0.1"),
        ("--seed", "-1", "whole number from 0"),
    ] {
        cosco()
            .args(["demos", flag, value, "--out"])
            .arg(dir.path().join("d"))
            .assert()
            .failure()
            .stderr(
                predicate::str::contains(flag)
                    .and(predicate::str::contains(format!("'{value}'")))
                    .and(predicate::str::contains(allowed))
                    .and(predicate::str::contains("unexpected argument").not()),
            );
    }
    assert!(!dir.path().join("d").exists());
}

/// `train` checks where the model goes before reading or training: a missing directory is
/// named at once, not after training.
#[test]
fn train_refuses_a_missing_output_directory_before_training() {
    let dir = tempfile::tempdir().unwrap();
    write_strokes(dir.path());
    let out = dir.path().join("no/such/dir/m.bin");
    cosco()
        .args(["train", "--demos"])
        .arg(dir.path())
        .arg("--out")
        .arg(&out)
        .assert()
        .failure()
        .stderr(
            predicate::str::contains("no/such/dir")
                .and(predicate::str::contains("does not exist"))
                .and(predicate::str::contains("saved").not()),
        );
    assert!(!out.exists());
}

/// A demonstration that never moves is named by its file in `evaluate`'s error (it was
/// "demonstration 1").
#[test]
fn a_motionless_demonstration_is_named_by_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_strokes(&d.join("demos"));
    let mut still = String::from("x,y\n");
    for _ in 0..60 {
        still += "0.5,0.5\n";
    }
    std::fs::write(d.join("demos/still.csv"), still).unwrap();
    let mut rep = String::from("step,x,y\n");
    for i in 0..60 {
        rep += &format!("{i},{},{}\n", i as f64 / 59.0, 1.0 - i as f64 / 59.0);
    }
    std::fs::write(d.join("rep.csv"), rep).unwrap();
    cosco()
        .args(["evaluate", "--reproduction"])
        .arg(d.join("rep.csv"))
        .arg("--demos")
        .arg(d.join("demos"))
        .assert()
        .failure()
        .stderr(predicate::str::contains("still.csv").and(predicate::str::contains("never moves")));
}

/// Every `cosco evaluate` error names the file it concerns: a reproduction of the arm's
/// joints too short to score on the arm, and one far outside their ranges.
#[cfg(feature = "sim")]
#[test]
fn evaluate_errors_name_the_reproduction_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let arm = "LShoulderPitch,LShoulderRoll,LElbowYaw,LElbowRoll,LWristYaw,LHand";
    let csv = |rows: &[&str]| format!("time,{arm}\n{}\n", rows.join("\n"));
    let arm_demo = [
        "0,1.4,0.3,-1.39,-1.01,0,0.25",
        "0.025,1.3,0.3,-1.39,-1.01,0,0.25",
        "0.05,1.2,0.3,-1.39,-1.01,0,0.25",
    ];
    let cases = [
        (vec![arm_demo[0]], "short_arm.csv", "1 sample"),
        (
            vec![arm_demo[0], "0.025,9,0.3,-1.39,-1.01,0,0.25"],
            "far_arm.csv",
            "LShoulderPitch = 9",
        ),
    ];
    for (rep_rows, name, cause) in cases {
        let demos = d.join(format!("demos_{name}"));
        std::fs::create_dir_all(&demos).unwrap();
        std::fs::write(demos.join("a.csv"), csv(&arm_demo)).unwrap();
        std::fs::write(d.join(name), csv(&rep_rows)).unwrap();
        cosco()
            .arg("evaluate")
            .arg("--reproduction")
            .arg(d.join(name))
            .arg("--demos")
            .arg(&demos)
            .assert()
            .failure()
            .stderr(
                predicate::str::contains(name)
                    .and(predicate::str::contains(cause))
                    .and(predicate::str::contains("panicked").not()),
            );
    }
}

#[test]
fn reproduce_meets_a_goal_and_a_via_point_exactly_and_refuses_bad_ones() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_strokes(&d.join("demos"));
    let model = d.join("m.bin");
    cosco()
        .args(["train", "--state-length-from-data", "--demos"])
        .arg(d.join("demos"))
        .arg("--out")
        .arg(&model)
        .assert()
        .success();
    let reproduce = |extra: &[&str], out: &std::path::Path| {
        let mut c = cosco();
        c.arg("reproduce")
            .arg("--model")
            .arg(&model)
            .args(["--initial", "0,0"])
            .args(extra)
            .arg("--out")
            .arg(out);
        c.assert()
    };
    let rows = postures;
    let (goal, via) = ([0.3, 2.1], [-0.4, 1.2]);
    let phase = 0.43;
    // the via-point read at its phase, between two rows
    let at = |r: &[Vec<f64>]| -> Vec<f64> {
        let x = phase * (r.len() - 1) as f64;
        let (i, a) = (x.floor() as usize, x - x.floor());
        (0..2)
            .map(|j| r[i][j] + a * (r[i + 1][j] - r[i][j]))
            .collect()
    };
    let miss = |r: &[Vec<f64>]| {
        let v = at(r);
        let last = r.last().unwrap();
        (0..2)
            .map(|j| (v[j] - via[j]).abs().max((last[j] - goal[j]).abs()))
            .fold(0.0, f64::max)
    };
    // negative control: the unconditioned reproduction misses them
    let plain = d.join("plain.csv");
    reproduce(&[], &plain).success();
    assert!(miss(&rows(&plain)) > 1e-3);
    let bent = d.join("bent.csv");
    let band = d.join("band.csv");
    let band_arg = band.to_str().unwrap();
    let conditions = [
        "--goal",
        "0.3,2.1",
        "--via",
        "0.43:-0.4,1.2",
        "--band",
        band_arg,
    ];
    reproduce(&conditions, &bent).success();
    let r = rows(&bent);
    assert_eq!(r[0], vec![0.0, 0.0]);
    assert!(miss(&r) < 1e-9, "missed by {}", miss(&r));
    // the band: one row per reproduction row, the reproduction's steps, lo <= value <= hi
    let text = std::fs::read_to_string(&band).unwrap();
    assert_eq!(text.lines().next().unwrap(), "step,x_lo,x_hi,y_lo,y_hi");
    let steps = |t: &str| -> Vec<String> {
        t.lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap().to_string())
            .collect()
    };
    let rep_text = std::fs::read_to_string(&bent).unwrap();
    assert_eq!(steps(&text), steps(&rep_text));
    for (b, p) in rows(&band).iter().zip(&r) {
        for j in 0..2 {
            assert!(
                b[2 * j] <= p[j] + 1e-12 && p[j] <= b[2 * j + 1] + 1e-12,
                "{b:?} {p:?}"
            );
        }
    }
    assert!(
        rows(&band).iter().any(|b| b[1] - b[0] > 1e-6),
        "a band of no width"
    );
    // bad conditions: a named error and nothing written
    let none = d.join("none.csv");
    for (args, says) in [
        (
            vec!["--goal", "1"],
            "the goal has 1 values; the model has 2 variables (x, y)",
        ),
        (vec!["--via", "1.5:0,0"], "phase is 1.5; allowed 0 to 1"),
        (
            vec!["--via", "0.5"],
            "'0.5' for '--via <VIA>': need PHASE:V1,V2,...",
        ),
        (
            vec!["--via", "0.5:0,0", "--via", "0.5:1,1"],
            "are both at phase 0.5 with different postures",
        ),
        (
            vec!["--goal", "0,nan"],
            "'0,nan' for '--goal <GOAL>': value 2 is 'nan'",
        ),
    ] {
        reproduce(&args, &none)
            .failure()
            .stderr(predicate::str::contains(says));
        assert!(!none.exists(), "{args:?} wrote a file");
    }
}

/// Every flag that takes a posture (`--initial`, `--goal`, `--via` of `reproduce` and
/// `export`) takes one whose first value is negative as written, `--goal -0.2,...` as
/// `--goal=-0.2,...`; a value that is not a number is named with its flag.
#[test]
fn postures_with_a_negative_first_value_are_taken_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_strokes(&d.join("demos"));
    let model = d.join("m.bin");
    cosco()
        .args(["train", "--state-length-from-data", "--demos"])
        .arg(d.join("demos"))
        .arg("--out")
        .arg(&model)
        .assert()
        .success();
    let reproduce = |args: &[&str], out: &std::path::Path| {
        cosco()
            .arg("reproduce")
            .arg("--model")
            .arg(&model)
            .args(args)
            .arg("--out")
            .arg(out)
            .assert()
    };
    let (spaced, joined) = (d.join("spaced.csv"), d.join("joined.csv"));
    reproduce(
        &[
            "--initial",
            "-0.01,0",
            "--goal",
            "-0.2,2.1",
            "--via",
            "0.43:-0.4,1.2",
        ],
        &spaced,
    )
    .success();
    reproduce(
        &[
            "--initial=-0.01,0",
            "--goal=-0.2,2.1",
            "--via=0.43:-0.4,1.2",
        ],
        &joined,
    )
    .success();
    let (a, b) = (
        std::fs::read(&spaced).unwrap(),
        std::fs::read(&joined).unwrap(),
    );
    assert_eq!(a, b);
    let r = postures(&spaced);
    assert_eq!(r[0], vec![-0.01, 0.0]);
    assert_eq!(r.last().unwrap(), &vec![-0.2, 2.1]);
    // negative control: another goal is another reproduction
    let other = d.join("other.csv");
    reproduce(&["--initial", "-0.01,0", "--goal", "-0.3,2.1"], &other).success();
    assert_ne!(std::fs::read(&other).unwrap(), a);
    // a value that is not a number: the flag, the text and the value named, nothing written
    let none = d.join("none.csv");
    for (args, flag, says) in [
        (vec!["--initial", "-0.01,x"], "--initial", "'-0.01,x'"),
        (
            vec!["--initial", "0,0", "--goal", "-0.2,x"],
            "--goal",
            "'-0.2,x'",
        ),
        (
            vec!["--initial", "0,0", "--via", "-x:0,0"],
            "--via",
            "'-x:0,0'",
        ),
    ] {
        reproduce(&args, &none).failure().stderr(
            predicate::str::contains(flag)
                .and(predicate::str::contains(says))
                .and(predicate::str::contains("unexpected argument").not()),
        );
        assert!(!none.exists(), "{args:?} wrote a file");
    }
    reproduce(&["--initial", "0,0", "--goal", "-0.2,x"], &none)
        .stderr(predicate::str::contains("value 2 is 'x'"));
    // `cosco export` reads its postures the same way
    cosco()
        .args(["export", "--model"])
        .arg(&model)
        .args([
            "--initial",
            "-0.01,0",
            "--goal",
            "-0.2,x",
            "--format",
            "csv",
        ])
        .arg("--out")
        .arg(&none)
        .assert()
        .failure()
        .stderr(
            predicate::str::contains("--goal")
                .and(predicate::str::contains("'-0.2,x'"))
                .and(predicate::str::contains("unexpected argument").not()),
        );
    assert!(!none.exists());
}

#[test]
fn train_from_a_saved_model_teaches_it_more_and_refuses_bad_input_leaving_it_untouched() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_strokes(&d.join("first"));
    write_strokes(&d.join("more"));
    let xml = strokes_config();
    std::fs::write(d.join("c.xml"), &xml).unwrap();
    let model = d.join("m.bin");
    let train = |args: &[&std::ffi::OsStr]| cosco().arg("train").args(args).assert();
    train(&[
        "--config".as_ref(),
        d.join("c.xml").as_os_str(),
        "--demos".as_ref(),
        d.join("first").as_os_str(),
        "--out".as_ref(),
        model.as_os_str(),
    ])
    .success();
    let before = std::fs::read(&model).unwrap();
    let updated = d.join("u.bin");
    train(&[
        "--from".as_ref(),
        model.as_os_str(),
        "--demos".as_ref(),
        d.join("more").as_os_str(),
        "--out".as_ref(),
        updated.as_os_str(),
    ])
    .success();
    assert_eq!(
        std::fs::read(&model).unwrap(),
        before,
        "the model updated from was written"
    );
    cosco()
        .arg("inspect")
        .arg(&updated)
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "learned from 6 demonstrations in 2 sittings",
        ));
    cosco()
        .arg("inspect")
        .arg(&model)
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "learned from 3 demonstrations in 1 sitting",
        ));
    // other columns: the file is named, nothing written, the model untouched
    std::fs::create_dir_all(d.join("other")).unwrap();
    std::fs::write(
        d.join("other/z.csv"),
        "y,x\n0,0\n0.5,0.2\n1,0.4\n1.5,0.1\n2,0\n",
    )
    .unwrap();
    let bad = d.join("bad.bin");
    train(&[
        "--from".as_ref(),
        model.as_os_str(),
        "--demos".as_ref(),
        d.join("other").as_os_str(),
        "--out".as_ref(),
        bad.as_os_str(),
    ])
    .failure()
    .stderr(predicate::str::contains("z.csv").and(predicate::str::contains("columns")));
    assert!(!bad.exists());
    // another configuration
    std::fs::write(
        d.join("c2.xml"),
        xml.replace("<seed>1</seed>", "<seed>2</seed>"),
    )
    .unwrap();
    train(&[
        "--from".as_ref(),
        model.as_os_str(),
        "--config".as_ref(),
        d.join("c2.xml").as_os_str(),
        "--demos".as_ref(),
        d.join("more").as_os_str(),
        "--out".as_ref(),
        bad.as_os_str(),
    ])
    .failure()
    .stderr(
        predicate::str::contains("c2.xml").and(predicate::str::contains("not the configuration")),
    );
    // a model file of a format version no longer read (the one before the oldest read)
    let mut old = before.clone();
    old[8] = old[8].wrapping_sub(2);
    std::fs::write(d.join("old.bin"), &old).unwrap();
    train(&[
        "--from".as_ref(),
        d.join("old.bin").as_os_str(),
        "--demos".as_ref(),
        d.join("more").as_os_str(),
        "--out".as_ref(),
        bad.as_os_str(),
    ])
    .failure()
    .stderr(predicate::str::contains("old.bin").and(predicate::str::contains("version")));
    assert!(!bad.exists());
    assert_eq!(std::fs::read(&model).unwrap(), before);
}
