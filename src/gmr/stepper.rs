//! GMM/GMR in the loop: by its clock, open loop (docs/ALGORITHM.md, section 11).

use crate::condition::Conditions;
use crate::stepper::{check_posture, ByClock, StepperError};

use super::{plan_at, GmrModel};

/// Why GMM/GMR takes no goal and no via-point, after its name.
pub const UNCONDITIONED: &str = "cannot be conditioned on a goal or a via-point: its \
    regression gives each instant a mean and a covariance, but no covariance across instants \
    through which a condition at one instant could move the others";

/// GMM/GMR in the loop: its plan ([`plan_at`]: the minimum-jerk lead-in from `initial` at
/// `peak_speed`, then the regression's mean every `1 / rate_hz` seconds) commanded by its
/// clock. It is open loop: a regression of the posture on time has no state to close a loop
/// on, so what the encoders read changes nothing (after a hold it goes on from wherever its
/// clock has got to). `conditions` must be empty, and its goal cannot be moved
/// ([`UNCONDITIONED`]).
pub fn stepper(
    model: &GmrModel,
    initial: &[f64],
    rate_hz: f64,
    peak_speed: f64,
    conditions: &Conditions,
) -> Result<ByClock, StepperError> {
    const GMR: &str = "GMM/GMR";
    check_posture("the initial posture", initial, model.columns())?;
    if !conditions.is_empty() {
        return Err(StepperError::Unsupported {
            method: GMR,
            reason: UNCONDITIONED.into(),
        });
    }
    let plan =
        plan_at(model, initial, rate_hz, peak_speed).map_err(|e| StepperError::method(GMR, e))?;
    Ok(ByClock::new(model.columns().to_vec(), plan.postures, GMR).refusing_goal(UNCONDITIONED))
}
