//! Steppers: a reproduction in the loop (docs/ALGORITHM.md, section 11). Given the posture
//! the encoders read at a tick, a [`Stepper`] gives the next posture to command; it says when the
//! reproduction has ended, and its goal can be moved while it runs.
//!
//! This room holds the trait and its error, the plan a stepper follows tick by tick
//! ([`Course`]: where the arm should be, the encoders' reading, re-joining and re-bending), the
//! closed-loop stepper that follows it ([`Follower`], the method saying how it re-plans), the
//! open-loop stepper of a fixed plan ([`ByClock`]) and the kinematic loop that runs any stepper
//! against a disturbance ([`kinematic`]). Each method's stepper lives beside its method:
//! [`crate::hsom::HsomStepper`] (both algorithms), [`crate::hsom::NearestStepper`],
//! [`crate::dmp::DmpStepper`], [`crate::promp::PrompStepper`] and [`crate::gmr::stepper`]
//! (GMM/GMR by its clock, open loop). It imports only the rooms below the methods
//! (conditions, curves, DTW), so that the methods, the evaluation, the simulator, the app
//! and the Python package can all import it.
//!
//! ```
//! use cosco_hsom::stepper::{ByClock, Stepper};
//! let plan = vec![vec![0.0], vec![0.5], vec![1.0]];
//! let mut s = ByClock::new(vec!["q".into()], plan, "the replay");
//! assert_eq!(s.step(&[0.0]).unwrap(), vec![0.5]);
//! assert!(!s.done());
//! assert_eq!(s.step(&[0.2]).unwrap(), vec![1.0]); // by its clock: the reading is not used
//! assert!(s.done());
//! ```

mod course;
mod disturbance;
mod follower;
pub mod kinematic;
#[cfg(test)]
mod tests;

pub use course::{Course, DEFAULT_TOLERANCE};
pub use disturbance::{Amount, Clock, Disturbance, Kind};
pub use follower::{Follower, Replan};
pub use kinematic::{KinematicLoop, Plant, Trace};

use crate::condition::{self, ConditionError};

/// A reproduction in the loop: each tick, given the posture the encoders read, the next
/// posture to command. The first call reads the arm at the initial posture the stepper was
/// made with; the last posture of the reproduction is commanded once [`Stepper::done`] turns
/// true. Calling [`Stepper::step`] after that commands the last posture again (a closed-loop
/// stepper whose arm is not there re-plans, and is no longer done).
pub trait Stepper {
    /// Values per posture.
    fn width(&self) -> usize;
    /// The next posture to command, given the posture the encoders read at this tick (`observed`,
    /// one finite value per variable).
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError>;
    /// Whether the reproduction has ended: its last posture has been commanded.
    fn done(&self) -> bool;
    /// Move the goal (the last posture) from this tick on: the rest of the reproduction is made
    /// again from the posture last commanded, so the command does not jump.
    fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError>;
    /// How far along the reproduction is, 0 (the start) to 1 (the end), as the stepper
    /// reckons it (its plan's ticks, its clock or its canonical phase).
    fn phase(&self) -> f64;
    /// Whether the observed posture changes what is commanded (false: open loop, by a clock).
    fn closed_loop(&self) -> bool;
    /// How many times the stepper has re-planned because the arm was not where it was sent.
    fn replans(&self) -> usize {
        0
    }
}

/// Why a stepper could not be made or could not step; each names the value and what is
/// allowed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StepperError {
    /// A posture of the wrong width.
    #[error("{what} has {found} values; the stepper's postures have {expected} ({columns})")]
    Width {
        /// `the observed posture`, `the initial posture`, `the goal`, ...
        what: String,
        /// Values given.
        found: usize,
        /// Values per posture.
        expected: usize,
        /// The variables' names, comma-separated.
        columns: String,
    },
    /// A goal or via-point refused (width, finite values, phase, the variables' ranges), one
    /// the reproduction could not be bent onto, or a posture's value that is not a finite
    /// number.
    #[error(transparent)]
    Condition(#[from] ConditionError),
    /// What the method cannot do (GMM/GMR takes no goal; the DMP no via-point).
    #[error("{method} {reason}")]
    Unsupported {
        /// The method.
        method: &'static str,
        /// What it cannot do and why.
        reason: String,
    },
    /// A setting or a disturbance out of its range.
    #[error("{what} is {value}; allowed {allowed}")]
    Invalid {
        /// The setting.
        what: &'static str,
        /// The rejected value, as text.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The method refused to plan or re-plan.
    #[error("{method}: {source}")]
    Method {
        /// The method.
        method: &'static str,
        /// Its error.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
    /// The plant (the simulated arm) refused the run or failed.
    #[error(transparent)]
    Plant(Box<dyn std::error::Error + Send + Sync>),
}

impl StepperError {
    /// `source` wrapped as the error of `method`.
    pub fn method(
        method: &'static str,
        source: impl std::error::Error + Send + Sync + 'static,
    ) -> StepperError {
        StepperError::Method {
            method,
            source: Box::new(source),
        }
    }
}

/// `posture` (named `what` in errors) is one finite value per variable of `columns`
/// ([`crate::condition::check_posture`]; a wrong width is the stepper's
/// [`StepperError::Width`], a value not finite the condition's error).
pub fn check_posture(what: &str, posture: &[f64], columns: &[String]) -> Result<(), StepperError> {
    condition::check_posture(what, posture, columns, None).map_err(|e| match e {
        ConditionError::Width { found, .. } => StepperError::Width {
            what: what.into(),
            found,
            expected: columns.len(),
            columns: columns.join(", "),
        },
        e => StepperError::Condition(e),
    })
}

/// `x0`, `x1`, ...: the names of `n` variables that have none.
pub fn plain_columns(n: usize) -> Vec<String> {
    (0..n).map(|i| format!("x{i}")).collect()
}

/// A fixed plan commanded by its clock, whatever the encoders read: open loop. GMM/GMR steps
/// so ([`crate::gmr::stepper`]: a regression on time has no state to close a loop on), and a
/// plan replayed this way is the negative control of the closed loops (after a hold it jumps
/// to wherever its clock has got to).
#[derive(Debug, Clone)]
pub struct ByClock {
    columns: Vec<String>,
    rows: Vec<Vec<f64>>,
    at: usize,
    method: &'static str,
    /// Why its goal cannot be moved.
    fixed: &'static str,
}

impl ByClock {
    /// `rows` (the first the initial posture, at least one) commanded one a tick by `method`
    /// (its name in errors).
    pub fn new(columns: Vec<String>, rows: Vec<Vec<f64>>, method: &'static str) -> ByClock {
        ByClock {
            columns,
            rows,
            at: 0,
            method,
            fixed: "commands a fixed plan by its clock: its goal cannot be moved",
        }
    }

    /// The same stepper refusing a goal with `reason` (after the method's name).
    pub fn refusing_goal(mut self, reason: &'static str) -> ByClock {
        self.fixed = reason;
        self
    }
}

impl Stepper for ByClock {
    fn width(&self) -> usize {
        self.columns.len()
    }
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError> {
        check_posture("the observed posture", observed, &self.columns)?;
        self.at = (self.at + 1).min(self.rows.len().saturating_sub(1));
        Ok(self.rows.get(self.at).cloned().unwrap_or_default())
    }
    fn done(&self) -> bool {
        self.at + 1 >= self.rows.len()
    }
    fn set_goal(&mut self, _goal: &[f64]) -> Result<(), StepperError> {
        Err(StepperError::Unsupported {
            method: self.method,
            reason: self.fixed.into(),
        })
    }
    fn phase(&self) -> f64 {
        self.at as f64 / (self.rows.len().max(2) - 1) as f64
    }
    fn closed_loop(&self) -> bool {
        false
    }
}
