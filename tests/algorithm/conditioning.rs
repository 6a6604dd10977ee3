//! Beyond the demonstrated path, held out (`cosco_hsom::eval`): folds conditioned on the
//! held-out demonstration's end and middle meet them exactly, the confidence band covers the
//! held-out demonstration about as often as it says, and a far goal is reached inside the
//! joint ranges. Needs no simulator: runs in both builds.

use crate::hsom_common;

use cosco_hsom::condition::ConfidenceBand;
use cosco_hsom::config::HsomConfig;
use cosco_hsom::curve::at_phase;
use cosco_hsom::dtw::{dtw, Band};
use cosco_hsom::eval::{
    all_but, far_target, leave_one_out, ConditionErrors, Conditioning, GestureLoo, Kinematic,
    LooSettings, Method,
};
use hsom_common::{handwriting, recommended_for};

/// The recommended configuration for 2-D data, trained briefly.
fn quick() -> HsomConfig {
    let mut p = recommended_for(2).into_params();
    p.training_steps = 1500;
    p.check("quick").unwrap()
}

fn study(conditioning: Conditioning) -> GestureLoo {
    let settings = LooSettings {
        height_1: false,
        gmr: false,
        promp: true,
        dmp: true,
        dba: true,
        replay: false,
        in_sample: false,
        conditioning,
        far: None,
        sittings: false,
        threads: 2,
        keep_learned: false,
    };
    let demos = handwriting(6, 21);
    leave_one_out(
        &quick(),
        vec![("w".into(), demos)],
        &settings,
        &Kinematic,
        None,
    )
    .unwrap()
    .remove(0)
}

#[test]
fn conditioned_folds_meet_the_held_out_end_and_middle_exactly() {
    let conditioned = study(Conditioning::EndMid);
    let plain = study(Conditioning::Unconditioned);
    for (k, (c, p)) in conditioned.held_out.iter().zip(&plain.held_out).enumerate() {
        let target = &conditioned.demonstrations[k];
        let s = c.score(Method::Hierarchy).unwrap();
        assert!(s.goal_error.unwrap() < 1e-6, "fold {k}: goal error {s:?}");
        assert!(s.via_error.unwrap() < 1e-6, "fold {k}: via error {s:?}");
        // negative control: the reproduction that ignores the conditions misses them
        let conditions = Conditioning::EndMid.of(target);
        let missed =
            ConditionErrors::of(&conditions, &p.run(Method::Hierarchy).unwrap().postures).unwrap();
        let diag = conditioned.diagonal;
        assert!(missed.via.unwrap() / diag > 1e-3, "fold {k}: {missed:?}");
        // the via-point is the held-out demonstration's own posture at phase 0.5
        assert_eq!(conditions.via[0].posture, at_phase(&target.rows, 0.5));
    }
    // conditioned on where the held-out demonstration goes, the hierarchy is closer to it
    let mean = |g: &GestureLoo| {
        g.mean(&g.held_out, Method::Hierarchy, |s| s.relative_dtw)
            .unwrap()
    };
    assert!(
        mean(&conditioned) < mean(&plain),
        "{} vs {}",
        mean(&conditioned),
        mean(&plain)
    );
}

#[test]
fn the_band_covers_the_held_out_demonstration_and_the_global_envelope_covers_too_much() {
    let g = study(Conditioning::Unconditioned);
    let covered = g
        .mean(&g.held_out, Method::Hierarchy, |s| s.coverage.unwrap())
        .unwrap();
    assert!(
        (0.85..=0.99).contains(&covered),
        "hierarchy's coverage {covered}"
    );
    // negative control: a band made of the demonstrations' global minimum and maximum of
    // each variable holds every sample, above the nominal 95 %'s bound
    let mut envelope = Vec::new();
    for (k, fold) in g.held_out.iter().enumerate() {
        let run = fold.run(Method::Hierarchy).unwrap();
        let all: Vec<&Vec<f64>> = g.demonstrations.iter().flat_map(|d| &d.rows).collect();
        let (lo, hi): (Vec<f64>, Vec<f64>) = (0..2)
            .map(|d| {
                let v = all.iter().map(|r| r[d]);
                (
                    v.clone().fold(f64::INFINITY, f64::min),
                    v.fold(f64::NEG_INFINITY, f64::max),
                )
            })
            .unzip();
        let band = ConfidenceBand {
            lo: vec![lo; run.postures.len()],
            hi: vec![hi; run.postures.len()],
        };
        let target = &g.demonstrations[k].rows;
        let path = dtw(&run.postures, target, Band::None).unwrap().path;
        envelope.push(band.coverage(target, &path));
    }
    let envelope = envelope.iter().sum::<f64>() / envelope.len() as f64;
    assert!(envelope > 0.99, "the global envelope covers {envelope}");
}

#[test]
fn a_far_goal_moves_the_held_out_end_and_keeps_its_start() {
    let demos = handwriting(5, 4);
    let train = all_but(&demos, 0);
    let moved = far_target(&train, &demos[0], 4.0);
    assert_eq!(moved.rows[0], demos[0].rows[0]);
    let ends: Vec<&Vec<f64>> = train.iter().map(|d| d.rows.last().unwrap()).collect();
    let spread = cosco_hsom::metrics::end_spread(&ends);
    let mean: Vec<f64> = (0..2)
        .map(|d| ends.iter().map(|e| e[d]).sum::<f64>() / ends.len() as f64)
        .collect();
    let away = cosco_hsom::dtw::euclidean(moved.rows.last().unwrap(), &mean);
    assert!(
        (away - 4.0 * spread).abs() < 1e-9 * (1.0 + spread),
        "{away} vs 4 x {spread}"
    );
    // K = 0: the goal is the mean end
    let at_mean = far_target(&train, &demos[0], 0.0);
    assert!(cosco_hsom::dtw::euclidean(at_mean.rows.last().unwrap(), &mean) < 1e-9);
}
