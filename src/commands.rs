//! The `cosco` subcommands that read and write files without the simulator (`train`,
//! `reproduce`, `recognize`, `evaluate`): the library's steps ([`crate::steps`]) put together
//! with the files they read and write, for the binary and the tests. Errors carry the file,
//! field and value, and what is allowed.

use std::path::{Path, PathBuf};

use crate::demos::sample_period;
use crate::hsom::{GestureModel, Reproduction};
use crate::labelled;
use crate::metrics::{FidelityReport, MetricsParams, StartEnd, StartEndReference};
use crate::steps;

/// Errors of the subcommands: the library's own, each naming the file, field or value.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CommandError {
    /// A file given to a step could not be read or used.
    #[error(transparent)]
    Step(#[from] steps::StepError),
    /// Demonstrations or a model of several gestures could not be read, trained or used.
    #[error(transparent)]
    Labelled(#[from] labelled::LabelledError),
    /// The gesture asked of a model of several gestures is not one of them.
    #[error(transparent)]
    Gesture(#[from] crate::hsom::GestureError),
    /// The configuration does not fit the data.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// A value given on the command line is not allowed.
    #[error("{0}")]
    Usage(String),
    /// Resuming after an encoder reading failed.
    #[error("resuming after {}", path.display())]
    Resume {
        /// The encoder reading.
        path: PathBuf,
        /// The cause.
        source: Box<steps::StepError>,
    },
    /// An output file could not be written.
    #[error("writing {}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The reproduction could not be put as CSV.
    #[error(transparent)]
    Csv(#[from] csv::Error),
    /// The answers could not be put as JSON.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    /// The arm's model or the arm's metrics failed.
    #[cfg(feature = "sim")]
    #[error(transparent)]
    Experiment(#[from] crate::experiment::ExperimentError),
}

/// The result of a subcommand.
pub type Result<T> = std::result::Result<T, CommandError>;

/// Write `bytes` atomically to `path`, naming it on failure.
fn write(path: &Path, bytes: &[u8]) -> Result<()> {
    crate::fsutil::write_atomic(path, bytes).map_err(|source| CommandError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// Load a model of one or several gestures (.bin or .txt).
pub fn load_gesture_model(path: &Path) -> Result<GestureModel> {
    Ok(labelled::load_gesture_model(path)?)
}

/// The binary model file of `model` by part (`Hsom::file_parts`), as `cosco inspect` prints
/// it: one line a part, its bytes, then the total and the configuration's ceiling for the
/// traced chunks (docs/BENCHMARKS.md, "The model file").
pub fn file_parts_lines(model: &crate::hsom::Hsom) -> String {
    let parts = model.file_parts();
    let total: usize = parts.iter().map(|p| p.bytes).sum();
    let mut s = String::from("binary model file by part (bytes):\n");
    for p in &parts {
        s.push_str(&format!("  {:>9}  {}\n", p.bytes, p.part));
    }
    s.push_str(&format!("  {total:>9}  total\n"));
    s.push_str(&format!(
        "  {:>9}  ceiling of the traced chunks this configuration allows\n",
        model.traced_ceiling()
    ));
    s
}

/// What `cosco evaluate` found (its `--json` document): the fidelity report's fields, and
/// the reproduction's start and end against the demonstrations given.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Evaluation {
    /// The fidelity metrics against the demonstrations.
    #[serde(flatten)]
    pub fidelity: FidelityReport,
    /// Its start speed against theirs and its mean final error against their end spread,
    /// in the diagonal of their bounding box (docs/METRICS.md, "Start and end").
    pub start_end: StartEnd,
    /// The unit of the distances: `rad` for the arm's joints, the data's own units otherwise.
    #[serde(skip)]
    pub unit: &'static str,
}

/// `cosco evaluate`: the fidelity metrics of a reproduction CSV against demonstrations, and
/// its start and end against theirs. Wrist paths need the arm's kinematics: with the feature
/// `sim` they are computed when the columns are the arm's joints (`model`: its MJCF file);
/// without it, never.
pub fn evaluate_files(
    reproduction: &Path,
    demo_paths: &[PathBuf],
    model: Option<&Path>,
) -> Result<Evaluation> {
    let (rep, demos) = steps::evaluation_inputs(reproduction, demo_paths)?;
    let params = MetricsParams {
        sample_period: sample_period(&demos[0]),
        ..MetricsParams::default()
    };
    let judged = |fidelity: FidelityReport, unit| {
        let reference = StartEndReference::of(&demos, crate::eval::diagonal(&demos));
        let start_end = reference.judge(
            &rep.rows,
            params.sample_period,
            fidelity.final_error_rad.mean,
        );
        Evaluation {
            fidelity,
            start_end,
            unit,
        }
    };
    #[cfg(feature = "sim")]
    if crate::experiment::are_arm_joints(&rep.columns) {
        let arm = crate::experiment::load_arm(model)?;
        let report = crate::sim::evaluate(Some(&arm), &demos, &rep.rows, &params)
            .map_err(crate::experiment::ExperimentError::from)?;
        return Ok(judged(report, "rad"));
    }
    let _ = model;
    Ok(judged(
        steps::evaluate_rows(&demos, &rep.rows, &params)?,
        "data units",
    ))
}

/// Human-readable lines of a reproduction's start and end against the demonstrations.
pub fn start_end_lines(s: &StartEnd, unit: &str) -> String {
    let num = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.4}"));
    let line = |label: String, value: String| format!("{label:<34}{value}\n");
    let verdict = |ok: bool, yes: &str, no: &str| if ok { yes } else { no }.to_string();
    line(
        format!("start speed ({unit}/s):"),
        format!(
            "{}; demonstrations' largest {}: {}",
            num(s.start_speed),
            num(s.demo_start_speed_max),
            verdict(
                s.start_in_range,
                "in range",
                "FASTER than every demonstration's start"
            )
        ),
    ) + &line(
        format!("final error ({unit}):"),
        format!(
            "{:.4}; demonstrations' end spread {:.4}, tolerance {:.4}: {}",
            s.final_error,
            s.end_spread,
            s.end_tolerance,
            verdict(s.end_within_spread, "within", "OUTSIDE the spread")
        ),
    )
}

/// Human-readable lines of a fidelity report.
pub fn fidelity_lines(f: &FidelityReport, unit: &str) -> String {
    let st = |s: &crate::metrics::Stat| format!("mean {:.4}, worst {:.4}", s.mean, s.worst);
    let mut out = String::new();
    let line = |label: String, value: String| format!("{label:<34}{value}\n");
    out += &line(
        format!("joint DTW ({unit}/step):"),
        st(&f.joint_dtw_rad_per_step),
    );
    if let Some(w) = &f.wrist_dtw_mm {
        out += &line("wrist-path DTW (mm/step):".into(), st(w));
    } else if cfg!(not(feature = "sim")) {
        out += &line(
            "wrist-path DTW (mm/step):".into(),
            "n/a (built without the `sim` feature: no arm kinematics)".into(),
        );
    }
    out += &line(format!("apex error ({unit}):"), st(&f.apex_error_rad));
    out += &line(
        format!("final-posture error ({unit}):"),
        st(&f.final_error_rad),
    );
    out += &line("duration ratio:".into(), st(&f.duration_ratio));
    out += &format!(
        "smoothness: normalized jerk {}, velocity reversals {} ({:?} per column)\n",
        f.reproduction_smoothness
            .normalized_jerk
            .map_or("n/a".into(), |j| format!("{j:.0}")),
        f.reproduction_smoothness.total_reversals,
        f.reproduction_smoothness.reversals
    );
    out
}

/// `cosco train`: read (one gesture, or labelled directories of several; resampled to
/// `resample` Hz when given), train
/// (`progress(done, total)`), save atomically.
pub fn train_files(
    config: Option<&Path>,
    demo_paths: &[PathBuf],
    out: &Path,
    state_length_from_data: bool,
    resample: Option<f64>,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<GestureModel> {
    // where the model goes is checked before any reading or training
    steps::check_model_output(out)?;
    let mut cfg = steps::config(config)?;
    if state_length_from_data {
        let sets = labelled::read_demo_sets_at(demo_paths, None, resample)?;
        let width = match &sets {
            labelled::DemoSets::Plain(d) => d[0].width(),
            labelled::DemoSets::Labelled(s) => s[0].1[0].width(),
        };
        cfg = cfg.for_width(width)?;
    }
    let sets = labelled::read_demo_sets_at(demo_paths, Some(cfg.params().state_length), resample)?;
    let model = labelled::train_sets(&cfg, &sets, progress)?;
    labelled::save_gesture_model(&model, out)?;
    Ok(model)
}

/// Write a reproduction CSV atomically (`step`, then the model's columns).
fn write_reproduction(model: &GestureModel, rep: &Reproduction, out: &Path) -> Result<()> {
    let bytes = steps::reproduction_csv(&model.branches()[0], rep)?;
    write(out, &bytes)
}

/// `cosco reproduce` with a model of one or several gestures: gesture `label` (required with
/// several) from the command line's initial posture or a demonstration's first row; with
/// `resume_from` (an encoder reading of part of that reproduction) the rest of it
/// ([`Hsom::resume`](crate::hsom::Hsom::resume)). Returns the number of postures and the
/// gesture.
pub fn reproduce_gesture_file(
    model: &Path,
    label: Option<&str>,
    initial: Option<&str>,
    initial_from: Option<&Path>,
    resume_from: Option<&Path>,
    out: &Path,
) -> Result<(usize, Option<String>)> {
    let m = load_gesture_model(model)?;
    // the gesture is checked before the initial posture is read
    let branch = m.branch(label)?;
    let initial = match (initial, initial_from) {
        (Some(text), None) => parse_posture(text)?,
        (None, Some(p)) => steps::initial_from_file(branch, p)?,
        _ => {
            return Err(CommandError::Usage(
                "give exactly one of --initial and --initial-from".into(),
            ))
        }
    };
    let rep = match resume_from {
        Some(path) => {
            let reading = steps::rows_from_file(branch, path)?;
            steps::resume(branch, &model.display().to_string(), &initial, &reading).map_err(
                |source| CommandError::Resume {
                    path: path.to_path_buf(),
                    source: Box::new(source),
                },
            )?
        }
        None => labelled::reproduce_gesture(&m, &model.display().to_string(), label, &initial)?,
    };
    write_reproduction(&m, &rep, out)?;
    Ok((rep.postures.len(), label.map(str::to_string)))
}

/// `cosco reproduce --prefix-from CSV --prefix N`: continue the gesture the hierarchy
/// recognises in the file's first N samples.
pub fn continue_file(
    model: &Path,
    prefix_from: &Path,
    prefix: usize,
    out: &Path,
) -> Result<(usize, Option<String>)> {
    let m = load_gesture_model(model)?;
    let (label, rep) = labelled::continue_file(&m, prefix_from, prefix)?;
    write_reproduction(&m, &rep, out)?;
    Ok((rep.postures.len(), Some(label)))
}

/// `cosco recognize`: one line per file (label, scores, early decision), an accuracy line
/// when the files came from label subdirectories; every answer as JSON when asked.
pub fn recognize_lines(model: &Path, demos: &Path, json: Option<&Path>) -> Result<Vec<String>> {
    let m = load_gesture_model(model)?;
    let answers = labelled::recognize_paths(&m, demos)?;
    let mut lines = Vec::new();
    for a in &answers {
        let r = &a.recognition;
        let scores: Vec<String> = r
            .scores
            .iter()
            .zip(&r.thresholds)
            .map(|((l, s), t)| format!("{l} {s:.4} (threshold {t:.4})"))
            .collect();
        lines.push(format!(
            "{}: {}{} | decided at sample {} of {} | scores: {}",
            a.file,
            r.label.as_deref().unwrap_or("unknown"),
            a.expected
                .as_ref()
                .map_or(String::new(), |e| format!(" (expected {e})")),
            r.decided_at,
            r.samples,
            scores.join(", ")
        ));
    }
    let labelled_files: Vec<_> = answers.iter().filter(|a| a.expected.is_some()).collect();
    if !labelled_files.is_empty() {
        let right = labelled_files
            .iter()
            .filter(|a| a.expected == a.recognition.label)
            .count();
        lines.push(format!(
            "{right} of {} recognised as their directory's label",
            labelled_files.len()
        ));
    }
    if let Some(p) = json {
        let bytes = serde_json::to_vec_pretty(&answers)?;
        write(p, &bytes)?;
    }
    Ok(lines)
}

/// Parse `"v1,v2,..."` into numbers, naming the bad entry.
pub fn parse_posture(text: &str) -> Result<Vec<f64>> {
    text.split(',')
        .enumerate()
        .map(|(i, v)| {
            let v = v.trim();
            match v.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(CommandError::Usage(format!(
                    "--initial: value {} is '{v}': need a finite number",
                    i + 1
                ))),
            }
        })
        .collect()
}
