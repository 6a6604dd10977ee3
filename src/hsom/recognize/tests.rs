use super::{new_demonstration_bounds, t99, weights, Weighing};
use crate::dtw::{dtw_distance, Band};

/// 14 variables at rest drifting (slowly, each at its own pace and phase from `seed`),
/// variable `moving` swung `swings` times (the upper body's nod moves HeadPitch, its
/// shake HeadYaw).
fn gesture(moving: usize, swings: f64, seed: u64) -> Vec<Vec<f64>> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let drift: Vec<(f64, f64)> = (0..14)
        .map(|_| {
            (
                0.2 + 0.5 * rng.gen::<f64>(),
                std::f64::consts::TAU * rng.gen::<f64>(),
            )
        })
        .collect();
    (0..200)
        .map(|t| {
            let phase = t as f64 / 199.0;
            let mut row: Vec<f64> = (drift.iter())
                .map(|(f, p)| 0.08 * (std::f64::consts::TAU * f * phase + p).sin())
                .collect();
            row[moving] += 0.5 * (std::f64::consts::TAU * swings * phase).sin();
            row
        })
        .collect()
}

#[test]
fn weighing_what_a_gesture_moves_tells_a_nod_from_a_shake_where_every_variable_alike_does_not() {
    let nods: Vec<Vec<Vec<f64>>> = (0..4).map(|s| gesture(1, 2.0, s)).collect();
    let reproduction = &nods[0];
    let (nod, shake) = (gesture(1, 2.0, 10), gesture(0, 2.0, 11));
    // the nod's score of a new nod and of a shake, weighed by `k`
    let ratio = |k: &Weighing| {
        let d = |x: &[Vec<f64>]| {
            dtw_distance(&k.rows(x), &k.rows(reproduction), Band::None)
                .unwrap()
                .per_step()
        };
        d(&shake) / d(&nod)
    };
    let w = weights(&nods, 14);
    assert!(w[1] > 3.0 && w[0] < 1.0, "{w:?}");
    let weighed = ratio(&Weighing::with(w, reproduction, 1));
    // the negative control: every variable weighed 1, values only (the score before)
    let alike = ratio(&Weighing {
        w: vec![1.0; 14],
        rate: 0.0,
        span: 1,
    });
    assert!(
        weighed > 3.0,
        "weighed: a shake {weighed} x a nod's score; alike {alike}"
    );
    assert!(alike < 0.6 * weighed, "alike: {alike} against {weighed}");
}

#[test]
fn the_bound_of_a_new_demonstration_widens_with_the_spread_and_the_fewness_of_scores() {
    // Student's t, as the tables print it
    assert_eq!(t99(1), 31.821);
    assert_eq!(t99(6), 3.143);
    assert_eq!(t99(30), 2.457);
    assert_eq!(t99(40), 2.423);
    assert!(t99(31) < t99(30) && t99(31) > t99(40));
    let bound = |own: &[f64]| new_demonstration_bounds(&[own.to_vec()])[0];
    // equal scores: no spread, the bound is the score
    assert!((bound(&[0.2; 6]) - 0.2).abs() < 1e-12);
    // above the scores when they spread
    let own = [0.02, 0.025, 0.03, 0.022, 0.028, 0.035];
    let b = bound(&own);
    assert!(b > 0.035 && b < 0.07, "{b}");
    // fewer scores of the same spread: a wider bound
    assert!(bound(&own[..3]) > bound(&own[..3].repeat(2)));
    // one score: twice it; none: 0; a zero score: finite
    assert_eq!(bound(&[0.1]), 0.2);
    assert_eq!(bound(&[]), 0.0);
    assert!(bound(&[0.0, 0.1, 0.12]).is_finite());
    // the spread is pooled: a label whose few scores happen to agree gets the spread
    // the other labels show, at its own level
    let tight = [0.0100, 0.0101, 0.0102];
    let alone = bound(&tight);
    let pooled = new_demonstration_bounds(&[tight.to_vec(), own.to_vec()]);
    assert!(pooled[0] > 1.2 * alone, "{pooled:?} against {alone}");
    assert!(pooled[0] < pooled[1], "{pooled:?}");
    // located at the median: one own score of a branch that reproduced badly does not
    // carry the bound up to it
    let odd = [0.055, 0.057, 0.06, 0.15];
    let b = new_demonstration_bounds(&[odd.to_vec(), own.to_vec(), own.to_vec()]);
    assert!(b[0] < 0.15 && b[0] > 0.06, "{b:?}");
}
