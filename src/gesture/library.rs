//! The named gestures of each robot: key poses and the timing a person would give them.
//!
//! The left arm's four are the paper's experiment. The upper body's use both arms and the
//! head: a pose there is built from a left-arm pose, a right-arm pose and the head's two
//! angles ([`upper`]); the right arm's poses are the left's mirrored ([`mirror`]) unless a
//! gesture says otherwise.

use crate::robot::Robot;

/// A posture of a robot's joints in NAOqi order (radians; a hand as an open fraction in 0..1).
pub type Pose = Vec<f64>;

/// A left-arm posture: LShoulderPitch, LShoulderRoll, LElbowYaw, LElbowRoll, LWristYaw, LHand.
pub type ArmPose = [f64; 6];

/// NAOqi's StandInit posture of `robot` (its model's keyframe): the initial and final
/// posture of every gesture here.
pub fn stand_init(robot: Robot) -> Pose {
    let p = robot.posture("StandInit");
    p.expect("StandInit is a keyframe of every shipped model")
        .to_vec()
}

/// The right arm's posture mirroring a left-arm one (nao-upper-body.md): ShoulderRoll,
/// ElbowYaw, ElbowRoll and WristYaw change sign.
pub fn mirror(left: ArmPose) -> ArmPose {
    let [p, r, y, e, w, h] = left;
    [p, -r, -y, -e, -w, h]
}

/// An upper-body posture (HeadYaw, HeadPitch, the left arm, the right arm).
pub fn upper(head: [f64; 2], left: ArmPose, right: ArmPose) -> Pose {
    head.iter().chain(&left).chain(&right).copied().collect()
}

/// One part of a gesture, in nominal (unperturbed) timing.
#[derive(Debug, Clone, PartialEq)]
pub enum Segment {
    /// Move to `to` in `duration` seconds (minimum-jerk profile per joint).
    Move {
        /// The key pose reached at the end.
        to: Pose,
        /// Nominal duration in seconds.
        duration: f64,
        /// Whether the demonstrator's imprecision perturbs this key pose (false for the final
        /// return to the initial posture, which the gesture must end on).
        perturb: bool,
    },
    /// Keep still for `duration` seconds.
    Hold {
        /// Nominal duration in seconds.
        duration: f64,
    },
    /// Oscillate joints around the current pose: `weight * amplitude * sin(2 pi t / period)`
    /// for `cycles` whole periods, faded in and out over a quarter period each; two arms
    /// oscillating together share one amplitude and phase, mirrored by their weights' signs.
    Oscillate {
        /// `(joint index in NAOqi order, weight)` of each joint that oscillates.
        joints: Vec<(usize, f64)>,
        /// Amplitude in radians.
        amplitude: f64,
        /// Nominal period in seconds.
        period: f64,
        /// Number of periods.
        cycles: f64,
    },
    /// Move to `to` as a perturbed [`Segment::Move`] does, the joints of `spread` varied
    /// further, each by its standard deviation (degrees): a person pointing at something else
    /// in each demonstration.
    Aim {
        /// The key pose reached at the end, before the spread.
        to: Pose,
        /// Nominal duration in seconds.
        duration: f64,
        /// `(joint index in NAOqi order, standard deviation in degrees)`.
        spread: Vec<(usize, f64)>,
    },
}

/// A named gesture: where it starts and the segments it goes through.
#[derive(Debug, Clone, PartialEq)]
pub struct Gesture {
    /// The robot whose joints it moves.
    pub robot: Robot,
    /// The name used on the command line (`reading-watch`, `wave`, ...).
    pub name: &'static str,
    /// One line for people.
    pub description: &'static str,
    /// The initial (and final) posture.
    pub initial: Pose,
    /// What the demonstrator does after the idle start and before the idle end.
    pub segments: Vec<Segment>,
}

impl Gesture {
    /// The key pose farthest (Euclidean, joint space) from the initial posture: the apex.
    pub fn apex(&self) -> Pose {
        let mut best = &self.initial;
        let mut best_d = 0.0;
        for s in &self.segments {
            if let Segment::Move { to, .. } | Segment::Aim { to, .. } = s {
                let d: f64 = to
                    .iter()
                    .zip(&self.initial)
                    .map(|(a, b)| (a - b).powi(2))
                    .sum();
                if d > best_d {
                    best_d = d;
                    best = to;
                }
            }
        }
        best.clone()
    }
}

/// The paper's gesture (Fig. 1): from StandInit raise the left forearm across the chest as if
/// to read a wristwatch, hold, and return to StandInit.
pub fn reading_watch() -> Gesture {
    Gesture {
        name: "reading-watch",
        description: "raise the forearm across the chest to read a wristwatch, hold, return",
        robot: Robot::LeftArm,
        initial: stand_init(Robot::LeftArm),
        segments: vec![
            Segment::Move {
                to: READING_WATCH.to_vec(),
                duration: 1.7,
                perturb: true,
            },
            Segment::Hold { duration: 1.2 },
            Segment::Move {
                to: stand_init(Robot::LeftArm),
                duration: 1.7,
                perturb: false,
            },
        ],
    }
}

/// The "reading watch" key pose (shared/docs/nao-left-arm.md): forearm across the chest,
/// back of the wrist towards the head camera; LHand as in StandInit.
pub const READING_WATCH: ArmPose = [-0.22, -0.29, 0.15, -1.05, 0.43, 0.25];

/// Raised forearm for waving: upper arm forward-up and out, elbow bent.
pub const WAVE_UP: ArmPose = [-0.55, 0.55, -1.35, -0.95, -0.2, 0.8];

/// A wave: raise the forearm, wave it three times (elbow roll), lower it.
pub fn wave() -> Gesture {
    Gesture {
        name: "wave",
        description: "raise the hand, wave three times with the elbow, lower it",
        robot: Robot::LeftArm,
        initial: stand_init(Robot::LeftArm),
        segments: vec![
            Segment::Move {
                to: WAVE_UP.to_vec(),
                duration: 1.5,
                perturb: true,
            },
            Segment::Oscillate {
                joints: vec![(3, 1.0)],
                amplitude: 0.38,
                period: 0.9,
                cycles: 3.0,
            },
            Segment::Move {
                to: stand_init(Robot::LeftArm),
                duration: 1.5,
                perturb: false,
            },
        ],
    }
}

/// Arm stretched forward at shoulder height, hand closed: pointing.
pub const POINT_FORWARD: ArmPose = [0.05, 0.05, -1.0, -0.1, 0.0, 0.0];

/// Reach forward and point, hold, come back.
pub fn reach_point() -> Gesture {
    Gesture {
        name: "reach-point",
        description: "stretch the arm forward and point, hold, come back",
        robot: Robot::LeftArm,
        initial: stand_init(Robot::LeftArm),
        segments: vec![
            Segment::Move {
                to: POINT_FORWARD.to_vec(),
                duration: 1.3,
                perturb: true,
            },
            Segment::Hold { duration: 0.9 },
            Segment::Move {
                to: stand_init(Robot::LeftArm),
                duration: 1.4,
                perturb: false,
            },
        ],
    }
}

/// Hand at the forehead: elbow high and out, forearm folded across towards the head (found by
/// a grid search of the simulated kinematics: gripper about 2 cm from (0.06, 0.055, 0.20) m).
pub const SALUTE: ArmPose = [-1.0, 0.45, -0.15, -1.48, -0.6, 1.0];

/// A quick salute: hand to the temple, short hold, down again.
pub fn salute() -> Gesture {
    Gesture {
        name: "salute",
        description: "bring the hand to the temple quickly, hold briefly, lower it",
        robot: Robot::LeftArm,
        initial: stand_init(Robot::LeftArm),
        segments: vec![
            Segment::Move {
                to: SALUTE.to_vec(),
                duration: 1.0,
                perturb: true,
            },
            Segment::Hold { duration: 0.6 },
            Segment::Move {
                to: stand_init(Robot::LeftArm),
                duration: 1.2,
                perturb: false,
            },
        ],
    }
}

/// The left arm outstretched forward, a little up and out, the elbow nearly straight, the
/// hand closed: pointing (the ray from the shoulder through the gripper about 10 degrees up
/// and 20 degrees to the left).
pub const POINT_LEFT: ArmPose = [-0.15, 0.35, -1.0, -0.1, 0.0, 0.0];

/// How widely a pointing gesture's direction varies from one demonstration to the next:
/// ShoulderPitch's and ShoulderRoll's standard deviation, degrees.
pub const POINT_SPREAD_DEG: f64 = 10.0;

/// Raise the arm to `to` (a posture of the whole robot) in 1.3 s and hold it pointing for a
/// second; the pointing arm's ShoulderPitch is joint `shoulder` (and its ShoulderRoll the
/// next), varied by [`POINT_SPREAD_DEG`].
pub fn pointing(to: Pose, shoulder: usize) -> Vec<Segment> {
    vec![
        Segment::Aim {
            to,
            duration: 1.3,
            spread: vec![
                (shoulder, POINT_SPREAD_DEG),
                (shoulder + 1, POINT_SPREAD_DEG),
            ],
        },
        Segment::Hold { duration: 1.0 },
    ]
}

/// Point with the left arm at something ahead: raise it, hold it pointing, lower it.
pub fn point_left() -> Gesture {
    let mut segments = pointing(POINT_LEFT.to_vec(), 0);
    segments.push(Segment::Move {
        to: stand_init(Robot::LeftArm),
        duration: 1.3,
        perturb: false,
    });
    Gesture {
        name: "point-left",
        description: "raise the left arm and point at something, hold it about a second, lower it",
        robot: Robot::LeftArm,
        initial: stand_init(Robot::LeftArm),
        segments,
    }
}
