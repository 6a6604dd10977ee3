//! Held-out folds in the loop (`cosco heldout --disturb`, `--goal-moves`; docs/ALGORITHM.md,
//! section 11): on the folds of the undisturbed study (each demonstration held out in turn,
//! the methods learning from the others), each method's stepper runs in the kinematic loop
//! ([`crate::stepper::kinematic`]: the arm goes where it is commanded except while it is
//! disturbed) from the held-out demonstration's first posture, once undisturbed and once
//! disturbed. Per method and fold: the final error, the largest step after the release against
//! the held-out demonstration's largest step (a jump when above 2), the DTW of the executed
//! path without the disturbed ticks, whether it finished, and the swings.

use std::sync::Arc;

use serde::Serialize;

use crate::condition::Conditions;
use crate::config::HsomConfig;
use crate::demos::{sample_period, Demonstration};
use crate::dtw::{dtw_distance, euclidean, Band};
use crate::metrics::column_swings;
use crate::stats::median;
use crate::stepper::kinematic::largest_step;
use crate::stepper::{Amount, Clock, Disturbance, Kind, Plant, Stepper, Trace};
use crate::table::Table;

use super::fold::{all_but, Split, SWING_MIN_AMPLITUDE_RAD};
use super::learned::Learned;
use super::loo::loo_map;
use super::method::{Method, GMR_COMPONENTS};
use super::results::GestureLoo;
use super::Pool;

/// The largest step after the release, over the held-out demonstration's largest step, above
/// which a run jumps.
pub const JUMP_RATIO: f64 = 2.0;
/// The final error, a share of the diagonal, within which a run ends where it should.
pub const FINAL_SHARE: f64 = 0.02;

/// One method's run in the loop: on a held-out fold (`cosco heldout --disturb`), or on the
/// simulated arm from the demonstrations' first posture (`simulate --loop closed`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoopRun {
    /// The method.
    pub method: Method,
    /// The held-out demonstration (the first one on the simulated arm).
    pub demonstration: String,
    /// Why it has no run (it cannot be fitted, cannot take the disturbance).
    pub error: Option<String>,
    /// The distance of the disturbed run's end from where it should end (the undisturbed
    /// run's end; with a moved goal, the goal), a share of the diagonal.
    pub final_error: f64,
    /// The largest step from the last release (or the goal's move, the later) over the
    /// demonstrations' largest step.
    pub jump: f64,
    /// DTW per step of the executed path without its disturbed ticks against the
    /// demonstrations (mean), a share of the diagonal.
    pub relative_dtw: f64,
    /// The same of the undisturbed run.
    pub undisturbed_dtw: f64,
    /// Whether the stepper finished (said it was done, the arm free, before the tick limit).
    pub finished: bool,
    /// LElbowRoll's swings over the whole path, the disturbed ticks included (a pushed arm may
    /// go on swinging; a held one adds none): disturbed, undisturbed, the (first)
    /// demonstration's.
    pub swings: Option<[usize; 3]>,
    /// Times the stepper re-planned.
    pub replans: usize,
    /// Per disturbance, how far it took the arm from where the undisturbed run had it
    /// ([`crate::stepper::Trace::displaced`]), data units (in the JSON of a fold's run, which
    /// has one, a number).
    #[serde(serialize_with = "first")]
    pub displaced: Vec<f64>,
    /// Whether the reading changes what it commands.
    #[serde(skip)]
    pub closed_loop: bool,
    /// The disturbed run's duration, s.
    #[serde(skip)]
    pub seconds: f64,
}

/// The first of `v` (none: null).
fn first<S: serde::Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
    v.first().copied().unwrap_or(f64::NAN).serialize(s)
}

/// The loop's runs of one gesture: per fold, one per method.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GestureLoop {
    /// The gesture.
    pub gesture: String,
    /// Per held-out fold, one run per method.
    pub folds: Vec<Vec<LoopRun>>,
}

/// The methods that step: the hierarchy, the nearest sequence, ProMP, the DMP, GMM/GMR.
pub const LOOP_METHODS: [Method; 5] = [
    Method::Hierarchy,
    Method::NearestSequence,
    Method::ProMP,
    Method::Dmp,
    Method::GmmGmr,
];

/// `e` as one line.
fn text(e: impl std::error::Error + 'static) -> String {
    crate::errors::error_line(&e)
}

/// What a method's runs in the loop are scored against.
pub struct Against<'d> {
    /// The demonstrations: the DTW is the mean over them, the jump over their largest step;
    /// the first's swings are counted beside the runs'.
    pub demos: &'d [Demonstration],
    /// Their diagonal.
    pub diagonal: f64,
    /// Their extent per variable (what `k` x the diagonal moves each by).
    pub extent: Vec<f64>,
    /// The column whose swings are counted (LElbowRoll), if any.
    pub swing_joint: Option<usize>,
}

/// A method's runs in the loop ([`method_runs`]): the undisturbed one, and per set of
/// disturbances the run scored with its trace, or why it did not run.
pub type Runs = (Trace, Vec<Result<(LoopRun, Trace), String>>);

/// The one loop study of a method, whichever the plant: `make`'s stepper (of `method`) run
/// on `plant` from `initial` for at most `limit` ticks of `tick_s` seconds, undisturbed and
/// then with each set of `sets` (amounts times the diagonal taken from `against`'s extent and
/// the undisturbed run's end; phases, shares of the undisturbed run's ticks), each scored
/// against `against`.
#[allow(clippy::too_many_arguments)]
pub fn method_runs<'s>(
    method: Method,
    make: &dyn Fn() -> Result<Box<dyn Stepper + 's>, String>,
    plant: &dyn Plant,
    initial: &[f64],
    against: &Against,
    sets: &[Vec<Disturbance>],
    limit: usize,
    tick_s: f64,
) -> Result<Runs, String> {
    let plain = (plant.run(make()?.as_mut(), initial, &[], 1, limit)).map_err(text)?;
    let duration = plain.path.len().saturating_sub(1).max(1);
    let end = plain.path.last().ok_or("no path")?.clone();
    let diag = against.diagonal;
    let dtw = |rows: &[Vec<f64>]| -> Result<f64, String> {
        let costs = (against.demos.iter())
            .map(|d| dtw_distance(rows, &d.rows, Band::None).map(|c| c.per_step() / diag))
            .collect::<Result<Vec<f64>, _>>()
            .map_err(|e| e.to_string())?;
        Ok(costs.iter().sum::<f64>() / costs.len().max(1) as f64)
    };
    let count = |rows: &[Vec<f64>]| -> Result<Option<usize>, String> {
        (against.swing_joint)
            .map(|j| column_swings(rows, j, SWING_MIN_AMPLITUDE_RAD).map_err(|e| e.to_string()))
            .transpose()
    };
    let demo_rows = against.demos.first().map_or(&[][..], |d| &d.rows[..]);
    let (plain_swings, demo_swings) = (count(&plain.path)?, count(demo_rows)?);
    let undisturbed_dtw = dtw(&plain.path)?;
    let demo_step = (against.demos.iter())
        .map(|d| largest_step(&d.rows, 1))
        .fold(0.0, f64::max);
    let disturbed = |set: &Vec<Disturbance>| -> Result<(LoopRun, Trace), String> {
        let set: Vec<Disturbance> = set
            .iter()
            .map(|d| d.absolute(&against.extent, &end))
            .collect();
        let mut s = make()?;
        let r = (plant.run(s.as_mut(), initial, &set, duration, limit)).map_err(text)?;
        let goal = set.iter().rev().find_map(|d| match &d.kind {
            Kind::Goal(Amount::Absolute(g)) => Some((d, g)),
            _ => None,
        });
        let should_end = goal.map_or(&end, |(_, g)| g);
        let moved = goal.map_or(1, |(d, _)| {
            let at = match d.clock {
                Clock::Phase => d.at * duration as f64,
                Clock::Seconds => d.at / tick_s,
            };
            at.round() as usize + 1
        });
        let swings = match (count(&r.path)?, plain_swings, demo_swings) {
            (Some(a), Some(b), Some(c)) => Some([a, b, c]),
            _ => None,
        };
        let run = LoopRun {
            method,
            demonstration: (against.demos.first()).map_or(String::new(), |d| d.source.clone()),
            error: None,
            final_error: euclidean(r.path.last().ok_or("no path")?, should_end) / diag,
            jump: match demo_step > 0.0 {
                true => r.largest_step_from(r.release.unwrap_or(1).max(moved)) / demo_step,
                false => f64::NAN,
            },
            relative_dtw: dtw(&r.free())?,
            undisturbed_dtw,
            finished: r.finished,
            swings,
            replans: s.replans(),
            displaced: r.displaced(&plain.path),
            closed_loop: s.closed_loop(),
            seconds: (r.path.len() - 1) as f64 * tick_s,
        };
        Ok((run, r))
    };
    let runs = sets.iter().map(disturbed).collect();
    Ok((plain, runs))
}

/// `method` on one fold (learned from `train`, the held-out demonstration `target`),
/// undisturbed and then with each of `disturbances`: one run per disturbance.
fn one(
    method: Method,
    learned: &Learned,
    train: &[Demonstration],
    target: &Demonstration,
    against: &Against,
    disturbances: &[Disturbance],
    plant: &dyn Plant,
) -> Result<Vec<LoopRun>, String> {
    let initial = target.rows.first().ok_or("no samples")?;
    let period = sample_period(target);
    let none = Conditions::default();
    let make = || learned.stepper(method, train, initial, &none, period);
    let limit = 8 * target.rows.len().max(1) + 400;
    let sets: Vec<Vec<Disturbance>> = disturbances.iter().map(|d| vec![d.clone()]).collect();
    let (_, runs) = method_runs(method, &make, plant, initial, against, &sets, limit, period)?;
    Ok((runs.into_iter())
        .map(|r| {
            r.map_or_else(
                |e| LoopRun::failed(method, &target.source, e),
                |(run, _)| run,
            )
        })
        .collect())
}

impl LoopRun {
    /// The run of `method` (on the fold of `demonstration`) that did not happen, and why.
    pub fn failed(method: Method, demonstration: &str, why: String) -> LoopRun {
        LoopRun {
            method,
            demonstration: demonstration.to_string(),
            error: Some(why),
            final_error: f64::NAN,
            jump: f64::NAN,
            relative_dtw: f64::NAN,
            undisturbed_dtw: f64::NAN,
            finished: false,
            swings: None,
            replans: 0,
            displaced: Vec::new(),
            closed_loop: false,
            seconds: f64::NAN,
        }
    }
}

/// Every method of `methods` that steps, in the loop on every held-out fold of `study`'s
/// gestures (their demonstrations and diagonals), undisturbed and with each of
/// `disturbances`: each method as its fold kept it ([`super::Fold::learned`]), else learned
/// once a fold (the hierarchy and the nearest sequence with `config`). Folds run on `pool`
/// ([`loo_map`]); a method that cannot run holds the reason. Per disturbance, its runs.
pub fn in_loop(
    config: &HsomConfig,
    study: &[GestureLoo],
    methods: &[Method],
    disturbances: &[Disturbance],
    plant: &dyn Plant,
    pool: &Pool,
) -> Vec<Vec<GestureLoop>> {
    let methods: Vec<Method> = (methods.iter().copied())
        .filter(|m| LOOP_METHODS.contains(m))
        .collect();
    let sets: Vec<&[Demonstration]> = study.iter().map(|s| &s.demonstrations[..]).collect();
    // per set, per held-out fold, per method, per disturbance
    let runs = loo_map(&sets, false, pool, None, |g, split| {
        let (s, Split::HeldOut(i)) = (&study[g], split) else {
            return Vec::new();
        };
        let demos = &s.demonstrations;
        let (train, target) = (all_but(demos, i), &demos[i]);
        let extent: Vec<f64> = (0..target.width())
            .map(|j| {
                let col = demos.iter().flat_map(|d| d.rows.iter().map(move |r| r[j]));
                let (lo, hi) = col.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                });
                hi - lo
            })
            .collect();
        let against = Against {
            demos: std::slice::from_ref(target),
            diagonal: s.diagonal,
            extent,
            swing_joint: crate::robot::Robot::of_columns(&target.columns)
                .map(|r| r.swing_joint().0),
        };
        // what the study's fold learned, else learned here (once a fold)
        let kept = s.held_out.get(i).map(|f| &f.learned);
        let period = sample_period(target);
        let mut model = None;
        let mut hsom = |_| {
            let fit = || Ok((Arc::new(config.fit(&train).map_err(text)?), 0.0));
            model.get_or_insert_with(fit).clone()
        };
        (methods.iter())
            .map(|&m| {
                let learned = match kept.and_then(|k| k.get(m)) {
                    Some(l) => Ok(l.clone()),
                    None => Learned::fit(m, &train, period, GMR_COMPONENTS, &mut hsom)
                        .map(|(l, _)| Arc::new(l)),
                };
                let r =
                    learned.and_then(|l| one(m, &l, &train, target, &against, disturbances, plant));
                r.unwrap_or_else(|e| {
                    let failed = LoopRun::failed(m, &target.source, e);
                    vec![failed; disturbances.len()]
                })
            })
            .collect::<Vec<Vec<LoopRun>>>()
    });
    (0..disturbances.len())
        .map(|d| {
            (study.iter().zip(&runs))
                .map(|(s, (held_out, _))| GestureLoop {
                    gesture: s.gesture.clone(),
                    folds: (held_out.iter())
                        .map(|per_method| per_method.iter().map(|r| r[d].clone()).collect())
                        .collect(),
                })
                .collect()
        })
        .collect()
}

/// The loop's table: per method over every fold, how many ran and finished, ended within
/// [`FINAL_SHARE`] of the diagonal, did not jump ([`JUMP_RATIO`]), made at least the
/// undisturbed run's swings, and the median relative DTW disturbed (without the disturbed ticks) and
/// undisturbed.
pub fn loop_markdown(disturbance: &Disturbance, gestures: &[GestureLoop]) -> String {
    let mut t = Table::new([
        "method",
        "folds run",
        "finished",
        "final error within 2 % of the diagonal",
        "no jump (largest step after release <= 2 x the demonstration's)",
        "swings kept (at least as undisturbed)",
        "relative DTW disturbed (median)",
        "relative DTW undisturbed (median)",
        "displaced from the undisturbed run (median, largest over the variables)",
    ]);
    let methods: Vec<Method> = gestures
        .iter()
        .flat_map(|g| g.folds.iter().flatten().map(|r| r.method))
        .fold(Vec::new(), |mut v, m| {
            if !v.contains(&m) {
                v.push(m);
            }
            v
        });
    for m in methods {
        let all: Vec<&LoopRun> = (gestures.iter())
            .flat_map(|g| g.folds.iter().flatten())
            .filter(|r| r.method == m)
            .collect();
        let ran: Vec<&&LoopRun> = all.iter().filter(|r| r.error.is_none()).collect();
        let count = |f: &dyn Fn(&LoopRun) -> bool| ran.iter().filter(|r| f(r)).count();
        let with_swings: Vec<[usize; 3]> = ran.iter().filter_map(|r| r.swings).collect();
        let med = |f: fn(&LoopRun) -> f64| {
            median(ran.iter().map(|r| f(r)))
                .map_or_else(|| "n/a".to_string(), |v| format!("{v:.4}"))
        };
        t.row([
            m.name().to_string(),
            format!("{} of {}", ran.len(), all.len()),
            format!("{}", count(&|r| r.finished)),
            format!("{}", count(&|r| r.final_error <= FINAL_SHARE)),
            format!("{}", count(&|r| r.jump <= JUMP_RATIO)),
            match with_swings.is_empty() {
                true => "n/a".to_string(),
                false => format!(
                    "{} of {}",
                    with_swings.iter().filter(|s| s[0] >= s[1]).count(),
                    with_swings.len()
                ),
            },
            med(|r| r.relative_dtw),
            med(|r| r.undisturbed_dtw),
            med(|r| r.displaced.first().copied().unwrap_or(f64::NAN)),
        ]);
    }
    // why a method did not run, each reason once with the folds it stopped
    let mut why: Vec<(Method, String, usize)> = Vec::new();
    for r in gestures.iter().flat_map(|g| g.folds.iter().flatten()) {
        if let Some(e) = &r.error {
            match why.iter_mut().find(|(m, w, _)| *m == r.method && w == e) {
                Some(w) => w.2 += 1,
                None => why.push((r.method, e.clone(), 1)),
            }
        }
    }
    let mut out = format!("## In the loop: {}\n\n{t}\n", disturbance.describe());
    for (m, w, n) in why {
        out.push_str(&format!("- {}: {w} ({n} folds)\n", m.name()));
    }
    if out.ends_with(")\n") {
        out.push('\n');
    }
    out
}
