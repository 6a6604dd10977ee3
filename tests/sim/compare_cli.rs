//! `cosco compare` end to end: demonstrations made by `cosco demos`, both methods executed on
//! the simulated arm, the report with both columns and every metric, the csvs, the models and
//! the plots.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use assert_cmd::Command;
use cosco_hsom::gmr::load_model;
use cosco_hsom::sim::JOINT_NAMES;
use std::path::Path;

use crate::common::cosco;

fn make_demos(dir: &Path, gesture: &str) {
    cosco()
        .args(["demos", "--gesture", gesture, "--count", "3", "--seed", "2"])
        .arg("--out")
        .arg(dir)
        .assert()
        .success();
}

/// Fraction of pixels that are not the background white.
fn drawn_fraction(path: &Path) -> f64 {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8();
    let total = img.pixels().len() as f64;
    img.pixels().filter(|p| p.0 != [255, 255, 255]).count() as f64 / total
}

const METRIC_ROWS: [&str; 15] = [
    "joint DTW (rad/step)",
    "wrist-path DTW (mm/step)",
    "apex error (rad)",
    "final-posture error (rad)",
    "duration ratio",
    "normalized jerk",
    "velocity reversals, all joints",
    "velocity reversals per joint",
    "reproduction duration (s)",
    "postures produced",
    "clamped values",
    "training time (s)",
    "reproduction time (s)",
    "model size (bytes)",
    "needs as input",
];

#[test]
fn compare_writes_both_methods_every_metric_csvs_models_and_plots() {
    let tmp = tempfile::tempdir().unwrap();
    let demos = tmp.path().join("demos");
    let out = tmp.path().join("out");
    make_demos(&demos, "reading-watch");
    let assert = cosco()
        .args(["compare", "--components", "bic"])
        .arg("--demos")
        .arg(&demos)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&assert.get_output().stdout).to_string();
    assert!(
        stdout.contains("CoSCo-HSOM:") && stdout.contains("GMM/GMR:"),
        "{stdout}"
    );

    // report.md: one table, one column per method, every metric row with a value per method
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("| metric (mean / worst) | CoSCo-HSOM | GMM/GMR |"),
        "{md}"
    );
    for row in METRIC_ROWS {
        let line = md
            .lines()
            .find(|l| l.starts_with(&format!("| {row}")))
            .unwrap_or_else(|| panic!("no row '{row}' in\n{md}"));
        // "| name | a | b |": two values
        assert_eq!(line.matches(" | ").count(), 2, "{line}");
    }
    assert!(
        md.contains("DTW-aligned"),
        "GMR's needs must name DTW: {md}"
    );
    assert!(
        md.contains("time index"),
        "GMR's needs must name the time index: {md}"
    );

    // report.json: both methods with every metric and cost filled in
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let methods = json["methods"].as_array().unwrap();
    assert_eq!(methods.len(), 2);
    assert_eq!(methods[0]["name"], "CoSCo-HSOM");
    assert_eq!(methods[1]["name"], "GMM/GMR");
    for m in methods {
        let f = &m["fidelity"];
        for key in [
            "joint_dtw_rad_per_step",
            "wrist_dtw_mm",
            "apex_error_rad",
            "final_error_rad",
            "duration_ratio",
        ] {
            assert!(f[key]["mean"].as_f64().unwrap().is_finite(), "{key}: {f}");
            assert!(f[key]["worst"].as_f64().unwrap().is_finite(), "{key}: {f}");
        }
        assert_eq!(f["per_demo"].as_array().unwrap().len(), 3);
        assert!(m["train_s"].as_f64().unwrap() >= 0.0);
        assert!(m["reproduce_s"].as_f64().unwrap() >= 0.0);
        assert!(m["model_bytes"].as_u64().unwrap() > 0);
        assert!(!m["needs"].as_str().unwrap().is_empty());
    }
    // the baseline follows the demonstrations closely on this gesture
    let gmr = &methods[1]["fidelity"];
    assert!(gmr["joint_dtw_rad_per_step"]["mean"].as_f64().unwrap() < 0.15);
    // the model size is the saved file's size
    let gmr_bytes = std::fs::metadata(out.join("gmr_model.txt")).unwrap().len();
    assert_eq!(methods[1]["model_bytes"].as_u64().unwrap(), gmr_bytes);

    // csvs: time then the joint names, for both reproductions
    let header = format!("time,{}", JOINT_NAMES.join(","));
    for csv in ["reproduction.csv", "gmr_reproduction.csv"] {
        let text = std::fs::read_to_string(out.join(csv)).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next().unwrap(), header, "{csv}");
        let first: Vec<f64> = lines
            .next()
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(first.len(), 7, "{csv}");
        assert_eq!(first[0], 0.0, "{csv} starts at time 0");
        assert!(lines.count() > 40, "{csv}: at least a second at 40 Hz");
    }
    // both start from the same initial posture: demo 1's first row
    let demo1 = std::fs::read_to_string(demos.join("demo_01.csv")).unwrap();
    let d0: Vec<f64> = demo1
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .skip(1)
        .map(|v| v.parse().unwrap())
        .collect();
    for csv in ["reproduction.csv", "gmr_reproduction.csv"] {
        let text = std::fs::read_to_string(out.join(csv)).unwrap();
        let r0: Vec<f64> = text
            .lines()
            .nth(1)
            .unwrap()
            .split(',')
            .skip(1)
            .map(|v| v.parse().unwrap())
            .collect();
        for (a, b) in r0.iter().zip(&d0) {
            assert!((a - b).abs() < 0.01, "{csv}: {r0:?} vs {d0:?}");
        }
    }

    // the GMR model loads back
    let model = load_model(&out.join("gmr_model.txt")).unwrap();
    assert_eq!(model.columns(), JOINT_NAMES);

    // the plots exist and are not blank
    for png in [
        "fig3_gmr_training_data.png",
        "fig5_gmr_lshoulderpitch.png",
        "joints_compare.png",
        "wrist_compare.png",
    ] {
        let f = drawn_fraction(&out.join(png));
        assert!(f > 0.03, "{png}: only {:.1} % drawn", f * 100.0);
    }
}

#[test]
fn compare_with_a_fixed_component_count_uses_it() {
    let tmp = tempfile::tempdir().unwrap();
    let demos = tmp.path().join("demos");
    let out = tmp.path().join("out");
    make_demos(&demos, "wave");
    cosco()
        .args(["compare", "--components", "3"])
        .arg("--demos")
        .arg(&demos)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let model = load_model(&out.join("gmr_model.txt")).unwrap();
    assert_eq!(model.gmm().n_components(), 3);
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("3 Gaussian components"), "{md}");
}

#[test]
fn compare_refuses_columns_that_are_not_the_arm_naming_the_expected_ones() {
    let tmp = tempfile::tempdir().unwrap();
    let demos = tmp.path().join("demos");
    std::fs::create_dir_all(&demos).unwrap();
    for i in 0..2 {
        let mut text = String::from("time,a,b\n");
        for k in 0..50 {
            let t = k as f64 * 0.025;
            text += &format!("{t},{},{}\n", (t + i as f64).sin(), t.cos());
        }
        std::fs::write(demos.join(format!("d{i}.csv")), text).unwrap();
    }
    let out = cosco()
        .arg("compare")
        .arg("--demos")
        .arg(&demos)
        .arg("--out")
        .arg(tmp.path().join("out"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        err.contains("LShoulderPitch") && err.contains("LHand"),
        "{err}"
    );
    assert!(err.contains("\"a\""), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn compare_refuses_a_bad_component_count() {
    let tmp = tempfile::tempdir().unwrap();
    for bad in ["0", "many"] {
        let out = cosco()
            .args(["compare", "--components", bad])
            .arg("--demos")
            .arg(tmp.path())
            .assert()
            .failure();
        let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
        assert!(err.contains("--components") && err.contains(bad), "{err}");
    }
}

#[test]
fn compare_with_one_demonstration_says_the_baseline_needs_two() {
    let tmp = tempfile::tempdir().unwrap();
    let demos = tmp.path().join("demos");
    cosco()
        .args(["demos", "--count", "1"])
        .arg("--out")
        .arg(&demos)
        .assert()
        .success();
    let out = cosco()
        .arg("compare")
        .arg("--demos")
        .arg(&demos)
        .arg("--out")
        .arg(tmp.path().join("out"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(err.contains("at least 2 demonstrations"), "{err}");
    // refused before anything is trained or written
    assert!(!tmp.path().join("out").join("model.bin").exists());
}

#[test]
fn simulate_report_has_the_baseline_column_and_its_files() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let assert = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--gesture", "salute", "--no-render"])
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&assert.get_output().stdout).to_string();
    assert!(stdout.contains("GMM/GMR:"), "{stdout}");
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("| metric (mean / worst) | CoSCo-HSOM | GMM/GMR |"),
        "{md}"
    );
    for f in [
        "gmr_model.txt",
        "gmr_reproduction.csv",
        "fig3_gmr_training_data.png",
        "fig5_gmr_lshoulderpitch.png",
        "joints_compare.png",
        "wrist_compare.png",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
        assert!(
            md.contains(&format!("`{f}`")),
            "{f} not listed in the report"
        );
    }
}

#[test]
fn simulate_with_one_demonstration_notes_that_the_baseline_did_not_run() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    Command::cargo_bin("simulate")
        .unwrap()
        .args(["--count", "1", "--no-render"])
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        md.contains("| metric (mean / worst) | CoSCo-HSOM |\n"),
        "{md}"
    );
    assert!(
        md.contains("GMM/GMR baseline not run") && md.contains("at least 2 demonstrations"),
        "{md}"
    );
    assert!(!out.join("gmr_model.txt").exists());
}

#[test]
fn simulate_duration_retimes_the_reproduction_and_refuses_what_the_servos_cannot_follow() {
    let tmp = tempfile::tempdir().unwrap();
    let simulate = |args: &[&str], out: &Path| {
        let o = Command::cargo_bin("simulate")
            .unwrap()
            .args([
                "--gesture",
                "wave",
                "--no-render",
                "--no-variants",
                "--no-heldout",
            ])
            .args(args)
            .arg("--out")
            .arg(out)
            .output()
            .unwrap();
        (
            o.status.success(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let out = tmp.path().join("slow");
    let (ok, err) = simulate(&["--duration", "14"], &out);
    assert!(ok, "{err}");
    // 14 s of commanded postures at 40 Hz, said in the report
    let rows = std::fs::read_to_string(out.join("reproduction.csv")).unwrap();
    assert_eq!(rows.lines().count(), 1 + 14 * 40 + 1);
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("retimed to 14 s (--duration)"), "{md}");
    // too fast for the servos: refused, naming the shortest duration they follow
    let (ok, err) = simulate(&["--duration", "1"], &tmp.path().join("fast"));
    assert!(
        !ok && err.contains("the shortest this gesture can take is"),
        "{err}"
    );
    // with --gesture all, refused before anything is recorded
    let all = tmp.path().join("all");
    let o = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--gesture", "all", "--duration", "5", "--out"])
        .arg(&all)
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(!all.exists());
}

#[test]
fn simulate_point_at_aims_the_executed_reproduction_and_refuses_what_it_cannot_aim() {
    use cosco_hsom::aim::{longest_within, pointing_errors, Arm};
    use cosco_hsom::robot::Robot;
    let tmp = tempfile::tempdir().unwrap();
    let simulate = |args: &[&str], out: &Path| {
        let o = Command::cargo_bin("simulate")
            .unwrap()
            .args([
                "--no-render",
                "--no-variants",
                "--no-heldout",
                "--count",
                "3",
            ])
            .args(args)
            .arg("--out")
            .arg(out)
            .output()
            .unwrap();
        (
            o.status.success(),
            String::from_utf8_lossy(&o.stderr).to_string(),
        )
    };
    let target = [1.5, 1.2, 0.6];
    // the longest stretch of the executed encoder rows (40 Hz) whose pointing ray is within 3
    // degrees of the target, in seconds
    let pointing_within_3_deg = |out: &Path| {
        let executed = cosco_hsom::demos::read_csv(&out.join("reproduction.csv")).unwrap();
        let errors = pointing_errors(Robot::LeftArm, Arm::Left, &executed.rows, target);
        longest_within(&errors, 3.0) as f64 / 40.0
    };
    let aimed = tmp.path().join("aimed");
    let (ok, err) = simulate(
        &["--gesture", "point-left", "--point-at", "1.5,1.2,0.6"],
        &aimed,
    );
    assert!(ok, "{err}");
    let md = std::fs::read_to_string(aimed.join("report.md")).unwrap();
    assert!(
        md.contains("aimed at (1.5, 1.2, 0.6) m (--point-at): the left arm's pointing ray within"),
        "{md}"
    );
    let held = pointing_within_3_deg(&aimed);
    assert!(held >= 0.5, "pointed within 3 deg for {held} s");
    // the control: the same gesture unaimed does not point there
    let plain = tmp.path().join("plain");
    let (ok, err) = simulate(&["--gesture", "point-left"], &plain);
    assert!(ok, "{err}");
    assert_eq!(pointing_within_3_deg(&plain), 0.0);
    // behind the robot on its right: refused before anything is recorded, naming the closest
    // direction the left arm reaches
    let behind = tmp.path().join("behind");
    let (ok, err) = simulate(
        &["--gesture", "point-left", "--point-at", "-0.5,-2,0.1"],
        &behind,
    );
    assert!(!ok && err.contains("closest direction"), "{err}");
    assert!(err.contains("--point-at -0.5,-2,0.1"), "{err}");
    assert!(!behind.exists());
    // every gesture, and a gaze on the arm without a head: refused before anything is recorded
    for (args, says) in [
        (
            &["--gesture", "all", "--point-at", "1.5,1.2,0.6"][..],
            "not with --gesture all",
        ),
        (
            &["--gesture", "point-left", "--look-at", "1.5,1.2,0.6"][..],
            "--look-at turns the head",
        ),
    ] {
        let out = tmp.path().join("refused");
        let (ok, err) = simulate(args, &out);
        assert!(!ok && err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?}");
    }
}
