//! Unit tests of the events extension: the executed curve (turning points, the monotone
//! cubic, the join from the initial posture, the smoothing).

use super::*;

#[test]
fn turning_points_are_kept_and_holds_are_not_moved() {
    // four events of 5 samples: knots at their middles, the initial posture and the end
    let t = [0.0, 2.5, 7.5, 12.5, 17.5, 20.0];
    let spans = [(0, 5), (5, 10), (10, 15), (15, 20)];
    let mean = |c: &[f64], (a, b): (usize, usize)| c[a..b].iter().sum::<f64>() / (b - a) as f64;
    let peak = [0.0, 0.3, 1.0, 0.3, 0.0, 0.0];
    let kept = turning_points_kept(&t, &peak, &spans, &[], &[]);
    let c = monotone_cubic(&t, &kept, 21);
    // the turn's event has the node's posture as its mean, so the curve turns beyond it
    assert!(
        (mean(&c, spans[1]) - 1.0).abs() < 1e-6,
        "{}",
        mean(&c, spans[1])
    );
    assert!(c.iter().cloned().fold(f64::MIN, f64::max) > 1.0);
    // only the turning point moved
    assert!(kept[2] > 1.0);
    assert_eq!((kept[0], kept[1], kept[3], kept[4]), (0.0, 0.3, 0.3, 0.0));
    // the control: through the knots alone, the turn's mean falls short of the posture
    let plain = monotone_cubic(&t, &peak, 21);
    assert!(mean(&plain, spans[1]) < 0.97, "{}", mean(&plain, spans[1]));
    // a hold (no strict extremum) is held where it is: nothing moves
    let hold = [0.0, 1.0, 1.0, 1.0, 0.0, 0.0];
    assert_eq!(
        turning_points_kept(&t, &hold, &spans, &[], &[]),
        hold.to_vec()
    );
}

/// A traced half whose consensus dips for a sample or two (DTW's pile-up of the other
/// demonstrations' deeper trough): its turning knot goes to that dip, so the curve turns
/// there; matching the half's mean instead (the control, no extremes known) turns well
/// inside it. A peak goes to its highest value, a knot that is no turning point stays,
/// and an extreme inside the knot's own place never pulls it back.
#[test]
fn a_traced_turn_reaches_the_extreme_of_its_span() {
    let t = [0.0, 5.0, 15.0, 25.0, 30.0];
    let spans = [(0, 10), (10, 20), (20, 30)];
    let traced = [false, true, true, true, false];
    let trough = [0.0, -0.3, -0.6, -0.3, 0.0];
    let reach = [
        None,
        Some((-0.5, -0.1)),
        Some((-1.0, -0.4)),
        Some((-0.5, -0.1)),
        None,
    ];
    let min = |v: &[f64]| {
        monotone_cubic(&t, v, 31)
            .into_iter()
            .fold(f64::MAX, f64::min)
    };
    let kept = turning_points_kept(&t, &trough, &spans, &traced, &reach);
    assert_eq!(kept[2], -1.0);
    assert!((min(&kept) + 1.0).abs() < 1e-9, "{}", min(&kept));
    // the control: the mean matched, the curve turns 0.2 rad inside the dip
    let mean_kept = turning_points_kept(&t, &trough, &spans, &traced, &[]);
    assert!(min(&mean_kept) > -0.8, "{}", min(&mean_kept));
    // a peak reaches its highest value
    let peak: Vec<f64> = trough.iter().map(|v| -v).collect();
    let up = [None, None, Some((0.4, 1.0)), None, None];
    assert_eq!(turning_points_kept(&t, &peak, &spans, &traced, &up)[2], 1.0);
    // knots that are no turning point ignore their extremes
    let slope = [0.0, -0.3, -0.6, -0.9, -1.0];
    let kept = turning_points_kept(&t, &slope, &spans, &traced, &reach);
    assert_eq!(kept, slope.to_vec());
    // an extreme inside the knot's place (not one of the span's samples) never moves
    // the turn inward
    let inside = [None, None, Some((-0.5, -0.4)), None, None];
    assert_eq!(
        turning_points_kept(&t, &trough, &spans, &traced, &inside)[2],
        -0.6
    );
}

#[test]
fn a_turn_at_the_first_sample_is_not_thrown_away_from_the_start() {
    // a first event of one sample at a turn: its only sample is the initial posture,
    // which no knot moves, so the knot stays at the node's posture
    let t = [0.0, 0.5, 5.0, 10.0];
    let spans = [(0, 1), (1, 9)];
    let v = [0.0, 0.01, -0.5, -0.5];
    let kept = turning_points_kept(&t, &v, &spans, &[], &[]);
    assert_eq!(kept, v.to_vec());
    let c = monotone_cubic(&t, &kept, 11);
    assert!(c.iter().all(|&x| x <= 0.01), "{c:?}");
    // a longer first event at a turn is still kept, on its samples after the start
    let t = [0.0, 2.5, 7.5, 10.0];
    let spans = [(0, 5), (5, 10)];
    let v = [0.0, 0.3, 0.0, 0.0];
    let kept = turning_points_kept(&t, &v, &spans, &[], &[]);
    let c = monotone_cubic(&t, &kept, 11);
    let mean = c[1..5].iter().sum::<f64>() / 4.0;
    assert!(
        (mean - 0.3).abs() < 1e-6 && kept[1] < 0.6,
        "{mean} {kept:?}"
    );
}

#[test]
fn a_turn_in_the_span_beside_its_turning_knot_is_kept_by_both() {
    // a slow descent to a trough at 20.3 samples, a fast rise, a hold: the trough lies at
    // the start of the span 20..25, whose mean the rise lifts above the mean of 15..20,
    // so the knot of 15..20 is the turning point and the one holding the trough is not
    let c0 = 20.3;
    let y = |j: f64| {
        use std::f64::consts::PI;
        if j < c0 {
            (PI * (j - (c0 - 20.0)) / 20.0).cos()
        } else if j < c0 + 12.0 {
            -(PI * (j - c0) / 12.0).cos()
        } else {
            1.0
        }
    };
    let spans: Vec<(usize, usize)> = (0..8).map(|i| (5 * i, 5 * i + 5)).collect();
    let mut t = vec![0.0];
    let mut v = vec![y(0.0)];
    for &(a, b) in &spans {
        t.push((a + b) as f64 / 2.0);
        v.push((a..b).map(|j| y(j as f64)).sum::<f64>() / (b - a) as f64);
    }
    t.push(40.0);
    v.push(y(40.0));
    let n = t.len();
    assert!(v[4] < v[5] && v[5] < v[6] && v[4] < v[3], "{v:?}");
    let mean = |c: &[f64], (a, b): (usize, usize)| c[a..b].iter().sum::<f64>() / (b - a) as f64;
    // the control, decoded knots: only the turning point moves; the span holding the
    // trough keeps its knot at its mean, and the curve's mean over it is off
    let plain = turning_points_kept(&t, &v, &spans, &vec![false; n], &[]);
    assert_eq!(plain[5], v[5]);
    let c = monotone_cubic(&t, &plain, 41);
    assert!(mean(&c, spans[4]) > v[5] + 0.01, "{}", mean(&c, spans[4]));
    // traced knots: the turning point's neighbours keep their spans' means too
    let mut traced = vec![true; n];
    (traced[0], traced[n - 1]) = (false, false);
    let kept = turning_points_kept(&t, &v, &spans, &traced, &[]);
    let c = monotone_cubic(&t, &kept, 41);
    for i in [3, 4, 5] {
        assert!((mean(&c, spans[i - 1]) - v[i]).abs() < 1e-3, "knot {i}");
    }
    // and the curve is nearer the one the means were taken from around the turn
    let off = |c: &[f64]| {
        let e2: f64 = (10..30).map(|j| (c[j] - y(j as f64)).powi(2)).sum();
        (e2 / 20.0).sqrt()
    };
    let plain_curve = monotone_cubic(&t, &plain, 41);
    assert!(
        off(&c) < off(&plain_curve),
        "{} against {}",
        off(&c),
        off(&plain_curve)
    );
    // knots away from the turn stay where they are (the ends, the slopes, the hold)
    for i in [0, 1, 2, 6, 7, 8, 9] {
        assert_eq!(kept[i], v[i], "knot {i}");
    }
    // one trough, no new turn
    let turns = c
        .windows(3)
        .filter(|w| (w[1] - w[0]) * (w[2] - w[1]) < 0.0)
        .count();
    assert_eq!(turns, 1, "{c:?}");
}

#[test]
fn monotone_cubic_holds_and_does_not_overshoot() {
    let t = [0.0, 10.0, 20.0, 30.0];
    let v = [0.0, 1.0, 1.0, 0.0];
    for (i, x) in monotone_cubic(&t, &v, 31).into_iter().enumerate() {
        assert!((0.0..=1.0).contains(&x), "{i}: {x}");
        if (10..=20).contains(&i) {
            assert!((x - 1.0).abs() < 1e-12, "the hold is held");
        }
    }
}

/// Third differences of `c`: the jerk per sample cubed.
fn third_differences(c: &[f64]) -> Vec<f64> {
    c.windows(4)
        .map(|w| w[3] - 3.0 * w[2] + 3.0 * w[1] - w[0])
        .collect()
}

fn largest(v: &[f64]) -> f64 {
    v.iter().map(|x| x.abs()).fold(0.0, f64::max)
}

/// The monotone cubic's acceleration steps at every knot (its third differences spike
/// there); the smoothed curve's are spread out: the largest under half the cubic's
/// (the control), its first and last values kept, leaving from rest and coming to rest, a
/// hold still a hold, and nothing changed with no weight.
#[test]
fn the_smoothed_curve_is_continuous_in_acceleration() {
    // uneven knots, as a plan's are: events of 3 to 9 samples, places a little off a line
    let t = [0.0, 2.0, 5.0, 9.5, 12.0, 18.0, 21.0, 26.0, 30.0];
    let v = [0.0, 0.05, 0.22, 0.41, 0.47, 0.75, 0.83, 0.97, 1.0];
    let c = monotone_cubic(&t, &v, 31);
    let smooth = jerk_smoothed(&c, 10.0, 0.0);
    let (raw, smoothed) = (
        largest(&third_differences(&c)),
        largest(&third_differences(&smooth)),
    );
    assert!(2.0 * smoothed < raw, "{smoothed} against the cubic's {raw}");
    assert_eq!((smooth[0], smooth[30]), (c[0], c[30]));
    // from rest and to rest: the first and last steps no larger than the cubic's
    assert!((smooth[1] - smooth[0]).abs() <= (c[1] - c[0]).abs() + 1e-12);
    assert!((smooth[30] - smooth[29]).abs() <= (c[30] - c[29]).abs() + 1e-3);
    // still close to the cubic: within 2 % of the motion
    let off = c
        .iter()
        .zip(&smooth)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(off < 0.02, "{off}");
    // a hold is held exactly; no weight, no change
    let hold = vec![0.4; 20];
    assert!(jerk_smoothed(&hold, 100.0, 0.0)
        .iter()
        .all(|x| (x - 0.4).abs() < 1e-12));
    assert_eq!(jerk_smoothed(&c, 0.0, 0.0), c);
}

/// A curve that starts in motion (a continuation) goes on at the arm's speed: smoothed as if
/// at rest before it (the control), its first step slows down.
#[test]
fn a_continuation_is_smoothed_from_the_arm_s_motion() {
    let c: Vec<f64> = (0..40)
        .map(|i| 0.02 * i as f64 + 0.001 * (i % 3) as f64)
        .collect();
    let moving = jerk_smoothed(&c, 30.0, 0.02);
    let resting = jerk_smoothed(&c, 30.0, 0.0);
    let step = |x: &[f64]| x[1] - x[0];
    assert!((step(&moving) - 0.02).abs() < 0.005, "{}", step(&moving));
    assert!(step(&resting) < 0.01, "{} (the control)", step(&resting));
}

/// Strokes of a family that start at different heights and end at one point, each from rest
/// along a minimum-jerk profile (as LASA's drawings do), read with a little sensor noise:
/// demonstration `i` of 5.
fn from_elsewhere(i: usize) -> Vec<Vec<f64>> {
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(i as u64);
    let n = 70 + 6 * i;
    let y0 = 0.1 * (i as f64 - 2.0);
    (0..n)
        .map(|j| {
            let u = j as f64 / (n - 1) as f64;
            let s = u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
            let mut noise = || 0.0005 * (rng.gen::<f64>() - 0.5);
            vec![
                s + noise(),
                y0 * (1.0 - s) + 0.25 * (std::f64::consts::PI * s).sin() + noise(),
            ]
        })
        .collect()
}

/// A start away from every demonstration's is joined to the plan: the reproduction starts
/// exactly there, no faster than the demonstrations start, as smooth as they are, and ends
/// where they end. The control: the plan with the given posture as its first knot and no
/// smoothing (the curve as it is without the join) leaves it faster than any demonstration.
#[test]
fn a_start_away_from_the_demonstrations_is_joined_smoothly() {
    let train: Vec<Vec<Vec<f64>>> = (0..5).map(from_elsewhere).collect();
    let m = config(2)
        .fit(&Demonstration::from_series(&train))
        .unwrap()
        .into_events();
    let speed = |r: &[Vec<f64>]| crate::dtw::euclidean(&r[1], &r[0]);
    let fastest_start = train.iter().map(|d| speed(d)).fold(0.0, f64::max);
    let y0 = [0.02, 0.33];
    let rep = m.reproduce(&y0).unwrap();
    assert!(rep.postures[0]
        .iter()
        .zip(y0)
        .all(|(a, b)| (a - b).abs() < 1e-12));
    assert!(
        speed(&rep.postures) <= fastest_start,
        "first step {} against the demonstrations' {fastest_start}",
        speed(&rep.postures)
    );
    let mut jerks: Vec<f64> = train
        .iter()
        .filter_map(|d| crate::metrics::normalized_jerk(d, 1.0))
        .collect();
    jerks.sort_by(f64::total_cmp);
    let jerk = crate::metrics::normalized_jerk(&rep.postures, 1.0).unwrap();
    assert!(
        jerk <= 1.5 * jerks[2],
        "{jerk} against the demonstrations' {jerks:?}"
    );
    // it ends where the demonstrations ended: their mean last posture
    let last = rep.postures.last().unwrap();
    let end: Vec<f64> = (0..2)
        .map(|j| train.iter().map(|d| d[d.len() - 1][j]).sum::<f64>() / train.len() as f64)
        .collect();
    assert!(
        (last[0] - end[0]).abs() < 1e-9 && (last[1] - end[1]).abs() < 1e-9,
        "{last:?} against {end:?}"
    );
    // the control
    let mut plain = m.clone();
    plain.part.demo_smoothness = None;
    let y = m.normalise(&y0);
    let r = &m.config.params().reproduction;
    let (executed, stop) = plain.plan_event_list(&y, &[], &[], r);
    let timed = plain.timed_knots(&y, &y, &executed, stop);
    let samples = timed.total.floor() as usize + 1;
    let snapped = plain.curve(&timed, &[0.0, 0.0], samples, stop);
    assert!(
        speed(&snapped.postures) > fastest_start,
        "first step {} (the control) against the demonstrations' {fastest_start}",
        speed(&snapped.postures)
    );
}

/// Nested curves keep their offset from one another to the end, so a start's offset lasts
/// the whole gesture; curves that start apart and meet within the first steps let it go at
/// once (the control).
#[test]
fn a_start_s_offset_lasts_as_long_as_the_demonstrations_own_did() {
    let curve = |k: usize, lasting: bool| -> Vec<Vec<f64>> {
        let offset = 0.1 * (k as f64 - 2.0);
        (0..60)
            .map(|i| {
                let u = i as f64 / 59.0;
                let keep = if lasting {
                    1.0
                } else {
                    (1.0 - 10.0 * u).max(0.0)
                };
                vec![u, (std::f64::consts::PI * u).sin() + offset * keep]
            })
            .collect()
    };
    let nested: Vec<Vec<Vec<f64>>> = (0..5).map(|k| curve(k, true)).collect();
    let meeting: Vec<Vec<Vec<f64>>> = (0..5).map(|k| curve(k, false)).collect();
    assert_eq!(start_fade(&nested, 2), Some(1.0));
    assert!(
        start_fade(&meeting, 2).unwrap() <= 0.125,
        "{:?}",
        start_fade(&meeting, 2)
    );
    assert_eq!(start_fade(&nested[..1], 2), None);
}

/// Knots at `t` with one variable's `v`, from rest, not joined.
fn knots(t: &[f64], v: &[f64]) -> Timed {
    Timed {
        t: t.to_vec(),
        values: vec![v.to_vec()],
        by: vec![1; t.len()],
        total: t[t.len() - 1],
        joined_from: None,
        timing: Timing::Planned,
    }
}

/// The largest step of the cubic through `timed`'s first variable over `samples`.
fn fastest(timed: &Timed, samples: usize) -> f64 {
    let y = monotone_cubic(&timed.t, &timed.values[0], samples);
    largest(&y.windows(2).map(|w| w[1] - w[0]).collect::<Vec<_>>())
}

#[test]
fn a_segment_faster_than_the_demonstrations_is_slowed_not_flattened() {
    // a rise of 1 in 2 samples between two holds; the demonstrations never stepped over 0.1
    let timed = knots(&[0.0, 10.0, 12.0, 30.0], &[0.0, 0.0, 1.0, 1.0]);
    assert!(
        fastest(&timed, 31) >= 0.5,
        "the control: the plan as timed is too fast"
    );
    let (slowed, samples) = no_faster_than(&timed, &[0.0], 31, &[0.1]);
    assert!(
        fastest(&slowed, samples) <= 0.1 * 1.001,
        "{}",
        fastest(&slowed, samples)
    );
    // the same knots, the rise longer, the holds as long, the samples grown by as much
    assert_eq!(slowed.values, timed.values);
    assert_eq!(slowed.t[1], 10.0);
    assert!(slowed.t[2] - slowed.t[1] >= 14.0, "{:?}", slowed.t);
    assert!(
        (slowed.t[3] - slowed.t[2] - 18.0).abs() < 1e-9,
        "{:?}",
        slowed.t
    );
    assert_eq!(samples, 31 + (slowed.total - timed.total).ceil() as usize);
    // a plan as slow as the demonstrations is left as it is
    let (same, n) = no_faster_than(&timed, &[0.0], 31, &[1.0]);
    assert_eq!((same.t, n), (timed.t, 31));
}

/// A warp with stairs (runs of three samples aligned to one sample of `b`) is read at an
/// even pace: every step a third of `b`'s, from `b`'s first sample to its last; the
/// stepped mean of the same alignment jumps a whole sample of `b` at each stair. A warp
/// without stairs reads `b` as it is.
/// Two knots per event (docs/ALGORITHM.md section 3.7): a traced event of four samples
/// or more passes through two knots, at a quarter and three quarters of its duration, at
/// its halves' places. On a family whose swings are about as short as its events (a wave
/// from a hold, three half-swings of 9-13 samples, 8 bottom nodes), held out, the
/// executed curve keeps the three swings on every fold; the control, every traced place
/// cleared (each event at its node's place), loses a turn on some fold.
#[test]
fn two_knots_per_event_keep_the_swings() {
    let wave = |i: usize| -> Vec<Vec<f64>> {
        let (hold, per) = (10 + 2 * i, 9 + i);
        let swings = 3.0 * per as f64;
        (0..2 * hold + swings as usize)
            .map(|j| {
                let u = (j as f64 - hold as f64).clamp(0.0, swings) / per as f64;
                let x = (std::f64::consts::PI * u).sin();
                vec![
                    0.5 * x,
                    0.2 * (1.0 - (std::f64::consts::PI * u / 3.0).cos()),
                ]
            })
            .collect()
    };
    let all: Vec<Vec<Vec<f64>>> = (0..5).map(wave).collect();
    let swings = |rows: &[Vec<f64>]| crate::metrics::column_swings(rows, 0, 0.3).unwrap();
    assert!(all.iter().all(|d| swings(d) == swings(&all[0])));
    let mut kept = [0, 0];
    for out in 0..5 {
        let train: Vec<Vec<Vec<f64>>> = (0..5)
            .filter(|&i| i != out)
            .map(|i| all[i].clone())
            .collect();
        let mut p = config(2).into_params();
        p.levels[0] = crate::config::LevelParams::new(4, 2, crate::som::Topology::Orthogonal, 0.1);
        let m = p
            .check("test")
            .unwrap()
            .fit(&Demonstration::from_series(&train))
            .unwrap()
            .into_events();
        let mut cleared = m.clone();
        let (k, pw) = (m.config.params().memory, trace_places(m.config.params()));
        let at = trace_postures_at(k, 1);
        for c in cleared.part.traces.as_mut().unwrap().levels[1].iter_mut() {
            c.words[at..trace_bmus_at(k, 1, pw)].fill(u32::MAX);
        }
        for (i, model) in [&m, &cleared].into_iter().enumerate() {
            let r = model.reproduce(&all[out][0]).unwrap().postures;
            kept[i] += usize::from(swings(&r) == swings(&all[out]));
        }
    }
    assert_eq!(kept[0], 5, "two knots per event {kept:?}");
    assert!(kept[1] < 5, "at the nodes' places {kept:?}");
    // an event passes through two knots only where each half lasts two samples: one
    // of 3.5 samples keeps one knot at its middle, one of 4 two, at its quarters, each
    // at its half's place
    let m = config(2)
        .fit(&Demonstration::from_series(&all[..4]))
        .unwrap()
        .into_events();
    let y0 = m.normalise(&all[0][0]);
    // the event, its halves, then each half's lowest and highest values (s = 2)
    let at: Vec<f64> = vec![
        0.0, 0.0, 0.1, 0.1, 0.2, 0.2, -0.3, -0.3, 0.4, 0.4, -0.5, -0.5, 0.6, 0.6,
    ];
    let n = m.dwell.iter().position(|&d| d > 0.0).unwrap();
    let executed: Vec<Step<usize>> = vec![(n, 3.5, 1, Some(at.clone())), (n, 4.0, 1, Some(at))];
    let places = m.knot_places(&y0, &y0, &executed, StopReason::LearnedLength);
    assert_eq!(places.t, vec![0.0, 1.75, 4.5, 6.5, 7.5]);
    let placed = m.placement(&y0);
    assert_eq!(places.by, vec![0, 1, 1, 1, 1]);
    assert_eq!(places.traced_mean, vec![false, true, true, true, false]);
    // the whole event at its place, the first half of the next at that half's, the
    // second at the second's
    for (k, off) in [(1, 0.0), (2, 0.1), (3, 0.2)] {
        assert!(
            (places.v[k][0] - (placed[2 * n] + off)).abs() < 1e-12,
            "knot {k}"
        );
    }
    // and the knots the curve passes through are those places, turning points kept
    let timed = m.timed_knots(&y0, &y0, &executed, StopReason::LearnedLength);
    assert_eq!(timed.t, places.t);
    let target: Vec<f64> = places.v.iter().map(|r| r[0]).collect();
    // each half's extremes go with its knot; the whole event and the end have none
    let reach: Vec<Option<(f64, f64)>> = places
        .reach
        .iter()
        .map(|r| r.as_ref().map(|(lo, hi)| (lo[0], hi[0])))
        .collect();
    let at = |off: f64| placed[2 * n] + off;
    assert_eq!(
        reach,
        vec![
            None,
            None,
            Some((at(-0.3), at(0.4))),
            Some((at(-0.5), at(0.6))),
            None
        ]
    );
    assert_eq!(
        timed.values[0],
        turning_points_kept(
            &places.t,
            &target,
            &places.spans,
            &places.traced_mean,
            &reach
        )
    );
}
