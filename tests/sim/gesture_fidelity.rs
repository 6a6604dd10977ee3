//! Gesture fidelity, end to end and headless: synthetic demonstrations recorded from the
//! simulated encoders -> CoSCo-HSOM with the paper's Table I -> reproduction from the initial
//! posture executed on the simulated arm -> metrics (docs/METRICS.md).
//!
//! The configuration is the recommended configs/nao-gestures.xml (the events extension).
//! Each gesture must meet the thresholds below; three negative controls must fail the same
//! checks: an untrained hierarchy (seeded initial weights, same configuration), a hierarchy
//! trained on the same demonstrations with their event order shuffled, and a hierarchy
//! trained on demonstrations of another gesture. The thresholds were measured (see
//! docs/METRICS.md, "Fidelity thresholds") and sit between the trained results and the
//! controls.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use crate::hsom_common;

use cosco_hsom::config::{load_config, HsomConfig};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::eval::{FoldInput, Method, MethodRun, Training};
use cosco_hsom::experiment::heldout::on_arm;
use cosco_hsom::experiment::{record_demonstrations, DemoSettings, Transition};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::metrics::{FidelityReport, MetricsParams};
use cosco_hsom::sim::{evaluate, NaoArm, Recording};
use hsom_common::shuffle_blocks;

/// Mean apex (key-pose) error over the demonstrations, rad: the reproduction gets close to
/// the pose the gesture is about (trained, seeds 1-10: 0.06-0.40).
const APEX_RAD: f64 = 0.45;
/// Mean final-posture error, rad: the reproduction comes back to the initial posture
/// (trained, seeds 1-10: 0.002-0.12, and 0.45 on wave seed 3; untrained 0.3-0.6).
const FINAL_RAD: f64 = 0.25;
/// Mean wrist-path DTW, mm per step: the hand follows the demonstrated path (trained, seeds
/// 1-10: 2.9-12.2 mm; untrained 13-29 mm; another gesture 60-105 mm).
const WRIST_DTW_MM: f64 = 15.0;
/// Velocity reversals of the reproduction (all joints) at most this factor times the
/// demonstrations' mean plus `REVERSALS_SLACK`: no more oscillation than a bound (demos 4-11;
/// trained 4-18; shuffled demonstrations 13-89).
const REVERSALS_FACTOR: f64 = 5.0;
const REVERSALS_SLACK: f64 = 20.0;
/// The reproduction lasts between 1/`DURATION_FACTOR` and `DURATION_FACTOR` times the
/// demonstrations (trained, seeds 1-10: 0.84-1.22, and 0.49 / 0.61 on wave seeds 5 and 7,
/// which leave out the waving; shuffled reach-point seed 3: 0.44).
const DURATION_FACTOR: f64 = 1.5;
/// Seeds of the demonstrations; a gesture passes when at least `MIN_PASSING` of them pass
/// every check, and every negative control must fail on every seed. Measured over seeds
/// 1-10 (40 runs, docs/METRICS.md): 37 pass; the three that fail are wave (seed 3 does not
/// come back, seeds 5 and 7 leave out the waving), as often with and without the exemplar
/// decoding of docs/ALGORITHM.md; the held-out gates are in tests/hierarchy_gates.rs.
const SEEDS: [u64; 3] = [1, 2, 3];
const MIN_PASSING: usize = 2;

fn failures(f: &FidelityReport) -> Vec<String> {
    eprintln!(
        "  joint {:.4} duration {:.2} apex {:.3} final {:.3} wrist {:.1} mm reversals {} (demos {:?}) moves {}",
        f.joint_dtw_rad_per_step.mean,
        f.duration_ratio.mean,
        f.apex_error_rad.mean,
        f.final_error_rad.mean,
        f.wrist_dtw_mm.map_or(f64::NAN, |w| w.mean),
        f.reproduction_smoothness.total_reversals,
        f.demo_smoothness
            .iter()
            .map(|s| s.total_reversals)
            .collect::<Vec<_>>(),
        f.reproduction_moves
    );
    let mut out = Vec::new();
    if f.apex_error_rad.mean > APEX_RAD {
        out.push(format!(
            "apex error {:.3} rad > {APEX_RAD}",
            f.apex_error_rad.mean
        ));
    }
    if f.final_error_rad.mean > FINAL_RAD {
        out.push(format!(
            "final-posture error {:.3} rad > {FINAL_RAD}",
            f.final_error_rad.mean
        ));
    }
    match &f.wrist_dtw_mm {
        Some(w) if w.mean <= WRIST_DTW_MM => {}
        Some(w) => out.push(format!("wrist-path DTW {:.1} mm > {WRIST_DTW_MM}", w.mean)),
        None => out.push("no wrist path".into()),
    }
    let demo_rev = f
        .demo_smoothness
        .iter()
        .map(|s| s.total_reversals as f64)
        .sum::<f64>()
        / f.demo_smoothness.len().max(1) as f64;
    let bound = REVERSALS_FACTOR * demo_rev + REVERSALS_SLACK;
    let rev = f.reproduction_smoothness.total_reversals as f64;
    if rev > bound {
        out.push(format!(
            "{rev} velocity reversals > {bound:.0} (demos: {demo_rev:.1})"
        ));
    }
    let d = f.duration_ratio.mean;
    if !(1.0 / DURATION_FACTOR..=DURATION_FACTOR).contains(&d) {
        out.push(format!(
            "duration ratio {d:.2} outside [1/{DURATION_FACTOR}, {DURATION_FACTOR}]"
        ));
    }
    if !f.reproduction_moves {
        out.push("the reproduction never moves".into());
    }
    out
}

fn table1() -> HsomConfig {
    load_config(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/nao-gestures.xml"
    )))
    .unwrap()
}

fn demos(arm: &NaoArm, g: &Gesture, seed: u64) -> Vec<Demonstration> {
    let settings = DemoSettings {
        encoder_noise: 0.001,
        ..DemoSettings::default()
    };
    record_demonstrations(arm, g, 3, seed, &settings, |_| {})
        .unwrap()
        .iter()
        .enumerate()
        .map(|(i, r)| r.to_demonstration(format!("{} #{i}", g.name)))
        .collect()
}

/// Learned from all of `d` (or only initialised), reproduced from the first, executed on the
/// arm and scored against all of them.
fn learn_and_reproduce(
    arm: &NaoArm,
    cfg: &HsomConfig,
    d: &[Demonstration],
    training: Training,
) -> MethodRun<Recording> {
    let input = FoldInput {
        config: Some(cfg),
        training,
        ..FoldInput::new(d, d)
    };
    on_arm(arm, Transition::Linear, Method::Hierarchy, &input).unwrap()
}

fn check_gesture(name: &str, other: &str) {
    let arm = NaoArm::load_default().unwrap();
    let cfg = table1();
    let g = Gesture::by_name(cosco_hsom::robot::Robot::LeftArm, name).unwrap();
    let og = Gesture::by_name(cosco_hsom::robot::Robot::LeftArm, other).unwrap();
    let mut passing = 0;
    let mut report = Vec::new();
    for seed in SEEDS {
        let d = demos(&arm, &g, seed);
        eprintln!("{name} seed {seed}: trained");
        let trained = learn_and_reproduce(&arm, &cfg, &d, Training::Trained);
        let f = failures(&trained.executed.fidelity);
        if f.is_empty() {
            passing += 1;
        }
        report.push(format!("seed {seed}: {f:?}"));

        // Negative control 1: the same configuration, untrained.
        eprintln!("{name} seed {seed}: untrained");
        let untrained = learn_and_reproduce(&arm, &cfg, &d, Training::Untrained);
        assert!(
            !failures(&untrained.executed.fidelity).is_empty(),
            "{name} seed {seed}: the UNTRAINED hierarchy passes the fidelity checks"
        );

        // Negative control 3: the same demonstrations with their event order shuffled (blocks
        // of 20 samples, about half a second, in a seeded random order).
        eprintln!("{name} seed {seed}: shuffled");
        let shuffled: Vec<Demonstration> = d.iter().map(|x| shuffle_blocks(x, seed)).collect();
        let sh = learn_and_reproduce(&arm, &cfg, &shuffled, Training::Trained);
        let scored = evaluate(
            Some(&arm),
            &d,
            &sh.executed.trace.qpos,
            &MetricsParams::default(),
        )
        .unwrap();
        assert!(
            !failures(&scored).is_empty(),
            "{name} seed {seed}: a hierarchy trained on shuffled demonstrations passes"
        );

        // Negative control 2: trained on another gesture, scored against this one's demonstrations.
        eprintln!("{name} seed {seed}: trained on {other}");
        let od = demos(&arm, &og, seed);
        let wrong = learn_and_reproduce(&arm, &cfg, &od, Training::Trained);
        let scored = evaluate(
            Some(&arm),
            &d,
            &wrong.executed.trace.qpos,
            &MetricsParams::default(),
        )
        .unwrap();
        assert!(
            !failures(&scored).is_empty(),
            "{name} seed {seed}: a hierarchy trained on {other} passes {name}'s checks"
        );
    }
    assert!(
        passing >= MIN_PASSING,
        "{name}: only {passing} of {} seeds pass: {report:?}",
        SEEDS.len()
    );
}

#[test]
fn reading_watch_is_reproduced_and_controls_fail() {
    check_gesture("reading-watch", "wave");
}

#[test]
fn wave_is_reproduced_and_controls_fail() {
    check_gesture("wave", "reach-point");
}

#[test]
fn reach_point_is_reproduced_and_controls_fail() {
    check_gesture("reach-point", "salute");
}

#[test]
fn salute_is_reproduced_and_controls_fail() {
    check_gesture("salute", "reading-watch");
}
