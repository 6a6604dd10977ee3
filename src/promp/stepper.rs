//! ProMP in the loop: by its clock, re-conditioned on the observed posture at its phase
//! (docs/ALGORITHM.md, section 11).

use crate::condition::Conditions;
use crate::stepper::{check_posture, plain_columns, Course, Stepper, StepperError};

use super::Promp;

/// ProMP's name in errors.
const PROMP: &str = "ProMP";

/// ProMP in the loop. Its phase is its clock (tick `t` at phase `t / (samples - 1)`). It
/// follows the mean conditioned on the initial posture, the via-points and the goal while the
/// arm reads where it was sent; when it does not, the weight distribution is conditioned
/// again on the posture read at the current phase, the via-points still ahead and the goal
/// (the earlier ones are past), and its mean from there on is followed. A moved goal conditions
/// it again on the posture last commanded at the current phase.
#[derive(Debug, Clone)]
pub struct PrompStepper {
    promp: Promp,
    course: Course,
}

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
        check_posture("the initial posture", initial, &columns)?;
        conditions.check(&columns, ranges, initial)?;
        let (plan, _) = promp
            .conditioned(initial, &conditions.points())
            .map_err(|e| StepperError::method(PROMP, e))?;
        let course = Course::new(columns, plan, conditions.clone(), ranges.map(<[_]>::to_vec))?;
        Ok(PrompStepper {
            promp: promp.clone(),
            course,
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

impl Stepper for PrompStepper {
    fn width(&self) -> usize {
        self.promp.width()
    }
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError> {
        let promp = &self.promp;
        self.course.step_with(observed, false, |c| {
            reconditioned(promp, c, observed, c.conditions())
        })
    }
    fn done(&self) -> bool {
        self.course.done()
    }
    fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError> {
        let conditions = self.course.with_goal(goal)?;
        let commanded = self.course.commanded().to_vec();
        let rest = reconditioned(&self.promp, &self.course, &commanded, &conditions)?;
        self.course.restart_with(rest, conditions);
        Ok(())
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
