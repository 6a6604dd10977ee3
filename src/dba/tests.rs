use super::*;

fn demo(rows: Vec<Vec<f64>>) -> Demonstration {
    Demonstration {
        source: "test".into(),
        columns: vec!["x".into()],
        time: None,
        rows,
    }
}

/// A bump from 0 to `height` and back: `n` samples, its peak at `at` (0 to 1).
fn bump(n: usize, at: f64, height: f64) -> Demonstration {
    let peak = at * (n - 1) as f64;
    demo(
        (0..n)
            .map(|i| {
                let x = i as f64;
                let u = if x <= peak {
                    x / peak
                } else {
                    (n - 1) as f64 - x
                };
                let u = if x <= peak {
                    u
                } else {
                    u / ((n - 1) as f64 - peak)
                };
                vec![height * (std::f64::consts::PI * 0.5 * u).sin()]
            })
            .collect(),
    )
}

#[test]
fn the_mean_of_bumps_out_of_phase_keeps_its_peak_and_the_medoids_length() {
    // three bumps peaking early, midway and late: their mean over time flattens the peak;
    // under alignment it keeps it, at the heights' mean
    let demos = [bump(40, 0.2, 1.0), bump(44, 0.5, 1.2), bump(48, 0.8, 1.4)];
    let dba = Dba::fit(&demos).unwrap();
    assert_eq!(dba.mean.len(), 44, "the medoid is the middle bump");
    let peak = dba.mean.iter().map(|r| r[0]).fold(0.0, f64::max);
    assert!(
        (peak - 1.2).abs() < 0.05,
        "peak {peak}, the heights' mean 1.2"
    );
    // the negative control: the mean over time at the same length fails the same gate
    let flat = (0..44)
        .map(|i| {
            demos
                .iter()
                .map(|d| d.rows[i * (d.rows.len() - 1) / 43][0])
                .sum::<f64>()
                / 3.0
        })
        .fold(0.0, f64::max);
    assert!(
        (flat - 1.2).abs() >= 0.05,
        "the mean over time peaks at {flat}"
    );
}

#[test]
fn a_reproduction_starts_at_the_initial_posture_and_ends_at_the_mean() {
    let demos = [bump(40, 0.2, 1.0), bump(44, 0.5, 1.2), bump(48, 0.8, 1.4)];
    let dba = Dba::fit(&demos).unwrap();
    let r = dba.reproduce(&[0.3]);
    assert_eq!(r[0], vec![0.3]);
    let end = (r.last().unwrap()[0] - dba.mean.last().unwrap()[0]).abs();
    assert!(end < 1e-6, "ends {end} from the mean's end");
    // never faster than the demonstrations' peak step by more than the join's rounding
    let fastest = r
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).abs())
        .fold(0.0, f64::max);
    let peak = dba.smoothness.as_ref().unwrap().peak_step[0];
    assert!(fastest <= 1.5 * peak, "{fastest} vs {peak}");
}

#[test]
fn no_demonstration_is_refused_by_name() {
    let e = Dba::fit(&[]).unwrap_err().to_string();
    assert!(e.contains("at least 1 demonstration"), "{e}");
    let e = Dba::fit(&[demo(vec![vec![0.0]]), demo(vec![vec![0.0, 1.0]])]).unwrap_err();
    assert!(e.to_string().contains("row 0 has 2 values"), "{e}");
}

#[test]
fn a_slower_demonstration_leaves_no_stairs_in_the_mean() {
    // one drawing twice as slow as the others: read along its warp sample by sample it would
    // hold each of its samples for two of the mean's, a stair in every step of the mean
    let ramp = |n: usize| demo((0..n).map(|i| vec![i as f64 / (n - 1) as f64]).collect());
    let dba = Dba::fit(&[ramp(30), ramp(31), ramp(15)]).unwrap();
    let steps: Vec<f64> = dba.mean.windows(2).map(|w| w[1][0] - w[0][0]).collect();
    let (lo, hi) = steps.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &s| {
        (lo.min(s), hi.max(s))
    });
    assert!(lo > 0.3 * hi, "steps from {lo} to {hi}: stairs");
}
