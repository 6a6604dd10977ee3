//! GMM fitting and GMR through the public API: identities, recovery of known Gaussians,
//! determinism, BIC, save/load and its errors.

use crate::gmr::{
    load_model, model_from_str, model_to_string, save_model, ComponentChoice, Gmm, GmrError,
    GmrModel, GmrParams,
};
use nalgebra::{DMatrix, DVector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// Points [t, q0, q1] of a noisy line: q = a + b t + noise.
fn linear_points(n: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = Normal::new(0.0, 0.05).unwrap();
    (0..n)
        .map(|i| {
            let t = 3.0 * i as f64 / (n - 1) as f64;
            vec![
                t,
                0.2 + 0.7 * t + noise.sample(&mut rng),
                -1.0 - 0.3 * t + noise.sample(&mut rng),
            ]
        })
        .collect()
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

#[test]
fn one_component_gmr_equals_linear_regression() {
    let pts = linear_points(200, 1);
    let params = GmrParams::new()
        .components(ComponentChoice::Fixed(1))
        .reg_covar(1e-12)
        .check()
        .unwrap();
    let (gmm, _) = params.fit_gmm(&pts).unwrap();
    let model = GmrModel::new(vec!["q0".into(), "q1".into()], 3.0, gmm).unwrap();
    let t: Vec<f64> = pts.iter().map(|p| p[0]).collect();
    let tm = mean(&t);
    let var_t = t.iter().map(|x| (x - tm).powi(2)).sum::<f64>() / t.len() as f64;
    for j in 1..3 {
        let q: Vec<f64> = pts.iter().map(|p| p[j]).collect();
        let qm = mean(&q);
        let cov = t
            .iter()
            .zip(&q)
            .map(|(a, b)| (a - tm) * (b - qm))
            .sum::<f64>()
            / t.len() as f64;
        let slope = cov / var_t;
        // residual variance of the least-squares fit (maximum-likelihood, divided by N)
        let resid = t
            .iter()
            .zip(&q)
            .map(|(a, b)| (b - qm - slope * (a - tm)).powi(2))
            .sum::<f64>()
            / t.len() as f64;
        for &tq in &[-1.0, 0.0, 0.7, 1.5, 3.0, 5.0] {
            let p = model.predict(tq).unwrap();
            let expect = qm + slope * (tq - tm);
            assert!(
                (p.mean[j - 1] - expect).abs() < 1e-8,
                "t={tq} joint {j}: {} vs {expect}",
                p.mean[j - 1]
            );
            assert!((p.covariance[j - 1][j - 1] - resid).abs() < 1e-8);
        }
    }
    // and the slope is the generating one, roughly: a sanity check on the data
    let p0 = model.predict(0.0).unwrap().mean[0];
    let p3 = model.predict(3.0).unwrap().mean[0];
    assert!(((p3 - p0) / 3.0 - 0.7).abs() < 0.05);
}

fn three_blobs(seed: u64) -> (Vec<Vec<f64>>, Vec<[f64; 2]>) {
    let centres = vec![[0.0, 0.0], [4.0, 1.0], [1.0, 5.0]];
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let n = Normal::new(0.0, 0.4).unwrap();
    let mut pts = Vec::new();
    for (c, size) in centres.iter().zip([150, 100, 250]) {
        for _ in 0..size {
            pts.push(vec![c[0] + n.sample(&mut rng), c[1] + n.sample(&mut rng)]);
        }
    }
    (pts, centres)
}

#[test]
fn mixture_recovers_known_gaussians() {
    let (pts, centres) = three_blobs(3);
    for seed in [0, 1, 2] {
        let params = GmrParams::new()
            .components(ComponentChoice::Fixed(3))
            .seed(seed)
            .check()
            .unwrap();
        let (gmm, _) = params.fit_gmm(&pts).unwrap();
        for (c, w) in centres.iter().zip([0.3, 0.2, 0.5]) {
            let (k, dist) = gmm
                .means()
                .iter()
                .enumerate()
                .map(|(k, m)| (k, ((m[0] - c[0]).powi(2) + (m[1] - c[1]).powi(2)).sqrt()))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap();
            assert!(dist < 0.15, "seed {seed}: centre {c:?} off by {dist}");
            assert!((gmm.weights()[k] - w).abs() < 0.03);
            let s = &gmm.covariances()[k];
            assert!((s[(0, 0)] - 0.16).abs() < 0.05 && (s[(1, 1)] - 0.16).abs() < 0.05);
        }
    }
}

#[test]
fn bic_picks_the_true_count() {
    let (pts, _) = three_blobs(4);
    let params = GmrParams::new()
        .components(ComponentChoice::Bic { min: 1, max: 6 })
        .check()
        .unwrap();
    let (gmm, scores) = params.fit_gmm(&pts).unwrap();
    assert_eq!(gmm.n_components(), 3, "{scores:?}");
    assert_eq!(scores.len(), 6);
}

#[test]
fn same_seed_same_model_bit_for_bit() {
    let (pts, _) = three_blobs(5);
    let fit = |seed| {
        GmrParams::new()
            .components(ComponentChoice::Fixed(4))
            .seed(seed)
            .check()
            .unwrap()
            .fit_gmm(&pts)
            .unwrap()
            .0
    };
    assert_eq!(fit(9), fit(9));
}

#[test]
fn fewer_points_than_components_is_an_error() {
    let pts = vec![vec![0.0, 1.0], vec![1.0, 2.0]];
    let params = GmrParams::new()
        .components(ComponentChoice::Fixed(3))
        .check()
        .unwrap();
    assert!(matches!(
        params.fit_gmm(&pts),
        Err(GmrError::TooFewPoints {
            points: 2,
            components: 3
        })
    ));
}

#[test]
fn mismatched_point_widths_are_an_error() {
    let pts = vec![vec![0.0, 1.0], vec![1.0, 2.0], vec![1.0]];
    let params = GmrParams::new()
        .components(ComponentChoice::Fixed(1))
        .check()
        .unwrap();
    match params.fit_gmm(&pts) {
        Err(GmrError::BadPoint { index, .. }) => assert_eq!(index, 2),
        other => panic!("unexpected {other:?}"),
    }
}

#[test]
fn degenerate_covariance_is_refused() {
    let m = vec![DVector::from_vec(vec![0.0, 0.0])];
    let singular = vec![DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0])];
    assert!(matches!(
        Gmm::new(vec![1.0], m.clone(), singular),
        Err(GmrError::DegenerateCovariance { component: 0, .. })
    ));
    let asym = vec![DMatrix::from_row_slice(2, 2, &[1.0, 0.5, 0.0, 1.0])];
    assert!(matches!(
        Gmm::new(vec![1.0], m.clone(), asym),
        Err(GmrError::InvalidModel { .. })
    ));
    let ok = vec![DMatrix::identity(2, 2)];
    assert!(matches!(
        Gmm::new(vec![0.5], m, ok),
        Err(GmrError::InvalidModel { .. })
    ));
}

#[test]
fn constant_joint_is_handled_by_regularisation() {
    // an unused joint (constant column) makes the data covariance singular
    let pts: Vec<Vec<f64>> = linear_points(100, 2)
        .into_iter()
        .map(|mut p| {
            p.push(0.25);
            p
        })
        .collect();
    let params = GmrParams::new()
        .components(ComponentChoice::Fixed(2))
        .check()
        .unwrap();
    let (gmm, _) = params.fit_gmm(&pts).unwrap();
    let model = GmrModel::new(vec!["a".into(), "b".into(), "c".into()], 3.0, gmm).unwrap();
    assert!((model.predict(1.0).unwrap().mean[2] - 0.25).abs() < 1e-9);
}

fn small_model() -> GmrModel {
    let (pts, _) = three_blobs(6);
    let pts: Vec<Vec<f64>> = pts.into_iter().map(|p| vec![p[0], p[1], -p[1]]).collect();
    let (gmm, _) = GmrParams::new()
        .components(ComponentChoice::Fixed(3))
        .check()
        .unwrap()
        .fit_gmm(&pts)
        .unwrap();
    GmrModel::new(vec!["LShoulderPitch".into(), "my joint".into()], 2.5, gmm).unwrap()
}

#[test]
fn save_then_load_gives_an_identical_model() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("gmr.txt");
    let model = small_model();
    save_model(&path, &model).unwrap();
    let back = load_model(&path).unwrap();
    assert_eq!(back, model);
    assert_eq!(back.predict(0.3).unwrap(), model.predict(0.3).unwrap());
}

fn load_err(text: &str) -> GmrError {
    model_from_str("m.txt", text).unwrap_err()
}

#[test]
fn loading_other_files_versions_and_truncations_fails_clearly() {
    let good = model_to_string(&small_model()).unwrap();
    assert!(model_from_str("m.txt", &good).is_ok());

    assert!(matches!(load_err(""), GmrError::Format { .. }));
    let e = load_err("hello\n");
    assert!(e.to_string().contains("not a GMR model"), "{e}");

    let v2 = good.replacen("version 1", "version 2", 1);
    assert!(matches!(load_err(&v2), GmrError::Version { .. }));

    // truncated at every line boundary: always an error, never a panic
    let lines: Vec<&str> = good.lines().collect();
    for cut in 0..lines.len() {
        let t = lines[..cut].join("\n");
        assert!(model_from_str("m.txt", &t).is_err(), "cut at {cut}");
    }

    let huge = good.replacen("components 3", "components 18446744073709551615", 1);
    assert!(matches!(load_err(&huge), GmrError::Format { .. }));
    let big = good.replacen("columns 2", "columns 99999", 1);
    assert!(matches!(load_err(&big), GmrError::Format { .. }));
    let bad_dim = good.replacen("dim 3", "dim 4", 1);
    let e = load_err(&bad_dim);
    assert!(e.to_string().contains("inconsistent"), "{e}");

    let extra = format!("{good}weight 1\n");
    assert!(matches!(load_err(&extra), GmrError::Format { .. }));

    let nan = good.replacen("weight ", "weight NaN ", 1);
    assert!(matches!(load_err(&nan), GmrError::Format { .. }));
}

#[test]
fn loading_a_missing_file_names_it() {
    let e = load_model(std::path::Path::new("/nonexistent/gmr.txt")).unwrap_err();
    assert!(matches!(e, GmrError::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/gmr.txt"));
}

#[test]
fn bad_queries_are_errors() {
    let m = small_model();
    assert!(matches!(m.predict(f64::NAN), Err(GmrError::Query { .. })));
    assert!(matches!(m.reproduce(0.0), Err(GmrError::Query { .. })));
    assert!(matches!(m.reproduce(-1.0), Err(GmrError::Query { .. })));
    let r = m.reproduce(0.025).unwrap();
    assert_eq!(r.len(), 101);
    assert!((r.last().unwrap().time - 2.5).abs() < 1e-12);
}

mod properties {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(16))]

        #[test]
        fn save_load_identity_and_psd_conditional_covariance(
            seed in 0u64..1000,
            k in 1usize..4,
            t in -1.0f64..4.0,
        ) {
            let pts = linear_points(60, seed);
            let (gmm, _) = GmrParams::new()
                .components(ComponentChoice::Fixed(k))
                .seed(seed)
                .check()
                .unwrap()
                .fit_gmm(&pts)
                .unwrap();
            let model = GmrModel::new(vec!["a".into(), "b".into()], 3.0, gmm).unwrap();
            let text = model_to_string(&model).unwrap();
            let back = model_from_str("p.txt", &text).unwrap();
            prop_assert_eq!(&back, &model);
            let p = model.predict(t).unwrap();
            let c = DMatrix::from_fn(2, 2, |i, j| p.covariance[i][j]);
            prop_assert!((c[(0, 1)] - c[(1, 0)]).abs() < 1e-12);
            let eig = c.symmetric_eigen().eigenvalues;
            prop_assert!(eig.iter().all(|&e| e > -1e-12), "{:?}", eig);
        }
    }
}
