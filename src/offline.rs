//! Leave-one-out on recorded demonstrations, without the simulator (`cosco heldout`): the
//! held-out test of `experiment::heldout` for any data, such as human demonstrations
//! recorded elsewhere. For each demonstration of a gesture in turn: learn from the others,
//! reproduce from its first sample, and score the reproduction against it alone. Side by side
//! on the same folds:
//!
//! - **hierarchy**: the configuration as given ([`Hsom::reproduce`]);
//! - **nearest sequence**: the same trained model's bottom code following the bottom events
//!   of the training demonstration whose first sample is nearest, no level above
//!   ([`Hsom::follow_nearest`]), the simpler thing the hierarchy has to beat;
//! - **height 1**: the same configuration with its bottom level alone
//!   ([`HsomConfig::at_height`]);
//! - **GMM/GMR**: the paper's baseline with the experiment's settings (components by BIC
//!   over 1..=16), a minimum-jerk lead-in from the first sample to GMR's first point at the
//!   training demonstrations' own peak speed ([`peak_speed`]), then GMR's mean every sample
//!   period;
//! - **replay**: the training demonstration whose first sample is nearest, as recorded (no
//!   model at all).
//!
//! Postures are scored as produced (nothing is executed): joint DTW in the data's own units
//! per step and relative to the diagonal of the gesture's bounding box (comparable across
//! gestures and units), final-sample error, duration ratio and normalised jerk over the
//! held-out demonstration's, all after the idle trimming of `docs/METRICS.md`. The in-sample
//! result (learn from all, reproduce from each demonstration's first sample, score against
//! that demonstration) is given beside the held-out one.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use serde::Serialize;

use crate::config::HsomConfig;
use crate::demos::Demonstration;
use crate::gmr::{plan_at, ComponentChoice, GmrParams};
use crate::hsom::Hsom;
use crate::metrics::{median, MetricsParams};
use crate::steps::{evaluate_rows, sample_period};

/// The components the GMM/GMR baseline chooses among (lowest BIC), as in the experiment.
pub const GMR_COMPONENTS: ComponentChoice = ComponentChoice::Bic { min: 1, max: 16 };

/// Gestures by name, each with its demonstrations.
pub type Gestures = Vec<(String, Vec<Demonstration>)>;

/// A method of the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// The configuration as given.
    Hierarchy,
    /// The same model's bottom code following the nearest training demonstration's events.
    NearestSequence,
    /// The configuration with its bottom level alone.
    Height1,
    /// The paper's GMM/GMR baseline.
    GmmGmr,
    /// The nearest training demonstration as recorded.
    Replay,
}

impl Method {
    /// Every method, in the order of the tables.
    pub const ALL: [Method; 5] = [
        Method::Hierarchy,
        Method::NearestSequence,
        Method::Height1,
        Method::GmmGmr,
        Method::Replay,
    ];

    /// The name in tables.
    pub fn name(self) -> &'static str {
        match self {
            Method::Hierarchy => "hierarchy",
            Method::NearestSequence => "nearest sequence",
            Method::Height1 => "height 1",
            Method::GmmGmr => "GMM/GMR",
            Method::Replay => "replay (no model)",
        }
    }
}

/// Which methods run besides the hierarchy and the nearest sequence, and whether the
/// in-sample result is computed too.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LooSettings {
    /// The configuration at height 1.
    pub height_1: bool,
    /// GMM/GMR.
    pub gmr: bool,
    /// The replay of the nearest training demonstration.
    pub replay: bool,
    /// Learn from all and score against each too.
    pub in_sample: bool,
    /// Worker threads (at least 1).
    pub threads: usize,
}

impl Default for LooSettings {
    fn default() -> Self {
        LooSettings {
            height_1: true,
            gmr: true,
            replay: true,
            in_sample: true,
            threads: 1,
        }
    }
}

/// One reproduction scored against one demonstration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Score {
    /// Per-step DTW distance in the data's units (rad for joints).
    pub dtw: f64,
    /// `dtw` over the diagonal of the gesture's bounding box.
    pub relative_dtw: f64,
    /// Trimmed duration of the reproduction over the demonstration's.
    pub duration_ratio: f64,
    /// Distance between the last samples, data units.
    pub final_error: f64,
    /// Normalised jerk of the reproduction over the demonstration's (`None` when either has
    /// none, or the demonstration's is below [`MIN_DEMO_JERK`]).
    pub jerk_ratio: Option<f64>,
}

/// A method's result on one fold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Run {
    /// Which method.
    pub method: Method,
    /// The score, when the method produced a reproduction.
    pub score: Option<Score>,
    /// Why it produced none.
    pub error: Option<String>,
    /// The reproduction (not serialised).
    #[serde(skip)]
    pub postures: Vec<Vec<f64>>,
}

/// The methods on one demonstration: held out (learned from the others) or in-sample
/// (learned from all).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fold {
    /// The demonstration scored against (its file).
    pub demonstration: String,
    /// One run per method, in [`Method::ALL`]'s order.
    pub runs: Vec<Run>,
}

impl Fold {
    /// The score of `method`, when it ran and succeeded.
    pub fn score(&self, method: Method) -> Option<&Score> {
        self.runs
            .iter()
            .find(|r| r.method == method)
            .and_then(|r| r.score.as_ref())
    }
}

/// Leave-one-out on one gesture's demonstrations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GestureLoo {
    /// The gesture's name (its directory, or `gesture` for plain files).
    pub gesture: String,
    /// Its demonstrations, in order (not serialised: the folds name their files).
    #[serde(skip)]
    pub demonstrations: Vec<Demonstration>,
    /// The diagonal of their bounding box, data units.
    pub diagonal: f64,
    /// One fold per demonstration, held out.
    pub held_out: Vec<Fold>,
    /// One per demonstration, in-sample (empty unless asked for).
    pub in_sample: Vec<Fold>,
}

impl GestureLoo {
    /// The mean of `f` over the folds where `method` succeeded (`None` when it never did).
    pub fn mean(&self, folds: &[Fold], method: Method, f: fn(&Score) -> f64) -> Option<f64> {
        let v: Vec<f64> = folds
            .iter()
            .filter_map(|fold| fold.score(method).map(f))
            .collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    }
}

/// Errors of the study.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LooError {
    /// Too few demonstrations to leave one out.
    #[error("gesture '{gesture}': leave-one-out needs at least 3 demonstrations (2 to learn from, 1 to score against), got {found}")]
    TooFew {
        /// The gesture.
        gesture: String,
        /// Demonstrations given.
        found: usize,
    },
    /// No gesture given.
    #[error("no gesture to evaluate")]
    Empty,
    /// A bad setting.
    #[error("threads = {0}: needs at least 1")]
    Threads(usize),
    /// The configuration (at height 1, or for the data's width) is not valid.
    #[error(transparent)]
    Config(#[from] crate::config::ConfigError),
    /// The demonstrations could not be read, or do not fit the configuration.
    #[error(transparent)]
    Read(#[from] crate::labelled::LabelledError),
    /// The demonstrations' width is not the configuration's state length.
    #[error("{path}: {found} columns but the configuration's stateLength is {expected}; give a configuration for {found} variables, or take stateLength from the data")]
    Width {
        /// The first file of another width.
        path: String,
        /// The configuration's state length.
        expected: usize,
        /// The file's columns.
        found: usize,
    },
    /// A demonstration is not valid (non-finite values, columns that differ within a
    /// gesture, ...).
    #[error(transparent)]
    Demo(#[from] crate::demos::DemoError),
    /// The figure could not be drawn or written.
    #[cfg(feature = "plot")]
    #[error(transparent)]
    Plot(#[from] crate::plot::PlotError),
}

/// The peak speed of demonstrations sampled every `period` seconds, units per second: the
/// median over the demonstrations of their largest speed on any variable, each speed a
/// difference over 4 samples (so a single noisy sample does not make it; over all of a
/// demonstration shorter than 5 samples; 0 for one sample). The lead-in of
/// GMM/GMR moves at most this fast.
pub fn peak_speed(demos: &[Demonstration], period: f64) -> f64 {
    let per_demo = demos.iter().map(|d| {
        // over 4 samples, or all of a shorter demonstration
        let span = d.rows.len().saturating_sub(1).min(4);
        if span == 0 {
            return 0.0;
        }
        d.rows
            .windows(span + 1)
            .flat_map(|w| w[span].iter().zip(&w[0]).map(|(b, a)| (b - a).abs()))
            .fold(0.0, f64::max)
            / (span as f64 * period)
    });
    median(per_demo).unwrap_or(0.0)
}

/// The diagonal of the bounding box of every sample of `demos`.
pub fn diagonal(demos: &[Demonstration]) -> f64 {
    let width = demos.first().map_or(0, |d| d.width());
    let mut lo = vec![f64::INFINITY; width];
    let mut hi = vec![f64::NEG_INFINITY; width];
    for row in demos.iter().flat_map(|d| &d.rows) {
        for (k, &v) in row.iter().enumerate() {
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
        }
    }
    lo.iter()
        .zip(&hi)
        .map(|(a, b)| (b - a).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// The smallest normalised jerk of a held-out demonstration for which the jerk ratio is
/// given. Every motion that starts and ends at rest has at least √360 ≈ 19 (minimum jerk);
/// below 1 the demonstration is a nearly uniform motion (a straight line at constant speed
/// has 0) and a ratio to it means nothing.
pub const MIN_DEMO_JERK: f64 = 1.0;

/// Score `postures` against `demo` alone.
fn score(demo: &Demonstration, postures: &[Vec<f64>], diag: f64) -> Result<Score, String> {
    let params = MetricsParams {
        sample_period: sample_period(demo),
        ..MetricsParams::default()
    };
    let f = evaluate_rows(std::slice::from_ref(demo), postures, &params)
        .map_err(|e| crate::steps::error_line(&e))?;
    let jerk = match (
        f.reproduction_smoothness.normalized_jerk,
        f.demo_smoothness[0].normalized_jerk,
    ) {
        (Some(r), Some(d)) if d >= MIN_DEMO_JERK => Some(r / d),
        _ => None,
    };
    Ok(Score {
        dtw: f.joint_dtw_rad_per_step.mean,
        relative_dtw: if diag > 0.0 {
            f.joint_dtw_rad_per_step.mean / diag
        } else {
            f64::NAN
        },
        duration_ratio: f.duration_ratio.mean,
        final_error: f.final_error_rad.mean,
        jerk_ratio: jerk,
    })
}

/// A run from a method's result.
fn run(
    method: Method,
    produced: Result<Vec<Vec<f64>>, String>,
    demo: &Demonstration,
    diag: f64,
) -> Run {
    match produced.and_then(|p| score(demo, &p, diag).map(|s| (p, s))) {
        Ok((postures, s)) => Run {
            method,
            score: Some(s),
            error: None,
            postures,
        },
        Err(e) => Run {
            method,
            score: None,
            error: Some(e),
            postures: Vec::new(),
        },
    }
}

fn msg(e: impl std::error::Error + 'static) -> String {
    crate::steps::error_line(&e)
}

/// The methods learned from `train`, reproducing from `target`'s first sample, scored
/// against `target`. `replay` is skipped in-sample (it would replay the target itself).
fn fold(
    config: &HsomConfig,
    height_1: Option<&HsomConfig>,
    train: &[Demonstration],
    target: &Demonstration,
    diag: f64,
    settings: &LooSettings,
    held_out: bool,
) -> Fold {
    let initial = &target.rows[0];
    let mut runs = Vec::new();
    match config.fit(train) {
        Ok(model) => {
            let rep = model.reproduce(initial).map(|r| r.postures).map_err(msg);
            runs.push(run(Method::Hierarchy, rep, target, diag));
            let near = model
                .follow_nearest(train, initial)
                .map(|r| r.postures)
                .map_err(msg);
            runs.push(run(Method::NearestSequence, near, target, diag));
        }
        Err(e) => {
            let e = msg(e);
            runs.push(run(Method::Hierarchy, Err(e.clone()), target, diag));
            runs.push(run(Method::NearestSequence, Err(e), target, diag));
        }
    }
    if let Some(h1) = height_1 {
        let rep = h1
            .fit(train)
            .map_err(msg)
            .and_then(|m: Hsom| m.reproduce(initial).map(|r| r.postures).map_err(msg));
        runs.push(run(Method::Height1, rep, target, diag));
    }
    if settings.gmr {
        let period = sample_period(target);
        let rep = GmrParams::new()
            .components(GMR_COMPONENTS)
            .sample_period(period)
            .check()
            .and_then(|p| p.fit(train))
            .and_then(|m| plan_at(&m, initial, 1.0 / period, peak_speed(train, period)))
            .map(|p| p.postures)
            .map_err(msg);
        runs.push(run(Method::GmmGmr, rep, target, diag));
    }
    if settings.replay && held_out {
        let start = |d: &Demonstration| crate::dtw::euclidean(&d.rows[0], initial);
        let rep = train
            .iter()
            .min_by(|a, b| start(a).total_cmp(&start(b)))
            .map(|d| d.rows.clone())
            .ok_or_else(|| "no training demonstration".to_string());
        runs.push(run(Method::Replay, rep, target, diag));
    }
    Fold {
        demonstration: target.source.clone(),
        runs,
    }
}

/// The gestures of `paths` as `cosco train` reads them: a directory of CSV files or files
/// (one gesture, named after its directory, else `gesture`), or directories of gesture
/// subdirectories (`DIR/<gesture>/*.csv`, each gesture on its own). With `from_data` the configuration is
/// adapted to the data's width ([`HsomConfig::for_width`]); otherwise [`leave_one_out`]
/// refuses files without the configuration's `stateLength` columns.
pub fn read_gestures(
    paths: &[std::path::PathBuf],
    config: &HsomConfig,
    from_data: bool,
) -> Result<(HsomConfig, Gestures), LooError> {
    read_gestures_at(paths, config, from_data, None)
}

/// [`read_gestures`], each demonstration first resampled to `resample_hz` when given
/// ([`crate::resample::resample_all`]).
pub fn read_gestures_at(
    paths: &[std::path::PathBuf],
    config: &HsomConfig,
    from_data: bool,
    resample_hz: Option<f64>,
) -> Result<(HsomConfig, Gestures), LooError> {
    let sets = match crate::labelled::read_demo_sets_at(paths, None, resample_hz)? {
        crate::labelled::DemoSets::Plain(d) => {
            let name = match paths {
                [one] if one.is_dir() => one.file_name().map(|n| n.to_string_lossy().to_string()),
                _ => None,
            };
            vec![(name.unwrap_or_else(|| "gesture".into()), d)]
        }
        crate::labelled::DemoSets::Labelled(sets) => sets,
    };
    let width = sets[0].1[0].width();
    let config = if from_data {
        config.for_width(width)?
    } else {
        config.clone()
    };
    Ok((config, sets))
}

/// Leave-one-out on each gesture's demonstrations (`(name, demonstrations)`; each set is
/// checked first: at least 3, of the configuration's `stateLength`, valid), with the
/// settings' methods; `progress(done, total)` after each fold when given. Folds run on `settings.threads` threads; the result does not
/// depend on their number.
pub fn leave_one_out(
    config: &HsomConfig,
    gestures: Gestures,
    settings: &LooSettings,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<Vec<GestureLoo>, LooError> {
    if gestures.is_empty() {
        return Err(LooError::Empty);
    }
    if settings.threads == 0 {
        return Err(LooError::Threads(0));
    }
    if let Some((g, d)) = gestures.iter().find(|(_, d)| d.len() < 3) {
        return Err(LooError::TooFew {
            gesture: g.clone(),
            found: d.len(),
        });
    }
    let expected = config.params().state_length;
    if let Some(d) = gestures
        .iter()
        .flat_map(|(_, d)| d)
        .find(|d| d.width() != expected)
    {
        return Err(LooError::Width {
            path: d.source.clone(),
            expected,
            found: d.width(),
        });
    }
    for (_, demos) in &gestures {
        crate::demos::validate_set(demos, None)?;
    }
    let height_1 = match settings.height_1 {
        true => Some(config.at_height(1)?),
        false => None,
    };
    // jobs: (gesture, demonstration, held out?)
    let mut jobs = Vec::new();
    for (g, (_, demos)) in gestures.iter().enumerate() {
        for i in 0..demos.len() {
            jobs.push((g, i, true));
            if settings.in_sample {
                jobs.push((g, i, false));
            }
        }
    }
    let diagonals: Vec<f64> = gestures.iter().map(|(_, d)| diagonal(d)).collect();
    let results: Mutex<Vec<Option<Fold>>> = Mutex::new(vec![None; jobs.len()]);
    let (next, done) = (AtomicUsize::new(0), AtomicUsize::new(0));
    std::thread::scope(|s| {
        for _ in 0..settings.threads.min(jobs.len()) {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&(g, i, held)) = jobs.get(k) else {
                    break;
                };
                let demos = &gestures[g].1;
                let train: Vec<Demonstration> = if held {
                    demos
                        .iter()
                        .enumerate()
                        .filter(|&(j, _)| j != i)
                        .map(|(_, d)| d.clone())
                        .collect()
                } else {
                    demos.clone()
                };
                let f = fold(
                    config,
                    height_1.as_ref(),
                    &train,
                    &demos[i],
                    diagonals[g],
                    settings,
                    held,
                );
                results.lock().unwrap_or_else(|p| p.into_inner())[k] = Some(f);
                let d = done.fetch_add(1, Ordering::Relaxed) + 1;
                if let Some(p) = progress {
                    p(d, jobs.len());
                }
            });
        }
    });
    let mut folds = results
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
        .into_iter();
    let mut out = Vec::new();
    for (g, (name, demos)) in gestures.into_iter().enumerate() {
        let (mut held_out, mut in_sample) = (Vec::new(), Vec::new());
        for _ in 0..demos.len() {
            held_out.push(folds.next().flatten().expect("every job ran"));
            if settings.in_sample {
                in_sample.push(folds.next().flatten().expect("every job ran"));
            }
        }
        out.push(GestureLoo {
            gesture: name,
            demonstrations: demos,
            diagonal: diagonals[g],
            held_out,
            in_sample,
        });
    }
    Ok(out)
}

/// One method over every gesture: medians over the gestures of the per-gesture means over
/// the folds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MethodSummary {
    /// Which method.
    pub method: Method,
    /// Folds it ran on (held out).
    pub folds: usize,
    /// Folds where it produced nothing.
    pub failed: usize,
    /// Median relative DTW, held out.
    pub relative_dtw: Option<f64>,
    /// Median relative DTW, in-sample (learned from all).
    pub relative_dtw_in_sample: Option<f64>,
    /// Median duration ratio, held out.
    pub duration_ratio: Option<f64>,
    /// Median final error over the diagonal, held out.
    pub relative_final_error: Option<f64>,
    /// Median jerk ratio, held out.
    pub jerk_ratio: Option<f64>,
    /// Median over gestures of the hierarchy's DTW over this method's (held out).
    pub hierarchy_ratio: Option<f64>,
    /// Gestures where the hierarchy's mean DTW is below this method's, of those both ran on.
    pub hierarchy_closer: (usize, usize),
}

fn held(g: &GestureLoo) -> &[Fold] {
    &g.held_out
}

fn ins(g: &GestureLoo) -> &[Fold] {
    &g.in_sample
}

/// The summary of every method that ran.
pub fn summary(study: &[GestureLoo]) -> Vec<MethodSummary> {
    let ran = |m: Method| {
        study.iter().any(|g| {
            g.held_out
                .iter()
                .any(|f| f.runs.iter().any(|r| r.method == m))
        })
    };
    Method::ALL
        .into_iter()
        .filter(|&m| ran(m))
        .map(|m| {
            let runs = || {
                study
                    .iter()
                    .flat_map(|g| &g.held_out)
                    .flat_map(|f| &f.runs)
                    .filter(move |r| r.method == m)
            };
            let med = |folds: fn(&GestureLoo) -> &[Fold], f: fn(&Score) -> f64| {
                median(study.iter().filter_map(|g| g.mean(folds(g), m, f)))
            };
            let pairs: Vec<(f64, f64)> = study
                .iter()
                .filter_map(|g| {
                    Some((
                        g.mean(&g.held_out, Method::Hierarchy, |s| s.dtw)?,
                        g.mean(&g.held_out, m, |s| s.dtw)?,
                    ))
                })
                .collect();
            MethodSummary {
                method: m,
                folds: runs().count(),
                failed: runs().filter(|r| r.score.is_none()).count(),
                relative_dtw: med(held, |s| s.relative_dtw),
                relative_dtw_in_sample: med(ins, |s| s.relative_dtw),
                duration_ratio: med(held, |s| s.duration_ratio),
                relative_final_error: median(study.iter().filter_map(|g| {
                    g.mean(&g.held_out, m, |s| s.final_error)
                        .map(|e| e / g.diagonal)
                })),
                jerk_ratio: median(
                    study.iter().filter_map(|g| {
                        g.mean(&g.held_out, m, |s| s.jerk_ratio.unwrap_or(f64::NAN))
                    }),
                ),
                hierarchy_ratio: median(pairs.iter().map(|(h, x)| h / x)),
                hierarchy_closer: (pairs.iter().filter(|(h, x)| h < x).count(), pairs.len()),
            }
        })
        .collect()
}

/// The study as a JSON document (what `cosco heldout --json` writes): the configuration's
/// name, the [`summary`] and every gesture's folds with every method's score.
pub fn json(config: &HsomConfig, study: &[GestureLoo]) -> String {
    let doc = serde_json::json!({
        "config": config.source(),
        "summary": summary(study),
        "gestures": study,
    });
    // cannot fail: plain numbers (non-finite ones become null), strings and enums
    serde_json::to_string_pretty(&doc).unwrap_or_default()
}

/// Every distinct reason a method produced nothing, with the folds it happened on
/// (`gesture`, held out or in-sample, the demonstration's file), in the order met.
pub fn failures(study: &[GestureLoo]) -> Vec<(Method, String, Vec<String>)> {
    let mut out: Vec<(Method, String, Vec<String>)> = Vec::new();
    for g in study {
        for (kind, folds) in [("held out", &g.held_out), ("in-sample", &g.in_sample)] {
            for f in folds {
                for r in &f.runs {
                    let Some(e) = &r.error else { continue };
                    let at = format!("{} ({kind}, {})", g.gesture, f.demonstration);
                    match out.iter_mut().find(|(m, w, _)| *m == r.method && w == e) {
                        Some((_, _, at_list)) => at_list.push(at),
                        None => out.push((r.method, e.clone(), vec![at])),
                    }
                }
            }
        }
    }
    out
}

/// The study as Markdown: per gesture, each method's mean relative DTW over the folds held
/// out (and in-sample), then the summary over the gestures.
pub fn markdown(study: &[GestureLoo]) -> String {
    use std::fmt::Write as _;
    let summaries = summary(study);
    let methods: Vec<Method> = summaries.iter().map(|s| s.method).collect();
    let cell = |v: Option<f64>| v.map_or("failed".to_string(), |v| format!("{v:.4}"));
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Relative DTW (per-step DTW / the gesture's bounding-box diagonal), mean over the \
         leave-one-out folds, held out (in-sample in brackets where learned from all):\n"
    );
    let _ = writeln!(
        out,
        "| gesture | demos | {} |",
        methods
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
            .join(" | ")
    );
    let _ = writeln!(out, "|---|---|{}", "---|".repeat(methods.len()));
    for g in study {
        let cells: Vec<String> = methods
            .iter()
            .map(|&m| {
                let h = cell(g.mean(&g.held_out, m, |s| s.relative_dtw));
                match g.mean(&g.in_sample, m, |s| s.relative_dtw) {
                    Some(i) => format!("{h} ({i:.4})"),
                    None => h,
                }
            })
            .collect();
        let _ = writeln!(
            out,
            "| {} | {} | {} |",
            g.gesture,
            g.demonstrations.len(),
            cells.join(" | ")
        );
    }
    let _ = writeln!(
        out,
        "\nMedians over the {} gestures (held out; per-gesture means over the folds):\n",
        study.len()
    );
    let _ = writeln!(
        out,
        "| method | relative DTW | in-sample | duration ratio | final error / diagonal | jerk ratio | hierarchy / method | hierarchy closer | failed folds |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|---|");
    let opt = |v: Option<f64>, d: usize| v.map_or("-".to_string(), |v| format!("{v:.d$}"));
    for s in summaries {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} of {} |",
            s.method.name(),
            opt(s.relative_dtw, 4),
            opt(s.relative_dtw_in_sample, 4),
            opt(s.duration_ratio, 2),
            opt(s.relative_final_error, 4),
            opt(s.jerk_ratio, 2),
            if s.method == Method::Hierarchy {
                "-".to_string()
            } else {
                opt(s.hierarchy_ratio, 3)
            },
            if s.method == Method::Hierarchy {
                "-".to_string()
            } else {
                format!("{} of {}", s.hierarchy_closer.0, s.hierarchy_closer.1)
            },
            s.failed,
            s.folds
        );
    }
    let failed = failures(study);
    if !failed.is_empty() {
        let _ = writeln!(out, "\nFailed runs (method: reason; where):\n");
        for (m, why, at) in failed {
            let shown = at.iter().take(3).cloned().collect::<Vec<_>>().join("; ");
            let more = match at.len() {
                n if n > 3 => format!("; and {} more", n - 3),
                _ => String::new(),
            };
            let _ = writeln!(out, "- {}: {why}; {shown}{more}", m.name());
        }
    }
    out
}

/// A figure of one fold per gesture: the gesture's demonstrations (thin, grey), the held-out
/// one (black) and the reproductions from its first sample of the hierarchy, the nearest
/// sequence and GMM/GMR (height 1 and the replay are in the tables only), in the plane of the
/// first two variables (against time for data of one variable). `fold` picks the held-out
/// demonstration (0-based; the last one where a gesture has fewer).
#[cfg(feature = "plot")]
pub fn png(path: &std::path::Path, study: &[GestureLoo], fold: usize) -> Result<(), LooError> {
    use crate::plot::{panels_png, Panel, Series, BLACK, PALETTE};
    use plotters::style::RGBColor;
    let color = |m: Method| match m {
        Method::Hierarchy => PALETTE[3],
        Method::NearestSequence => PALETTE[0],
        Method::Height1 => PALETTE[4],
        Method::GmmGmr => RGBColor(200, 0, 130),
        Method::Replay => PALETTE[2],
    };
    let points = |rows: &[Vec<f64>], period: f64| -> Vec<(f64, f64)> {
        rows.iter()
            .enumerate()
            .map(|(k, r)| match r.len() {
                1 => (k as f64 * period, r[0]),
                _ => (r[0], r[1]),
            })
            .collect()
    };
    let mut panels = Vec::new();
    for g in study {
        let k = fold.min(g.held_out.len().saturating_sub(1));
        let (Some(target), Some(f)) = (g.demonstrations.get(k), g.held_out.get(k)) else {
            continue;
        };
        let period = sample_period(target);
        let (x, y) = match target.columns.len() {
            1 => ("time (s)".to_string(), target.columns[0].clone()),
            _ => (target.columns[0].clone(), target.columns[1].clone()),
        };
        let mut panel = Panel::new(format!("{} (fold {})", g.gesture, k + 1), x, y);
        panel.equal_aspect = target.columns.len() > 1;
        for (j, d) in g.demonstrations.iter().enumerate() {
            if j != k {
                let mut s = Series::new("", RGBColor(170, 170, 170), points(&d.rows, period));
                s.label = (j == usize::from(k == 0)).then(|| "training".to_string());
                s.width = 1;
                panel.series.push(s);
            }
        }
        panel
            .series
            .push(Series::new("held out", BLACK, points(&target.rows, period)));
        // GMM/GMR first, the hierarchy last (on top)
        for r in f.runs.iter().rev().filter(|r| !r.postures.is_empty()) {
            if r.method == Method::Height1 || r.method == Method::Replay {
                continue;
            }
            panel.series.push(Series::new(
                r.method.name(),
                color(r.method),
                points(&r.postures, period),
            ));
        }
        panels.push(panel);
    }
    let cols = (panels.len() as f64).sqrt().ceil().max(1.0) as usize;
    panels_png(
        path,
        "Held out (black), reproduced from its first sample",
        &panels,
        cols,
        (420, 360),
    )?;
    Ok(())
}
