//! Far goals (`cosco heldout --far K`): a fold's goal moved `K` times the training
//! demonstrations' end spread away from their mean end, and the held-out demonstration shifted
//! by the same offset, fading in as the goal does, to score the reproduction's shape against.

use crate::curve::minimum_jerk_at;
use crate::demos::Demonstration;
use crate::dtw::euclidean;
use crate::metrics::end_spread;

/// The held-out demonstration `target` moved to a far goal: the training demonstrations'
/// (`train`) mean end plus `k` times their end spread ([`end_spread`]) along the direction
/// from that mean to the target's own end (along their mean displacement, end minus start,
/// when the target ends at the mean; along the first variable when that is none either).
/// Every sample moves by the offset from the target's end to the far goal times the
/// minimum-jerk profile of its phase: the start stays, the end is the far goal.
pub fn far_target(train: &[Demonstration], target: &Demonstration, k: f64) -> Demonstration {
    let (Some(end), Some(width)) = (target.rows.last(), target.rows.first().map(Vec::len)) else {
        return target.clone();
    };
    let mean = |f: &dyn Fn(&Demonstration) -> Vec<f64>| -> Vec<f64> {
        let mut m = vec![0.0; width];
        for d in train.iter().filter(|d| !d.rows.is_empty()) {
            m.iter_mut()
                .zip(f(d))
                .for_each(|(a, v)| *a += v / train.len() as f64);
        }
        m
    };
    let mean_end = mean(&|d| d.rows[d.rows.len() - 1].clone());
    let ends: Vec<&Vec<f64>> = train.iter().filter_map(|d| d.rows.last()).collect();
    let spread = end_spread(&ends);
    let unit = |v: Vec<f64>| -> Option<Vec<f64>> {
        let n = euclidean(&v, &vec![0.0; v.len()]);
        (n > 1e-12).then(|| v.iter().map(|x| x / n).collect())
    };
    let away: Vec<f64> = end.iter().zip(&mean_end).map(|(e, m)| e - m).collect();
    let travel = mean(&|d| {
        let (a, b) = (&d.rows[0], &d.rows[d.rows.len() - 1]);
        b.iter().zip(a).map(|(b, a)| b - a).collect()
    });
    let first_axis = (0..width).map(|d| f64::from(u8::from(d == 0))).collect();
    let dir = unit(away).or_else(|| unit(travel)).unwrap_or(first_axis);
    let goal: Vec<f64> = mean_end
        .iter()
        .zip(&dir)
        .map(|(m, u)| m + k * spread * u)
        .collect();
    let offset: Vec<f64> = goal.iter().zip(end).map(|(g, e)| g - e).collect();
    let last = (target.rows.len().max(2) - 1) as f64;
    let mut moved = target.clone();
    for (i, row) in moved.rows.iter_mut().enumerate() {
        let h = minimum_jerk_at(i as f64 / last);
        row.iter_mut().zip(&offset).for_each(|(v, o)| *v += o * h);
    }
    moved.source = format!("{} (goal {k} x the end spread away)", target.source);
    moved
}
