//! Reference data of the Nao H25 V5 upper body for tests/upper_body/upper_body_model.rs: the
//! published joint tables (nao-left-arm.md, nao-upper-body.md), NAOqi's postures and a
//! closed-form forward kinematics of the chains.

use nalgebra::{Rotation3, Unit, Vector3};

/// One row of the published joint tables.
#[derive(Clone, Copy)]
pub struct Joint {
    pub name: &'static str,
    /// Origin in the parent link's frame (m); every published rpy is 0.
    pub origin: [f64; 3],
    pub axis: [f64; 3],
    pub range: (f64, f64),
    pub max_torque: f64,
}

pub const fn j(
    name: &'static str,
    origin: [f64; 3],
    axis: [f64; 3],
    range: (f64, f64),
    max_torque: f64,
) -> Joint {
    Joint {
        name,
        origin,
        axis,
        range,
        max_torque,
    }
}

pub const X: [f64; 3] = [1.0, 0.0, 0.0];
pub const Y: [f64; 3] = [0.0, 1.0, 0.0];
pub const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// nao-upper-body.md, "Chains": the head.
pub const HEAD: [Joint; 2] = [
    j("HeadYaw", [0.0, 0.0, 0.1265], Z, (-2.08567, 2.08567), 1.547),
    j("HeadPitch", [0.0; 3], Y, (-0.671952, 0.514872), 1.532),
];
/// Head -> CameraTop_frame: origin and rpy (0, pitch, 0).
pub const CAMERA_TOP: ([f64; 3], f64) = ([0.05871, 0.0, 0.06364], 0.0209435);
/// nao-left-arm.md, "Chain". LHand's origin is l_gripper's offset in the wrist frame.
pub const LEFT: [Joint; 6] = [
    j(
        "LShoulderPitch",
        [0.0, 0.098, 0.1],
        Y,
        (-2.08567, 2.08567),
        1.329,
    ),
    j("LShoulderRoll", [0.0; 3], Z, (-0.314159, 1.32645), 1.7835),
    j(
        "LElbowYaw",
        [0.105, 0.015, 0.0],
        X,
        (-2.08567, 2.08567),
        1.547,
    ),
    j("LElbowRoll", [0.0; 3], Z, (-1.54462, -0.0349066), 1.532),
    j(
        "LWristYaw",
        [0.05595, 0.0, 0.0],
        X,
        (-1.82387, 1.82387),
        0.4075,
    ),
    j("LHand", [0.05775, 0.0, -0.01231], X, (0.0, 1.0), 0.292),
];
/// nao-upper-body.md, "Chains": the right arm as published (not an exact mirror).
pub const RIGHT: [Joint; 6] = [
    j(
        "RShoulderPitch",
        [0.0, -0.098, 0.1],
        Y,
        (-2.08567, 2.08567),
        1.329,
    ),
    j("RShoulderRoll", [0.0; 3], Z, (-1.32645, 0.314159), 1.783),
    j(
        "RElbowYaw",
        [0.105, -0.015, 0.0],
        X,
        (-2.08567, 2.08567),
        1.547,
    ),
    j("RElbowRoll", [0.0; 3], Z, (0.0349066, 1.54462), 1.532),
    j(
        "RWristYaw",
        [0.05595, 0.0, 0.0],
        X,
        (-1.82387, 1.82387),
        0.4075,
    ),
    j("RHand", [0.05775, 0.0, -0.01213], X, (0.0, 1.0), 0.292),
];

/// The sites, in the order [`reference_sites`] gives them.
pub const SITES: [&str; 5] = ["l_wrist", "l_gripper", "r_wrist", "r_gripper", "camera_top"];
pub const LEFT_BODIES: [&str; 6] = [
    "LShoulder",
    "LBicep",
    "LElbow",
    "LForeArm",
    "l_wrist",
    "LHand_fingers",
];
pub const RIGHT_BODIES: [&str; 6] = [
    "RShoulder",
    "RBicep",
    "RElbow",
    "RForeArm",
    "r_wrist",
    "RHand_fingers",
];

/// A whole posture in the model's joint order: head (2), left arm (6), right arm (6).
pub type Posture = [f64; 14];
pub type Arm = [f64; 6];

/// NAOqi's left-arm postures (nao-left-arm.md; LHand 0 where not given).
pub const STAND_INIT: Arm = [1.4, 0.3, -1.39, -1.01, 0.0, 0.25];
#[allow(clippy::approx_constant)] // Stand's 1.4426 is NAOqi's angle, not log2(e)
pub const DOCUMENTED: [(&str, Arm); 5] = [
    ("StandInit", STAND_INIT),
    ("Stand", [1.4426, 0.2245, -1.2023, -0.4173, 0.1, 0.3]),
    ("Crouch", [1.3969, 0.1596, -0.7917, -1.0737, 0.15, 0.0]),
    ("StandZero", [0.0, 0.0087, 0.0, -0.0349066, 0.0, 0.0]),
    ("ReadingWatch", [-0.22, -0.29, 0.15, -1.05, 0.43, 0.0]),
];
/// The left hand driven into the chest: shoulder roll at its inner limit, elbow fully bent.
pub const HAND_INTO_CHEST: Arm = [0.6, -0.314159, 0.0, -1.54, 0.0, 0.0];
/// Both forearms folded in front of the chest at shoulder height: the hands cross.
pub const HUG: Arm = [0.0, -0.314159, 0.0, -1.54, 0.0, 0.0];

/// nao-upper-body.md: a right-arm posture mirrors a left-arm one by negating ShoulderRoll,
/// ElbowYaw, ElbowRoll and WristYaw.
pub fn mirror(a: Arm) -> Arm {
    [a[0], -a[1], -a[2], -a[3], -a[4], a[5]]
}

pub fn posture(head: [f64; 2], left: Arm, right: Arm) -> Posture {
    let mut q = [0.0; 14];
    q[..2].copy_from_slice(&head);
    q[2..8].copy_from_slice(&left);
    q[8..].copy_from_slice(&right);
    q
}

pub fn all_joints() -> Vec<Joint> {
    HEAD.iter().chain(&LEFT).chain(&RIGHT).copied().collect()
}

// ---------------------------------------------------------------------------------------
// forward kinematics

pub type Frame = (Rotation3<f64>, Vector3<f64>);

pub fn v3(a: [f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// Torso -> the frame after `joints` at angles `q`: each joint translates by its origin in
/// the parent frame, then turns about its axis.
pub fn chain(joints: &[Joint], q: &[f64]) -> Frame {
    let mut r = Rotation3::identity();
    let mut p = Vector3::zeros();
    for (joint, angle) in joints.iter().zip(q) {
        p += r * v3(joint.origin);
        r *= Rotation3::from_axis_angle(&Unit::new_normalize(v3(joint.axis)), *angle);
    }
    (r, p)
}

/// The reference frames of [`SITES`] at posture `q`, from the tables given.
pub fn reference_sites(
    left: &[Joint; 6],
    right: &[Joint; 6],
    camera_pitch: f64,
    q: &Posture,
) -> [Frame; 5] {
    let arm = |table: &[Joint; 6], q: &[f64]| {
        let (r, p) = chain(&table[..5], &q[..5]);
        [(r, p), (r, p + r * v3(table[5].origin))]
    };
    let [lw, lg] = arm(left, &q[2..8]);
    let [rw, rg] = arm(right, &q[8..]);
    let (hr, hp) = chain(&HEAD, &q[..2]);
    let cam = (
        hr * Rotation3::from_axis_angle(&Vector3::y_axis(), camera_pitch),
        hp + hr * v3(CAMERA_TOP.0),
    );
    [lw, lg, rw, rg, cam]
}
