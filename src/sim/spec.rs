//! The left arm's joint table and named postures, as the simulator's fixed-size postures: read
//! from the robot description ([`crate::robot`]).

use super::error::{Result, SimError};

use std::sync::LazyLock;

use crate::robot::{Joint, Robot, LEFT_ARM_JOINTS};

/// Number of actuated joints of the left arm (five arm joints and the hand).
pub const NJ: usize = 6;

/// Joint names in NAOqi order; also the actuator names in the model.
pub const JOINT_NAMES: [&str; NJ] = LEFT_ARM_JOINTS;

/// A posture: one value per joint in [`JOINT_NAMES`] order (radians; LHand is the open fraction).
pub type Posture = [f64; NJ];

/// One row of the reference joint table: the robot description's [`Joint`].
pub type JointSpec = Joint;

/// The reference joint table (Nao H25 V5, NAOqi conventions), in [`JOINT_NAMES`] order: the
/// left arm of the robot description ([`Robot::LeftArm`]).
pub static JOINT_SPECS: LazyLock<[JointSpec; NJ]> = LazyLock::new(|| {
    <[Joint; NJ]>::try_from(Robot::LeftArm.joints()).expect("the left arm has six joints")
});

/// Check one value: finite and within the joint's range.
pub fn check_joint(spec: &JointSpec, value: f64) -> Result<f64> {
    if !value.is_finite() {
        return Err(SimError::NotFinite {
            joint: spec.name,
            value,
            range: spec.range,
        });
    }
    if value < spec.range.0 || value > spec.range.1 {
        return Err(SimError::OutOfLimit {
            joint: spec.name,
            value,
            range: spec.range,
        });
    }
    Ok(value)
}

/// Clamp one value into the joint's range. NaN is still an error (there is no sensible clamp).
pub fn clamp_joint(spec: &JointSpec, value: f64) -> Result<f64> {
    if value.is_nan() {
        return Err(SimError::NotFinite {
            joint: spec.name,
            value,
            range: spec.range,
        });
    }
    Ok(value.clamp(spec.range.0, spec.range.1))
}

/// Check a posture given as a slice: six values, each finite and within its joint's range.
/// The error names the first offending joint, its value and its range.
pub fn check_posture(values: &[f64]) -> Result<Posture> {
    check_posture_of(Robot::LeftArm, values)
}

/// Clamp a posture into the joint ranges (documented as such: out-of-range values are moved to
/// the nearest limit). Wrong joint counts and NaN are still errors.
pub fn clamp_posture(values: &[f64]) -> Result<Posture> {
    clamp_posture_of(Robot::LeftArm, values)
}

/// [`check_posture`] for `robot`'s `N` joints.
pub fn check_posture_of<const N: usize>(robot: Robot, values: &[f64]) -> Result<[f64; N]> {
    let mut p = to_array(values)?;
    for (v, spec) in p.iter_mut().zip(robot.joints()) {
        *v = check_joint(spec, *v)?;
    }
    Ok(p)
}

/// [`clamp_posture`] for `robot`'s `N` joints.
pub fn clamp_posture_of<const N: usize>(robot: Robot, values: &[f64]) -> Result<[f64; N]> {
    let mut p = to_array(values)?;
    for (v, spec) in p.iter_mut().zip(robot.joints()) {
        *v = clamp_joint(spec, *v)?;
    }
    Ok(p)
}

fn to_array<const N: usize>(values: &[f64]) -> Result<[f64; N]> {
    <[f64; N]>::try_from(values).map_err(|_| SimError::WrongJointCount {
        expected: N,
        got: values.len(),
    })
}

/// NAOqi's named postures of the left arm (docs: nao-left-arm.md, "Reference postures").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NamedPosture {
    /// The usual rest and initial posture: arm down, elbow bent, hand slightly open.
    StandInit,
    /// NAOqi `Stand`.
    Stand,
    /// NAOqi `Crouch`.
    Crouch,
    /// Arm straight forward (NAOqi `StandZero`). LElbowRoll is its limit -0.0349066 (the
    /// documentation's rounded -0.0349 is 7e-6 rad beyond it); LHand 0 (not given).
    StandZero,
    /// Forearm across the chest, back of the wrist towards the head camera; the wrist is at
    /// about (0.117, 0.028, 0.119) m in the torso frame. Collision-free in this model (no
    /// contacts are simulated); LHand 0 (not given).
    ReadingWatch,
}

impl NamedPosture {
    /// All named postures.
    pub const ALL: [NamedPosture; 5] = [
        NamedPosture::StandInit,
        NamedPosture::Stand,
        NamedPosture::Crouch,
        NamedPosture::StandZero,
        NamedPosture::ReadingWatch,
    ];

    /// The posture's name (also the model's keyframe name).
    pub fn name(self) -> &'static str {
        match self {
            NamedPosture::StandInit => "StandInit",
            NamedPosture::Stand => "Stand",
            NamedPosture::Crouch => "Crouch",
            NamedPosture::StandZero => "StandZero",
            NamedPosture::ReadingWatch => "ReadingWatch",
        }
    }

    /// Joint values in [`JOINT_NAMES`] order (the model's keyframe of this name).
    pub fn angles(self) -> Posture {
        let p = Robot::LeftArm.posture(self.name());
        p.and_then(|p| Posture::try_from(p).ok())
            .expect("every named posture is a keyframe of the left-arm model")
    }

    /// Look a posture up by name (case-sensitive, as in [`NamedPosture::name`]).
    pub fn from_name(name: &str) -> Option<NamedPosture> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
}

#[cfg(test)]
mod tests;
