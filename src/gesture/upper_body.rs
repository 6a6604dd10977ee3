//! The upper body's gestures: both arms and the head, as a Nao greets, welcomes, claps,
//! shrugs, nods and shakes its head. Joint indices are NAOqi order: HeadYaw 0, HeadPitch 1,
//! the left arm 2..8, the right arm 8..14.

use super::library::{
    mirror, pointing, stand_init, upper, ArmPose, Gesture, Segment, POINT_LEFT, READING_WATCH,
    SALUTE, WAVE_UP,
};
use crate::robot::Robot;

const HEAD_YAW: usize = 0;
const HEAD_PITCH: usize = 1;
const R_ELBOW_ROLL: usize = 11;

/// Both hands before the chest, open, about 13 cm apart (the gripper sites), palms turned
/// towards each other.
pub const CLAP_OPEN: ArmPose = [0.5, 0.15, -0.85, -1.0, -0.45, 1.0];
/// The hands driven together: commanded past each other, so the servos press them into
/// contact (the clap's own contact: the hands' shells meet, the gripper sites about 2.5 cm
/// apart).
pub const CLAP_SHUT: ArmPose = [0.5, -0.15, -0.4, -1.1, -0.45, 1.0];
/// Arms opened wide to the sides, forearms raised, hands open.
pub const WELCOME: ArmPose = [0.2, 1.1, -1.0, -0.35, -1.0, 1.0];
/// Elbows out, forearms turned out, palms up (each palm's normal within 15 degrees of
/// vertical), hands open.
pub const SHRUG: ArmPose = [1.1, 0.5, -1.9, -1.0, -1.6, 1.0];

fn gesture(name: &'static str, description: &'static str, segments: Vec<Segment>) -> Gesture {
    Gesture {
        robot: Robot::UpperBody,
        name,
        description,
        initial: stand_init(Robot::UpperBody),
        segments,
    }
}

fn to(head: [f64; 2], left: ArmPose, right: ArmPose, duration: f64) -> Segment {
    Segment::Move {
        to: upper(head, left, right),
        duration,
        perturb: true,
    }
}

fn home(duration: f64) -> Segment {
    Segment::Move {
        to: stand_init(Robot::UpperBody),
        duration,
        perturb: false,
    }
}

/// The pointing gestures of the upper body: `point-left` and `point-right` (the head looks
/// ahead; aim them with `--point-at` and `--look-at`).
pub fn aimed() -> Vec<Gesture> {
    let rest_pose = stand_init(Robot::UpperBody);
    let left_rest: ArmPose = rest_pose[2..8].try_into().expect("six left-arm joints");
    let rest: ArmPose = rest_pose[8..14].try_into().expect("six right-arm joints");
    let point = |name, description, left, right, shoulder| {
        let mut segments = pointing(upper([0.0, 0.0], left, right), shoulder);
        segments.push(home(1.3));
        gesture(name, description, segments)
    };
    vec![
        point(
            "point-left",
            "raise the left arm and point at something, hold it about a second, lower it",
            POINT_LEFT,
            rest,
            2,
        ),
        point(
            "point-right",
            "raise the right arm and point at something, hold it about a second, lower it",
            left_rest,
            mirror(POINT_LEFT),
            8,
        ),
    ]
}

/// The upper body's gestures that `--gesture all` teaches together.
pub fn all() -> Vec<Gesture> {
    let rest_pose = stand_init(Robot::UpperBody);
    let left_rest: ArmPose = rest_pose[2..8].try_into().expect("six left-arm joints");
    let rest: ArmPose = rest_pose[8..14].try_into().expect("six right-arm joints");
    let wave_right = vec![
        to([0.0, 0.0], left_rest, mirror(WAVE_UP), 1.5),
        Segment::Oscillate {
            joints: vec![(R_ELBOW_ROLL, -1.0)],
            amplitude: 0.38,
            period: 0.9,
            cycles: 3.0,
        },
        home(1.5),
    ];
    let mut clap = vec![to([0.0, 0.1], CLAP_OPEN, mirror(CLAP_OPEN), 1.2)];
    for _ in 0..3 {
        clap.push(to([0.0, 0.1], CLAP_SHUT, mirror(CLAP_SHUT), 0.3));
        clap.push(to([0.0, 0.1], CLAP_OPEN, mirror(CLAP_OPEN), 0.3));
    }
    clap.push(home(1.3));
    let nod = vec![
        to([0.0, 0.1], left_rest, rest, 0.5),
        Segment::Oscillate {
            joints: vec![(HEAD_PITCH, 1.0)],
            amplitude: 0.2,
            period: 0.7,
            cycles: 2.0,
        },
        home(0.6),
    ];
    let shake = vec![
        to([0.0, 0.12], left_rest, rest, 0.4),
        Segment::Oscillate {
            joints: vec![(HEAD_YAW, 1.0)],
            amplitude: 0.45,
            period: 0.8,
            cycles: 2.5,
        },
        home(0.5),
    ];
    vec![
        gesture(
            "wave-right",
            "raise the right hand, wave three times with the elbow, lower it",
            wave_right,
        ),
        gesture(
            "clap",
            "bring both hands before the chest, clap three times, lower them",
            clap,
        ),
        gesture(
            "welcome",
            "open both arms wide, hands open, head up a little, hold, return",
            vec![
                to([0.0, -0.12], WELCOME, mirror(WELCOME), 1.6),
                Segment::Hold { duration: 1.0 },
                home(1.6),
            ],
        ),
        gesture(
            "shrug",
            "elbows out, palms up, head tilted down a little, hold briefly, return",
            vec![
                to([0.0, 0.15], SHRUG, mirror(SHRUG), 0.9),
                Segment::Hold { duration: 0.6 },
                home(1.0),
            ],
        ),
        gesture("nod", "nod twice", nod),
        gesture("shake-head", "shake the head twice and a half", shake),
        gesture(
            "reading-watch",
            "raise the left forearm across the chest and look at the watch, hold, return",
            vec![
                to([0.35, 0.3], READING_WATCH, rest, 1.7),
                Segment::Hold { duration: 1.2 },
                home(1.7),
            ],
        ),
        gesture(
            "salute",
            "bring the right hand to the temple quickly, hold briefly, lower it",
            vec![
                to([0.0, 0.0], left_rest, mirror(SALUTE), 1.0),
                Segment::Hold { duration: 0.6 },
                home(1.2),
            ],
        ),
    ]
}
