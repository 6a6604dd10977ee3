//! A held-out study over gestures, seeds and configurations (`examples/heldout.rs`):
//! demonstrations recorded once per (gesture, seed) and reused for every configuration,
//! leave-one-out for CoSCo-HSOM, GMM/GMR and ProMP (the baselines do not depend on the
//! configuration: run once per set), optionally the in-sample result, and the per-level accuracy of a
//! hierarchy trained on the first three demonstrations. (gesture, seed) jobs run on worker
//! threads sharing one arm model.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use cosco_hsom::config::HsomConfig;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::fsutil::write_atomic;
use cosco_hsom::gesture::Gesture;
use cosco_hsom::hsom::LevelSummary;
use cosco_hsom::metrics::FidelityReport;
use cosco_hsom::sim::NaoArm;
pub use cosco_hsom::stats::median;

use cosco_hsom::eval::{FoldInput, FoldScores, HeldOut, HeldOutSummary, Method, Pool, Training};
use cosco_hsom::experiment::heldout::{folds, on_arm};
use cosco_hsom::experiment::{synthetic_demonstrations, DemoSettings, ExperimentError, Transition};

/// Demonstrations the per-level accuracy is measured on (the first ones of each set).
pub const LEVEL_DEMOS: usize = 3;

/// How the study runs.
#[derive(Debug, Clone, PartialEq)]
pub struct StudySettings {
    /// Demonstrations per (gesture, seed), at least 2.
    pub count: usize,
    /// Encoder noise of the synthetic demonstrations, rad.
    pub noise: f64,
    /// How CoSCo-HSOM's postures become servo targets.
    pub transition: Transition,
    /// Also learn from all and score against all (the in-sample result).
    pub in_sample: bool,
    /// Worker threads (at least 1).
    pub threads: usize,
}

/// The in-sample result of one set of demonstrations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InSample {
    /// CoSCo-HSOM learned from all, scored against all.
    pub hsom: FidelityReport,
    /// GMM/GMR the same way, when it ran.
    pub gmr: Option<FidelityReport>,
    /// Why GMM/GMR did not run.
    pub gmr_error: Option<String>,
}

/// One configuration on one (gesture, seed) set of demonstrations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StudyRow {
    /// Gesture name.
    pub gesture: String,
    /// Seed of the demonstrations.
    pub seed: u64,
    /// Leave-one-out for both methods.
    pub heldout: HeldOut,
    /// Learned from all, scored against all (with `in_sample`).
    pub in_sample: Option<InSample>,
    /// Levels of a hierarchy trained on the first `levels_demos` demonstrations.
    pub levels: Vec<LevelSummary>,
    /// Demonstrations that hierarchy learned from.
    pub levels_demos: usize,
}

/// Every row of one configuration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ConfigStudy {
    /// The configuration's source (file name).
    pub config: String,
    /// One row per (gesture, seed), in the order of the jobs.
    pub rows: Vec<StudyRow>,
}

/// The whole study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Study {
    /// Demonstrations per set.
    pub count: usize,
    /// Encoder noise, rad.
    pub noise: f64,
    /// Transition of CoSCo-HSOM's postures.
    pub transition: String,
    /// One entry per configuration, in the order given.
    pub configs: Vec<ConfigStudy>,
}

/// Everything one (gesture, seed) job computes: one row per configuration.
fn run_job(
    arm: &NaoArm,
    configs: &[HsomConfig],
    gesture: &Gesture,
    seed: u64,
    settings: &StudySettings,
) -> Result<Vec<StudyRow>, ExperimentError> {
    let demo_settings = DemoSettings {
        encoder_noise: settings.noise,
        ..DemoSettings::default()
    };
    let demos =
        synthetic_demonstrations(arm, gesture, settings.count, seed, &demo_settings, |_| {})?;
    // the baselines do not depend on the configuration: their folds once per set
    let baselines = [Method::GmmGmr, Method::ProMP, Method::Dmp, Method::Dba];
    let trained = Training::Trained;
    let baseline_folds = folds(arm, &demos, &baselines, None, trained, settings.transition)?;
    let gmr_in_sample = if settings.in_sample {
        Some(gmr_in_sample(arm, &demos))
    } else {
        None
    };
    let levels_demos = LEVEL_DEMOS.min(demos.len());
    configs
        .iter()
        .map(|config| {
            let methods = [Method::Hierarchy, Method::NearestSequence];
            let mut all = folds(
                arm,
                &demos,
                &methods,
                Some(config),
                trained,
                settings.transition,
            )?;
            for (f, b) in all.iter_mut().zip(&baseline_folds) {
                f.runs.extend(b.runs.iter().cloned());
            }
            let heldout = HeldOut::of(all)?;
            let in_sample = match &gmr_in_sample {
                Some(g) => {
                    let input = FoldInput {
                        config: Some(config),
                        ..FoldInput::new(&demos, &demos)
                    };
                    let run = on_arm(arm, settings.transition, Method::Hierarchy, &input)?;
                    Some(InSample {
                        hsom: run.executed.fidelity,
                        gmr: g.as_ref().ok().cloned(),
                        gmr_error: g.as_ref().err().cloned(),
                    })
                }
                None => None,
            };
            let model = config.fit(&demos[..levels_demos])?;
            Ok(StudyRow {
                gesture: gesture.name.to_string(),
                seed,
                heldout,
                in_sample,
                levels: model.summary().levels,
                levels_demos,
            })
        })
        .collect()
}

/// GMM/GMR learned from all `demos`, scored against all (the reason when it cannot run).
fn gmr_in_sample(arm: &NaoArm, demos: &[Demonstration]) -> Result<FidelityReport, String> {
    let input = FoldInput::new(demos, demos);
    on_arm(arm, Transition::Linear, Method::GmmGmr, &input)
        .map(|r| r.executed.fidelity)
        .map_err(|e| e.to_string())
}

/// Run the study: every (gesture, seed) of `jobs` on `settings.threads` worker threads (the
/// library's [`Pool`]), each set of demonstrations recorded once and used for every
/// configuration. `on_job_done(done, total)` is called after each job (from the worker
/// threads).
pub fn run_study(
    arm: &NaoArm,
    configs: &[HsomConfig],
    jobs: &[(Gesture, u64)],
    settings: &StudySettings,
    on_job_done: &(dyn Fn(usize, usize) + Sync),
) -> Result<Study, ExperimentError> {
    if settings.count < 2 {
        return Err(ExperimentError::Invalid(format!(
            "count = {}: leave-one-out needs at least 2 demonstrations per set",
            settings.count
        )));
    }
    if settings.threads == 0 {
        return Err(ExperimentError::Invalid(
            "threads = 0: need at least 1 worker thread".into(),
        ));
    }
    if configs.is_empty() || jobs.is_empty() {
        return Err(ExperimentError::Invalid(format!(
            "{} configurations and {} (gesture, seed) jobs: need at least one of each",
            configs.len(),
            jobs.len()
        )));
    }
    let pool = Pool::new(settings.threads).map_err(ExperimentError::Invalid)?;
    let slots = pool.map(
        jobs,
        |(gesture, seed)| {
            run_job(arm, configs, gesture, *seed, settings).map_err(|e| {
                ExperimentError::Invalid(format!("gesture {} seed {seed}: {e}", gesture.name))
            })
        },
        Some(on_job_done),
    );
    let mut configs_out: Vec<ConfigStudy> = configs
        .iter()
        .map(|c| ConfigStudy {
            config: c.source().to_string(),
            rows: Vec::with_capacity(jobs.len()),
        })
        .collect();
    for slot in slots {
        let rows = slot?;
        for (c, row) in configs_out.iter_mut().zip(rows) {
            c.rows.push(row);
        }
    }
    Ok(Study {
        count: settings.count,
        noise: settings.noise,
        transition: settings.transition.name(),
        configs: configs_out,
    })
}

/// The distinct `names`, in the order they first appear.
fn first_seen<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for n in names {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

fn number(v: Option<f64>, digits: usize) -> String {
    match v {
        Some(v) if v.is_finite() => format!("{v:.digits$}"),
        _ => "n/a".into(),
    }
}

/// What the held-out gates of issue 8 (its "How it is judged") need of one
/// (gesture, seed) set: the hierarchy's and GMM/GMR's means over the same folds, and per
/// fold the swings counted (hierarchy, held-out demonstration, nearest sequence).
#[derive(Debug, Clone, PartialEq)]
pub struct GateRow {
    /// Gesture name.
    pub gesture: String,
    /// Seed of the demonstrations.
    pub seed: u64,
    /// CoSCo-HSOM, means over every fold.
    pub hsom: HeldOutSummary,
    /// (CoSCo-HSOM, GMM/GMR) over the folds where GMM/GMR ran.
    pub paired: Option<(HeldOutSummary, HeldOutSummary)>,
    /// Per fold: (the hierarchy's swings, the held-out demonstration's, the nearest
    /// sequence's when it ran).
    pub swings: Vec<(usize, usize, Option<usize>)>,
}

impl GateRow {
    /// The gate row of a study row.
    pub fn of(r: &StudyRow) -> GateRow {
        GateRow {
            gesture: r.gesture.clone(),
            seed: r.seed,
            hsom: r.heldout.hsom.clone(),
            paired: r.heldout.paired(),
            swings: r
                .heldout
                .folds
                .iter()
                .filter_map(|f| {
                    let swings = |m| f.scores(m).and_then(|s: &FoldScores| s.swings.as_ref());
                    let h = swings(Method::Hierarchy)?;
                    let sequence = swings(Method::NearestSequence).map(|s| s.reproduction);
                    Some((h.reproduction, h.demo, sequence))
                })
                .collect(),
        }
    }
}

/// Demonstrated large swings per fold, on average, from which a gesture's count is a gate
/// (the wave: 6 half-swings; the other gestures 0-1).
pub const REPEATED_SWINGS: f64 = 2.0;

/// The shortest mean time at the apex of a set's held-out demonstrations (seconds,
/// `apex_dwell`) for which the apex hold is a gate: the Nao gestures that hold at their apex
/// (reading-watch 1.2 s, reach-point 0.9 s, salute 0.6 s nominal) stay there 1.0-2.3 s
/// measured, the wave, which does not hold, 0.3 s (the turn of one swing).
pub const HOLD_GATE_MIN_S: f64 = 0.5;

/// How far a set's apex hold may be from its held-out demonstrations' mean hold, as a
/// fraction of it (issue 8: within 25 %).
pub const HOLD_TOLERANCE: f64 = 0.25;

/// Folds of one repeated gesture whose swings match the held-out demonstration's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SwingGate {
    /// Gesture name.
    pub gesture: String,
    /// Folds where the hierarchy swings exactly as the held-out demonstration.
    pub hierarchy: usize,
    /// The same for the nearest sequence (`None` when it did not run on every fold).
    pub sequence: Option<usize>,
    /// Folds.
    pub folds: usize,
}

/// The held-out gates of issue 8 over one configuration's (gesture, seed) sets.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Gates {
    /// (gesture, seed) sets.
    pub sets: usize,
    /// Medians over the sets where GMM/GMR ran of the hierarchy's and GMM/GMR's joint DTW
    /// (rad/step) on the same folds: the goal is at most GMM/GMR's, 1.1x at the very worst.
    pub joint_dtw: Option<(f64, f64)>,
    /// The same for the wrist-path DTW (mm/step).
    pub wrist_dtw: Option<(f64, f64)>,
    /// Median duration ratio (the gate: 0.85-1.15).
    pub duration_ratio: Option<f64>,
    /// Sets whose mean velocity reversals exceed the demonstrations' mean + 1.
    pub reversals_above: Vec<(String, u64)>,
    /// Sets whose normalised jerk exceeds 2x the demonstrations'.
    pub jerk_above: Vec<(String, u64)>,
    /// Sets whose held-out demonstrations stay at their apex at least [`HOLD_GATE_MIN_S`] on
    /// average.
    pub hold_sets: usize,
    /// Of those, the median of the reproductions' mean time at the apex over the
    /// demonstrations'.
    pub hold_ratio: Option<f64>,
    /// Of those, the sets whose mean time at the apex is off the demonstrations' by more
    /// than [`HOLD_TOLERANCE`] of it.
    pub hold_off: Vec<(String, u64)>,
    /// Per gesture whose demonstrations swing at least [`REPEATED_SWINGS`] times on
    /// average: the folds that keep the count.
    pub swings: Vec<SwingGate>,
}

impl Gates {
    /// The gates over `rows`.
    pub fn of(rows: &[GateRow]) -> Gates {
        let paired: Vec<&(HeldOutSummary, HeldOutSummary)> =
            rows.iter().filter_map(|r| r.paired.as_ref()).collect();
        let both = |f: fn(&HeldOutSummary) -> Option<f64>| {
            let h = median(paired.iter().filter_map(|(h, _)| f(h)))?;
            let g = median(paired.iter().filter_map(|(_, g)| f(g)))?;
            Some((h, g))
        };
        let gestures = first_seen(rows.iter().map(|r| r.gesture.as_str()));
        let swings = gestures
            .iter()
            .filter_map(|g| {
                let folds: Vec<&(usize, usize, Option<usize>)> = rows
                    .iter()
                    .filter(|r| r.gesture == *g)
                    .flat_map(|r| &r.swings)
                    .collect();
                let demo = folds.iter().map(|f| f.1 as f64).sum::<f64>() / folds.len() as f64;
                (!folds.is_empty() && demo >= REPEATED_SWINGS).then(|| SwingGate {
                    gesture: g.to_string(),
                    hierarchy: folds.iter().filter(|f| f.0 == f.1).count(),
                    sequence: folds
                        .iter()
                        .map(|f| f.2.map(|s| usize::from(s == f.1)))
                        .sum::<Option<usize>>(),
                    folds: folds.len(),
                })
            })
            .collect();
        let above = |f: &dyn Fn(&HeldOutSummary) -> bool| {
            rows.iter()
                .filter(|r| f(&r.hsom))
                .map(|r| (r.gesture.clone(), r.seed))
                .collect()
        };
        let holding: Vec<&GateRow> = rows
            .iter()
            .filter(|r| r.hsom.demo_hold_s >= HOLD_GATE_MIN_S)
            .collect();
        let hold_ratio = |r: &GateRow| r.hsom.hold_s / r.hsom.demo_hold_s;
        Gates {
            sets: rows.len(),
            hold_sets: holding.len(),
            hold_ratio: median(holding.iter().map(|r| hold_ratio(r))),
            hold_off: holding
                .iter()
                .filter(|r| (hold_ratio(r) - 1.0).abs() > HOLD_TOLERANCE)
                .map(|r| (r.gesture.clone(), r.seed))
                .collect(),
            joint_dtw: both(|s| Some(s.joint_dtw_rad_per_step)),
            wrist_dtw: both(|s| s.wrist_dtw_mm),
            duration_ratio: median(rows.iter().map(|r| r.hsom.duration_ratio)),
            reversals_above: above(&|s| s.velocity_reversals > s.demo_velocity_reversals + 1.0),
            jerk_above: above(&|s| match (s.normalized_jerk, s.demo_normalized_jerk) {
                (Some(j), Some(d)) => j > 2.0 * d,
                _ => false,
            }),
            swings,
        }
    }

    /// The gates as a Markdown list, each with its figure and whether it is met.
    pub fn to_markdown(&self) -> String {
        let mut md = String::new();
        let fidelity = |what: &str, unit: &str, digits: usize, v: Option<(f64, f64)>| match v {
            Some((h, g)) if g > 0.0 => {
                let r = h / g;
                let verdict = if r <= 1.0 {
                    "met"
                } else if r <= 1.1 {
                    "within 1.1x, not at or below"
                } else {
                    "not met"
                };
                format!(
                    "- {what}: median {h:.digits$} {unit} against GMM/GMR's {g:.digits$} on the same \
                     folds ({r:.2}x; at or below, 1.1x at the very worst): {verdict}\n"
                )
            }
            _ => format!("- {what}: GMM/GMR did not run\n"),
        };
        md.push_str(&fidelity("joint DTW", "rad/step", 4, self.joint_dtw));
        md.push_str(&fidelity("wrist-path DTW", "mm/step", 2, self.wrist_dtw));
        let _ = writeln!(
            md,
            "- timing: median duration ratio {} (0.85-1.15): {}",
            number(self.duration_ratio, 2),
            match self.duration_ratio {
                Some(d) if (0.85..=1.15).contains(&d) => "met",
                Some(_) => "not met",
                None => "n/a",
            }
        );
        let list = |sets: &[(String, u64)]| {
            if sets.is_empty() {
                "none: met".to_string()
            } else {
                let named: Vec<String> = sets.iter().map(|(g, s)| format!("{g} {s}")).collect();
                format!("{} of {} sets: {}", sets.len(), self.sets, named.join(", "))
            }
        };
        let _ = writeln!(
            md,
            "- velocity reversals above the demonstrations' mean + 1: {}",
            list(&self.reversals_above)
        );
        let _ = writeln!(
            md,
            "- normalised jerk above 2x the demonstrations': {}",
            list(&self.jerk_above)
        );
        if self.hold_sets > 0 {
            let _ = writeln!(
                md,
                "- apex hold (the time at the apex, within a tenth of the amplitude of the key \
                 pose) against the held-out demonstrations' mean, over the {} sets whose \
                 demonstrations stay there {HOLD_GATE_MIN_S} s or more: median ratio {}; off by \
                 more than {:.0} %: {}",
                self.hold_sets,
                number(self.hold_ratio, 2),
                100.0 * HOLD_TOLERANCE,
                list(&self.hold_off)
            );
        }
        for g in &self.swings {
            let seq = g
                .sequence
                .map_or(String::new(), |s| format!(" (the nearest sequence {s})"));
            let _ = writeln!(
                md,
                "- {}: the held-out demonstration's swing count kept on {} of {} folds{seq}: {}",
                g.gesture,
                g.hierarchy,
                g.folds,
                if g.hierarchy == g.folds {
                    "met"
                } else {
                    "not met"
                }
            );
        }
        md
    }
}

impl ConfigStudy {
    /// The gates of issue 8 over this configuration's sets.
    pub fn gates(&self) -> Gates {
        Gates::of(&self.rows.iter().map(GateRow::of).collect::<Vec<_>>())
    }
}

impl Study {
    /// Every configuration's tables in Markdown.
    pub fn to_markdown(&self, in_sample: bool) -> String {
        let mut md = String::new();
        for c in &self.configs {
            let _ = writeln!(
                md,
                "## {}\n\nHeld-out (leave-one-out over {} demonstrations, encoder noise {} rad, \
                 transition {}): CoSCo-HSOM's means over the folds; GMM/GMR and ProMP on \
                 the same folds (those where each ran).\n",
                c.config, self.count, self.noise, self.transition
            );
            md.push_str(&c.table(in_sample));
            let levels_demos = c.rows.first().map_or(0, |r| r.levels_demos);
            let _ = writeln!(
                md,
                "\nPer level, a hierarchy trained on the first {levels_demos} demonstrations: \
                 prediction accuracy / lookup-table accuracy.\n"
            );
            md.push_str(&c.levels_table());
            let _ = writeln!(
                md,
                "\nThe held-out gates of issue 8 (its \"How it is judged\") over these {} \
                 sets:\n",
                c.rows.len()
            );
            md.push_str(&c.gates().to_markdown());
            md.push('\n');
        }
        md
    }

    /// Write every number as JSON to `path`, atomically: the study, and `gates`, each
    /// configuration's [`Gates`] in the order of `configs`.
    pub fn write_json(&self, path: &Path) -> std::io::Result<()> {
        #[derive(Serialize)]
        struct WithGates<'a> {
            #[serde(flatten)]
            study: &'a Study,
            gates: Vec<Gates>,
        }
        let out = WithGates {
            study: self,
            gates: self.configs.iter().map(ConfigStudy::gates).collect(),
        };
        let json = serde_json::to_vec_pretty(&out).map_err(std::io::Error::other)?;
        write_atomic(path, &json)
    }
}

#[path = "study/table.rs"]
mod table;
#[cfg(test)]
#[path = "study/tests.rs"]
mod tests;
