//! Unit tests of the events extension: several gestures in one model.

use super::*;

#[test]
fn each_branch_executes_its_own_gesture_on_the_shared_nodes() {
    // two gestures from the same rest posture along nearby paths, on a bottom too small
    // to give each its own nodes: the nodes they share sit between them (written:
    // own 0.025, weights 0.061, the other gesture's 0.078)
    let a: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
    let b: Vec<Vec<Vec<f64>>> = a
        .iter()
        .map(|d| d.iter().map(|r| vec![r[0], 1.6 * r[1]]).collect())
        .collect();
    let demos = |set: &[Vec<Vec<f64>>]| -> Vec<Demonstration> {
        set.iter()
            .map(|rows| Demonstration {
                source: "demo".into(),
                columns: vec!["x".into(), "y".into()],
                time: None,
                rows: rows.clone(),
            })
            .collect()
    };
    let mut p = config(2).params().clone();
    p.levels[0] = crate::config::LevelParams::new(4, 4, crate::som::Topology::Orthogonal, 0.1);
    let cfg = p.check("test").unwrap();
    let sets = vec![("a".to_string(), demos(&a)), ("b".to_string(), demos(&b))];
    let m = cfg.fit_model(&sets, crate::hsom::Fit::default()).unwrap();
    // mean distance between a demonstration and its re-encoding by a branch
    let err = |br: &EventsHsom, set: &[Demonstration]| {
        let mut e = 0.0;
        for d in set {
            let r = br.reencode(d).unwrap();
            assert_eq!(r.postures.len(), d.rows.len());
            e += r
                .postures
                .iter()
                .zip(&d.rows)
                .map(|(x, y)| dist2(x, y).sqrt())
                .sum::<f64>()
                / d.rows.len() as f64;
        }
        e / set.len() as f64
    };
    let (ba, bb) = (
        m.branches[0].as_events().unwrap(),
        m.branches[1].as_events().unwrap(),
    );
    assert!(ba.part.knots.is_some() && bb.part.knots.is_some());
    let weights_only = |br: &EventsHsom| {
        let mut m = br.clone();
        m.part.knots = None;
        m
    };
    let mut other = ba.clone();
    other.part.knots = bb.part.knots.clone();
    let (own, plain, wrong) = (
        err(ba, &sets[0].1),
        err(&weights_only(ba), &sets[0].1),
        err(&other, &sets[0].1),
    );
    // its own gesture's postures: closer than the shared nodes' weights; the other's: farther
    assert!(own < 0.7 * plain, "own {own} vs weights {plain}");
    assert!(
        wrong > plain,
        "the other gesture's postures {wrong} vs weights {plain}"
    );
    // one gesture through fit_model's labelled sets places them as fit does; an untrained model, or one
    // demonstration (nothing to agree on), executes the nodes' weights
    let alone = cfg
        .fit_model(&sets[..1], crate::hsom::Fit::default())
        .unwrap();
    assert_eq!(
        alone.branches[0].as_events().unwrap().part.knots,
        cfg.fit(&sets[0].1).unwrap().into_events().part.knots
    );
    assert!(cfg
        .fit_model(&sets, crate::hsom::Fit::UNTRAINED)
        .unwrap()
        .branches[0]
        .as_events()
        .unwrap()
        .part
        .knots
        .is_none());
    assert!(cfg
        .fit(&sets[0].1[..1])
        .unwrap()
        .into_events()
        .part
        .knots
        .is_none());
}

/// Velocity reversals of variable `v` of `rows` (changes under `still` ignored).
fn reversals(rows: &[Vec<f64>], v: usize, still: f64) -> usize {
    let mut last = None;
    let mut count = 0;
    for w in rows.windows(2) {
        let d = w[1][v] - w[0][v];
        if d.abs() > still {
            count += usize::from(last.is_some_and(|up| up != (d > 0.0)));
            last = Some(d > 0.0);
        }
    }
    count
}

#[test]
fn a_gesture_of_small_motions_keeps_its_swings_among_larger_ones() {
    use crate::hsom::inputs::{demo_series, Series};
    use crate::hsom::kept::Warm;
    use rand::SeedableRng;
    // four gestures sweeping x from the rest posture (0, 0) and back, and a nod: y reverses
    // five times, small beside them, x held at rest (the upper body's nod among arm gestures)
    let demo = |rows: Vec<Vec<f64>>| Demonstration {
        source: "demo".into(),
        columns: vec!["x".into(), "y".into()],
        time: None,
        rows,
    };
    let noisy = |seed: u64, f: &dyn Fn(f64) -> (f64, f64)| {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let n = 100 + 5 * (seed % 3) as usize;
        (0..n)
            .map(|i| {
                let (x, y) = f(i as f64 / (n - 1) as f64);
                vec![x + 0.002 * rng.gen::<f64>(), y + 0.002 * rng.gen::<f64>()]
            })
            .collect::<Vec<_>>()
    };
    let mut sets: Vec<(String, Vec<Demonstration>)> = (0..4)
        .map(|g| {
            let top = 0.4 + 0.2 * g as f64;
            let demos = (0..3)
                .map(|i| {
                    demo(noisy(10 * g + i, &|t| {
                        let x = top * (std::f64::consts::PI * t).sin();
                        (x, 0.2 * g as f64 * x)
                    }))
                })
                .collect();
            (format!("sweep{g}"), demos)
        })
        .collect();
    let nod = (0..3)
        .map(|i| {
            demo(noisy(100 + i, &|t| {
                (0.0, 0.1 * (5.0 * std::f64::consts::PI * t).sin())
            }))
        })
        .collect();
    sets.push(("nod".into(), nod));
    // a bottom of 16 nodes
    let mut p = config(2).params().clone();
    p.levels[0] = crate::config::LevelParams::new(4, 4, crate::som::Topology::Orthogonal, 0.1);
    let cfg = p.check("test").unwrap();
    let m = cfg.fit_model(&sets, crate::hsom::Fit::default()).unwrap();
    let swings = |b: &EventsHsom| {
        let rep = b.reproduce(&sets[4].1[0].rows[0]).unwrap();
        reversals(&rep.postures, 1, 0.002)
    };
    let want = reversals(&sets[4].1[0].rows, 1, 0.002);
    assert_eq!(want, 5, "the nod's demonstrations reverse five times");
    let own = swings(m.branches[4].as_events().unwrap());
    // the nod's levels on one bottom learned from every gesture's demonstrations, the
    // shared bottom level this model does not have: its nodes go where most of the data
    // moves, along x, and the nod's swings merge (written: 1 reversal against 5)
    let all: Vec<Demonstration> = sets.iter().flat_map(|(_, d)| d.clone()).collect();
    let series: Vec<Series<'_>> = demo_series(&all);
    let b = m.branches[4].as_events().unwrap();
    let units = Warm::units(&b.offset, &b.scale, cfg.params().seed);
    let mut shared_cfg = cfg.params().clone();
    shared_cfg.training_steps *= sets.len();
    let shared = shared_cfg
        .check("test")
        .unwrap()
        .fit_from(
            &series,
            None,
            true,
            vec!["x".into(), "y".into()],
            Some(&units),
        )
        .unwrap()
        .into_events();
    let norm: Vec<Vec<Vec<f64>>> = sets[4]
        .1
        .iter()
        .map(|d| b.normalise_rows(&d.rows))
        .collect();
    let on_shared = swings(&shared.build_branch(&norm, true, cfg.params().seed));
    assert!(
        own.abs_diff(want) <= 1,
        "own bottom: {own} swings, demonstrations {want}"
    );
    assert!(
        on_shared.abs_diff(want) > 1,
        "the control, a shared bottom: {on_shared} swings, demonstrations {want}"
    );
}
