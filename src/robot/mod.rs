//! The Nao H25 V5 as this project simulates and exports it: one description of each robot
//! it knows ([`Robot`]): its joints in NAOqi order with their ranges, maximum velocities and
//! torques ([`Joint`]), its named postures, its MJCF model, its recommended configuration,
//! the gesture `simulate` shows without `--gesture`, the joint whose swings the studies count
//! and the joints its figures show.
//!
//! The MJCF files under `models/` hold the ranges (joint `range`), the torques (actuator
//! `forcerange`) and the named postures (keyframes): they are read from there, once. What
//! MJCF has no place for, the maximum velocities, stands in [`published`] (the
//! `nao_description` URDF of ros-naoqi, robot "NaoH25V50", joint `<limit velocity>`, which
//! agrees with Aldebaran's H25 documentation). The simulator checks a loaded model against
//! this description; the export checks a trajectory against it; conditioning and the
//! demonstrator keep postures within it.

mod mjcf;
#[cfg(test)]
use mjcf::read;
mod published;

use std::sync::LazyLock;

pub use mjcf::joint_ranges;

/// A robot this project simulates, exports to, and checks postures against. Its name on the
/// command line (`--robot`) and in files is [`Robot::name`]'s.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize, clap::ValueEnum,
)]
#[serde(rename_all = "kebab-case")]
pub enum Robot {
    /// The left arm of the paper's experiment: five arm joints and the hand.
    LeftArm,
    /// The upper body, torso fixed: the head's two joints, then the left arm's six and the
    /// right arm's six.
    UpperBody,
}

/// One joint of a robot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// NAOqi joint name; also the actuator's name in the model.
    pub name: &'static str,
    /// Range (lower, upper), rad (a hand: open fraction 0..1).
    pub range: (f64, f64),
    /// Maximum velocity, rad/s (a hand: fraction per second).
    pub max_velocity: f64,
    /// Maximum torque, N m.
    pub max_torque: f64,
}

/// The left arm's joints in NAOqi order.
pub const LEFT_ARM_JOINTS: [&str; 6] = [
    "LShoulderPitch",
    "LShoulderRoll",
    "LElbowYaw",
    "LElbowRoll",
    "LWristYaw",
    "LHand",
];

/// The upper body's joints in NAOqi order.
pub const UPPER_BODY_JOINTS: [&str; 14] = [
    "HeadYaw",
    "HeadPitch",
    "LShoulderPitch",
    "LShoulderRoll",
    "LElbowYaw",
    "LElbowRoll",
    "LWristYaw",
    "LHand",
    "RShoulderPitch",
    "RShoulderRoll",
    "RElbowYaw",
    "RElbowRoll",
    "RWristYaw",
    "RHand",
];

const LEFT_ARM_MJCF: &str = include_str!("../../models/nao_left_arm.xml");
const UPPER_BODY_MJCF: &str = include_str!("../../models/nao_upper_body.xml");

static LEFT_ARM: LazyLock<Description> =
    LazyLock::new(|| Description::read(&LEFT_ARM_JOINTS, LEFT_ARM_MJCF));
static UPPER_BODY: LazyLock<Description> =
    LazyLock::new(|| Description::read(&UPPER_BODY_JOINTS, UPPER_BODY_MJCF));

/// What is read once from a robot's MJCF model and the published velocities.
struct Description {
    joints: Vec<Joint>,
    postures: Vec<(String, Vec<f64>)>,
}

impl Description {
    /// The shipped model is part of the crate and checked by its tests: a model that lacks a
    /// joint, a range or a force range the description names is a broken build, not input.
    fn read(names: &'static [&'static str], xml: &str) -> Description {
        let model = mjcf::read(xml).unwrap_or_else(|e| panic!("a shipped model: {e}"));
        let joints = names
            .iter()
            .map(|&name| Joint {
                name,
                range: model
                    .range(name)
                    .unwrap_or_else(|| panic!("{name} has no range")),
                max_velocity: published::max_velocity(name),
                max_torque: model
                    .max_torque(name)
                    .unwrap_or_else(|| panic!("{name} has no force range")),
            })
            .collect();
        let postures = model.postures(names);
        Description {
            joints,
            postures: postures.unwrap_or_else(|e| panic!("a shipped model: {e}")),
        }
    }
}

impl Robot {
    /// Every robot, the default first.
    pub const ALL: [Robot; 2] = [Robot::LeftArm, Robot::UpperBody];

    /// The name on the command line (`--robot`).
    pub fn name(self) -> &'static str {
        match self {
            Robot::LeftArm => "left-arm",
            Robot::UpperBody => "upper-body",
        }
    }

    /// The robot in a sentence: "left arm" or "upper body" (of the simulated Nao).
    pub fn phrase(self) -> &'static str {
        match self {
            Robot::LeftArm => "left arm",
            Robot::UpperBody => "upper body",
        }
    }

    /// The robot of a command-line name; the error lists the names allowed.
    pub fn from_name(name: &str) -> Result<Robot, String> {
        Self::ALL
            .into_iter()
            .find(|r| r.name() == name)
            .ok_or_else(|| {
                let names: Vec<&str> = Self::ALL.iter().map(|r| r.name()).collect();
                format!("unknown robot `{name}`; use one of: {}", names.join(", "))
            })
    }

    /// Its recommended configuration, built in so that the binaries run from any directory:
    /// `(its name in reports and messages, the XML)`. The left arm's is the default of
    /// `simulate` and `cosco`; demonstrations of the upper body's joints take the upper body's.
    pub const fn config(self) -> (&'static str, &'static str) {
        match self {
            Robot::LeftArm => (
                "configs/nao-gestures.xml (built in)",
                include_str!("../../configs/nao-gestures.xml"),
            ),
            Robot::UpperBody => (
                "configs/nao-upper-body.xml (built in)",
                include_str!("../../configs/nao-upper-body.xml"),
            ),
        }
    }

    /// The gesture `simulate` demonstrates without `--gesture`: the left arm's
    /// `reading-watch`, the upper body's `wave-right`.
    pub const fn default_gesture(self) -> &'static str {
        match self {
            Robot::LeftArm => "reading-watch",
            Robot::UpperBody => "wave-right",
        }
    }

    /// The joint whose large swings the studies count, `(column, name)`: `LElbowRoll`, the
    /// wave's joint.
    pub const fn swing_joint(self) -> (usize, &'static str) {
        match self {
            Robot::LeftArm => (3, "LElbowRoll"),
            Robot::UpperBody => (5, "LElbowRoll"),
        }
    }

    /// The joints its joint figures show, `(column, name)`: the paper's Fig. 4 on the left
    /// arm (the shoulder's two joints and the elbow's), every joint on the upper body.
    pub fn plot_panels(self) -> Vec<(usize, &'static str)> {
        let all = self.joint_names().iter().copied().enumerate();
        match self {
            Robot::LeftArm => all.take(4).collect(),
            Robot::UpperBody => all.collect(),
        }
    }

    fn description(self) -> &'static Description {
        match self {
            Robot::LeftArm => &LEFT_ARM,
            Robot::UpperBody => &UPPER_BODY,
        }
    }

    /// Its joints in NAOqi order.
    pub fn joints(self) -> &'static [Joint] {
        &self.description().joints
    }

    /// Its joint names in NAOqi order (the columns of its demonstrations).
    pub fn joint_names(self) -> &'static [&'static str] {
        match self {
            Robot::LeftArm => &LEFT_ARM_JOINTS,
            Robot::UpperBody => &UPPER_BODY_JOINTS,
        }
    }

    /// Its joint ranges `(lower, upper)` in NAOqi order.
    pub fn ranges(self) -> Vec<(f64, f64)> {
        self.joints().iter().map(|j| j.range).collect()
    }

    /// A named posture (a keyframe of the model: StandInit, ...), in NAOqi order.
    pub fn posture(self, name: &str) -> Option<&'static [f64]> {
        let postures = &self.description().postures;
        postures
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, p)| p.as_slice())
    }

    /// Whether its shipped model has collision shapes, so that contacts between its parts are
    /// simulated and reported: the upper body's links, torso and head have them; the left
    /// arm's model is collision-free (its torso and head are silhouettes).
    pub const fn has_collision_shapes(self) -> bool {
        matches!(self, Robot::UpperBody)
    }

    /// The shipped MJCF model's path.
    pub const fn model_path(self) -> &'static str {
        match self {
            Robot::LeftArm => concat!(env!("CARGO_MANIFEST_DIR"), "/models/nao_left_arm.xml"),
            Robot::UpperBody => concat!(env!("CARGO_MANIFEST_DIR"), "/models/nao_upper_body.xml"),
        }
    }

    /// The robot whose joints `columns` are, in NAOqi order (then its ranges apply and, on the
    /// simulator, its wrist paths exist); `None` for any other variables.
    pub fn of_columns(columns: &[String]) -> Option<Robot> {
        Self::ALL.into_iter().find(|r| {
            let names = r.joint_names();
            columns.len() == names.len() && columns.iter().zip(names).all(|(c, n)| c == n)
        })
    }
}

/// Whether `columns` are the Nao left arm's joints in NAOqi order (the simulated arm's
/// columns: then wrist paths exist and the joint ranges apply).
pub fn are_arm_joints(columns: &[String]) -> bool {
    Robot::of_columns(columns) == Some(Robot::LeftArm)
}

/// The joint ranges, `(lower, upper)` in NAOqi order, when `columns` are a robot's joints
/// ([`Robot::of_columns`]); `None` otherwise.
pub fn arm_ranges(columns: &[String]) -> Option<Vec<(f64, f64)>> {
    Robot::of_columns(columns).map(Robot::ranges)
}

/// A joint's axis in a figure, its name with its unit: `LElbowRoll (rad)`, a hand's
/// `LHand (open fraction)`.
pub fn axis_label(joint: &str) -> String {
    match joint {
        "LHand" | "RHand" => format!("{joint} (open fraction)"),
        _ => format!("{joint} (rad)"),
    }
}

/// How far beyond a joint's range a recorded or reproduced value may lie and still be scored,
/// rad: encoders read a hair beyond a limit, and the simulated joints' soft limits let a
/// motion driven into a limit pass it by up to 0.07 rad (measured on the shuffled controls of
/// tests/sim/gesture_fidelity.rs).
pub const RANGE_TOLERANCE_RAD: f64 = 0.25;

#[cfg(test)]
mod tests;
