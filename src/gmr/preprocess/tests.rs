//! Baseline pre-processing (trim, DTW alignment, resampling), the pipeline's input checks,
//! and one `invalid_*` test per parameter.

use crate::demos::{DemoError, Demonstration};
use crate::dtw::{dtw, Band};
use crate::gmr::preprocess::{align_to, choose_reference, preprocess};
use crate::gmr::{active_range, ComponentChoice, GmrError, GmrParams, IdleTrim};
use crate::robot::LEFT_ARM_JOINTS;
use std::f64::consts::PI;

/// A reading-watch-like 2-D gesture: `idle` still samples, a raise and return over `len`
/// samples, `idle_end` still samples.
fn gesture(idle: usize, len: usize, idle_end: usize) -> Vec<Vec<f64>> {
    let mut rows = vec![vec![1.5, 0.1]; idle];
    rows.extend((0..len).map(|i| {
        let s = (PI * i as f64 / (len - 1) as f64).sin();
        vec![1.5 - 1.2 * s, 0.1 + 0.4 * s * s]
    }));
    rows.extend(vec![vec![1.5, 0.1]; idle_end]);
    rows
}

fn demo(name: &str, rows: Vec<Vec<f64>>) -> Demonstration {
    Demonstration {
        source: name.into(),
        columns: vec!["pitch".into(), "roll".into()],
        time: None,
        rows,
    }
}

#[test]
fn trim_finds_the_motion_between_idle_parts() {
    let rows = gesture(40, 120, 25);
    let r = active_range(&rows, None, 0.025, &IdleTrim::default()).unwrap();
    // the motion occupies samples 40..160; trimming keeps it within a few samples
    assert!(r.start >= 38 && r.start <= 45, "{r:?}");
    assert!(r.end >= 155 && r.end <= 162, "{r:?}");
}

/// `rows` with white gaussian noise of deviation `sigma` on every value (seeded).
fn noisy(rows: &[Vec<f64>], sigma: f64, seed: u64) -> Vec<Vec<f64>> {
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let normal = Normal::new(0.0, sigma).unwrap();
    rows.iter()
        .map(|r| r.iter().map(|x| x + normal.sample(&mut rng)).collect())
        .collect()
}

/// Six joints: the 2-D gesture's two columns three times.
fn six_joints(rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
    rows.iter().map(|r| [r.as_slice(); 3].concat()).collect()
}

#[test]
fn trim_ignores_encoder_noise_at_rest() {
    // 3 mrad of noise on six joints: the noise alone moves the smoothed speed above the
    // relative threshold in the idle parts (the control below), yet the motion is found
    // where the clean recording has it
    let clean = six_joints(&gesture(80, 120, 60));
    let trim = IdleTrim::default();
    let want = active_range(&clean, None, 0.025, &trim).unwrap();
    for seed in 1..=5 {
        let rows = noisy(&clean, 0.003, seed);
        let speeds = crate::gmr::preprocess::smoothed_speeds(&rows, None, 0.025, 2);
        let peak = speeds.iter().cloned().fold(0.0, f64::max);
        let theta = trim.min_speed.max(trim.relative * peak);
        assert!(
            speeds[..70].iter().any(|&s| s > theta),
            "control: the noise should cross the speed threshold at rest (seed {seed})"
        );
        let got = active_range(&rows, None, 0.025, &trim).unwrap();
        assert!(
            got.start.abs_diff(want.start) <= 4 && got.end.abs_diff(want.end) <= 4,
            "seed {seed}: {got:?} vs clean {want:?}"
        );
    }
    // the floor scales with the noise: none without it
    assert!(crate::gmr::preprocess::noise_displacement(&clean) < 1e-3);
    assert!(crate::gmr::preprocess::noise_displacement(&noisy(&clean, 0.003, 9)) > 0.01);
}

#[test]
fn trim_uses_time_stamps_when_given() {
    let rows = gesture(10, 60, 10);
    let times: Vec<f64> = (0..rows.len()).map(|k| k as f64 * 0.025).collect();
    let a = active_range(&rows, Some(&times), 99.0, &IdleTrim::default());
    let b = active_range(&rows, None, 0.025, &IdleTrim::default());
    assert_eq!(a, b);
}

#[test]
fn motionless_sequence_has_no_active_part() {
    let rows = vec![vec![0.3, 0.2]; 50];
    assert_eq!(active_range(&rows, None, 0.025, &IdleTrim::default()), None);
    let one = vec![vec![0.3]];
    assert_eq!(active_range(&one, None, 0.025, &IdleTrim::default()), None);
}

#[test]
fn alignment_of_a_time_warped_copy_recovers_the_warp() {
    // x(u) on a fine grid; y is x read at a warped clock w(s) = s^1.5 (slow start, fast end)
    let n = 120;
    let f = |u: f64| vec![(2.0 * PI * u).sin(), (3.0 * PI * u).cos() * u];
    let x: Vec<Vec<f64>> = (0..n).map(|i| f(i as f64 / (n - 1) as f64)).collect();
    let warp = |s: f64| s.powf(1.5);
    let y: Vec<Vec<f64>> = (0..n).map(|i| f(warp(i as f64 / (n - 1) as f64))).collect();
    let al = dtw(&y, &x, Band::None).unwrap();
    // every pair (i, j) of the path: j/(n-1) ≈ w(i/(n-1))
    let worst = al
        .path
        .iter()
        .map(|&(i, j)| (j as f64 / (n - 1) as f64 - warp(i as f64 / (n - 1) as f64)).abs())
        .fold(0.0, f64::max);
    assert!(worst < 0.04, "worst warp error {worst}");
    // aligning y back onto x's clock gives x again, nearly
    let back = align_to(&x, &y, Band::None).unwrap();
    let err = back
        .iter()
        .zip(&x)
        .map(|(a, b)| crate::dtw::euclidean(a, b))
        .fold(0.0, f64::max);
    assert!(err < 0.1, "aligned copy off by {err}");
    // negative control: without alignment the warped copy is far from x
    let raw = y
        .iter()
        .zip(&x)
        .map(|(a, b)| crate::dtw::euclidean(a, b))
        .fold(0.0, f64::max);
    assert!(raw > 5.0 * err.max(0.05), "raw {raw} vs aligned {err}");
}

#[test]
fn reference_is_the_medoid() {
    let a = gesture(0, 100, 0);
    let b = gesture(0, 110, 0);
    let mut c = gesture(0, 90, 0);
    for r in &mut c {
        r[0] += 0.5; // an outlier
    }
    let seqs = vec![c, a, b];
    let r = choose_reference(&seqs, Band::None).unwrap();
    assert_ne!(r, 0);
}

#[test]
fn preprocess_trims_aligns_and_resamples() {
    let demos = vec![
        demo("d0", gesture(30, 120, 10)),
        demo("d1", gesture(5, 140, 40)),
        demo("d2", gesture(60, 100, 0)),
    ];
    let params = GmrParams::new().n_points(80).check().unwrap();
    let set = preprocess(&demos, &params).unwrap();
    assert_eq!(set.demos.len(), 3);
    assert!(set.demos.iter().all(|d| d.len() == 80));
    assert_eq!(set.times.len(), 80);
    assert_eq!(set.times[0], 0.0);
    let r = set.reference.unwrap();
    assert!((set.duration - (set.kept[r].len() - 1) as f64 * 0.025).abs() < 1e-12);
    // after alignment the three demonstrations nearly coincide at every point
    for k in 0..80 {
        let spread = crate::dtw::euclidean(&set.demos[0][k], &set.demos[2][k]);
        assert!(spread < 0.1, "k={k}: {spread}");
    }
    assert_eq!(set.points().len(), 240);
    assert_eq!(set.points()[0].len(), 3);
}

#[test]
fn fitted_baseline_reproduces_the_gesture() {
    let demos = vec![
        demo("d0", gesture(30, 120, 10)),
        demo("d1", gesture(5, 140, 40)),
        demo("d2", gesture(60, 100, 0)),
    ];
    let model = GmrParams::new()
        .components(ComponentChoice::Fixed(6))
        .check()
        .unwrap()
        .fit(&demos)
        .unwrap();
    let rep = model.reproduce(0.025).unwrap();
    let min_pitch = rep.iter().map(|p| p.mean[0]).fold(f64::MAX, f64::min);
    assert!((min_pitch - 0.3).abs() < 0.08, "apex pitch {min_pitch}");
    assert!(
        (rep[0].mean[0] - 1.5).abs() < 0.1,
        "start {}",
        rep[0].mean[0]
    );
    assert!((rep.last().unwrap().mean[0] - 1.5).abs() < 0.1);
}

#[test]
fn single_demonstration_is_refused() {
    let params = GmrParams::new().check().unwrap();
    let e = params.fit(&[demo("d0", gesture(5, 60, 5))]).unwrap_err();
    assert!(matches!(
        e,
        GmrError::TooFewDemonstrations {
            found: 1,
            required: 2
        }
    ));
}

#[test]
fn mismatched_columns_are_refused() {
    let mut b = demo("d1", gesture(5, 60, 5));
    b.columns = vec!["pitch".into(), "yaw".into()];
    let params = GmrParams::new().check().unwrap();
    let e = params.fit(&[demo("d0", gesture(5, 60, 5)), b]).unwrap_err();
    assert!(matches!(e, GmrError::Demo(DemoError::ColumnsDiffer { .. })));
}

#[test]
fn mismatched_widths_are_refused() {
    let mut b = demo("d1", gesture(5, 60, 5));
    b.rows[3].pop();
    let params = GmrParams::new().check().unwrap();
    let e = params.fit(&[demo("d0", gesture(5, 60, 5)), b]).unwrap_err();
    assert!(matches!(
        e,
        GmrError::Demo(DemoError::RowWidth { sample: 3, .. })
    ));
}

#[test]
fn motionless_demonstration_is_refused_by_name() {
    let still = demo("still.csv", vec![vec![1.5, 0.1]; 50]);
    let params = GmrParams::new().check().unwrap();
    let e = params
        .fit(&[demo("d0", gesture(5, 60, 5)), still])
        .unwrap_err();
    assert!(matches!(e, GmrError::NoMotion { .. }));
    assert!(e.to_string().contains("still.csv"));
}

#[test]
fn more_components_than_points_is_refused() {
    let params = GmrParams::new()
        .n_points(3)
        .components(ComponentChoice::Fixed(7))
        .check()
        .unwrap();
    let e = params
        .fit(&[demo("d0", gesture(5, 60, 5)), demo("d1", gesture(5, 60, 5))])
        .unwrap_err();
    assert!(matches!(
        e,
        GmrError::TooFewPoints {
            points: 6,
            components: 7
        }
    ));
}

fn invalid(p: GmrParams, name: &str) {
    match p.check() {
        Err(GmrError::InvalidParam { name: n, .. }) => assert_eq!(n, name),
        other => panic!("{name}: expected InvalidParam, got {other:?}"),
    }
}

#[test]
fn invalid_components() {
    invalid(
        GmrParams::new().components(ComponentChoice::Fixed(0)),
        "components",
    );
    invalid(
        GmrParams::new().components(ComponentChoice::Bic { min: 0, max: 3 }),
        "components",
    );
    invalid(
        GmrParams::new().components(ComponentChoice::Bic { min: 4, max: 3 }),
        "components",
    );
}

#[test]
fn invalid_reg_covar() {
    for v in [0.0, -1e-6, f64::NAN, f64::INFINITY] {
        invalid(GmrParams::new().reg_covar(v), "reg_covar");
    }
}

#[test]
fn invalid_tolerance() {
    for v in [0.0, -1.0, f64::NAN] {
        invalid(GmrParams::new().tolerance(v), "tolerance");
    }
}

#[test]
fn invalid_max_iterations() {
    invalid(GmrParams::new().max_iterations(0), "max_iterations");
}

#[test]
fn invalid_n_points() {
    invalid(GmrParams::new().n_points(1), "n_points");
}

#[test]
fn invalid_sample_period() {
    for v in [0.0, -0.025, f64::NAN] {
        invalid(GmrParams::new().sample_period(v), "sample_period");
    }
}

#[test]
fn invalid_trim() {
    let t = IdleTrim {
        min_speed: 0.0,
        ..IdleTrim::default()
    };
    invalid(GmrParams::new().trim(t), "trim.min_speed");
    let t = IdleTrim {
        relative: 1.0,
        ..IdleTrim::default()
    };
    invalid(GmrParams::new().trim(t), "trim.relative");
    let t = IdleTrim {
        half_window: 5000,
        ..IdleTrim::default()
    };
    invalid(GmrParams::new().trim(t), "trim.half_window");
}

#[test]
fn invalid_band() {
    invalid(GmrParams::new().band(Band::Fraction(1.5)), "band");
}

#[test]
fn valid_defaults_pass() {
    assert!(GmrParams::new().check().is_ok());
}

#[test]
fn six_joints_with_two_unused_fit_with_default_bic() {
    // the Nao arm: wrist yaw and hand never move in the reading-watch gesture
    let six = |idle: usize, len: usize, idle_end: usize| -> Demonstration {
        let rows = gesture(idle, len, idle_end)
            .into_iter()
            .map(|q| vec![q[0], q[1], -1.2 + 0.5 * q[1], -0.5 - q[1], 0.0, 0.3])
            .collect();
        Demonstration {
            source: format!("six{idle}"),
            columns: LEFT_ARM_JOINTS.iter().map(|s| s.to_string()).collect(),
            time: None,
            rows,
        }
    };
    let demos = vec![six(30, 120, 10), six(5, 140, 40), six(60, 100, 0)];
    let (model, set, scores) = GmrParams::new()
        .check()
        .unwrap()
        .fit_with_details(&demos)
        .unwrap();
    assert_eq!(scores.len(), 8);
    assert!(model.gmm().n_components() >= 2, "{scores:?}");
    assert_eq!(set.points()[0].len(), 7);
    let rep = model.reproduce(0.025).unwrap();
    for p in &rep {
        assert!((p.mean[4] - 0.0).abs() < 1e-6 && (p.mean[5] - 0.3).abs() < 1e-6);
    }
    let min_pitch = rep.iter().map(|p| p.mean[0]).fold(f64::MAX, f64::min);
    assert!((min_pitch - 0.3).abs() < 0.1, "apex pitch {min_pitch}");
}
