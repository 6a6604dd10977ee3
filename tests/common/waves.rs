//! The demonstrator's waves on the Nao's left arm, without the simulator (the tests of the
//! kinematic loop and benches/stepper.rs).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use cosco_hsom::demos::Demonstration;
use cosco_hsom::gesture::{Gesture, HumanTrajectory, Variation};
use cosco_hsom::robot::Robot;

/// The demonstrations' sample period (40 Hz).
pub const WAVE_PERIOD_S: f64 = 0.025;

/// Four waves of the demonstrator on the Nao's left arm (seeded), sampled at 40 Hz, named
/// `wave 0` .. `wave 3`, one column per joint; no simulator.
pub fn waves(seed: u64) -> Vec<Demonstration> {
    let g = Gesture::by_name(Robot::LeftArm, "wave").unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let columns: Vec<String> = Robot::LeftArm
        .joint_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    (0..4)
        .map(|i| {
            let t = HumanTrajectory::sample(&g, &Variation::default(), &mut rng).unwrap();
            Demonstration {
                source: format!("wave {i}"),
                columns: columns.clone(),
                time: None,
                rows: t
                    .sampled(WAVE_PERIOD_S)
                    .into_iter()
                    .map(|(_, q)| q)
                    .collect(),
            }
        })
        .collect()
}
