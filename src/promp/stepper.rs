//! ProMP in the loop: by its clock, re-conditioned on the observed posture at its phase
//! (docs/ALGORITHM.md, section 11).

use crate::condition::Conditions;
use crate::stepper::{plain_columns, Course, Follower, Replan, StepperError};

use super::Promp;

/// ProMP's name in errors.
const PROMP: &str = "ProMP";

/// ProMP in the loop. Its phase is its clock (tick `t` at phase `t / (samples - 1)`). It
/// follows the mean conditioned on the initial posture, the via-points and the goal while the
/// arm reads where it was sent; when it does not, the weight distribution is conditioned
/// again on the posture read at the current phase, the via-points still ahead and the goal
/// (the earlier ones are past), and its mean from there on is followed. A moved goal conditions
/// it again on the posture last commanded at the current phase.
pub type PrompStepper = Follower<PrompReplan>;

/// How ProMP re-plans in the loop ([`PrompStepper`]): conditioned again.
#[derive(Debug, Clone)]
pub struct PrompReplan(Promp);

impl PrompStepper {
    /// The stepper of `promp` from `initial` through `conditions` (a goal, via-points),
    /// checked against `ranges` when given.
    pub fn new(
        promp: &Promp,
        initial: &[f64],
        conditions: &Conditions,
        ranges: Option<&[(f64, f64)]>,
    ) -> Result<Self, StepperError> {
        let columns = plain_columns(promp.width());
        let method = PrompReplan(promp.clone());
        Follower::start(method, columns, initial, conditions, ranges, |_| {
            let (plan, _) = promp
                .conditioned(initial, &conditions.points())
                .map_err(|e| StepperError::method(PROMP, e))?;
            Ok(plan)
        })
    }
}

/// The mean of `promp` conditioned on `posture` at the phase of `course`, the via-points of
/// `conditions` ahead and their goal, from the current tick to the end.
fn reconditioned(
    promp: &Promp,
    course: &Course,
    posture: &[f64],
    conditions: &Conditions,
) -> Result<Vec<Vec<f64>>, StepperError> {
    let phase = course.phase();
    let last = (promp.samples().max(2) - 1) as f64;
    let tick = (phase * last).round() as usize;
    let points: Vec<(f64, &[f64])> = std::iter::once((phase, posture))
        .chain(
            (conditions.via.iter())
                .filter(|v| v.phase > phase && v.phase < 1.0)
                .map(|v| (v.phase, v.posture.as_slice())),
        )
        .chain(conditions.goal.iter().map(|g| (1.0, g.as_slice())))
        .collect();
    let mut rest = promp
        .conditioned_from(&points, tick)
        .map_err(|e| StepperError::method(PROMP, e))?;
    if let Some(first) = rest.first_mut() {
        *first = posture.to_vec();
    }
    Ok(rest)
}

impl Replan for PrompReplan {
    const BEND: bool = false;
    fn replan(&self, c: &Course, observed: &[f64]) -> Result<Vec<Vec<f64>>, StepperError> {
        reconditioned(&self.0, c, observed, c.conditions())
    }
    fn set_goal(&self, course: &mut Course, goal: &[f64]) -> Result<(), StepperError> {
        let conditions = course.with_goal(goal)?;
        let commanded = course.commanded().to_vec();
        let rest = reconditioned(&self.0, course, &commanded, &conditions)?;
        course.restart_with(rest, conditions);
        Ok(())
    }
}
