//! Every robot's gestures, by name.

use super::library::{point_left, reach_point, reading_watch, salute, wave, Gesture};
use super::upper_body;
use crate::robot::Robot;

impl Gesture {
    /// The gestures of `robot` that `--gesture all` teaches together (the studies' sets of
    /// several gestures); the pointing gestures ([`Gesture::aimed`]) stand apart.
    pub fn all(robot: Robot) -> Vec<Gesture> {
        match robot {
            Robot::LeftArm => vec![reading_watch(), wave(), reach_point(), salute()],
            Robot::UpperBody => upper_body::all(),
        }
    }

    /// The pointing gestures of `robot`, aimed at a target (`--point-at`), asked for by name.
    pub fn aimed(robot: Robot) -> Vec<Gesture> {
        match robot {
            Robot::LeftArm => vec![point_left()],
            Robot::UpperBody => upper_body::aimed(),
        }
    }

    /// Every gesture this crate can demonstrate on `robot`: [`Gesture::all`]'s, then
    /// [`Gesture::aimed`]'s.
    pub fn every(robot: Robot) -> Vec<Gesture> {
        let mut every = Gesture::all(robot);
        every.extend(Gesture::aimed(robot));
        every
    }

    /// The names of [`Gesture::every`], for messages.
    pub fn names(robot: Robot) -> Vec<&'static str> {
        Gesture::every(robot).iter().map(|g| g.name).collect()
    }

    /// Look a gesture of `robot` up by name.
    pub fn by_name(robot: Robot, name: &str) -> Option<Gesture> {
        Gesture::every(robot).into_iter().find(|g| g.name == name)
    }
}
