//! Regression: a reproduction always ends. With `timing = speed` and lists updated every step,
//! the reflex could keep re-executing a node whose output equals the current posture: zero
//! distance, zero postures, forever (found by the before/after variants of `simulate`).
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use cosco_hsom::config::{load_config, ListUpdate};
use cosco_hsom::experiment::{record_demonstrations, DemoSettings};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::sim::NaoArm;

#[test]
fn reproduction_ends_when_steps_produce_no_postures() {
    let arm = NaoArm::load_default().unwrap();
    let g = Gesture::by_name("reading-watch").unwrap();
    let settings = DemoSettings {
        encoder_noise: 0.001,
        ..DemoSettings::default()
    };
    let demos: Vec<_> = record_demonstrations(&arm, &g, 3, 1, &settings, |_| {})
        .unwrap()
        .iter()
        .map(|r| r.to_demonstration("reading-watch"))
        .collect();
    let cfg = load_config(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/configs/successor-table.xml"
    )))
    .unwrap();
    let mut p = cfg.params().clone();
    p.list_update = ListUpdate::EveryStep;
    p.change_ratio = 1.0;
    let cfg = p.check("table1.xml with listUpdate=everyStep").unwrap();
    let model = cfg.fit(&demos).unwrap();
    let rep = model.reproduce(&demos[0].rows[0]).unwrap();
    assert!(!rep.postures.is_empty());
    assert!(rep.postures.len() <= cfg.params().reproduction.max_length);
}
