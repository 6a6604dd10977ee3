//! One fold of an evaluation: each method learns from the training demonstrations, produces
//! postures from the target's initial posture, and the executor carries them out and scores
//! them against the target.

use std::time::Instant;

use crate::config::HsomConfig;
use crate::demos::{sample_period, Demonstration};
use crate::gmr::{plan_at, GmrParams};
use crate::hsom::Hsom;
use crate::promp::PrompSettings;

use super::executor::{Executed, Executor};
use super::method::{Method, GMR_COMPONENTS};

/// Whether the hierarchy learns (the real thing) or keeps its seeded initial weights (the
/// negative control of every fidelity check).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Training {
    /// Train as configured.
    #[default]
    Trained,
    /// Initial weights only.
    Untrained,
}

/// One fold: what the methods learn from and whom they are scored against.
#[derive(Debug, Clone, Copy)]
pub struct FoldInput<'a> {
    /// The configuration of the hierarchy and of the nearest sequence (`None` when neither
    /// runs).
    pub config: Option<&'a HsomConfig>,
    /// The configuration at height 1 ([`Method::Height1`]; `None` when not run).
    pub height_1: Option<&'a HsomConfig>,
    /// Demonstrations to learn from.
    pub train: &'a [Demonstration],
    /// The demonstration whose first sample the methods start from and which they are scored
    /// against alone.
    pub target: &'a Demonstration,
    /// Whether the hierarchy (and height 1) learn, or keep their initial weights.
    pub training: Training,
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
}

/// Each method of a fold with its run, or the reason it produced none.
pub type FoldRuns<T> = Vec<(Method, Result<MethodRun<T>, String>)>;

/// The error and its causes on one line.
fn msg(e: impl std::error::Error + 'static) -> String {
    crate::app::error_line(&e)
}

/// Train with `config` (or only initialise, the negative control), timed.
fn fit(
    config: &HsomConfig,
    train: &[Demonstration],
    training: Training,
) -> Result<(Hsom, f64), String> {
    let t = Instant::now();
    let model = match training {
        Training::Trained => config.fit(train),
        Training::Untrained => config.initialise(train),
    }
    .map_err(msg)?;
    Ok((model, t.elapsed().as_secs_f64()))
}

/// Each of `methods` on one fold: learned from `input.train`, started from `input.target`'s
/// first sample, executed by `executor` and scored against `input.target`; in `methods`'
/// order, each with its run or the reason it produced none. The hierarchy and the nearest
/// sequence share one trained model.
pub fn run_fold<E: Executor>(
    methods: &[Method],
    input: &FoldInput<'_>,
    executor: &E,
) -> FoldRuns<E::Trace> {
    let (train, target) = (input.train, input.target);
    let Some(initial) = target.rows.first() else {
        let why = format!("{}: no samples", target.source);
        return methods.iter().map(|&m| (m, Err(why.clone()))).collect();
    };
    let mut model: Option<Result<(Hsom, f64), String>> = None;
    methods
        .iter()
        .map(|&method| {
            let produced = match method {
                Method::Hierarchy | Method::NearestSequence => {
                    let trained = model.get_or_insert_with(|| {
                        input
                            .config
                            .ok_or_else(|| "no configuration of the hierarchy given".to_string())
                            .and_then(|c| fit(c, train, input.training))
                    });
                    match trained {
                        Ok((m, train_s)) => {
                            let t = Instant::now();
                            let rep = match method {
                                Method::Hierarchy => m.reproduce(initial),
                                _ => m.follow_nearest(train, initial),
                            };
                            rep.map(|r| (r.postures, *train_s, t.elapsed().as_secs_f64()))
                                .map_err(msg)
                        }
                        Err(e) => Err(e.clone()),
                    }
                }
                Method::Height1 => input
                    .height_1
                    .ok_or_else(|| "no configuration at height 1 given".to_string())
                    .and_then(|h1| fit(h1, train, input.training))
                    .and_then(|(m, train_s)| {
                        let t = Instant::now();
                        let rep = m.reproduce(initial).map_err(msg)?;
                        Ok((rep.postures, train_s, t.elapsed().as_secs_f64()))
                    }),
                Method::GmmGmr => {
                    let period = sample_period(target);
                    let t = Instant::now();
                    GmrParams::new()
                        .components(GMR_COMPONENTS)
                        .sample_period(period)
                        .check()
                        .and_then(|p| p.fit(train))
                        .and_then(|m| {
                            let train_s = t.elapsed().as_secs_f64();
                            let t = Instant::now();
                            let speed = executor.gmr_lead_in_speed(train, period);
                            plan_at(&m, initial, 1.0 / period, speed)
                                .map(|p| (p.postures, train_s, t.elapsed().as_secs_f64()))
                        })
                        .map_err(msg)
                }
                Method::ProMP => {
                    let t = Instant::now();
                    PrompSettings::default()
                        .fit(train)
                        .and_then(|m| {
                            let train_s = t.elapsed().as_secs_f64();
                            let t = Instant::now();
                            m.reproduce(initial)
                                .map(|p| (p, train_s, t.elapsed().as_secs_f64()))
                        })
                        .map_err(msg)
                }
                Method::Replay => {
                    let start = |d: &Demonstration| crate::dtw::euclidean(&d.rows[0], initial);
                    train
                        .iter()
                        .min_by(|a, b| start(a).total_cmp(&start(b)))
                        .map(|d| (d.rows.clone(), 0.0, 0.0))
                        .ok_or_else(|| "no training demonstration".to_string())
                }
            };
            let run = produced.and_then(|(postures, train_s, reproduce_s)| {
                let executed = executor.execute(method, &postures, target)?;
                Ok(MethodRun {
                    postures,
                    executed,
                    train_s,
                    reproduce_s,
                })
            });
            (method, run)
        })
        .collect()
}
