//! The `robot` axis of a sweep: the left arm (the default: a spec without the axis has the
//! identity, run files and run ids it has always had) or the upper body. The defaults of
//! [`AxisValues::robot`] and [`Axes::robot`] (which leave the left arm out of identities and
//! run files), the axis' default gesture and its catalogue of gestures, its model.
//!
//! [`AxisValues::robot`]: super::spec::AxisValues::robot
//! [`Axes::robot`]: super::spec::Axes::robot

use std::path::Path;

use crate::gesture::Gesture;
use crate::robot::Robot;
use crate::sim::{NaoArm, SimError};

/// The default robot.
pub fn left_arm() -> Robot {
    Robot::LeftArm
}

/// Whether `r` is the default robot.
pub fn is_left_arm(r: &Robot) -> bool {
    *r == Robot::LeftArm
}

/// Whether `r` is the default robot alone.
pub fn left_arm_only(r: &[Robot]) -> bool {
    r == [Robot::LeftArm]
}

/// The gesture when the spec has no `gesture` axis: `simulate`'s default of the first robot of
/// `robots` whose default every robot of `robots` has (`reading-watch` for the left arm with
/// the upper body).
pub fn shared_default_gesture(robots: &[Robot]) -> &'static str {
    let shared = |g: &str| robots.iter().all(|&r| Gesture::by_name(r, g).is_some());
    robots
        .iter()
        .map(|&r| r.default_gesture())
        .find(|g| shared(g))
        .unwrap_or_else(|| Robot::LeftArm.default_gesture())
}

/// A gesture of the `gesture` axis, if every robot of `robots` has it; the error names the
/// robot that has not and its gestures.
pub fn check_gesture(robots: &[Robot], g: String) -> Result<String, String> {
    match robots.iter().find(|&&r| Gesture::by_name(r, &g).is_none()) {
        None => Ok(g),
        Some(&r) if robots == [Robot::LeftArm] => Err(format!(
            "unknown gesture '{g}': allowed {}",
            Gesture::names(r).join(", ")
        )),
        Some(&r) => Err(format!(
            "'{g}' is no gesture of the {} (axis `robot` = {}): allowed {}",
            r.name(),
            robot_names(robots),
            Gesture::names(r).join(", ")
        )),
    }
}

/// `left-arm, upper-body`.
pub fn robot_names(robots: &[Robot]) -> String {
    robots
        .iter()
        .map(|r| r.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Load `robot`'s model from `path`, as a run would.
pub fn load_model(robot: Robot, path: &Path) -> Result<(), SimError> {
    match robot {
        Robot::LeftArm => NaoArm::<6>::load_robot(robot, path).map(drop),
        Robot::UpperBody => NaoArm::<14>::load_robot(robot, path).map(drop),
    }
}
