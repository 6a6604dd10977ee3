//! The main job's report: `report.json` (everything, machine-readable) and `report.md` (the
//! same for people: tables of every fidelity metric, side by side for each method or variant).

use std::fmt::Write as _;
use std::path::Path;

use serde::ser::SerializeStruct as _;
use serde::{Serialize, Serializer};

use crate::fsutil::write_atomic;
use crate::metrics::registry::{
    Metric, APEX_ERROR, DURATION_RATIO, FINAL_ERROR, JOINT_DTW, WRIST_DTW,
};
use crate::metrics::{FidelityReport, Smoothness, Stat};

use crate::demos::{sample_period, Demonstration};
use crate::eval::SWING_MIN_AMPLITUDE_RAD;
use crate::eval::{FoldScores, HeldOut, HeldOutSummary, Method, MethodRun};
use crate::hsom::LevelSummary;
use crate::robot::Robot;
use crate::sim::{Recording, Touch, JOINT_NAMES, SWING_JOINT};
use crate::table::Table;

/// One demonstration used for training.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DemoInfo {
    /// File (relative to the output directory) or source.
    pub file: String,
    /// Number of samples.
    pub samples: usize,
    /// Duration, seconds.
    pub duration_s: f64,
    /// Contacts between the robot's parts while it was recorded, on a model with collision
    /// shapes ([`Robot::has_collision_shapes`]); none otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contacts: Option<Vec<Touch>>,
}

impl DemoInfo {
    /// `demo`, listed as `file`.
    pub fn new(file: String, demo: &Demonstration) -> Self {
        let samples = demo.rows.len();
        let duration_s = samples.saturating_sub(1) as f64 * sample_period(demo);
        DemoInfo {
            file,
            samples,
            duration_s,
            contacts: None,
        }
    }
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
    /// Contacts between the robot's parts during the executed reproduction, on a model with
    /// collision shapes ([`Robot::has_collision_shapes`]); none otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contacts: Option<Vec<Touch>>,
}

impl MethodResult {
    /// `run`'s column of a comparison table, without held-out figures (see
    /// `heldout::leave_one_out`): the method named `name` needs `needs` as input;
    /// `model_bytes` is the size of its saved model.
    pub fn of(
        name: &str,
        needs: &str,
        run: &MethodRun<Recording>,
        model_bytes: u64,
        notes: Vec<String>,
    ) -> Self {
        MethodResult {
            name: name.into(),
            needs: needs.into(),
            fidelity: run.executed.fidelity.clone(),
            train_s: run.train_s,
            reproduce_s: run.reproduce_s,
            model_bytes,
            postures: run.postures.len(),
            clamped_values: run.executed.clamped_values,
            notes,
            heldout: None,
            contacts: executed_contacts(&run.executed.trace),
        }
    }
}

/// The contacts of an executed motion, when its robot's model has collision shapes.
fn executed_contacts(trace: &Recording) -> Option<Vec<Touch>> {
    let robot = Robot::of_columns(&trace.joint_names)?;
    robot.has_collision_shapes().then(|| trace.contacts.clone())
}

/// Contacts for people: `none`, or each one described ([`Touch::describe`]), `; ` between.
pub fn contacts_text(contacts: &[Touch]) -> String {
    if contacts.is_empty() {
        return "none".into();
    }
    let all: Vec<String> = contacts.iter().map(Touch::describe).collect();
    all.join("; ")
}

/// A level of the main model in `report.json`: how many nodes it has (rows x cols) and uses,
/// and how well it predicts the level below beside the lookup-table baseline, in sample and
/// held out, and whether reproduction plans from it.
impl Serialize for LevelSummary {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut level = s.serialize_struct("LevelRow", 8)?;
        level.serialize_field("level", &self.level)?;
        level.serialize_field("nodes", &(self.rows * self.cols))?;
        level.serialize_field("nodes_used", &self.nodes_used)?;
        level.serialize_field("prediction_accuracy", &self.prediction_accuracy)?;
        level.serialize_field("lookup_accuracy", &self.lookup_accuracy)?;
        let prediction = self.heldout_prediction_accuracy;
        level.serialize_field("heldout_prediction_accuracy", &prediction)?;
        level.serialize_field("heldout_lookup_accuracy", &self.heldout_lookup_accuracy)?;
        level.serialize_field("used_in_reproduction", &self.used_in_reproduction)?;
        level.end()
    }
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
    /// The levels of the main model ([`crate::hsom::Hsom::summary`]).
    pub levels: Vec<LevelSummary>,
    /// Wall time per stage.
    pub stages: Vec<Stage>,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
    /// What this job leaves out of the main job on this robot, and why, one line each.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub not_run: Vec<String>,
    /// The reproduction in the loop (`simulate --loop closed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub in_loop: Option<super::arm_loop::LoopSection>,
}

fn stat(s: &Stat, digits: usize) -> String {
    format!("{:.*} / {:.*}", digits, s.mean, digits, s.worst)
}

fn opt_stat(s: &Option<Stat>, digits: usize) -> String {
    s.as_ref()
        .map_or_else(|| "n/a".to_string(), |s| stat(s, digits))
}

/// The rows of [`comparison_table`]: a name and how one result fills it, given the
/// demonstrations' mean normalized jerk and velocity reversals.
type ComparisonRow = (&'static str, fn(&MethodResult, (f64, f64)) -> String);

/// The wrist-path DTW as the report shows it (to 1 decimal).
const WRIST_PATH: Metric = WRIST_DTW.titled("wrist-path DTW (mm/step)").to(1);

/// The duration ratio as the report shows it (to 2 decimals).
const DURATION: Metric = DURATION_RATIO.to(2);

/// The fidelity metrics of the report's tables, in order.
const FIDELITY: [Metric; 5] = [JOINT_DTW, WRIST_PATH, APEX_ERROR, FINAL_ERROR, DURATION];

/// The means of `f`'s [`FIDELITY`] metrics over the demonstrations.
fn fidelity_means(f: &FidelityReport) -> [Option<f64>; 5] {
    [
        Some(f.joint_dtw_rad_per_step.mean),
        f.wrist_dtw_mm.map(|w| w.mean),
        Some(f.apex_error_rad.mean),
        Some(f.final_error_rad.mean),
        Some(f.duration_ratio.mean),
    ]
}

const COMPARISON_ROWS: [ComparisonRow; 15] = [
    (JOINT_DTW.label, |r, _| {
        stat(&r.fidelity.joint_dtw_rad_per_step, JOINT_DTW.digits)
    }),
    (WRIST_PATH.label, |r, _| {
        opt_stat(&r.fidelity.wrist_dtw_mm, WRIST_PATH.digits)
    }),
    (APEX_ERROR.label, |r, _| {
        stat(&r.fidelity.apex_error_rad, APEX_ERROR.digits)
    }),
    (FINAL_ERROR.label, |r, _| {
        stat(&r.fidelity.final_error_rad, FINAL_ERROR.digits)
    }),
    (DURATION.label, |r, _| {
        stat(&r.fidelity.duration_ratio, DURATION.digits)
    }),
    (
        "normalized jerk (demos' mean in brackets)",
        |r, (jerk, _)| {
            let j = r.fidelity.reproduction_smoothness.normalized_jerk;
            format!(
                "{} ({jerk:.0})",
                j.map_or("n/a".into(), |j| format!("{j:.0}"))
            )
        },
    ),
    (
        "velocity reversals, all joints (demos' mean)",
        |r, (_, rev)| {
            format!(
                "{} ({rev:.1})",
                r.fidelity.reproduction_smoothness.total_reversals
            )
        },
    ),
    ("velocity reversals per joint", |r, _| {
        let v = &r.fidelity.reproduction_smoothness.reversals;
        v.iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    }),
    ("reproduction duration (s)", |r, _| {
        format!("{:.2}", r.fidelity.reproduction_duration_s)
    }),
    ("postures produced", |r, _| r.postures.to_string()),
    ("clamped values", |r, _| r.clamped_values.to_string()),
    ("training time (s)", |r, _| format!("{:.3}", r.train_s)),
    ("reproduction time (s)", |r, _| {
        format!("{:.4}", r.reproduce_s)
    }),
    ("model size (bytes)", |r, _| r.model_bytes.to_string()),
    ("needs as input", |r, _| r.needs.clone()),
];

/// A markdown table with one column per result: every fidelity metric (mean / worst over the
/// demonstrations), smoothness, and costs; then each result's notes, one line each.
pub fn comparison_table(results: &[MethodResult]) -> String {
    let mut table = Table::new(
        std::iter::once("metric (mean / worst)").chain(results.iter().map(|r| r.name.as_str())),
    );
    let demos = results
        .first()
        .map_or(&[][..], |r| &r.fidelity.demo_smoothness);
    let demo_means = (
        demo_mean(demos, |s| s.normalized_jerk).unwrap_or(f64::NAN),
        demo_mean(demos, |s| Some(s.total_reversals as f64)).unwrap_or(f64::NAN),
    );
    // two arms (the upper body): the wrist row is the left wrist's, the right's beside it
    let two_wrists = results
        .iter()
        .any(|r| r.fidelity.right_wrist_dtw_mm.is_some());
    let mut row = |name: &str, cell: &dyn Fn(&MethodResult) -> String| {
        table.row(std::iter::once(name.to_string()).chain(results.iter().map(cell)));
    };
    for (name, cell) in COMPARISON_ROWS {
        if two_wrists && name == WRIST_PATH.label {
            row("left wrist-path DTW, l_wrist (mm/step)", &|r| {
                opt_stat(&r.fidelity.wrist_dtw_mm, 1)
            });
            row("right wrist-path DTW, r_wrist (mm/step)", &|r| {
                opt_stat(&r.fidelity.right_wrist_dtw_mm, 1)
            });
            continue;
        }
        row(name, &|r| cell(r, demo_means));
    }
    if results.iter().any(|r| r.contacts.is_some()) {
        row("contacts between parts (time, parts, deepest)", &|r| {
            r.contacts
                .as_deref()
                .map_or_else(|| "n/a".into(), contacts_text)
        });
    }
    let mut t = table.to_string();
    for r in results {
        for n in &r.notes {
            let _ = writeln!(t, "- {}: {n}", r.name);
        }
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
/// the held-out large swings of LElbowRoll; then one row per method of `held_out_only`
/// (`name`, held-out summary), evaluated held out only. `n/a` where a figure was not
/// computed.
pub fn heldout_table(
    results: &[MethodResult],
    held_out_only: &[(&str, &HeldOutSummary)],
) -> String {
    let swings = format!(
        "{} swings > {} rad, held-out (demo)",
        JOINT_NAMES[SWING_JOINT], SWING_MIN_AMPLITUDE_RAD
    );
    let fidelity = FIDELITY.map(|m| m.label);
    let mut table = Table::new(
        ["method (in-sample / held-out)", "folds"]
            .into_iter()
            .chain(fidelity)
            .chain([
                "normalized jerk (demos')",
                "velocity reversals (demos')",
                &swings,
            ]),
    );
    for r in results {
        table.row(heldout_row(&r.name, Some(&r.fidelity), r.heldout.as_ref()));
    }
    for (name, h) in held_out_only {
        table.row(heldout_row(name, None, Some(h)));
    }
    table.to_string()
}

/// Decimals of the in-sample / held-out pairs of [`heldout_row`], in its column order.
const HELDOUT_DIGITS: [usize; 9] = [
    FIDELITY[0].digits,
    FIDELITY[1].digits,
    FIDELITY[2].digits,
    FIDELITY[3].digits,
    FIDELITY[4].digits,
    0,
    0,
    1,
    1,
];

/// The in-sample figures of [`heldout_row`]'s pairs, in its column order.
fn in_sample_figures(f: &FidelityReport) -> [Option<f64>; 9] {
    let [joint, wrist, apex, last, duration] = fidelity_means(f);
    [
        joint,
        wrist,
        apex,
        last,
        duration,
        f.reproduction_smoothness.normalized_jerk,
        demo_mean(&f.demo_smoothness, |s| s.normalized_jerk),
        Some(f.reproduction_smoothness.total_reversals as f64),
        demo_mean(&f.demo_smoothness, |s| Some(s.total_reversals as f64)),
    ]
}

/// The held-out figures of [`heldout_row`]'s pairs, in its column order.
fn heldout_figures(h: &HeldOutSummary) -> [Option<f64>; 9] {
    [
        Some(h.joint_dtw_rad_per_step),
        h.wrist_dtw_mm,
        Some(h.apex_error_rad),
        Some(h.final_error_rad),
        Some(h.duration_ratio),
        h.normalized_jerk,
        h.demo_normalized_jerk,
        Some(h.velocity_reversals),
        Some(h.demo_velocity_reversals),
    ]
}

/// One row of [`heldout_table`]: `name`'s in-sample fidelity `f` (`n/a` without one: a method
/// evaluated held out only) beside its held-out means `h`.
fn heldout_row(name: &str, f: Option<&FidelityReport>, h: Option<&HeldOutSummary>) -> Vec<String> {
    let (a, b) = (
        f.map_or([None; 9], in_sample_figures),
        h.map_or([None; 9], heldout_figures),
    );
    let pair = |i: usize| {
        format!(
            "{} / {}",
            num(a[i], HELDOUT_DIGITS[i]),
            num(b[i], HELDOUT_DIGITS[i])
        )
    };
    let folds = h.map_or("n/a".into(), |h| h.folds.to_string());
    let swings = h.map_or("n/a".into(), |h| {
        format!(
            "{} ({})",
            num(Some(h.swings), 1),
            num(Some(h.demo_swings), 1)
        )
    });
    vec![
        name.to_string(),
        folds,
        pair(0),
        pair(1),
        pair(2),
        pair(3),
        pair(4),
        format!("{} ({})", pair(5), pair(6)),
        format!("{} ({})", pair(7), pair(8)),
        swings,
    ]
}

/// ProMP's name in the report's tables (held out only: no in-sample column).
pub const PROMP_NAME: &str = "ProMP (held out only)";

/// The DMP's name in the report's tables (held out only).
pub const DMP_NAME: &str = "DMP (held out only)";

/// The DTW mean's name in the report's tables (held out only).
pub const DBA_NAME: &str = "DBA (held out only)";

/// A markdown table with one row per `(name, held-out summary)`: where the reproductions start
/// and end against the folds' training demonstrations and how smooth they are, the motion the
/// arm executed beside the postures the method handed the servos (docs/METRICS.md, "Start and
/// end"). `n/a` where a figure was not computed.
pub fn start_end_table(rows: &[(&str, &HeldOutSummary)]) -> String {
    let pct = |v: Option<f64>| v.map_or("n/a".into(), |v| format!("{:.0} %", 100.0 * v));
    let mut table = Table::new([
        "method (executed / commanded)",
        "folds",
        "start speed (rad/s)",
        "training demos' largest start speed (rad/s)",
        "start in range",
        "end within spread",
        "normalized jerk (held-out demos')",
    ]);
    for (name, h) in rows {
        table.row([
            name.to_string(),
            h.folds.to_string(),
            format!(
                "{} / {}",
                num(h.start_speed, 3),
                num(h.commanded_start_speed, 3)
            ),
            num(h.demo_start_speed_max, 3),
            format!(
                "{} / {}",
                pct(h.start_in_range),
                pct(h.commanded_start_in_range)
            ),
            format!(
                "{} / {}",
                pct(h.end_within_spread),
                pct(h.commanded_end_within_spread)
            ),
            format!(
                "{} / {} ({})",
                num(h.normalized_jerk, 0),
                num(h.commanded_normalized_jerk, 0),
                num(h.demo_normalized_jerk, 0)
            ),
        ]);
    }
    table.to_string()
}

/// A markdown table of every fold: the held-out demonstration and both methods' scores
/// against it, the nearest-sequence baseline's joint DTW and swings, and ProMP's joint DTW,
/// final error and swings (`n/a` when one was not run).
pub fn folds_table(h: &HeldOut) -> String {
    let mut table = Table::new([
        "fold",
        "held out",
        "CoSCo-HSOM joint DTW",
        "wrist DTW",
        "apex",
        "final",
        "duration ratio",
        "swings (demo)",
        "GMM/GMR joint DTW",
        "wrist DTW",
        "apex",
        "final",
        "duration ratio",
        "swings",
        "nearest-sequence joint DTW",
        "swings",
        "ProMP joint DTW",
        "final",
        "swings",
        "DBA joint DTW",
        "swings",
    ]);
    let swings = |s: &FoldScores, demo: bool| {
        s.swings.as_ref().map_or("n/a".to_string(), |w| {
            (if demo { w.demo } else { w.reproduction }).to_string()
        })
    };
    // a method that did not run: why, then blanks to the end of its columns
    let not_run = |why: &str, columns: usize| {
        std::iter::once(format!("not run: {why}")).chain(vec![String::new(); columns - 1])
    };
    for (i, f) in h.folds.iter().enumerate() {
        let Some(hsom) = f.scores(Method::Hierarchy) else {
            continue;
        };
        let scores = |s: &FoldScores| {
            let means = fidelity_means(&s.fidelity);
            (FIDELITY.iter().zip(means)).map(|(m, v)| match m.key {
                k if k == WRIST_DTW.key => num(v, m.digits),
                _ => m.cell(v, "n/a"),
            })
        };
        let mut row = vec![(i + 1).to_string(), f.demonstration.clone()];
        row.extend(scores(hsom));
        row.push(format!("{} ({})", swings(hsom, false), swings(hsom, true)));
        match (f.scores(Method::GmmGmr), f.error(Method::GmmGmr)) {
            (Some(g), _) => {
                row.extend(scores(g));
                row.push(swings(g, false));
            }
            (None, e) => row.extend(not_run(e.unwrap_or("no reason given"), 6)),
        }
        match f.scores(Method::NearestSequence) {
            Some(s) => row.extend([
                JOINT_DTW.cell(Some(s.fidelity.joint_dtw_rad_per_step.mean), "n/a"),
                swings(s, false),
            ]),
            None => row.extend(["n/a".to_string(), "n/a".to_string()]),
        }
        match (f.scores(Method::ProMP), f.error(Method::ProMP)) {
            (Some(p), _) => row.extend([
                JOINT_DTW.cell(Some(p.fidelity.joint_dtw_rad_per_step.mean), "n/a"),
                FINAL_ERROR.cell(Some(p.fidelity.final_error_rad.mean), "n/a"),
                swings(p, false),
            ]),
            (None, Some(e)) => row.extend(not_run(e, 3)),
            (None, None) => row.extend(["n/a", "n/a", "n/a"].map(String::from)),
        }
        match (f.scores(Method::Dba), f.error(Method::Dba)) {
            (Some(d), _) => row.extend([
                JOINT_DTW.cell(Some(d.fidelity.joint_dtw_rad_per_step.mean), "n/a"),
                swings(d, false),
            ]),
            (None, Some(e)) => row.extend(not_run(e, 2)),
            (None, None) => row.extend(["n/a", "n/a"].map(String::from)),
        }
        table.row(row);
    }
    table.to_string()
}

/// A markdown table of a model's levels: nodes used, prediction accuracy, lookup-table
/// accuracy, both in-sample and held out.
pub fn levels_table(levels: &[LevelSummary]) -> String {
    let mut table = Table::new([
        "level",
        "nodes used / nodes",
        "prediction accuracy",
        "lookup-table accuracy",
        "held out: prediction",
        "held out: lookup table",
        "plans in reproduction",
    ]);
    for l in levels {
        table.row([
            l.level.to_string(),
            format!("{} / {}", l.nodes_used, l.rows * l.cols),
            format!("{:.3}", l.prediction_accuracy),
            format!("{:.3}", l.lookup_accuracy),
            format!("{:.3}", l.heldout_prediction_accuracy),
            format!("{:.3}", l.heldout_lookup_accuracy),
            crate::hsom::plans_word(l.level, l.used_in_reproduction).to_string(),
        ]);
    }
    table.to_string()
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
            let contacts = d.contacts.as_deref().map_or(String::new(), |c| {
                format!("; contacts between parts: {}", contacts_text(c))
            });
            let _ = writeln!(
                md,
                "  - `{}`: {} samples, {:.2} s{contacts}",
                d.file, d.samples, d.duration_s
            );
        }
        let executions: Option<Vec<Vec<Touch>>> =
            self.demos.iter().map(|d| d.contacts.clone()).collect();
        let own = crate::sim::own_contacts(&executions.unwrap_or_default());
        if !own.is_empty() {
            let pairs: Vec<String> = own
                .iter()
                .map(|p| format!("{} and {}", p[0], p[1]))
                .collect();
            let _ = writeln!(
                md,
                "- the gesture's own contacts (every demonstration makes them; a reproduction \
                 may too): {}",
                pairs.join("; ")
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
        if !self.not_run.is_empty() {
            let _ = writeln!(md, "\n## Not run on this robot\n");
            for n in &self.not_run {
                let _ = writeln!(md, "- {n}");
            }
        }
        if let Some(l) = &self.in_loop {
            md.push('\n');
            md.push_str(&super::arm_loop::loop_markdown(l));
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
                let held_out_only: Vec<(&str, &HeldOutSummary)> = [
                    h.promp.as_ref().map(|p| (PROMP_NAME, p)),
                    h.dmp.as_ref().map(|d| (DMP_NAME, d)),
                    h.dba.as_ref().map(|d| (DBA_NAME, d)),
                ]
                .into_iter()
                .flatten()
                .collect();
                md.push_str(&heldout_table(&self.methods, &held_out_only));
                if let Some(s) = &h.sequence {
                    let _ = writeln!(
                        md,
                        "\nNearest-sequence baseline (the same CoSCo-HSOM model's bottom code \
                         following the bottom events of the training demonstration that starts \
                         nearest, no level above; docs/ALGORITHM.md), held out over {} folds: \
                         joint DTW {} rad/step, wrist-path DTW {} mm/step, duration ratio {}, \
                         {} swings {} ({}).",
                        s.folds,
                        num(Some(s.joint_dtw_rad_per_step), JOINT_DTW.digits),
                        num(s.wrist_dtw_mm, WRIST_PATH.digits),
                        num(Some(s.duration_ratio), DURATION.digits),
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
                rows.extend(h.dmp.as_ref().map(|d| (DMP_NAME, d)));
                rows.extend(h.dba.as_ref().map(|d| (DBA_NAME, d)));
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
                md.push_str(&heldout_table(&self.variants, &[]));
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
        }
        let _ = writeln!(md, "\n## Wall time per stage\n");
        let mut table = Table::new(["stage", "seconds"]);
        for s in &self.stages {
            table.row([s.stage.to_string(), format!("{:.3}", s.seconds)]);
        }
        let total = self.stages.iter().fold(0.0, |t, s| t + s.seconds);
        table.row(["**total**".to_string(), format!("{total:.3}")]);
        md.push_str(&table.to_string());
        md + &files_section(&self.files)
    }

    /// Write `report.json` and `report.md` into `dir`, atomically.
    pub fn write(&self, dir: &Path) -> std::io::Result<()> {
        write_report(dir, self, &self.to_markdown())
    }
}

/// The Markdown list of the files a job wrote (nothing when it wrote none).
pub fn files_section(files: &[String]) -> String {
    if files.is_empty() {
        return String::new();
    }
    let list: String = files.iter().map(|f| format!("- `{f}`\n")).collect();
    format!("\n## Files\n\n{list}")
}

/// Write `report` as `report.json` and `markdown` as `report.md` into `dir`, atomically.
pub fn write_report(dir: &Path, report: &impl Serialize, markdown: &str) -> std::io::Result<()> {
    let json = serde_json::to_vec_pretty(report).map_err(std::io::Error::other)?;
    write_atomic(&dir.join("report.json"), &json)?;
    write_atomic(&dir.join("report.md"), markdown.as_bytes())
}
