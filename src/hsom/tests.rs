//! The settings each algorithm reads beyond Table I's numbers (docs/CONFIG.md): the measured
//! prediction accuracy, the events algorithm's action horizon, the column names stored in the
//! model, and small configurations of either algorithm.

#[path = "../../tests/hsom_common/mod.rs"]
mod hsom_common;

use crate::demos::Demonstration;
use crate::hsom::Hsom;
use hsom_common::*;

/// A 2-D gesture with a long, perfectly still start and end (the paper's footnote 3): out
/// along a quarter circle and back.
fn idle_gesture(k: usize) -> Vec<Demonstration> {
    (0..k)
        .map(|i| {
            let mut rows = vec![vec![0.0, 0.0]; 40 + 10 * i];
            let m = 80;
            for j in 0..=m {
                let t = std::f64::consts::PI * j as f64 / m as f64;
                let s = t.sin();
                rows.push(vec![s, s * s * 0.6]);
            }
            rows.extend(std::iter::repeat(vec![0.0, 0.0]).take(50 - 10 * i));
            Demonstration {
                source: format!("idle{i}"),
                columns: vec!["u".into(), "v".into()],
                time: None,
                rows,
            }
        })
        .collect()
}

#[test]
fn accuracy_is_measured_per_level() {
    let demos = stroke(4, 3);
    let model = table1_for(2).fit(&demos).unwrap();
    let acc = model.prediction_accuracy();
    assert_eq!(acc.len(), 6);
    assert_eq!(acc[0], 0.0);
    assert!(acc.iter().all(|a| (0.0..=1.0).contains(a)));
    assert!(
        acc[1] > 0.0,
        "level 1 never predicted its next entry: {acc:?}"
    );
    let s = model.summary();
    assert_eq!(s.levels[1].prediction_accuracy, acc[1]);
}

#[test]
fn action_horizon_changes_the_bottom_input_and_keeps_reproducing() {
    let demos = joints6(4, 21);
    let mut p = recommended_for(6).into_params();
    p.events_mut().unwrap().action_horizon = 1;
    let a = p.clone().check("t").unwrap().fit(&demos[1..]).unwrap();
    p.events_mut().unwrap().action_horizon = 10;
    let b = p.clone().check("t").unwrap().fit(&demos[1..]).unwrap();
    assert_ne!(a.maps()[0].all_weights(), b.maps()[0].all_weights());
    let e = relative_dtw(
        &b.reproduce(&demos[0].rows[0]).unwrap().postures,
        &demos[1..],
    );
    let u = p
        .check("t")
        .unwrap()
        .fit_model(&demos[1..], cosco_hsom::hsom::Fit::UNTRAINED)
        .map(|m| m.branches()[0].clone())
        .unwrap();
    let eu = relative_dtw(
        &u.reproduce(&demos[0].rows[0]).unwrap().postures,
        &demos[1..],
    );
    println!("horizon 10: {e:.4}, untrained {eu:.4}");
    assert!(e < 0.5 * eu, "horizon 10 {e}, untrained {eu}");
}

#[test]
fn the_model_keeps_the_column_names_in_both_formats() {
    let demos = idle_gesture(2);
    let cfg = table1_for(2);
    let m = cfg.fit(&demos).unwrap();
    assert_eq!(m.columns(), &["u".to_string(), "v".to_string()]);
    let series: Vec<Vec<Vec<f64>>> = demos.iter().map(|d| d.rows.clone()).collect();
    let s = cfg
        .fit(&cosco_hsom::demos::Demonstration::from_series(&series))
        .unwrap();
    assert_eq!(s.columns(), &["x0".to_string(), "x1".to_string()]);
    let dir = tempfile::tempdir().unwrap();
    for name in ["m.bin", "m.txt"] {
        let p = dir.path().join(name);
        m.save(&p).unwrap();
        let back = Hsom::load(&p).unwrap();
        assert_eq!(back.columns(), m.columns(), "{name}");
        assert_eq!(back, m, "{name}");
    }
}

#[test]
fn small_configurations_of_either_algorithm_never_panic_and_round_trip() {
    use crate::config::{AlgorithmParams, EventsParams, LevelParams, MemoryMode};
    use crate::som::Topology;
    let demos = idle_gesture(2);
    let dir = tempfile::tempdir().unwrap();
    let mut n = 0;
    for height in [1, 2, 3] {
        for memory in [1, 2, 4] {
            // the paper's two memories, then the events algorithm at three action horizons
            let kinds = [
                (Some(MemoryMode::Lists), 1),
                (Some(MemoryMode::Levels), 1),
                (None, 1),
                (None, 3),
                (None, 500),
            ];
            for (mode, horizon) in kinds {
                let mut p = table1_for(2).into_params();
                p.height = height;
                p.memory = memory;
                match mode {
                    Some(m) => {
                        let q = p.paper_mut().unwrap();
                        q.memory_mode = m;
                        q.offset = memory.min(q.offset).max(1);
                    }
                    None => {
                        p.algorithm = AlgorithmParams::Events(EventsParams {
                            change_ratio: 0.6,
                            action_horizon: horizon,
                        })
                    }
                }
                p.training_steps = 300;
                p.levels = (0..height)
                    .map(|l| LevelParams::new(3 + l, 2, Topology::Hexagonal, 0.4))
                    .collect();
                p.reproduction.max_length = 200;
                let cfg = p.check("t").unwrap();
                if demos.iter().any(|d| d.len() <= horizon) {
                    // a horizon longer than a demonstration is refused, naming it
                    let e = cfg.fit(&demos).unwrap_err();
                    assert!(
                        matches!(e, crate::hsom::HsomError::TooShort { needed, .. } if needed == horizon + 1),
                        "{e}"
                    );
                    continue;
                }
                let m = cfg.fit(&demos).unwrap();
                let rep = m.reproduce(&demos[0].rows[0]).unwrap();
                assert!(!rep.postures.is_empty() && rep.postures.len() <= 200);
                assert!(rep.postures.iter().flatten().all(|v| v.is_finite()));
                let path = dir.path().join(format!("m{n}.txt"));
                m.save(&path).unwrap();
                assert_eq!(Hsom::load(&path).unwrap(), m);
                n += 1;
            }
        }
    }
}
