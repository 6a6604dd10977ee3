//! The paper's baseline (Section V: GMM/GMR after Calinon) executed exactly like CoSCo-HSOM:
//! the same demonstrations, the same position controller on the simulated arm, the same
//! initial posture, recorded at the same rate, scored with the same metrics.
//!
//! **Starting from the initial posture.** GMR's mean trajectory starts wherever the
//! regression puts `E[q | t = 0]` (close to, but not exactly at, the initial posture: it is
//! a weighted mean over the aligned demonstrations' first samples). The executed plan is
//! therefore
//!
//! 1. a minimum-jerk lead-in from the initial posture `q₀` to `m(0)` (GMR's first point):
//!    `q(s) = q₀ + (m(0) − q₀)(10 s³ − 15 s⁴ + 6 s⁵)`, `s = k / n`, `k = 0 … n−1`, whose
//!    duration `T = max(`[`LEAD_IN_MIN_S`](crate::gmr::LEAD_IN_MIN_S)`, 1.875 · max_j |m_j(0) − q₀_j| / `[`LEAD_IN_PEAK_SPEED`]`)`
//!    (1.875 · Δ / T is the peak speed of a minimum-jerk move), rounded up to whole ticks
//!    (`n = ⌈T · rate⌉`);
//! 2. then GMR's mean `m(t)` at `t = 0, dt, …, duration` (the reference demonstration's
//!    trimmed duration).
//!
//! The lead-in is counted in the executed trajectory (it is part of what the arm does), so
//! every metric includes it. Values outside a joint's range are clamped and counted, as for
//! CoSCo-HSOM.

use std::path::Path;

use plotters::style::RGBColor;

use crate::gmr::TrainingSet;
use crate::gmr::{plan_at, ComponentChoice, GmrModel, GmrPlan};
use crate::plot::{panels_png, Band, Ellipse, Panel, Scatter, Series};
use crate::sim::LEAD_IN_PEAK_SPEED;

use super::figures::{joint_panels_png, Curve};
use super::ExperimentError;

/// Name of the baseline in reports.
pub const GMR_NAME: &str = "GMM/GMR";
/// What the baseline needs as input (the report's "needs as input" row).
pub const GMR_NEEDS: &str = "at least 2 demonstrations, pre-processed: idle start/end trimmed, \
    DTW-aligned to the medoid demonstration, resampled to a fixed number of points; a time \
    index t (it regresses q on t over the learned duration); the initial posture only for \
    the minimum-jerk lead-in to GMR's first point";
/// The default component choice: the evaluator's ([`crate::eval::GMR_COMPONENTS`]), the lowest
/// BIC over 1..=16; over 1..=16 it has an interior minimum on the four gestures (12 to 15).
pub const DEFAULT_COMPONENTS: ComponentChoice = crate::eval::GMR_COMPONENTS;
/// Colour of the baseline's curves.
pub const GMR_COLOR: RGBColor = RGBColor(200, 0, 130);

/// The plan: the lead-in from `initial` to GMR's first point, then GMR's mean every
/// `1 / rate_hz` seconds over the model's duration.
pub fn plan(model: &GmrModel, initial: &[f64], rate_hz: f64) -> Result<GmrPlan, ExperimentError> {
    Ok(plan_at(model, initial, rate_hz, LEAD_IN_PEAK_SPEED)?)
}

/// The paper's Fig. 3: the pre-processed (trimmed, aligned, resampled) training data, one
/// panel per `(column index, name)` of `joints`.
pub fn fig3_png(
    path: &Path,
    training: &TrainingSet,
    joints: &[(usize, &str)],
) -> Result<(), ExperimentError> {
    let curves: Vec<Curve> = (training.demos.iter().enumerate())
        .map(|(i, d)| Curve::demo(i, (&training.times[..], &d[..])))
        .collect();
    let title = format!(
        "Pre-processed training data for GMM: idle trimmed, DTW-aligned{}, {} points each",
        training
            .reference
            .map_or(String::new(), |r| format!(" to demonstration {}", r + 1)),
        training.times.len()
    );
    Ok(joint_panels_png(path, &title, joints, &curves, None)?)
}

/// The paper's Fig. 5 for column `joint` (named `name`): each Gaussian's marginal over
/// `[t, q_joint]` as its 2-sigma ellipse, GMR's mean, the ±2σ envelope of GMR's conditional
/// variance, and the aligned training data as dots.
pub fn fig5_png(
    path: &Path,
    model: &GmrModel,
    training: &TrainingSet,
    joint: usize,
    name: &str,
    period: f64,
) -> Result<(), ExperimentError> {
    if joint >= model.columns().len() {
        return Err(ExperimentError::Invalid(format!(
            "joint index {joint} for {name}: the model has {} columns",
            model.columns().len()
        )));
    }
    let preds = model.reproduce(period)?;
    let mut p = Panel::new(
        "green: Gaussians (2 sigma); blue: GMR mean; light blue: +-2 sigma; dots: aligned data",
        "time (s)",
        format!("{name} (rad)"),
    );
    let g = model.gmm();
    for (m, s) in g.means().iter().zip(g.covariances()) {
        let j = joint + 1;
        p.ellipses.push(Ellipse {
            mean: (m[0], m[j]),
            cov: [[s[(0, 0)], s[(0, j)]], [s[(j, 0)], s[(j, j)]]],
            n_sigma: 2.0,
            color: RGBColor(40, 170, 60),
        });
    }
    p.bands.push(Band {
        label: None,
        color: RGBColor(90, 160, 255),
        points: preds
            .iter()
            .map(|q| {
                let sd = q.covariance[joint][joint].max(0.0).sqrt();
                (q.time, q.mean[joint] - 2.0 * sd, q.mean[joint] + 2.0 * sd)
            })
            .collect(),
    });
    p.scatter.push(Scatter {
        label: None,
        color: RGBColor(60, 60, 60),
        size: 2,
        points: training
            .demos
            .iter()
            .flat_map(|d| {
                training
                    .times
                    .iter()
                    .zip(d)
                    .filter_map(|(t, q)| q.get(joint).map(|v| (*t, *v)))
            })
            .collect(),
    });
    p.series.push(Series {
        label: None,
        color: RGBColor(0, 40, 200),
        width: 2,
        points: preds.iter().map(|q| (q.time, q.mean[joint])).collect(),
    });
    let title = format!(
        "GMM/GMR on {name}: {} Gaussian components, regression of q on t",
        g.n_components()
    );
    Ok(panels_png(path, &title, &[p], 1, (1000, 600))?)
}

#[cfg(test)]
mod tests;
