use super::super::library::{reading_watch, stand_init, wave};
use super::*;
use crate::robot::Robot;
use rand::SeedableRng;

const LIMITS: [(f64, f64); 6] = [
    (-2.08567, 2.08567),
    (-0.314159, 1.32645),
    (-2.08567, 2.08567),
    (-1.54462, -0.0349066),
    (-1.82387, 1.82387),
    (0.0, 1.0),
];

fn dist(a: &Pose, b: &Pose) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn starts_and_ends_at_the_initial_posture_and_reaches_the_apex() {
    let g = reading_watch();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let h = HumanTrajectory::sample(&g, &Variation::default(), &mut rng).unwrap();
    assert!(dist(&h.at(0.0), &stand_init(Robot::LeftArm)) < 1e-12);
    assert!(dist(&h.at(h.duration()), &stand_init(Robot::LeftArm)) < 1e-9);
    let closest = h
        .sampled(0.01)
        .iter()
        .map(|(_, q)| dist(q, &g.apex()))
        .fold(f64::INFINITY, f64::min);
    // key pose perturbed by 3 degrees per joint: within ~5 sigma of 6 joints
    assert!(closest < 0.2, "closest approach to the apex {closest} rad");
}

#[test]
fn demonstrations_differ_in_length_and_seeds_repeat() {
    let g = wave();
    let v = Variation::default();
    let mut r1 = ChaCha8Rng::seed_from_u64(1);
    let a = HumanTrajectory::sample(&g, &v, &mut r1).unwrap();
    let b = HumanTrajectory::sample(&g, &v, &mut r1).unwrap();
    assert!((a.duration() - b.duration()).abs() > 0.05);
    let mut r2 = ChaCha8Rng::seed_from_u64(1);
    let a2 = HumanTrajectory::sample(&g, &v, &mut r2).unwrap();
    assert_eq!(a.sampled(0.05).len(), a2.sampled(0.05).len());
    assert_eq!(a.at(2.0), a2.at(2.0));
}

#[test]
fn stays_inside_limits_and_is_still_while_idle() {
    for g in super::super::library::Gesture::all(crate::robot::Robot::LeftArm) {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let h = HumanTrajectory::sample(&g, &Variation::default(), &mut rng).unwrap();
        for (_, q) in h.sampled(0.01) {
            for (j, v) in q.iter().enumerate() {
                assert!(
                    *v >= LIMITS[j].0 && *v <= LIMITS[j].1,
                    "{} joint {j} = {v}",
                    g.name
                );
            }
        }
        let (s, _) = h.motion_interval();
        assert!(
            dist(&h.at(s * 0.9), &g.initial) < 1e-12,
            "{} moves while idle",
            g.name
        );
    }
}

#[test]
fn bad_variation_is_rejected_with_the_field_name() {
    let v = Variation {
        speed: 1.5,
        ..Variation::default()
    };
    let mut rng = ChaCha8Rng::seed_from_u64(0);
    let e = HumanTrajectory::sample(&reading_watch(), &v, &mut rng).unwrap_err();
    assert!(e.contains("speed"), "{e}");
}
