//! One fold of an evaluation: each method learns from the training demonstrations, produces
//! postures from the first target's initial posture, and the executor carries them out and
//! scores them against the targets. Held out and in-sample are two [`Split`]s of the same
//! [`run_fold`]; [`fold`] scores every run of a split into a [`Fold`].

use std::borrow::Cow;
use std::sync::Arc;

use crate::aim::{Aim, Aimed};
use crate::condition::{Conditions, ConfidenceBand};
use crate::config::HsomConfig;
use crate::curve::at_phase;
use crate::demos::{sample_period, Demonstration};
use crate::dtw::{dtw, euclidean, Band};
use crate::gmr::ComponentChoice;
use crate::hsom::Hsom;
use crate::metrics::{column_swings, trimmed_normalized_jerk, MetricsParams, StartEndReference};
use crate::robot::{arm_ranges, Robot};

use super::executor::{Executed, Executor};
use super::learned::{msg, timed, Fitted, Kept, Learned, Planned};
use super::method::{Method, GMR_COMPONENTS};
use super::results::{Commanded, ConditionErrors, Fold, FoldScores, Run, Score, Swings};

/// Smallest excursion between turning points that counts as a swing, rad.
pub const SWING_MIN_AMPLITUDE_RAD: f64 = 0.3;

/// Whether the hierarchy learns (the real thing) or keeps its seeded initial weights (the
/// negative control of every fidelity check).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Training {
    /// Train as configured.
    #[default]
    Trained,
    /// Initial weights only.
    Untrained,
    /// In two sittings: the first half of the training demonstrations (rounded down, at
    /// least one), then an update with the rest ([`Hsom::update`]); GMM/GMR, ProMP, the DMP,
    /// the nearest sequence and the replay refit on what a model keeps of the first half
    /// ([`crate::hsom::kept_demonstrations`]) and the rest.
    Sittings,
}

impl Training {
    /// What the methods other than the hierarchy learn from under this training: `train`
    /// itself, or in sittings what a model keeps of its first half and its second half.
    fn refit<'t>(self, train: &'t [Demonstration], seed: u64) -> Cow<'t, [Demonstration]> {
        match self {
            Training::Sittings => {
                let (first, rest) = train.split_at(sitting(train.len()));
                let mut kept = crate::hsom::kept_demonstrations(first, seed);
                kept.extend_from_slice(rest);
                Cow::Owned(kept)
            }
            _ => Cow::Borrowed(train),
        }
    }
}

/// How many of `n` training demonstrations the first sitting learns from: half, rounded
/// down, at least one.
pub fn sitting(n: usize) -> usize {
    (n / 2).max(1).min(n)
}

/// Which demonstrations of a set a fold learns from and which it is scored against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Split {
    /// Learn from all but demonstration `i`; start from it and score against it alone.
    HeldOut(usize),
    /// Learn from all; start from demonstration `i` and score against it alone.
    InSample(usize),
    /// Learn from all; start from the first and score against each of them (the in-sample
    /// result of the simulated arm's reports).
    InSampleAll,
}

impl Split {
    /// The training demonstrations and the targets of this split of `demos`.
    pub fn of(self, demos: &[Demonstration]) -> (Cow<'_, [Demonstration]>, &[Demonstration]) {
        match self {
            Split::HeldOut(i) => (Cow::Owned(all_but(demos, i)), one(demos, i)),
            Split::InSample(i) => (Cow::Borrowed(demos), one(demos, i)),
            Split::InSampleAll => (Cow::Borrowed(demos), demos),
        }
    }
}

/// What a fold's reproductions are conditioned on besides the held-out demonstration's
/// initial posture (`cosco heldout --condition`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum Conditioning {
    /// The initial posture only.
    #[default]
    #[serde(rename = "none")]
    Unconditioned,
    /// Also the held-out demonstration's last posture, as the goal.
    #[serde(rename = "end")]
    End,
    /// Also its last posture and its posture at phase 0.5, as a via-point.
    #[serde(rename = "end+mid")]
    EndMid,
}

impl Conditioning {
    /// The name on the command line (`none` unconditioned).
    pub fn name(self) -> &'static str {
        match self {
            Conditioning::Unconditioned => "none",
            Conditioning::End => "end",
            Conditioning::EndMid => "end+mid",
        }
    }

    /// The conditions on a reproduction scored against `target` (none for a target without
    /// samples).
    pub fn of(self, target: &Demonstration) -> Conditions {
        let Some(last) = target.rows.last() else {
            return Conditions::default();
        };
        let mut c = Conditions::default();
        if self != Conditioning::Unconditioned {
            c.goal = Some(last.clone());
        }
        if self == Conditioning::EndMid {
            c.via.push(crate::condition::ViaPoint {
                phase: 0.5,
                posture: at_phase(&target.rows, 0.5),
            });
        }
        c
    }
}

/// Why GMM/GMR produces nothing on a conditioned fold.
pub const GMR_UNCONDITIONED: &str = "GMM/GMR cannot be conditioned on a goal or a via-point: \
    its regression gives each instant a mean and a covariance, but no covariance across \
    instants through which a condition at one instant could move the others";

fn one(demos: &[Demonstration], i: usize) -> &[Demonstration] {
    demos.get(i..=i).unwrap_or_default()
}

/// Fold `i`'s training demonstrations: all but `demos[i]`.
pub fn all_but(demos: &[Demonstration], i: usize) -> Vec<Demonstration> {
    demos
        .iter()
        .enumerate()
        .filter(|&(j, _)| j != i)
        .map(|(_, d)| d.clone())
        .collect()
}

pub use crate::metrics::diagonal;

/// One fold: what the methods learn from, how, and whom they are scored against.
#[derive(Clone, Copy)]
pub struct FoldInput<'a> {
    /// The configuration of the hierarchy and of the nearest sequence (`None` when neither
    /// runs).
    pub config: Option<&'a HsomConfig>,
    /// The configuration at height 1 ([`Method::Height1`]; `None` when not run).
    pub height_1: Option<&'a HsomConfig>,
    /// Demonstrations to learn from.
    pub train: &'a [Demonstration],
    /// The demonstrations the methods are scored against; they start from the first one's
    /// first sample, at its sample period.
    pub targets: &'a [Demonstration],
    /// Whether the hierarchy (and height 1) learn, or keep their initial weights.
    pub training: Training,
    /// What the reproductions are conditioned on besides the first target's first sample
    /// (its last posture, its posture at phase 0.5).
    pub conditioning: Conditioning,
    /// A far goal ([`fold`]: each split's target moved by [`far_target`] with this `K`, and
    /// the reproductions conditioned on its end), `None` for none.
    ///
    /// [`far_target`]: super::far_target
    pub far: Option<f64>,
    /// GMM/GMR's choice of the number of components.
    pub gmr_components: ComponentChoice,
    /// Called with `(done, total)` as the hierarchy trains.
    pub progress: Option<&'a dyn Fn(usize, usize)>,
    /// Keep what the methods learned in the [`Fold`] ([`Fold::learned`]), for the loop study.
    pub keep: bool,
    /// The hierarchy's reproduction retimed to this many seconds, its path kept
    /// ([`crate::export::limits::at_duration`]; `None`: its own tempo).
    pub duration: Option<f64>,
    /// What the hierarchy's reproduction points and looks at during its held part
    /// ([`crate::aim::aim_conditions`]: via-points through the aimed posture, solved on its
    /// reproduction through the fold's conditions alone), before any retiming (empty: not
    /// aimed).
    pub aim: Aim,
}

impl<'a> FoldInput<'a> {
    /// Learn from `train` and score against `targets`: no configuration, trained,
    /// [`GMR_COMPONENTS`], no progress.
    pub fn new(train: &'a [Demonstration], targets: &'a [Demonstration]) -> FoldInput<'a> {
        FoldInput {
            config: None,
            height_1: None,
            train,
            targets,
            training: Training::Trained,
            conditioning: Conditioning::Unconditioned,
            far: None,
            gmr_components: GMR_COMPONENTS,
            progress: None,
            keep: false,
            duration: None,
            aim: Aim::default(),
        }
    }
}

/// A method's run on one fold.
#[derive(Debug, Clone)]
pub struct MethodRun<T> {
    /// The postures the method produced, before execution.
    pub postures: Vec<Vec<f64>>,
    /// What the executor made of them.
    pub executed: Executed<T>,
    /// Training time, seconds (the hierarchy's for the nearest sequence, which uses its model).
    pub train_s: f64,
    /// Time to produce the postures, seconds.
    pub reproduce_s: f64,
    /// What the hierarchy or GMM/GMR learned (`None` for the other methods).
    pub fitted: Option<Fitted>,
    /// What the postures were conditioned on besides the initial posture.
    pub conditions: Conditions,
    /// The central 95 % band about the postures, for the methods that give one (the
    /// hierarchy, the nearest sequence and height 1 from their training paths; GMM/GMR and
    /// ProMP their own).
    pub band: Option<ConfidenceBand>,
    /// What the method learned (`None` for a run made otherwise).
    pub learned: Option<Arc<Learned>>,
    /// What the hierarchy's postures were aimed at, solved ([`FoldInput::aim`]; `None` when
    /// not aimed), its held part in rows of `postures`.
    pub aimed: Option<Aimed>,
}

/// Each method of a fold with its run, or the reason it produced none.
pub type FoldRuns<T> = Vec<(Method, Result<MethodRun<T>, String>)>;

/// Why a fold without a target has no run.
const NO_TARGET: &str = "no demonstration to score against";

/// Train with `config` (or only initialise, the negative control), timed.
fn fit(
    config: &HsomConfig,
    input: &FoldInput<'_>,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<(Arc<Hsom>, f64), String> {
    // one gesture's model: its one branch
    let fit = |demos, untrained| {
        let how = crate::hsom::Fit {
            progress,
            untrained,
        };
        config
            .fit_model(demos, how)
            .map(|m| m.branches()[0].clone())
    };
    let (model, s) = timed(|| match input.training {
        Training::Trained => fit(input.train, false),
        Training::Untrained => fit(input.train, true),
        Training::Sittings => {
            let (first, rest) = input.train.split_at(sitting(input.train.len()));
            fit(first, false).and_then(|m| Ok(m.update(rest)?))
        }
    });
    Ok((Arc::new(model.map_err(msg)?), s))
}

/// Each of `methods` on one fold: learned from `input.train` ([`Learned::fit`]), planned from
/// the first target's first sample, executed by `executor` and scored against
/// `input.targets`; in `methods`' order, each with its run or the reason it produced none. The
/// hierarchy and the nearest sequence share one trained model.
pub fn run_fold<E: Executor>(
    methods: &[Method],
    input: &FoldInput<'_>,
    executor: &E,
) -> FoldRuns<E::Trace> {
    let seed = input.config.map_or(0, |c| c.params().seed);
    let refit = input.training.refit(input.train, seed);
    let train = &refit[..];
    let first = input.targets.first();
    let Some((target, initial)) = first.and_then(|t| t.rows.first().map(|r| (t, r))) else {
        let why = first.map_or_else(
            || NO_TARGET.to_string(),
            |t| format!("{}: no samples", t.source),
        );
        return methods.iter().map(|&m| (m, Err(why.clone()))).collect();
    };
    let conditions = input.conditioning.of(target);
    let period = sample_period(target);
    let mut model: Option<Result<(Arc<Hsom>, f64), String>> = None;
    let mut hsom = |method| match method {
        Method::Height1 => {
            let h1 = input.height_1.ok_or("no configuration at height 1 given")?;
            fit(h1, input, None)
        }
        _ => model
            .get_or_insert_with(|| {
                input
                    .config
                    .ok_or_else(|| "no configuration of the hierarchy given".to_string())
                    .and_then(|c| fit(c, input, input.progress))
            })
            .clone(),
    };
    let mut run = |method| -> Result<MethodRun<E::Trace>, String> {
        if method == Method::GmmGmr && !conditions.points().is_empty() {
            return Err(GMR_UNCONDITIONED.to_string());
        }
        let (learned, train_s) =
            Learned::fit(method, train, period, input.gmr_components, &mut hsom)?;
        let speed = executor.gmr_lead_in_speed(train, period);
        let mut p = learned.plan(method, train, initial, &conditions, period, speed)?;
        let (mut used, mut aimed) = (conditions.clone(), None);
        if method == Method::Hierarchy && !input.aim.is_empty() {
            let (c, a) = aim_conditions(&target.columns, initial, &conditions, &input.aim, &p)?;
            let q = learned.plan(method, train, initial, &c, period, speed)?;
            p = Planned {
                reproduce_s: p.reproduce_s + q.reproduce_s,
                ..q
            };
            (used, aimed) = (c, Some(a));
        }
        if let (Method::Hierarchy, Some(d)) = (method, input.duration) {
            let len = p.postures.len();
            p = p.at_duration(&target.columns, period, d)?;
            aimed = aimed.map(|a| retimed_span(a, len, p.postures.len()));
        }
        let executed = executor.execute(method, &p.postures, input.targets)?;
        Ok(MethodRun {
            postures: p.postures,
            executed,
            train_s,
            reproduce_s: p.reproduce_s,
            fitted: p.fitted,
            conditions: used,
            band: p.band,
            learned: Some(Arc::new(learned)),
            aimed,
        })
    };
    methods.iter().map(|&m| (m, run(m))).collect()
}

/// `conditions` and the via-points that aim `plan` (the hierarchy's reproduction from
/// `initial` through `conditions` alone, of the variables `columns`) at `aim`
/// ([`crate::aim::aim_conditions`]), with what was solved; checked as `cosco reproduce
/// --point-at` checks them (against the robot's joint ranges). Refused when `columns` are not
/// a robot's joints.
fn aim_conditions(
    columns: &[String],
    initial: &[f64],
    conditions: &Conditions,
    aim: &Aim,
    plan: &Planned,
) -> Result<(Conditions, Aimed), String> {
    let robot = Robot::of_columns(columns).ok_or_else(|| {
        format!(
            "--point-at and --look-at aim through a Nao's kinematics: the demonstrations' variables are {}, not the joints of the left arm or the upper body",
            columns.join(", ")
        )
    })?;
    let (aimed, solved) =
        crate::aim::aim_conditions(robot, &plan.postures, conditions, aim).map_err(msg)?;
    (aimed.check(columns, Some(&robot.ranges()), initial)).map_err(msg)?;
    Ok((aimed, solved))
}

/// `aimed` with its held part in rows of the reproduction of `len` rows retimed to `n` rows
/// (the same path read at another pace: row `i` is at row `i (n - 1) / (len - 1)`).
fn retimed_span(aimed: Aimed, len: usize, n: usize) -> Aimed {
    let at = |i: usize| {
        let scaled = (i * (n - 1)) as f64 / (len - 1).max(1) as f64;
        (scaled.round() as usize).min(n - 1)
    };
    Aimed {
        span: (at(aimed.span.0), at(aimed.span.1)),
        ..aimed
    }
}

/// Every metric of `run` (executed by `executor`) against its first target, the motion's and
/// the commanded postures' start and end judged against the demonstrations it learned from
/// (`train`) in a gesture of bounding-box diagonal `diag`.
pub fn fold_scores<E: Executor>(
    run: &MethodRun<E::Trace>,
    executor: &E,
    train: &[Demonstration],
    target: &Demonstration,
    diag: f64,
) -> Result<FoldScores, String> {
    let reference = StartEndReference::of(train, diag);
    let metrics = MetricsParams {
        sample_period: sample_period(target),
        ..MetricsParams::default()
    };
    let dt = metrics.sample_period;
    let executed = &run.executed;
    let motion = executor.motion(executed);
    let start_end = reference.judge(motion, dt, executed.fidelity.final_error_rad.mean);
    let commanded = match (executed.commanded.last(), target.rows.last()) {
        (Some(c), Some(h)) => Some(Commanded {
            postures: executed.commanded.len(),
            normalized_jerk: trimmed_normalized_jerk(&executed.commanded, &metrics),
            start_end: reference.judge(&executed.commanded, dt, euclidean(c, h)),
        }),
        _ => None,
    };
    // without the arm's executor, data of its joints still count LElbowRoll's swings
    let arm_swing = || crate::robot::Robot::of_columns(&target.columns).map(|r| r.swing_joint());
    let swings = match executor.swing_joint().or_else(arm_swing) {
        Some((j, name)) => {
            let count = |rows: &[Vec<f64>]| {
                column_swings(rows, j, SWING_MIN_AMPLITUDE_RAD).map_err(|e| e.to_string())
            };
            Some(Swings {
                joint: name.to_string(),
                min_amplitude_rad: SWING_MIN_AMPLITUDE_RAD,
                reproduction: count(motion)?,
                demo: count(&target.rows)?,
            })
        }
        None => None,
    };
    let coverage = match &run.band {
        Some(b) if b.len() == run.postures.len() && !target.rows.is_empty() => {
            let path = dtw(&run.postures, &target.rows, Band::None).map_err(|e| e.to_string())?;
            Some(b.coverage(&target.rows, &path.path))
        }
        _ => None,
    };
    let out_of_range = arm_ranges(&target.columns).map(|ranges| {
        (run.postures.iter().flat_map(|r| r.iter().zip(&ranges)))
            .filter(|(v, (lo, hi))| !(lo..=hi).contains(v))
            .count()
    });
    Ok(FoldScores {
        swings,
        out_of_range,
        conditions: ConditionErrors::of(&run.conditions, &run.postures),
        coverage,
        postures: run.postures.len(),
        clamped_values: executed.clamped_values,
        train_s: run.train_s,
        reproduce_s: run.reproduce_s,
        start_end: Some(start_end),
        commanded,
        fidelity: executed.fidelity.clone(),
    })
}

/// A method's run (or the reason it has none) as a [`Run`]: its every metric
/// ([`fold_scores`]) against the first of `targets` and its [`Score`] in the gesture's
/// diagonal `diag`.
pub fn scored<E: Executor>(
    method: Method,
    run: Result<MethodRun<E::Trace>, String>,
    executor: &E,
    train: &[Demonstration],
    targets: &[Demonstration],
    diag: f64,
) -> Run {
    let scores = run.and_then(|r| {
        let target = targets.first().ok_or_else(|| NO_TARGET.to_string())?;
        Ok((fold_scores(&r, executor, train, target, diag)?, r))
    });
    match scores {
        Ok((s, r)) => Run {
            method,
            score: (s.start_end.as_ref()).map(|se| Score::of(&s.fidelity, diag, se).with(&s, diag)),
            error: None,
            postures: r.postures,
            band: r.band,
            scores: Some(s),
        },
        Err(e) => Run::failed(method, e),
    }
}

/// `methods` on split `split` of `demos` (learned as `base` says: configuration, height 1,
/// training, GMM/GMR's components), every run scored against the split's first target in the
/// diagonal `diag` of the set.
pub fn fold<E: Executor>(
    methods: &[Method],
    base: &FoldInput<'_>,
    demos: &[Demonstration],
    split: Split,
    diag: f64,
    executor: &E,
) -> Fold {
    let (train, targets) = split.of(demos);
    // a far goal: the target moved, and the reproduction conditioned on its end
    let moved: Vec<Demonstration> = match base.far {
        Some(k) => targets
            .iter()
            .map(|t| super::far_target(&train, t, k))
            .collect(),
        None => Vec::new(),
    };
    let (targets, conditioning) = match base.far {
        Some(_) => (&moved[..], Conditioning::End),
        None => (targets, base.conditioning),
    };
    let input = FoldInput {
        train: &train,
        targets,
        conditioning,
        ..*base
    };
    let runs = run_fold(methods, &input, executor);
    let kept = (runs.iter().filter(|_| base.keep))
        .filter_map(|(m, r)| Some((*m, r.as_ref().ok()?.learned.clone()?)))
        .collect();
    Fold {
        demonstration: targets
            .first()
            .map_or_else(String::new, |t| t.source.clone()),
        runs: (runs.into_iter())
            .map(|(m, r)| scored(m, r, executor, &train, targets, diag))
            .collect(),
        learned: Kept(kept),
    }
}
