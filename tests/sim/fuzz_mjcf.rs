//! Fuzzing of the MJCF loading path (proptest): the shipped arm model with attribute values
//! replaced by extreme or malformed ones, elements removed or duplicated, the text cut; and
//! arbitrary bytes. Loading (MuJoCo's parser, then the arm's own checks) must return an error
//! or an arm that the controller can run: never a panic, an abort or a hang. A loaded arm
//! simulates a short motion, so an accepted option (a time step, say) is one the controller
//! can run in bounded time.
//!
//! `PROPTEST_CASES` sets the cases (CI: the default below); the long campaign:
//! docs/RELIABILITY.md.
#![cfg(feature = "sim")] // needs the simulated arm (MuJoCo, OSMesa)

use crate::hsom_common;

use proptest::prelude::*;

use cosco_hsom::sim::{Controller, ControllerConfig, KeyPose, NaoArm};

const ARM: &str = include_str!("../../models/nao_left_arm.xml");

const VALUES: &[&str] = &[
    "0", "-1", "1e308", "-1e308", "nan", "inf", "1e-300", "", "abc", "1 2", "0.05", "1e9",
];

/// The shipped model with op `kind` applied at the `at`-th attribute (or element).
fn mutate(kind: u8, at: usize, value: usize) -> String {
    let attrs: Vec<(usize, usize)> = ARM
        .match_indices("=\"")
        .map(|(i, _)| {
            let start = i + 2;
            let end = start + ARM[start..].find('"').unwrap();
            (start, end)
        })
        .collect();
    match kind % 4 {
        0 | 1 => {
            let (s, e) = attrs[at % attrs.len()];
            format!("{}{}{}", &ARM[..s], VALUES[value % VALUES.len()], &ARM[e..])
        }
        2 => {
            // an element removed (from one '<' to the next '>')
            let opens: Vec<usize> = ARM.match_indices('<').map(|(i, _)| i).collect();
            let s = opens[at % opens.len()];
            let e = s + ARM[s..].find('>').unwrap() + 1;
            format!("{}{}", &ARM[..s], &ARM[e..])
        }
        _ => ARM[..(at % ARM.len())].to_string(),
    }
}

proptest! {
    #![proptest_config(hsom_common::fuzz_config(32))]

    #[test]
    fn mjcf_loading(xml in prop_oneof![
        (any::<u8>(), any::<usize>(), any::<usize>()).prop_map(|(k, a, v)| mutate(k, a, v)),
        prop::collection::vec(any::<u8>(), 0..256).prop_map(|b| String::from_utf8_lossy(&b).into_owned()),
    ]) {
        if let Ok(arm) = NaoArm::from_xml_str(&xml) {
            // what loads must run: a quarter second towards the initial posture
            if let Ok(mut sim) = arm.sim() {
                let c = Controller::new(ControllerConfig::default()).expect("default controller");
                let pose = KeyPose::new_clamped(&sim.posture())
                    .and_then(|k| k.with_hold(0.25));
                if let Ok(k) = pose {
                    let _ = c.execute(&mut sim, &[k]);
                }
            }
        }
    }
}
