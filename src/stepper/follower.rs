//! A closed-loop stepper over a [`Course`]: the method says how it re-plans when the arm is
//! not where it was sent and how it moves its goal; following the plan is the same for all.

use crate::condition::Conditions;

use super::{check_posture, Course, Stepper, StepperError};

/// What a method adds to a [`Follower`]: how it re-plans from the encoders' reading and how
/// it moves its goal.
pub trait Replan {
    /// Whether a re-planned rest is met onto the goal and the via-points ahead by the course
    /// (false: the method conditions its own).
    const BEND: bool;
    /// The rest from the current tick (its first row is replaced by the posture read), given
    /// the course and `observed`, the posture just read (the last of its reading).
    fn replan(&self, course: &Course, observed: &[f64]) -> Result<Vec<Vec<f64>>, StepperError>;
    /// Move the goal of `course`; by default the course's rest re-bent onto it
    /// ([`Course::set_goal`]).
    fn set_goal(&self, course: &mut Course, goal: &[f64]) -> Result<(), StepperError> {
        course.set_goal(goal)
    }
}

/// A method in the loop: it follows its plan while the arm reads where it was sent (within the
/// [`Course`]'s tolerance) and re-plans by `R` when it does not.
#[derive(Debug, Clone)]
pub struct Follower<R> {
    method: R,
    course: Course,
}

impl<R: Replan> Follower<R> {
    /// `method` following the plan `plan` makes from `initial` through `conditions` (postures
    /// of `columns`; the initial posture and the conditions checked first, the conditions
    /// against `ranges` when given: per variable, its lowest and highest value, which also
    /// bound the rests bent later).
    pub fn start(
        method: R,
        columns: Vec<String>,
        initial: &[f64],
        conditions: &Conditions,
        ranges: Option<&[(f64, f64)]>,
        plan: impl FnOnce(&R) -> Result<Vec<Vec<f64>>, StepperError>,
    ) -> Result<Self, StepperError> {
        check_posture("the initial posture", initial, &columns)?;
        conditions.check(&columns, ranges, initial)?;
        let plan = plan(&method)?;
        let course = Course::new(columns, plan, conditions.clone(), ranges.map(<[_]>::to_vec))?;
        Ok(Follower { method, course })
    }

    /// The same stepper taking the arm to be where it was sent within `share` of its plan's
    /// bounding-box diagonal ([`Course::with_tolerance`]).
    pub fn with_tolerance(mut self, share: f64) -> Result<Self, StepperError> {
        self.course = self.course.with_tolerance(share)?;
        Ok(self)
    }

    /// The plan followed, the reading and the conditions.
    pub fn course(&self) -> &Course {
        &self.course
    }

    /// Replace the via-points from this tick on ([`Course::set_via`]): the rest re-bent onto
    /// those ahead, from the posture last commanded.
    pub fn set_via(&mut self, via: Vec<crate::condition::ViaPoint>) -> Result<(), StepperError> {
        self.course.set_via(via)
    }
}

impl<R: Replan> Stepper for Follower<R> {
    fn width(&self) -> usize {
        self.course.columns().len()
    }
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError> {
        let method = &self.method;
        (self.course).step_with(observed, R::BEND, |c| method.replan(c, observed))
    }
    fn done(&self) -> bool {
        self.course.done()
    }
    fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError> {
        self.method.set_goal(&mut self.course, goal)
    }
    fn phase(&self) -> f64 {
        self.course.phase()
    }
    fn closed_loop(&self) -> bool {
        true
    }
    fn replans(&self) -> usize {
        self.course.replans()
    }
}
