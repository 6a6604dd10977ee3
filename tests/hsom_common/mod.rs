//! Synthetic demonstration families and a plain DTW distance, shared by the hsom tests.
#![allow(dead_code)]

use cosco_hsom::config::{AlgorithmParams, EventsParams, HsomConfig, HsomParams, LevelParams};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::som::Topology;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// Mean Euclidean distance between aligned samples along the optimal DTW path.
pub fn dtw(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let (n, m) = (a.len(), b.len());
    let inf = f64::INFINITY;
    let mut cost = vec![inf; (n + 1) * (m + 1)];
    let mut len = vec![0usize; (n + 1) * (m + 1)];
    cost[0] = 0.0;
    let at = |i: usize, j: usize| i * (m + 1) + j;
    for i in 1..=n {
        for j in 1..=m {
            let d: f64 = a[i - 1]
                .iter()
                .zip(&b[j - 1])
                .map(|(x, y)| (x - y) * (x - y))
                .sum::<f64>()
                .sqrt();
            let cands = [
                (cost[at(i - 1, j - 1)], len[at(i - 1, j - 1)]),
                (cost[at(i - 1, j)], len[at(i - 1, j)]),
                (cost[at(i, j - 1)], len[at(i, j - 1)]),
            ];
            let best = cands
                .iter()
                .cloned()
                .fold((inf, 0), |acc, c| if c.0 < acc.0 { c } else { acc });
            cost[at(i, j)] = best.0 + d;
            len[at(i, j)] = best.1 + 1;
        }
    }
    cost[at(n, m)] / len[at(n, m)] as f64
}

/// Diagonal of the bounding box of all demonstrations (the scale for relative errors).
pub use cosco_hsom::eval::diagonal;

/// Mean DTW distance from `rep` to the demonstrations, relative to their bounding-box diagonal.
pub fn relative_dtw(rep: &[Vec<f64>], demos: &[Demonstration]) -> f64 {
    demos.iter().map(|d| dtw(rep, &d.rows)).sum::<f64>() / demos.len() as f64 / diagonal(demos)
}

fn demo(name: String, cols: usize, rows: Vec<Vec<f64>>) -> Demonstration {
    Demonstration {
        source: name,
        columns: (0..cols).map(|i| format!("x{i}")).collect(),
        time: None,
        rows,
    }
}

/// Monotone time warp of [0, 1]: u = t + a sin(pi t) sin(...) with |a| small.
fn warp(t: f64, a: f64) -> f64 {
    (t + a * (std::f64::consts::PI * t).sin() / std::f64::consts::PI).clamp(0.0, 1.0)
}

/// 2-D figure eight in pixel-like units (centre 300, 200; half-width 80), `k` demonstrations
/// of 150..250 samples with timing variation and noise.
pub fn figure_eight(k: usize, seed: u64) -> Vec<Demonstration> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = Normal::new(0.0, 0.8).unwrap();
    (0..k)
        .map(|i| {
            let n = rng.gen_range(150..250);
            let a = rng.gen_range(-0.4..0.4);
            let rows = (0..n)
                .map(|j| {
                    let u = warp(j as f64 / (n - 1) as f64, a) * 2.0 * std::f64::consts::PI;
                    vec![
                        300.0 + 80.0 * u.sin() + noise.sample(&mut rng),
                        200.0 + 40.0 * (2.0 * u).sin() + noise.sample(&mut rng),
                    ]
                })
                .collect();
            demo(format!("eight{i}"), 2, rows)
        })
        .collect()
}

/// 2-D letter-like open stroke (a cursive "l e"-like curve with a loop), in millimetres.
pub fn stroke(k: usize, seed: u64) -> Vec<Demonstration> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = Normal::new(0.0, 0.15).unwrap();
    (0..k)
        .map(|i| {
            let n = rng.gen_range(120..220);
            let a = rng.gen_range(-0.4..0.4);
            let rows = (0..n)
                .map(|j| {
                    let u = warp(j as f64 / (n - 1) as f64, a);
                    let th = 3.0 * std::f64::consts::PI * u;
                    vec![
                        40.0 * u + 6.0 * th.sin() + noise.sample(&mut rng),
                        10.0 * (1.0 - th.cos()) * (1.0 - 0.5 * u) + noise.sample(&mut rng),
                    ]
                })
                .collect();
            demo(format!("stroke{i}"), 2, rows)
        })
        .collect()
}

/// 6-D joint gesture in radians (raise an arm and come back, as in the paper's task: the
/// initial and final postures are equal), idle start and end of random length, 150..300 samples.
pub fn joints6(k: usize, seed: u64) -> Vec<Demonstration> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = Normal::new(0.0, 0.004).unwrap();
    let rest = [1.4, 0.2, -1.2, -0.5, 0.0, 0.3];
    let peak = [-0.3, 0.6, -0.4, -1.4, 1.2, 0.3];
    (0..k)
        .map(|i| {
            let idle0 = rng.gen_range(10..40);
            let idle1 = rng.gen_range(10..40);
            let m = rng.gen_range(120..200);
            let a = rng.gen_range(-0.3..0.3);
            let mut rows = Vec::new();
            for _ in 0..idle0 {
                rows.push(rest.iter().map(|v| v + noise.sample(&mut rng)).collect());
            }
            for j in 0..m {
                let u = warp(j as f64 / (m - 1) as f64, a);
                // up with a hold-ish shape, then down, joints slightly out of phase
                let row = (0..6)
                    .map(|d| {
                        let ph = (u - 0.04 * d as f64).clamp(0.0, 1.0);
                        let s = (std::f64::consts::PI * ph).sin().powf(1.5);
                        rest[d] + (peak[d] - rest[d]) * s + noise.sample(&mut rng)
                    })
                    .collect();
                rows.push(row);
            }
            for _ in 0..idle1 {
                rows.push(rest.iter().map(|v| v + noise.sample(&mut rng)).collect());
            }
            demo(format!("joints{i}"), 6, rows)
        })
        .collect()
}

/// 2-D handwriting-like family: a cursive "w"-like word with a loop at the end, in
/// millimetres, `k` demonstrations of about 100 samples (90..110) with timing warp, slant and
/// size variation and pen noise.
pub fn handwriting(k: usize, seed: u64) -> Vec<Demonstration> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let noise = Normal::new(0.0, 0.1).unwrap();
    (0..k)
        .map(|i| {
            let n = rng.gen_range(90..110);
            let a = rng.gen_range(-0.3..0.3);
            let size = rng.gen_range(0.9..1.1);
            let slant = rng.gen_range(-0.15..0.15);
            let rows = (0..n)
                .map(|j| {
                    let u = warp(j as f64 / (n - 1) as f64, a);
                    let th = 4.0 * std::f64::consts::PI * u;
                    let y = size * (8.0 * (0.5 * th).sin().abs() + 3.0 * (u * 6.0).sin());
                    let x = size * (30.0 * u + 2.5 * th.sin());
                    vec![
                        x + slant * y + noise.sample(&mut rng),
                        y + noise.sample(&mut rng),
                    ]
                })
                .collect();
            demo(format!("hand{i}"), 2, rows)
        })
        .collect()
}

/// The recommended configs/nao-gestures.xml with the state length of the data.
pub fn recommended_for(dims: usize) -> HsomConfig {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml");
    let mut p = cosco_hsom::config::load_config(&path)
        .unwrap()
        .into_params();
    p.state_length = dims;
    p.action_length = dims;
    p.check("nao-gestures.xml").unwrap()
}

/// The demonstration cut into blocks of 20 samples (about half a second at 40 Hz) put in a
/// seeded random order, its first block kept first so the initial posture is unchanged: the
/// same postures with their event order shuffled (the negative control of sequence tests).
pub fn shuffle_blocks(d: &Demonstration, seed: u64) -> Demonstration {
    use rand::seq::SliceRandom;
    let mut blocks: Vec<Vec<Vec<f64>>> = d.rows.chunks(20).map(|c| c.to_vec()).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    blocks[1..].shuffle(&mut rng);
    let mut out = d.clone();
    out.rows = blocks.concat();
    out
}

/// Table I with the state length of the data.
pub fn table1_for(dims: usize) -> HsomConfig {
    let mut p = HsomParams::table1();
    p.state_length = dims;
    p.action_length = dims;
    p.check("table1").unwrap()
}

/// A plain-text model file with its checksum line recomputed (FNV-1a over everything before
/// it), as anyone can: a valid checksum is no validation.
pub fn with_checksum(text: &str) -> String {
    let body_end = text.trim_end_matches('\n').rfind('\n').map_or(0, |i| i + 1);
    let body = &text[..body_end];
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in body.as_bytes() {
        h ^= b as u64;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{body}checksum {h:016x}\n")
}

/// The proptest configuration of the fuzz targets: `cases` cases (or `PROPTEST_CASES`) from
/// the fixed seed 1 (or `PROPTEST_RNG_SEED`): CI runs the same cases every time; the long
/// campaign (scripts/fuzz-campaign.sh) varies the seed.
pub fn fuzz_config(cases: u32) -> proptest::test_runner::Config {
    let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<u64>().ok());
    proptest::test_runner::Config {
        cases: env("PROPTEST_CASES").map_or(cases, |c| c.min(u32::MAX as u64) as u32),
        rng_seed: proptest::test_runner::RngSeed::Fixed(env("PROPTEST_RNG_SEED").unwrap_or(1)),
        ..proptest::test_runner::Config::default()
    }
}

/// A plain-text model file (three header lines, the model as one line of JSON, the checksum
/// line) with its model edited by `edit` and the checksum recomputed, as anyone can.
pub fn edit_model_text(text: &str, edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let lines: Vec<&str> = text.lines().collect();
    let mut model: serde_json::Value = serde_json::from_str(lines[3]).unwrap();
    edit(&mut model);
    with_checksum(&format!("{}\n{model}\nchecksum 0\n", lines[..3].join("\n")))
}

/// A small 2-D gesture (several gestures in one hierarchy): hold at the origin, go to `apex`
/// and back, hold; `seed` varies the holds, the amplitude and the encoder noise.
pub fn apex_gesture(apex: [f64; 2], seed: u64) -> Vec<Vec<f64>> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let hold = 20 + rng.gen_range(0..10);
    let amp = 1.0 + rng.gen_range(-0.05..0.05);
    let mut rows = Vec::new();
    let mut push = |t: f64, rng: &mut rand_chacha::ChaCha8Rng| {
        rows.push(vec![
            amp * apex[0] * t + 0.002 * rng.gen::<f64>(),
            amp * apex[1] * t + 0.002 * rng.gen::<f64>(),
        ]);
    };
    for _ in 0..hold {
        push(0.0, &mut rng);
    }
    for i in 0..40 {
        push(i as f64 / 40.0, &mut rng);
    }
    for _ in 0..hold {
        push(1.0, &mut rng);
    }
    for i in 0..40 {
        push(1.0 - i as f64 / 40.0, &mut rng);
    }
    for _ in 0..hold {
        push(0.0, &mut rng);
    }
    rows
}

/// Three gestures of [`apex_gesture`]: their labels and apexes.
pub const APEXES: [(&str, [f64; 2]); 3] = [
    ("up", [0.0, 1.0]),
    ("right", [1.0, 0.0]),
    ("diag", [-0.7, 0.7]),
];

/// A configuration of the events extension for [`apex_gesture`] that trains in well under a
/// second.
pub fn apex_config() -> HsomConfig {
    let mut p = HsomParams::table1();
    p.algorithm = AlgorithmParams::Events(EventsParams {
        change_ratio: 0.6,
        action_horizon: 5,
    });
    p.state_length = 2;
    p.action_length = 2;
    p.height = 3;
    p.levels.truncate(3);
    p.levels[0] = LevelParams::new(10, 10, Topology::Orthogonal, 0.1);
    for l in 1..3 {
        p.levels[l] = LevelParams::new(6, 6, Topology::Orthogonal, 0.5);
    }
    p.training_steps = 3000;
    p.check("test").unwrap()
}

/// A demonstration of two columns `x0`, `x1`.
pub fn apex_demo(name: &str, rows: Vec<Vec<f64>>) -> Demonstration {
    Demonstration {
        source: name.to_string(),
        columns: vec!["x0".into(), "x1".into()],
        time: None,
        rows,
    }
}

/// Labelled sets: three demonstrations (seeds 0-2) of each gesture.
pub fn apex_sets(labels: &[(&str, [f64; 2])]) -> Vec<(String, Vec<Demonstration>)> {
    labels
        .iter()
        .map(|(l, a)| {
            (
                l.to_string(),
                (0..3).map(|i| apex_demo(l, apex_gesture(*a, i))).collect(),
            )
        })
        .collect()
}
