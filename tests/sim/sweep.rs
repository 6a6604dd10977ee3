//! Sweeps through the public API and the `cosco` binary, on tiny grids (one gesture, two
//! seeds, two demonstrations): shards cover the grid exactly once and merge to the unsharded
//! tables; a restarted sweep skips what is recorded, also after being killed; merge computes
//! the statistics of the run files and lists failed runs; bad specs and output directories
//! are refused before any run; a run on the upper body is the same pipeline at 14 joints, and
//! its gestures are checked against the upper body's.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::time::{Duration, Instant};

use assert_cmd::cargo::CommandCargoExt;
use cosco_hsom::gesture::Gesture;
use cosco_hsom::robot::Robot;
use cosco_hsom::sweep::merge::{TABLES_CSV, TABLES_MD, WINS_CSV};
use cosco_hsom::sweep::runner::{run_files, RUNS_DIR};
use cosco_hsom::sweep::{
    merge, method_name, run_sweep, Progress, RunRecord, Shard, SweepError, SweepOptions, SweepSpec,
};

const CONFIG: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/nao-gestures.xml");

/// A spec file in `dir` with `axes` (TOML lines) and, unless they name one, the shipped
/// configuration.
fn spec_file(dir: &Path, name: &str, axes: &str) -> PathBuf {
    let p = dir.join(name);
    let config = if axes.contains("config =") {
        String::new()
    } else {
        format!("config = [\"{CONFIG}\"]\n")
    };
    std::fs::write(
        &p,
        format!("[sweep]\nname = \"test\"\n[axes]\n{config}{axes}"),
    )
    .unwrap();
    p
}

/// Both methods as separate runs, in-sample: 1 gesture x 2 seeds x 2 methods = 4 runs.
const PAIRED: &str = "gesture = [\"salute\"]\nseed = [1, 2]\ncount = [2]\n\
                      method = [\"cosco-hsom\", \"gmr\"]\n";

fn options(shard: Shard) -> SweepOptions {
    SweepOptions {
        shard,
        threads: Some(2),
        retry_failed: false,
    }
}

/// Run a sweep, returning (to_run, skipped) as announced at its start.
fn sweep(spec: &SweepSpec, out: &Path, shard: Shard) -> Result<(usize, usize), SweepError> {
    let start = Mutex::new((0, 0));
    run_sweep(spec, out, &options(shard), &|p| {
        if let Progress::Start {
            to_run, skipped, ..
        } = p
        {
            *start.lock().unwrap() = (to_run, skipped);
        }
    })?;
    Ok(start.into_inner().unwrap())
}

fn run_ids(out: &Path) -> Vec<String> {
    run_files(out)
        .unwrap()
        .iter()
        .map(|f| RunRecord::read(f).unwrap().run_id)
        .collect()
}

fn read(p: PathBuf) -> String {
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn two_shards_cover_the_grid_once_and_merge_to_the_unsharded_tables() {
    let dir = tempfile::tempdir().unwrap();
    let spec = SweepSpec::load(&spec_file(dir.path(), "s.toml", PAIRED)).unwrap();
    let all: Vec<String> = spec.runs().into_iter().map(|r| r.id).collect();
    assert_eq!(all.len(), 4);

    let whole = dir.path().join("whole");
    assert_eq!(sweep(&spec, &whole, Shard::ALL).unwrap(), (4, 0));
    merge(&whole).unwrap();

    let sharded = dir.path().join("sharded");
    let mut per_shard = Vec::new();
    for i in 0..2 {
        let shard = Shard::new(i, 2, "test").unwrap();
        let before = run_ids_or_none(&sharded);
        assert_eq!(sweep(&spec, &sharded, shard).unwrap(), (2, 0));
        let added: Vec<String> = run_ids(&sharded)
            .into_iter()
            .filter(|id| !before.contains(id))
            .collect();
        per_shard.push(added);
    }
    // every run exactly once over the shards, index i modulo 2 in shard i
    assert_eq!(per_shard[0], vec![all[0].clone(), all[2].clone()]);
    assert_eq!(per_shard[1], vec![all[1].clone(), all[3].clone()]);
    merge(&sharded).unwrap();
    for f in [TABLES_MD, TABLES_CSV, WINS_CSV] {
        assert_eq!(
            read(sharded.join(f)),
            read(whole.join(f)),
            "{f} differs between the sharded and the unsharded sweep"
        );
    }
    // and the run files agree on every number but the times
    for id in &all {
        let a = RunRecord::read(&whole.join(RUNS_DIR).join(format!("{id}.json"))).unwrap();
        let b = RunRecord::read(&sharded.join(RUNS_DIR).join(format!("{id}.json"))).unwrap();
        assert_eq!(a.methods.len(), b.methods.len(), "{id}");
        for (a, b) in a.methods.iter().zip(&b.methods) {
            assert_eq!((&a.metrics, &a.detail), (&b.metrics, &b.detail), "{id}");
        }
    }
}

fn run_ids_or_none(out: &Path) -> Vec<String> {
    if out.join(RUNS_DIR).exists() {
        run_ids(out)
    } else {
        Vec::new()
    }
}

#[test]
fn merge_tables_hold_the_statistics_of_the_run_files_and_the_paired_wins() {
    let dir = tempfile::tempdir().unwrap();
    let spec = SweepSpec::load(&spec_file(dir.path(), "s.toml", PAIRED)).unwrap();
    let out = dir.path().join("out");
    sweep(&spec, &out, Shard::ALL).unwrap();
    let summary = merge(&out).unwrap();
    assert_eq!((summary.grid, summary.recorded), (4, 4));
    assert!(summary.failed.is_empty() && summary.missing.is_empty());

    // joint DTW of each method, from the run files
    let mut dtw: BTreeMap<&str, Vec<f64>> = BTreeMap::new();
    for f in run_files(&out).unwrap() {
        let r = RunRecord::read(&f).unwrap();
        assert!(r.error.is_none(), "{}", r.run_id);
        assert_eq!(r.config_sha256.len(), 64);
        for m in r.methods {
            dtw.entry(method_name(m.method))
                .or_default()
                .push(m.metrics["joint_dtw_rad_per_step"]);
        }
    }
    let csv = read(out.join(TABLES_CSV));
    for (method, v) in &dtw {
        assert_eq!(v.len(), 2);
        let median = (v[0] + v[1]) / 2.0;
        let q1 = v[0].min(v[1]) + 0.25 * (v[0] - v[1]).abs();
        let row = csv
            .lines()
            .find(|l| l.starts_with(&format!("joint_dtw_rad_per_step,all,all,{method},")))
            .unwrap_or_else(|| panic!("no 'all' row for {method}:\n{csv}"));
        let cells: Vec<f64> = row.split(',').skip(4).map(|c| c.parse().unwrap()).collect();
        assert_eq!(cells[0], 2.0, "{row}");
        assert!((cells[1] - median).abs() < 1e-12, "{row}: median {median}");
        assert!((cells[2] - median).abs() < 1e-12, "{row}: mean {median}");
        assert!((cells[3] - q1).abs() < 1e-12, "{row}: q1 {q1}");
    }
    // paired wins over both seeds: who has the lower joint DTW on each
    let (h, g) = (&dtw["cosco-hsom"], &dtw["gmr"]);
    let hsom_wins = h.iter().zip(g).filter(|(h, g)| h < g).count();
    let wins = read(out.join(WINS_CSV));
    let all_row = format!(
        "joint_dtw_rad_per_step,all,all,{hsom_wins},{},0",
        2 - hsom_wins
    );
    assert!(
        wins.lines().any(|l| l == all_row),
        "{all_row} not in\n{wins}"
    );
    let md = read(out.join(TABLES_MD));
    assert!(
        md.contains("## joint DTW (rad/step), lower is better"),
        "{md}"
    );
    assert!(md.contains("| seed | 2 |"), "{md}");
    for m in ["joint_dtw_rad_per_step", "duration_ratio"] {
        let png = out.join("plots").join(format!("{m}.png"));
        let img = image::open(&png).unwrap();
        assert!(img.width() > 500, "{}", png.display());
    }
}

#[test]
fn a_restarted_sweep_skips_recorded_runs_and_leaves_their_files_alone() {
    let dir = tempfile::tempdir().unwrap();
    let axes = "gesture = [\"salute\"]\nseed = [1, 2, 3]\ncount = [2]\nmethod = [\"cosco-hsom\"]\n";
    let spec = SweepSpec::load(&spec_file(dir.path(), "s.toml", axes)).unwrap();
    let out = dir.path().join("out");
    assert_eq!(sweep(&spec, &out, Shard::ALL).unwrap(), (3, 0));
    let files = run_files(&out).unwrap();
    let kept: Vec<(PathBuf, Vec<u8>)> = files[1..]
        .iter()
        .map(|f| (f.clone(), std::fs::read(f).unwrap()))
        .collect();
    std::fs::remove_file(&files[0]).unwrap();
    // only the missing run runs again
    assert_eq!(sweep(&spec, &out, Shard::ALL).unwrap(), (1, 2));
    for (f, bytes) in kept {
        assert_eq!(
            std::fs::read(&f).unwrap(),
            bytes,
            "{} rewritten",
            f.display()
        );
    }
    assert_eq!(run_files(&out).unwrap(), files);
    // nothing left to do
    assert_eq!(sweep(&spec, &out, Shard::ALL).unwrap(), (0, 3));
}

#[test]
fn a_failed_run_is_recorded_the_sweep_goes_on_and_merge_lists_it() {
    let dir = tempfile::tempdir().unwrap();
    // leave-one-out on 2 demonstrations: GMM/GMR has 1 to learn from on every fold and cannot
    // run; CoSCo-HSOM can
    let axes = "gesture = [\"salute\"]\nseed = [1]\ncount = [2]\nmethod = [\"both\"]\n\
                evaluation = [\"leave-one-out\"]\n";
    let spec = SweepSpec::load(&spec_file(dir.path(), "s.toml", axes)).unwrap();
    let out = dir.path().join("out");
    sweep(&spec, &out, Shard::ALL).unwrap();
    let r = RunRecord::read(&run_files(&out).unwrap()[0]).unwrap();
    assert!(r.failed());
    let gmr = r
        .methods
        .iter()
        .find(|m| method_name(m.method) == "gmr")
        .unwrap();
    assert!(gmr.error.as_deref().unwrap().contains("no fold"), "{gmr:?}");
    let hsom = r
        .methods
        .iter()
        .find(|m| method_name(m.method) == "cosco-hsom")
        .unwrap();
    assert!(hsom.error.is_none() && hsom.metrics.contains_key("joint_dtw_rad_per_step"));
    let summary = merge(&out).unwrap();
    assert_eq!(summary.failed.len(), 1, "{:?}", summary.failed);
    assert!(summary.failed[0].contains(&r.run_id));
    let md = read(out.join(TABLES_MD));
    let failed = md.split("## Failed runs").nth(1).unwrap();
    assert!(failed.contains(&r.run_id) && failed.contains("gmr"), "{md}");
    // a failed run is finished: skipped on restart unless asked
    let again = run_sweep(
        &spec,
        &out,
        &SweepOptions {
            retry_failed: true,
            ..options(Shard::ALL)
        },
        &|_| {},
    )
    .unwrap();
    assert_eq!((again.ran, again.skipped), (1, 0));
    assert_eq!(sweep(&spec, &out, Shard::ALL).unwrap(), (0, 1));
}

#[test]
fn an_output_directory_of_another_spec_is_refused_before_any_run() {
    let dir = tempfile::tempdir().unwrap();
    let axes = "gesture = [\"salute\"]\nseed = [1]\ncount = [2]\nmethod = [\"cosco-hsom\"]\n";
    let a = SweepSpec::load(&spec_file(dir.path(), "a.toml", axes)).unwrap();
    let b_axes = axes.replace("seed = [1]", "seed = [2]");
    let b = SweepSpec::load(&spec_file(dir.path(), "b.toml", &b_axes)).unwrap();
    let out = dir.path().join("out");
    sweep(&a, &out, Shard::ALL).unwrap();
    let before = run_ids(&out);
    let e = sweep(&b, &out, Shard::ALL).unwrap_err();
    assert!(matches!(e, SweepError::OutDir { .. }), "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("another spec") && msg.contains("a.toml"),
        "{msg}"
    );
    assert_eq!(run_ids(&out), before);
    // also when the manifest is gone: the run files carry the spec's hash
    std::fs::remove_file(out.join("sweep.json")).unwrap();
    let e = sweep(&b, &out, Shard::ALL).unwrap_err().to_string();
    assert!(e.contains("a run of another spec"), "{e}");
    assert_eq!(run_ids(&out), before);
}

/// `cosco sweep --spec SPEC --out OUT`, outside any SLURM job.
fn cosco_sweep(spec: &Path, out: &Path) -> Command {
    let mut c = Command::cargo_bin("cosco").unwrap();
    c.env_remove("SLURM_ARRAY_TASK_ID")
        .env_remove("SLURM_ARRAY_TASK_COUNT")
        .args(["sweep", "--spec"])
        .arg(spec)
        .arg("--out")
        .arg(out);
    c
}

#[test]
fn cli_bad_specs_and_shards_are_errors_before_any_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let good = spec_file(dir.path(), "good.toml", "seed = [1]\ncount = [2]\n");
    let cases = [
        (
            spec_file(dir.path(), "axis.toml", "speed = [1]\n"),
            vec![],
            "unknown field `speed`",
        ),
        (
            spec_file(dir.path(), "empty.toml", "gesture = []\n"),
            vec![],
            "axis `gesture` is empty",
        ),
        (
            spec_file(dir.path(), "cfg.toml", "config = [\"missing.xml\"]\n"),
            vec![],
            "'missing.xml'",
        ),
        (good.clone(), vec!["--shard", "2/2"], "out of range"),
    ];
    for (spec, extra, needle) in cases {
        let o = cosco_sweep(&spec, &out).args(&extra).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{}: {err}", spec.display());
        assert!(
            err.contains("Error:") && err.contains(needle),
            "{needle}: {err}"
        );
        assert!(
            !out.exists(),
            "{}: output written before the error",
            spec.display()
        );
    }
    // SLURM's variables choose the shard; out of range is an error too
    let o = cosco_sweep(&good, &out)
        .env("SLURM_ARRAY_TASK_ID", "5")
        .env("SLURM_ARRAY_TASK_COUNT", "2")
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("SLURM_ARRAY_TASK_ID"),
        "{err}"
    );
    assert!(!out.exists());
}

#[test]
fn cli_a_killed_sweep_resumes_without_redoing_finished_runs_or_corrupt_files() {
    let dir = tempfile::tempdir().unwrap();
    let axes = "gesture = [\"salute\", \"wave\"]\nseed = [1, 2, 3, 4]\ncount = [2]\n\
                method = [\"cosco-hsom\"]\n";
    let spec = spec_file(dir.path(), "s.toml", axes);
    let out = dir.path().join("out");
    let mut child = cosco_sweep(&spec, &out)
        .args(["--threads", "1"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // kill it (SIGKILL) as soon as the first run file is there; the bound only keeps a broken
    // build from hanging the suite
    let deadline = Instant::now() + Duration::from_secs(300);
    while run_files(&out).map_or(true, |f| f.is_empty()) && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let done: Vec<(PathBuf, Vec<u8>)> = run_files(&out)
        .unwrap()
        .into_iter()
        .map(|f| {
            let bytes = std::fs::read(&f).unwrap();
            // every file there is whole
            RunRecord::read(&f).unwrap();
            (f, bytes)
        })
        .collect();
    assert!(
        !done.is_empty() && done.len() < 8,
        "{} of 8 runs done",
        done.len()
    );

    let o = cosco_sweep(&spec, &out).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let announced = format!(
        "{} runs to do, {} already recorded",
        8 - done.len(),
        done.len()
    );
    assert!(err.contains(&announced), "'{announced}' not in {err}");
    for (f, bytes) in &done {
        assert_eq!(&std::fs::read(f).unwrap(), bytes, "{} redone", f.display());
    }
    assert_eq!(run_files(&out).unwrap().len(), 8);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("merged 8 of 8 runs (0 failed, 0 missing)"),
        "{stdout}"
    );
}

/// A spec file in `dir` with exactly `axes` (no configuration added: each robot's own).
fn bare_spec_file(dir: &Path, axes: &str) -> PathBuf {
    let p = dir.join("ub.toml");
    std::fs::write(&p, format!("[sweep]\nname = \"ub\"\n[axes]\n{axes}")).unwrap();
    p
}

#[test]
fn an_upper_body_run_records_its_robot_and_fourteen_joints() {
    let dir = tempfile::tempdir().unwrap();
    // the smallest run: one demonstration of a short gesture, in-sample, CoSCo-HSOM alone,
    // with the upper body's own configuration (no `config` axis)
    let axes = "robot = [\"upper-body\"]\ngesture = [\"nod\"]\nseed = [41]\ncount = [1]\n\
                method = [\"cosco-hsom\"]\n";
    let spec = SweepSpec::load(&bare_spec_file(dir.path(), axes)).unwrap();
    let out = dir.path().join("out");
    assert_eq!(sweep(&spec, &out, Shard::ALL).unwrap(), (1, 0));
    let files = run_files(&out).unwrap();
    assert_eq!(files.len(), 1);
    let name = files[0].file_name().unwrap().to_string_lossy().into_owned();
    assert!(
        name.starts_with("0000-upper-body-nod-s41-nao-upper-body-"),
        "{name}"
    );
    let text = read(files[0].clone());
    assert!(text.contains("\"robot\": \"upper-body\""), "{text}");
    let r = RunRecord::read(&files[0]).unwrap();
    assert_eq!(r.axes.robot, Robot::UpperBody);
    assert!(r.axes.config.ends_with("configs/nao-upper-body.xml"));
    assert!(!r.failed(), "{:?} {:?}", r.error, r.methods);
    let m = &r.methods[0];
    for key in [
        "joint_dtw_rad_per_step",
        "wrist_dtw_mm_per_step",
        "demo_swings",
    ] {
        assert!(m.metrics[key].is_finite(), "{key}: {:?}", m.metrics);
    }
    // the fidelity report of the 14 joints: reversals per joint, both wrists
    let detail = &m.detail;
    let per_joint = |v: &serde_json::Value| v["reversals"].as_array().map(Vec::len);
    assert_eq!(per_joint(&detail["reproduction_smoothness"]), Some(14));
    assert_eq!(per_joint(&detail["demo_smoothness"][0]), Some(14));
    assert!(detail["right_wrist_dtw_mm"]["mean"].is_f64(), "{detail}");
    // and the left arm's runs have 6 (the same code at another width)
    let la = spec_file(
        dir.path(),
        "la.toml",
        &axes
            .replace("robot = [\"upper-body\"]\n", "")
            .replace("nod", "salute"),
    );
    let la = SweepSpec::load(&la).unwrap();
    let la_out = dir.path().join("la");
    sweep(&la, &la_out, Shard::ALL).unwrap();
    let la_run = RunRecord::read(&run_files(&la_out).unwrap()[0]).unwrap();
    assert_eq!(la_run.axes.robot, Robot::LeftArm);
    assert!(!read(run_files(&la_out).unwrap()[0].clone()).contains("\"robot\""));
    assert_eq!(
        per_joint(&la_run.methods[0].detail["reproduction_smoothness"]),
        Some(6)
    );
    // merged: the robot is named among what every run shares
    merge(&out).unwrap();
    let md = read(out.join(TABLES_MD));
    assert!(
        md.contains("Same in every run: robot = upper-body, "),
        "{md}"
    );
}

#[test]
fn a_left_arm_gesture_on_the_upper_body_is_refused_naming_the_axis_and_the_gestures() {
    let dir = tempfile::tempdir().unwrap();
    for g in ["wave", "reach-point"] {
        let axes = format!("robot = [\"upper-body\"]\ngesture = [\"clap\", \"{g}\"]\n");
        let file = bare_spec_file(dir.path(), &axes);
        let e = SweepSpec::load(&file).unwrap_err().to_string();
        assert!(e.contains("ub.toml"), "{e}");
        assert!(
            e.contains("axis `gesture`") && e.contains(&format!("'{g}'")),
            "{e}"
        );
        assert!(e.contains("upper-body"), "{e}");
        for allowed in Gesture::names(Robot::UpperBody) {
            assert!(e.contains(allowed), "'{allowed}' not in: {e}");
        }
    }
    // the same gesture on the left arm is fine
    let file = bare_spec_file(dir.path(), "gesture = [\"wave\"]\n");
    assert!(SweepSpec::load(&file).is_ok());
}

#[test]
fn an_unknown_robot_is_refused_before_any_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let spec = bare_spec_file(dir.path(), "robot = [\"right-leg\"]\n");
    let o = cosco_sweep(&spec, &out).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    for needle in [
        "ub.toml",
        "axis `robot`",
        "`right-leg`",
        "left-arm, upper-body",
    ] {
        assert!(err.contains(needle), "'{needle}' not in: {err}");
    }
    assert!(!out.exists(), "output written before the error");
}
