//! Unit tests of updates: nothing taught changes nothing, the kept sample is bounded and
//! uniform, what an update refuses, and one gesture taught in two sittings.

use rand::{Rng, SeedableRng};

use super::*;
use crate::config::HsomConfig;
use crate::hsom::kept::reservoir;
use crate::hsom::KEPT_DEMONSTRATIONS;
use rand_chacha::ChaCha8Rng;

/// A 2-D stroke out and back, `seed` varying its holds and noise.
fn stroke(seed: u64, flip: bool) -> Demonstration {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let hold = 10 + rng.gen_range(0..5);
    let rows = (0..2 * hold + 60)
        .map(|i| {
            let u = ((i as f64 - hold as f64) / 60.0).clamp(0.0, 1.0);
            let x = (std::f64::consts::PI * u).sin() + 0.002 * rng.gen::<f64>();
            let y = u + 0.002 * rng.gen::<f64>();
            if flip {
                vec![-y, x]
            } else {
                vec![x, y]
            }
        })
        .collect::<Vec<Vec<f64>>>();
    Demonstration {
        source: format!("stroke-{seed}{}.csv", if flip { "-flipped" } else { "" }),
        columns: vec!["x".into(), "y".into()],
        time: Some((0..rows.len()).map(|k| k as f64 * 0.025).collect()),
        rows,
    }
}

fn config(paper: bool) -> HsomConfig {
    let mut p = crate::config::HsomParams::table1();
    if !paper {
        p.algorithm = crate::config::AlgorithmParams::Events(crate::config::EventsParams {
            change_ratio: 0.6,
            action_horizon: 3,
        });
    }
    p.state_length = 2;
    p.action_length = 2;
    p.height = 3;
    p.levels.truncate(3);
    p.levels[0] = crate::config::LevelParams::new(8, 8, crate::som::Topology::Orthogonal, 0.1);
    for l in 1..3 {
        p.levels[l] = crate::config::LevelParams::new(4, 4, crate::som::Topology::Orthogonal, 0.5);
    }
    p.training_steps = 2000;
    p.check("test").unwrap()
}

fn demos(seeds: std::ops::Range<u64>, flip: bool) -> Vec<Demonstration> {
    seeds.map(|s| stroke(s, flip)).collect()
}

#[test]
fn an_update_with_nothing_is_the_model_it_came_from() {
    for paper in [true, false] {
        let m = config(paper).fit(&demos(0..3, false)).unwrap();
        assert_eq!(m.update(&[]).unwrap(), m);
    }
    let g = config(false)
        .fit_model(
            &[("a".into(), demos(0..3, false))],
            crate::hsom::Fit::default(),
        )
        .unwrap();
    assert_eq!(g.update(Some("b"), &[], None).unwrap(), g);
    assert_eq!(g.update_labelled(&[], None).unwrap(), g);
    // the negative control: one demonstration more changes it
    assert_ne!(g.update(Some("a"), &demos(3..4, false), None).unwrap(), g);
}

#[test]
fn the_kept_sample_is_bounded_by_the_configuration_and_counts_what_was_learned() {
    let cfg = config(false);
    let m = cfg.fit(&demos(0..10, false)).unwrap();
    assert_eq!(m.learned(), (10, KEPT_DEMONSTRATIONS, 0));
    let size = |m: &Hsom| {
        m.file_parts()
            .iter()
            .find(|p| p.part.starts_with("kept demonstrations"))
            .unwrap()
            .bytes
    };
    let mut u = m.clone();
    for k in 0..3 {
        u = u.update(&demos(10 + 5 * k..15 + 5 * k, false)).unwrap();
    }
    assert_eq!(u.learned(), (25, KEPT_DEMONSTRATIONS, 3));
    assert_eq!(
        size(&u),
        size(&m),
        "the kept part grew with the demonstrations"
    );
    // kept paths are restored at their own lengths, in the data's units
    let Hsom::Events(e) = &u else { panic!() };
    let rows = e.kept_rows();
    assert_eq!(rows.len(), KEPT_DEMONSTRATIONS);
    assert!(
        rows.iter().all(|r| (80..=90).contains(&r.len())),
        "{:?}",
        rows.iter().map(Vec::len).collect::<Vec<_>>()
    );
    assert!(rows
        .iter()
        .flatten()
        .flatten()
        .all(|v| (-0.1..1.1).contains(v)));
}

#[test]
fn the_reservoir_keeps_every_demonstration_equally_often() {
    // 24 demonstrations, taught 12 then 4 x 3: each kept with probability 6/24 whatever
    // when it came
    let mut counts = [0usize; 24];
    let trials = 3000;
    for seed in 0..trials {
        let mut slots = Vec::new();
        let mut seen = 0;
        reservoir(&mut slots, &mut seen, 0..12usize, seed);
        for k in 0..3 {
            reservoir(&mut slots, &mut seen, 12 + 4 * k..16 + 4 * k, seed);
        }
        assert_eq!((slots.len(), seen), (KEPT_DEMONSTRATIONS, 24));
        slots.iter().for_each(|&i| counts[i] += 1);
    }
    let expected = trials as f64 * KEPT_DEMONSTRATIONS as f64 / 24.0;
    for (i, &c) in counts.iter().enumerate() {
        assert!(
            (c as f64 - expected).abs() < 0.15 * expected,
            "demonstration {i} kept {c} times, {expected} expected: {counts:?}"
        );
    }
}

#[test]
fn an_update_refuses_other_columns_and_rates_naming_the_file() {
    let m = config(false).fit(&demos(0..3, false)).unwrap();
    let mut other = stroke(7, false);
    other.columns = vec!["y".into(), "x".into()];
    let e = m.update(&[other]).unwrap_err().to_string();
    assert!(
        e.contains("stroke-7.csv") && e.contains("[\"y\", \"x\"]"),
        "{e}"
    );
    let mut slow = stroke(8, false);
    slow.time = Some((0..slow.rows.len()).map(|k| k as f64 * 0.05).collect());
    let e = m.update(&[slow]).unwrap_err().to_string();
    assert!(
        e.contains("stroke-8.csv") && e.contains("0.05") && e.contains("0.025"),
        "{e}"
    );
    // a model of one unlabelled gesture takes no labels
    let g: GestureModel = m.into();
    let e = g.update(Some("a"), &demos(3..4, false), None).unwrap_err();
    assert!(matches!(e, GestureError::UnlabelledUpdate), "{e}");
}

#[test]
fn an_update_that_would_count_past_the_bound_is_refused_before_training() {
    use crate::hsom::MAX_LEARNED;
    let counted = |m: &mut Hsom, learned: u64| match m {
        Hsom::Paper(m) => m.kept.learned = learned,
        Hsom::Events(m) => m.kept.learned = learned,
    };
    let mut m = config(false).fit(&demos(0..3, false)).unwrap();
    counted(&mut m, MAX_LEARNED - 1);
    let e = m.update(&demos(3..5, false)).unwrap_err();
    assert!(
        matches!(e, HsomError::TooManyLearned { learned, new: 2, .. } if learned == MAX_LEARNED - 1),
        "{e}"
    );
    assert!(
        e.to_string()
            .starts_with("the model learned from 999999999"),
        "{e}"
    );
    // negative control: up to the bound it is taught, and counted
    let u = m.update(&demos(3..4, false)).unwrap();
    assert_eq!(u.learned().0, MAX_LEARNED);
    // a gesture of several: named by its label; another gesture's count is its own
    let g = config(false)
        .fit_model(
            &[
                ("a".into(), demos(0..3, false)),
                ("b".into(), demos(0..3, true)),
            ],
            crate::hsom::Fit::default(),
        )
        .unwrap();
    let mut branches = g.branches.clone();
    counted(&mut branches[0], MAX_LEARNED);
    let full = GestureModel { branches, ..g };
    let e = full
        .update(Some("a"), &demos(3..4, false), None)
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("gesture \"a\" learned from 1000000000"),
        "{e}"
    );
    assert!(full.update(Some("b"), &demos(3..4, true), None).is_ok());
}

#[test]
fn a_gesture_in_two_sittings_reproduces_as_well_as_taught_at_once() {
    let cfg = config(false);
    let all = demos(0..6, false);
    let held = stroke(99, false);
    let score = |m: &Hsom| {
        let rep = m.reproduce(&held.rows[0]).unwrap();
        crate::dtw::dtw_distance(&rep.postures, &held.rows, crate::dtw::Band::None)
            .unwrap()
            .per_step()
    };
    let once = score(&cfg.fit(&all).unwrap());
    let sittings = score(&cfg.fit(&all[..3]).unwrap().update(&all[3..]).unwrap());
    assert!(
        sittings <= 1.05 * once,
        "in sittings {sittings}, at once {once}"
    );
    // the negative control: an update that is a training from scratch on another gesture's
    // files alone reproduces that gesture instead
    let other = score(&cfg.fit(&demos(0..3, true)).unwrap());
    assert!(
        other > 1.05 * once,
        "another gesture {other}, at once {once}"
    );
}
