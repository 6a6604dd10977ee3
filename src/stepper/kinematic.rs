//! A kinematic loop: any [`Stepper`] run on an arm that goes exactly where it is commanded,
//! except while a [`Disturbance`] has it (held, or moved and held). It is what held-out
//! studies of the loop call: the executed path, which ticks were disturbed, whether the
//! reproduction finished.
//!
//! ```
//! use cosco_hsom::stepper::kinematic::{run, Disturbance};
//! use cosco_hsom::stepper::ByClock;
//! let plan: Vec<Vec<f64>> = (0..11).map(|i| vec![i as f64 / 10.0]).collect();
//! let mut s = ByClock::new(vec!["q".into()], plan.clone(), "the replay");
//! let held = Disturbance::Hold { at: 0.4, share: 0.3 };
//! let r = run(&mut s, &plan[0], &held, 10, 100).unwrap();
//! assert!(r.finished);
//! assert_eq!(r.path[5], r.path[4]); // held from tick 4 to tick 6
//! assert_eq!(r.release, Some(7));
//! // by its clock the replay jumps on release to where its clock has got to
//! assert!((r.largest_step_from(7) - 0.4).abs() < 1e-12);
//! ```

use crate::dtw::euclidean;

use super::{Stepper, StepperError};

/// What a stepper runs on: an arm that reads the posture it is in and goes (or is kept from
/// going) where it is commanded. [`KinematicLoop`] is the loop of [`run`]; the simulated arm is
/// [`crate::sim::in_loop::ArmLoop`].
pub trait Plant: Sync {
    /// `stepper` (made from `initial`) run until it is done and the arm is free, or for
    /// `limit` ticks, under `disturbance`, whose phases are shares of `duration` ticks.
    fn run(
        &self,
        stepper: &mut dyn Stepper,
        initial: &[f64],
        disturbance: &Disturbance,
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
        disturbance: &Disturbance,
        duration: usize,
        limit: usize,
    ) -> Result<Trace, StepperError> {
        run(stepper, initial, disturbance, duration, limit)
    }
}

/// What happens to the arm, at a phase of the reproduction's duration (the `duration` given
/// to [`run`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Disturbance {
    /// The arm goes wherever it is commanded.
    None,
    /// From phase `at`, for `share` of the duration, the arm stays where it is whatever is
    /// commanded.
    Hold {
        /// When, 0 to 1.
        at: f64,
        /// For how long, a share of the duration (>= 0).
        share: f64,
    },
    /// At phase `at` the arm is displaced by `by` (one value per variable) and held there for
    /// `share` of the duration (at least the tick it is moved).
    Move {
        /// When, 0 to 1.
        at: f64,
        /// The displacement.
        by: Vec<f64>,
        /// For how long it is held there, a share of the duration (>= 0).
        share: f64,
    },
    /// From phase `at`, for `share` of the duration, a force `force` (N, the robot's torso
    /// frame) pushes the link `body`: only a simulated arm can be pushed
    /// ([`crate::sim::in_loop::ArmLoop`]); the kinematic loop refuses it.
    Push {
        /// When, 0 to 1.
        at: f64,
        /// The link (the model's body name).
        body: String,
        /// The force, N.
        force: [f64; 3],
        /// For how long, a share of the duration (>= 0).
        share: f64,
    },
    /// At phase `at` the stepper's goal is moved to `goal` ([`Stepper::set_goal`]); the arm
    /// goes wherever it is commanded.
    Goal {
        /// When, 0 to 1.
        at: f64,
        /// The new goal.
        goal: Vec<f64>,
    },
}

/// A stepper's run in a loop ([`run`], or any [`Plant`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// The arm's posture at each tick (what the stepper read), the first the initial posture.
    pub path: Vec<Vec<f64>>,
    /// What the stepper commanded at each tick (`commanded[k]` given `path[k]`; on the
    /// simulated arm the last row repeats the last command).
    pub commanded: Vec<Vec<f64>>,
    /// Per row of `path`: whether the disturbance had the arm (held or moved) at that tick.
    pub held: Vec<bool>,
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

    /// How far the disturbance took the arm from where `plain` (the same stepper's undisturbed
    /// run) had it at the same ticks: the largest distance over the disturbed ticks and the
    /// variables (0 without a hold, move or push).
    pub fn displaced_from(&self, plain: &[Vec<f64>]) -> f64 {
        (self.path.iter().zip(plain).zip(&self.held))
            .filter(|(_, h)| **h)
            .flat_map(|((a, b), _)| a.iter().zip(b).map(|(x, y)| (x - y).abs()))
            .fold(0.0, f64::max)
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

/// `stepper` (made from `initial`) run until it is done: each tick it is given the arm's
/// posture and the arm goes where it commands, except at the ticks `disturbance` holds or
/// moves it. `duration` (ticks, at least 1) is what the disturbance's phases are shares of
/// (normally the undisturbed reproduction's or the demonstration's); the tick `k` is at phase
/// `k / duration`, and a disturbance from phase `at` for `share` has the arm at the ticks
/// `round(at duration)` to `round(at duration) + round(share duration) - 1`. The run ends
/// when the stepper is done and the arm is free, or after `limit` ticks (`finished` false).
pub fn run(
    stepper: &mut dyn Stepper,
    initial: &[f64],
    disturbance: &Disturbance,
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
    // the ticks the arm is held: [from, to)
    let (from, to, by) = match disturbance {
        Disturbance::None | Disturbance::Goal { .. } => (usize::MAX, usize::MAX, None),
        Disturbance::Push { .. } => {
            return Err(StepperError::Unsupported {
                method: "the kinematic loop",
                reason: "cannot push a link: a push needs the simulated arm".into(),
            })
        }
        Disturbance::Hold { at, share } => {
            check_phase(*at)?;
            check_share(*share)?;
            (tick(*at).max(1), tick(*at).max(1) + tick(*share), None)
        }
        Disturbance::Move { at, by, share } => {
            check_phase(*at)?;
            check_share(*share)?;
            if by.len() != initial.len() || by.iter().any(|v| !v.is_finite()) {
                return Err(StepperError::Invalid {
                    what: "the displacement",
                    value: format!("{by:?}"),
                    allowed: "one finite value per variable",
                });
            }
            let from = tick(*at).max(1);
            (from, from + tick(*share).max(1), Some(by))
        }
    };
    let goal = match disturbance {
        Disturbance::Goal { at, goal } => {
            check_phase(*at)?;
            Some((tick(*at), goal))
        }
        _ => None,
    };
    let mut out = Trace {
        path: vec![initial.to_vec()],
        commanded: Vec::new(),
        held: vec![false],
        release: (to > from && to != usize::MAX).then_some(to),
        finished: false,
    };
    let mut arm = initial.to_vec();
    for k in 0..limit {
        if let Some((_, g)) = goal.filter(|(at, _)| *at == k) {
            stepper.set_goal(g)?;
        }
        let command = stepper.step(&arm)?;
        let next = k + 1;
        let held = (from..to).contains(&next);
        arm = match (held, by) {
            (true, Some(by)) if next == from => arm.iter().zip(by).map(|(a, b)| a + b).collect(),
            (true, _) => arm,
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
