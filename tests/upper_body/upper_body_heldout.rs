//! The upper body held out: the hierarchy with `configs/nao-upper-body.xml` on recorded clap
//! demonstrations keeps the two arms' lag within the demonstrations' spread and, executed on the
//! simulated upper body, touches nothing; one arm delayed fails the lag (the negative control).

#![cfg(feature = "sim")]

use cosco_hsom::config::load_config;
use cosco_hsom::eval::{leave_one_out, two_arms, Kinematic, LooSettings, Method};
use cosco_hsom::experiment::demonstrate::{record_demonstrations, DemoSettings};
use cosco_hsom::experiment::signature::signature;
use cosco_hsom::experiment::upper_body::{contacts_section, execute_contacts};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::metrics::two_arms::{arm_lag, LagSpread};
use cosco_hsom::robot::Robot;
use cosco_hsom::sim::NaoArm;

#[test]
fn the_hierarchy_claps_with_both_arms_together_its_hands_meeting_and_touches_nothing_else() {
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody).unwrap();
    let clap = Gesture::by_name(Robot::UpperBody, "clap").unwrap();
    let demos: Vec<_> = record_demonstrations(&arm, &clap, 3, 41, &DemoSettings::default(), |_| {})
        .unwrap()
        .iter()
        .enumerate()
        .map(|(i, r)| r.to_demonstration(format!("clap/demo_{:02}.csv", i + 1)))
        .collect();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/nao-upper-body.xml");
    let config = load_config(std::path::Path::new(path)).unwrap();
    let settings = LooSettings {
        height_1: false,
        gmr: false,
        promp: false,
        dmp: false,
        dba: false,
        replay: false,
        in_sample: false,
        threads: 2,
        ..LooSettings::default()
    };
    let study = leave_one_out(
        &config,
        vec![("clap".into(), demos.clone())],
        &settings,
        &Kinematic,
        None,
    )
    .unwrap();
    let lags = two_arms(&study);
    assert_eq!(lags.len(), 1, "the clap moves both arms");
    let hierarchy = (lags[0].methods.iter())
        .find(|m| m.method == Method::Hierarchy)
        .unwrap();
    assert_eq!(
        (hierarchy.within, hierarchy.folds),
        (3, 3),
        "{:?}, demonstrations {:?}",
        hierarchy.lags,
        lags[0].demo_lags
    );

    // the negative control: fold 1's reproduction with the right arm delayed by 20 samples
    let rows = &study[0].held_out[0]
        .run(Method::Hierarchy)
        .unwrap()
        .postures;
    let delayed: Vec<Vec<f64>> = (0..rows.len())
        .map(|k| {
            let mut row = rows[k].clone();
            row[8..14].copy_from_slice(&rows[k.saturating_sub(20)][8..14]);
            row
        })
        .collect();
    let spread = LagSpread::of_demos(&[&demos[1].rows, &demos[2].rows]).unwrap();
    let lag = arm_lag(&delayed).unwrap();
    assert!(!spread.contains(lag), "lag {lag} in {spread:?}");

    // every fold's reproduction keeps the clap's signature: the hands meet more than once
    for fold in &study[0].held_out {
        let rows = &fold.run(Method::Hierarchy).unwrap().postures;
        let s = signature(&arm, "clap", rows).unwrap().unwrap();
        assert!(s.holds, "{}: {s:?}", fold.demonstration);
    }
    // executed on the simulated upper body: the hands' contact, the clap's own, and no other
    let section = contacts_section(&study, 2).unwrap().unwrap();
    assert_eq!(section.json["executed"], 3, "{}", section.markdown);
    assert_eq!(section.json["with_own_contact"], 3, "{}", section.markdown);
    assert_eq!(section.json["with_contact"], 0, "{}", section.markdown);
    // the same path reports a contact: the left hand driven into the chest
    let rest = Robot::UpperBody.posture("StandInit").unwrap().to_vec();
    let mut chest = rest.clone();
    chest[2..8].copy_from_slice(&[0.6, -0.314159, 0.0, -1.54, 0.0, 0.0]);
    let into_chest: Vec<Vec<f64>> = (0..80)
        .map(|k| match k {
            20..=60 => chest.clone(),
            _ => rest.clone(),
        })
        .collect();
    assert!(!execute_contacts(&arm, &into_chest, 0.025)
        .unwrap()
        .is_empty());
}
