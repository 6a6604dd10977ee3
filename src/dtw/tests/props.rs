//! DTW identities (proptest), hand-computed small cases, band behaviour and errors.

use crate::dtw::{dtw, dtw_distance, Band, DtwError};
use proptest::prelude::*;

fn seq(width: usize, max_len: usize) -> impl Strategy<Value = Vec<Vec<f64>>> {
    prop::collection::vec(prop::collection::vec(-10.0f64..10.0, width), 1..max_len)
}

fn pair() -> impl Strategy<Value = (Vec<Vec<f64>>, Vec<Vec<f64>>)> {
    (1usize..4).prop_flat_map(|w| (seq(w, 25), seq(w, 25)))
}

proptest! {
    #[test]
    fn distance_to_itself_is_zero(a in seq(3, 40)) {
        let al = dtw(&a, &a, Band::None).unwrap();
        prop_assert_eq!(al.distance, 0.0);
        // the diagonal is the cheapest path and wins ties
        let diag: Vec<(usize, usize)> = (0..a.len()).map(|i| (i, i)).collect();
        prop_assert_eq!(al.path, diag);
    }

    #[test]
    fn symmetric_and_non_negative((a, b) in pair()) {
        let ab = dtw(&a, &b, Band::None).unwrap();
        let ba = dtw(&b, &a, Band::None).unwrap();
        prop_assert!(ab.distance >= 0.0);
        prop_assert_eq!(ab.distance, ba.distance);
    }

    #[test]
    fn distance_only_agrees_with_full((a, b) in pair(), w in 0usize..10) {
        for band in [Band::None, Band::Samples(w), Band::Fraction(0.2)] {
            let full = dtw(&a, &b, band).unwrap();
            let light = dtw_distance(&a, &b, band).unwrap();
            prop_assert_eq!(full.distance, light.distance);
            prop_assert_eq!(full.path.len(), light.steps);
            prop_assert_eq!(full.normalized, light.per_step());
        }
    }

    #[test]
    fn path_is_monotone_continuous_and_its_cost_is_the_distance((a, b) in pair()) {
        let al = dtw(&a, &b, Band::None).unwrap();
        prop_assert_eq!(al.path[0], (0, 0));
        prop_assert_eq!(*al.path.last().unwrap(), (a.len() - 1, b.len() - 1));
        for s in al.path.windows(2) {
            let (di, dj) = (s[1].0 - s[0].0, s[1].1 - s[0].1);
            prop_assert!(di <= 1 && dj <= 1 && di + dj >= 1);
        }
        let cost: f64 = al.path.iter().map(|&(i, j)| {
            a[i].iter().zip(&b[j]).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
        }).sum();
        prop_assert!((cost - al.distance).abs() <= 1e-9 * (1.0 + cost));
        prop_assert!(al.path.len() >= a.len().max(b.len()));
        prop_assert!(al.path.len() < a.len() + b.len());
    }

    #[test]
    fn a_band_never_lowers_the_distance((a, b) in pair(), w in 0usize..10) {
        let free = dtw_distance(&a, &b, Band::None).unwrap().distance;
        let banded = dtw_distance(&a, &b, Band::Samples(w)).unwrap().distance;
        prop_assert!(banded.is_finite());
        prop_assert!(banded >= free);
    }
}

#[test]
fn hand_computed_one_dimensional_case() {
    // a = [0, 2, 4], b = [0, 4]
    // local costs        b0  b1
    //             a0      0   4
    //             a1      2   2
    //             a2      4   0
    // D: a0: 0, 4 ; a1: 2, 2 (=2+min(0,4,2)) ; a2: 6, 2 (=0+min(2,2,6))
    // the last cell ties between its diagonal (a1,b0) and (a1,b1): the diagonal wins
    let a = vec![vec![0.0], vec![2.0], vec![4.0]];
    let b = vec![vec![0.0], vec![4.0]];
    let al = dtw(&a, &b, Band::None).unwrap();
    assert_eq!(al.distance, 2.0);
    assert_eq!(al.path, vec![(0, 0), (1, 0), (2, 1)]);
    assert_eq!(al.normalized, 2.0 / 3.0);
}

#[test]
fn hand_computed_two_dimensional_case() {
    // a = [(0,0), (3,4)], b = [(0,0), (0,0), (3,4)]: the repeat costs nothing
    let a = vec![vec![0.0, 0.0], vec![3.0, 4.0]];
    let b = vec![vec![0.0, 0.0], vec![0.0, 0.0], vec![3.0, 4.0]];
    let al = dtw(&a, &b, Band::None).unwrap();
    assert_eq!(al.distance, 0.0);
    assert_eq!(al.path, vec![(0, 0), (0, 1), (1, 2)]);
    // against a constant shift of (3,4): every step costs 5
    let c = vec![vec![3.0, 4.0], vec![6.0, 8.0]];
    assert_eq!(dtw(&a, &c, Band::None).unwrap().distance, 5.0 + 5.0);
}

#[test]
fn narrow_band_forces_a_costlier_path() {
    // b is a delayed by 3 samples; without a band the warp absorbs the delay
    let a: Vec<Vec<f64>> = (0..20).map(|i| vec![((i as f64) * 0.4).sin()]).collect();
    let mut b = vec![a[0].clone(); 3];
    b.extend_from_slice(&a[..17]);
    let free = dtw(&a, &b, Band::None).unwrap();
    let tight = dtw(&a, &b, Band::Samples(0)).unwrap();
    assert!(tight.distance > free.distance + 0.5);
    assert!(tight.path.iter().all(|&(i, j)| i == j));
}

#[test]
fn slices_of_rows_work_too() {
    let a: Vec<[f64; 2]> = vec![[0.0, 0.0], [1.0, 1.0]];
    let b: Vec<[f64; 2]> = vec![[0.0, 0.0], [1.0, 1.0]];
    assert_eq!(dtw(&a, &b, Band::None).unwrap().distance, 0.0);
    let sa: Vec<&[f64]> = a.iter().map(|r| &r[..]).collect();
    assert_eq!(dtw_distance(&sa, &sa, Band::None).unwrap().distance, 0.0);
}

#[test]
fn bad_inputs_are_clear_errors() {
    let empty: Vec<Vec<f64>> = vec![];
    let one = vec![vec![1.0, 2.0]];
    assert_eq!(
        dtw(&empty, &one, Band::None).unwrap_err(),
        DtwError::Empty { len_a: 0, len_b: 1 }
    );
    let narrow = vec![vec![1.0]];
    let e = dtw(&one, &narrow, Band::None).unwrap_err();
    assert!(matches!(
        e,
        DtwError::Width {
            which: "second",
            index: 0,
            expected: 2,
            found: 1
        }
    ));
    assert!(e.to_string().contains("second"));
    let nan = vec![vec![f64::NAN, 0.0]];
    assert!(matches!(
        dtw_distance(&one, &nan, Band::None),
        Err(DtwError::NotFinite { .. })
    ));
    for f in [-0.1, 1.5, f64::NAN] {
        assert!(matches!(
            dtw(&one, &one, Band::Fraction(f)),
            Err(DtwError::BandFraction { .. })
        ));
    }
}
