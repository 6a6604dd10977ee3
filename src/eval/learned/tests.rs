use super::*;
use crate::config::HsomConfig;
use crate::eval::{in_loop, leave_one_out, GestureLoo, Kinematic, LooSettings, LoopRun, Pool};
use crate::stepper::{Disturbance, KinematicLoop};

/// Five half circles of growing radius in 2-D, 60 samples each.
fn arcs() -> Vec<Demonstration> {
    (0..5)
        .map(|k| {
            let r = 1.0 + 0.05 * k as f64;
            let rows = (0..60)
                .map(|i| {
                    let a = std::f64::consts::PI * i as f64 / 59.0;
                    vec![r * a.cos(), r * a.sin() + 0.02 * k as f64]
                })
                .collect();
            Demonstration {
                source: format!("arc {k}"),
                columns: vec!["x".into(), "y".into()],
                time: None,
                rows,
            }
        })
        .collect()
}

/// The recommended configuration for 2-D data, trained briefly.
fn quick() -> HsomConfig {
    let config = crate::config::load_config_or_default(None).unwrap();
    let mut p = config.for_width(2).unwrap().into_params();
    p.training_steps = 1500;
    p.check("quick").unwrap()
}

/// Leave-one-out on the arcs with ProMP and the DMP, what the folds learned kept or not.
fn study(keep_learned: bool) -> Vec<GestureLoo> {
    let settings = LooSettings {
        height_1: false,
        gmr: false,
        replay: false,
        in_sample: false,
        keep_learned,
        ..LooSettings::default()
    };
    leave_one_out(
        &quick(),
        vec![("arcs".into(), arcs())],
        &settings,
        &Kinematic,
        None,
    )
    .unwrap()
}

/// ProMP and the DMP in the loop, held, on every fold of `study`: per fold, one run each.
fn runs(study: &[GestureLoo]) -> Vec<Vec<LoopRun>> {
    let hold = Disturbance::disturb("hold:0.4:0.2").unwrap();
    let methods = [Method::ProMP, Method::Dmp];
    let pool = Pool::new(1).unwrap();
    let mut all = in_loop(&quick(), study, &methods, &[hold], &KinematicLoop, &pool);
    all.remove(0).remove(0).folds
}

#[test]
fn a_fold_keeps_what_its_methods_learned_when_asked() {
    let kept = study(true);
    let fold = &kept[0].held_out[0];
    let methods: Vec<Method> = fold.learned.0.iter().map(|(m, _)| *m).collect();
    let expected = [
        Method::Hierarchy,
        Method::NearestSequence,
        Method::ProMP,
        Method::Dmp,
        Method::Dba,
    ];
    assert_eq!(methods, expected);
    // the hierarchy and the nearest sequence share one model
    let model = |m| match &**fold.learned.get(m).unwrap() {
        Learned::Hsom(h) => h.clone(),
        other => panic!("{} learned {other:?}", m.name()),
    };
    let (h, n) = (model(Method::Hierarchy), model(Method::NearestSequence));
    assert!(Arc::ptr_eq(&h, &n));
    assert!(study(false)[0].held_out[0].learned.0.is_empty());
}

#[test]
fn the_loop_runs_what_each_fold_learned() {
    let kept = study(true);
    let ran = runs(&kept);
    assert_eq!(ran.len(), 5);
    assert!(ran.iter().flatten().all(|r| r.error.is_none()), "{ran:?}");
    // kept or learned again, the same runs
    assert_eq!(ran, runs(&study(false)));
    // fold 1 given fold 2's ProMP: its ProMP run changes, its DMP run does not
    let mut swapped = kept.clone();
    let other = kept[0].held_out[1].learned.get(Method::ProMP).unwrap();
    for (m, l) in &mut swapped[0].held_out[0].learned.0 {
        if *m == Method::ProMP {
            *l = other.clone();
        }
    }
    let changed = runs(&swapped);
    assert_ne!(changed[0][0], ran[0][0]);
    assert_eq!(changed[0][1], ran[0][1]);
    assert_eq!(changed[1..], ran[1..]);
}
