//! Data shared by the benchmarks.

use cosco_hsom::demos::Demonstration;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `k` gesture-like 6-D demonstrations of `n` samples (sines with 1 % noise, seed 3).
pub fn gestures(k: usize, n: usize) -> Vec<Demonstration> {
    gestures_of(k, n, 6)
}

/// `k` gesture-like demonstrations of `width` variables and `n` samples (sines with 1 % noise,
/// seed 3).
pub fn gestures_of(k: usize, n: usize, width: usize) -> Vec<Demonstration> {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    (0..k)
        .map(|i| Demonstration {
            source: format!("g{i}"),
            columns: (0..width).map(|d| format!("j{d}")).collect(),
            time: None,
            rows: (0..n)
                .map(|j| {
                    let u = j as f64 / n as f64 * std::f64::consts::PI;
                    (0..width)
                        .map(|d| (u + 0.2 * d as f64).sin() + rng.gen_range(-0.01..0.01))
                        .collect()
                })
                .collect(),
        })
        .collect()
}
