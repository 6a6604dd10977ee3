use rand::Rng;

use crate::config::HsomConfig;
use crate::demos::Demonstration;

use super::consensus::*;
use super::curve::*;
use super::encode::*;
use super::levels::*;
use super::plan::*;
use super::smoothing::*;
use super::start::*;
use super::traces::*;
use super::END;
use crate::config::HsomParams;
use crate::hsom::errors::HsomError;
use crate::hsom::followers::*;
use crate::hsom::inputs::Layout;
use crate::hsom::model::{EventsHsom, StartKnots};
use crate::hsom::reproduction::StopReason;

mod consensus;
mod curve;
mod follow;
mod gestures;

/// A 2-D gesture: hold at the origin, go to (1, 0), hold, come back, hold.
fn gesture(hold: usize, noise_seed: u64) -> Vec<Vec<f64>> {
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(noise_seed);
    let mut rows = Vec::new();
    let mut push = |x: f64, rng: &mut rand_chacha::ChaCha8Rng| {
        rows.push(vec![x + 0.002 * rng.gen::<f64>(), 0.5 * x]);
    };
    for _ in 0..hold {
        push(0.0, &mut rng);
    }
    for i in 0..40 {
        push(i as f64 / 40.0, &mut rng);
    }
    for _ in 0..hold {
        push(1.0, &mut rng);
    }
    for i in 0..40 {
        push(1.0 - i as f64 / 40.0, &mut rng);
    }
    for _ in 0..hold {
        push(0.0, &mut rng);
    }
    rows
}

fn config(height: usize) -> HsomConfig {
    let mut p = HsomParams::table1();
    p.algorithm = crate::config::AlgorithmParams::Events(crate::config::EventsParams {
        change_ratio: 0.6,
        action_horizon: 5,
    });
    p.state_length = 2;
    p.action_length = 2;
    p.height = height;
    p.levels.truncate(height);
    p.levels[0] = crate::config::LevelParams::new(8, 8, crate::som::Topology::Orthogonal, 0.1);
    for l in 1..height {
        p.levels[l] = crate::config::LevelParams::new(6, 6, crate::som::Topology::Orthogonal, 0.5);
    }
    p.training_steps = 3000;
    p.check("test").unwrap()
}

/// The untrained model of `series` (height 3, the seeded weights): the negative control.
fn untrained(series: &[Vec<Vec<f64>>]) -> EventsHsom {
    let m = config(3).fit_model(
        &Demonstration::from_series(series),
        crate::hsom::Fit::UNTRAINED,
    );
    m.unwrap().branches()[0].clone().into_events()
}

fn trained(height: usize) -> EventsHsom {
    let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
    config(height)
        .fit(&Demonstration::from_series(&series))
        .unwrap()
        .into_events()
}

#[test]
fn events_tile_the_demonstration_and_hold_their_durations() {
    let m = trained(3);
    let demo = gesture(30, 9);
    let y: Vec<Vec<f64>> = demo.iter().map(|r| m.normalise(r)).collect();
    let ev = bottom_events(&m, &y);
    // every sample but the last belongs to exactly one event
    let total: f64 = ev.iter().map(|e| e.1).sum();
    assert_eq!(total as usize, y.len() - 1);
    // consecutive events are different nodes (an event ends when the BMU changes)
    assert!(ev.windows(2).all(|w| w[0].0 != w[1].0));
    // the holds are single long events, not flicker from the noise
    assert!(ev.first().unwrap().1 >= 25.0, "{ev:?}");
    assert!(ev.iter().any(|e| e.1 >= 25.0 && e.0 != ev[0].0), "{ev:?}");
    assert!(ev.len() < 40, "{} events for {} samples", ev.len(), y.len());
}

#[test]
fn chunks_tile_without_overlap_and_end_with_the_end() {
    let lay = Layout { s: 1, k: 4 };
    let items: Vec<Item> = (0..9)
        .map(|i| Item {
            node: i,
            content: vec![i as f64, i as f64 + 0.5, 0.1, 0.0],
        })
        .collect();
    let c = chunks(lay, &items, 1.0, 9.0);
    assert_eq!(c.len(), 3);
    assert!(
        c[0].begin && !c[1].begin && !c[2].begin,
        "only the first chunk is the begin"
    );
    assert_eq!(c[1].prev, vec![3.5], "context: the last posture before");
    assert_eq!(c[2].slots[0], items[8].content);
    // slots after the last entry are the end, holding the last posture
    for j in 1..4 {
        assert_eq!(c[2].slots[j], vec![8.5, 8.5, 0.0, 1.0]);
    }
    let phases: Vec<f64> = c.iter().map(|x| x.phase).collect();
    assert_eq!(phases, vec![0.0, 4.0 / 9.0, 8.0 / 9.0]);
}

#[test]
fn followers_count_the_begin_and_the_most_frequent_first() {
    let seqs = vec![
        vec![1, 2, 3, END],
        vec![1, 2, 4, END],
        vec![1, 3, 2, 4, END],
    ];
    let t = followers_table(5, &seqs);
    let row = |n: usize| t[n * FOLLOWERS..(n + 1) * FOLLOWERS].to_vec();
    assert_eq!(row(5)[0], 1, "the begin is followed by 1");
    assert_eq!(row(2)[0], 4, "2 -> 4 twice, 2 -> 3 once");
    assert_eq!(row(2)[1], 3);
    assert_eq!(row(4), vec![END, u32::MAX, u32::MAX, u32::MAX]);
}

#[test]
fn decoding_by_content_picks_the_nearest_follower() {
    let m = trained(3);
    let lay = Layout::of(&m.config);
    let code = DurationCode::from_dwell(&m.dwell);
    // the first follower of the begin, decoded from its own content
    let first = m.part.followers[0][m.maps[0].len() * FOLLOWERS];
    assert_ne!(first, u32::MAX);
    let c = entry_content(&m, lay, 0, first as usize, code);
    let dec = Decoder {
        model: &m,
        lay,
        code,
    };
    assert_eq!(
        dec.decode(1, &c, &[], u32::MAX, 0.0, f64::NAN, u32::MAX),
        first
    );
    // a slot whose end flag is set decodes to the end
    let mut e = c.clone();
    e[2 * lay.s + 1] = 1.0;
    assert_eq!(
        dec.decode(1, &e, &[], u32::MAX, 0.0, f64::NAN, u32::MAX),
        END
    );
    // an exemplar entry that followed the previous one wins over content; one that never
    // followed it is ignored
    let row = &m.part.followers[0][m.maps[0].len() * FOLLOWERS..][..FOLLOWERS];
    let never = (0..m.maps[0].len() as u32)
        .find(|n| !row.contains(n))
        .unwrap();
    assert_eq!(
        dec.decode(1, &c, &[], u32::MAX, 0.0, f64::NAN, never),
        first
    );
    if let Some(&other) = row
        .iter()
        .find(|&&f| f != first && f != u32::MAX && f != END)
    {
        assert_eq!(
            dec.decode(1, &c, &[], u32::MAX, 0.0, f64::NAN, other),
            other
        );
    }
}

/// A node passed more than once leads on to different followers at different positions:
/// the follower table keeps where each transition came, and level 1 decodes among
/// followers equally near by content by where the plan places the entry.
#[test]
fn decoding_prefers_the_follower_seen_at_the_planned_position() {
    // node 2 is followed by 3 early and by 4 late
    let seqs = vec![vec![1, 2, 3, 2, 4, END]];
    let table = followers_table(5, &seqs);
    let at = follower_positions(5, &seqs, &table, 6.0);
    let row = &table[2 * FOLLOWERS..3 * FOLLOWERS];
    let pos = |f: u32| at[2 * FOLLOWERS + row.iter().position(|&x| x == f).unwrap()];
    assert!((pos(3) - 2.0 / 6.0).abs() < 1e-12 && (pos(4) - 4.0 / 6.0).abs() < 1e-12);
    assert_eq!(at[5 * FOLLOWERS], 0.0, "the begin row: node 1 at 0");

    let mut m = trained(3);
    let lay = Layout::of(&m.config);
    let code = DurationCode::from_dwell(&m.dwell);
    let (p, a, b) = (0usize, 1u32, 2u32);
    m.part.followers[0][p * FOLLOWERS..(p + 1) * FOLLOWERS].copy_from_slice(&[
        a,
        b,
        u32::MAX,
        u32::MAX,
    ]);
    m.part.follower_at[p * FOLLOWERS] = 0.1;
    m.part.follower_at[p * FOLLOWERS + 1] = 0.9;
    // a slot halfway between a and b: content alone cannot choose
    let ca = entry_content(&m, lay, 0, a as usize, code);
    let cb = entry_content(&m, lay, 0, b as usize, code);
    let mut c: Vec<f64> = ca.iter().zip(&cb).map(|(x, y)| 0.5 * (x + y)).collect();
    c[2 * lay.s + 1] = 0.0;
    let dec = Decoder {
        model: &m,
        lay,
        code,
    };
    assert_eq!(dec.decode(1, &c, &[], p as u32, 0.0, 0.1, u32::MAX), a);
    assert_eq!(dec.decode(1, &c, &[], p as u32, 0.0, 0.9, u32::MAX), b);
    // no position (the training replay): the first of equals
    assert_eq!(dec.decode(1, &c, &[], p as u32, 0.0, f64::NAN, u32::MAX), a);
}

/// Home is followed by the start of the gesture (at its begin) and by the end (at its
/// end): a plan that comes home early, before the shortest demonstration's number of
/// events, ends where its position is nearer the end's, and starts again where it is
/// nearer the start's (the paper's replication, which the count alone let through).
/// Two demonstrations of a 2-D gesture from different starts: out along x and back once
/// from (0, 0), twice from (0, 0.3); and the model `config(2)` trained on them.
fn once_and_twice() -> ([Demonstration; 2], EventsHsom) {
    let demo = |source: &str, rows: Vec<Vec<f64>>, y: f64| Demonstration {
        source: source.into(),
        columns: vec!["x".into(), "y".into()],
        time: None,
        rows: rows.into_iter().map(|r| vec![r[0], r[1] + y]).collect(),
    };
    let demos = [
        demo("once", gesture(30, 1), 0.0),
        demo("twice", [gesture(30, 2), gesture(30, 3)].concat(), 0.3),
    ];
    let m = config(2).fit(&demos).unwrap().into_events();
    (demos, m)
}

/// The same model with the traces' stored places cleared: each event at its node's place.
fn at_nodes(m: &EventsHsom) -> EventsHsom {
    let mut cleared = m.clone();
    let (k, s) = (m.config.params().memory, trace_places(m.config.params()));
    let at = trace_postures_at(k, 1);
    for c in cleared.part.traces.as_mut().unwrap().levels[1].iter_mut() {
        c.words[at..trace_bmus_at(k, 1, s)].fill(u32::MAX);
    }
    cleared
}

/// Turning points of x larger than 0.5 (out and back once: 1; twice: 3).
fn excursions(rows: &[Vec<f64>]) -> usize {
    crate::metrics::column_swings(rows, 0, 0.5).unwrap()
}

/// The nearest-sequence baseline follows the training demonstration that starts nearest
/// the initial posture: from each demonstration's start, its events at their nodes make
/// that one's number of excursions (one, or two), where the other has the other number;
/// bad input is refused with the error naming it. (At the consensus places, two
/// demonstrations of different structure are averaged: "twice"'s second excursion stays
/// under the 0.5 the count needs.)
#[test]
fn following_the_nearest_demonstration_keeps_its_number_of_excursions() {
    let (demos, m) = once_and_twice();
    assert_ne!(excursions(&demos[0].rows), excursions(&demos[1].rows));
    // without traces, the followed events are placed at their nodes
    let mut nodes = m.clone();
    nodes.part.traces = None;
    for d in &demos {
        let r = nodes.follow_nearest(&demos, &d.rows[0]).unwrap();
        assert_eq!(excursions(&r.postures), excursions(&d.rows), "{}", d.source);
        assert!(r.predicted_by.iter().all(|&l| l == 0));
    }
    let e = m.follow_nearest(&[], &[0.0, 0.0]).unwrap_err();
    assert!(matches!(e, HsomError::NoDemonstrations), "{e}");
    let e = m.follow_nearest(&demos, &[0.0]).unwrap_err().to_string();
    assert!(e.contains("initial posture") && e.contains('2'), "{e}");
}

/// A traced plan replays the demonstrated stretch its node stands for and goes on along
/// the same demonstration across chunks: from each demonstration's start the hierarchy
/// executes exactly that demonstration's bottom events (one excursion, or two, counted
/// with each event at its node), at its nodes' learned durations. The traces have a size
/// bounded by the configuration alone (at most `TRACED_CHUNKS` chunks a node). The control: with every traced chunk of the first
/// demonstration marked as the second's and its events made the second's, its start makes
/// the second's number of excursions, so the plan is the traces' and not the levels'
/// decoding.
#[test]
fn a_traced_plan_replays_the_demonstration_its_node_stands_for() {
    let (demos, _) = once_and_twice();
    let m = config(2).fit(&demos).unwrap().into_events();
    let r = &m.config.params().reproduction;
    let tr = m.part.traces.as_ref().unwrap();
    let (k, s) = (m.config.params().memory, trace_places(m.config.params()));
    let width = trace_width(k, 1, s).unwrap();
    assert!(tr.levels[1].len() <= m.maps[1].len() * TRACED_CHUNKS);
    assert!(tr.levels[1].iter().all(|c| c.words.len() == width));
    for d in &demos {
        let y0 = m.normalise(&d.rows[0]);
        let (executed, stop) = m.plan_event_list(&y0, &[], &[], r);
        assert_eq!(stop, StopReason::EndEvent);
        let demonstrated: Vec<usize> = bottom_events(&m, &m.normalise_rows(&d.rows))
            .iter()
            .map(|e| e.0)
            .collect();
        let nodes: Vec<usize> = executed.iter().map(|e| e.0).collect();
        assert_eq!(nodes, demonstrated, "{}", d.source);
        assert!(executed.iter().all(|e| e.1 == m.dwell[e.0].max(1.0)));
        let rep = at_nodes(&m).reproduce(&d.rows[0]).unwrap();
        assert_eq!(
            excursions(&rep.postures),
            excursions(&d.rows),
            "{}",
            d.source
        );
    }
    // the control: the first demonstration's traced chunks replaced by the second's
    let mut other = m.clone();
    let chunks = &mut other.part.traces.as_mut().unwrap().levels[1];
    let second: Vec<Vec<u32>> = chunks
        .iter()
        .filter(|c| c.words[2] == 1)
        .map(|c| c.words.clone())
        .collect();
    for slot in chunks
        .iter_mut()
        .map(|c| &mut c.words)
        .filter(|c| c[2] == 0)
    {
        if let Some(theirs) = second.iter().find(|c| c[0] == slot[0]) {
            slot[TRACE_HEAD..].copy_from_slice(&theirs[TRACE_HEAD..]);
        }
        slot[2] = 1;
    }
    let rep = at_nodes(&other).reproduce(&demos[0].rows[0]).unwrap();
    assert_eq!(excursions(&rep.postures), excursions(&demos[1].rows));
}

/// Strokes of a family (a bent line, drawn with varying bend, tempo and length; 2-D,
/// without holds): demonstration `i` of 5.
fn stroke(i: usize) -> Vec<Vec<f64>> {
    let n = 80 + 7 * i;
    let bend = 0.3 * (1.0 + 0.15 * (i as f64 - 2.0));
    let warp = 0.8 + 0.1 * i as f64;
    (0..n)
        .map(|j| {
            let t = (j as f64 / (n - 1) as f64).powf(warp);
            vec![t, bend * (std::f64::consts::PI * t).sin()]
        })
        .collect()
}

/// A traced plan places each event where the demonstrations agree at that event of the
/// demonstration it follows (`Hsom::event_postures`), not where its node pools every visit
/// from wherever in the gesture: held out on a family of strokes, the reproduction is
/// smoother on every fold (twice as smooth over the folds together), and no farther from
/// the held-out stroke. The control: the same model with the stored places cleared (each
/// event at its node's place) is jerkier. Both curves unsmoothed (no demonstrations' jerk
/// to reach, section 3.8), which would hide what the places do.
#[test]
fn traced_events_at_their_place_in_the_consensus_are_smoother_than_at_their_nodes() {
    let all: Vec<Vec<Vec<f64>>> = (0..5).map(stroke).collect();
    let mut placed = Vec::new();
    let mut nodes = Vec::new();
    let mut dtw_placed = Vec::new();
    let mut dtw_nodes = Vec::new();
    for out in 0..5 {
        let train: Vec<Vec<Vec<f64>>> = (0..5)
            .filter(|&i| i != out)
            .map(|i| all[i].clone())
            .collect();
        let mut m = config(2)
            .fit(&Demonstration::from_series(&train))
            .unwrap()
            .into_events();
        m.part.demo_smoothness = None;
        let cleared = at_nodes(&m);
        let y0 = &all[out][0];
        let a = m.reproduce(y0).unwrap().postures;
        let b = cleared.reproduce(y0).unwrap().postures;
        placed.push(crate::metrics::normalized_jerk(&a, 0.025).unwrap());
        nodes.push(crate::metrics::normalized_jerk(&b, 0.025).unwrap());
        let d = |r: &[Vec<f64>]| {
            crate::dtw::dtw_distance(r, &all[out], crate::dtw::Band::None)
                .unwrap()
                .per_step()
        };
        dtw_placed.push(d(&a));
        dtw_nodes.push(d(&b));
    }
    // smoother on every fold, and at least twice as smooth over the folds together
    // (measured: 4 of 5 folds at least twice as smooth, the fifth 540 against 948)
    for (a, b) in placed.iter().zip(&nodes) {
        assert!(
            a < b,
            "jerk at the places {placed:?}, at the nodes {nodes:?}"
        );
    }
    let (a, b): (f64, f64) = (placed.iter().sum(), nodes.iter().sum());
    assert!(
        2.0 * a < b,
        "jerk at the places {placed:?}, at the nodes {nodes:?}"
    );
    let (a, b): (f64, f64) = (dtw_placed.iter().sum(), dtw_nodes.iter().sum());
    assert!(a < 1.05 * b, "DTW {dtw_placed:?} against {dtw_nodes:?}");
}

#[test]
fn a_plan_ends_at_home_where_its_position_is_nearer_the_end() {
    let mut m = trained(3);
    let lay = Layout::of(&m.config);
    let code = DurationCode::from_dwell(&m.dwell);
    let (home, start) = (0usize, 1u32);
    m.part.followers[0][home * FOLLOWERS..(home + 1) * FOLLOWERS].copy_from_slice(&[
        start,
        END,
        u32::MAX,
        u32::MAX,
    ]);
    m.part.follower_at[home * FOLLOWERS] = 0.0;
    m.part.follower_at[home * FOLLOWERS + 1] = 1.0;
    // a slot that reads as the start of the gesture: content says "start again"
    let mut c = entry_content(&m, lay, 0, start as usize, code);
    c[2 * lay.s + 1] = 0.0;
    let dec = Decoder {
        model: &m,
        lay,
        code,
    };
    let early = m.demo_runs[0] - 10.0;
    assert_eq!(
        dec.decode(1, &c, &[], home as u32, early, 0.7, u32::MAX),
        END
    );
    // the controls: the plan at the begin, and no position (only the count decides)
    assert_eq!(
        dec.decode(1, &c, &[], home as u32, early, 0.2, u32::MAX),
        start
    );
    assert_eq!(
        dec.decode(1, &c, &[], home as u32, early, f64::NAN, u32::MAX),
        start
    );
    assert_eq!(
        dec.decode(1, &c, &[], home as u32, m.demo_runs[0], f64::NAN, u32::MAX),
        END
    );
}

/// Every used node of a level above the bottom has an exemplar's position: the phase of
/// a training chunk it is the BMU of.
#[test]
fn exemplar_positions_are_phases_of_training_chunks() {
    let m = trained(3);
    for l in 1..m.maps.len() {
        for n in (0..m.maps[l].len()).filter(|&n| m.hits[l][n] > 0) {
            let p = m.part.exemplar_phase[l][n];
            assert!(
                p.is_finite() && (0.0..=2.0).contains(&p),
                "level {l} node {n}: {p}"
            );
        }
    }
    // the begin chunk's node is at 0
    assert!((1..m.maps.len()).all(|l| m.part.exemplar_phase[l].contains(&0.0)));
}

/// Every used node of a level above the bottom has an exemplar: the entries below of a
/// training chunk it is the BMU of, so expanding it replays a demonstrated sequence.
#[test]
fn exemplars_are_training_chunks_of_their_node() {
    let m = trained(3);
    let k = m.config.params().memory;
    let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
    let norm: Vec<Vec<Vec<f64>>> = series
        .iter()
        .map(|d| d.iter().map(|r| m.normalise(r)).collect())
        .collect();
    let seqs: Vec<Vec<u32>> = norm
        .iter()
        .map(|d| {
            bottom_events(&m, d)
                .iter()
                .map(|e| e.0 as u32)
                .chain([END])
                .collect()
        })
        .collect();
    let windows: Vec<Vec<u32>> = seqs
        .iter()
        .flat_map(|s| {
            s.chunks(k)
                .map(|c| {
                    let mut c = c.to_vec();
                    c.resize(k, END);
                    c
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let used1 = used(&m, 1);
    assert!(!used1.is_empty());
    for &n in &used1 {
        let ex: Vec<u32> = (0..k).map(|j| m.exemplar(1, n, j)).collect();
        assert!(
            windows.contains(&ex),
            "node {n}: {ex:?} is no training chunk"
        );
    }
    // unused nodes have none
    for n in (0..m.maps[1].len()).filter(|n| !used1.contains(n)) {
        assert_eq!(m.exemplar(1, n, 0), u32::MAX);
    }
}

#[test]
fn reproduction_goes_there_and_back_at_the_learned_tempo_and_ends_by_itself() {
    let m = trained(3);
    let rep = m.reproduce(&[0.0, 0.0]).unwrap();
    assert_eq!(rep.stop, StopReason::EndEvent);
    let xs: Vec<f64> = rep.postures.iter().map(|p| p[0]).collect();
    let top = xs.iter().cloned().fold(f64::MIN, f64::max);
    assert!(top > 0.85, "reaches the far posture: {top}");
    assert!(xs.last().unwrap().abs() < 0.15, "comes back: {xs:?}");
    // the hold at the far posture lasts about as long as demonstrated (30-40 samples)
    let held = xs.iter().filter(|&&x| x > 0.9).count();
    assert!((20..=60).contains(&held), "held {held} samples");
    let n = rep.postures.len() as f64;
    assert!((0.7 * 150.0..=1.3 * 200.0).contains(&n), "length {n}");
    // the levels above the bottom carried it, each only where it beats its lookup table
    assert!(rep.predicted_by.iter().any(|&l| l >= 1));
    assert!(rep.predicted_by.iter().all(|&l| m.level_trusted(l)));
    // deterministic
    assert_eq!(rep, m.reproduce(&[0.0, 0.0]).unwrap());
}

#[test]
fn a_plan_that_ends_by_its_end_event_ends_where_the_demonstrations_ended() {
    // three strokes from rest to (1, 0.5) that end in motion, at the far end
    let stroke = |hold: usize, seed: u64| -> Vec<Vec<f64>> {
        let mut rows = gesture(hold, seed);
        rows.truncate(hold + 40);
        rows
    };
    let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| stroke(30 + 5 * i, i as u64)).collect();
    let m = config(3)
        .fit(&Demonstration::from_series(&series))
        .unwrap()
        .into_events();
    let ended: Vec<f64> = (0..2)
        .map(|j| series.iter().map(|d| d.last().unwrap()[j]).sum::<f64>() / 3.0)
        .collect();
    let end = m.denormalise(m.part.end_posture.as_ref().unwrap());
    assert!(
        end.iter().zip(&ended).all(|(a, b)| (a - b).abs() < 1e-9),
        "{end:?}"
    );
    let rep = m.reproduce(&[0.0, 0.0]).unwrap();
    assert_eq!(rep.stop, StopReason::EndEvent);
    let last = rep.postures.last().unwrap();
    assert!(
        (last[0] - ended[0]).abs() < 1e-6 && (last[1] - ended[1]).abs() < 1e-6,
        "{last:?} against {ended:?}"
    );
    // a plan that ends two events early (its end decoded by content) still ends where they
    // ended; the control: the same events cut by a length cap stop where the last one's
    // action leads, short of it
    let norm = m.normalise_rows(&series[0]);
    let mut executed: Vec<Step<usize>> = bottom_events(&m, &norm)
        .into_iter()
        .map(|(n, d)| (n, d, 0, None))
        .collect();
    executed.truncate(executed.len() - 2);
    let early = m.timed_postures(
        &norm[0],
        &norm[0],
        &executed,
        StopReason::EndEvent,
        Timing::Planned,
    );
    let capped = m.timed_postures(
        &norm[0],
        &norm[0],
        &executed,
        StopReason::LearnedLength,
        Timing::Planned,
    );
    let (e, c) = (
        early.postures.last().unwrap(),
        capped.postures.last().unwrap(),
    );
    assert!((e[0] - ended[0]).abs() < 1e-6, "{e:?}");
    assert!(c[0] < ended[0] - 0.05, "{c:?} (the control)");
}

#[test]
fn a_level_plans_only_where_it_and_the_levels_below_beat_their_lookup_tables() {
    let mut m = trained(4);
    m.accuracy = vec![0.0, 0.5, 0.9, 0.9];
    m.lookup = vec![0.0, 0.9, 0.8, 0.8];
    // level 1 always (the lowest level with a sequence), whatever its table
    assert!(m.level_trusted(0) && m.level_trusted(1));
    assert!(m.level_trusted(2) && m.level_trusted(3));
    // a tie is not better; a level above an untrusted one is not reached
    m.accuracy[2] = 0.8;
    assert!(!m.level_trusted(2) && !m.level_trusted(3));
    m.accuracy[2] = 0.9;
    m.accuracy[3] = 0.7;
    assert!(m.level_trusted(2) && !m.level_trusted(3));
    let rep = m.reproduce(&[0.0, 0.0]).unwrap();
    assert!(
        rep.predicted_by.iter().all(|&l| l <= 2),
        "{:?}",
        rep.predicted_by
    );
    // the summary says which levels plan
    let used: Vec<bool> = m
        .summary()
        .levels
        .iter()
        .map(|l| l.used_in_reproduction)
        .collect();
    assert_eq!(used, vec![true, true, true, false]);
}

#[test]
fn reencoding_keeps_what_the_bottom_code_keeps_and_an_untrained_code_loses_it() {
    let rows = gesture(30, 0);
    let demo = Demonstration {
        source: "g".into(),
        columns: vec!["x".into(), "y".into()],
        time: None,
        rows: rows.clone(),
    };
    let err = |m: &EventsHsom| {
        let r = m.reencode(&demo).unwrap();
        assert!(r.predicted_by.iter().all(|&l| l == 0));
        crate::dtw::dtw_distance(&r.postures, &rows, crate::dtw::Band::None)
            .unwrap()
            .per_step()
    };
    let model = trained(3);
    let good = err(&model);
    assert!(good < 0.05, "trained: {good}");
    // negative control: the initial (random) bottom map
    let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
    let untrained = err(&untrained(&series));
    // it fails the gate the trained code passes, by an order of magnitude
    assert!(
        untrained > 0.05 && untrained > 10.0 * good,
        "untrained: {untrained}, trained: {good}"
    );
    // a demonstration of another width is refused, not re-encoded
    let mut bad = demo.clone();
    bad.rows[3] = vec![0.0];
    assert!(matches!(
        model.reencode(&bad),
        Err(HsomError::DimensionMismatch { row: 3, .. })
    ));
}

#[test]
fn an_untrained_hierarchy_does_not_reproduce_the_gesture() {
    let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
    let m = untrained(&series);
    let rep = m.reproduce(&[0.0, 0.0]).unwrap();
    let xs: Vec<f64> = rep.postures.iter().map(|p| p[0]).collect();
    let held = xs.iter().filter(|&&x| x > 0.9).count();
    let top = xs.iter().cloned().fold(f64::MIN, f64::max);
    assert!(
        !(top > 0.85 && (20..=60).contains(&held) && xs.last().unwrap().abs() < 0.15),
        "untrained: top {top}, held {held}"
    );
}

/// The events of a training demonstration, pushed up the lists, complete chunks whose
/// nodes are the training replay's; a plan that expected another node there is surprised.
#[test]
fn executed_events_climb_the_lists_and_a_wrong_expectation_is_a_surprise() {
    let m = trained(3);
    let lay = Layout::of(&m.config);
    let code = DurationCode::from_dwell(&m.dwell);
    let mean = m.demo_runs[1];
    let demo = gesture(35, 1);
    let y: Vec<Vec<f64>> = demo.iter().map(|r| m.normalise(r)).collect();
    let ev = bottom_events(&m, &y);
    assert!(ev.len() >= 2 * lay.k);
    let start = m.maps[0].weights(ev[0].0)[..lay.s].to_vec();
    // expecting exactly what the lists will find: no surprise
    let mut probe = Lists::new(m.maps.len(), &start);
    for &(n, d) in &ev[..lay.k] {
        probe.push_event(&m, lay, code, mean, n, d);
    }
    let first_chunk = probe.tail[1];
    assert_ne!(first_chunk, u32::MAX, "a full chunk reaches level 1");
    let mut lists = Lists::new(m.maps.len(), &start);
    lists.expected[1].push_back(first_chunk);
    let mut surprised = false;
    for &(n, d) in &ev[..lay.k] {
        surprised |= lists.push_event(&m, lay, code, mean, n, d);
    }
    assert!(!surprised);
    assert_eq!(lists.index[1], 1, "one chunk completed at level 1");
    assert!(lists.chunk[1].is_empty());
    assert!(lists.expected[1].is_empty(), "the expectation was consumed");
    // expecting another node: surprise, at the event that completes the chunk only
    let mut lists = Lists::new(m.maps.len(), &start);
    let other = (first_chunk + 1) % m.maps[1].len() as u32;
    lists.expected[1].push_back(other);
    let flags: Vec<bool> = ev[..lay.k]
        .iter()
        .map(|&(n, d)| lists.push_event(&m, lay, code, mean, n, d))
        .collect();
    assert_eq!(flags.iter().filter(|&&f| f).count(), 1);
    assert!(flags[lay.k - 1], "{flags:?}");
}

/// A model file's durations are untrusted: an absurd learned duration cannot make the
/// reproduction longer than its cap (nor allocate without bound).
#[test]
fn absurd_durations_are_capped_by_the_length_cap() {
    let mut m = trained(3);
    m.dwell.iter_mut().for_each(|d| {
        if *d > 0.0 {
            *d = 1e300
        }
    });
    let rep = m.reproduce(&[0.0, 0.0]).unwrap();
    let cap = (m.demo_len[2] * m.config.params().reproduction.length_factor).ceil();
    assert!(
        rep.postures.len() as f64 <= cap + 1.0,
        "{}",
        rep.postures.len()
    );
}
