//! `simulate --robot upper-body`: the main job on the head and both arms (14 joints), end to
//! end without rendering, and the clip's camera `front` showing the arm that moves.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use assert_cmd::Command;
use cosco_hsom::experiment::report::contacts_text;
use cosco_hsom::experiment::{film, record_demonstrations, DemoSettings};
use cosco_hsom::gesture::{Gesture, Variation};
use cosco_hsom::render::RenderOptions;
use cosco_hsom::robot::{Robot, UPPER_BODY_JOINTS};
use cosco_hsom::sim::{NaoArm, Touch};

/// The header of a written trajectory: `time`, then its joints.
fn header(path: &std::path::Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let first = text.lines().next().unwrap_or_default();
    first.split(',').map(str::to_string).collect()
}

#[test]
fn the_main_job_runs_on_the_upper_body_with_14_joints_contacts_and_what_it_leaves_out() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let assert = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--robot", "upper-body", "--gesture", "clap", "--count", "2"])
        .arg("--no-render")
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&assert.get_output().stdout).to_string();
    assert!(
        stdout.contains("(left),") && stdout.contains("(right)"),
        "{stdout}"
    );

    // 14 joint columns after time, in NAOqi order, for the demonstrations and both methods
    let mut expected = vec!["time".to_string()];
    expected.extend(UPPER_BODY_JOINTS.iter().map(|j| j.to_string()));
    for f in [
        "demos/demo_01.csv",
        "reproduction.csv",
        "gmr_reproduction.csv",
    ] {
        assert_eq!(header(&out.join(f)), expected, "{f}");
    }
    for f in ["joints.png", "wrist.png", "wrist_right.png", "model.bin"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    assert!(
        !out.join("clip.gif").exists(),
        "--no-render renders nothing"
    );

    // a reproduction was executed: it moves, and every joint of it is scored
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("report.json")).unwrap()).unwrap();
    let hsom = &json["methods"][0];
    assert_eq!(hsom["name"], "CoSCo-HSOM");
    assert_eq!(hsom["fidelity"]["reproduction_moves"], true);
    assert!(
        hsom["postures"].as_u64().unwrap() > 40,
        "{}",
        hsom["postures"]
    );
    let reversals = hsom["fidelity"]["reproduction_smoothness"]["reversals"]
        .as_array()
        .unwrap();
    assert_eq!(reversals.len(), 14);
    let rows = std::fs::read_to_string(out.join("reproduction.csv")).unwrap();
    assert!(rows.lines().count() > 40);
    // both wrists scored, contacts listed for the demonstrations and both methods
    for m in json["methods"].as_array().unwrap() {
        assert!(
            m["fidelity"]["right_wrist_dtw_mm"]["mean"].is_number(),
            "{m}"
        );
        assert!(m["contacts"].is_array(), "{m}");
    }
    assert_eq!(json["methods"][1]["name"], "GMM/GMR");
    assert!(json["demos"][0]["contacts"].is_array());

    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.starts_with("# CoSCo-HSOM on the simulated Nao upper body: clap"));
    assert!(
        md.contains("`configs/nao-upper-body.xml (built in)`"),
        "{md}"
    );
    let row = md
        .lines()
        .find(|l| l.starts_with("| contacts between parts"))
        .unwrap_or_else(|| panic!("no contacts row:\n{md}"));
    assert_eq!(row.matches('|').count(), 4, "{row}: one cell per method");
    assert!(
        md.contains("| right wrist-path DTW, r_wrist (mm/step) |"),
        "{md}"
    );
    assert_eq!(md.matches("; contacts between parts: ").count(), 2, "{md}");
    assert!(md.contains("## Not run on this robot"), "{md}");
    assert!(md.contains("the before/after variants"), "{md}");
    assert!(!md.contains("## CoSCo-HSOM variants"), "{md}");
}

#[test]
fn the_upper_body_refuses_what_it_cannot_do_naming_what_is_allowed() {
    // --gesture all is the left arm's; a left-arm gesture is no upper-body gesture
    let tmp = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let a = Command::cargo_bin("simulate")
            .unwrap()
            .args(args)
            .arg("--out")
            .arg(tmp.path().join("out"))
            .assert()
            .failure();
        String::from_utf8_lossy(&a.get_output().stderr).to_string()
    };
    let e = run(&["--robot", "upper-body", "--gesture", "all", "--no-render"]);
    assert!(e.contains("--gesture all runs on the left arm"), "{e}");
    let e = run(&["--robot", "upper-body", "--gesture", "wave", "--no-render"]);
    for g in Gesture::names(Robot::UpperBody) {
        assert!(e.contains(g), "{e} lacks {g}");
    }
    // `all`, which the upper body refuses, is not offered; where wave is, is said
    assert!(!e.contains("or all"), "{e}");
    assert!(
        e.contains("'wave' is the left-arm's: give --robot left-arm"),
        "{e}"
    );
    let e = run(&["--robot", "torso"]);
    assert!(e.contains("left-arm, upper-body"), "{e}");
    // the left arm's list, with the robot whose gesture clap is
    let e = run(&["--gesture", "clap", "--no-render"]);
    assert!(e.contains("reading-watch") && e.contains("or all"), "{e}");
    assert!(
        e.contains("'clap' is the upper-body's: give --robot upper-body"),
        "{e}"
    );
    // a refused run leaves nothing behind (no empty OUT/demos/)
    assert!(!tmp.path().join("out").exists());
}

#[test]
fn contacts_read_none_or_each_touch_with_its_time_parts_and_depth() {
    assert_eq!(contacts_text(&[]), "none");
    let touch = |a: &str, b: &str, start_s, depth_m| Touch {
        parts: [a.into(), b.into()],
        start_s,
        end_s: start_s + 0.1,
        depth_m,
    };
    let text = contacts_text(&[
        touch("LForeArm", "torso", 0.5, 0.0018),
        touch("l_wrist", "r_wrist", 2.0, 0.0004),
    ]);
    assert_eq!(
        text,
        "0.50-0.60 s: LForeArm and torso, 1.8 mm deep; 2.00-2.10 s: l_wrist and r_wrist, 0.4 mm deep"
    );
    // shapes that meet, or nearly: touching, not "0.0 mm deep"
    let text = contacts_text(&[touch("LHand_fingers", "torso", 0.5, 0.00002)]);
    assert_eq!(text, "0.50-0.60 s: LHand_fingers and torso, touching");
}

/// The fraction of pixels in columns `cols` that differ between two frames.
fn changed(a: &image::RgbImage, b: &image::RgbImage, cols: std::ops::Range<u32>) -> f64 {
    let mut n = 0;
    for x in cols.clone() {
        for y in 0..a.height() {
            let (p, q) = (a.get_pixel(x, y), b.get_pixel(x, y));
            n += usize::from(p.0.iter().zip(q.0).any(|(u, v)| u.abs_diff(v) > 8));
        }
    }
    n as f64 / (cols.len() as f64 * a.height() as f64)
}

#[test]
fn the_front_camera_films_the_upper_body_and_the_waving_arm_on_the_robots_right() {
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let settings = DemoSettings {
        variation: Variation::none(),
        ..DemoSettings::default()
    };
    let wave = Gesture::by_name(Robot::UpperBody, "wave-right").unwrap();
    let rec = record_demonstrations(&arm, &wave, 1, 3, &settings, |_| {})
        .unwrap()
        .remove(0);
    // the frame where the right hand is highest (RShoulderPitch lowest), and the rest frame
    let top = (0..rec.len())
        .min_by(|&a, &b| rec.qpos[a][8].total_cmp(&rec.qpos[b][8]))
        .unwrap();
    let stride = top.max(1);
    let opts = RenderOptions {
        width: 160,
        height: 120,
        shadows: false,
        multisample: false,
        camera: Some("front".into()),
    };
    let clip = film(&arm, &rec, &opts, stride, |_, _| {}).unwrap();
    let frames: Vec<_> = clip.frames().map(|(_, f)| f.clone()).collect();
    assert!(frames.len() >= 2 && frames.len() <= 20, "{}", frames.len());
    let (rest, raised) = (&frames[0], &frames[1]);
    // facing the robot, its right arm is on the left of the picture: the wave changes the
    // left half, and the robot's left half (its left arm at rest) much less
    let (w, half) = (rest.width(), rest.width() / 2);
    let right_arm = changed(rest, raised, 0..half);
    let left_arm = changed(rest, raised, half..w);
    assert!(
        right_arm > 0.02,
        "the raised right arm changed {right_arm:.4}"
    );
    assert!(
        left_arm < right_arm / 3.0,
        "the resting left arm's half changed {left_arm:.4} beside {right_arm:.4}"
    );
    // control: the same measure sees no change between the rest frame and itself
    assert_eq!(changed(rest, rest, 0..w), 0.0);
}
