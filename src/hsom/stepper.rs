//! The hierarchy and the nearest-sequence baseline in the loop (docs/ALGORITHM.md, section
//! 11): each follows its plan while the arm is where it was sent, and re-plans from the
//! encoders' reading when it is not.

use std::borrow::Borrow;

use crate::condition::{meet, Conditions};
use crate::demos::Demonstration;
use crate::stepper::{check_posture, Course, Stepper, StepperError};

use super::model::Hsom;

/// The hierarchy's name in errors.
const HIERARCHY: &str = "the hierarchy";
/// The nearest sequence's.
const NEAREST: &str = "the nearest sequence";

/// The course of a plan from `initial` to `conditions` (checked first: width, finite values,
/// the ranges) made by `plan`.
fn course(
    model: &Hsom,
    initial: &[f64],
    conditions: &Conditions,
    ranges: Option<&[(f64, f64)]>,
    plan: impl FnOnce() -> Result<Vec<Vec<f64>>, StepperError>,
) -> Result<Course, StepperError> {
    check_posture("the initial posture", initial, model.columns())?;
    conditions.check(model.columns(), ranges, initial)?;
    Course::new(
        model.columns().to_vec(),
        plan()?,
        conditions.clone(),
        ranges.map(<[_]>::to_vec),
    )
}

/// Whether `model` can take `reading` as the context of a re-plan: at least `actionHorizon +
/// 1` samples (and 2), as a prefix must have.
fn long_enough(model: &Hsom, reading: &[Vec<f64>]) -> bool {
    reading.len() >= (model.config().params().action_horizon() + 1).max(2)
}

/// The hierarchy in the loop, of either algorithm. It follows its plan
/// ([`Hsom::reproduce_conditioned`]) while the arm reads where it was sent (within the
/// [`Course`]'s tolerance); when it does not, the rest is planned again from what the encoders
/// have read, and met onto the goal and the via-points still ahead:
///
/// - `algorithm = events`: [`Hsom::resume`] on the whole reading (the plan's own events
///   executed for the durations read, pushed up the lists; the levels plan the rest);
/// - `algorithm = paper`, whose lists cannot take a reading as context, and either algorithm
///   before the reading holds `actionHorizon + 1` samples: the plan re-joined where the reading
///   is along it ([`Course::realigned`]).
///
/// `M` is the model or anything that borrows it (`&Hsom`, `Arc<Hsom>`).
#[derive(Debug, Clone)]
pub struct HsomStepper<M: Borrow<Hsom>> {
    model: M,
    initial: Vec<f64>,
    course: Course,
}

impl<M: Borrow<Hsom>> HsomStepper<M> {
    /// The stepper of `model`'s reproduction from `initial` through `conditions` (a goal,
    /// via-points), each checked against `ranges` when given (per variable, its lowest and
    /// highest value; the rests are bent within them).
    pub fn new(
        model: M,
        initial: &[f64],
        conditions: &Conditions,
        ranges: Option<&[(f64, f64)]>,
    ) -> Result<Self, StepperError> {
        let m = model.borrow();
        let course = course(m, initial, conditions, ranges, || {
            m.reproduce_conditioned(initial, conditions, ranges)
                .map(|r| r.postures)
                .map_err(|e| StepperError::method(HIERARCHY, e))
        })?;
        Ok(HsomStepper {
            model,
            initial: initial.to_vec(),
            course,
        })
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
}

impl<M: Borrow<Hsom>> Stepper for HsomStepper<M> {
    fn width(&self) -> usize {
        self.course.columns().len()
    }
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError> {
        let (model, initial) = (self.model.borrow(), &self.initial);
        self.course.step_with(observed, true, |c| {
            if model.as_events().is_none() || !long_enough(model, c.reading()) {
                return Ok(c.realigned());
            }
            model
                .resume(initial, c.reading())
                .map(|r| r.postures)
                .map_err(|e| StepperError::method(HIERARCHY, e))
        })
    }
    fn done(&self) -> bool {
        self.course.done()
    }
    fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError> {
        self.course.set_goal(goal)
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

/// The nearest-sequence baseline in the loop: it follows [`Hsom::follow_nearest`] (met onto
/// the goal and via-points) while the arm reads where it was sent; when it does not, it
/// re-aligns with [`Hsom::follow_nearest_from`] on the whole reading (before the reading holds
/// `actionHorizon + 1` samples: [`Course::realigned`]), met onto the goal and the via-points
/// ahead.
#[derive(Debug, Clone)]
pub struct NearestStepper<M: Borrow<Hsom>> {
    model: M,
    demos: Vec<Demonstration>,
    course: Course,
}

impl<M: Borrow<Hsom>> NearestStepper<M> {
    /// The stepper of the nearest sequence of `demos` (normally `model`'s training
    /// demonstrations) from `initial` through `conditions`, checked against `ranges` as
    /// [`HsomStepper::new`] does.
    pub fn new(
        model: M,
        demos: Vec<Demonstration>,
        initial: &[f64],
        conditions: &Conditions,
        ranges: Option<&[(f64, f64)]>,
    ) -> Result<Self, StepperError> {
        let m = model.borrow();
        let course = course(m, initial, conditions, ranges, || {
            let plan = m
                .follow_nearest(&demos, initial)
                .map_err(|e| StepperError::method(NEAREST, e))?
                .postures;
            match conditions.is_empty() {
                true => Ok(plan),
                false => Ok(meet(&plan, &conditions.points(), ranges)?),
            }
        })?;
        Ok(NearestStepper {
            model,
            demos,
            course,
        })
    }
}

impl<M: Borrow<Hsom>> Stepper for NearestStepper<M> {
    fn width(&self) -> usize {
        self.course.columns().len()
    }
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError> {
        let (model, demos) = (self.model.borrow(), &self.demos);
        self.course.step_with(observed, true, |c| {
            if !long_enough(model, c.reading()) {
                return Ok(c.realigned());
            }
            model
                .follow_nearest_from(demos, c.reading())
                .map(|r| r.postures)
                .map_err(|e| StepperError::method(NEAREST, e))
        })
    }
    fn done(&self) -> bool {
        self.course.done()
    }
    fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError> {
        self.course.set_goal(goal)
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
