//! Unit tests of the events extension: the consensus and the placements weighed by the starts.

use super::*;

#[test]
fn the_consensus_averages_aligned_samples_whatever_their_tempo() {
    // two bumps from rest: one to 1 early and quickly, one to 2 late and slowly
    let bump = |start: usize, rise: usize, peak: f64| -> Vec<Vec<f64>> {
        let mut d = vec![vec![0.0, 0.0]; start];
        d.extend((0..=rise).map(|i| vec![peak * i as f64 / rise as f64, 1.0]));
        d.extend((0..=rise).map(|i| vec![peak * (1.0 - i as f64 / rise as f64), 1.0]));
        d.extend(vec![vec![0.0, 0.0]; 10]);
        d
    };
    let (a, b) = (bump(5, 10, 1.0), bump(20, 25, 2.0));
    let top = |d: &[Vec<f64>]| d.iter().map(|r| r[0]).fold(f64::MIN, f64::max);
    for max_aligned in [MAX_ALIGNED, 16] {
        let c = consensus(
            &[a.clone(), b.clone()],
            &aligned_samples(&[a.clone(), b.clone()], max_aligned),
        );
        assert_eq!((c[0].len(), c[1].len()), (a.len(), b.len()));
        // each consensus path's apex lies between the two apexes (1 and 2), toward the
        // other's: the higher apex aligned to the lower one's single top sample gives
        // their mean, 1.5; the lower one's top, aligned to the higher one's whole crest,
        // the crest's mean (written: 1.25 and 1.5; in blocks of 3 and 6 samples 1.27 and
        // 1.48); the rest stays at rest
        for cd in &c {
            assert!(
                (1.1..=1.55).contains(&top(cd)),
                "{max_aligned}: {}",
                top(cd)
            );
            assert!(cd[0].iter().all(|v| v.abs() < 1e-12), "{:?}", cd[0]);
        }
    }
    // one demonstration is its own consensus
    assert_eq!(
        consensus(
            std::slice::from_ref(&a),
            &aligned_samples(std::slice::from_ref(&a), MAX_ALIGNED),
        ),
        vec![a]
    );
}

#[test]
fn the_starts_weigh_the_placements_only_where_they_predict_them() {
    // six demonstrations whose placements of two nodes follow their starts (nested
    // curves: where a drawing starts tells where it goes)
    let starts: Vec<Vec<f64>> = (0..6).map(|i| vec![i as f64, 0.0]).collect();
    let knots: Vec<Vec<f64>> = (0..6)
        .map(|i| vec![i as f64, 1.0, 2.0 * i as f64, -1.0])
        .collect();
    let count = [3.0, 1.0];
    let fitted = StartKnots::fit(starts.clone(), knots.clone(), &count, 1);
    assert!(fitted.width.is_finite(), "{}", fitted.width);
    // a reproduction that starts where the last one did is placed where it was, not at
    // the mean of all (2.5, 5)
    let p = fitted.placed(&[5.0, 0.0]);
    assert!(
        (p[0] - 5.0).abs() < 0.1 && (p[2] - 10.0).abs() < 0.2,
        "{p:?}"
    );
    // the same seed, the same width
    assert_eq!(
        StartKnots::fit(starts.clone(), knots.clone(), &count, 1),
        fitted
    );
    // the control: the same placements in an order the starts do not predict
    let shuffled: Vec<Vec<f64>> = [3, 0, 5, 1, 4, 2]
        .iter()
        .map(|&i| knots[i].clone())
        .collect();
    let control = StartKnots::fit(starts.clone(), shuffled, &count, 1);
    assert!(!control.width.is_finite(), "{}", control.width);
    let mean = control.placed(&[5.0, 0.0]);
    assert!(
        (mean[0] - 2.5).abs() < 1e-12 && (mean[2] - 5.0).abs() < 1e-12,
        "{mean:?}"
    );
    // three demonstrations cannot show it (6 orders: the starts' own is 1 in 6), nor
    // identical starts
    let three = StartKnots::fit(starts[..3].to_vec(), knots[..3].to_vec(), &count, 1);
    assert!(!three.width.is_finite());
    let same = StartKnots::fit(vec![vec![0.0, 0.0]; 6], knots.clone(), &count, 1);
    assert!(!same.width.is_finite());
    // more than six demonstrations: shuffles from the seed
    let starts9: Vec<Vec<f64>> = (0..9).map(|i| vec![i as f64, 0.0]).collect();
    let knots9: Vec<Vec<f64>> = (0..9).map(|i| vec![i as f64, 0.0, 0.0, 0.0]).collect();
    assert!(StartKnots::fit(starts9, knots9, &count, 7)
        .width
        .is_finite());
    assert_eq!(all_orders(3).len(), 6);
    assert_eq!(all_orders(3)[0], vec![0, 1, 2]);
}

#[test]
fn each_node_is_placed_where_the_demonstrations_agree() {
    // the same gesture at three amplitudes: each demonstration's apex has its own
    // nodes, and a reproduction along any of them should reach the mean apex (1.0)
    let series: Vec<Vec<Vec<f64>>> = [0.8, 1.0, 1.2]
        .iter()
        .enumerate()
        .map(|(i, &k)| {
            gesture(30 + 5 * i, 100 + i as u64)
                .into_iter()
                .map(|r| vec![k * r[0], k * r[1]])
                .collect()
        })
        .collect();
    let m = config(2)
        .fit(&Demonstration::from_series(&series))
        .unwrap()
        .into_events();
    // where each demonstration's apex events are placed, raw units
    let apex = |h: &EventsHsom, d: &[Vec<f64>]| {
        let y = m.normalise_rows(d);
        let ev = bottom_events(h, &y);
        let node = ev.iter().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap().0;
        let node = if node == ev[0].0 {
            // the longest event is the rest; the apex is the longest other one
            ev.iter()
                .filter(|e| e.0 != ev[0].0)
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap()
                .0
        } else {
            node
        };
        let s = m.config.params().state_length;
        h.denormalise(&h.placement(&[])[node * s..(node + 1) * s])[0]
    };
    // the control: each node at its own samples' mean, each demonstration its own apex
    let norm: Vec<Vec<Vec<f64>>> = series.iter().map(|d| m.normalise_rows(d)).collect();
    let mut own = m.clone();
    own.part.knots = Some(m.own_postures(&norm));
    for d in &series {
        let amplitude = d.iter().map(|r| r[0]).fold(f64::MIN, f64::max);
        let toward_mean = |h: &EventsHsom| (apex(h, d) - 1.0).abs() < 0.7 * (amplitude - 1.0).abs();
        if (amplitude - 1.0).abs() < 0.1 {
            assert!((apex(&m, d) - 1.0).abs() < 0.05, "{}", apex(&m, d));
            continue;
        }
        // moved toward the mean apex (written: 0.80 -> 0.87, 1.20 -> 0.99), where the
        // demonstration's own samples leave it
        assert!(
            toward_mean(&m),
            "{amplitude}: consensus apex {}",
            apex(&m, d)
        );
        assert!(
            !toward_mean(&own),
            "{amplitude}: own apex {}",
            apex(&own, d)
        );
    }
}

#[test]
fn a_smooth_warp_moves_on_evenly_through_the_stairs() {
    let b: Vec<Vec<f64>> = (0..4).map(|i| vec![i as f64, -2.0 * i as f64]).collect();
    let stairs: Vec<f64> = (0..12).map(|x| (x / 3) as f64).collect();
    let read = smooth_warp(&stairs, &b);
    assert_eq!(read.len(), 12);
    assert_eq!((read[0][0], read[11][0]), (0.0, 3.0));
    let steps: Vec<f64> = read.windows(2).map(|w| w[1][0] - w[0][0]).collect();
    // the middles 1, 4, 7, 10 are a third of a sample of b apart, after the first run
    // and before the last
    for (x, d) in steps.iter().enumerate().skip(1).take(9) {
        assert!((d - 1.0 / 3.0).abs() < 1e-12, "step {x}: {d}");
    }
    assert!(
        steps.iter().all(|&d| (-1e-12..=0.5).contains(&d)),
        "{steps:?}"
    );
    // both variables read at the same place
    assert!(read.iter().all(|r| (r[1] + 2.0 * r[0]).abs() < 1e-12));
    let stepped: Vec<f64> = stairs.iter().map(|&y| b[y as usize][0]).collect();
    assert!(stepped.windows(2).any(|w| w[1] - w[0] == 1.0));
    let identity: Vec<f64> = (0..4).map(|x| x as f64).collect();
    assert_eq!(smooth_warp(&identity, &b), b);
    assert!(smooth_warp(&[], &b).is_empty());
}
