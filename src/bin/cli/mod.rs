//! The steps shared by the `simulate` and `cosco` binaries: progress bars, printing, and the
//! library's steps ([`cosco_hsom::steps`]) with `anyhow` errors (binaries only); the library's
//! typed errors carry the file, field and value. What needs the simulated arm is in [`arm`].
#![allow(dead_code)]

#[cfg(feature = "sim")]
pub mod arm;
#[cfg(feature = "sim")]
pub mod compare;
pub mod export;
#[cfg(feature = "sim")]
pub mod sweep;

#[cfg(feature = "sim")]
pub use arm::*;

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};

use cosco_hsom::config::HsomConfig;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::hsom::{GestureModel, Hsom, Reproduction};
use cosco_hsom::labelled;
use cosco_hsom::metrics::{FidelityReport, MetricsParams};
#[cfg(feature = "sim")]
pub use cosco_hsom::steps::DEFAULT_CONFIG_NAME;
use cosco_hsom::steps::{self, sample_period};

/// A progress bar on stderr (hidden when stderr is not a terminal).
pub fn progress(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template(
            "{msg:>14} [{bar:40.cyan/blue}] {pos}/{len} {elapsed_precise}",
        )
        .expect("static template")
        .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    pb
}

/// Load a CoSCo-HSOM configuration file, or the built-in recommended configuration.
pub fn hsom_config(path: Option<&Path>) -> Result<HsomConfig> {
    Ok(steps::config(path)?)
}

/// How a report names the configuration: its path, or the built-in default's name.
#[cfg(feature = "sim")]
pub fn config_name(path: Option<&Path>) -> String {
    path.map_or(DEFAULT_CONFIG_NAME.into(), |p| p.display().to_string())
}

/// Read demonstration files (a directory of *.csv or explicit files), checked as a set.
pub fn read_demos(paths: &[PathBuf], state_length: Option<usize>) -> Result<Vec<Demonstration>> {
    Ok(steps::read_demos(paths, state_length)?)
}

/// Train with a progress bar.
pub fn train(cfg: &HsomConfig, demos: &[Demonstration]) -> Result<Hsom> {
    let pb = progress(cfg.params().training_steps as u64, "training");
    let model = steps::train(
        cfg,
        demos,
        Some(&|done, _total| pb.set_position(done as u64)),
    )?;
    pb.finish_and_clear();
    Ok(model)
}

/// `cosco evaluate`: the fidelity metrics of a reproduction CSV against demonstrations, and
/// the unit of its distances (`rad` for the arm's joints, the data's own units otherwise).
/// Wrist paths need the arm's kinematics: with the feature `sim` they are computed when the
/// columns are the arm's joints (`model`: its MJCF file); without it, never.
pub fn evaluate_files(
    reproduction: &Path,
    demo_paths: &[PathBuf],
    model: Option<&Path>,
) -> Result<(FidelityReport, &'static str)> {
    let (rep, demos) = steps::evaluation_inputs(reproduction, demo_paths)?;
    let params = MetricsParams {
        sample_period: sample_period(&demos[0]),
        ..MetricsParams::default()
    };
    #[cfg(feature = "sim")]
    if cosco_hsom::experiment::are_arm_joints(&rep.columns) {
        let arm = load_arm(model)?;
        let report = cosco_hsom::experiment::evaluate(Some(&arm), &demos, &rep.rows, &params)?;
        return Ok((report, "rad"));
    }
    let _ = model;
    Ok((
        steps::evaluate_rows(&demos, &rep.rows, &params)?,
        "data units",
    ))
}

/// Human-readable lines of a fidelity report.
pub fn fidelity_lines(f: &FidelityReport, unit: &str) -> String {
    let st = |s: &cosco_hsom::metrics::Stat| format!("mean {:.4}, worst {:.4}", s.mean, s.worst);
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

/// `cosco train`: read (one gesture, or labelled directories of several), train with a
/// progress bar, save atomically.
pub fn train_files(
    config: Option<&Path>,
    demo_paths: &[PathBuf],
    out: &Path,
    state_length_from_data: bool,
    resample: Option<f64>,
) -> Result<GestureModel> {
    // where the model goes is checked before any reading or training
    steps::check_model_output(out)?;
    let mut cfg = hsom_config(config)?;
    if state_length_from_data {
        let sets = labelled::read_demo_sets_at(demo_paths, None, resample)?;
        let width = match &sets {
            labelled::DemoSets::Plain(d) => d[0].width(),
            labelled::DemoSets::Labelled(s) => s[0].1[0].width(),
        };
        cfg = cfg.for_width(width)?;
    }
    let sets = labelled::read_demo_sets_at(demo_paths, Some(cfg.params().state_length), resample)?;
    let pb = progress(cfg.params().training_steps as u64, "training");
    let model = labelled::train_sets(
        &cfg,
        &sets,
        Some(&|done, _total| pb.set_position(done as u64)),
    )?;
    pb.finish_and_clear();
    labelled::save_gesture_model(&model, out)?;
    Ok(model)
}

/// Load a model of one or several gestures (.bin or .txt).
pub fn load_gesture_model(path: &Path) -> Result<GestureModel> {
    Ok(labelled::load_gesture_model(path)?)
}

/// Write a reproduction CSV atomically (`step`, then the model's columns).
fn write_reproduction(model: &GestureModel, rep: &Reproduction, out: &Path) -> Result<()> {
    let bytes = steps::reproduction_csv(&model.branches()[0], rep)?;
    cosco_hsom::fsutil::write_atomic(out, &bytes)
        .with_context(|| format!("writing {}", out.display()))
}

/// `cosco reproduce` with a model of one or several gestures: gesture `label` (required with
/// several) from the command line's initial posture or a demonstration's first row; with
/// `resume_from` (an encoder reading of part of that reproduction) the rest of it
/// ([`Hsom::resume`](cosco_hsom::hsom::Hsom::resume)). Returns the number of postures and the
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
        _ => bail!("give exactly one of --initial and --initial-from"),
    };
    let rep = match resume_from {
        Some(path) => {
            let reading = steps::rows_from_file(branch, path)?;
            steps::resume(branch, &model.display().to_string(), &initial, &reading)
                .with_context(|| format!("resuming after {}", path.display()))?
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
        cosco_hsom::fsutil::write_atomic(p, &bytes)
            .with_context(|| format!("writing {}", p.display()))?;
    }
    Ok(lines)
}

/// Load a saved model (.bin or .txt).
pub fn load_model(path: &Path) -> Result<Hsom> {
    Ok(steps::load_model(path)?)
}

/// The error and its causes on one line ([`steps::error_line`]).
pub fn error_line(e: &anyhow::Error) -> String {
    steps::error_line(e.as_ref())
}

/// Parse `"v1,v2,..."` into numbers, naming the bad entry.
pub fn parse_posture(text: &str) -> Result<Vec<f64>> {
    text.split(',')
        .enumerate()
        .map(|(i, v)| {
            let v = v.trim();
            match v.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => bail!("--initial: value {} is '{v}': need a finite number", i + 1),
            }
        })
        .collect()
}

/// `cosco reproduce`: the initial posture from the command line or a demonstration's first
/// row, the reproduction written as `step` + the model's column names. Returns the number of
/// postures.
pub fn reproduce_file(
    model: &Path,
    initial: Option<&str>,
    initial_from: Option<&Path>,
    out: &Path,
) -> Result<usize> {
    let m = load_model(model)?;
    let initial = match (initial, initial_from) {
        (Some(text), None) => parse_posture(text)?,
        (None, Some(p)) => steps::initial_from_file(&m, p)?,
        _ => bail!("give exactly one of --initial and --initial-from"),
    };
    let rep = steps::reproduce(&m, &model.display().to_string(), &initial)?;
    let bytes = steps::reproduction_csv(&m, &rep)?;
    cosco_hsom::fsutil::write_atomic(out, &bytes)
        .with_context(|| format!("writing {}", out.display()))?;
    Ok(rep.postures.len())
}

/// `--count`: a whole number of demonstrations, at least 1 (negative numbers reach this
/// parser, so that `--count -1` is answered with what is allowed, not "unexpected argument").
#[cfg(feature = "sim")]
pub fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "expected a whole number of demonstrations, at least 1; got {s:?}"
        )),
    }
}

/// `--seed`: a whole number from 0 to 2^64 - 1.
#[cfg(feature = "sim")]
pub fn parse_seed(s: &str) -> Result<u64, String> {
    s.trim()
        .parse::<u64>()
        .map_err(|_| format!("expected a whole number from 0 to {}; got {s:?}", u64::MAX))
}

/// `--noise`: a standard deviation in rad, finite and at least 0.
#[cfg(feature = "sim")]
pub fn parse_noise(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!(
            "expected a standard deviation in rad: a finite number >= 0; got {s:?}"
        )),
    }
}

/// Every core (1 when it cannot be told).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// What `cosco heldout` does.
pub struct HeldoutJob {
    /// Demonstration paths, as for `cosco train`.
    pub demos: Vec<PathBuf>,
    /// Configuration file (default: the built-in recommended one).
    pub config: Option<PathBuf>,
    /// Take `stateLength` from the data.
    pub state_length_from_data: bool,
    /// Resample the demonstrations to this rate, Hz.
    pub resample: Option<f64>,
    /// Override the configuration's consensus.
    pub consensus: Option<cosco_hsom::config::Consensus>,
    /// Override the configuration's plan.
    pub plan: Option<cosco_hsom::config::Plan>,
    /// Override the configuration's alignment.
    pub alignment: Option<cosco_hsom::config::Alignment>,
    /// Override the configuration's knots.
    pub knots: Option<cosco_hsom::config::Knots>,
    /// Which methods, which results, how many threads.
    pub settings: cosco_hsom::offline::LooSettings,
    /// Where to write every fold's scores as JSON.
    pub json: Option<PathBuf>,
    /// Where to draw one fold per gesture.
    pub png: Option<PathBuf>,
}

/// `cosco heldout`: leave-one-out on the demonstrations with a progress bar; the Markdown
/// tables, after writing the JSON and the figure when asked.
pub fn heldout(job: &HeldoutJob) -> Result<String> {
    use cosco_hsom::offline;
    for p in job.json.iter().chain(&job.png) {
        steps::check_output(p)?;
    }
    let mut cfg = hsom_config(job.config.as_deref())?;
    if let Some(p) = job.plan {
        cfg = cfg.with_plan(p)?;
    }
    if let Some(c) = job.consensus {
        cfg = cfg.with_consensus(c)?;
    }
    if let Some(a) = job.alignment {
        cfg = cfg.with_alignment(a)?;
    }
    if let Some(k) = job.knots {
        cfg = cfg.with_knots(k)?;
    }
    let (cfg, gestures) =
        offline::read_gestures_at(&job.demos, &cfg, job.state_length_from_data, job.resample)?;
    let folds: usize = gestures.iter().map(|(_, d)| d.len()).sum();
    let per = if job.settings.in_sample { 2 } else { 1 };
    let pb = progress((folds * per) as u64, "folds");
    let study = offline::leave_one_out(
        &cfg,
        gestures,
        &job.settings,
        Some(&|done, _| pb.set_position(done as u64)),
    )?;
    pb.finish_and_clear();
    // nothing to compare when the hierarchy itself never ran: the reason, as an error
    let ran = |m| {
        study
            .iter()
            .flat_map(|g| &g.held_out)
            .flat_map(|f| &f.runs)
            .any(|r| r.method == m && r.score.is_some())
    };
    if !ran(offline::Method::Hierarchy) {
        let why = offline::failures(&study)
            .into_iter()
            .find(|(m, _, _)| *m == offline::Method::Hierarchy)
            .map_or_else(|| "no fold ran".to_string(), |(_, why, _)| why);
        bail!("the hierarchy produced no reproduction on any fold: {why}");
    }
    if let Some(p) = &job.json {
        cosco_hsom::fsutil::write_atomic(p, offline::json(&cfg, &study).as_bytes())
            .with_context(|| format!("writing {}", p.display()))?;
    }
    #[cfg(feature = "plot")]
    if let Some(p) = &job.png {
        offline::png(p, &study, 0)?;
    }
    Ok(offline::markdown(&study))
}
