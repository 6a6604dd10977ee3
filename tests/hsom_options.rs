//! The options that depart from the literal paper (docs/ALGORITHM.md): one test each, plus
//! the column names stored in the model.

mod hsom_common;

use cosco_hsom::config::{HsomParams, ListUpdate, Reflex, Timing};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::hsom::Hsom;
use hsom_common::*;

/// Table I with the options of the shipped configs/table1.xml, for `dims` variables.
fn file_options(dims: usize) -> HsomParams {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/configs/successor-table.xml");
    let mut p = cosco_hsom::config::load_config(&path)
        .unwrap()
        .into_params();
    p.state_length = dims;
    p.action_length = dims;
    p
}

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

fn max_excursion(rows: &[Vec<f64>], from: &[f64]) -> f64 {
    rows.iter()
        .map(|r| {
            r.iter()
                .zip(from)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max)
}

#[test]
fn on_change_lists_count_training_steps_in_list_updates() {
    // 5000 list updates need many more samples when the data sit still for long stretches
    let demos = idle_gesture(3);
    let mut p = file_options(2);
    p.list_update = ListUpdate::OnChange;
    let m = p.clone().check("t").unwrap().fit(&demos).unwrap();
    let t = m.trained_counts();
    assert!(t[0] > 5000, "bottom trained {}", t[0]);
    // level 1 trains on (almost) every other list update, as with everyStep
    assert!(t[1] > 2000 && t[1] <= 2500, "level 1 trained {}", t[1]);
    p.list_update = ListUpdate::EveryStep;
    let e = p.check("t").unwrap().fit(&demos).unwrap();
    assert_eq!(e.trained_counts()[0], 5000);
}

#[test]
fn successor_reflex_leaves_an_idle_start_that_the_bmu_reflex_cannot() {
    let demos = idle_gesture(3);
    let mut p = file_options(2);
    p.reproduction.reflex = Reflex::Bmu;
    let model = p.clone().check("t").unwrap().fit(&demos).unwrap();
    let init = &demos[0].rows[0];
    let bmu = model.reproduce(init).unwrap();
    let mut r = p.reproduction.clone();
    r.reflex = Reflex::Successor;
    let succ = model.reproduce_with(init, &r).unwrap();
    let (eb, es) = (
        max_excursion(&bmu.postures, init),
        max_excursion(&succ.postures, init),
    );
    println!("bmu reflex excursion {eb:.3}, successor reflex {es:.3}");
    // the gesture goes 1.17 away from the start
    assert!(eb < 0.1, "the BMU reflex left the idle start ({eb})");
    assert!(
        es > 0.5,
        "the successor reflex did not leave the idle start ({es})"
    );
}

#[test]
fn dwell_timing_restores_the_time_spent_on_each_node() {
    let demos = idle_gesture(3);
    let p = file_options(2);
    let model = p.clone().check("t").unwrap().fit(&demos).unwrap();
    let init = &demos[0].rows[0];
    let mut r = p.reproduction.clone();
    r.stop = cosco_hsom::config::StopRule::Learned;
    // the whole hierarchy predicts (its expansions skip key postures)
    r.min_accuracy = 0.0;
    r.timing = Timing::Dwell;
    let dwell = model.reproduce_with(init, &r).unwrap();
    r.timing = Timing::Speed;
    let speed_timing = model.reproduce_with(init, &r).unwrap();
    r.timing = Timing::Step;
    let step = model.reproduce_with(init, &r).unwrap();
    println!(
        "dwell: {} postures ({:?}), step: {} postures ({:?})",
        dwell.postures.len(),
        dwell.stop,
        step.postures.len(),
        step.stop
    );
    // speed: mean distance between consecutive postures while moving
    let speed = |rows: &[Vec<f64>]| {
        let steps: Vec<f64> = rows
            .windows(2)
            .map(|w| {
                w[0].iter()
                    .zip(&w[1])
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>()
                    .sqrt()
            })
            .filter(|&d| d > 1e-6)
            .collect();
        steps.iter().sum::<f64>() / steps.len().max(1) as f64
    };
    let demo_speed = demos.iter().map(|d| speed(&d.rows)).sum::<f64>() / demos.len() as f64;
    let (sd, ss) = (speed(&dwell.postures), speed(&step.postures));
    let sv = speed(&speed_timing.postures);
    println!("speed: demos {demo_speed:.4}, dwell {sd:.4}, speed {sv:.4}, step {ss:.4}");
    assert!(
        (sv / demo_speed).ln().abs() < (ss / demo_speed).ln().abs(),
        "speed-timed pace {sv} vs demos {demo_speed} (step {ss})"
    );
    // one posture per key node jumps from node to node; the dwell restores the pace
    assert!(
        ss > 2.0 * demo_speed,
        "step timing is not faster: {ss} vs {demo_speed}"
    );
    assert!(
        (sd / demo_speed).ln().abs() < (ss / demo_speed).ln().abs(),
        "dwell pace {sd} vs demos {demo_speed} (step {ss})"
    );
}

#[test]
fn accuracy_is_measured_per_level_and_min_accuracy_keeps_confused_levels_out() {
    let demos = stroke(4, 3);
    let p = file_options(2);
    let model = p.clone().check("t").unwrap().fit(&demos).unwrap();
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
    // a threshold no level reaches: only the reflex predicts
    let mut r = p.reproduction.clone();
    r.min_accuracy = 1.0;
    let rep = model.reproduce_with(&demos[0].rows[0], &r).unwrap();
    assert!(rep.predicted_by.iter().all(|&l| l == 0));
    // with level 1's own accuracy as the threshold, level 1 (and any level that measured at
    // least as well) predicts, no other
    r.min_accuracy = acc[1];
    let rep = model.reproduce_with(&demos[0].rows[0], &r).unwrap();
    assert!(rep.predicted_by.iter().any(|&l| l >= 1));
    assert!(rep
        .predicted_by
        .iter()
        .all(|&l| l == 0 || acc[l] >= r.min_accuracy));
}

#[test]
fn action_horizon_changes_the_bottom_input_and_keeps_reproducing() {
    let demos = joints6(4, 21);
    let mut p = file_options(6);
    p.action_horizon = 1;
    let a = p.clone().check("t").unwrap().fit(&demos[1..]).unwrap();
    p.action_horizon = 10;
    let b = p.clone().check("t").unwrap().fit(&demos[1..]).unwrap();
    assert_ne!(a.maps()[0].all_weights(), b.maps()[0].all_weights());
    let e = relative_dtw(
        &b.reproduce(&demos[0].rows[0]).unwrap().postures,
        &demos[1..],
    );
    let u = p.check("t").unwrap().initialise(&demos[1..]).unwrap();
    let eu = relative_dtw(
        &u.reproduce(&demos[0].rows[0]).unwrap().postures,
        &demos[1..],
    );
    println!("horizon 10: {e:.4}, untrained {eu:.4}");
    assert!(e < 0.5 * eu, "horizon 10 {e}, untrained {eu}");
}

#[test]
fn shipped_options_reproduce_idle_gestures_and_the_untrained_control_does_not() {
    for (name, demos) in [("joints6", joints6(5, 9)), ("idle", idle_gesture(3))] {
        let dims = demos[0].rows[0].len();
        let cfg = file_options(dims).check("t").unwrap();
        let m = cfg.fit(&demos[1..]).unwrap();
        let init = &demos[0].rows[0];
        let e = relative_dtw(&m.reproduce(init).unwrap().postures, &demos[1..]);
        let u = cfg.initialise(&demos[1..]).unwrap();
        let eu = relative_dtw(&u.reproduce(init).unwrap().postures, &demos[1..]);
        println!("{name}: trained {e:.4}, untrained {eu:.4}");
        assert!(e < 0.08, "{name}: trained {e}");
        assert!(eu >= 0.08, "{name}: untrained {eu} passes the check");
    }
}

#[test]
fn the_model_keeps_the_column_names_in_both_formats() {
    let demos = idle_gesture(2);
    let cfg = file_options(2).check("t").unwrap();
    let m = cfg.fit(&demos).unwrap();
    assert_eq!(m.columns(), &["u".to_string(), "v".to_string()]);
    let series: Vec<Vec<Vec<f64>>> = demos.iter().map(|d| d.rows.clone()).collect();
    let s = cfg.fit_series(&series).unwrap();
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
fn loop_breaking_is_off_by_default_deterministic_and_keeps_good_reproductions() {
    assert_eq!(HsomParams::table1().reproduction.loop_visits, 0);
    for (name, demos) in [("joints6", joints6(5, 9)), ("idle", idle_gesture(3))] {
        let dims = demos[0].rows[0].len();
        let mut off = file_options(dims);
        off.reproduction.loop_visits = 0;
        let on = file_options(dims);
        assert!(
            on.reproduction.loop_visits > 0,
            "configs/table1.xml switches it on"
        );
        let init = &demos[0].rows[0];
        let m = off.clone().check("t").unwrap().fit(&demos[1..]).unwrap();
        let (r_off, r_on) = (&off.reproduction, &on.reproduction);
        let a = m.reproduce_with(init, r_off).unwrap();
        let b = m.reproduce_with(init, r_on).unwrap();
        assert_eq!(
            b,
            m.reproduce_with(init, r_on).unwrap(),
            "{name}: not deterministic"
        );
        let (ea, eb) = (
            relative_dtw(&a.postures, &demos[1..]),
            relative_dtw(&b.postures, &demos[1..]),
        );
        println!("{name}: loop breaking off {ea:.4}, on {eb:.4}");
        assert!(eb < 0.08, "{name}: with loop breaking {eb}");
        // the strictest setting (any revisit within a window of 1) never panics
        let mut strict = r_on.clone();
        strict.loop_visits = 1;
        strict.loop_window = 1;
        let c = m.reproduce_with(init, &strict).unwrap();
        assert!(c.postures.iter().flatten().all(|v| v.is_finite()));
    }
}

#[test]
fn new_options_in_small_configurations_never_panic_and_round_trip() {
    use cosco_hsom::config::{LevelParams, MemoryMode, PartialTraining};
    use cosco_hsom::som::Topology;
    let demos = idle_gesture(2);
    let dir = tempfile::tempdir().unwrap();
    let mut n = 0;
    for height in [1, 2, 3] {
        for memory in [1, 2, 4] {
            for mode in [MemoryMode::Lists, MemoryMode::Levels] {
                for horizon in [1, 3, 500] {
                    for partial in [PartialTraining::Skip, PartialTraining::Masked] {
                        let mut p = file_options(2);
                        p.height = height;
                        p.memory = memory;
                        p.memory_mode = mode;
                        p.partial_training = partial;
                        p.action_horizon = horizon;
                        p.training_steps = 300;
                        p.levels = (0..height)
                            .map(|l| LevelParams::new(3 + l, 2, Topology::Hexagonal, 0.4))
                            .collect();
                        p.reproduction.offset = memory.min(p.reproduction.offset).max(1);
                        p.reproduction.max_length = 200;
                        let cfg = p.check("t").unwrap();
                        if demos.iter().any(|d| d.len() <= horizon) {
                            // a horizon longer than a demonstration is refused, naming it
                            let e = cfg.fit(&demos).unwrap_err();
                            assert!(
                                matches!(e, cosco_hsom::hsom::HsomError::TooShort { needed, .. } if needed == horizon + 1),
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
    }
}
