//! Held-out (leave-one-out) evaluation: one fold per demonstration, each scored against the
//! held-out demonstration only, for CoSCo-HSOM and GMM/GMR; an untrained hierarchy (the
//! negative control) scores worse held-out than a trained one; the large-swing counter.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use std::sync::OnceLock;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use cosco_hsom::config::{load_config, HsomConfig};
use cosco_hsom::demos::{sample_period, Demonstration};
#[path = "../../examples/common/continuation.rs"]
mod continuation;
#[path = "../../examples/common/swing_folds.rs"]
mod swing;
use continuation::{continuation_folds, Disturbance};
use cosco_hsom::eval::{
    all_but, diagonal, FoldScores, HeldOut, Method, Training, SWING_MIN_AMPLITUDE_RAD,
};
use cosco_hsom::experiment::heldout::hierarchy_held_out;
use cosco_hsom::experiment::{leave_one_out, synthetic_demonstrations, DemoSettings, Transition};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::gmr::{active_range, IdleTrim};
use cosco_hsom::metrics::{column_swings, end_spread, end_tolerance, large_swings, start_speed};
use cosco_hsom::sim::NaoArm;
use cosco_hsom::sim::SWING_JOINT;
use swing::{swing_folds, swing_folds_png};

const COUNT: usize = 4;
const SEED: u64 = 11;

struct Fixture {
    arm: NaoArm,
    config: HsomConfig,
    demos: Vec<Demonstration>,
    heldout: HeldOut,
}

/// reading-watch, 4 demonstrations, seed 11, the default configuration; recorded and
/// evaluated once for every test of this file.
fn fixture() -> &'static Fixture {
    static F: OnceLock<Fixture> = OnceLock::new();
    F.get_or_init(|| {
        let arm = NaoArm::load_default().unwrap();
        let config = load_config(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml"),
        )
        .unwrap();
        let settings = DemoSettings {
            encoder_noise: 0.001,
            ..DemoSettings::default()
        };
        let g = Gesture::by_name(cosco_hsom::robot::Robot::LeftArm, "reading-watch").unwrap();
        let demos = synthetic_demonstrations(&arm, &g, COUNT, SEED, &settings, |_| {}).unwrap();
        let heldout = leave_one_out(&arm, &config, &demos, Transition::Linear).unwrap();
        Fixture {
            arm,
            config,
            demos,
            heldout,
        }
    })
}

/// The hierarchy's scores on a fold.
fn hsom(fold: &cosco_hsom::eval::Fold) -> &FoldScores {
    fold.scores(Method::Hierarchy).expect("the hierarchy ran")
}

/// Trimmed duration of a demonstration, seconds (docs/METRICS.md).
fn trimmed_duration(d: &Demonstration) -> f64 {
    let dt = sample_period(d);
    let r = active_range(&d.rows, None, dt, &IdleTrim::default()).unwrap();
    (r.len() - 1) as f64 * dt
}

#[test]
fn start_and_end_are_judged_against_each_folds_training_demonstrations() {
    let f = fixture();
    let h = &f.heldout;
    let diag = diagonal(&f.demos);
    let mut judged = (0, 0);
    for (i, fold) in h.folds.iter().enumerate() {
        let train = all_but(&f.demos, i);
        let fastest = train
            .iter()
            .filter_map(|d| start_speed(&d.rows, sample_period(d)))
            .fold(0.0, f64::max);
        let ends: Vec<&Vec<f64>> = train.iter().filter_map(|d| d.rows.last()).collect();
        let hsom = fold.scores(Method::Hierarchy).unwrap();
        let sequence = fold.scores(Method::NearestSequence).unwrap();
        let promp = fold.scores(Method::ProMP).unwrap();
        for (method, s) in [
            ("CoSCo-HSOM", hsom),
            ("nearest-sequence", sequence),
            ("ProMP", promp),
        ] {
            let e = s.start_end.as_ref().unwrap();
            assert_eq!(e.demo_start_speed_max, Some(fastest), "{method} fold {i}");
            assert!(
                (e.end_spread - end_spread(&ends)).abs() < 1e-15,
                "{method} fold {i}"
            );
            assert_eq!(e.end_tolerance, end_tolerance(e.end_spread, diag));
            assert_eq!(e.final_error, s.fidelity.final_error_rad.mean);
            assert_eq!(e.end_within_spread, e.final_error <= e.end_tolerance);
            // linear: every posture goes to the servos as it is
            let c = s.commanded.as_ref().unwrap();
            assert_eq!(c.postures, s.postures, "{method} fold {i}");
            assert_eq!(c.start_end.demo_start_speed_max, Some(fastest));
            assert!(
                c.normalized_jerk.is_some_and(|j| j > 0.0),
                "{method} fold {i}"
            );
            assert_eq!(c.start_end.end_tolerance, e.end_tolerance);
        }
        judged.0 += usize::from(hsom.start_end.unwrap().start_in_range);
        judged.1 += 1;
    }
    // the summary's fraction counts the folds
    assert_eq!(
        h.hsom.start_in_range,
        Some(judged.0 as f64 / judged.1 as f64)
    );
    assert!(h.hsom.commanded_normalized_jerk.is_some());
}

#[test]
fn one_fold_per_demonstration_each_scored_against_it_alone() {
    let f = fixture();
    let h = &f.heldout;
    assert_eq!(h.folds.len(), COUNT);
    assert_eq!(h.hsom.folds, COUNT);
    assert_eq!(h.gmr.as_ref().map(|g| g.folds), Some(COUNT));
    assert_eq!(h.sequence.as_ref().map(|s| s.folds), Some(COUNT));
    assert_eq!(h.promp.as_ref().map(|p| p.folds), Some(COUNT));
    let durations: Vec<f64> = f.demos.iter().map(trimmed_duration).collect();
    // the demonstrations differ in tempo, so scoring against the wrong one would show
    for w in durations.windows(2) {
        assert!((w[0] - w[1]).abs() > 0.05, "{durations:?}");
    }
    for (i, fold) in h.folds.iter().enumerate() {
        assert_eq!(fold.demonstration, f.demos[i].source);
        let hsom = fold.scores(Method::Hierarchy).unwrap();
        let gmr = fold.scores(Method::GmmGmr).unwrap_or_else(|| {
            let e = fold.error(Method::GmmGmr);
            panic!("fold {i}: GMM/GMR did not run: {e:?}")
        });
        let sequence = fold
            .scores(Method::NearestSequence)
            .expect("the nearest-sequence baseline ran");
        let promp = fold.scores(Method::ProMP).unwrap_or_else(|| {
            let e = fold.error(Method::ProMP);
            panic!("fold {i}: ProMP did not run: {e:?}")
        });
        for (method, s) in [
            ("CoSCo-HSOM", hsom),
            ("GMM/GMR", gmr),
            ("nearest-sequence", sequence),
            ("ProMP", promp),
        ] {
            let r = &s.fidelity;
            assert_eq!(r.per_demo.len(), 1, "{method} fold {i}");
            assert_eq!(r.demo_smoothness.len(), 1, "{method} fold {i}");
            let d = &r.per_demo[0];
            assert!(
                (d.demo_duration_s - durations[i]).abs() < 1e-9,
                "{method} fold {i}: scored against a demonstration of {} s, held out {} s",
                d.demo_duration_s,
                durations[i]
            );
            let expected = r.reproduction_duration_s / durations[i];
            assert!(
                (r.duration_ratio.mean - expected).abs() < 1e-9,
                "{method} fold {i}: duration ratio {} != {expected}",
                r.duration_ratio.mean
            );
            assert_eq!(
                s.swings.as_ref().unwrap().demo,
                column_swings(&f.demos[i].rows, SWING_JOINT, SWING_MIN_AMPLITUDE_RAD).unwrap()
            );
            assert!(r.wrist_dtw_mm.is_some(), "{method} fold {i}: no wrist path");
        }
    }
    // the summary is the mean over the folds
    let mean = h
        .folds
        .iter()
        .map(|f| hsom(f).fidelity.joint_dtw_rad_per_step.mean)
        .sum::<f64>()
        / COUNT as f64;
    assert!((h.hsom.joint_dtw_rad_per_step - mean).abs() < 1e-12);
    let (ph, pg) = h.paired().unwrap();
    assert_eq!(ph, h.hsom);
    assert_eq!(Some(pg), h.gmr.clone());
}

#[test]
fn an_untrained_hierarchy_scores_worse_held_out_than_a_trained_one() {
    let f = fixture();
    let u = hierarchy_held_out(
        &f.arm,
        &f.config,
        &f.demos,
        Training::Untrained,
        Transition::Linear,
    )
    .unwrap();
    let t = &f.heldout.hsom;
    eprintln!("trained {t:?}\nuntrained {u:?}");
    assert!(
        u.joint_dtw_rad_per_step > t.joint_dtw_rad_per_step,
        "joint DTW: untrained {} <= trained {}",
        u.joint_dtw_rad_per_step,
        t.joint_dtw_rad_per_step
    );
    assert!(
        u.wrist_dtw_mm.unwrap() > t.wrist_dtw_mm.unwrap(),
        "wrist DTW: untrained {:?} <= trained {:?}",
        u.wrist_dtw_mm,
        t.wrist_dtw_mm
    );
}

/// The drawn folds are the scored folds: the same reproductions, counts and DTW as the
/// leave-one-out of the fixture, with both traces of the counted joint, and a PNG.
#[test]
fn swing_folds_draw_the_scored_folds() {
    let f = fixture();
    let folds = swing_folds(&f.arm, &f.config, &f.demos, Transition::Linear).unwrap();
    assert_eq!(folds.len(), COUNT);
    for (i, (drawn, scored)) in folds.iter().zip(&f.heldout.folds).enumerate() {
        assert_eq!(drawn.held_out, i);
        assert_eq!(Some(&drawn.swings), hsom(scored).swings.as_ref());
        assert_eq!(
            drawn.joint_dtw,
            hsom(scored).fidelity.joint_dtw_rad_per_step.mean
        );
        let demo = &f.demos[drawn.held_out];
        assert_eq!(drawn.demo.len(), demo.rows.len());
        assert!(drawn
            .demo
            .iter()
            .zip(&demo.rows)
            .all(|(p, r)| p.1 == r[SWING_JOINT]));
        assert!(drawn.reproduction.windows(2).all(|w| w[1].0 > w[0].0));
    }
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("folds.png");
    swing_folds_png(&path, "reading-watch", &folds).unwrap();
    let png = std::fs::read(&path).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

/// Continuing a prefix: one fold per demonstration for the hierarchy and the nearest
/// sequence, each scored against its held-out demonstration alone, whose first half both
/// executed as given; a prefix share outside (0, 1) is refused.
#[test]
fn continuing_a_prefix_is_scored_against_the_held_out_demonstration() {
    let f = fixture();
    let (h, s) = continuation_folds(
        &f.arm,
        &f.config,
        &f.demos,
        0.5,
        Disturbance::None,
        Transition::Linear,
    )
    .unwrap();
    assert_eq!((h.len(), s.len()), (COUNT, COUNT));
    for (i, (a, b)) in h.iter().zip(&s).enumerate() {
        let d = trimmed_duration(&f.demos[i]);
        for (method, fold) in [("hierarchy", a), ("nearest sequence", b)] {
            let r = &fold.fidelity;
            assert_eq!(r.per_demo.len(), 1, "{method} fold {i}");
            assert!(
                (r.per_demo[0].demo_duration_s - d).abs() < 1e-9,
                "{method} fold {i}"
            );
            // the prefix is half the held-out demonstration, the continuation the rest
            assert!(
                fold.postures > f.demos[i].rows.len() / 2,
                "{method} fold {i}"
            );
        }
    }
    for bad in [0.0, 1.0, f64::NAN] {
        let e = continuation_folds(
            &f.arm,
            &f.config,
            &f.demos,
            bad,
            Disturbance::None,
            Transition::Linear,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("strictly between 0 and 1"), "{bad}: {e}");
    }
}

/// A disturbance is what the encoders read at the prefix's end: held still, or the path
/// retraced backwards; bad words are refused naming what is allowed.
#[test]
fn disturbances_hold_or_retrace_the_prefix() {
    let prefix: Vec<Vec<f64>> = (0..5).map(|i| vec![i as f64]).collect();
    let col = |rows: Vec<Vec<f64>>| rows.into_iter().map(|r| r[0]).collect::<Vec<_>>();
    assert_eq!(
        col(Disturbance::None.apply(&prefix)),
        [0.0, 1.0, 2.0, 3.0, 4.0]
    );
    assert_eq!(
        col(Disturbance::parse("hold:2").unwrap().apply(&prefix)),
        [0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0]
    );
    assert_eq!(
        col(Disturbance::parse("rewind:2").unwrap().apply(&prefix)),
        [0.0, 1.0, 2.0, 3.0, 4.0, 3.0, 2.0]
    );
    // never past the prefix's start
    assert_eq!(
        col(Disturbance::Rewind(9).apply(&prefix)),
        [0.0, 1.0, 2.0, 3.0, 4.0, 3.0, 2.0, 1.0, 0.0]
    );
    assert!(Disturbance::Rewind(3).apply(&[]).is_empty());
    assert!(Disturbance::Hold(3).apply(&[]).is_empty());
    for bad in ["hold", "hold:0", "push:3", "rewind:x", ""] {
        let e = Disturbance::parse(bad).unwrap_err().to_string();
        assert!(e.contains("none, hold:N or rewind:N"), "{bad}: {e}");
    }
}

#[test]
fn two_demonstrations_run_without_the_baseline_and_one_is_refused() {
    let f = fixture();
    let h = leave_one_out(&f.arm, &f.config, &f.demos[..2], Transition::Linear).unwrap();
    assert_eq!(h.folds.len(), 2);
    assert!(h.gmr.is_none() && h.promp.is_none());
    // the nearest-sequence baseline needs one demonstration to follow: it runs
    assert_eq!(h.sequence.as_ref().map(|s| s.folds), Some(2));
    for fold in &h.folds {
        let e = fold.error(Method::GmmGmr).unwrap();
        assert!(e.contains("at least 2"), "{e}");
        let e = fold.error(Method::ProMP).unwrap();
        assert!(e.contains("ProMP needs at least 2"), "{e}");
    }
    let e = leave_one_out(&f.arm, &f.config, &f.demos[..1], Transition::Linear)
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least 2") && e.contains("got 1"), "{e}");
}

fn sine(periods: f64, amplitude: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|k| amplitude * (std::f64::consts::TAU * periods * k as f64 / n as f64).sin())
        .collect()
}

#[test]
fn swings_of_a_sine_are_two_per_period() {
    let s = sine(3.0, 0.5, 360);
    assert_eq!(large_swings(&s, 0.3).unwrap(), 6);
    // a smaller amplitude than half the threshold: nothing
    assert_eq!(large_swings(&sine(3.0, 0.1, 360), 0.3).unwrap(), 0);
}

#[test]
fn noise_below_the_amplitude_adds_no_swings() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    // +-0.1 rad of noise at every sample: many velocity sign changes, no large swing
    let noisy: Vec<f64> = sine(3.0, 0.5, 360)
        .into_iter()
        .map(|v| v + rng.gen_range(-0.1..0.1))
        .collect();
    let sign_changes = noisy
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
        .count();
    assert!(sign_changes > 50, "{sign_changes}");
    assert_eq!(large_swings(&noisy, 0.3).unwrap(), 6);
    let still: Vec<f64> = (0..400).map(|_| rng.gen_range(-0.12..0.12)).collect();
    assert_eq!(large_swings(&still, 0.3).unwrap(), 0);
}
