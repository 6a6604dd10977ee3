//! The one error type of the `sim` room.

use crate::mujoco::MjError;

/// Everything that can go wrong when loading the arm model, commanding it or recording it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SimError {
    /// MuJoCo refused the model or failed while simulating (its message is kept).
    #[error("MuJoCo: {0}")]
    Mujoco(#[from] MjError),
    /// The model lacks a joint, actuator or site the arm needs.
    #[error("the arm model has no {kind} named `{name}`; use models/nao_left_arm.xml or add it")]
    Missing {
        /// "joint", "actuator" or "site".
        kind: &'static str,
        /// The expected name.
        name: String,
    },
    /// The model disagrees with the reference joint table (src/sim/spec.rs).
    #[error("model mismatch for `{name}`: {what} is {found}, the reference table says {expected}")]
    ModelMismatch {
        /// Joint or actuator name.
        name: String,
        /// Which property differs.
        what: &'static str,
        /// The value found in the model.
        found: String,
        /// The value of the reference table.
        expected: String,
    },
    /// A joint value (posture or target) lies outside the joint's range.
    #[error("{joint} = {value} rad is outside its range [{}, {}]; use a value within the range (or the _clamped variant)", range.0, range.1)]
    OutOfLimit {
        /// Joint name.
        joint: &'static str,
        /// The rejected value.
        value: f64,
        /// The joint's range (min, max).
        range: (f64, f64),
    },
    /// A joint value is NaN or infinite.
    #[error("{joint} = {value} is not a finite number (range [{}, {}])", range.0, range.1)]
    NotFinite {
        /// Joint name.
        joint: &'static str,
        /// The rejected value.
        value: f64,
        /// The joint's range (min, max).
        range: (f64, f64),
    },
    /// A posture or target vector does not have one value per joint.
    #[error("expected {expected} joint values ({}), got {got}", joint_list(*expected))]
    WrongJointCount {
        /// Number of joints of the arm.
        expected: usize,
        /// Number of values given.
        got: usize,
    },
    /// A controller or trajectory parameter is invalid.
    #[error("invalid {name} = {value}: {reason}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What is expected instead.
        reason: &'static str,
    },
    /// A simulation option of the model is outside what the controller can run.
    #[error("the arm model's {name} = {value} is not allowed: {allowed}")]
    BadOption {
        /// The MJCF option (e.g. `option/@timestep`).
        name: &'static str,
        /// The value found.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// A target trajectory is malformed (empty, times not increasing, lengths differ).
    #[error("invalid target trajectory: {0}")]
    InvalidTrajectory(String),
    /// Postures, demonstrations or a setting that cannot be executed or scored on the arm
    /// (named in the message).
    #[error("{0}")]
    Invalid(String),
    /// The metrics refused their input.
    #[error(transparent)]
    Metrics(#[from] crate::metrics::MetricsError),
}

/// Result of the `sim` room.
pub type Result<T> = std::result::Result<T, SimError>;

/// The joints of the robot with `count` joints, for messages.
fn joint_list(count: usize) -> String {
    let robot = crate::robot::Robot::ALL.into_iter();
    let names = robot.map(|r| r.joint_names()).find(|n| n.len() == count);
    names.map_or_else(|| "one per joint".into(), |n| n.join(", "))
}
