//! The GMM/GMR baseline as the comparison runs it: idle trimming that ignores encoder noise,
//! and the baseline executed on the simulated arm from the initial posture.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use cosco_hsom::eval::{run_fold, Fitted, FoldInput, Method};
use cosco_hsom::experiment::ArmExecutor;
use cosco_hsom::experiment::{record_demonstrations, DemoSettings};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::gmr::{active_range, load_model, save_model, ComponentChoice, IdleTrim};
use cosco_hsom::sim::{NaoArm, Transition, LEAD_IN_PEAK_SPEED};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use std::f64::consts::PI;

/// Six joints: `idle` still samples, a raise and return over `len`, `idle_end` still; plus
/// independent encoder noise of `sigma` rad on every value.
fn noisy_gesture(idle: usize, len: usize, idle_end: usize, sigma: f64) -> Vec<Vec<f64>> {
    let rest = vec![1.4, 0.3, -1.39, -1.01, 0.0, 0.25];
    let mut rows = vec![rest.clone(); idle];
    rows.extend((0..len).map(|i| {
        let s = (PI * i as f64 / (len - 1) as f64).sin();
        let mut q = rest.clone();
        q[0] -= 1.5 * s;
        q[1] -= 0.5 * s;
        q[2] += 1.5 * s;
        q
    }));
    rows.extend(vec![rest; idle_end]);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let noise = Normal::new(0.0, sigma).unwrap();
    for r in rows.iter_mut() {
        for v in r.iter_mut() {
            *v += noise.sample(&mut rng);
        }
    }
    rows
}

#[test]
fn idle_trimming_ignores_one_milliradian_of_encoder_noise() {
    // 1 mrad on six joints at 40 Hz: per-step speeds of a still arm average ~0.14 rad/s,
    // as much as 5 % of this gesture's peak; the windowed speed must not count it as motion
    let rows = noisy_gesture(80, 160, 60, 0.001);
    let r = active_range(&rows, None, 0.025, &IdleTrim::default()).unwrap();
    assert!(r.start >= 72 && r.start <= 90, "start {r:?}");
    assert!(r.end >= 230 && r.end <= 248, "end {r:?}");
}

#[test]
fn baseline_runs_on_the_arm_from_the_initial_posture_and_follows_the_demonstrations() {
    let arm = NaoArm::load_default().unwrap();
    let g = Gesture::by_name(cosco_hsom::robot::Robot::LeftArm, "reading-watch").unwrap();
    let settings = DemoSettings {
        encoder_noise: 0.001,
        ..DemoSettings::default()
    };
    let recs = record_demonstrations(&arm, &g, 3, 5, &settings, |_| {}).unwrap();
    let demos: Vec<_> = recs
        .iter()
        .enumerate()
        .map(|(i, r)| r.to_demonstration(format!("demo {i}")))
        .collect();
    // the library's default (components by BIC over 1..=8); learned from all, scored against
    // all
    let input = FoldInput {
        gmr_components: ComponentChoice::Bic { min: 1, max: 8 },
        ..FoldInput::new(&demos, &demos)
    };
    let executor = ArmExecutor {
        arm: &arm,
        transition: Transition::Linear,
    };
    let (_, run) = run_fold(&[Method::GmmGmr], &input, &executor).remove(0);
    let run = run.unwrap();
    let Some(Fitted::GmmGmr {
        model,
        training,
        plan,
        ..
    }) = &run.fitted
    else {
        panic!("GMM/GMR's model is kept");
    };

    // executed from demos[0]'s first posture, at 40 Hz
    assert_eq!(run.executed.trace.rate_hz, 40.0);
    let start = &run.executed.trace.qpos[0];
    for (a, b) in start.iter().zip(&demos[0].rows[0]) {
        assert!((a - b).abs() < 0.01, "{start:?} vs {:?}", demos[0].rows[0]);
    }
    assert_eq!(plan.postures[0], demos[0].rows[0]);
    // the lead-in keeps to its speed limit
    for w in plan.postures[..=plan.lead_in].windows(2) {
        for (a, b) in w[0].iter().zip(&w[1]) {
            assert!((b - a).abs() * 40.0 <= LEAD_IN_PEAK_SPEED + 1e-9);
        }
    }
    // trimming worked on the noisy demonstrations: the learned duration is the motion, not
    // the whole recording
    let r = training.reference.unwrap();
    let whole = (demos[r].rows.len() - 1) as f64 * 0.025;
    assert!(
        training.duration < whole - 0.5,
        "learned {} s of a {whole} s recording",
        training.duration
    );
    // it follows the demonstrations: a tenth of a radian per step at most, the key pose
    // reached, the tempo within 25 %, and it settles where they do
    let f = &run.executed.fidelity;
    assert!(f.joint_dtw_rad_per_step.mean < 0.1, "{f:?}");
    assert!(f.apex_error_rad.mean < 0.2, "{f:?}");
    assert!(
        (f.duration_ratio.mean - 1.0).abs() < 0.25,
        "duration ratio {}",
        f.duration_ratio.mean
    );
    assert!(f.final_error_rad.mean < 0.15, "{f:?}");
    assert!(f.wrist_dtw_mm.unwrap().mean < 20.0, "{f:?}");

    // the model saves and loads back identical
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("gmr_model.txt");
    save_model(&p, model).unwrap();
    assert_eq!(load_model(&p).unwrap(), **model);
}

#[test]
fn baseline_needs_two_demonstrations() {
    let arm = NaoArm::load_default().unwrap();
    let g = Gesture::by_name(cosco_hsom::robot::Robot::LeftArm, "wave").unwrap();
    let recs = record_demonstrations(&arm, &g, 1, 1, &DemoSettings::default(), |_| {}).unwrap();
    let demos = vec![recs[0].to_demonstration("only")];
    let executor = ArmExecutor {
        arm: &arm,
        transition: Transition::Linear,
    };
    let input = FoldInput::new(&demos, &demos);
    let (_, run) = run_fold(&[Method::GmmGmr], &input, &executor).remove(0);
    let e = run.unwrap_err();
    assert!(e.contains("at least 2"), "{e}");
}
