//! What the arm's scoring ([`crate::sim::evaluate`]) and the steps share: which columns are
//! the arm's joints, and how far beyond a joint's range a value may lie.

use crate::sim::JOINT_NAMES;

/// Whether `columns` are the arm's joints in the model's order (then wrist paths exist).
pub fn are_arm_joints(columns: &[String]) -> bool {
    columns.len() == JOINT_NAMES.len() && columns.iter().zip(JOINT_NAMES).all(|(c, j)| c == j)
}

/// How far beyond a joint's range a recorded or reproduced value may lie and still be scored,
/// rad: encoders read a hair beyond a limit, and the simulated joints' soft limits let a
/// motion driven into a limit pass it by up to 0.07 rad (measured on the shuffled controls of
/// tests/gesture_fidelity.rs).
pub const RANGE_TOLERANCE_RAD: f64 = 0.25;
