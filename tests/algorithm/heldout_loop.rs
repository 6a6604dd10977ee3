//! `cosco heldout --disturb` and `--goal-moves`: every fold of the undisturbed study run in
//! the kinematic loop. Held from phase 0.4 for a quarter of the duration, the hierarchy
//! finishes every fold where its undisturbed run ends, without a jump, keeping the wave's
//! swings; GMM/GMR, open loop by its clock, is the control in the same run: it jumps on
//! release. A goal moved half-way is reached. Bad values are refused naming the flag.

use cosco_hsom::demos::write_csv;

use crate::common::cosco;

/// Four waves of the demonstrator (seed 11), at 40 Hz, written to `dir`.
fn waves(dir: &std::path::Path) {
    for (i, demo) in crate::common::waves::waves(11).iter().enumerate() {
        write_csv(&dir.join(format!("demo_0{}.csv", i + 1)), demo).unwrap();
    }
}

/// The runs of `method` in the JSON's first in-loop section.
fn runs<'a>(
    doc: &'a serde_json::Value,
    section: usize,
    method: &str,
) -> Vec<&'a serde_json::Value> {
    doc["in_loop"][section]["gestures"][0]["folds"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|f| f.as_array().unwrap())
        .filter(|r| r["method"] == method)
        .collect()
}

#[test]
fn held_the_hierarchy_rejoins_and_the_open_loop_control_jumps() {
    let tmp = tempfile::tempdir().unwrap();
    let demos = tmp.path().join("wave");
    std::fs::create_dir(&demos).unwrap();
    waves(&demos);
    let json = tmp.path().join("loop.json");
    let out = cosco()
        .args([
            "heldout",
            "--no-in-sample",
            "--no-height-1",
            "--no-promp",
            "--no-dmp",
        ])
        .arg("--demos")
        .arg(&demos)
        .args([
            "--disturb",
            "hold:0.4:0.25",
            "--goal-moves",
            "0.5:0.1",
            "--json",
        ])
        .arg(&json)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("## In the loop: held from phase 0.4 for 0.25 of the duration"));
    assert!(text.contains("## In the loop: goal moved 0.1 x the diagonal at phase 0.5"));
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let num = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap();
    let held = runs(&doc, 0, "hierarchy");
    assert_eq!(held.len(), 4);
    for r in &held {
        assert_eq!(r["finished"], true);
        assert!(num(r, "final_error") <= 0.02, "{r}");
        assert!(num(r, "jump") <= 2.0, "{r}");
        let s = r["swings"].as_array().unwrap();
        assert!(
            s[0].as_u64() >= s[1].as_u64(),
            "the held wave keeps its swings: {r}"
        );
    }
    // the control: GMM/GMR by its clock jumps to where its clock has got to on release
    let gmr = runs(&doc, 0, "gmm_gmr");
    assert!(gmr.iter().any(|r| num(r, "jump") > 2.0), "{gmr:?}");
    // the goal moved half-way is reached; GMM/GMR takes no goal, and says why
    for r in runs(&doc, 1, "hierarchy") {
        assert!(num(r, "final_error") < 1e-6, "{r}");
        assert!(num(r, "jump") <= 2.0, "{r}");
    }
    assert!(runs(&doc, 1, "gmm_gmr")
        .iter()
        .all(|r| r["error"].is_string()));
    assert!(text.contains("- GMM/GMR: "), "{text}");
}

/// The kinematic loop cannot push a link: refused before the study runs, naming where
/// pushes run.
#[test]
fn a_push_in_the_kinematic_loop_is_refused_naming_where_pushes_run() {
    let out = cosco()
        .args(["heldout", "--demos", "nowhere"])
        .args(["--disturb", "push:0.4:LForeArm:0,0,-8:0.1"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--disturb") && err.contains("simulate"),
        "{err}"
    );
    assert!(
        err.contains("--loop closed") && err.contains("example heldout"),
        "{err}"
    );
}

#[test]
fn bad_disturbances_are_refused_naming_the_flag() {
    for (flag, value) in [
        ("--disturb", "hold:1.5:0.2"),
        ("--disturb", "spin:0.4:0.2"),
        ("--disturb", "move:0.1:0.1"),
        ("--goal-moves", "0.5:-1"),
        ("--goal-moves", "0.5"),
    ] {
        let out = cosco()
            .args(["heldout", "--demos", "nowhere", flag, value])
            .output()
            .unwrap();
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(flag), "{flag} {value}: {err}");
    }
}
