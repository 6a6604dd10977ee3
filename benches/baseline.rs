//! Benchmarks of the GMM/GMR baseline and DTW on data generated here:
//! three reading-watch-like 6-D demonstrations (~300 samples each at 40 Hz, with idle
//! start and end), EM fit, GMR reproduction, and DTW between two 400-sample 6-D sequences.
//!
//! `cargo bench --bench baseline -- --warm-up-time 1 --measurement-time 3`

use cosco_hsom::demos::Demonstration;
use cosco_hsom::dtw::{dtw, dtw_distance, Band};
use cosco_hsom::gmr::preprocess::preprocess;
use cosco_hsom::gmr::{ComponentChoice, GmrParams};
use criterion::{black_box, criterion_group, criterion_main, Criterion};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use std::f64::consts::PI;

/// A raise-and-return of the left arm: six joints, `idle` still samples, a bell-shaped
/// motion over `len` samples, `idle_end` still samples, 1 mrad sensor noise.
fn reading_watch(idle: usize, len: usize, idle_end: usize, gain: f64, seed: u64) -> Vec<Vec<f64>> {
    let rest = [1.5, 0.15, -1.2, -0.5, 0.0, 0.3];
    let apex = [0.2, 0.35, -1.6, -1.45, -1.0, 0.3];
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = Normal::new(0.0, 0.001).unwrap();
    let mut rows = Vec::with_capacity(idle + len + idle_end);
    for k in 0..idle + len + idle_end {
        let s = if k < idle || k >= idle + len {
            0.0
        } else {
            (PI * (k - idle) as f64 / (len - 1) as f64).sin().powi(2) * gain
        };
        rows.push(
            (0..6)
                .map(|j| rest[j] + s * (apex[j] - rest[j]) + noise.sample(&mut rng))
                .collect(),
        );
    }
    rows
}

fn demos() -> Vec<Demonstration> {
    [(40, 220, 30, 1.0), (15, 250, 45, 0.95), (70, 200, 20, 1.05)]
        .iter()
        .enumerate()
        .map(|(i, &(a, b, c, g))| Demonstration {
            source: format!("synthetic{i}"),
            columns: (0..6).map(|j| format!("q{j}")).collect(),
            time: None,
            rows: reading_watch(a, b, c, g, i as u64),
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let demos = demos();
    let params = GmrParams::new()
        .components(ComponentChoice::Fixed(6))
        .n_points(100)
        .seed(1)
        .check()
        .unwrap();
    let training = preprocess(&demos, &params).unwrap();
    let points = training.points();

    c.bench_function("preprocess 3x~300x6 (trim, DTW align, resample)", |b| {
        b.iter(|| preprocess(black_box(&demos), &params).unwrap())
    });
    c.bench_function("EM fit K=6 on 300 points [t,q] 7-D", |b| {
        b.iter(|| params.fit_gmm(black_box(&points)).unwrap())
    });
    let bic = GmrParams::new()
        .components(ComponentChoice::Bic { min: 1, max: 8 })
        .check()
        .unwrap();
    c.bench_function("EM fit with BIC over K=1..=8", |b| {
        b.iter(|| bic.fit_gmm(black_box(&points)).unwrap())
    });
    let model = params.fit(&demos).unwrap();
    c.bench_function("GMR reproduce at 40 Hz (K=6, 6 joints)", |b| {
        b.iter(|| model.reproduce(black_box(0.025)).unwrap())
    });

    let a = reading_watch(30, 340, 30, 1.0, 7);
    let b2 = reading_watch(50, 320, 30, 0.9, 8);
    assert_eq!((a.len(), b2.len()), (400, 400));
    c.bench_function("DTW with path 400x400 6-D", |b| {
        b.iter(|| dtw(black_box(&a), black_box(&b2), Band::None).unwrap())
    });
    c.bench_function("DTW distance only 400x400 6-D", |b| {
        b.iter(|| dtw_distance(black_box(&a), black_box(&b2), Band::None).unwrap())
    });
    c.bench_function("DTW distance 400x400 6-D, band 10%", |b| {
        b.iter(|| dtw_distance(black_box(&a), black_box(&b2), Band::Fraction(0.1)).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
