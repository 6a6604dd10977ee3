//! The hierarchy carries the gesture, measured held out (leave-one-out over 4 demonstrations
//! recorded on the simulated arm): the recommended configs/nao-gestures.xml against the same
//! configuration at height 1, with negative controls (an untrained hierarchy; the same
//! demonstrations with their event order shuffled) that must fail the same gates.
//! Demonstration seed 21 (no setting was chosen on it). Figures: docs/ALGORITHM.md.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use crate::hsom_common;

use cosco_hsom::config::{load_config, HsomConfig};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::eval::{FoldInput, HeldOut, HeldOutSummary, Method, Training};
use cosco_hsom::experiment::heldout::{folds, hierarchy_held_out, on_arm};
use cosco_hsom::experiment::{record_demonstrations, DemoSettings, Transition};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::sim::NaoArm;

const SEED: u64 = 21;
const GESTURES: [&str; 4] = ["reading-watch", "wave", "reach-point", "salute"];

fn recommended() -> HsomConfig {
    load_config(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/nao-gestures.xml"
    )))
    .unwrap()
}

fn demos(arm: &NaoArm, name: &str) -> Vec<Demonstration> {
    let g = Gesture::by_name(cosco_hsom::robot::Robot::LeftArm, name).unwrap();
    let settings = DemoSettings {
        encoder_noise: 0.001,
        ..DemoSettings::default()
    };
    record_demonstrations(arm, &g, 4, SEED, &settings, |_| {})
        .unwrap()
        .iter()
        .enumerate()
        .map(|(i, r)| r.to_demonstration(format!("{name} #{i}")))
        .collect()
}

fn held_out(arm: &NaoArm, cfg: &HsomConfig, d: &[Demonstration], t: Training) -> HeldOutSummary {
    hierarchy_held_out(arm, cfg, d, t, Transition::Linear).unwrap()
}

/// The fidelity and timing gates one held-out summary must pass (docs/ALGORITHM.md; the
/// recommended configuration measured 0.10-0.15 rad/step, 5-10 mm, duration ratio 0.9-1.1 on
/// seeds 11-15): a reproduction that goes the demonstrated way at the demonstrated tempo.
fn failures(s: &HeldOutSummary) -> Vec<String> {
    let mut out = Vec::new();
    if s.joint_dtw_rad_per_step > 0.25 {
        out.push(format!("joint DTW {:.3} > 0.25", s.joint_dtw_rad_per_step));
    }
    if !s.wrist_dtw_mm.is_some_and(|w| w <= 15.0) {
        out.push(format!("wrist DTW {:?} > 15 mm", s.wrist_dtw_mm));
    }
    if !(0.7..=1.4).contains(&s.duration_ratio) {
        out.push(format!(
            "duration ratio {:.2} outside 0.7-1.4",
            s.duration_ratio
        ));
    }
    if s.final_error_rad > 0.3 {
        out.push(format!("final error {:.3} > 0.3", s.final_error_rad));
    }
    out
}

#[test]
fn the_hierarchy_beats_height_one_held_out_and_the_controls_fail() {
    let arm = NaoArm::load_default().unwrap();
    let cfg = recommended();
    let h1 = cfg.at_height(1).unwrap();
    let mut wins = 0;
    for g in GESTURES {
        let d = demos(&arm, g);
        let full = held_out(&arm, &cfg, &d, Training::Trained);
        let one = held_out(&arm, &h1, &d, Training::Trained);
        eprintln!(
            "{g}: height 4 {:.4} rad/step {:?} mm ratio {:.2}; height 1 {:.4} {:?}",
            full.joint_dtw_rad_per_step,
            full.wrist_dtw_mm,
            full.duration_ratio,
            one.joint_dtw_rad_per_step,
            one.wrist_dtw_mm
        );
        assert!(failures(&full).is_empty(), "{g}: {:?}", failures(&full));
        if full.joint_dtw_rad_per_step < one.joint_dtw_rad_per_step
            && full.wrist_dtw_mm.unwrap() < one.wrist_dtw_mm.unwrap()
        {
            wins += 1;
        }
        // negative controls
        let untrained = held_out(&arm, &cfg, &d, Training::Untrained);
        assert!(
            !failures(&untrained).is_empty(),
            "{g}: an untrained hierarchy passes the gates"
        );
        let sh: Vec<Demonstration> = d
            .iter()
            .map(|x| hsom_common::shuffle_blocks(x, SEED))
            .collect();
        // trained on shuffled demonstrations, scored against the real held-out ones
        let folds: Vec<_> = (0..d.len())
            .map(|i| {
                let train: Vec<Demonstration> = sh
                    .iter()
                    .enumerate()
                    .filter(|(j, _)| *j != i)
                    .map(|(_, x)| x.clone())
                    .collect();
                let input = FoldInput {
                    config: Some(&cfg),
                    ..FoldInput::new(&train, std::slice::from_ref(&d[i]))
                };
                on_arm(&arm, Transition::Linear, Method::Hierarchy, &input)
                    .unwrap()
                    .executed
                    .fidelity
            })
            .collect();
        let joint = folds
            .iter()
            .map(|f| f.joint_dtw_rad_per_step.mean)
            .sum::<f64>()
            / 4.0;
        let wrist = folds
            .iter()
            .map(|f| f.wrist_dtw_mm.unwrap().mean)
            .sum::<f64>()
            / 4.0;
        eprintln!("{g}: shuffled {joint:.4} rad/step {wrist:.1} mm");
        assert!(
            joint > 0.25 || wrist > 15.0,
            "{g}: a hierarchy trained on shuffled demonstrations passes ({joint:.3}, {wrist:.1} mm)"
        );
    }
    assert!(wins >= 3, "height 4 beats height 1 on {wins} of 4 gestures");
}

/// The fidelity gate against the paper's baseline, on the same folds: the median over
/// the four gestures of CoSCo-HSOM / GMM/GMR (means over the folds) at most 1.1 on joint and
/// wrist DTW (measured on seed 21: 1.02 and 1.04; docs/ALGORITHM.md), where an untrained
/// hierarchy is far outside it.
#[test]
fn held_out_fidelity_is_within_a_tenth_of_gmm_gmr_and_an_untrained_hierarchy_is_not() {
    let arm = NaoArm::load_default().unwrap();
    let cfg = recommended();
    let median = |v: Vec<f64>| cosco_hsom::stats::median(v).unwrap();
    let (mut joint, mut wrist, mut untrained) = (Vec::new(), Vec::new(), Vec::new());
    for g in GESTURES {
        let d = demos(&arm, g);
        let methods = [Method::Hierarchy, Method::GmmGmr];
        let all = folds(
            &arm,
            &d,
            &methods,
            Some(&cfg),
            Training::Trained,
            Transition::Linear,
        );
        let all = all.unwrap();
        assert!(all.iter().all(|f| f.scores(Method::GmmGmr).is_some()));
        let gmr = HeldOut::of(all).unwrap().gmr.unwrap();
        let hsom = held_out(&arm, &cfg, &d, Training::Trained);
        let none = held_out(&arm, &cfg, &d, Training::Untrained);
        joint.push(hsom.joint_dtw_rad_per_step / gmr.joint_dtw_rad_per_step);
        wrist.push(hsom.wrist_dtw_mm.unwrap() / gmr.wrist_dtw_mm.unwrap());
        untrained.push(none.joint_dtw_rad_per_step / gmr.joint_dtw_rad_per_step);
        eprintln!(
            "{g}: HSOM/GMR joint {:.2} wrist {:.2}; untrained {:.2}",
            joint.last().unwrap(),
            wrist.last().unwrap(),
            untrained.last().unwrap()
        );
    }
    let (j, w, u) = (median(joint), median(wrist), median(untrained));
    assert!(j <= 1.1, "joint DTW {j:.2}x GMM/GMR");
    assert!(w <= 1.1, "wrist DTW {w:.2}x GMM/GMR");
    assert!(u > 1.1, "an untrained hierarchy at {u:.2}x GMM/GMR passes");
}
