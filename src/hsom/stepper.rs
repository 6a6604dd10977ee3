//! The hierarchy and the nearest-sequence baseline in the loop (docs/ALGORITHM.md, section
//! 11): each follows its plan while the arm is where it was sent, and re-plans from the
//! encoders' reading when it is not ([`Follower`]).

use std::borrow::Borrow;

use crate::condition::{meet, Conditions};
use crate::demos::Demonstration;
use crate::stepper::{Course, Follower, Replan, StepperError};

use super::model::Hsom;

/// The hierarchy's name in errors.
const HIERARCHY: &str = "the hierarchy";
/// The nearest sequence's.
const NEAREST: &str = "the nearest sequence";

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
pub type HsomStepper<M> = Follower<HsomReplan<M>>;

/// How the hierarchy re-plans in the loop ([`HsomStepper`]): the model and the initial posture.
#[derive(Debug, Clone)]
pub struct HsomReplan<M> {
    model: M,
    initial: Vec<f64>,
}

impl<M: Borrow<Hsom>> Replan for HsomReplan<M> {
    const BEND: bool = true;
    fn replan(&self, c: &Course, _observed: &[f64]) -> Result<Vec<Vec<f64>>, StepperError> {
        let model = self.model.borrow();
        if model.as_events().is_none() || !long_enough(model, c.reading()) {
            return Ok(c.realigned());
        }
        model
            .resume(&self.initial, c.reading())
            .map(|r| r.postures)
            .map_err(|e| StepperError::method(HIERARCHY, e))
    }
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
        let columns = model.borrow().columns().to_vec();
        let method = HsomReplan {
            model,
            initial: initial.to_vec(),
        };
        Follower::start(method, columns, initial, conditions, ranges, |h| {
            (h.model.borrow())
                .reproduce_conditioned(initial, conditions, ranges)
                .map(|r| r.postures)
                .map_err(|e| StepperError::method(HIERARCHY, e))
        })
    }
}

/// The nearest-sequence baseline in the loop: it follows [`Hsom::follow_nearest`] (met onto
/// the goal and via-points) while the arm reads where it was sent; when it does not, it
/// re-aligns with [`Hsom::follow_nearest_from`] on the whole reading (before the reading holds
/// `actionHorizon + 1` samples: [`Course::realigned`]), met onto the goal and the via-points
/// ahead.
pub type NearestStepper<M> = Follower<NearestReplan<M>>;

/// How the nearest sequence re-plans in the loop ([`NearestStepper`]): the model and the
/// demonstrations it chooses from.
#[derive(Debug, Clone)]
pub struct NearestReplan<M> {
    model: M,
    demos: Vec<Demonstration>,
}

impl<M: Borrow<Hsom>> Replan for NearestReplan<M> {
    const BEND: bool = true;
    fn replan(&self, c: &Course, _observed: &[f64]) -> Result<Vec<Vec<f64>>, StepperError> {
        let model = self.model.borrow();
        if !long_enough(model, c.reading()) {
            return Ok(c.realigned());
        }
        model
            .follow_nearest_from(&self.demos, c.reading())
            .map(|r| r.postures)
            .map_err(|e| StepperError::method(NEAREST, e))
    }
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
        let columns = model.borrow().columns().to_vec();
        let method = NearestReplan { model, demos };
        Follower::start(method, columns, initial, conditions, ranges, |n| {
            let plan = (n.model.borrow())
                .follow_nearest(&n.demos, initial)
                .map_err(|e| StepperError::method(NEAREST, e))?
                .postures;
            match conditions.is_empty() {
                true => Ok(plan),
                false => Ok(meet(&plan, &conditions.points(), ranges)?),
            }
        })
    }
}
