//! The DMP in the loop, closed on the observed posture with phase stopping (Ijspeert,
//! Nakanishi, Hoffmann, Pastor and Schaal 2013, section 2.1.4; docs/ALGORITHM.md, section
//! 11).

use crate::condition::Conditions;
use crate::stepper::{check_posture, plain_columns, Stepper, StepperError};

use super::Dmp;

/// The DMP's name in errors.
const DMP: &str = "the DMP";

/// How the DMP's loop is closed on the observed posture `ỹ` (its own state `y` is the posture
/// it commanded last): the canonical time advances by `1 / (1 + phase_stop e²)` of a sample
/// a tick, `e = |ỹ - y|` over the demonstrations' bounding-box diagonal (phase stopping), and
/// each tick the state is pulled by `coupling (ỹ - y)` towards what is read (the coupling
/// term). Where the arm is where it was sent, `e = 0`: the DMP runs as its open-loop
/// reproduction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DmpLoop {
    /// Share of the tracking error the state moves towards the observed posture per tick,
    /// 0 to 1.
    pub coupling: f64,
    /// Phase-stopping gain on the squared relative tracking error, finite, >= 0: at 1e4 an
    /// error of 1 % of the diagonal halves the phase's pace.
    pub phase_stop: f64,
}

impl Default for DmpLoop {
    fn default() -> Self {
        DmpLoop {
            coupling: 1.0,
            phase_stop: 1e4,
        }
    }
}

impl DmpLoop {
    /// The settings, or the first out of its range.
    pub fn check(self) -> Result<Self, StepperError> {
        if !(0.0..=1.0).contains(&self.coupling) {
            return Err(StepperError::Invalid {
                what: "the DMP's coupling",
                value: self.coupling.to_string(),
                allowed: "0 to 1",
            });
        }
        if !(self.phase_stop.is_finite() && self.phase_stop >= 0.0) {
            return Err(StepperError::Invalid {
                what: "the DMP's phase-stopping gain",
                value: self.phase_stop.to_string(),
                allowed: "a finite number >= 0",
            });
        }
        Ok(self)
    }
}

/// The DMP in the loop ([`DmpLoop`]): each tick one Runge-Kutta step of its transformation
/// system, from the posture it commanded last pulled towards the one read, with its phase
/// slowed by the tracking error. It is done once its canonical time has reached the
/// reproduction's duration. The goal moves the spring's anchor (the command does not jump);
/// it takes no via-point.
#[derive(Debug, Clone)]
pub struct DmpStepper {
    dmp: Dmp,
    columns: Vec<String>,
    ranges: Option<Vec<(f64, f64)>>,
    initial: Vec<f64>,
    goal: Vec<f64>,
    settings: DmpLoop,
    /// Position (the posture commanded last) and velocity per sample.
    y: Vec<f64>,
    v: Vec<f64>,
    /// Canonical time reached, samples.
    t: f64,
}

impl DmpStepper {
    /// The stepper of `dmp` from rest at `initial` to the goal of `conditions` (the
    /// demonstrations' mean end without one), checked against `ranges` when given; with the
    /// default [`DmpLoop`].
    pub fn new(
        dmp: &Dmp,
        initial: &[f64],
        conditions: &Conditions,
        ranges: Option<&[(f64, f64)]>,
    ) -> Result<Self, StepperError> {
        let columns = plain_columns(dmp.width());
        check_posture("the initial posture", initial, &columns)?;
        if !conditions.via.is_empty() {
            return Err(StepperError::Unsupported {
                method: DMP,
                reason: "takes no via-point: its only conditions are its start and its goal".into(),
            });
        }
        conditions.check(&columns, ranges, initial)?;
        let goal = conditions.goal.clone().unwrap_or_else(|| dmp.goal.clone());
        Ok(DmpStepper {
            dmp: dmp.clone(),
            ranges: ranges.map(<[_]>::to_vec),
            columns,
            initial: initial.to_vec(),
            goal,
            settings: DmpLoop::default(),
            y: initial.to_vec(),
            v: vec![0.0; initial.len()],
            t: 0.0,
        })
    }

    /// The same stepper closed on the observed posture with `settings` (checked).
    pub fn with_loop(mut self, settings: DmpLoop) -> Result<Self, StepperError> {
        self.settings = settings.check()?;
        Ok(self)
    }
}

impl Stepper for DmpStepper {
    fn width(&self) -> usize {
        self.columns.len()
    }
    fn step(&mut self, observed: &[f64]) -> Result<Vec<f64>, StepperError> {
        check_posture("the observed posture", observed, &self.columns)?;
        let scale = if self.dmp.extent > 0.0 {
            self.dmp.extent
        } else {
            1.0
        };
        let e2 = (observed.iter().zip(&self.y))
            .map(|(o, y)| ((o - y) / scale).powi(2))
            .sum::<f64>();
        let pace = 1.0 / (1.0 + self.settings.phase_stop * e2);
        let before = self.y.clone();
        let t0 = self.t;
        self.dmp.integrate(
            &mut self.y,
            &mut self.v,
            &self.goal,
            [t0, t0 + 0.5 * pace, t0 + pace],
        );
        for ((y, o), b) in self.y.iter_mut().zip(observed).zip(&before) {
            *y += self.settings.coupling * (o - b);
        }
        self.t = t0 + pace;
        Ok(self.y.clone())
    }
    fn done(&self) -> bool {
        self.t >= self.dmp.t_end()
    }
    fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError> {
        let conditions = Conditions {
            goal: Some(goal.to_vec()),
            via: Vec::new(),
        };
        conditions.check(&self.columns, self.ranges.as_deref(), &self.initial)?;
        self.goal = goal.to_vec();
        Ok(())
    }
    fn phase(&self) -> f64 {
        (self.t / self.dmp.t_end()).min(1.0)
    }
    fn closed_loop(&self) -> bool {
        true
    }
}
