//! The plan a closed-loop stepper follows tick by tick: where the arm should be, what the
//! encoders have read, and the plan's rest made again when the arm is elsewhere (re-joined)
//! or the goal moves (re-bent).

use crate::condition::{meet, Conditions};
use crate::curve::{minimum_jerk, minimum_jerk_at, MINIMUM_JERK_PEAK};
use crate::dtw::{euclidean, open_end_cost};

use super::{check_posture, StepperError};

/// How near the posture last commanded the arm must read to be where it was sent: this share
/// of the plan's bounding-box diagonal (Euclidean distance). Within it the stepper follows its
/// plan; beyond it, it re-plans from the reading.
pub const DEFAULT_TOLERANCE: f64 = 2e-3;

/// A plan followed tick by tick ([`Course::observe`], then [`Course::advance`]): the rows of
/// the plan being followed and the row last commanded, the reading (every posture observed,
/// from the initial one), the goal and via-points, and how the plan's rest is made again.
///
/// Phase: the plan first made spans phases 0 to 1; a rest that replaces it at phase `p`
/// spans `p` to 1. A via-point still ahead at phase `v` is at phase `(v - p) / (1 - p)` of
/// such a rest; one less than a tick ahead is taken as passed.
#[derive(Debug, Clone)]
pub struct Course {
    columns: Vec<String>,
    /// The plan first made, from the initial posture: what a reading is aligned with to
    /// re-join it ([`Course::realigned`]).
    reference: Vec<Vec<f64>>,
    /// The plan being followed; `rows[at]` was commanded last.
    rows: Vec<Vec<f64>>,
    at: usize,
    /// The phase at `rows[0]`.
    phase0: f64,
    conditions: Conditions,
    ranges: Option<Vec<(f64, f64)>>,
    /// Euclidean distance, the data's units.
    tolerance: f64,
    /// The reference's largest step (Euclidean, per tick): how fast a re-join may fade.
    largest_step: f64,
    reading: Vec<Vec<f64>>,
    replans: usize,
}

/// The diagonal of the bounding box of `rows`.
fn diagonal(rows: &[Vec<f64>]) -> f64 {
    let w = rows.first().map_or(0, Vec::len);
    (0..w)
        .map(|d| {
            let (lo, hi) = rows
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), r| {
                    (l.min(r[d]), h.max(r[d]))
                });
            (hi - lo).powi(2)
        })
        .sum::<f64>()
        .sqrt()
}

impl Course {
    /// Follow `plan` (postures of `columns`, the first the initial posture; already met onto
    /// `conditions` where there are any); `ranges` (per variable, its lowest and highest
    /// value) bound a goal set later and the re-bent rests. The tolerance is
    /// [`DEFAULT_TOLERANCE`].
    pub fn new(
        columns: Vec<String>,
        plan: Vec<Vec<f64>>,
        conditions: Conditions,
        ranges: Option<Vec<(f64, f64)>>,
    ) -> Result<Course, StepperError> {
        if plan.is_empty() {
            return Err(StepperError::Invalid {
                what: "the plan",
                value: "0 postures".into(),
                allowed: "at least one (the initial posture)",
            });
        }
        for (i, r) in plan.iter().enumerate() {
            check_posture(&format!("posture {i} of the plan"), r, &columns)?;
        }
        let largest_step = plan
            .windows(2)
            .map(|w| euclidean(&w[0], &w[1]))
            .fold(0.0, f64::max);
        Ok(Course {
            tolerance: DEFAULT_TOLERANCE * diagonal(&plan),
            columns,
            reference: plan.clone(),
            rows: plan,
            at: 0,
            phase0: 0.0,
            conditions,
            ranges,
            largest_step,
            reading: Vec::new(),
            replans: 0,
        })
    }

    /// The same course with the arm taken to be where it was sent within `share` of the
    /// plan's bounding-box diagonal (a finite number >= 0).
    pub fn with_tolerance(mut self, share: f64) -> Result<Course, StepperError> {
        if !(share.is_finite() && share >= 0.0) {
            return Err(StepperError::Invalid {
                what: "the tolerance",
                value: share.to_string(),
                allowed: "a finite share of the plan's diagonal >= 0",
            });
        }
        self.tolerance = share * diagonal(&self.reference);
        Ok(self)
    }

    /// The variables' names.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }
    /// The plan first made, from the initial posture.
    pub fn first_plan(&self) -> &[Vec<f64>] {
        &self.reference
    }
    /// The initial posture.
    pub fn initial(&self) -> &[f64] {
        &self.reference[0]
    }
    /// Every posture observed so far, the first at the initial posture.
    pub fn reading(&self) -> &[Vec<f64>] {
        &self.reading
    }
    /// The current goal and via-points.
    pub fn conditions(&self) -> &Conditions {
        &self.conditions
    }
    /// The posture last commanded (the initial posture before the first step).
    pub fn commanded(&self) -> &[f64] {
        &self.rows[self.at]
    }
    /// Re-plans so far.
    pub fn replans(&self) -> usize {
        self.replans
    }
    /// Whether the plan's last posture has been commanded.
    pub fn done(&self) -> bool {
        self.at + 1 >= self.rows.len()
    }
    /// How far along the plan, 0 to 1.
    pub fn phase(&self) -> f64 {
        let n = self.rows.len();
        if n < 2 {
            return 1.0;
        }
        self.phase0 + (1.0 - self.phase0) * self.at as f64 / (n - 1) as f64
    }

    /// `observed` read: checked (one finite value per variable) and added to the reading;
    /// whether the arm is where it was sent (within the tolerance of the posture last
    /// commanded).
    pub fn observe(&mut self, observed: &[f64]) -> Result<bool, StepperError> {
        check_posture("the observed posture", observed, &self.columns)?;
        let on = euclidean(observed, &self.rows[self.at]) <= self.tolerance;
        self.reading.push(observed.to_vec());
        Ok(on)
    }

    /// The next posture of the plan (its last again once it has ended), to be commanded.
    pub fn advance(&mut self) -> Vec<f64> {
        self.at = (self.at + 1).min(self.rows.len() - 1);
        self.rows[self.at].clone()
    }

    /// The plan first made re-joined from the last posture read: the reading aligned with it
    /// (open-end DTW in the data's units) says where along it the arm has got to; its rest
    /// from there, offset so that it starts at the posture read, the offset faded out along
    /// a minimum-jerk profile no faster than half the plan's largest step. A method that
    /// cannot take a reading as its context re-joins so (the paper's algorithm, and every
    /// method before its reading is long enough).
    pub fn realigned(&self) -> Vec<Vec<f64>> {
        let Some(observed) = self.reading.last() else {
            return self.rows[self.at..].to_vec();
        };
        let (end, _) = open_end_cost(&self.reading, &self.reference);
        let base = &self.reference[end..];
        if base.len() < 2 {
            return self.approach(observed, &base[0]);
        }
        let offset: Vec<f64> = observed.iter().zip(&base[0]).map(|(o, b)| o - b).collect();
        let size = offset.iter().map(|v| v * v).sum::<f64>().sqrt();
        let ticks = match self.largest_step > 0.0 {
            true => (2.0 * MINIMUM_JERK_PEAK * size / self.largest_step).ceil() as usize,
            false => base.len() - 1,
        };
        let ticks = ticks.clamp(1, base.len() - 1);
        let mut rest: Vec<Vec<f64>> = base
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let keep = 1.0 - minimum_jerk_at(i as f64 / ticks as f64);
                b.iter().zip(&offset).map(|(b, o)| b + keep * o).collect()
            })
            .collect();
        rest[0] = observed.clone();
        rest
    }

    /// From `from` to `to` along a minimum-jerk profile whose peak step is the plan's largest
    /// (at least one tick), both ends included.
    fn approach(&self, from: &[f64], to: &[f64]) -> Vec<Vec<f64>> {
        let d = euclidean(from, to);
        let ticks = match self.largest_step > 0.0 {
            true => (MINIMUM_JERK_PEAK * d / self.largest_step).ceil() as usize,
            false => 1,
        }
        .max(1);
        let mut rows = minimum_jerk(from, to, ticks);
        rows.push(to.to_vec());
        rows
    }

    /// The goal and the via-points still ahead of the current phase, as phases of a rest of
    /// `n` rows that starts at the current tick (a via-point less than a tick ahead is passed).
    pub fn points_ahead(&self, n: usize) -> Vec<(f64, Vec<f64>)> {
        let p = self.phase();
        let ticks = n.saturating_sub(1) as f64;
        let mut points: Vec<(f64, Vec<f64>)> = self
            .conditions
            .via
            .iter()
            .filter(|v| v.phase > p && v.phase < 1.0)
            .map(|v| ((v.phase - p) / (1.0 - p), v.posture.clone()))
            .filter(|(q, _)| q * ticks >= 1.0)
            .chain(self.conditions.goal.iter().map(|g| (1.0, g.clone())))
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        points.dedup_by(|a, b| a.0 == b.0);
        points
    }

    /// `rest` (from the current tick) met onto the goal and the via-points ahead ([`meet`],
    /// the ranges given): first lengthened by a minimum-jerk approach to the goal when it is too short to
    /// reach it with steps no larger than the plan's.
    fn bent(&self, mut rest: Vec<Vec<f64>>) -> Result<Vec<Vec<f64>>, StepperError> {
        if let (Some(goal), Some(last)) = (&self.conditions.goal, rest.last().cloned()) {
            let need = match self.largest_step > 0.0 {
                true => {
                    (MINIMUM_JERK_PEAK * euclidean(&last, goal) / self.largest_step).ceil() as usize
                }
                false => 1,
            };
            if rest.len() < need.max(1) + 1 {
                rest.extend(self.approach(&last, goal).into_iter().skip(1));
            }
        }
        let points = self.points_ahead(rest.len());
        if points.is_empty() {
            return Ok(rest);
        }
        Ok(meet(&rest, &points, self.ranges.as_deref())?)
    }

    /// One tick of a closed-loop stepper over this course: `observed` read; when the arm is
    /// not where it was sent, the rest `replan` makes from the course (its first row the
    /// posture read) is followed from this tick ([`Course::rejoin`], met onto the goal and the
    /// via-points ahead when `bend`); the next posture to command.
    pub fn step_with(
        &mut self,
        observed: &[f64],
        bend: bool,
        replan: impl FnOnce(&Course) -> Result<Vec<Vec<f64>>, StepperError>,
    ) -> Result<Vec<f64>, StepperError> {
        if !self.observe(observed)? {
            let mut rest = replan(self)?;
            match rest.first_mut() {
                Some(first) => *first = observed.to_vec(),
                None => rest.push(observed.to_vec()),
            }
            self.rejoin(rest, bend)?;
        }
        Ok(self.advance())
    }

    /// Follow `rest` from this tick (its first row the posture last read): met onto the goal and
    /// the via-points ahead when `bend`, else as it is (a method that conditions its own).
    /// Counts as a re-plan.
    pub fn rejoin(&mut self, rest: Vec<Vec<f64>>, bend: bool) -> Result<(), StepperError> {
        let rest = if bend { self.bent(rest)? } else { rest };
        self.restart(rest);
        self.replans += 1;
        Ok(())
    }

    /// Follow `rest` (at least one row, its first commanded already) from this tick.
    pub fn restart(&mut self, rest: Vec<Vec<f64>>) {
        if rest.is_empty() {
            return;
        }
        self.phase0 = self.phase();
        self.rows = rest;
        self.at = 0;
    }

    /// This course's conditions with `goal` for their goal, checked (width, finite values,
    /// the ranges, no other posture at phase 1); the course is not changed.
    pub fn with_goal(&self, goal: &[f64]) -> Result<Conditions, StepperError> {
        let conditions = Conditions {
            goal: Some(goal.to_vec()),
            via: self.conditions.via.clone(),
        };
        conditions.check(&self.columns, self.ranges.as_deref(), self.initial())?;
        Ok(conditions)
    }

    /// Follow `rest` (at least one row, its first the posture last commanded) from this tick, with
    /// `conditions` (checked by [`Course::with_goal`]) for the goal and via-points: a method
    /// that conditions its own plan moves its goal so.
    pub fn restart_with(&mut self, rest: Vec<Vec<f64>>, conditions: Conditions) {
        self.conditions = conditions;
        self.restart(rest);
    }

    /// Move the goal: checked ([`Course::with_goal`]), and the plan's rest from the posture
    /// last commanded re-bent onto it and the via-points ahead (pinned at the posture last
    /// commanded, so the command does not jump).
    pub fn set_goal(&mut self, goal: &[f64]) -> Result<(), StepperError> {
        let conditions = self.with_goal(goal)?;
        self.rebend(conditions)
    }

    /// Replace the via-points (phases of the whole reproduction, as at the start): checked as
    /// the goal is, and the plan's rest from the posture last commanded re-bent onto the goal
    /// and the via-points ahead. Those behind the current phase no longer matter.
    pub fn set_via(&mut self, via: Vec<crate::condition::ViaPoint>) -> Result<(), StepperError> {
        let conditions = Conditions {
            goal: self.conditions.goal.clone(),
            via,
        };
        conditions.check(&self.columns, self.ranges.as_deref(), self.initial())?;
        self.rebend(conditions)
    }

    /// Take `conditions` and re-bend the rest onto them; on a refusal, nothing changes.
    fn rebend(&mut self, conditions: Conditions) -> Result<(), StepperError> {
        let kept = std::mem::replace(&mut self.conditions, conditions);
        match self.bent(self.rows[self.at..].to_vec()) {
            Ok(rest) => {
                self.restart(rest);
                Ok(())
            }
            Err(e) => {
                self.conditions = kept;
                Err(e)
            }
        }
    }
}
