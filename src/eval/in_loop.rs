//! Held-out folds in the loop (`cosco heldout --disturb`, `--goal-moves`; docs/ALGORITHM.md,
//! section 11): on the folds of the undisturbed study (each demonstration held out in turn,
//! the methods learning from the others), each method's stepper runs in the kinematic loop
//! ([`crate::stepper::kinematic`]: the arm goes where it is commanded except while it is
//! disturbed) from the held-out demonstration's first posture, once undisturbed and once
//! disturbed. Per method and fold: the final error, the largest step after the release against
//! the held-out demonstration's largest step (a jump when above 2), the DTW of the executed
//! path without the disturbed ticks, whether it finished, and the swings.

use std::str::FromStr;
use std::sync::Arc;

use serde::Serialize;

use crate::condition::Conditions;
use crate::config::HsomConfig;
use crate::demos::{sample_period, Demonstration};
use crate::dtw::{dtw_distance, euclidean, Band};
use crate::metrics::column_swings;
use crate::stats::median;
use crate::stepper::kinematic::{largest_step, Disturbance};
use crate::stepper::Plant;
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

/// What the loop's folds are disturbed with.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum LoopDisturbance {
    /// `hold:P:D`: the arm held where it is from phase `at` for `share` of the duration.
    Hold {
        /// When, 0 to 1.
        at: f64,
        /// How long, a share of the duration.
        share: f64,
    },
    /// `move:P:D:K`: at phase `at` the arm moved `k` times the demonstrations' diagonal
    /// (along it: `k` times each variable's extent) and held there for `share`.
    Move {
        /// When, 0 to 1.
        at: f64,
        /// How long, a share of the duration.
        share: f64,
        /// How far, times the diagonal.
        k: f64,
    },
    /// `push:P:BODY:FX,FY,FZ:D`: from phase `at`, for `share` of the duration, the force
    /// `force` (N, the torso's frame) on the link `body` (the simulated arm only).
    Push {
        /// When, 0 to 1.
        at: f64,
        /// How long, a share of the duration.
        share: f64,
        /// The link (the model's body name).
        body: String,
        /// The force, N.
        force: [f64; 3],
    },
    /// `--goal-moves P:K`: at phase `at` the goal moved `k` times the diagonal from the
    /// undisturbed run's end (along the diagonal).
    Goal {
        /// When, 0 to 1.
        at: f64,
        /// How far, times the diagonal.
        k: f64,
    },
}

/// `TEXT` as `n` numbers separated by ':', each finite and >= 0, or the reason naming `what`.
fn numbers(text: &str, n: usize, what: &str) -> Result<Vec<f64>, String> {
    let v: Vec<f64> = text
        .split(':')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("{what} {text:?}: needs {n} numbers separated by ':'"))?;
    if v.len() != n || v.iter().any(|x| !(x.is_finite() && *x >= 0.0)) {
        return Err(format!(
            "{what} {text:?}: needs {n} finite numbers >= 0 separated by ':'"
        ));
    }
    Ok(v)
}

/// A phase from 0 to 1, or the reason naming `what`.
fn phase(at: f64, what: &str) -> Result<f64, String> {
    match at <= 1.0 {
        true => Ok(at),
        false => Err(format!(
            "{what}: the phase {at} is past 1 (0 is the start, 1 the end)"
        )),
    }
}

impl FromStr for LoopDisturbance {
    type Err = String;
    /// `hold:P:D` or `move:P:D:K` (`cosco heldout --disturb`).
    fn from_str(s: &str) -> Result<Self, String> {
        let what = "--disturb";
        match s.split_once(':') {
            Some(("hold", rest)) => {
                let v = numbers(rest, 2, what)?;
                Ok(LoopDisturbance::Hold {
                    at: phase(v[0], what)?,
                    share: v[1],
                })
            }
            Some(("move", rest)) => {
                let v = numbers(rest, 3, what)?;
                Ok(LoopDisturbance::Move {
                    at: phase(v[0], what)?,
                    share: v[1],
                    k: v[2],
                })
            }
            Some(("push", rest)) => {
                let usage = || {
                    format!(
                        "{what} {s:?}: needs push:P:BODY:FX,FY,FZ:D (a force in N on the link \
                         BODY from phase P for D of the duration)"
                    )
                };
                let [p, body, f, d] = rest.split(':').collect::<Vec<_>>()[..] else {
                    return Err(usage());
                };
                let v = numbers(&format!("{p}:{d}"), 2, what)?;
                let force: Vec<f64> = (f.split(','))
                    .map(|x| x.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
                    .collect::<Option<_>>()
                    .ok_or_else(usage)?;
                Ok(LoopDisturbance::Push {
                    at: phase(v[0], what)?,
                    share: v[1],
                    body: body.trim().to_string(),
                    force: force.try_into().map_err(|_| usage())?,
                })
            }
            _ => Err(format!(
                "{what} {s:?}: needs hold:P:D (held from phase P for D of the duration), \
                 move:P:D:K (moved K x the diagonal at phase P, held for D) or \
                 push:P:BODY:FX,FY,FZ:D (the simulated arm's link BODY pushed)"
            )),
        }
    }
}

impl LoopDisturbance {
    /// `--goal-moves P:K`.
    pub fn goal_moves(s: &str) -> Result<Self, String> {
        let what = "--goal-moves";
        let v = numbers(s, 2, what)?;
        Ok(LoopDisturbance::Goal {
            at: phase(v[0], what)?,
            k: v[1],
        })
    }

    /// Its name in the tables.
    pub fn name(&self) -> String {
        match self {
            LoopDisturbance::Hold { at, share } => {
                format!("held from phase {at} for {share} of the duration")
            }
            LoopDisturbance::Move { at, share, k } => {
                format!("moved {k} x the diagonal at phase {at}, held for {share}")
            }
            LoopDisturbance::Push {
                at,
                share,
                body,
                force,
            } => format!(
                "{body} pushed with ({}, {}, {}) N from phase {at} for {share}",
                force[0], force[1], force[2]
            ),
            LoopDisturbance::Goal { at, k } => {
                format!("goal moved {k} x the diagonal at phase {at}")
            }
        }
    }

    /// The kinematic loop's disturbance, for demonstrations spanning `extent` per variable,
    /// and the undisturbed run's end `end`.
    fn of(&self, extent: &[f64], end: &[f64]) -> Disturbance {
        let along = |k: f64| extent.iter().map(|e| k * e).collect::<Vec<f64>>();
        match *self {
            LoopDisturbance::Hold { at, share } => Disturbance::Hold { at, share },
            LoopDisturbance::Push {
                at,
                share,
                ref body,
                force,
            } => Disturbance::Push {
                at,
                body: body.clone(),
                force,
                share,
            },
            LoopDisturbance::Move { at, share, k } => Disturbance::Move {
                at,
                by: along(k),
                share,
            },
            LoopDisturbance::Goal { at, k } => Disturbance::Goal {
                at,
                goal: end.iter().zip(along(k)).map(|(e, d)| e + d).collect(),
            },
        }
    }
}

/// One method's run in the loop on one fold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LoopRun {
    /// The method.
    pub method: Method,
    /// The held-out demonstration.
    pub demonstration: String,
    /// Why it has no run (it cannot be fitted, cannot take the disturbance).
    pub error: Option<String>,
    /// The distance of the disturbed run's end from where it should end (the undisturbed
    /// run's end; with a moved goal, the goal), a share of the diagonal.
    pub final_error: f64,
    /// The largest step from the release (a moved goal: from its tick) over the held-out
    /// demonstration's largest step.
    pub jump: f64,
    /// DTW per step of the executed path without its disturbed ticks against the held-out
    /// demonstration, a share of the diagonal.
    pub relative_dtw: f64,
    /// The same of the undisturbed run.
    pub undisturbed_dtw: f64,
    /// Whether the stepper finished (said it was done before the tick limit).
    pub finished: bool,
    /// LElbowRoll's swings over the whole path, the disturbed ticks included (a pushed arm may
    /// go on swinging; a held one adds none): disturbed, undisturbed, the held-out
    /// demonstration's.
    pub swings: Option<[usize; 3]>,
    /// Times the stepper re-planned.
    pub replans: usize,
    /// How far the disturbance took the arm from where the undisturbed run had it, the largest
    /// over the disturbed ticks and the variables ([`crate::stepper::Trace::displaced_from`]), data units.
    pub displaced: f64,
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

/// `method` on one fold (learned from `train`, the held-out demonstration `target`),
/// undisturbed and then with each of `disturbances`: one run per disturbance.
#[allow(clippy::too_many_arguments)]
fn one(
    method: Method,
    learned: &Learned,
    train: &[Demonstration],
    target: &Demonstration,
    diag: f64,
    extent: &[f64],
    disturbances: &[LoopDisturbance],
    plant: &dyn Plant,
) -> Result<Vec<LoopRun>, String> {
    let initial = target.rows.first().ok_or("no samples")?;
    let period = sample_period(target);
    let none = Conditions::default();
    let make = || learned.stepper(method, train, initial, &none, period);
    let limit = 8 * target.rows.len().max(1) + 400;
    let plain =
        (plant.run(make()?.as_mut(), initial, &Disturbance::None, 1, limit)).map_err(text)?;
    let duration = plain.path.len().saturating_sub(1).max(1);
    let end = plain.path.last().ok_or("no path")?;
    let dtw = |rows: &[Vec<f64>]| -> Result<f64, String> {
        let c = dtw_distance(rows, &target.rows, Band::None).map_err(|e| e.to_string())?;
        Ok(c.per_step() / diag)
    };
    let swing_joint = crate::robot::Robot::of_columns(&target.columns).map(|r| r.swing_joint().0);
    let count = |rows: &[Vec<f64>]| -> Result<Option<usize>, String> {
        swing_joint
            .map(|j| column_swings(rows, j, SWING_MIN_AMPLITUDE_RAD).map_err(|e| e.to_string()))
            .transpose()
    };
    let (plain_swings, demo_swings) = (count(&plain.path)?, count(&target.rows)?);
    let undisturbed_dtw = dtw(&plain.path)?;
    let demo_step = largest_step(&target.rows, 1);
    let disturbed = |disturbance: &LoopDisturbance| -> Result<LoopRun, String> {
        let d = disturbance.of(extent, end);
        let mut s = make()?;
        let r = plant
            .run(s.as_mut(), initial, &d, duration, limit)
            .map_err(text)?;
        let should_end = match &d {
            Disturbance::Goal { goal, .. } => goal.clone(),
            _ => end.clone(),
        };
        let from = match disturbance {
            LoopDisturbance::Goal { at, .. } => (at * duration as f64).round() as usize + 1,
            _ => r.release.unwrap_or(1),
        };
        let swings = match (count(&r.path)?, plain_swings, demo_swings) {
            (Some(a), Some(b), Some(c)) => Some([a, b, c]),
            _ => None,
        };
        Ok(LoopRun {
            method,
            demonstration: target.source.clone(),
            error: None,
            final_error: euclidean(r.path.last().ok_or("no path")?, &should_end) / diag,
            jump: match demo_step > 0.0 {
                true => r.largest_step_from(from) / demo_step,
                false => f64::NAN,
            },
            relative_dtw: dtw(&r.free())?,
            undisturbed_dtw,
            finished: r.finished,
            swings,
            replans: s.replans(),
            displaced: r.displaced_from(&plain.path),
        })
    };
    Ok(disturbances
        .iter()
        .map(|d| disturbed(d).unwrap_or_else(|e| LoopRun::failed(method, target, e)))
        .collect())
}

impl LoopRun {
    /// The run of `method` on the fold of `target` that did not happen, and why.
    fn failed(method: Method, target: &Demonstration, why: String) -> LoopRun {
        LoopRun {
            method,
            demonstration: target.source.clone(),
            error: Some(why),
            final_error: f64::NAN,
            jump: f64::NAN,
            relative_dtw: f64::NAN,
            undisturbed_dtw: f64::NAN,
            finished: false,
            swings: None,
            replans: 0,
            displaced: f64::NAN,
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
    disturbances: &[LoopDisturbance],
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
                let r = learned.and_then(|l| {
                    one(
                        m,
                        &l,
                        &train,
                        target,
                        s.diagonal,
                        &extent,
                        disturbances,
                        plant,
                    )
                });
                r.unwrap_or_else(|e| {
                    let failed = LoopRun::failed(m, target, e);
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
pub fn loop_markdown(disturbance: &LoopDisturbance, gestures: &[GestureLoop]) -> String {
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
            med(|r| r.displaced),
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
    let mut out = format!("## In the loop: {}\n\n{t}\n", disturbance.name());
    for (m, w, n) in why {
        out.push_str(&format!("- {}: {w} ({n} folds)\n", m.name()));
    }
    if out.ends_with(")\n") {
        out.push('\n');
    }
    out
}
