//! `simulate --gesture all`: one hierarchy learns every gesture of the library, each
//! is reproduced on cue and executed on the simulated arm, and the report sets the shared
//! hierarchy's per-gesture fidelity beside the same gesture learned alone, with the
//! recognition of held-out demonstrations (confusion matrices of CoSCo-HSOM and of the 1-NN
//! DTW baseline) and a clip of the gestures in turn.
//!
//! Held out, leave-one-out across the demonstrations of every gesture: with `count`
//! demonstrations per gesture, fold `k` learns from all but the `k`-th of every gesture and
//! is scored on the `k`-th ones (`count - 1` = 3 learned per gesture by default, as in the
//! issue). The model saved, reproduced and filmed is fold `count - 1`'s (learned from the
//! first `count - 1` demonstrations of each gesture).

use serde::Serialize;

use crate::config::{load_config_or_default, HsomConfig};
use crate::demos::{write_csv, Demonstration};
use crate::dtw::Band;
use crate::eval::{Executed, Executor, FoldInput, Method};
use crate::gesture::Gesture;
use crate::hsom::{GestureError, GestureModel};
use crate::nearest::NearestNeighbour;
use crate::plot::{caption, confusion_png, ConfusionPanel};
use crate::render::{contact_sheet, save_png, Clip};
use crate::sim::{NaoArm, Recording};
use crate::table::Table;

use super::demonstrate::{synthetic_demonstrations, write_demos, DemoSettings};
use super::executor::ArmExecutor;
use super::film::{clip_options, film, film_marked};
use super::heldout::on_arm;
use super::job::Job;
use super::output::{config_name, load_arm};
use super::report::{files_section, write_report};
use super::{ExperimentError, Progress};
use crate::stats::median;

/// The variable that `demos` move most (the largest standard deviation over time, averaged
/// over the demonstrations).
fn most_moving(demos: &[Demonstration]) -> usize {
    let width = demos.first().map_or(0, |d| d.columns.len());
    let spread = |v: usize| {
        (demos.iter())
            .map(|d| {
                let n = d.rows.len().max(1) as f64;
                let mean = d.rows.iter().map(|r| r[v]).sum::<f64>() / n;
                (d.rows.iter().map(|r| (r[v] - mean).powi(2)).sum::<f64>() / n).sqrt()
            })
            .sum::<f64>()
    };
    (0..width)
        .max_by(|&a, &b| spread(a).total_cmp(&spread(b)))
        .unwrap_or(0)
}

/// Frames of each gesture on the contact sheet (one row per gesture).
const SHEET_COLUMNS: usize = 4;

/// One gesture's fidelity, held out: the shared hierarchy beside the gesture learned alone
/// (same configuration, same folds), means over the folds.
#[derive(Debug, Clone, Serialize)]
pub struct GestureFidelity {
    /// The gesture.
    pub gesture: String,
    /// Joint DTW of the shared hierarchy's reproductions on cue, rad per step.
    pub shared_joint_dtw: f64,
    /// Joint DTW of the gesture learned alone, rad per step.
    pub alone_joint_dtw: f64,
    /// Wrist-path DTW, shared, mm per step.
    pub shared_wrist_dtw_mm: Option<f64>,
    /// Wrist-path DTW, alone, mm per step.
    pub alone_wrist_dtw_mm: Option<f64>,
    /// Duration ratio of the shared hierarchy's reproductions.
    pub shared_duration_ratio: f64,
    /// Folds whose executed reproduction reverses the gesture's most moving joint (over its
    /// training demonstrations) within 1 as often as the held-out demonstration does
    /// (velocity reversals, deadband 0.25 rad/s).
    pub reversals_kept: usize,
    /// Folds averaged.
    pub folds: usize,
    /// Joint DTW of each fold's shared reproduction (fold k held out demonstration k).
    pub shared_per_fold: Vec<f64>,
    /// Joint DTW of each fold's reproduction by the gesture learned alone.
    pub alone_per_fold: Vec<f64>,
}

impl GestureFidelity {
    /// Shared / alone joint DTW (the gate: at most 1.2).
    pub fn ratio(&self) -> f64 {
        self.shared_joint_dtw / self.alone_joint_dtw
    }
}

/// One held-out recognition query.
#[derive(Debug, Clone, Serialize)]
pub struct AllQuery {
    /// The gesture shown.
    pub expected: String,
    /// CoSCo-HSOM's answer (`None`: unknown).
    pub hsom: Option<String>,
    /// Fraction of the sequence after which CoSCo-HSOM's answer stayed the same.
    pub hsom_decided_fraction: f64,
    /// Time of CoSCo-HSOM's recognition, ms.
    pub hsom_ms: f64,
    /// The 1-NN DTW baseline's answer.
    pub nn: String,
    /// Time of the baseline's answer, ms.
    pub nn_ms: f64,
}

/// Everything `simulate --gesture all` measured.
#[derive(Debug, Clone, Serialize)]
pub struct AllReport {
    /// Labels, in order.
    pub labels: Vec<String>,
    /// Configuration file (or description).
    pub config: String,
    /// Settings: demonstrations per gesture, seed, noise.
    pub count: usize,
    /// Seed of the demonstrations.
    pub seed: u64,
    /// Encoder noise, rad.
    pub noise: f64,
    /// Held-out fidelity per gesture.
    pub fidelity: Vec<GestureFidelity>,
    /// Held-out recognition queries (every fold).
    pub queries: Vec<AllQuery>,
    /// CoSCo-HSOM's confusion counts: rows the labels, columns the labels then `unknown`.
    pub confusion: Vec<Vec<usize>>,
    /// The 1-NN DTW baseline's confusion counts (it never answers `unknown`).
    pub nn_confusion: Vec<Vec<usize>>,
    /// The saved model's reproductions on cue: (gesture, samples, how it stopped).
    pub reproductions: Vec<(String, usize, String)>,
    /// Files written, relative to the output directory.
    pub files: Vec<String>,
    /// With `--recognize`: each gesture's last held-out demonstration streamed, a sample at a
    /// time, into the recogniser of the fold that did not learn it.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub streamed: Vec<StreamedGesture>,
}

/// A held-out demonstration streamed into the recogniser (`simulate --gesture all --recognize`).
#[derive(Debug, Clone, Serialize)]
pub struct StreamedGesture {
    /// The gesture shown.
    pub gesture: String,
    /// What the recogniser committed to (`None`: unknown), when it committed.
    pub committed: Option<Option<String>>,
    /// The sample it committed on (counted from 1), when it did.
    pub at_sample: Option<usize>,
    /// The demonstration's samples.
    pub samples: usize,
}

/// A held-out demonstration streamed: what was committed after each sample (`None` before
/// the commitment), and the demonstration as a recording to film.
struct Stream {
    report: StreamedGesture,
    recording: Recording,
}

/// `test` (of `gesture`) pushed a sample at a time into `model`'s recogniser.
fn stream(
    model: &GestureModel,
    gesture: &str,
    test: &Demonstration,
) -> Result<Stream, ExperimentError> {
    let mut r = model.recognizer().map_err(gerr)?;
    for row in &test.rows {
        r.push(row).map_err(gerr)?;
    }
    let commit = r.commit();
    let period = crate::demos::sample_period(test);
    let mut recording = Recording::new(1.0 / period, crate::robot::Robot::LeftArm);
    recording.time = (0..test.rows.len()).map(|k| k as f64 * period).collect();
    recording.qpos = test.rows.clone();
    recording.target = test.rows.clone();
    Ok(Stream {
        report: StreamedGesture {
            gesture: gesture.to_string(),
            committed: commit.map(|c| c.label.clone()),
            at_sample: commit.map(|c| c.samples),
            samples: test.rows.len(),
        },
        recording,
    })
}

impl StreamedGesture {
    /// What the clip says at sample `i` (from 0): the gesture shown and, once committed, the
    /// answer.
    fn caption(&self, i: usize, t: f64) -> String {
        let answer = match (&self.committed, self.at_sample) {
            (Some(label), Some(n)) if i + 1 >= n => {
                format!("committed: {}", label.as_deref().unwrap_or("unknown"))
            }
            _ => "recognising...".to_string(),
        };
        format!("{} shown, t = {t:.1} s: {answer}", self.gesture)
    }
}

impl AllReport {
    /// Fraction of queries CoSCo-HSOM answered with the gesture shown.
    pub fn accuracy(&self) -> f64 {
        self.share(|q| q.hsom.as_deref() == Some(q.expected.as_str()))
    }

    /// Fraction of queries the 1-NN DTW baseline answered with the gesture shown.
    pub fn nn_accuracy(&self) -> f64 {
        self.share(|q| q.nn == q.expected)
    }

    fn share(&self, right: impl Fn(&AllQuery) -> bool) -> f64 {
        let right = self.queries.iter().filter(|&q| right(q)).count();
        right as f64 / self.queries.len().max(1) as f64
    }

    /// The report as Markdown.
    pub fn to_markdown(&self) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "# CoSCo-HSOM on the simulated Nao left arm: {} gestures in one hierarchy\n",
            self.labels.len()
        );
        let _ = writeln!(
            s,
            "Configuration {}; {} demonstrations per gesture (seed {}, encoder noise {} rad), \
             leave-one-out: each fold learns from {} of every gesture and is scored on the \
             remaining one of each. One model: one branch per gesture, each learned alone in the \
             units of all of them (docs/ALGORITHM.md, section 4).\n",
            self.config,
            self.count,
            self.seed,
            self.noise,
            self.count - 1
        );
        let _ = writeln!(
            s,
            "## Fidelity per gesture, held out: the shared hierarchy beside the gesture learned alone\n"
        );
        let mm = |v: Option<f64>| v.map_or("n/a".to_string(), |x| format!("{x:.1}"));
        let mut table = Table::new([
            "gesture",
            "shared joint DTW (rad/step)",
            "alone joint DTW",
            "shared / alone",
            "shared wrist DTW (mm)",
            "alone wrist DTW (mm)",
            "shared duration ratio",
            "reversals within 1 (folds)",
            "folds",
        ]);
        for f in &self.fidelity {
            table.row([
                f.gesture.clone(),
                format!("{:.4}", f.shared_joint_dtw),
                format!("{:.4}", f.alone_joint_dtw),
                format!("{:.2}", f.ratio()),
                mm(f.shared_wrist_dtw_mm),
                mm(f.alone_wrist_dtw_mm),
                format!("{:.2}", f.shared_duration_ratio),
                format!("{} of {}", f.reversals_kept, f.folds),
                f.folds.to_string(),
            ]);
        }
        s += &table.to_string();
        let _ = writeln!(
            s,
            "\nThe gates: shared / alone at most 1.2 on every gesture; the reversals of each \
             gesture's most moving joint within 1 of the held-out demonstration's on at least 90 % \
             of folds. Per fold (fold k holds out demonstration k), joint DTW shared / alone:\n"
        );
        for f in &self.fidelity {
            let folds: Vec<String> = f
                .shared_per_fold
                .iter()
                .zip(&f.alone_per_fold)
                .map(|(a, b)| format!("{a:.3} / {b:.3}"))
                .collect();
            let _ = writeln!(s, "- {}: {}", f.gesture, folds.join(", "));
        }
        let _ = writeln!(s);
        let _ = writeln!(s, "## Recognition of the held-out demonstrations\n");
        let early = |f: &dyn Fn(&AllQuery) -> f64| median(self.queries.iter().map(f));
        let _ = writeln!(
            s,
            "CoSCo-HSOM {:.1} % ({} queries; median fraction of the gesture seen before the \
             answer stayed the same {:.2}; median {:.2} ms a query); 1-NN DTW on the same \
             training demonstrations {:.1} % (median {:.2} ms a query). Figure: \
             `confusion.png`.\n",
            100.0 * self.accuracy(),
            self.queries.len(),
            early(&|q| q.hsom_decided_fraction).unwrap_or(f64::NAN),
            early(&|q| q.hsom_ms).unwrap_or(f64::NAN),
            100.0 * self.nn_accuracy(),
            early(&|q| q.nn_ms).unwrap_or(f64::NAN),
        );
        if !self.streamed.is_empty() {
            let _ = writeln!(
                s,
                "Streamed (`--recognize`): each gesture's last held-out demonstration pushed a \
                 sample at a time into the recogniser of the fold that did not learn it; the \
                 clip shows the answer from the sample it committed on.\n"
            );
            let mut t = Table::new([
                "gesture shown",
                "committed to",
                "at sample",
                "share of the gesture",
            ]);
            for g in &self.streamed {
                t.row([
                    g.gesture.clone(),
                    match &g.committed {
                        Some(l) => l.clone().unwrap_or_else(|| "unknown".into()),
                        None => "(not committed)".into(),
                    },
                    g.at_sample.map_or("-".into(), |n| n.to_string()),
                    g.at_sample.map_or("-".into(), |n| {
                        format!("{:.2}", n as f64 / g.samples.max(1) as f64)
                    }),
                ]);
            }
            let _ = writeln!(s, "{t}");
        }
        let _ = writeln!(s, "CoSCo-HSOM (rows: gesture shown; columns: answer):\n");
        s += &confusion_markdown(&self.confusion, &self.labels, true);
        let _ = writeln!(s, "\n1-NN DTW:\n");
        s += &confusion_markdown(&self.nn_confusion, &self.labels, false);
        let _ = writeln!(
            s,
            "\nThe unknown-gesture study and the negative controls (untrained hierarchy, shuffled \
             labels) over several seeds: `cargo run --release --example multi_heldout -- --seeds \
             11-15` (docs/COMPARISON.md).\n"
        );
        let _ = writeln!(
            s,
            "## The saved model's reproductions on cue\n\n`model.bin` learned from \
             the first {} demonstrations of each gesture; each gesture reproduced from its \
             held-out demonstration's first posture and executed on the arm \
             (`reproduction_<gesture>.csv`; `clip.gif` plays them in turn).\n",
            self.count - 1
        );
        let mut table = Table::new(["gesture", "samples", "stopped"]);
        for (g, n, stop) in &self.reproductions {
            table.row([g.to_string(), n.to_string(), stop.to_string()]);
        }
        s += &table.to_string();
        s + &files_section(&self.files)
    }
}

fn gerr(e: GestureError) -> ExperimentError {
    ExperimentError::Invalid(e.to_string())
}

fn werr(what: &str, e: impl std::fmt::Display) -> ExperimentError {
    ExperimentError::Invalid(format!("{what}: {e}"))
}

/// `simulate --gesture all`: one hierarchy for every gesture, its files written into
/// `job.out` (see [`run_all_gestures`]); returns the report's summary lines.
pub fn all_gestures_job(job: &Job, progress: Progress<'_>) -> Result<Vec<String>, ExperimentError> {
    if job.demos.is_some() {
        return Err(ExperimentError::Invalid(
            "--gesture all records synthetic demonstrations of every gesture; to learn several gestures from recorded files use `cosco train --demos DIR` with one subdirectory per gesture (DIR/<gesture>/*.csv)"
        .into()));
    }
    if job.robot != crate::robot::Robot::LeftArm {
        return Err(ExperimentError::Invalid(format!(
            "--gesture all runs on the left arm; on the {} give one gesture: {}",
            job.robot.name(),
            Gesture::names(job.robot).join(", ")
        )));
    }
    let out = &job.out;
    std::fs::create_dir_all(out).map_err(ExperimentError::io("creating", out))?;
    let cfg = load_config_or_default(job.config.as_deref())?;
    let arm = load_arm(job.model.as_deref())?;
    let report = run_all_gestures(
        &arm,
        &cfg,
        &Gesture::all(crate::robot::Robot::LeftArm),
        job,
        progress,
    )?;
    let mut lines: Vec<String> = report
        .fidelity
        .iter()
        .map(|f| {
            format!(
                "{:<14} held-out joint DTW {:.4} rad/step in the shared hierarchy, {:.4} learned alone ({:.2}x)",
                f.gesture,
                f.shared_joint_dtw,
                f.alone_joint_dtw,
                f.ratio()
            )
        })
        .collect();
    lines.push(format!(
        "recognition of {} held-out demonstrations: CoSCo-HSOM {:.0} %, 1-NN DTW {:.0} %",
        report.queries.len(),
        100.0 * report.accuracy(),
        100.0 * report.nn_accuracy()
    ));
    Ok(lines)
}

/// Run the job on `gestures` as `job` says (demonstrations per gesture, seed, encoder noise,
/// transition, rendering) and write its files into `job.out`: `demos/<gesture>/demo_NN.csv`,
/// `model.bin`, `reproduction_<gesture>.csv`, `confusion.png`, `report.md`, `report.json`,
/// and with rendering `clip.gif` and `contact_sheet.png`.
fn run_all_gestures(
    arm: &NaoArm,
    config: &HsomConfig,
    gestures: &[Gesture],
    job: &Job,
    progress: Progress<'_>,
) -> Result<AllReport, ExperimentError> {
    let (count, transition, out) = (job.count, job.transition, &job.out);
    if count < 2 {
        return Err(ExperimentError::Invalid(format!(
            "--count {count} with --gesture all: at least 2 demonstrations per gesture (each is held out in turn)"
        )));
    }
    if gestures.len() < 2 {
        return Err(ExperimentError::Invalid(
            "--gesture all needs at least 2 gestures".into(),
        ));
    }
    if config.params().kind() != crate::config::Algorithm::Events {
        // refused before anything is recorded
        return Err(gerr(GestureError::NeedsEvents));
    }
    let labels: Vec<String> = gestures.iter().map(|g| g.name.to_string()).collect();
    let mut files = Vec::new();
    // 1. demonstrations, written into labelled subdirectories (`cosco train` reads them back)
    let demo_settings = DemoSettings {
        encoder_noise: job.noise,
        ..DemoSettings::default()
    };
    let mut all: Vec<Vec<Demonstration>> = Vec::new();
    for (i, g) in gestures.iter().enumerate() {
        progress("demonstrations", i, gestures.len());
        let demos = synthetic_demonstrations(arm, g, count, job.seed, &demo_settings, |_| {})?;
        for path in write_demos(&out.join("demos").join(g.name), &demos)? {
            files.push(
                path.strip_prefix(out)
                    .unwrap_or(&path)
                    .display()
                    .to_string(),
            );
        }
        all.push(demos);
    }
    progress("demonstrations", gestures.len(), gestures.len());
    // 2. leave-one-out folds
    let mut queries = Vec::new();
    let mut per_gesture: Vec<Vec<[f64; 6]>> = vec![Vec::new(); labels.len()];
    let mut wrist_missing = false;
    let mut last_model = None;
    // the saved model's reproductions on cue, kept for their files and the clip
    let (mut reproductions, mut executed) = (Vec::new(), Vec::<(String, Recording)>::new());
    let mut streams = Vec::new();
    for k in 0..count {
        progress("held-out folds", k, count);
        let sets: Vec<(String, Vec<Demonstration>)> = labels
            .iter()
            .zip(&all)
            .map(|(l, ds)| {
                let train = ds
                    .iter()
                    .enumerate()
                    .filter(|&(j, _)| j != k)
                    .map(|(_, d)| d.clone())
                    .collect();
                (l.clone(), train)
            })
            .collect();
        let model = config
            .fit_model(&sets, crate::hsom::Fit::default())
            .map_err(gerr)?;
        let nn = NearestNeighbour::new(
            sets.iter()
                .flat_map(|(l, ds)| ds.iter().map(move |d| (l.clone(), d.rows.clone())))
                .collect(),
            Band::None,
        );
        for (gi, (label, train)) in sets.iter().enumerate() {
            let test = &all[gi][k];
            // recognition, both classifiers
            let t = std::time::Instant::now();
            let r = model.recognize(&test.rows).map_err(gerr)?;
            let hsom_ms = 1e3 * t.elapsed().as_secs_f64();
            let t = std::time::Instant::now();
            let a = nn.classify(&test.rows).map_err(|e| werr("1-NN DTW", e))?;
            let nn_ms = 1e3 * t.elapsed().as_secs_f64();
            queries.push(AllQuery {
                expected: label.clone(),
                hsom: r.label.clone(),
                hsom_decided_fraction: r.decided_fraction(),
                hsom_ms,
                nn: a.label,
                nn_ms,
            });
            // fidelity on cue, shared and alone, executed on the arm
            let targets = std::slice::from_ref(test);
            let shared = model
                .branch(Some(label))
                .and_then(|b| Ok(b.reproduce(&test.rows[0])?))
                .map_err(gerr)?;
            let s = ArmExecutor { arm, transition }
                .execute(Method::Hierarchy, &shared.postures, targets)
                .map_err(ExperimentError::Invalid)?;
            let alone = FoldInput {
                config: Some(config),
                ..FoldInput::new(train, targets)
            };
            let a = on_arm(arm, transition, Method::Hierarchy, &alone)?.executed;
            let wrist = |e: &Executed<Recording>| e.fidelity.wrist_dtw_mm.map(|w| w.mean);
            wrist_missing |= wrist(&s).is_none() || wrist(&a).is_none();
            // the reversals of the gesture's most moving joint, the reproduction's against
            // the held-out demonstration's
            let j = most_moving(train);
            let reversals = |r: &crate::metrics::Smoothness| r.reversals.get(j).copied();
            let kept = match (
                reversals(&s.fidelity.reproduction_smoothness),
                s.fidelity.demo_smoothness.first().and_then(reversals),
            ) {
                (Some(r), Some(d)) => r.abs_diff(d) <= 1,
                _ => false,
            };
            per_gesture[gi].push([
                s.fidelity.joint_dtw_rad_per_step.mean,
                a.fidelity.joint_dtw_rad_per_step.mean,
                wrist(&s).unwrap_or(f64::NAN),
                wrist(&a).unwrap_or(f64::NAN),
                s.fidelity.duration_ratio.mean,
                f64::from(u8::from(kept)),
            ]);
            if k == count - 1 && job.recognize {
                streams.push(stream(&model, label, test)?);
            }
            if k == count - 1 {
                let stop = format!("{:?}", shared.stop);
                reproductions.push((label.clone(), shared.postures.len(), stop));
                executed.push((label.clone(), s.trace));
            }
        }
        last_model = Some(model);
    }
    progress("held-out folds", count, count);
    let model: GestureModel = last_model.expect("count >= 2 folds ran");
    let mean = |v: &[[f64; 6]], i: usize| v.iter().map(|x| x[i]).sum::<f64>() / v.len() as f64;
    let fidelity: Vec<GestureFidelity> = labels
        .iter()
        .zip(&per_gesture)
        .map(|(l, v)| GestureFidelity {
            gesture: l.clone(),
            shared_joint_dtw: mean(v, 0),
            alone_joint_dtw: mean(v, 1),
            shared_wrist_dtw_mm: (!wrist_missing).then(|| mean(v, 2)),
            alone_wrist_dtw_mm: (!wrist_missing).then(|| mean(v, 3)),
            shared_duration_ratio: mean(v, 4),
            reversals_kept: v.iter().filter(|x| x[5] > 0.0).count(),
            folds: v.len(),
            shared_per_fold: v.iter().map(|x| x[0]).collect(),
            alone_per_fold: v.iter().map(|x| x[1]).collect(),
        })
        .collect();
    let confusion = confusion_counts(
        &labels,
        queries.iter().map(|q| (&q.expected, q.hsom.as_ref())),
    );
    let nn_confusion =
        confusion_counts(&labels, queries.iter().map(|q| (&q.expected, Some(&q.nn))));
    // 3. the last fold's model, its reproductions on cue (executed in that fold) and files
    model
        .save(&out.join("model.bin"))
        .map_err(|e| werr("model.bin", e))?;
    files.push("model.bin".into());
    for (label, rec) in &executed {
        let rel = format!("reproduction_{label}.csv");
        let name = format!("CoSCo-HSOM reproduction of {label} (shared hierarchy)");
        write_csv(&out.join(&rel), &rec.to_demonstration(&name)).map_err(|err| werr(&rel, err))?;
        files.push(rel);
    }
    // 4. the confusion matrices as a figure
    let panel = |title: String, counts: &[Vec<usize>], unknown: bool| ConfusionPanel {
        title,
        rows: labels.clone(),
        columns: labels
            .iter()
            .cloned()
            .chain(unknown.then(|| "unknown".to_string()))
            .collect(),
        counts: counts
            .iter()
            .map(|r| r[..labels.len() + usize::from(unknown)].to_vec())
            .collect(),
    };
    let mut report = AllReport {
        labels: labels.clone(),
        config: config_name(job.config.as_deref()),
        count,
        seed: job.seed,
        noise: job.noise,
        fidelity,
        queries,
        confusion,
        nn_confusion,
        reproductions,
        files,
        streamed: streams.iter().map(|s| s.report.clone()).collect(),
    };
    confusion_png(
        &out.join("confusion.png"),
        "Recognition of held-out demonstrations (leave-one-out)",
        &[
            panel(
                format!("CoSCo-HSOM: {:.0} % right", 100.0 * report.accuracy()),
                &report.confusion,
                true,
            ),
            panel(
                format!("1-NN DTW: {:.0} % right", 100.0 * report.nn_accuracy()),
                &report.nn_confusion,
                false,
            ),
        ],
    )
    .map_err(|e| werr("confusion.png", e))?;
    report.files.push("confusion.png".into());
    // 5. the clip: the gestures in turn (with --recognize: the held-out demonstrations streamed,
    // captioned with the recogniser's answer from the sample it committed on)
    if job.render {
        let opts = clip_options();
        let stride = 3;
        let filmed: Vec<(&str, &Recording, Option<&StreamedGesture>)> = match streams.is_empty() {
            true => (executed.iter())
                .map(|(l, r)| (l.as_str(), r, None))
                .collect(),
            false => (streams.iter())
                .map(|s| (s.report.gesture.as_str(), &s.recording, Some(&s.report)))
                .collect(),
        };
        let total: usize = filmed
            .iter()
            .map(|(_, r, _)| r.len().div_ceil(stride))
            .sum();
        let mut clip: Option<Clip> = None;
        let mut sheet: Vec<image::RgbImage> = Vec::new();
        let (mut offset, mut done) = (0.0, 0);
        for &(label, rec, streamed) in &filmed {
            let on_frame = |n, _| progress("rendering", done + n, total);
            let part = match streamed {
                None => film(arm, rec, &opts, stride, on_frame)?,
                Some(g) => {
                    let mark = |i: usize, _: &crate::mujoco::Data<'_>, f: &mut image::RgbImage| {
                        caption(f, &g.caption(i, rec.time[i]), 18)
                    };
                    film_marked(arm, rec, &opts, stride, mark, on_frame)?
                }
            };
            done += part.len();
            // four frames of each gesture, one row of the contact sheet, named
            for i in sheet_frames(rec, stride, part.len()) {
                let (t, f) = part.frames().nth(i).expect("a key frame is a frame");
                let mut f = f.clone();
                if streamed.is_none() {
                    caption(&mut f, &format!("{label}  t = {t:.1} s"), 18);
                }
                sheet.push(f);
            }
            let c = match &mut clip {
                Some(c) => c,
                None => clip.insert(Clip::new(part.delay_ms())?),
            };
            for (t, frame) in part.frames() {
                c.push(offset + t, frame.clone())?;
            }
            offset += rec.time.last().copied().unwrap_or(0.0) + 1.0 / rec.rate_hz;
        }
        if let Some(c) = clip {
            c.write_gif(&out.join("clip.gif"))?;
            report.files.push("clip.gif".into());
            let picked: Vec<(Option<String>, &image::RgbImage)> =
                sheet.iter().map(|f| (None, f)).collect();
            save_png(
                &contact_sheet(&picked, SHEET_COLUMNS)?,
                &out.join("contact_sheet.png"),
            )?;
            report.files.push("contact_sheet.png".into());
        }
    }
    report
        .files
        .extend(["report.md".into(), "report.json".into()]);
    write_report(out, &report, &report.to_markdown())
        .map_err(ExperimentError::io("writing the report into", out))?;
    Ok(report)
}

/// Frames of `rec` (filmed every `stride` samples into `frames` frames) for its row of the
/// contact sheet: on the way to the apex (the posture farthest from the first), at the apex,
/// and on the way back, so that each row shows the gesture rather than its idle start.
fn sheet_frames(rec: &Recording, stride: usize, frames: usize) -> Vec<usize> {
    let first = &rec.qpos[0];
    let apex = (0..rec.qpos.len())
        .max_by(|&a, &b| {
            let d = |i: usize| crate::dtw::euclidean(&rec.qpos[i], first);
            d(a).total_cmp(&d(b))
        })
        .unwrap_or(0);
    let n = rec.qpos.len();
    [apex / 3, 2 * apex / 3, apex, apex + (n - apex) / 3]
        .iter()
        .map(|&i| (i / stride.max(1)).min(frames.saturating_sub(1)))
        .collect()
}

/// Confusion counts from (shown, answer) pairs: rows the labels, columns the labels then
/// `unknown` (an answer of `None` or of no label).
pub fn confusion_counts<'a>(
    labels: &[String],
    pairs: impl Iterator<Item = (&'a String, Option<&'a String>)>,
) -> Vec<Vec<usize>> {
    let mut m = vec![vec![0usize; labels.len() + 1]; labels.len()];
    for (shown, answer) in pairs {
        if let Some(r) = labels.iter().position(|l| l == shown) {
            let c = answer
                .and_then(|a| labels.iter().position(|l| l == a))
                .unwrap_or(labels.len());
            m[r][c] += 1;
        }
    }
    m
}

/// A confusion matrix as a Markdown table; with `unknown`, its last column is `unknown`
/// (a classifier that never answers it, such as 1-NN DTW, leaves it out).
pub fn confusion_markdown(m: &[Vec<usize>], labels: &[String], unknown: bool) -> String {
    let n = labels.len() + usize::from(unknown);
    let header = labels.iter().map(String::as_str);
    let mut table = Table::new(
        std::iter::once("gesture")
            .chain(header)
            .chain(unknown.then_some("unknown")),
    );
    for (l, row) in labels.iter().zip(m) {
        table.row(std::iter::once(l.clone()).chain(row.iter().take(n).map(|c| c.to_string())));
    }
    table.to_string()
}
