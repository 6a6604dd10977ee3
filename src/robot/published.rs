//! What the MJCF models have no place for: each joint's maximum velocity as published (the
//! `nao_description` URDF of ros-naoqi, robot "NaoH25V50", joint `<limit velocity>`; the
//! hands' from Aldebaran's H25 documentation), rad/s (a hand: open fraction per second).

const MAX_VELOCITY: [(&str, f64); 14] = [
    ("HeadYaw", 8.26797),
    ("HeadPitch", 7.19407),
    ("LShoulderPitch", 8.26797),
    ("LShoulderRoll", 7.19407),
    ("LElbowYaw", 8.26797),
    ("LElbowRoll", 7.19407),
    ("LWristYaw", 24.6229),
    ("LHand", 8.33),
    ("RShoulderPitch", 8.26797),
    ("RShoulderRoll", 7.19407),
    ("RElbowYaw", 8.26797),
    ("RElbowRoll", 7.19407),
    ("RWristYaw", 24.6229),
    ("RHand", 8.33),
];

/// A joint's published maximum velocity; every joint of a shipped model has one (its tests
/// check it).
pub(super) fn max_velocity(joint: &str) -> f64 {
    MAX_VELOCITY
        .iter()
        .find(|(n, _)| *n == joint)
        .map(|(_, v)| *v)
        .unwrap_or_else(|| panic!("no published maximum velocity for `{joint}`"))
}
