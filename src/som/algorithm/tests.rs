use super::super::reference::NodeMajorMap;
use super::super::{Decay, Schedule, SomParams};
use super::*;
use rand::{Rng, SeedableRng};

#[test]
fn ids_round_trip_through_indices() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let m = SelfOrganizingMap::new_random(
        3,
        5,
        2,
        Topology::Orthogonal,
        &[0.0; 2],
        &[1.0; 2],
        &mut rng,
    );
    for i in 0..15 {
        assert_eq!(m.index(m.id(i)), i);
    }
    assert_eq!(m.id(7), (2, 1));
}

#[test]
fn hexagonal_inner_node_has_six_neighbours() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    let m = SelfOrganizingMap::new_random(5, 5, 1, Topology::Hexagonal, &[0.0], &[1.0], &mut rng);
    let c = m.index((2, 2));
    let n = (0..25)
        .filter(|&j| j != c && m.are_neighbours(c, j))
        .count();
    assert_eq!(n, 6);
    let o = SelfOrganizingMap::new_random(5, 5, 1, Topology::Orthogonal, &[0.0], &[1.0], &mut rng);
    let n = (0..25)
        .filter(|&j| j != c && o.are_neighbours(c, j))
        .count();
    assert_eq!(n, 8);
}

#[test]
fn initial_weights_lie_in_the_given_box() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
    let m = SelfOrganizingMap::new_random(
        4,
        4,
        2,
        Topology::Orthogonal,
        &[10.0, -5.0],
        &[20.0, -4.0],
        &mut rng,
    );
    for i in 0..m.len() {
        let w = m.weights(i);
        assert!((10.0..=20.0).contains(&w[0]) && (-5.0..=-4.0).contains(&w[1]));
    }
}

#[test]
fn masked_bmu_ignores_unknown_dimensions() {
    let m =
        SelfOrganizingMap::from_weights(1, 2, 2, Topology::Orthogonal, vec![0.0, 100.0, 5.0, 0.0])
            .unwrap();
    assert_eq!(m.bmu(&[0.0, 0.0]).0, 1);
    assert_eq!(m.bmu_masked(&[0.0, 0.0], &[true, false]).0, 0);
}

#[test]
fn schedules_start_and_end_at_their_values() {
    for decay in [Decay::Exponential, Decay::Linear] {
        let s = Schedule {
            initial: 0.5,
            last: 0.01,
            decay,
        };
        assert!((s.at(0.0) - 0.5).abs() < 1e-12 && (s.at(1.0) - 0.01).abs() < 1e-12);
        assert!(s.at(0.5) < 0.5 && s.at(0.5) > 0.01);
    }
}

#[test]
fn training_lowers_quantization_error_and_keeps_topology() {
    // points along a line: a trained 1x10 map orders itself along it
    let data: Vec<Vec<f64>> = (0..200)
        .map(|i| vec![((i * 37) % 200) as f64 / 10.0])
        .collect();
    let mut p = SomParams::new(1, 10);
    p.steps = 2000;
    let m = p.fit(&data).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
    let untrained =
        SelfOrganizingMap::new_random(1, 10, 1, Topology::Orthogonal, &[0.0], &[20.0], &mut rng);
    assert!(
        m.quantization_error(&data) < 0.6,
        "{}",
        m.quantization_error(&data)
    );
    assert!(m.quantization_error(&data) < untrained.quantization_error(&data));
    assert!(m.topographic_error(&data) < 0.05);
    let w: Vec<f64> = (0..10).map(|i| m.weights(i)[0]).collect();
    let inc = w.windows(2).all(|p| p[0] < p[1]);
    let dec = w.windows(2).all(|p| p[0] > p[1]);
    assert!(inc || dec, "{w:?}");
}

/// Largest |a - b| / max(1, |b|) over all weights.
fn max_rel_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / y.abs().max(1.0))
        .fold(0.0, f64::max)
}

fn random_map(rows: usize, cols: usize, dim: usize, t: Topology, seed: u64) -> SelfOrganizingMap {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    SelfOrganizingMap::new_random(
        rows,
        cols,
        dim,
        t,
        &vec![-1.0; dim],
        &vec![1.0; dim],
        &mut rng,
    )
}

/// Map shapes with a partial last block (node counts not multiples of 8), a single node,
/// a wide dimension, both topologies.
const SHAPES: [(usize, usize, usize); 7] = [
    (1, 1, 3),
    (3, 5, 2),
    (7, 9, 12),
    (16, 16, 12),
    (5, 13, 7),
    (4, 4, 40),
    (1, 10, 1),
];

#[test]
fn every_instruction_set_matches_the_reference() {
    // the baseline (scalar lanes), AVX2 and AVX-512 kernels, whichever this CPU runs
    assert!(!kernel::tests::available().is_empty());
    kernel::tests::on_every_arch(|arch| {
        let m = random_map(7, 9, 12, Topology::Hexagonal, 3);
        let r = NodeMajorMap::of(&m);
        let x: Vec<f64> = (0..12).map(|d| (d as f64 * 0.37).sin()).collect();
        let mask: Vec<bool> = (0..12).map(|d| d % 3 != 0).collect();
        assert_eq!(m.bmu(&x), r.bmu(&x), "{arch}");
        assert_eq!(m.bmu_masked(&x, &mask), r.bmu_masked(&x, &mask), "{arch}");
        assert_eq!(m.best_two(&x), r.best_two(&x), "{arch}");
        let (mut m, mut r) = (m, r);
        train_both(
            &mut m,
            &mut r,
            Neighbourhood::Gaussian,
            Reach::Cut {
                h_min: DEFAULT_H_MIN,
            },
            DEFAULT_H_MIN,
            9,
        );
        let e = max_rel_diff(&m.all_weights(), r.weights());
        assert!(e <= 1e-12, "{arch}: {e:e}");
    });
}

#[test]
fn searches_match_the_node_by_node_reference_exactly() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    for (s, &(rows, cols, dim)) in SHAPES.iter().enumerate() {
        for t in [Topology::Orthogonal, Topology::Hexagonal] {
            let mut m = random_map(rows, cols, dim, t, s as u64);
            // duplicated nodes: ties must go to the lowest index
            if m.len() > 3 {
                let w = m.weights(1).to_vec();
                m.set_weights(m.len() - 1, &w);
            }
            let r = NodeMajorMap::of(&m);
            for q in 0..50 {
                let x: Vec<f64> = if q % 5 == 0 {
                    m.weights(1.min(m.len() - 1)).to_vec()
                } else {
                    (0..dim).map(|_| rng.gen_range(-1.5..1.5)).collect()
                };
                let mask: Vec<bool> = (0..dim).map(|_| rng.gen_bool(0.6)).collect();
                assert_eq!(m.bmu(&x), r.bmu(&x));
                assert_eq!(m.bmu_masked(&x, &mask), r.bmu_masked(&x, &mask));
                assert_eq!(m.best_two(&x), r.best_two(&x));
                let half = dim / 2;
                assert_eq!(
                    m.bmu_range(&x[half..], half..dim),
                    r.bmu_range(&x[half..], half..dim)
                );
                assert_eq!(m.bmu_range(&x, 0..half), r.bmu_range(&x, 0..half));
                for i in [0, m.len() - 1] {
                    let d = m.distance2(i, &x, 0..dim);
                    let w = m.weights(i);
                    let e: f64 = w.iter().zip(&x).map(|(a, b)| (a - b) * (a - b)).sum();
                    assert_eq!(d, e);
                }
            }
        }
    }
}

#[test]
fn search_finds_a_node_in_the_partial_last_block_and_never_a_padding_lane() {
    // 10 nodes: the second block has 2 real nodes and 6 padding lanes holding 0
    let mut m = random_map(2, 5, 3, Topology::Orthogonal, 1);
    m.set_weights(9, &[0.5, 0.5, 0.5]);
    assert_eq!(m.bmu(&[0.5, 0.5, 0.5]), (9, 0.0));
    // the padding lanes hold 0: a query at 0 must still get a real node
    let (b, _) = m.bmu(&[0.0, 0.0, 0.0]);
    assert!(b < 10);
    let (a, b) = m.best_two(&[0.5, 0.5, 0.5]);
    assert!(a == 9 && b < 10);
}

/// Train a map and its reference side by side with the same inputs and schedules.
fn train_both(
    m: &mut SelfOrganizingMap,
    r: &mut NodeMajorMap,
    nb: Neighbourhood,
    reach: Reach,
    h_min_ref: f64,
    seed: u64,
) {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let dim = m.dim();
    let steps = 400;
    for t in 0..steps {
        let p = t as f64 / steps as f64;
        let x: Vec<f64> = (0..dim).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let mask: Vec<bool> = (0..dim).map(|d| d % 3 != 1 || t % 2 == 0).collect();
        let mask = (t % 3 == 0).then_some(&mask[..]);
        let (b, _) = r.bmu(&x);
        let radius = 4.0 * (0.1f64 / 4.0).powf(p);
        let alpha = 0.5 * (0.01f64 / 0.5).powf(p);
        r.update(&x, mask, b, alpha, radius, nb, h_min_ref);
        m.update_reach(&x, mask, b, alpha, radius, nb, reach);
    }
}

#[test]
fn training_matches_the_reference_within_1e_12() {
    for (s, &(rows, cols, dim)) in SHAPES.iter().enumerate() {
        for t in [Topology::Orthogonal, Topology::Hexagonal] {
            for nb in [Neighbourhood::Gaussian, Neighbourhood::Bubble] {
                let cut = Reach::Cut {
                    h_min: DEFAULT_H_MIN,
                };
                for (reach, h_ref) in [(cut, DEFAULT_H_MIN), (Reach::Exact, 0.0)] {
                    let mut m = random_map(rows, cols, dim, t, 10 + s as u64);
                    let mut r = NodeMajorMap::of(&m);
                    train_both(&mut m, &mut r, nb, reach, h_ref, s as u64);
                    let e = max_rel_diff(&m.all_weights(), r.weights());
                    assert!(
                        e <= 1e-12,
                        "{rows}x{cols}x{dim} {t:?} {nb:?} {reach:?}: {e:e}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_comparison_with_the_reference_can_fail() {
    // negative control: a 0.1 % larger radius is far beyond the 1e-12 tolerance
    let mut m = random_map(16, 16, 12, Topology::Orthogonal, 3);
    let mut r = NodeMajorMap::of(&m);
    let x = vec![0.3; 12];
    let (b, _) = r.bmu(&x);
    r.update(
        &x,
        None,
        b,
        0.2,
        2.0,
        Neighbourhood::Gaussian,
        DEFAULT_H_MIN,
    );
    m.update(&x, None, b, 0.2, 2.002, Neighbourhood::Gaussian);
    assert!(max_rel_diff(&m.all_weights(), r.weights()) > 1e-6);
}

#[test]
fn a_tighter_cut_moves_no_node_by_more_than_its_bound() {
    // h_min = exp(-4.5) cuts the gaussian at 3 radii; a node left out would have moved by
    // alpha h |x - w| < alpha h_min |x - w|; the nodes inside move exactly
    let h_min = (-4.5f64).exp();
    for t in [Topology::Orthogonal, Topology::Hexagonal] {
        let before = random_map(20, 20, 6, t, 4);
        let x = vec![0.25; 6];
        let (b, _) = before.bmu(&x);
        let (alpha, radius) = (0.3, 2.5);
        let mut exact = before.clone();
        exact.update_reach(
            &x,
            None,
            b,
            alpha,
            radius,
            Neighbourhood::Gaussian,
            Reach::Exact,
        );
        let mut cut = before.clone();
        cut.update_reach(
            &x,
            None,
            b,
            alpha,
            radius,
            Neighbourhood::Gaussian,
            Reach::Cut { h_min },
        );
        let mut left_out = 0;
        for i in 0..before.len() {
            let (w0, we, wc) = (before.weights(i), exact.weights(i), cut.weights(i));
            let inside = before.grid_distance2(b, i) < 9.0 * radius * radius * (1.0 - 1e-9);
            for d in 0..6 {
                if inside {
                    assert!((wc[d] - we[d]).abs() <= 1e-12 * we[d].abs().max(1.0));
                } else {
                    assert_eq!(wc[d], w0[d]);
                    assert!((we[d] - wc[d]).abs() <= alpha * h_min * (x[d] - w0[d]).abs());
                }
            }
            left_out += usize::from(!inside);
        }
        assert!(left_out > 100, "{left_out}");
    }
}

#[test]
fn weights_round_trip_through_the_node_major_layout() {
    let mut m = random_map(5, 13, 7, Topology::Hexagonal, 8);
    m.update(&[0.1; 7], None, 17, 0.4, 3.0, Neighbourhood::Gaussian);
    let back =
        SelfOrganizingMap::from_weights(5, 13, 7, Topology::Hexagonal, m.all_weights()).unwrap();
    assert_eq!(back, m);
    assert_eq!(m.weights(17).len(), 7);
    let wide = random_map(3, 3, 70, Topology::Orthogonal, 2);
    assert_eq!(wide.weights(8).len(), 70);
    assert_eq!(&wide.weights(8)[..], &wide.all_weights()[8 * 70..]);
}

#[test]
fn invalid_learning_factor_is_rejected() {
    let mut p = SomParams::new(2, 2);
    p.learning_factor.initial = 1.5;
    assert!(matches!(
        p.fit(&[vec![0.0]]),
        Err(SomError::InvalidParam { .. })
    ));
}
