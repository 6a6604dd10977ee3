//! Training through the public API: the schedule, list clearing, determinism, progress, errors.

use crate::hsom_common;

use cosco_hsom::config::{HsomParams, LevelParams, MemoryMode};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::hsom::HsomError;
use cosco_hsom::som::Topology;

fn small(height: usize, update_period: usize, memory: usize, steps: usize) -> HsomParams {
    let mut p = HsomParams::table1();
    p.height = height;
    p.paper_mut().unwrap().update_period = update_period;
    p.memory = memory;
    p.training_steps = steps;
    p.state_length = 2;
    p.action_length = 2;
    p.levels = (0..height)
        .map(|l| LevelParams::new(4 + l, 4, Topology::Orthogonal, 0.3))
        .collect();
    p.paper_mut().unwrap().offset = 1;
    p
}

fn line(n: usize, name: &str) -> Demonstration {
    Demonstration {
        source: name.into(),
        columns: vec!["a".into(), "b".into()],
        time: None,
        rows: (0..n)
            .map(|i| vec![i as f64, (i * i) as f64 * 0.1])
            .collect(),
    }
}

#[test]
fn footnote_2_schedule_after_step_7() {
    // updatePeriod 2, three levels: after step 7 the levels were trained 7, 3 and 1 times
    // (memory 1: a list is full from its first entry)
    let p = small(3, 2, 1, 7);
    let m = p.check("t").unwrap().fit(&[line(20, "d")]).unwrap();
    assert_eq!(m.trained_counts(), &[7, 3, 1]);
}

#[test]
fn schedule_over_a_long_run_is_steps_over_period_to_the_level() {
    let p = small(4, 3, 1, 1000);
    let m = p.check("t").unwrap().fit(&[line(2000, "d")]).unwrap();
    assert_eq!(m.trained_counts(), &[1000, 333, 111, 37]);
}

#[test]
fn activity_lists_are_cleared_when_a_demonstration_ends() {
    // memory 4, updatePeriod 1, lists must be full to train level 1 ("skip"). A demonstration
    // of 4 samples gives 3 state-action pairs: if lists were not cleared between
    // demonstrations they would fill up and level 1 would train.
    let p = small(2, 1, 4, 300);
    let m = p
        .clone()
        .check("t")
        .unwrap()
        .fit(&[line(4, "a"), line(4, "b")])
        .unwrap();
    assert_eq!(m.trained_counts(), &[300, 0]);
    // with 6 samples (5 pairs) per demonstration the list is full at pairs 4 and 5 only:
    // 2 of every 5 steps
    let m = p.check("t").unwrap().fit(&[line(6, "a")]).unwrap();
    assert_eq!(m.trained_counts(), &[300, 120]);
}

#[test]
fn same_seed_gives_a_bit_identical_model_and_another_seed_does_not() {
    let demos = hsom_common::stroke(3, 1);
    let mut p = small(3, 2, 4, 1500);
    let a = p.clone().check("t").unwrap().fit(&demos).unwrap();
    let b = p.clone().check("t").unwrap().fit(&demos).unwrap();
    assert_eq!(a, b);
    assert_eq!(a.to_bytes(), b.to_bytes());
    p.seed = 99;
    let c = p.check("t").unwrap().fit(&demos).unwrap();
    assert_ne!(a.maps()[0].all_weights(), c.maps()[0].all_weights());
}

#[test]
fn progress_callback_reports_up_to_the_total() {
    let p = small(2, 2, 4, 500).check("t").unwrap();
    let seen = std::cell::RefCell::new(Vec::new());
    let cb = |done: usize, total: usize| seen.borrow_mut().push((done, total));
    p.fit_model(
        &[line(50, "d")],
        cosco_hsom::hsom::Fit {
            progress: Some(&cb),
            untrained: false,
        },
    )
    .map(|m| m.branches()[0].clone())
    .unwrap();
    let seen = seen.into_inner();
    assert!(seen.len() >= 50 && seen.len() <= 101, "{}", seen.len());
    assert_eq!(*seen.last().unwrap(), (500, 500));
    assert!(seen.windows(2).all(|w| w[0].0 < w[1].0));
}

#[test]
fn initial_weights_lie_in_the_data_bounding_box_whatever_the_units() {
    // data in thousands: the untrained bottom map must already lie inside the data's box
    let d = Demonstration {
        source: "big".into(),
        columns: vec!["a".into(), "b".into()],
        time: None,
        rows: (0..100)
            .map(|i| vec![5000.0 + i as f64 * 10.0, -3000.0 - i as f64])
            .collect(),
    };
    let m = small(2, 2, 4, 10)
        .check("t")
        .unwrap()
        .fit_model(std::slice::from_ref(&d), cosco_hsom::hsom::Fit::UNTRAINED)
        .map(|m| m.branches()[0].clone())
        .unwrap();
    // postures are the nodes' action halves
    let rep = m.reproduce(&d.rows[0]).unwrap();
    for y in &rep.postures[1..] {
        assert!(
            y[0] >= 4999.0 && y[0] <= 6000.0 && y[1] <= -2999.0 && y[1] >= -3100.0,
            "{y:?}"
        );
    }
}

#[test]
fn levels_memory_mode_trains_on_activity_maps() {
    let mut p = small(3, 2, 4, 400);
    p.paper_mut().unwrap().memory_mode = MemoryMode::Levels;
    let m = p
        .check("t")
        .unwrap()
        .fit(&hsom_common::stroke(2, 3))
        .unwrap();
    assert_eq!(m.maps()[1].dim(), 4 * 4);
    assert_eq!(m.maps()[2].dim(), 5 * 4);
    assert!(m.trained_counts()[1] > 0);
    let rep = m.reproduce(&[0.0, 0.0]).unwrap();
    assert!(rep.postures.len() > 1);
}

#[test]
fn summary_lists_every_level_with_quality() {
    let demos = hsom_common::stroke(3, 2);
    let m = small(3, 2, 4, 2000)
        .check("t")
        .unwrap()
        .fit(&demos)
        .unwrap();
    let s = m.summary();
    assert_eq!(s.levels.len(), 3);
    assert_eq!(
        (s.levels[1].rows, s.levels[1].cols, s.levels[1].period),
        (5, 4, 2)
    );
    assert!(s
        .levels
        .iter()
        .all(|l| l.quantization_error.is_finite() && (0.0..=1.0).contains(&l.topographic_error)));
    let untrained = small(3, 2, 4, 2000)
        .check("t")
        .unwrap()
        .fit_model(&demos, cosco_hsom::hsom::Fit::UNTRAINED)
        .map(|m| m.branches()[0].clone())
        .unwrap();
    assert!(s.levels[0].quantization_error < untrained.summary().levels[0].quantization_error);
    let text = s.to_string();
    assert!(text.contains("level") && text.contains("5x4"), "{text}");
}

#[test]
fn bad_demonstrations_are_clear_errors() {
    let c = small(2, 2, 4, 10).check("t").unwrap();
    assert!(matches!(c.fit(&[]), Err(HsomError::NoDemonstrations)));
    assert!(matches!(
        c.fit(&[line(1, "one")]),
        Err(HsomError::TooShort { rows: 1, .. })
    ));
    let mut d = line(5, "wide");
    d.rows[2].push(1.0);
    let e = c.fit(&[d]).unwrap_err();
    assert!(
        matches!(
            e,
            HsomError::DimensionMismatch {
                row: 2,
                expected: 2,
                found: 3,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("wide"));
    let mut d = line(5, "nan");
    d.rows[3][1] = f64::NAN;
    assert!(matches!(
        c.fit(&[d]),
        Err(HsomError::NonFinite {
            row: 3,
            column: 1,
            ..
        })
    ));
    let m = c.fit(&[line(5, "ok")]).unwrap();
    assert!(matches!(
        m.reproduce(&[1.0]),
        Err(HsomError::DimensionMismatch { .. })
    ));
    assert!(matches!(
        m.reproduce(&[1.0, f64::INFINITY]),
        Err(HsomError::NonFinite { .. })
    ));
}

#[test]
fn partial_matching_ignores_unknown_slots() {
    use cosco_hsom::hsom::ActivityList;
    use cosco_hsom::som::SelfOrganizingMap;
    // memory 4; three known entries go into the three oldest slots, slot 0 is unknown.
    let mut list = ActivityList::new(4);
    for id in [(1, 1), (2, 2), (3, 3)] {
        list.push(id);
    }
    // node 0 recalls the known history exactly and predicts (9, 9) in slot 0;
    // node 1 is closer on every slot counted together but wrong on the known ones.
    let node0 = [9.0, 9.0, 3.0, 3.0, 2.0, 2.0, 1.0, 1.0];
    let node1 = [0.0, 0.0, 3.5, 3.5, 2.5, 2.5, 1.5, 1.5];
    let w: Vec<f64> = node0.iter().chain(&node1).cloned().collect();
    let map = SelfOrganizingMap::from_weights(1, 2, 8, Topology::Orthogonal, w).unwrap();
    let mut x = vec![0.0; 8];
    let mut mask = vec![true; 8];
    list.encode(3, 1, &mut x, &mut mask);
    assert_eq!(&mask[..2], &[false, false]);
    assert_eq!(map.bmu_masked(&x, &mask).0, 0);
    // counting the unknown slot as zeros would pick the wrong node
    assert_eq!(map.bmu(&x).0, 1);
}

#[test]
fn hexagonal_hierarchy_trains_and_reproduces() {
    let mut p = small(3, 2, 4, 1000);
    for l in p.levels.iter_mut() {
        l.topology = Topology::Hexagonal;
    }
    let demos = hsom_common::stroke(3, 4);
    let m = p.check("t").unwrap().fit(&demos).unwrap();
    assert_eq!(m.maps()[0].topology(), Topology::Hexagonal);
    let rep = m.reproduce(&demos[0].rows[0]).unwrap();
    assert!(rep.postures.len() > 2 && rep.postures.iter().all(|y| y.iter().all(|v| v.is_finite())));
}

#[test]
fn random_small_configurations_never_panic_and_round_trip() {
    use cosco_hsom::config::IdDecoding;
    use cosco_hsom::hsom::Hsom;
    use rand::{Rng, SeedableRng};
    let dir = tempfile::tempdir().unwrap();
    for seed in 0..40u64 {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let dims = rng.gen_range(1..5);
        let height = rng.gen_range(1..5);
        let memory = rng.gen_range(1..6);
        let mut p = small(height, rng.gen_range(1..4), memory, rng.gen_range(1..300));
        p.state_length = dims;
        p.action_length = dims;
        for l in p.levels.iter_mut() {
            *l = LevelParams::new(
                rng.gen_range(1..7),
                rng.gen_range(1..7),
                if rng.gen() {
                    Topology::Hexagonal
                } else {
                    Topology::Orthogonal
                },
                rng.gen_range(0.05..1.0),
            );
        }
        p.paper_mut().unwrap().memory_mode = if rng.gen_bool(0.3) {
            MemoryMode::Levels
        } else {
            MemoryMode::Lists
        };
        p.paper_mut().unwrap().offset = rng.gen_range(1..=memory);
        p.paper_mut().unwrap().id_decoding =
            [IdDecoding::Round, IdDecoding::Floor, IdDecoding::Nearest][rng.gen_range(0..3)];
        p.reproduction.max_length = rng.gen_range(1..300);
        let cfg = p.check("random").unwrap();
        let demos: Vec<Demonstration> = (0..rng.gen_range(1..4))
            .map(|i| Demonstration {
                source: format!("r{i}"),
                columns: (0..dims).map(|d| format!("c{d}")).collect(),
                time: None,
                rows: (0..rng.gen_range(2..60))
                    .map(|_| (0..dims).map(|_| rng.gen_range(-1e3..1e3)).collect())
                    .collect(),
            })
            .collect();
        let m = cfg.fit(&demos).unwrap();
        let rep = m.reproduce(&demos[0].rows[0]).unwrap();
        assert!(
            !rep.postures.is_empty() && rep.postures.len() <= cfg.params().reproduction.max_length
        );
        assert!(
            rep.postures.iter().flatten().all(|v| v.is_finite()),
            "seed {seed}"
        );
        for ext in ["bin", "txt"] {
            let path = dir.path().join(format!("m{seed}.{ext}"));
            m.save(&path).unwrap();
            assert_eq!(Hsom::load(&path).unwrap(), m, "seed {seed} {ext}");
        }
    }
}
