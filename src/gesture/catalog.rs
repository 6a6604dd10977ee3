//! Every robot's gestures, by name.

use super::library::{reach_point, reading_watch, salute, wave, Gesture};
use super::upper_body;
use crate::robot::Robot;

impl Gesture {
    /// Every gesture this crate can demonstrate on `robot`.
    pub fn all(robot: Robot) -> Vec<Gesture> {
        match robot {
            Robot::LeftArm => vec![reading_watch(), wave(), reach_point(), salute()],
            Robot::UpperBody => upper_body::all(),
        }
    }

    /// The names of [`Gesture::all`], for messages.
    pub fn names(robot: Robot) -> Vec<&'static str> {
        Gesture::all(robot).iter().map(|g| g.name).collect()
    }

    /// Look a gesture of `robot` up by name.
    pub fn by_name(robot: Robot, name: &str) -> Option<Gesture> {
        Gesture::all(robot).into_iter().find(|g| g.name == name)
    }
}
