//! A kinematic loop: any [`Stepper`] run on an arm that goes exactly where it is commanded,
//! except while a [`Disturbance`] has it (held, or moved and held) or its goal moves. It is what held-out
//! studies of the loop call: the executed path, which ticks were disturbed, whether the
//! reproduction finished.
//!
//! ```
//! use cosco_hsom::stepper::kinematic::run;
//! use cosco_hsom::stepper::{ByClock, Disturbance};
//! let plan: Vec<Vec<f64>> = (0..11).map(|i| vec![i as f64 / 10.0]).collect();
//! let mut s = ByClock::new(vec!["q".into()], plan.clone(), "the replay");
//! let held = [Disturbance::hold(0.4, 0.3)];
//! let r = run(&mut s, &plan[0], &held, 10, 100).unwrap();
//! assert!(r.finished);
//! assert_eq!(r.path[5], r.path[4]); // held from tick 4 to tick 6
//! assert_eq!(r.release, Some(7));
//! // by its clock the replay jumps on release to where its clock has got to
//! assert!((r.largest_step_from(7) - 0.4).abs() < 1e-12);
//! ```

use crate::dtw::euclidean;

use super::disturbance::{Amount, Clock, Disturbance, Kind};
use super::{Stepper, StepperError};

/// What a stepper runs on: an arm that reads the posture it is in and goes (or is kept from
/// going) where it is commanded. [`KinematicLoop`] is the loop of [`run`]; the simulated arm is
/// [`crate::sim::in_loop::ArmLoop`].
pub trait Plant: Sync {
    /// `stepper` (made from `initial`) run until it is done and the arm is free, or for
    /// `limit` ticks, under `disturbances` (their amounts absolute), whose phases are shares of
    /// `duration` ticks.
    fn run(
        &self,
        stepper: &mut dyn Stepper,
        initial: &[f64],
        disturbances: &[Disturbance],
        duration: usize,
        limit: usize,
    ) -> Result<Trace, StepperError>;
}

/// The kinematic loop ([`run`]) as a [`Plant`].
#[derive(Debug, Clone, Copy, Default)]
pub struct KinematicLoop;

impl Plant for KinematicLoop {
    fn run(
        &self,
        stepper: &mut dyn Stepper,
        initial: &[f64],
        disturbances: &[Disturbance],
        duration: usize,
        limit: usize,
    ) -> Result<Trace, StepperError> {
        run(stepper, initial, disturbances, duration, limit)
    }
}

/// A stepper's run in a loop ([`run`], or any [`Plant`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// The arm's posture at each tick (what the stepper read), the first the initial posture.
    pub path: Vec<Vec<f64>>,
    /// What the stepper commanded at each tick (`commanded[k]` given `path[k]`; on the
    /// simulated arm the last row repeats the last command).
    pub commanded: Vec<Vec<f64>>,
    /// Per row of `path`: whether a disturbance had the arm (held, moved or pushed) at that tick.
    pub held: Vec<bool>,
    /// Per disturbance, per row of `path`: whether it had the arm.
    pub acting: Vec<Vec<bool>>,
    /// The first row of `path` after a hold or a move (`None` without one).
    pub release: Option<usize>,
    /// Whether the stepper said it was done before the tick limit.
    pub finished: bool,
}

impl Trace {
    /// The largest step of the path (Euclidean) into row `from` or any row after it: with
    /// `from` the release, the step the arm makes when let go and every one after.
    pub fn largest_step_from(&self, from: usize) -> f64 {
        largest_step(&self.path, from)
    }

    /// The path without its disturbed ticks ([`free_rows`]).
    pub fn free(&self) -> Vec<Vec<f64>> {
        free_rows(&self.path, &self.held)
    }

    /// Per disturbance, how far it took the arm from where `plain` (the same stepper's
    /// undisturbed run) had it at the same ticks: the largest distance over the ticks it had
    /// the arm and the variables (0 for a goal's move).
    pub fn displaced(&self, plain: &[Vec<f64>]) -> Vec<f64> {
        (self.acting.iter())
            .map(|acting| {
                (self.path.iter().zip(plain).zip(acting))
                    .filter(|(_, h)| **h)
                    .flat_map(|((a, b), _)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
                    .fold(0.0, f64::max)
            })
            .collect()
    }
}

/// The largest step (Euclidean) between consecutive rows of `rows`, into row `from` or any
/// row after it (`from` 1: every step).
pub fn largest_step(rows: &[Vec<f64>], from: usize) -> f64 {
    (from.max(1)..rows.len())
        .map(|k| euclidean(&rows[k], &rows[k - 1]))
        .fold(0.0, f64::max)
}

/// The rows of `path` at the ticks `held` does not mark: a path without its disturbed ticks.
pub fn free_rows(path: &[Vec<f64>], held: &[bool]) -> Vec<Vec<f64>> {
    (path.iter().zip(held))
        .filter(|(_, h)| !**h)
        .map(|(p, _)| p.clone())
        .collect()
}

/// A phase 0 to 1.
fn check_phase(at: f64) -> Result<(), StepperError> {
    if (0.0..=1.0).contains(&at) {
        return Ok(());
    }
    Err(StepperError::Invalid {
        what: "the disturbance's phase",
        value: at.to_string(),
        allowed: "0 to 1",
    })
}

/// A share of the duration, finite and >= 0.
fn check_share(share: f64) -> Result<(), StepperError> {
    if share.is_finite() && share >= 0.0 {
        return Ok(());
    }
    Err(StepperError::Invalid {
        what: "the disturbance's share of the duration",
        value: share.to_string(),
        allowed: "a finite number >= 0",
    })
}

/// The ticks a disturbance has the arm, `[from, to)`, and a move's displacement (a goal's
/// move: none).
type Span<'d> = Option<(usize, usize, Option<&'d Vec<f64>>)>;

/// `stepper` (made from `initial`) run until it is done: each tick it is given the arm's
/// posture and the arm goes where it commands, except at the ticks a disturbance of
/// `disturbances` (on the phase clock, amounts absolute) holds or moves it. `duration`
/// (ticks, at least 1) is what the disturbances' phases are shares of (normally the
/// undisturbed reproduction's or the demonstration's); the tick `k` is at phase
/// `k / duration`, and a disturbance from phase `at` for `share` has the arm at the ticks
/// `round(at duration)` to `round(at duration) + round(share duration) - 1`. The run ends
/// when the stepper is done and the arm is free, or after `limit` ticks (`finished` false).
pub fn run(
    stepper: &mut dyn Stepper,
    initial: &[f64],
    disturbances: &[Disturbance],
    duration: usize,
    limit: usize,
) -> Result<Trace, StepperError> {
    if duration == 0 {
        return Err(StepperError::Invalid {
            what: "the duration",
            value: "0".into(),
            allowed: "at least 1 tick",
        });
    }
    let tick = |phase: f64| (phase * duration as f64).round() as usize;
    // per disturbance, the ticks it has the arm, [from, to), and a move's displacement
    let mut spans: Vec<Span> = Vec::new();
    let mut goals = Vec::new();
    for d in disturbances {
        if d.clock != Clock::Phase {
            return Err(StepperError::Invalid {
                what: "the disturbance's clock",
                value: d.describe(),
                allowed: "phases of the duration (the kinematic loop counts no seconds)",
            });
        }
        check_phase(d.at)?;
        let from = tick(d.at).max(1);
        spans.push(match &d.kind {
            Kind::Push { .. } => {
                return Err(StepperError::Unsupported {
                    method: "the kinematic loop",
                    reason: "cannot push a link: a push needs the simulated arm".into(),
                })
            }
            Kind::Hold => {
                check_share(d.lasts)?;
                Some((from, from + tick(d.lasts), None))
            }
            Kind::Move(Amount::Absolute(by)) => {
                check_share(d.lasts)?;
                if by.len() != initial.len() || by.iter().any(|v| !v.is_finite()) {
                    return Err(StepperError::Invalid {
                        what: "the displacement",
                        value: format!("{by:?}"),
                        allowed: "one finite value per variable",
                    });
                }
                Some((from, from + tick(d.lasts).max(1), Some(by)))
            }
            Kind::Goal(Amount::Absolute(goal)) => {
                goals.push((tick(d.at), goal));
                None
            }
            Kind::Move(_) | Kind::Goal(_) => {
                return Err(StepperError::Invalid {
                    what: "the disturbance's amount",
                    value: d.describe(),
                    allowed: "one value per variable (a study makes k x the diagonal absolute)",
                })
            }
        });
    }
    let spans_ticks = spans.iter().flatten();
    let mut out = Trace {
        path: vec![initial.to_vec()],
        commanded: Vec::new(),
        held: vec![false],
        acting: vec![vec![false]; spans.len()],
        release: spans_ticks
            .filter(|(from, to, _)| to > from)
            .map(|s| s.1)
            .max(),
        finished: false,
    };
    let mut arm = initial.to_vec();
    for k in 0..limit {
        for (_, g) in goals.iter().filter(|(at, _)| *at == k) {
            stepper.set_goal(g)?;
        }
        let command = stepper.step(&arm)?;
        let next = k + 1;
        let mut held = false;
        let mut by = None;
        for (span, acting) in spans.iter().zip(&mut out.acting) {
            let on = span.is_some_and(|(from, to, _)| (from..to).contains(&next));
            acting.push(on);
            held |= on;
            if let Some((_, _, Some(b))) = span.filter(|(from, _, _)| *from == next) {
                by = Some(b);
            }
        }
        arm = match (held, by) {
            (true, Some(by)) => arm.iter().zip(by).map(|(a, b)| a + b).collect(),
            (true, None) => arm,
            (false, _) => command.clone(),
        };
        out.commanded.push(command);
        out.path.push(arm.clone());
        out.held.push(held);
        if stepper.done() && !held {
            out.finished = true;
            break;
        }
    }
    Ok(out)
}
