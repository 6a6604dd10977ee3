//! The arm in the loop: a stepper drives the simulated arm at 40 Hz from its encoders
//! (`sim::in_loop`), held by a hand, pushed by a force on a link, or given a new goal; and
//! `simulate --loop closed`. A held-out fold of the wave (seed 11): the hierarchy learns from
//! three demonstrations and runs from the fourth's initial posture.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo)

use assert_cmd::Command;
use cosco_hsom::condition::Conditions;
use cosco_hsom::config::load_config;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::dtw::{dtw_distance, euclidean, Band};
use cosco_hsom::experiment::{synthetic_demonstrations, DemoSettings};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::hsom::{Hsom, HsomStepper};
use cosco_hsom::metrics::{column_swings, diagonal};
use cosco_hsom::robot::Robot;
use cosco_hsom::sim::in_loop::{resistible_force, run_in_loop, ArmRun};
use cosco_hsom::sim::{execute_postures, ControllerConfig, NaoArm};
use cosco_hsom::stepper::{Amount, ByClock, Clock, Disturbance, Kind, Stepper};

/// LElbowRoll, the wave's swinging joint.
const ELBOW_ROLL: usize = 3;

struct Fold {
    arm: NaoArm,
    model: Hsom,
    target: Demonstration,
    diagonal: f64,
}

fn fold() -> Fold {
    let arm = NaoArm::load_default().unwrap();
    let cfg = load_config(std::path::Path::new("configs/nao-gestures.xml")).unwrap();
    let wave = Gesture::by_name(Robot::LeftArm, "wave").unwrap();
    let demos =
        synthetic_demonstrations(&arm, &wave, 4, 11, &DemoSettings::default(), |_| {}).unwrap();
    let model = cfg.fit(&demos[1..]).unwrap();
    Fold {
        diagonal: diagonal(&demos),
        target: demos[0].clone(),
        arm,
        model,
    }
}

fn largest_step(rows: &[Vec<f64>], from: usize) -> f64 {
    (from.max(1)..rows.len())
        .map(|k| euclidean(&rows[k], &rows[k - 1]))
        .fold(0.0, f64::max)
}

fn swings(rows: &[Vec<f64>]) -> usize {
    column_swings(rows, ELBOW_ROLL, cosco_hsom::eval::SWING_MIN_AMPLITUDE_RAD).unwrap()
}

/// `kind` from `at` s for `lasts` s.
fn at_s(at: f64, lasts: f64, kind: Kind) -> Disturbance {
    Disturbance {
        clock: Clock::Seconds,
        at,
        lasts,
        kind,
    }
}

fn run(f: &Fold, s: &mut dyn Stepper, d: &[Disturbance]) -> ArmRun {
    let initial = &f.target.rows[0];
    run_in_loop(&f.arm, &ControllerConfig::default(), s, initial, d, 60.0).unwrap()
}

fn hierarchy(f: &Fold) -> HsomStepper<&Hsom> {
    HsomStepper::new(&f.model, &f.target.rows[0], &Conditions::default(), None).unwrap()
}

/// A disturbance from phase 0.4 of the undisturbed run for `share` of it, in seconds.
fn window(plain: &ArmRun, share: f64) -> (f64, f64) {
    let n = (plain.recording.len() - 1) as f64;
    ((0.4 * n).round() / 40.0, (share * n).round() / 40.0)
}

#[test]
fn held_the_hierarchy_rejoins_without_a_jump_and_keeps_its_swings_a_replay_by_its_clock_does_not() {
    let f = fold();
    let mut undisturbed = hierarchy(&f);
    let plain = run(&f, &mut undisturbed, &[]);
    assert!(plain.finished);
    // undisturbed, the closed loop is its plan executed: no re-plan, the same DTW to within 2 %
    assert_eq!(undisturbed.replans(), 0);
    let plan = undisturbed.course().first_plan().to_vec();
    let open = execute_postures(&f.arm, &plan, 40.0).unwrap();
    let dtw = |rows: &[Vec<f64>]| {
        dtw_distance(rows, &f.target.rows, Band::None)
            .unwrap()
            .per_step()
    };
    let ratio = dtw(&plain.recording.qpos) / dtw(&open.qpos);
    assert!(
        (ratio - 1.0).abs() <= 0.02,
        "closed / open loop DTW {ratio}"
    );
    let (at, seconds) = window(&plain, 0.25);
    let hold = [at_s(at, seconds, Kind::Hold)];
    let mut s = hierarchy(&f);
    let held = run(&f, &mut s, &hold);
    assert!(held.finished, "the held run finishes");
    assert!(s.replans() > 0, "the hold made it re-plan");
    let end = plain.recording.qpos.last().unwrap();
    let final_error = euclidean(held.recording.qpos.last().unwrap(), end) / f.diagonal;
    assert!(final_error <= 0.02, "final error {final_error}");
    let release = held.held.iter().rposition(|h| *h).unwrap() + 1;
    let demo_step = largest_step(&f.target.rows, 1);
    let jump = largest_step(&held.recording.qpos, release) / demo_step;
    assert!(
        jump <= 2.0,
        "largest step after the release {jump} x the demonstration's"
    );
    let (kept, before) = (swings(&held.recording.qpos), swings(&plain.recording.qpos));
    assert!(kept >= before, "swings {kept} held, {before} undisturbed");
    // the negative control: the same plan commanded by its clock, whatever the encoders read,
    // skips what its clock ran through while the arm was held
    let columns: Vec<String> = Robot::LeftArm
        .joint_names()
        .iter()
        .map(|n| n.to_string())
        .collect();
    let plan = s.course().first_plan().to_vec();
    let mut replay = ByClock::new(columns, plan, "the replay");
    let by_clock = run(&f, &mut replay, &hold);
    let lost = swings(&by_clock.recording.qpos);
    assert!(
        lost < before,
        "by its clock: {lost} swings, {before} undisturbed"
    );
}

#[test]
fn a_push_moves_the_forearm_and_the_hierarchy_finishes_where_it_should() {
    let f = fold();
    let plain = run(&f, &mut hierarchy(&f), &[]);
    let (at, seconds) = window(&plain, 0.1);
    let push = |force| Kind::Push {
        body: "LForeArm".into(),
        force,
    };
    let pushed = [at_s(at, seconds, push([0.0, 0.0, -8.0]))];
    let pushed = run(&f, &mut hierarchy(&f), &pushed);
    assert!(pushed.finished);
    let moved = (pushed
        .recording
        .qpos
        .iter()
        .zip(&plain.recording.qpos)
        .zip(&pushed.held))
    .filter(|(_, h)| **h)
    .flat_map(|((a, b), _)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
    .fold(0.0, f64::max);
    assert!(
        moved >= 0.2,
        "the push moved the arm {moved} rad from its undisturbed run"
    );
    let end = plain.recording.qpos.last().unwrap();
    let final_error = euclidean(pushed.recording.qpos.last().unwrap(), end) / f.diagonal;
    assert!(final_error <= 0.02, "final error {final_error}");
    // without a force the same push changes nothing
    let none = [at_s(at, seconds, push([0.0; 3]))];
    let unpushed = run(&f, &mut hierarchy(&f), &none);
    assert_eq!(unpushed.recording.qpos, plain.recording.qpos);
}

#[test]
fn a_goal_moved_in_the_loop_is_reached_within_the_servos_static_error() {
    let f = fold();
    let plain = run(&f, &mut hierarchy(&f), &[]);
    let end = plain.recording.qpos.last().unwrap().clone();
    // 0.1 x the diagonal along it: each joint's extent over the demonstration
    let goal: Vec<f64> = (0..end.len())
        .map(|j| {
            let col = f.target.rows.iter().map(|r| r[j]);
            let (lo, hi) = col.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
            end[j] + 0.1 * (hi - lo)
        })
        .collect();
    let at = (0.5 * (plain.recording.len() - 1) as f64).round() / 40.0;
    let moved = [at_s(at, 0.0, Kind::Goal(Amount::Absolute(goal.clone())))];
    let r = run(&f, &mut hierarchy(&f), &moved);
    assert!(r.finished);
    let last = r.recording.qpos.last().unwrap();
    let off = (last.iter().zip(&goal))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(off <= 0.01, "{off} rad from the moved goal");
    let from = (at * 40.0).round() as usize + 1;
    let jump = largest_step(&r.recording.qpos, from) / largest_step(&f.target.rows, 1);
    assert!(
        jump <= 2.0,
        "largest step after the goal moved {jump} x the demonstration's"
    );
    // the control: the undisturbed run does not end there
    let plain_off = (end.iter().zip(&goal))
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(plain_off > 0.01);
}

#[test]
fn a_push_on_a_link_the_arm_lacks_is_refused_naming_the_links() {
    let f = fold();
    let push = [at_s(
        0.1,
        0.1,
        Kind::Push {
            body: "RForeArm".into(),
            force: [0.0, 0.0, -1.0],
        },
    )];
    let initial = &f.target.rows[0];
    let e = run_in_loop(
        &f.arm,
        &ControllerConfig::default(),
        &mut hierarchy(&f),
        initial,
        &push,
        60.0,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("RForeArm") && e.contains("LForeArm"), "{e}");
    for bad in [
        "1.0:LForeArm:0,0:0.1",
        "x:LForeArm:0,0,1:0.1",
        "1.0::0,0,1:0.1",
    ] {
        assert!(
            Disturbance::parse("push", bad, Clock::Seconds).is_err(),
            "{bad}"
        );
    }
    assert!(Disturbance::parse("hold", "-1:0.5", Clock::Seconds).is_err());
}

#[test]
fn simulate_loop_closed_writes_the_loop_and_refuses_disturbances_without_it() {
    let out = tempfile::tempdir().unwrap();
    let err = Command::cargo_bin("simulate")
        .unwrap()
        .args(["--hold", "1.0:0.5", "--out"])
        .arg(out.path())
        .assert()
        .failure()
        .get_output()
        .stderr
        .clone();
    let err = String::from_utf8_lossy(&err);
    assert!(err.contains("--loop closed"), "{err}");
    Command::cargo_bin("simulate")
        .unwrap()
        .args([
            "--gesture",
            "wave",
            "--seed",
            "11",
            "--no-render",
            "--no-variants",
        ])
        .args(["--no-heldout", "--loop", "closed", "--hold", "3.0:0.5"])
        .args(["--push", "5.0:LForeArm:0,0,-8:0.2", "--out"])
        .arg(out.path())
        .assert()
        .success();
    let csv = std::fs::read_to_string(out.path().join("in_loop.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(
        header.starts_with("time,disturbed,LShoulderPitch,"),
        "{header}"
    );
    assert!(header.ends_with(",LHand_command"), "{header}");
    assert!(csv
        .lines()
        .skip(1)
        .any(|l| l.split(',').nth(1) == Some("1")));
    let report = std::fs::read_to_string(out.path().join("report.md")).unwrap();
    assert!(report.contains("## In the loop"), "{report}");
    assert!(report.contains("LForeArm pushed with (0, 0, -8) N at 5.00 s for 0.20 s"));
    assert!(out.path().join("in_loop.png").exists());
    let json = std::fs::read_to_string(out.path().join("report.json")).unwrap();
    assert!(json.contains("\"in_loop\""));
}

/// `simulate --loop closed` on the wave with `flags`, into a directory that does not exist:
/// it fails, writes nothing, and says why on stderr.
fn refused(flags: &[&str]) -> String {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x");
    let a = ["--gesture", "wave", "--seed", "11", "--loop", "closed"];
    let got = Command::cargo_bin("simulate")
        .unwrap()
        .args(a)
        .args(flags)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(!got.status.success(), "{flags:?} ran");
    assert!(!out.exists(), "{flags:?} left {}", out.display());
    String::from_utf8_lossy(&got.stderr).into_owned()
}

#[test]
fn a_push_on_a_missing_link_or_a_goal_of_the_wrong_width_is_refused_before_the_job() {
    let e = refused(&["--push", "5.0:LFoot:0,0,-8:0.2"]);
    assert!(e.contains("LFoot") && e.contains("LForeArm"), "{e}");
    let e = refused(&["--goal-at", "6.0:1.4,0.3,-1.39"]);
    assert!(
        e.contains("3 values") && e.contains("LShoulderPitch"),
        "{e}"
    );
}

#[test]
fn a_goal_outside_the_joint_ranges_is_refused_naming_the_joint_value_and_range() {
    let e = refused(&["--goal-at", "4.0:5,0.5,-1.39,-1.01,0,0.25"]);
    assert!(e.contains("LShoulderPitch") && e.contains('5'), "{e}");
    assert!(e.contains("[-2.08567, 2.08567]"), "{e}");
}

#[test]
fn a_disturbance_after_the_motion_is_refused() {
    let e = refused(&["--hold", "30:1"]);
    assert!(e.contains("after the motion"), "{e}");
    let e = refused(&["--goal-at", "30:1.4,0.3,-1.39,-1.01,0,0.25"]);
    assert!(e.contains("after the motion"), "{e}");
}

/// The force the servos hold the forearm against, from their torque limits: a few newtons
/// (LShoulderPitch's 1.329 N m over some 0.1-0.2 m), so 8000 N throws the arm and 1 N does not.
#[test]
fn the_force_the_servos_hold_a_link_against_is_their_torque_over_its_lever() {
    let arm = NaoArm::load_default().unwrap();
    let stand = Robot::LeftArm.posture("StandInit").unwrap().to_vec();
    let down = [0.0, 0.0, -1.0];
    let (holds, joint) = resistible_force(&arm, &stand, "LForeArm", down)
        .unwrap()
        .unwrap();
    assert!((2.0..=40.0).contains(&holds), "{holds} N ({joint})");
    assert!(joint.starts_with('L'), "{joint}");
    // nearer the shoulder, a longer lever for nothing: the upper arm holds more
    let (bicep, _) = resistible_force(&arm, &stand, "LBicep", down)
        .unwrap()
        .unwrap();
    assert!(
        bicep > holds,
        "{bicep} N on the upper arm, {holds} N on the forearm"
    );
    assert!(resistible_force(&arm, &stand, "LFoot", down)
        .unwrap()
        .is_none());
    assert!(resistible_force(&arm, &stand, "LForeArm", [0.0; 3])
        .unwrap()
        .is_none());
}
