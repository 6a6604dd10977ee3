//! The results of an evaluation, in one place: a method's run on one fold ([`Run`]: its
//! [`Score`] and every metric, [`FoldScores`]), the fold ([`Fold`]), a gesture's folds held
//! out and in-sample ([`GestureLoo`]), the summary over gestures ([`MethodSummary`]); and the
//! means over one set's folds ([`HeldOut`], [`HeldOutSummary`]) that the simulated arm's
//! reports show.

use serde::Serialize;

use crate::demos::Demonstration;
use crate::metrics::{FidelityReport, StartEnd};
use crate::stats::median;

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
    /// The reproduction's first step's speed, data units/s (`None` with one sample;
    /// docs/METRICS.md, "Start and end").
    pub start_speed: Option<f64>,
    /// The largest first-step speed of the demonstrations it learned from, data units/s.
    pub demo_start_speed_max: Option<f64>,
    /// Whether `start_speed` is at most `demo_start_speed_max`.
    pub start_in_range: bool,
    /// The mean pairwise distance between the last samples of the demonstrations it learned
    /// from, data units (0 for one).
    pub end_spread: f64,
    /// Whether `final_error` is at most 2 x `end_spread` or 1 % of the gesture's diagonal.
    pub end_within_spread: bool,
    /// The share of the demonstration inside the method's 95 % band ([`FoldScores::coverage`];
    /// `None` for a method without a band).
    pub coverage: Option<f64>,
    /// The goal's error over the gesture's diagonal (`None` without a goal).
    pub goal_error: Option<f64>,
    /// The largest via-point's error over the diagonal (`None` without via-points).
    pub via_error: Option<f64>,
    /// Posture values outside the Nao arm's joint ranges (`None` for other variables).
    pub out_of_range: Option<usize>,
    /// Large swings of LElbowRoll: the reproduction's and the demonstration's (`None` for
    /// other variables; [`Swings`]).
    pub swings: Option<[usize; 2]>,
}

/// A method's result on one fold (equal to another with the same results, whatever the time
/// each took).
#[derive(Debug, Clone, Serialize)]
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
    /// Its 95 % band, for a method that gives one (not serialised).
    #[serde(skip)]
    pub band: Option<crate::condition::ConfidenceBand>,
    /// Every metric of the executed reproduction (not serialised here: [`HeldOut`] writes it).
    #[serde(skip)]
    pub scores: Option<FoldScores>,
}

impl Run {
    /// `method`'s run that produced no reproduction, and why.
    pub fn failed(method: Method, error: String) -> Run {
        Run {
            method,
            score: None,
            error: Some(error),
            postures: Vec::new(),
            band: None,
            scores: None,
        }
    }
}

impl PartialEq for Run {
    fn eq(&self, other: &Run) -> bool {
        let untimed = |r: &Run| {
            r.scores.as_ref().map(|s| FoldScores {
                train_s: 0.0,
                reproduce_s: 0.0,
                ..s.clone()
            })
        };
        (self.method, &self.score, &self.error, &self.postures)
            == (other.method, &other.score, &other.error, &other.postures)
            && untimed(self) == untimed(other)
    }
}

/// The methods on one demonstration: held out (learned from the others) or in-sample
/// (learned from all).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fold {
    /// The demonstration scored against (its file).
    pub demonstration: String,
    /// One run per method, in [`Method::ALL`]'s order.
    pub runs: Vec<Run>,
    /// What the methods learned, when the fold was asked to keep it
    /// ([`FoldInput::keep`](super::FoldInput::keep)).
    #[serde(skip)]
    pub learned: super::learned::Kept,
}

impl Fold {
    /// The run of `method`, when it was asked for.
    pub fn run(&self, method: Method) -> Option<&Run> {
        self.runs.iter().find(|r| r.method == method)
    }

    /// The score of `method`, when it ran and succeeded.
    pub fn score(&self, method: Method) -> Option<&Score> {
        self.run(method).and_then(|r| r.score.as_ref())
    }

    /// Every metric of `method`'s run, when it ran and succeeded.
    pub fn scores(&self, method: Method) -> Option<&FoldScores> {
        self.run(method).and_then(|r| r.scores.as_ref())
    }

    /// Why `method` produced nothing, when it was asked for and failed.
    pub fn error(&self, method: Method) -> Option<&str> {
        self.run(method).and_then(|r| r.error.as_deref())
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
    /// gesture whose bounding box has the diagonal `diag`, and whose start and end against the
    /// demonstrations it learned from are `start_end`.
    pub fn of(f: &FidelityReport, diag: f64, start_end: &StartEnd) -> Score {
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
            start_speed: start_end.start_speed,
            demo_start_speed_max: start_end.demo_start_speed_max,
            start_in_range: start_end.start_in_range,
            end_spread: start_end.end_spread,
            end_within_spread: start_end.end_within_spread,
            coverage: None,
            goal_error: None,
            via_error: None,
            out_of_range: None,
            swings: None,
        }
    }

    /// The score with the band's coverage and the conditions' errors (over the diagonal
    /// `diag`) of `scores`.
    pub fn with(self, scores: &FoldScores, diag: f64) -> Score {
        let c = scores.conditions.as_ref();
        Score {
            coverage: scores.coverage,
            goal_error: c.and_then(|c| c.goal).map(|e| e / diag),
            via_error: c.and_then(|c| c.via).map(|e| e / diag),
            out_of_range: scores.out_of_range,
            swings: scores.swings.as_ref().map(|w| [w.reproduction, w.demo]),
            ..self
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
    /// Fraction of the held-out folds it ran on whose reproduction starts in range
    /// ([`Score::start_in_range`]; a fold without a reproduction counts as not).
    pub start_in_range: Option<f64>,
    /// The same for ending within the spread ([`Score::end_within_spread`]).
    pub end_within_spread: Option<f64>,
    /// Median band coverage, held out (`None` for a method without a band).
    pub coverage: Option<f64>,
    /// The largest goal error over the diagonal of any held-out fold (`None` without goals).
    pub worst_goal_error: Option<f64>,
    /// The largest via-point error over the diagonal of any held-out fold (`None` without
    /// via-points).
    pub worst_via_error: Option<f64>,
    /// Posture values outside the Nao arm's joint ranges over the held-out folds (`None` for
    /// other variables).
    pub out_of_range: Option<usize>,
}

/// The held-out runs of `method` in `study`.
pub(super) fn held_out_runs(study: &[GestureLoo], method: Method) -> impl Iterator<Item = &Run> {
    let folds = study.iter().flat_map(|g| &g.held_out);
    folds
        .flat_map(|f| &f.runs)
        .filter(move |r| r.method == method)
}

/// The held-out folds of `method` in `study` where it produced a reproduction whose score
/// passes `pass`, and the held-out folds it ran on.
pub fn passed(study: &[GestureLoo], method: Method, pass: fn(&Score) -> bool) -> (usize, usize) {
    held_out_runs(study, method).fold((0, 0), |(k, n), r| {
        (k + usize::from(r.score.as_ref().is_some_and(pass)), n + 1)
    })
}

/// `k / n` of a [`passed`] count (`None` when `n` is 0).
fn fraction((k, n): (usize, usize)) -> Option<f64> {
    (n > 0).then(|| k as f64 / n as f64)
}

/// The summary of every method that ran.
pub fn summary(study: &[GestureLoo]) -> Vec<MethodSummary> {
    let ran = |m: Method| held_out_runs(study, m).next().is_some();
    Method::ALL
        .into_iter()
        .filter(|&m| ran(m))
        .map(|m| {
            // the median over the gestures of a per-gesture figure
            let med =
                |per: &dyn Fn(&GestureLoo) -> Option<f64>| median(study.iter().filter_map(per));
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
                folds: held_out_runs(study, m).count(),
                failed: held_out_runs(study, m)
                    .filter(|r| r.score.is_none())
                    .count(),
                relative_dtw: med(&|g| g.mean(&g.held_out, m, |s| s.relative_dtw)),
                relative_dtw_in_sample: med(&|g| g.mean(&g.in_sample, m, |s| s.relative_dtw)),
                duration_ratio: med(&|g| g.mean(&g.held_out, m, |s| s.duration_ratio)),
                relative_final_error: med(&|g| {
                    Some(g.mean(&g.held_out, m, |s| s.final_error)? / g.diagonal)
                }),
                jerk_ratio: med(&|g| g.mean(&g.held_out, m, |s| s.jerk_ratio.unwrap_or(f64::NAN))),
                hierarchy_ratio: median(pairs.iter().map(|(h, x)| h / x)),
                hierarchy_closer: (pairs.iter().filter(|(h, x)| h < x).count(), pairs.len()),
                start_in_range: fraction(passed(study, m, |s| s.start_in_range)),
                end_within_spread: fraction(passed(study, m, |s| s.end_within_spread)),
                coverage: med(&|g| g.mean(&g.held_out, m, |s| s.coverage.unwrap_or(f64::NAN))),
                worst_goal_error: worst(study, m, |s| s.goal_error),
                worst_via_error: worst(study, m, |s| s.via_error),
                out_of_range: held_out_runs(study, m)
                    .filter_map(|r| r.score.as_ref()?.out_of_range)
                    .reduce(|a, b| a + b),
            }
        })
        .collect()
}

/// The largest `f` of `method`'s held-out scores (`None` where none has one).
fn worst(study: &[GestureLoo], method: Method, f: fn(&Score) -> Option<f64>) -> Option<f64> {
    held_out_runs(study, method)
        .filter_map(|r| r.score.as_ref().and_then(f))
        .reduce(f64::max)
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

// Every metric of a run, and their means over one set's folds (`experiment::heldout`,
// `simulate`'s report, the sweeps).

/// Per-fold results that do not go together (named in the message).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct FoldsError(pub String);

/// Large swings of the executor's swing joint ([`Executor::swing_joint`](super::Executor);
/// see [`crate::metrics::large_swings`]): the reproduction's and the held-out
/// demonstration's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Swings {
    /// Joint name.
    pub joint: String,
    /// Smallest excursion counted, rad.
    pub min_amplitude_rad: f64,
    /// Swings of the executed reproduction.
    pub reproduction: usize,
    /// Swings of the held-out demonstration.
    pub demo: usize,
}

/// Every metric of one method on one fold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FoldScores {
    /// Fidelity of the executed trajectory against the fold's targets (held out: the held-out
    /// demonstration only).
    pub fidelity: FidelityReport,
    /// Large swings of the swing joint (`None` when the executor counts none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub swings: Option<Swings>,
    /// Values of the postures (before execution) outside the Nao arm's joint ranges (`None`
    /// when the variables are not its joints).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub out_of_range: Option<usize>,
    /// How far the postures (before execution) miss what they were conditioned on (`None`
    /// when unconditioned).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub conditions: Option<ConditionErrors>,
    /// The share of the held-out demonstration inside the method's 95 % band, the
    /// demonstration aligned to the postures by DTW (docs/METRICS.md, "Confidence band";
    /// `None` for a method without a band).
    pub coverage: Option<f64>,
    /// Postures the method produced.
    pub postures: usize,
    /// Posture values clamped into the joint ranges before execution.
    pub clamped_values: usize,
    /// Training time, seconds.
    pub train_s: f64,
    /// Time to produce the postures, seconds.
    pub reproduce_s: f64,
    /// The executed motion's start and end against the fold's training demonstrations
    /// (docs/METRICS.md, "Start and end"; `None` where not judged).
    pub start_end: Option<StartEnd>,
    /// The postures handed to the servos, scored the same way (`None` where not judged).
    pub commanded: Option<Commanded>,
}

/// How far a reproduction's postures miss the postures it was conditioned on, data units:
/// each read at its phase between two rows ([`crate::curve::at_phase`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConditionErrors {
    /// The last posture's distance from the goal (`None` without a goal).
    pub goal: Option<f64>,
    /// The largest distance from a via-point (`None` without via-points).
    pub via: Option<f64>,
}

impl ConditionErrors {
    /// The errors of `postures` conditioned on `c` (`None` when `c` has no condition or
    /// `postures` no row).
    pub fn of(c: &crate::condition::Conditions, postures: &[Vec<f64>]) -> Option<Self> {
        use crate::curve::at_phase;
        use crate::dtw::euclidean;
        if c.is_empty() || postures.is_empty() {
            return None;
        }
        let miss = |phase: f64, p: &[f64]| euclidean(&at_phase(postures, phase), p);
        Some(ConditionErrors {
            goal: c.goal.as_deref().map(|g| miss(1.0, g)),
            via: c
                .via
                .iter()
                .map(|v| miss(v.phase, &v.posture))
                .reduce(f64::max),
        })
    }
}

/// What a method handed the servos on one fold (the postures clamped into the joint ranges and
/// shaped by the transition, one per tick), scored without the servos' filtering.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Commanded {
    /// Postures handed over.
    pub postures: usize,
    /// Their normalised jerk, trimmed as the executed motion's
    /// ([`crate::metrics::trimmed_normalized_jerk`]).
    pub normalized_jerk: Option<f64>,
    /// Their start and end against the fold's training demonstrations.
    pub start_end: StartEnd,
}

/// Means over folds of one method.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeldOutSummary {
    /// Folds averaged.
    pub folds: usize,
    /// Joint-space DTW, rad per step.
    pub joint_dtw_rad_per_step: f64,
    /// Wrist-path DTW, mm per step (when every fold has wrist paths).
    pub wrist_dtw_mm: Option<f64>,
    /// Apex (key-pose) error, rad.
    pub apex_error_rad: f64,
    /// Final-posture error, rad.
    pub final_error_rad: f64,
    /// Duration ratio, reproduction / held-out demonstration (trimmed).
    pub duration_ratio: f64,
    /// Normalized jerk of the reproductions (mean over the folds where it is defined).
    pub normalized_jerk: Option<f64>,
    /// Velocity reversals of the reproductions, all joints.
    pub velocity_reversals: f64,
    /// Normalized jerk of the held-out demonstrations (mean where defined; of a fold scored
    /// against several, their mean).
    pub demo_normalized_jerk: Option<f64>,
    /// Velocity reversals of the held-out demonstrations, all joints (of a fold scored against
    /// several, their mean).
    pub demo_velocity_reversals: f64,
    /// Large swings of the swing joint of the reproductions.
    pub swings: f64,
    /// Large swings of the swing joint of the held-out demonstrations.
    pub demo_swings: f64,
    /// How long the reproductions stay at their apex, seconds (docs/METRICS.md,
    /// `apex_dwell`).
    pub hold_s: f64,
    /// The same for the held-out demonstrations.
    pub demo_hold_s: f64,
    /// Mean start speed of the executed motions, rad/s (over the folds where judged).
    pub start_speed: Option<f64>,
    /// Mean over the folds of the training demonstrations' largest start speed, rad/s.
    pub demo_start_speed_max: Option<f64>,
    /// Fraction of the judged folds whose executed motion starts in range.
    pub start_in_range: Option<f64>,
    /// Fraction of the judged folds whose executed motion ends within the spread.
    pub end_within_spread: Option<f64>,
    /// Mean normalised jerk of the commanded postures (over the folds where it is defined).
    pub commanded_normalized_jerk: Option<f64>,
    /// Mean start speed of the commanded postures, rad/s.
    pub commanded_start_speed: Option<f64>,
    /// Fraction of the judged folds whose commanded postures start in range.
    pub commanded_start_in_range: Option<f64>,
    /// Fraction of the judged folds whose commanded postures end within the spread.
    pub commanded_end_within_spread: Option<f64>,
    /// Mean band coverage (over the folds with a band).
    pub coverage: Option<f64>,
}

fn mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    (n > 0).then(|| sum / n as f64)
}

/// The fraction of `flags` that are true (`None` when there are none).
fn share(flags: impl Iterator<Item = bool>) -> Option<f64> {
    mean(flags.map(|b| f64::from(u8::from(b))))
}

impl HeldOutSummary {
    /// Means over `folds`; `None` when there are none.
    pub fn of(folds: &[&FoldScores]) -> Option<HeldOutSummary> {
        let m = |f: &dyn Fn(&FoldScores) -> f64| mean(folds.iter().map(|s| f(s)));
        let executed = || folds.iter().filter_map(|s| s.start_end.as_ref());
        let commanded = || folds.iter().filter_map(|s| s.commanded.as_ref());
        Some(HeldOutSummary {
            folds: folds.len(),
            joint_dtw_rad_per_step: m(&|s| s.fidelity.joint_dtw_rad_per_step.mean)?,
            wrist_dtw_mm: folds
                .iter()
                .map(|s| s.fidelity.wrist_dtw_mm.map(|w| w.mean))
                .collect::<Option<Vec<f64>>>()
                .and_then(|v| mean(v.into_iter())),
            apex_error_rad: m(&|s| s.fidelity.apex_error_rad.mean)?,
            final_error_rad: m(&|s| s.fidelity.final_error_rad.mean)?,
            duration_ratio: m(&|s| s.fidelity.duration_ratio.mean)?,
            normalized_jerk: mean(
                folds
                    .iter()
                    .filter_map(|s| s.fidelity.reproduction_smoothness.normalized_jerk),
            ),
            velocity_reversals: m(&|s| s.fidelity.reproduction_smoothness.total_reversals as f64)?,
            demo_normalized_jerk: mean(folds.iter().filter_map(|s| {
                mean(
                    s.fidelity
                        .demo_smoothness
                        .iter()
                        .filter_map(|d| d.normalized_jerk),
                )
            })),
            demo_velocity_reversals: m(&|s| {
                let demos = s.fidelity.demo_smoothness.iter();
                mean(demos.map(|d| d.total_reversals as f64)).unwrap_or(f64::NAN)
            })?,
            swings: m(&|s| {
                s.swings
                    .as_ref()
                    .map_or(f64::NAN, |w| w.reproduction as f64)
            })?,
            demo_swings: m(&|s| s.swings.as_ref().map_or(f64::NAN, |w| w.demo as f64))?,
            hold_s: m(&|s| s.fidelity.reproduction_hold_s)?,
            demo_hold_s: m(&|s| s.fidelity.demo_hold_s.first().copied().unwrap_or(f64::NAN))?,
            start_speed: mean(executed().filter_map(|e| e.start_speed)),
            demo_start_speed_max: mean(executed().filter_map(|e| e.demo_start_speed_max)),
            start_in_range: share(executed().map(|e| e.start_in_range)),
            end_within_spread: share(executed().map(|e| e.end_within_spread)),
            commanded_normalized_jerk: mean(commanded().filter_map(|c| c.normalized_jerk)),
            commanded_start_speed: mean(commanded().filter_map(|c| c.start_end.start_speed)),
            commanded_start_in_range: share(commanded().map(|c| c.start_end.start_in_range)),
            commanded_end_within_spread: share(commanded().map(|c| c.start_end.end_within_spread)),
            coverage: mean(folds.iter().filter_map(|s| s.coverage)),
        })
    }
}

/// One set's folds with the means over them of the hierarchy, GMM/GMR, and when run the
/// nearest sequence and ProMP.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HeldOut {
    /// One fold per demonstration, in order (written per method: `hsom`, `gmr`, `sequence`,
    /// `promp`, `dmp`, `dba`, each with its scores, and the reason where a baseline did not run).
    #[serde(serialize_with = "per_method")]
    pub folds: Vec<Fold>,
    /// CoSCo-HSOM: means over all folds.
    pub hsom: HeldOutSummary,
    /// GMM/GMR: means over the folds where it ran (`None` when it ran on none).
    pub gmr: Option<HeldOutSummary>,
    /// The nearest-sequence baseline: means over all folds (`None` when it was not run).
    pub sequence: Option<HeldOutSummary>,
    /// ProMP: means over the folds where it ran (`None` when it was not run or ran on none).
    pub promp: Option<HeldOutSummary>,
    /// The DMP: means over the folds where it ran (`None` when it was not run or ran on none).
    pub dmp: Option<HeldOutSummary>,
    /// The DTW mean: means over the folds where it ran (`None` when it was not run or ran on
    /// none).
    pub dba: Option<HeldOutSummary>,
}

/// The folds as the reports write them: per method.
fn per_method<S: serde::Serializer>(folds: &[Fold], s: S) -> Result<S::Ok, S::Error> {
    #[derive(Serialize)]
    struct Row<'a> {
        held_out: usize,
        source: &'a str,
        hsom: Option<&'a FoldScores>,
        gmr: Option<&'a FoldScores>,
        gmr_error: Option<&'a str>,
        sequence: Option<&'a FoldScores>,
        promp: Option<&'a FoldScores>,
        promp_error: Option<&'a str>,
        dmp: Option<&'a FoldScores>,
        dmp_error: Option<&'a str>,
        dba: Option<&'a FoldScores>,
        dba_error: Option<&'a str>,
    }
    s.collect_seq(folds.iter().enumerate().map(|(i, f)| Row {
        held_out: i,
        source: &f.demonstration,
        hsom: f.scores(Method::Hierarchy),
        gmr: f.scores(Method::GmmGmr),
        gmr_error: f.error(Method::GmmGmr),
        sequence: f.scores(Method::NearestSequence),
        promp: f.scores(Method::ProMP),
        promp_error: f.error(Method::ProMP),
        dmp: f.scores(Method::Dmp),
        dmp_error: f.error(Method::Dmp),
        dba: f.scores(Method::Dba),
        dba_error: f.error(Method::Dba),
    }))
}

impl HeldOut {
    /// The means over `folds`; an error when there are none, or when the hierarchy (or the
    /// nearest sequence, when run) failed on one.
    pub fn of(folds: Vec<Fold>) -> Result<HeldOut, FoldsError> {
        for m in [Method::Hierarchy, Method::NearestSequence] {
            if let Some(e) = folds.iter().find_map(|f| f.error(m)) {
                return Err(FoldsError(e.to_string()));
            }
        }
        let summary = |m| {
            let ran: Vec<&FoldScores> = folds.iter().filter_map(|f| f.scores(m)).collect();
            HeldOutSummary::of(&ran)
        };
        let hsom = summary(Method::Hierarchy)
            .ok_or_else(|| FoldsError("held-out results: no folds (no demonstrations)".into()))?;
        Ok(HeldOut {
            hsom,
            gmr: summary(Method::GmmGmr),
            sequence: summary(Method::NearestSequence),
            promp: summary(Method::ProMP),
            dmp: summary(Method::Dmp),
            dba: summary(Method::Dba),
            folds,
        })
    }

    /// Both methods averaged over the same folds (those where GMM/GMR ran): (CoSCo-HSOM,
    /// GMM/GMR); `None` when GMM/GMR ran on none.
    pub fn paired(&self) -> Option<(HeldOutSummary, HeldOutSummary)> {
        self.paired_with(Method::GmmGmr)
    }

    /// CoSCo-HSOM and `other` averaged over the same folds, those where the other ran; `None`
    /// when it ran on none.
    pub fn paired_with(&self, other: Method) -> Option<(HeldOutSummary, HeldOutSummary)> {
        let (h, g): (Vec<&FoldScores>, Vec<&FoldScores>) = self
            .folds
            .iter()
            .filter_map(|f| Some((f.scores(Method::Hierarchy)?, f.scores(other)?)))
            .unzip();
        Some((HeldOutSummary::of(&h)?, HeldOutSummary::of(&g)?))
    }
}
