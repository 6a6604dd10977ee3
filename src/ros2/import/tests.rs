use super::*;

#[test]
fn pauses_cut_the_motion_and_short_stops_do_not() {
    // 10 Hz: still 1 s, move 1 s, still 0.3 s, move 1 s, still 2 s, move 1 s, still 1 s
    let mut q = 0.0;
    let mut rows = Vec::new();
    let plan = [
        (10, 0.0),
        (10, 0.5),
        (3, 0.0),
        (10, -0.5),
        (20, 0.0),
        (10, 0.5),
        (10, 0.0),
    ];
    for (n, v) in plan {
        for _ in 0..n {
            q += v * 0.1;
            rows.push(vec![q]);
        }
    }
    let times: Vec<f64> = (0..rows.len()).map(|i| i as f64 * 0.1).collect();
    let segs = moving_segments(&times, &rows, 1.0);
    assert_eq!(segs.len(), 2, "{segs:?}");
    // the first segment spans both moves around the 0.3 s stop
    let (a, b) = segs[0];
    assert!(times[b - 1] - times[a] > 2.0, "{segs:?}");
    // with a pause threshold below the short stop, it splits too
    assert_eq!(moving_segments(&times, &rows, 0.2).len(), 3);
}
