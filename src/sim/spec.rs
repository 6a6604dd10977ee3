//! Reference data of Nao H25 V5's left arm (docs: nao-left-arm.md) and named postures.

use super::error::{Result, SimError};

/// Number of actuated joints of the left arm (five arm joints and the hand).
pub const NJ: usize = 6;

/// Joint names in NAOqi order; also the actuator names in the model.
pub const JOINT_NAMES: [&str; NJ] = [
    "LShoulderPitch",
    "LShoulderRoll",
    "LElbowYaw",
    "LElbowRoll",
    "LWristYaw",
    "LHand",
];

/// A posture: one value per joint in [`JOINT_NAMES`] order (radians; LHand is the open fraction).
pub type Posture = [f64; NJ];

/// One row of the reference joint table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointSpec {
    /// NAOqi joint name.
    pub name: &'static str,
    /// Range (min, max) in rad (LHand: open fraction 0..1).
    pub range: (f64, f64),
    /// Maximum velocity, rad/s.
    pub max_velocity: f64,
    /// Maximum torque, N m.
    pub max_torque: f64,
}

impl JointSpec {
    /// Check one value: finite and within the range.
    pub fn check(&self, value: f64) -> Result<f64> {
        if !value.is_finite() {
            return Err(SimError::NotFinite {
                joint: self.name,
                value,
                range: self.range,
            });
        }
        if value < self.range.0 || value > self.range.1 {
            return Err(SimError::OutOfLimit {
                joint: self.name,
                value,
                range: self.range,
            });
        }
        Ok(value)
    }

    /// Clamp one value into the range. NaN is still an error (there is no sensible clamp).
    pub fn clamp(&self, value: f64) -> Result<f64> {
        if value.is_nan() {
            return Err(SimError::NotFinite {
                joint: self.name,
                value,
                range: self.range,
            });
        }
        Ok(value.clamp(self.range.0, self.range.1))
    }
}

/// The reference joint table (Nao H25 V5, NAOqi conventions), in [`JOINT_NAMES`] order.
pub const JOINT_SPECS: [JointSpec; NJ] = [
    JointSpec {
        name: "LShoulderPitch",
        range: (-2.08567, 2.08567),
        max_velocity: 8.26797,
        max_torque: 1.329,
    },
    JointSpec {
        name: "LShoulderRoll",
        range: (-0.314159, 1.32645),
        max_velocity: 7.19407,
        max_torque: 1.7835,
    },
    JointSpec {
        name: "LElbowYaw",
        range: (-2.08567, 2.08567),
        max_velocity: 8.26797,
        max_torque: 1.547,
    },
    JointSpec {
        name: "LElbowRoll",
        range: (-1.54462, -0.0349066),
        max_velocity: 7.19407,
        max_torque: 1.532,
    },
    JointSpec {
        name: "LWristYaw",
        range: (-1.82387, 1.82387),
        max_velocity: 24.6229,
        max_torque: 0.4075,
    },
    JointSpec {
        name: "LHand",
        range: (0.0, 1.0),
        max_velocity: 8.33,
        max_torque: 0.292,
    },
];

/// Check a posture given as a slice: six values, each finite and within its joint's range.
/// The error names the first offending joint, its value and its range.
pub fn check_posture(values: &[f64]) -> Result<Posture> {
    let mut p = to_array(values)?;
    for (v, spec) in p.iter_mut().zip(JOINT_SPECS.iter()) {
        *v = spec.check(*v)?;
    }
    Ok(p)
}

/// Clamp a posture into the joint ranges (documented as such: out-of-range values are moved to
/// the nearest limit). Wrong joint counts and NaN are still errors.
pub fn clamp_posture(values: &[f64]) -> Result<Posture> {
    let mut p = to_array(values)?;
    for (v, spec) in p.iter_mut().zip(JOINT_SPECS.iter()) {
        *v = spec.clamp(*v)?;
    }
    Ok(p)
}

fn to_array(values: &[f64]) -> Result<Posture> {
    <Posture>::try_from(values).map_err(|_| SimError::WrongJointCount {
        expected: NJ,
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

    /// Joint values in [`JOINT_NAMES`] order.
    #[allow(clippy::approx_constant)] // Stand's 1.4426 is NAOqi's angle, not log2(e)
    pub fn angles(self) -> Posture {
        match self {
            NamedPosture::StandInit => [1.4, 0.3, -1.39, -1.01, 0.0, 0.25],
            NamedPosture::Stand => [1.4426, 0.2245, -1.2023, -0.4173, 0.1, 0.3],
            NamedPosture::Crouch => [1.3969, 0.1596, -0.7917, -1.0737, 0.15, 0.0],
            NamedPosture::StandZero => [0.0, 0.0087, 0.0, -0.0349066, 0.0, 0.0],
            NamedPosture::ReadingWatch => [-0.22, -0.29, 0.15, -1.05, 0.43, 0.0],
        }
    }

    /// Look a posture up by name (case-sensitive, as in [`NamedPosture::name`]).
    pub fn from_name(name: &str) -> Option<NamedPosture> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
}

#[cfg(test)]
mod tests;
