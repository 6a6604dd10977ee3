use super::*;

#[test]
fn single_sample_each() {
    let al = dtw(&[vec![0.0, 0.0]], &[vec![3.0, 4.0]], Band::None).unwrap();
    assert_eq!(al.distance, 5.0);
    assert_eq!(al.path, vec![(0, 0)]);
}

/// The open end stops where `a` (a prefix of `b`, the middle held) has got along `b`, and
/// its path is the one full DTW finds against `b` cut there.
#[test]
fn the_open_end_stops_where_a_prefix_has_got() {
    let b: Vec<Vec<f64>> = (0..20).map(|i| vec![i as f64]).collect();
    let mut a: Vec<Vec<f64>> = (0..8).map(|i| vec![i as f64]).collect();
    a.splice(4..4, std::iter::repeat(vec![4.0]).take(5));
    let open = dtw_open_end(&a, &b).unwrap();
    assert_eq!(*open.path.last().unwrap(), (a.len() - 1, 7));
    assert_eq!(open.distance, 0.0);
    let cut = dtw(&a, &b[..8], Band::None).unwrap();
    assert_eq!(open.path, cut.path);
    // the full alignment must reach b's end, at a cost
    assert!(dtw(&a, &b, Band::None).unwrap().distance > 0.0);
}

#[test]
fn band_is_widened_to_length_difference() {
    let a: Vec<Vec<f64>> = (0..3).map(|i| vec![i as f64]).collect();
    let b: Vec<Vec<f64>> = (0..10).map(|i| vec![i as f64 * 0.2]).collect();
    let al = dtw(&a, &b, Band::Samples(0)).unwrap();
    assert!(al.distance.is_finite());
    assert_eq!(*al.path.last().unwrap(), (2, 9));
    assert_eq!(Band::Samples(0).width(3, 10).unwrap(), Some(7));
}

/// The whole cost is [`dtw_distance`]'s; every prefix of a sequence that follows the start of
/// `b` costs nothing, and a sequence that turns away costs more from where it turns (the
/// control: against the whole of `b`, the closed end, it is never free).
#[test]
fn prefixes_cost_what_they_have_followed_so_far() {
    let b: Vec<Vec<f64>> = (0..20).map(|i| vec![i as f64, 0.0]).collect();
    let a: Vec<Vec<f64>> = (0..10)
        .map(|i| vec![i.min(5) as f64, (i as f64 - 5.0).max(0.0)])
        .collect();
    let (whole, prefixes) = dtw_with_prefixes(&a, &b).unwrap();
    assert_eq!(whole, dtw_distance(&a, &b, Band::None).unwrap());
    assert_eq!(prefixes.len(), a.len());
    assert!(prefixes[..6].iter().all(|&p| p == 0.0), "{prefixes:?}");
    assert!(
        prefixes[6..].windows(2).all(|w| w[1] > w[0]),
        "{prefixes:?}"
    );
    assert!(whole.per_step() > prefixes[5]);
    assert!(dtw_with_prefixes(&a, &[]).is_err());
}

/// The pruned DTW with every prefix's cost gives bit for bit what the full computation
/// gives (whole cost, steps, every prefix), on sequences alike and unlike, of one sample and
/// of lengths that differ, short and long, with ties (repeated samples); and it does skip
/// cells.
#[test]
fn pruning_changes_no_answer() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let walk = |rng: &mut rand_chacha::ChaCha8Rng, n: usize, d: usize, step: f64| {
        let mut x = vec![0.0; d];
        (0..n)
            .map(|_| {
                for v in &mut x {
                    *v += rng.gen_range(-step..step);
                }
                x.clone()
            })
            .collect::<Vec<Vec<f64>>>()
    };
    let mut skipped = 0.0;
    let mut cases = 0;
    for case in 0..240 {
        let d = 1 + case % 6;
        // short ones, and from 200 on as long as a gesture (the band and the boxes at work)
        let most = if case < 200 { 60 } else { 320 };
        let (n, m) = (1 + rng.gen_range(0..most), 1 + rng.gen_range(0..most));
        let b = walk(&mut rng, m, d, 0.3);
        let a = match case % 4 {
            // a noisy copy of b, warped
            0 => (0..n)
                .map(|i| {
                    let j = i * (m - 1) / (n - 1).max(1);
                    b[j].iter()
                        .map(|v| v + rng.gen_range(-0.01..0.01))
                        .collect()
                })
                .collect(),
            // ties: every sample repeated, of a coarse grid
            1 => walk(&mut rng, n, d, 1.0)
                .into_iter()
                .map(|r| r.iter().map(|v| v.round()).collect())
                .collect(),
            _ => walk(&mut rng, n, d, 0.3),
        };
        let fast = dtw_with_prefixes(&a, &b).unwrap();
        let full = dtw_with_prefixes_full(&a, &b).unwrap();
        assert_eq!(
            fast.0.distance.to_bits(),
            full.0.distance.to_bits(),
            "case {case}"
        );
        assert_eq!(fast.0.steps, full.0.steps, "case {case}");
        let bits = |p: &[f64]| p.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&fast.1), bits(&full.1), "case {case}");
        if case % 4 == 0 && n > 20 && m > 20 {
            skipped += prefix_pruning_rate(&a, &b).unwrap();
            cases += 1;
        }
    }
    assert!(skipped / cases as f64 > 0.2, "{}", skipped / cases as f64);
}

mod props;
