//! From an initial posture to GMR's mean trajectory: a minimum-jerk lead-in to GMR's first
//! point, then the mean every sample period (what the baseline executes; the formula is in
//! `experiment::baseline`'s documentation). Here without the simulator, for any data: the
//! lead-in's peak speed is an argument (the arm's 1 rad/s in `experiment::baseline`; the
//! demonstrations' own speed in [`crate::eval`]).

use super::{GmrError, GmrModel, Prediction};
use crate::curve::{minimum_jerk, minimum_jerk_at, MINIMUM_JERK_PEAK};

/// Shortest lead-in, seconds.
pub const LEAD_IN_MIN_S: f64 = 0.1;

/// Ticks of a minimum-jerk lead-in from `from` to `to` at `rate_hz` whose peak speed is at
/// most `peak_speed` (units per second) on every variable, lasting at least
/// [`LEAD_IN_MIN_S`]; at least 1 (the initial posture itself).
pub fn lead_in_ticks_at(from: &[f64], to: &[f64], rate_hz: f64, peak_speed: f64) -> usize {
    let delta = from
        .iter()
        .zip(to)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let t = LEAD_IN_MIN_S.max(MINIMUM_JERK_PEAK * delta / peak_speed);
    ((t * rate_hz).ceil() as usize).max(1)
}

/// The postures of GMR's reproduction from an initial posture.
#[derive(Debug, Clone, PartialEq)]
pub struct GmrPlan {
    /// One posture per tick; the first is the initial posture.
    pub postures: Vec<Vec<f64>>,
    /// How many leading postures are the minimum-jerk lead-in.
    pub lead_in: usize,
    /// GMR's predictions (`time` on GMR's own time line, from 0), one per posture after
    /// the lead-in.
    pub predictions: Vec<Prediction>,
}

/// The plan: the lead-in from `initial` to GMR's first point at `peak_speed`, then GMR's
/// mean every `1 / rate_hz` seconds over the model's duration. The rate and the speed must
/// be finite and above 0, the initial posture one finite value per column of the model.
pub fn plan_at(
    model: &GmrModel,
    initial: &[f64],
    rate_hz: f64,
    peak_speed: f64,
) -> Result<GmrPlan, GmrError> {
    if !(rate_hz.is_finite() && rate_hz > 0.0) {
        return Err(GmrError::InvalidParam {
            name: "rate_hz",
            value: rate_hz.to_string(),
            reason: "a finite rate > 0",
        });
    }
    if !(peak_speed.is_finite() && peak_speed > 0.0) {
        return Err(GmrError::InvalidParam {
            name: "peak_speed",
            value: peak_speed.to_string(),
            reason: "a finite speed > 0",
        });
    }
    if initial.len() != model.columns().len() || initial.iter().any(|v| !v.is_finite()) {
        return Err(GmrError::BadInitial {
            found: format!("{initial:?}"),
            expected: model.columns().len(),
            columns: model.columns().join(", "),
        });
    }
    let predictions = model.reproduce(1.0 / rate_hz)?;
    let first = &predictions[0].mean;
    let lead_in = lead_in_ticks_at(initial, first, rate_hz, peak_speed);
    let mut postures = minimum_jerk(initial, first, lead_in);
    postures.extend(predictions.iter().map(|p| p.mean.clone()));
    Ok(GmrPlan {
        postures,
        lead_in,
        predictions,
    })
}

impl GmrPlan {
    /// The half-widths of GMR's own central 95 % band about the plan, per posture and
    /// variable: 1.96 conditional standard deviations at each of GMR's points; over the
    /// lead-in, from 0 at the given initial posture growing by the lead-in's minimum-jerk
    /// profile to the half-width at GMR's first point. The band is the postures minus and
    /// plus these (`condition::ConfidenceBand::around`).
    pub fn band_half_widths(&self) -> Vec<Vec<f64>> {
        let sd = |p: &Prediction| -> Vec<f64> {
            (0..p.mean.len())
                .map(|d| 1.96 * p.covariance[d][d].max(0.0).sqrt())
                .collect()
        };
        let first = self.predictions.first().map(sd).unwrap_or_default();
        let lead = (0..self.lead_in).map(|k| {
            let h = minimum_jerk_at(k as f64 / self.lead_in.max(1) as f64);
            first.iter().map(|v| v * h).collect::<Vec<f64>>()
        });
        lead.chain(self.predictions.iter().map(sd)).collect()
    }
}
