//! Recognition held out (docs/ALGORITHM.md, section 4): one hierarchy taught several
//! labelled gestures, asked about demonstrations it did not learn from. For each taught
//! demonstration in turn, the model of several gestures is trained on every other taught
//! demonstration and recognises it (accepted: its own label, not `unknown`; also whether its
//! label scores lowest); every untaught demonstration is recognised by the model trained on
//! all taught ones (right: `unknown`). The untrained model (seeded initial weights,
//! calibrated the same way) answers the same questions: the negative control, which must
//! fail the gates ([`ACCEPT_GATE`], [`UNKNOWN_GATE`]).
//!
//! Used by `cosco recognition` (any recorded data, [`recognition`]) and the tests
//! ([`recognition_study`]). Its errors are the held-out studies' [`LooError`].

mod report;
pub mod stream;
pub mod teaching;

use std::path::PathBuf;

use serde::Serialize;

use super::loo::{check_width, loo_map, write};
use super::Split;
use super::{LooError, MIN_TAUGHT_DEMOS};

use crate::config::{load_config_or_default, HsomConfig};
use crate::demo_sets::{read_demo_sets, DemoSets};
use crate::demos::{is_plain_label, Demonstration};
use crate::fsutil::check_output;
use crate::hsom::{GestureError, GestureModel, StreamCalibration};

pub use report::{recognition_json, recognition_markdown};

/// Labelled sets of demonstrations: `(label, demonstrations)`.
pub type LabelledSets = Vec<(String, Vec<Demonstration>)>;

/// The gate on held-out demonstrations of taught gestures: at least this fraction accepted
/// (recognised as their own label).
pub const ACCEPT_GATE: f64 = 0.97;

/// The gate on demonstrations of untaught gestures: at least this fraction called `unknown`.
pub const UNKNOWN_GATE: f64 = 0.90;

/// What the study runs besides the trained model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RecognitionSettings {
    /// Also the untrained model (the negative control).
    pub control: bool,
    /// Teach every model one gesture after another ([`teaching`]), and reproduce each
    /// held-out demonstration's gesture with it, with the model taught at once and with the
    /// model right after its gesture was taught.
    pub one_at_a_time: bool,
    /// Worker threads (at least 1); the result does not depend on their number.
    pub threads: usize,
    /// Also stream every demonstration, a sample at a time, into the recogniser of the model
    /// that answers it ([`stream`]), under the rule and under the first-sample control.
    pub stream: bool,
}

impl Default for RecognitionSettings {
    fn default() -> Self {
        RecognitionSettings {
            control: true,
            one_at_a_time: false,
            threads: 1,
            stream: false,
        }
    }
}

/// One demonstration recognised.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Answer {
    /// Its own gesture label (taught or untaught).
    pub label: String,
    /// The demonstration (its file).
    pub demonstration: String,
    /// The model's answer (`None`: unknown).
    pub answer: Option<String>,
    /// The label with the lowest score.
    pub best: String,
    /// The lowest score.
    pub best_score: f64,
    /// The threshold of the label with the lowest score.
    pub threshold: f64,
    /// The score of its own label (`None` for an untaught gesture).
    pub own_score: Option<f64>,
    /// Streamed into the recogniser (with [`RecognitionSettings::stream`]): under the rule,
    /// then under the first-sample control.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub streamed: Option<Box<[stream::Streamed; 2]>>,
}

/// The answers of one model (trained, or the untrained control).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Answers {
    /// Every taught demonstration, recognised by the model trained without it.
    pub held_out: Vec<Answer>,
    /// Every untaught demonstration, recognised by the model trained on all taught ones.
    pub untaught: Vec<Answer>,
}

/// The fraction of `answers` that are `right` (`None` without any).
pub(crate) fn fraction(answers: &[Answer], right: fn(&Answer) -> bool) -> Option<f64> {
    (!answers.is_empty())
        .then(|| answers.iter().filter(|a| right(a)).count() as f64 / answers.len() as f64)
}

impl Answer {
    /// Recognised as its own label.
    pub fn accepted(&self) -> bool {
        self.answer.as_ref() == Some(&self.label)
    }

    /// Its own label scores lowest (whether or not it is below its threshold).
    pub fn right_by_best(&self) -> bool {
        self.best == self.label
    }

    /// Called `unknown`.
    pub fn unknown(&self) -> bool {
        self.answer.is_none()
    }

    /// Answered with a (taught) label other than its own.
    pub fn other_label(&self) -> bool {
        self.answer.as_ref().is_some_and(|l| *l != self.label)
    }
}

impl Answers {
    /// Fraction of held-out taught demonstrations recognised as their own label.
    pub fn accepted(&self) -> Option<f64> {
        fraction(&self.held_out, Answer::accepted)
    }

    /// Fraction of held-out taught demonstrations whose own label scores lowest (whether or
    /// not it is below its threshold).
    pub fn right_by_best(&self) -> Option<f64> {
        fraction(&self.held_out, Answer::right_by_best)
    }

    /// Fraction of untaught demonstrations called `unknown` (`None` without any).
    pub fn unknown(&self) -> Option<f64> {
        fraction(&self.untaught, Answer::unknown)
    }

    /// Whether both gates pass: held-out accepted at least [`ACCEPT_GATE`] and, when there
    /// are untaught demonstrations, `unknown` for at least [`UNKNOWN_GATE`] of them.
    pub fn passes(&self) -> bool {
        self.accepted().is_some_and(|a| a >= ACCEPT_GATE)
            && self.unknown().map_or(true, |u| u >= UNKNOWN_GATE)
    }
}

/// The study: the taught and untaught labels, the trained model's answers and the control's.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecognitionStudy {
    /// The taught labels, in the model's order.
    pub taught: Vec<String>,
    /// The untaught labels.
    pub untaught: Vec<String>,
    /// The trained model's answers.
    pub model: Answers,
    /// The untrained model's answers (`None` without the control).
    pub control: Option<Answers>,
    /// Taught one gesture at a time: every held-out demonstration's gesture reproduced by
    /// the three models of its fold (empty otherwise).
    pub reproduced: Vec<teaching::Reproduced>,
}

/// One unit of work: a fold (taught label, demonstration held out) or the model of all
/// taught demonstrations (for the untaught ones); trained or untrained.
#[derive(Debug, Clone, Copy)]
enum Job {
    Fold { g: usize, i: usize, learn: bool },
    All { learn: bool },
}

/// What a job answered.
enum Done {
    Fold(Answer, Option<teaching::Reproduced>),
    All(Vec<Answer>),
}

/// How a demonstration is asked: its label, whether the label is taught, and the recogniser's
/// calibration of the model when it is also streamed (made once a model).
struct Query<'a> {
    label: &'a str,
    taught: bool,
    calibration: Option<StreamCalibration>,
}

/// `model`'s recogniser calibration when the study streams (`stream`).
fn calibration(
    model: &GestureModel,
    stream: bool,
    what: &str,
) -> Result<Option<StreamCalibration>, LooError> {
    let c = stream.then(|| model.stream_calibration()).transpose();
    c.map_err(|e| LooError::Gesture {
        what: format!("{what}, calibrating its recogniser"),
        source: Box::new(e),
    })
}

fn answer(
    model: &GestureModel,
    q: &Query<'_>,
    demo: &Demonstration,
    what: &str,
) -> Result<Answer, LooError> {
    let label = q.label;
    let gesture = |e: GestureError| LooError::Gesture {
        what: format!("{what}, recognising {}", demo.source),
        source: Box::new(e),
    };
    let r = model.recognize(&demo.rows).map_err(gesture)?;
    let streamed = match &q.calibration {
        None => None,
        Some(c) => {
            let expected = q.taught.then_some(label);
            let rule = stream::stream(model, c, &demo.rows, expected, stream::Policy::Rule);
            let first = stream::stream(model, c, &demo.rows, expected, stream::Policy::FirstSample);
            Some(Box::new([rule.map_err(gesture)?, first.map_err(gesture)?]))
        }
    };
    let b = model
        .labels()
        .iter()
        .position(|l| *l == r.best)
        .unwrap_or(0);
    Ok(Answer {
        label: label.to_string(),
        demonstration: demo.source.clone(),
        answer: r.label,
        best: r.best,
        best_score: r.scores[b].1,
        threshold: r.thresholds[b],
        own_score: r.scores.iter().find(|(l, _)| l == label).map(|s| s.1),
        streamed,
    })
}

fn train(
    config: &HsomConfig,
    sets: &[(String, Vec<Demonstration>)],
    learn: bool,
    what: &str,
) -> Result<GestureModel, LooError> {
    let how = crate::hsom::Fit {
        progress: None,
        untrained: !learn,
    };
    config.fit_model(sets, how).map_err(|e| LooError::Gesture {
        what: what.to_string(),
        source: Box::new(e),
    })
}

/// `model`'s answer to every untaught demonstration.
fn untaught_answers(
    model: &GestureModel,
    untaught: &[(String, Vec<Demonstration>)],
    stream: bool,
    what: &str,
) -> Result<Done, LooError> {
    let calibration = calibration(model, stream, what)?;
    untaught
        .iter()
        .flat_map(|(l, ds)| ds.iter().map(move |d| (l, d)))
        .map(|(label, d)| {
            let q = Query {
                label,
                taught: false,
                calibration: calibration.clone(),
            };
            answer(model, &q, d, what)
        })
        .collect::<Result<_, _>>()
        .map(Done::All)
}

fn run_job(
    config: &HsomConfig,
    taught: &[(String, Vec<Demonstration>)],
    untaught: &[(String, Vec<Demonstration>)],
    job: Job,
    settings: &RecognitionSettings,
) -> Result<Done, LooError> {
    let (one_at_a_time, stream) = (settings.one_at_a_time, settings.stream);
    let taught_query = |g: usize, m: &GestureModel, what: &str| -> Result<Query, LooError> {
        Ok(Query {
            label: &taught[g].0,
            taught: true,
            calibration: calibration(m, stream, what)?,
        })
    };
    match job {
        Job::Fold { g, i, learn: true } if one_at_a_time => {
            let (m, r) = teaching::fold(config, taught, g, i)?;
            let what = format!(
                "the model taught one gesture at a time without {}",
                taught[g].1[i].source
            );
            let a = answer(&m, &taught_query(g, &m, &what)?, &taught[g].1[i], &what)?;
            Ok(Done::Fold(a, Some(r)))
        }
        Job::All { learn: true } if one_at_a_time => {
            let what = "the model taught every taught gesture one at a time";
            let m = teaching::in_turn(config, taught, what, |_, _| Ok(()))?;
            untaught_answers(&m, untaught, stream, what)
        }
        Job::Fold { g, i, learn } => {
            let demos = &taught[g].1;
            let mut sets = taught.to_vec();
            sets[g].1.remove(i);
            let what = format!("the model trained without {}", demos[i].source);
            let m = train(config, &sets, learn, &what)?;
            Ok(Done::Fold(
                answer(&m, &taught_query(g, &m, &what)?, &demos[i], &what)?,
                None,
            ))
        }
        Job::All { learn } => {
            let what = "the model trained on every taught demonstration";
            let m = train(config, taught, learn, what)?;
            untaught_answers(&m, untaught, stream, what)
        }
    }
}

/// Check the sets: at least one taught label, each with at least [`MIN_TAUGHT_DEMOS`]
/// demonstrations, labels plain and distinct, every demonstration valid and of the first
/// taught demonstration's columns, `stateLength` of them.
fn check_sets(
    config: &HsomConfig,
    taught: &[(String, Vec<Demonstration>)],
    untaught: &[(String, Vec<Demonstration>)],
) -> Result<(), LooError> {
    let first = taught
        .first()
        .and_then(|(_, d)| d.first())
        .ok_or(LooError::NoTaught)?;
    let named = taught
        .iter()
        .map(|s| (s, "taught"))
        .chain(untaught.iter().map(|s| (s, "untaught")));
    let mut seen: Vec<(&str, &'static str)> = Vec::new();
    for ((label, demos), kind) in named {
        if !is_plain_label(label) {
            return Err(LooError::BadLabel {
                path: demos.first().map_or_else(String::new, |d| d.source.clone()),
                label: label.clone(),
            });
        }
        if let Some(&(_, first)) = seen.iter().find(|(l, _)| l == label) {
            return Err(LooError::DuplicateLabel {
                label: label.clone(),
                first,
                second: kind,
            });
        }
        seen.push((label, kind));
        if kind == "taught" && demos.len() < MIN_TAUGHT_DEMOS {
            return Err(LooError::TooFewTaught {
                label: label.clone(),
                found: demos.len(),
            });
        }
        crate::demos::validate_set(demos, None)?;
        if let Some(d) = demos.iter().find(|d| d.columns != first.columns) {
            return Err(LooError::Columns {
                path: d.source.clone(),
                found: d.columns.clone(),
                first: first.source.clone(),
                expected: first.columns.clone(),
            });
        }
    }
    // every demonstration has the first one's columns by now
    check_width(std::iter::once(first), config)
}

/// The study on labelled sets (`taught`: at least one label, each with at least
/// [`MIN_TAUGHT_DEMOS`] demonstrations; `untaught`: any, possibly none), with `config` (the
/// events extension, of the data's `stateLength`); `progress(done, total)` after each model
/// trained and asked.
pub fn recognition_study(
    config: &HsomConfig,
    taught: &[(String, Vec<Demonstration>)],
    untaught: &[(String, Vec<Demonstration>)],
    settings: &RecognitionSettings,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<RecognitionStudy, LooError> {
    if settings.threads == 0 {
        return Err(LooError::Threads(0));
    }
    check_sets(config, taught, untaught)?;
    // the trained model's folds, then the control's: the held-out loop on the taught sets,
    // once per model; each model's answers to the untaught beside
    let learns: Vec<bool> = [true, false]
        .into_iter()
        .filter(|&learn| learn || settings.control)
        .collect();
    let sets: Vec<&[Demonstration]> = (learns.iter())
        .flat_map(|_| taught.iter().map(|(_, d)| &d[..]))
        .collect();
    let pool = super::Pool::new(settings.threads).map_err(LooError::Pool)?;
    let n = taught.len();
    let folds = loo_map(&sets, false, &pool, progress, |s, split| {
        let Split::HeldOut(i) = split else {
            return Err(LooError::NoTaught);
        };
        let learn = s < n;
        run_job(
            config,
            taught,
            untaught,
            Job::Fold { g: s % n, i, learn },
            settings,
        )
    });
    let whole: Vec<bool> = learns
        .iter()
        .filter(|_| !untaught.is_empty())
        .copied()
        .collect();
    let mut whole = pool
        .map(
            &whole,
            |&learn| run_job(config, taught, untaught, Job::All { learn }, settings),
            None,
        )
        .into_iter();
    let (mut model, mut control) = (Answers::default(), Answers::default());
    let mut reproduced = Vec::new();
    let per_model = taught.iter().map(|(_, d)| d.len()).sum();
    let mut folds = folds.into_iter().flat_map(|(held_out, _)| held_out);
    for learn in learns {
        let to = if learn { &mut model } else { &mut control };
        for d in folds.by_ref().take(per_model).chain(whole.next()) {
            match d? {
                Done::Fold(a, r) => {
                    to.held_out.push(a);
                    reproduced.extend(r);
                }
                Done::All(a) => to.untaught = a,
            }
        }
    }
    Ok(RecognitionStudy {
        taught: taught.iter().map(|(l, _)| l.clone()).collect(),
        untaught: untaught.iter().map(|(l, _)| l.clone()).collect(),
        model,
        control: settings.control.then_some(control),
        reproduced,
    })
}

/// The labelled sets of `paths`: each a directory of CSV files (one gesture, named after the
/// directory) or of gesture subdirectories (`DIR/<gesture>/*.csv`), resampled to
/// `resample_hz` when given.
pub fn read_labelled_dirs(
    paths: &[PathBuf],
    resample_hz: Option<f64>,
) -> Result<LabelledSets, LooError> {
    let mut sets = Vec::new();
    for p in paths {
        if !p.is_dir() {
            return Err(LooError::NotADirectory {
                path: p.display().to_string(),
            });
        }
        match read_demo_sets(std::slice::from_ref(p), None, resample_hz)? {
            DemoSets::Plain(d) => {
                let label = p
                    .canonicalize()
                    .ok()
                    .and_then(|c| c.file_name().map(|n| n.to_string_lossy().to_string()))
                    .unwrap_or_default();
                if !is_plain_label(&label) {
                    return Err(LooError::BadLabel {
                        path: p.display().to_string(),
                        label,
                    });
                }
                sets.push((label, d));
            }
            DemoSets::Labelled(s) => sets.extend(s),
        }
    }
    Ok(sets)
}

/// What `cosco recognition` does.
#[derive(Debug, Clone)]
pub struct RecognitionJob {
    /// Directories of the taught gestures (see [`read_labelled_dirs`]).
    pub taught: Vec<PathBuf>,
    /// Directories of the untaught gestures.
    pub untaught: Vec<PathBuf>,
    /// Configuration file (default: the built-in recommended one).
    pub config: Option<PathBuf>,
    /// Take `stateLength` from the data.
    pub state_length_from_data: bool,
    /// Resample the demonstrations to this rate, Hz.
    pub resample: Option<f64>,
    /// The control, the threads.
    pub settings: RecognitionSettings,
    /// Where to write every answer as JSON.
    pub json: Option<PathBuf>,
}

/// `cosco recognition`: the study on directories of demonstration files; the Markdown
/// tables, after writing the JSON when asked.
pub fn recognition(
    job: &RecognitionJob,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<String, LooError> {
    if let Some(p) = &job.json {
        check_output(p)?;
    }
    let cfg = load_config_or_default(job.config.as_deref())?;
    let taught = read_labelled_dirs(&job.taught, job.resample)?;
    let untaught = read_labelled_dirs(&job.untaught, job.resample)?;
    let width = taught
        .first()
        .and_then(|(_, d)| d.first())
        .ok_or(LooError::NoTaught)?
        .width();
    let cfg = match job.state_length_from_data {
        true => cfg.for_width(width)?,
        false => cfg,
    };
    let study = recognition_study(&cfg, &taught, &untaught, &job.settings, progress)?;
    if let Some(p) = &job.json {
        write(p, recognition_json(&study).as_bytes())?;
    }
    Ok(recognition_markdown(&study))
}
