//! The main job's report: `report.json` (everything, machine-readable) and `report.md` (the
//! same for people: tables of every fidelity metric, side by side for each method or variant).

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use crate::fsutil::write_atomic;
use crate::metrics::{FidelityReport, Smoothness, Stat};

use crate::eval::{FoldScores, HeldOut, HeldOutSummary, Method, SWING_MIN_AMPLITUDE_RAD};
use crate::hsom::Hsom;
use crate::sim::JOINT_NAMES;
use crate::sim::SWING_JOINT;

/// One demonstration used for training.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DemoInfo {
    /// File (relative to the output directory) or source.
    pub file: String,
    /// Number of samples.
    pub samples: usize,
    /// Duration, seconds.
    pub duration_s: f64,
}

/// How one method (or variant of a method) did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodResult {
    /// Short name, e.g. `CoSCo-HSOM` or `GMM/GMR`.
    pub name: String,
    /// What the method needs as input (pre-processing, time index, initial posture).
    pub needs: String,
    /// Fidelity of the executed trajectory against each demonstration.
    pub fidelity: FidelityReport,
    /// Training (fitting) time, seconds.
    pub train_s: f64,
    /// Time to produce the postures to execute, seconds.
    pub reproduce_s: f64,
    /// Size of the saved model, bytes.
    pub model_bytes: u64,
    /// Number of postures the method produced.
    pub postures: usize,
    /// Posture values outside a joint's range, clamped before execution (0 = none).
    pub clamped_values: usize,
    /// Anything else worth a line (why the reproduction stopped, components chosen, ...).
    pub notes: Vec<String>,
    /// Held-out (leave-one-out) means, when evaluated.
    pub heldout: Option<HeldOutSummary>,
}

/// One level of a trained hierarchy: how many nodes it uses and how well it predicts the
/// level below, beside the lookup-table baseline (`hsom::LevelSummary`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LevelRow {
    /// Level (0 = bottom).
    pub level: usize,
    /// Nodes of the map (rows x cols).
    pub nodes: usize,
    /// Nodes that are the best match of some training input.
    pub nodes_used: usize,
    /// Fraction of the next entries of the level below predicted exactly (0 for level 0).
    pub prediction_accuracy: f64,
    /// The same for a "next entry given the last entry" lookup table.
    pub lookup_accuracy: f64,
    /// `prediction_accuracy` held out: each training demonstration's entries predicted by
    /// the levels trained on the others ([`crate::hsom::LevelSummary`]).
    pub heldout_prediction_accuracy: f64,
    /// `lookup_accuracy` held out the same way.
    pub heldout_lookup_accuracy: f64,
    /// Whether reproduction may plan from this level (levels above 1: only when it beats
    /// the lookup table; [`Hsom::level_trusted`]).
    pub used_in_reproduction: bool,
}

/// The levels of `model`, bottom first.
pub fn level_rows(model: &Hsom) -> Vec<LevelRow> {
    model
        .summary()
        .levels
        .iter()
        .map(|l| LevelRow {
            level: l.level,
            nodes: l.rows * l.cols,
            nodes_used: l.nodes_used,
            prediction_accuracy: l.prediction_accuracy,
            lookup_accuracy: l.lookup_accuracy,
            heldout_prediction_accuracy: l.heldout_prediction_accuracy,
            heldout_lookup_accuracy: l.heldout_lookup_accuracy,
            used_in_reproduction: l.used_in_reproduction,
        })
        .collect()
}

/// Wall time of one stage of the job.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Stage {
    /// What was done.
    pub stage: String,
    /// Seconds.
    pub seconds: f64,
}

/// Everything the main job found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Title line.
    pub title: String,
    /// Gesture name when the demonstrations were synthetic.
    pub gesture: Option<String>,
    /// Seed of every random choice.
    pub seed: u64,
    /// Configuration file of the hierarchy.
    pub config: String,
    /// The training demonstrations.
    pub demos: Vec<DemoInfo>,
    /// The methods compared, the main one first.
    pub methods: Vec<MethodResult>,
    /// Variants of the main method (beyond-the-paper options switched on and off).
    pub variants: Vec<MethodResult>,
    /// Held-out (leave-one-out) evaluation of both methods, every fold.
    pub heldout: Option<HeldOut>,
    /// Why the held-out evaluation did not run (when it did not).
    pub heldout_note: Option<String>,
    /// The levels of the main model.
    pub levels: Vec<LevelRow>,
    /// Wall time per stage.
    pub stages: Vec<Stage>,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
}

fn stat(s: &Stat, digits: usize) -> String {
    format!("{:.*} / {:.*}", digits, s.mean, digits, s.worst)
}

fn opt_stat(s: &Option<Stat>, digits: usize) -> String {
    s.as_ref()
        .map_or_else(|| "n/a".to_string(), |s| stat(s, digits))
}

/// A markdown table with one column per result: every fidelity metric (mean / worst over the
/// demonstrations), smoothness, and costs.
pub fn comparison_table(results: &[MethodResult]) -> String {
    let mut t = String::new();
    let _ = write!(t, "| metric (mean / worst) |");
    for r in results {
        let _ = write!(t, " {} |", r.name);
    }
    let _ = write!(t, "\n|---|");
    for _ in results {
        let _ = write!(t, "---|");
    }
    t.push('\n');
    let demo_jerk = results
        .first()
        .map(|r| {
            let v: Vec<f64> = r
                .fidelity
                .demo_smoothness
                .iter()
                .filter_map(|s| s.normalized_jerk)
                .collect();
            if v.is_empty() {
                f64::NAN
            } else {
                v.iter().sum::<f64>() / v.len() as f64
            }
        })
        .unwrap_or(f64::NAN);
    let demo_rev = results
        .first()
        .map(|r| {
            let v: Vec<usize> = r
                .fidelity
                .demo_smoothness
                .iter()
                .map(|s| s.total_reversals)
                .collect();
            if v.is_empty() {
                f64::NAN
            } else {
                v.iter().sum::<usize>() as f64 / v.len() as f64
            }
        })
        .unwrap_or(f64::NAN);
    type Row<'a> = (&'a str, Box<dyn Fn(&MethodResult) -> String>);
    let rows: Vec<Row> = vec![
        (
            "joint DTW (rad/step)",
            Box::new(|r| stat(&r.fidelity.joint_dtw_rad_per_step, 4)),
        ),
        (
            "wrist-path DTW (mm/step)",
            Box::new(|r| opt_stat(&r.fidelity.wrist_dtw_mm, 1)),
        ),
        (
            "apex error (rad)",
            Box::new(|r| stat(&r.fidelity.apex_error_rad, 3)),
        ),
        (
            "final-posture error (rad)",
            Box::new(|r| stat(&r.fidelity.final_error_rad, 3)),
        ),
        (
            "duration ratio",
            Box::new(|r| stat(&r.fidelity.duration_ratio, 2)),
        ),
        (
            "normalized jerk (demos' mean in brackets)",
            Box::new(move |r| {
                let j = r.fidelity.reproduction_smoothness.normalized_jerk;
                format!(
                    "{} ({demo_jerk:.0})",
                    j.map_or("n/a".into(), |j| format!("{j:.0}"))
                )
            }),
        ),
        (
            "velocity reversals, all joints (demos' mean)",
            Box::new(move |r| {
                format!(
                    "{} ({demo_rev:.1})",
                    r.fidelity.reproduction_smoothness.total_reversals
                )
            }),
        ),
        (
            "velocity reversals per joint",
            Box::new(|r| {
                let v: Vec<String> = r
                    .fidelity
                    .reproduction_smoothness
                    .reversals
                    .iter()
                    .map(|n| n.to_string())
                    .collect();
                v.join(" ")
            }),
        ),
        (
            "reproduction duration (s)",
            Box::new(|r| format!("{:.2}", r.fidelity.reproduction_duration_s)),
        ),
        ("postures produced", Box::new(|r| r.postures.to_string())),
        ("clamped values", Box::new(|r| r.clamped_values.to_string())),
        (
            "training time (s)",
            Box::new(|r| format!("{:.3}", r.train_s)),
        ),
        (
            "reproduction time (s)",
            Box::new(|r| format!("{:.4}", r.reproduce_s)),
        ),
        (
            "model size (bytes)",
            Box::new(|r| r.model_bytes.to_string()),
        ),
        ("needs as input", Box::new(|r| r.needs.clone())),
    ];
    for (name, f) in rows {
        let _ = write!(t, "| {name} |");
        for r in results {
            let _ = write!(t, " {} |", f(r));
        }
        t.push('\n');
    }
    t
}

fn num(v: Option<f64>, digits: usize) -> String {
    match v {
        Some(v) if v.is_finite() => format!("{v:.digits$}"),
        _ => "n/a".into(),
    }
}

/// Mean over the demonstrations of one smoothness figure (`None` when none has it).
fn demo_mean(s: &[Smoothness], f: impl Fn(&Smoothness) -> Option<f64>) -> Option<f64> {
    let v: Vec<f64> = s.iter().filter_map(f).collect();
    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
}

/// A markdown table with one row per result: the in-sample mean (over the demonstrations)
/// beside the held-out mean (over the leave-one-out folds) of every fidelity metric, and
/// the held-out large swings of LElbowRoll. `n/a` where a figure was not computed.
pub fn heldout_table(results: &[MethodResult]) -> String {
    let mut t = format!(
        "| method (in-sample / held-out) | folds | joint DTW (rad/step) | wrist-path DTW \
         (mm/step) | apex error (rad) | final-posture error (rad) | duration ratio | \
         normalized jerk (demos') | velocity reversals (demos') | {} swings > {} rad, \
         held-out (demo) |\n|---|---|---|---|---|---|---|---|---|---|\n",
        JOINT_NAMES[SWING_JOINT], SWING_MIN_AMPLITUDE_RAD
    );
    for r in results {
        t.push_str(&heldout_row(&r.name, Some(&r.fidelity), r.heldout.as_ref()));
    }
    t
}

/// One row of [`heldout_table`]: `name`'s in-sample fidelity `f` (`n/a` without one: a method
/// evaluated held out only) beside its held-out means `h`.
pub fn heldout_row(name: &str, f: Option<&FidelityReport>, h: Option<&HeldOutSummary>) -> String {
    let pair = |a: Option<f64>, b: Option<f64>, digits: usize| {
        format!("{} / {}", num(a, digits), num(b, digits))
    };
    let fm = |g: fn(&FidelityReport) -> Option<f64>| f.and_then(g);
    let demo_jerk = f.and_then(|f| demo_mean(&f.demo_smoothness, |s| s.normalized_jerk));
    let demo_rev =
        f.and_then(|f| demo_mean(&f.demo_smoothness, |s| Some(s.total_reversals as f64)));
    format!(
        "| {} | {} | {} | {} | {} | {} | {} | {} ({}) | {} ({}) | {} |\n",
        name,
        h.map_or("n/a".into(), |h| h.folds.to_string()),
        pair(
            fm(|f| Some(f.joint_dtw_rad_per_step.mean)),
            h.map(|h| h.joint_dtw_rad_per_step),
            4
        ),
        pair(
            fm(|f| f.wrist_dtw_mm.map(|w| w.mean)),
            h.and_then(|h| h.wrist_dtw_mm),
            1
        ),
        pair(
            fm(|f| Some(f.apex_error_rad.mean)),
            h.map(|h| h.apex_error_rad),
            3
        ),
        pair(
            fm(|f| Some(f.final_error_rad.mean)),
            h.map(|h| h.final_error_rad),
            3
        ),
        pair(
            fm(|f| Some(f.duration_ratio.mean)),
            h.map(|h| h.duration_ratio),
            2
        ),
        pair(
            fm(|f| f.reproduction_smoothness.normalized_jerk),
            h.and_then(|h| h.normalized_jerk),
            0
        ),
        pair(demo_jerk, h.and_then(|h| h.demo_normalized_jerk), 0),
        pair(
            fm(|f| Some(f.reproduction_smoothness.total_reversals as f64)),
            h.map(|h| h.velocity_reversals),
            1
        ),
        pair(demo_rev, h.map(|h| h.demo_velocity_reversals), 1),
        h.map_or("n/a".into(), |h| format!(
            "{} ({})",
            num(Some(h.swings), 1),
            num(Some(h.demo_swings), 1)
        )),
    )
}

/// ProMP's name in the report's tables (held out only: no in-sample column).
pub const PROMP_NAME: &str = "ProMP (held out only)";

/// A markdown table with one row per `(name, held-out summary)`: where the reproductions start
/// and end against the folds' training demonstrations and how smooth they are, the motion the
/// arm executed beside the postures the method handed the servos (docs/METRICS.md, "Start and
/// end"). `n/a` where a figure was not computed.
pub fn start_end_table(rows: &[(&str, &HeldOutSummary)]) -> String {
    let pct = |v: Option<f64>| v.map_or("n/a".into(), |v| format!("{:.0} %", 100.0 * v));
    let mut t = String::from(
        "| method (executed / commanded) | folds | start speed (rad/s) | training demos' \
         largest start speed (rad/s) | start in range | end within spread | normalized jerk \
         (held-out demos') |\n|---|---|---|---|---|---|---|\n",
    );
    for (name, h) in rows {
        let _ = writeln!(
            t,
            "| {name} | {} | {} / {} | {} | {} / {} | {} / {} | {} / {} ({}) |",
            h.folds,
            num(h.start_speed, 3),
            num(h.commanded_start_speed, 3),
            num(h.demo_start_speed_max, 3),
            pct(h.start_in_range),
            pct(h.commanded_start_in_range),
            pct(h.end_within_spread),
            pct(h.commanded_end_within_spread),
            num(h.normalized_jerk, 0),
            num(h.commanded_normalized_jerk, 0),
            num(h.demo_normalized_jerk, 0),
        );
    }
    t
}

/// A markdown table of every fold: the held-out demonstration and both methods' scores
/// against it, the nearest-sequence baseline's joint DTW and swings, and ProMP's joint DTW,
/// final error and swings (`n/a` when one was not run).
pub fn folds_table(h: &HeldOut) -> String {
    let mut t = String::from(
        "| fold | held out | CoSCo-HSOM joint DTW | wrist DTW | apex | final | duration ratio \
         | swings (demo) | GMM/GMR joint DTW | wrist DTW | apex | final | duration ratio \
         | swings | nearest-sequence joint DTW | swings | ProMP joint DTW | final | swings \
         |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let swings = |s: &FoldScores, demo: bool| {
        s.swings.as_ref().map_or("n/a".to_string(), |w| {
            (if demo { w.demo } else { w.reproduction }).to_string()
        })
    };
    for (i, f) in h.folds.iter().enumerate() {
        let Some(hsom) = f.scores(Method::Hierarchy) else {
            continue;
        };
        let scores = |s: &FoldScores| {
            let r = &s.fidelity;
            format!(
                "{:.4} | {} | {:.3} | {:.3} | {:.2}",
                r.joint_dtw_rad_per_step.mean,
                num(r.wrist_dtw_mm.map(|w| w.mean), 1),
                r.apex_error_rad.mean,
                r.final_error_rad.mean,
                r.duration_ratio.mean
            )
        };
        let gmr = match (f.scores(Method::GmmGmr), f.error(Method::GmmGmr)) {
            (Some(g), _) => format!("{} | {}", scores(g), swings(g, false)),
            (None, e) => format!("not run: {} | | | | | ", e.unwrap_or("no reason given")),
        };
        let sequence = f
            .scores(Method::NearestSequence)
            .map_or("n/a | n/a".into(), |s| {
                format!(
                    "{:.4} | {}",
                    s.fidelity.joint_dtw_rad_per_step.mean,
                    swings(s, false)
                )
            });
        let promp = match (f.scores(Method::ProMP), f.error(Method::ProMP)) {
            (Some(p), _) => format!(
                "{:.4} | {:.3} | {}",
                p.fidelity.joint_dtw_rad_per_step.mean,
                p.fidelity.final_error_rad.mean,
                swings(p, false)
            ),
            (None, Some(e)) => format!("not run: {e} | | "),
            (None, None) => "n/a | n/a | n/a".into(),
        };
        let _ = writeln!(
            t,
            "| {} | {} | {} | {} ({}) | {gmr} | {sequence} | {promp} |",
            i + 1,
            f.demonstration,
            scores(hsom),
            swings(hsom, false),
            swings(hsom, true)
        );
    }
    t
}

/// A markdown table of a model's levels: nodes used, prediction accuracy, lookup-table
/// accuracy, both in-sample and held out.
pub fn levels_table(levels: &[LevelRow]) -> String {
    let mut t = String::from(
        "| level | nodes used / nodes | prediction accuracy | lookup-table accuracy | held out: prediction | held out: lookup table | plans in reproduction |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for l in levels {
        let _ = writeln!(
            t,
            "| {} | {} / {} | {:.3} | {:.3} | {:.3} | {:.3} | {} |",
            l.level,
            l.nodes_used,
            l.nodes,
            l.prediction_accuracy,
            l.lookup_accuracy,
            l.heldout_prediction_accuracy,
            l.heldout_lookup_accuracy,
            crate::hsom::plans_word(l.level, l.used_in_reproduction)
        );
    }
    t
}

impl Report {
    /// The report for people.
    pub fn to_markdown(&self) -> String {
        let mut md = String::new();
        let _ = writeln!(md, "# {}\n", self.title);
        if let Some(g) = &self.gesture {
            let _ = writeln!(md, "- gesture: `{g}` (synthetic demonstrations recorded from the simulated encoders at 40 Hz)");
        }
        let _ = writeln!(md, "- seed: {}", self.seed);
        let _ = writeln!(md, "- configuration: `{}`", self.config);
        let _ = writeln!(md, "- demonstrations:");
        for d in &self.demos {
            let _ = writeln!(
                md,
                "  - `{}`: {} samples, {:.2} s",
                d.file, d.samples, d.duration_s
            );
        }
        let _ = writeln!(
            md,
            "\nEvery metric is computed on the trajectory executed by the simulated arm, against \
             each demonstration (idle start and end trimmed), and given as mean / worst. \
             Definitions: docs/METRICS.md.\n"
        );
        let _ = writeln!(md, "## Methods side by side\n");
        md.push_str(&comparison_table(&self.methods));
        for m in &self.methods {
            for n in &m.notes {
                let _ = writeln!(md, "- {}: {n}", m.name);
            }
        }
        match &self.heldout {
            None if self.heldout_note.is_none() => {}
            Some(h) => {
                let _ = writeln!(md, "\n## Held-out (leave-one-out)\n");
                let _ = writeln!(
                    md,
                    "Each demonstration in turn is held out: the method learns from the \
                     others, reproduces from the held-out demonstration's initial posture and \
                     is scored against that demonstration only. In-sample: learned from all, \
                     scored against all (the table above). Means; held-out over the folds.\n"
                );
                md.push_str(&heldout_table(&self.methods));
                if let Some(p) = &h.promp {
                    md.push_str(&heldout_row(PROMP_NAME, None, Some(p)));
                }
                if let Some(s) = &h.sequence {
                    let _ = writeln!(
                        md,
                        "\nNearest-sequence baseline (the same CoSCo-HSOM model's bottom code \
                         following the bottom events of the training demonstration that starts \
                         nearest, no level above; docs/ALGORITHM.md), held out over {} folds: \
                         joint DTW {} rad/step, wrist-path DTW {} mm/step, duration ratio {}, \
                         {} swings {} ({}).",
                        s.folds,
                        num(Some(s.joint_dtw_rad_per_step), 4),
                        num(s.wrist_dtw_mm, 1),
                        num(Some(s.duration_ratio), 2),
                        JOINT_NAMES[SWING_JOINT],
                        num(Some(s.swings), 1),
                        num(Some(s.demo_swings), 1)
                    );
                }
                let _ = writeln!(
                    md,
                    "\nStart, end and smoothness, held out: the motion the arm executed beside \
                     the postures the method handed the servos (clamped into the joint ranges, \
                     shaped by the transition). Start in range: the first step no faster than \
                     the fastest first step of the fold's training demonstrations; end within \
                     spread: the final error at most 2 x the mean distance between their last \
                     postures, or 1 % of the gesture's diagonal.\n"
                );
                let mut rows: Vec<(&str, &HeldOutSummary)> = vec![("CoSCo-HSOM", &h.hsom)];
                rows.extend(h.gmr.as_ref().map(|g| ("GMM/GMR", g)));
                rows.extend(h.promp.as_ref().map(|p| (PROMP_NAME, p)));
                rows.extend(h.sequence.as_ref().map(|s| ("nearest sequence", s)));
                md.push_str(&start_end_table(&rows));
                let _ = writeln!(md);
                md.push_str(&folds_table(h));
            }
            None => {
                let _ = writeln!(
                    md,
                    "\n## Held-out (leave-one-out)\n\nNot run: {}",
                    self.heldout_note.as_deref().unwrap_or_default()
                );
            }
        }
        if !self.levels.is_empty() {
            let _ = writeln!(
                md,
                "\n## Levels of the CoSCo-HSOM model\n\nPrediction accuracy: fraction of \
                 the next entries of the level below predicted exactly from the partial list \
                 on the training data; lookup-table accuracy: the same for a table of \"next \
                 entry given the last entry\" (the baseline a level must beat).\n"
            );
            md.push_str(&levels_table(&self.levels));
        }
        if !self.variants.is_empty() {
            let _ = writeln!(
                md,
                "\n## CoSCo-HSOM variants: before and after the beyond-the-paper options\n"
            );
            if self.variants.iter().any(|v| v.heldout.is_some()) {
                let _ = writeln!(md, "In-sample / held-out (leave-one-out) means:\n");
                md.push_str(&heldout_table(&self.variants));
                let _ = writeln!(md, "\nHeld out, start, end and smoothness:\n");
                let rows: Vec<(&str, &HeldOutSummary)> = self
                    .variants
                    .iter()
                    .filter_map(|v| v.heldout.as_ref().map(|h| (v.name.as_str(), h)))
                    .collect();
                md.push_str(&start_end_table(&rows));
                let _ = writeln!(md, "\nIn-sample, every metric:\n");
            }
            md.push_str(&comparison_table(&self.variants));
            for m in &self.variants {
                for n in &m.notes {
                    let _ = writeln!(md, "- {}: {n}", m.name);
                }
            }
        }
        let _ = writeln!(
            md,
            "\n## Wall time per stage\n\n| stage | seconds |\n|---|---|"
        );
        let mut total = 0.0;
        for s in &self.stages {
            let _ = writeln!(md, "| {} | {:.3} |", s.stage, s.seconds);
            total += s.seconds;
        }
        let _ = writeln!(md, "| **total** | {total:.3} |");
        if !self.files.is_empty() {
            let _ = writeln!(md, "\n## Files\n");
            for f in &self.files {
                let _ = writeln!(md, "- `{f}`");
            }
        }
        md
    }

    /// Write `report.json` and `report.md` into `dir`, atomically.
    pub fn write(&self, dir: &Path) -> std::io::Result<()> {
        let json = serde_json::to_vec_pretty(self).map_err(std::io::Error::other)?;
        write_atomic(&dir.join("report.json"), &json)?;
        write_atomic(&dir.join("report.md"), self.to_markdown().as_bytes())
    }
}
