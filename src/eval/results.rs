//! The results of an evaluation, in one place: a method's score on one fold, the fold, a
//! gesture's folds held out and in-sample, and the summary over gestures.

use serde::Serialize;

use crate::demos::Demonstration;
use crate::metrics::{median, FidelityReport};

use super::method::Method;

/// The smallest normalised jerk of a held-out demonstration for which the jerk ratio is
/// given. Every motion that starts and ends at rest has at least √360 ≈ 19 (minimum jerk);
/// below 1 the demonstration is a nearly uniform motion (a straight line at constant speed
/// has 0) and a ratio to it means nothing.
pub const MIN_DEMO_JERK: f64 = 1.0;

/// One reproduction scored against one demonstration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Score {
    /// Per-step DTW distance in the data's units (rad for joints).
    pub dtw: f64,
    /// `dtw` over the diagonal of the gesture's bounding box.
    pub relative_dtw: f64,
    /// Trimmed duration of the reproduction over the demonstration's.
    pub duration_ratio: f64,
    /// Distance between the last samples, data units.
    pub final_error: f64,
    /// Normalised jerk of the reproduction over the demonstration's (`None` when either has
    /// none, or the demonstration's is below [`MIN_DEMO_JERK`]).
    pub jerk_ratio: Option<f64>,
}

/// A method's result on one fold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Run {
    /// Which method.
    pub method: Method,
    /// The score, when the method produced a reproduction.
    pub score: Option<Score>,
    /// Why it produced none.
    pub error: Option<String>,
    /// The reproduction (not serialised).
    #[serde(skip)]
    pub postures: Vec<Vec<f64>>,
}

/// The methods on one demonstration: held out (learned from the others) or in-sample
/// (learned from all).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fold {
    /// The demonstration scored against (its file).
    pub demonstration: String,
    /// One run per method, in [`Method::ALL`]'s order.
    pub runs: Vec<Run>,
}

impl Fold {
    /// The score of `method`, when it ran and succeeded.
    pub fn score(&self, method: Method) -> Option<&Score> {
        self.runs
            .iter()
            .find(|r| r.method == method)
            .and_then(|r| r.score.as_ref())
    }
}

/// Leave-one-out on one gesture's demonstrations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GestureLoo {
    /// The gesture's name (its directory, or `gesture` for plain files).
    pub gesture: String,
    /// Its demonstrations, in order (not serialised: the folds name their files).
    #[serde(skip)]
    pub demonstrations: Vec<Demonstration>,
    /// The diagonal of their bounding box, data units.
    pub diagonal: f64,
    /// One fold per demonstration, held out.
    pub held_out: Vec<Fold>,
    /// One per demonstration, in-sample (empty unless asked for).
    pub in_sample: Vec<Fold>,
}

impl GestureLoo {
    /// The mean of `f` over the folds where `method` succeeded (`None` when it never did).
    pub fn mean(&self, folds: &[Fold], method: Method, f: fn(&Score) -> f64) -> Option<f64> {
        let v: Vec<f64> = folds
            .iter()
            .filter_map(|fold| fold.score(method).map(f))
            .collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    }
}

impl Score {
    /// The score of a reproduction whose fidelity against one demonstration is `f`, in a
    /// gesture whose bounding box has the diagonal `diag`.
    pub fn of(f: &FidelityReport, diag: f64) -> Score {
        let jerk = match (
            f.reproduction_smoothness.normalized_jerk,
            f.demo_smoothness.first().and_then(|d| d.normalized_jerk),
        ) {
            (Some(r), Some(d)) if d >= MIN_DEMO_JERK => Some(r / d),
            _ => None,
        };
        Score {
            dtw: f.joint_dtw_rad_per_step.mean,
            relative_dtw: if diag > 0.0 {
                f.joint_dtw_rad_per_step.mean / diag
            } else {
                f64::NAN
            },
            duration_ratio: f.duration_ratio.mean,
            final_error: f.final_error_rad.mean,
            jerk_ratio: jerk,
        }
    }
}

/// One method over every gesture: medians over the gestures of the per-gesture means over
/// the folds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodSummary {
    /// Which method.
    pub method: Method,
    /// Folds it ran on (held out).
    pub folds: usize,
    /// Folds where it produced nothing.
    pub failed: usize,
    /// Median relative DTW, held out.
    pub relative_dtw: Option<f64>,
    /// Median relative DTW, in-sample (learned from all).
    pub relative_dtw_in_sample: Option<f64>,
    /// Median duration ratio, held out.
    pub duration_ratio: Option<f64>,
    /// Median final error over the diagonal, held out.
    pub relative_final_error: Option<f64>,
    /// Median jerk ratio, held out.
    pub jerk_ratio: Option<f64>,
    /// Median over gestures of the hierarchy's DTW over this method's (held out).
    pub hierarchy_ratio: Option<f64>,
    /// Gestures where the hierarchy's mean DTW is below this method's, of those both ran on.
    pub hierarchy_closer: (usize, usize),
}

fn held(g: &GestureLoo) -> &[Fold] {
    &g.held_out
}

fn ins(g: &GestureLoo) -> &[Fold] {
    &g.in_sample
}

/// The summary of every method that ran.
pub fn summary(study: &[GestureLoo]) -> Vec<MethodSummary> {
    let ran = |m: Method| {
        study.iter().any(|g| {
            g.held_out
                .iter()
                .any(|f| f.runs.iter().any(|r| r.method == m))
        })
    };
    Method::ALL
        .into_iter()
        .filter(|&m| ran(m))
        .map(|m| {
            let runs = || {
                study
                    .iter()
                    .flat_map(|g| &g.held_out)
                    .flat_map(|f| &f.runs)
                    .filter(move |r| r.method == m)
            };
            let med = |folds: fn(&GestureLoo) -> &[Fold], f: fn(&Score) -> f64| {
                median(study.iter().filter_map(|g| g.mean(folds(g), m, f)))
            };
            let pairs: Vec<(f64, f64)> = study
                .iter()
                .filter_map(|g| {
                    Some((
                        g.mean(&g.held_out, Method::Hierarchy, |s| s.dtw)?,
                        g.mean(&g.held_out, m, |s| s.dtw)?,
                    ))
                })
                .collect();
            MethodSummary {
                method: m,
                folds: runs().count(),
                failed: runs().filter(|r| r.score.is_none()).count(),
                relative_dtw: med(held, |s| s.relative_dtw),
                relative_dtw_in_sample: med(ins, |s| s.relative_dtw),
                duration_ratio: med(held, |s| s.duration_ratio),
                relative_final_error: median(study.iter().filter_map(|g| {
                    g.mean(&g.held_out, m, |s| s.final_error)
                        .map(|e| e / g.diagonal)
                })),
                jerk_ratio: median(
                    study.iter().filter_map(|g| {
                        g.mean(&g.held_out, m, |s| s.jerk_ratio.unwrap_or(f64::NAN))
                    }),
                ),
                hierarchy_ratio: median(pairs.iter().map(|(h, x)| h / x)),
                hierarchy_closer: (pairs.iter().filter(|(h, x)| h < x).count(), pairs.len()),
            }
        })
        .collect()
}

/// Every distinct reason a method produced nothing, with the folds it happened on
/// (`gesture`, held out or in-sample, the demonstration's file), in the order met.
pub fn failures(study: &[GestureLoo]) -> Vec<(Method, String, Vec<String>)> {
    let mut out: Vec<(Method, String, Vec<String>)> = Vec::new();
    for g in study {
        for (kind, folds) in [("held out", &g.held_out), ("in-sample", &g.in_sample)] {
            for f in folds {
                for r in &f.runs {
                    let Some(e) = &r.error else { continue };
                    let at = format!("{} ({kind}, {})", g.gesture, f.demonstration);
                    match out.iter_mut().find(|(m, w, _)| *m == r.method && w == e) {
                        Some((_, _, at_list)) => at_list.push(at),
                        None => out.push((r.method, e.clone(), vec![at])),
                    }
                }
            }
        }
    }
    out
}
