//! The steps of several gestures, shared by `cosco` and the Python package:
//! labelled demonstration directories (`demos/<label>/*.csv`), training one hierarchy on
//! them, reproduction on cue, continuation of a prefix, and recognition of files.
//!
//! ```
//! use cosco_hsom::config::{AlgorithmParams, EventsParams, HsomParams};
//! use cosco_hsom::labelled::train_gestures;
//! use cosco_hsom::steps::demonstrations_from_rows;
//! let mut p = HsomParams::table1();
//! p.algorithm = AlgorithmParams::Events(EventsParams { change_ratio: 1.0, action_horizon: 1 });
//! p.state_length = 2;
//! p.action_length = 2;
//! p.training_steps = 300;
//! let cfg = p.check("example").unwrap();
//! let up: Vec<Vec<f64>> = (0..40).map(|i| vec![i as f64 / 40.0, 0.0]).collect();
//! let side: Vec<Vec<f64>> = (0..40).map(|i| vec![0.0, i as f64 / 40.0]).collect();
//! let sets = vec![
//!     ("up".to_string(), demonstrations_from_rows(vec![up.clone(), up.clone()], None).unwrap()),
//!     ("side".to_string(), demonstrations_from_rows(vec![side.clone(), side.clone()], None).unwrap()),
//! ];
//! let model = train_gestures(&cfg, &sets, None).unwrap();
//! assert_eq!(model.labels(), ["up", "side"]);
//! assert_eq!(model.recognize(&side).unwrap().best, "side");
//! ```

use std::path::{Path, PathBuf};

use crate::config::HsomConfig;
use crate::demos::{self, DemoError, Demonstration};
use crate::hsom::{is_plain_label, GestureError, GestureModel, Recognition, Reproduction};
use crate::steps::{self, StepError};

/// Why a multi-gesture step was refused.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LabelledError {
    /// A step shared with single gestures was refused.
    #[error(transparent)]
    Step(#[from] StepError),
    /// A multi-gesture step was refused.
    #[error(transparent)]
    Gesture(#[from] GestureError),
    /// A demonstration file was refused.
    #[error(transparent)]
    Demo(#[from] DemoError),
    /// A directory that holds both CSV files and gesture subdirectories, or labelled and
    /// plain demonstrations given together.
    #[error("{path}: {reason}")]
    Layout {
        /// The directory or file.
        path: String,
        /// What is wrong and what to do.
        reason: String,
    },
    /// A gesture label that is not a plain word.
    #[error("{dir}: the gesture label {label:?} is not a plain word: name the directory with letters, digits, '_' and '-' only")]
    BadLabel {
        /// The label's directory.
        dir: String,
        /// The label.
        label: String,
    },
}

/// Demonstrations as read from `--demos`: one unlabelled gesture (a directory of CSV files or
/// files, as before), or labelled sets (directories whose subdirectories are the labels).
#[derive(Debug, Clone)]
pub enum DemoSets {
    /// One gesture, no label.
    Plain(Vec<Demonstration>),
    /// `(label, demonstrations)` in the order of the paths, labels sorted within a directory.
    Labelled(Vec<(String, Vec<Demonstration>)>),
}

/// Subdirectories of a directory, sorted (empty for a file).
fn subdirectories(path: &Path) -> Result<Vec<PathBuf>, LabelledError> {
    if !path.is_dir() {
        return Ok(Vec::new());
    }
    let io = |source| DemoError::Io {
        path: path.display().to_string(),
        source,
    };
    let mut dirs = Vec::new();
    for e in std::fs::read_dir(path).map_err(io)? {
        let p = e.map_err(io)?.path();
        if p.is_dir() {
            dirs.push(p);
        }
    }
    dirs.sort();
    Ok(dirs)
}

/// True when the directory holds a `*.csv` file.
fn has_csv(path: &Path) -> bool {
    std::fs::read_dir(path).is_ok_and(|rd| {
        rd.flatten().any(|e| {
            let p = e.path();
            p.is_file()
                && p.extension()
                    .and_then(|x| x.to_str())
                    .is_some_and(|x| x.eq_ignore_ascii_case("csv"))
        })
    })
}

/// Read `--demos`: a directory whose subdirectories hold CSV files is labelled (each
/// subdirectory's name a label, a plain word, with at least one CSV); otherwise the paths are
/// read as today ([`steps::read_demos`]). Every label's set is checked on its own and
/// against `state_length` when given; labels must record the same columns.
pub fn read_demo_sets(
    paths: &[PathBuf],
    state_length: Option<usize>,
) -> Result<DemoSets, LabelledError> {
    read_demo_sets_at(paths, state_length, None)
}

/// [`read_demo_sets`], each demonstration first resampled to `resample_hz` when given
/// ([`crate::resample::resample_all`]).
pub fn read_demo_sets_at(
    paths: &[PathBuf],
    state_length: Option<usize>,
    resample_hz: Option<f64>,
) -> Result<DemoSets, LabelledError> {
    let subs: Vec<Vec<PathBuf>> = paths
        .iter()
        .map(|p| subdirectories(p))
        .collect::<Result<_, _>>()?;
    let labelled: Vec<bool> = paths
        .iter()
        .zip(&subs)
        .map(|(p, s)| !s.is_empty() && !has_csv(p))
        .collect();
    if !labelled.iter().any(|&l| l) {
        return Ok(DemoSets::Plain(steps::read_demos_at(
            paths,
            state_length,
            resample_hz,
        )?));
    }
    if let Some(i) = labelled.iter().position(|&l| !l) {
        return Err(LabelledError::Layout {
            path: paths[i].display().to_string(),
            reason: "plain demonstrations given together with labelled directories: give only directories of gesture subdirectories (demos/<label>/*.csv)".into(),
        });
    }
    let mut sets: Vec<(String, Vec<Demonstration>)> = Vec::new();
    for dir in subs.iter().flatten() {
        let label = dir
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_default();
        if !is_plain_label(&label) {
            return Err(LabelledError::BadLabel {
                dir: dir.display().to_string(),
                label,
            });
        }
        let demos = demos::read_dir_or_files(std::slice::from_ref(dir))?;
        let demos = crate::resample::resample_all(demos, resample_hz)?;
        demos::validate_set(&demos, state_length)?;
        match sets.iter_mut().find(|(l, _)| *l == label) {
            Some((_, d)) => d.extend(demos),
            None => sets.push((label, demos)),
        }
    }
    let (first_label, first) = (&sets[0].0, &sets[0].1[0].columns);
    for (label, demos) in &sets {
        if let Some(d) = demos.iter().find(|d| &d.columns != first) {
            return Err(GestureError::ColumnsDiffer {
                label: label.clone(),
                found: d.columns.clone(),
                first_label: first_label.clone(),
                expected: first.clone(),
            }
            .into());
        }
    }
    Ok(DemoSets::Labelled(sets))
}

/// Check every label's set against the configuration, then train one hierarchy on them,
/// calling `progress(done, total)` now and then (the shared bottom level's training).
pub fn train_gestures(
    cfg: &HsomConfig,
    sets: &[(String, Vec<Demonstration>)],
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<GestureModel, LabelledError> {
    for (label, demos) in sets {
        // a label without demonstrations is named (validate_set would only say "none")
        if demos.is_empty() {
            return Err(GestureError::EmptyLabel {
                label: label.clone(),
            }
            .into());
        }
        demos::validate_set(demos, Some(cfg.params().state_length))?;
    }
    Ok(cfg.fit_gestures(sets, progress)?)
}

/// Train on what `--demos` holds: a single-gesture model for plain demonstrations (exactly
/// as [`steps::train`]), a multi-gesture one for labelled sets.
pub fn train_sets(
    cfg: &HsomConfig,
    sets: &DemoSets,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<GestureModel, LabelledError> {
    Ok(match sets {
        DemoSets::Plain(d) => steps::train(cfg, d, progress)?.into(),
        DemoSets::Labelled(s) => train_gestures(cfg, s, progress)?,
    })
}

/// Save a model (`.bin` or `.txt`, atomically): one gesture without labels, several with.
pub fn save_gesture_model(model: &GestureModel, path: &Path) -> Result<(), LabelledError> {
    steps::check_model_extension(path)?;
    model
        .save(path)
        .map_err(|e| LabelledError::Step(StepError::Persist(e)))
}

/// Load a model of one or several gestures (`.bin` or `.txt`).
pub fn load_gesture_model(path: &Path) -> Result<GestureModel, LabelledError> {
    steps::check_model_extension(path)?;
    GestureModel::load(path).map_err(|e| LabelledError::Step(StepError::Persist(e)))
}

/// Reproduce gesture `label` (required for a multi-gesture model) from `initial`, with the
/// checks of [`steps::reproduce`].
pub fn reproduce_gesture(
    model: &GestureModel,
    model_name: &str,
    label: Option<&str>,
    initial: &[f64],
) -> Result<Reproduction, LabelledError> {
    let branch = model.branch(label)?;
    Ok(steps::reproduce(branch, model_name, initial)?)
}

/// A demonstration file whose columns are the model's.
fn read_for_model(model: &GestureModel, path: &Path) -> Result<Demonstration, LabelledError> {
    Ok(steps::read_for_columns(path, model.columns())?)
}

/// The first `prefix` samples of a demonstration file, continued by the gesture the
/// hierarchy recognises in them; the label and the postures (the prefix first).
pub fn continue_file(
    model: &GestureModel,
    path: &Path,
    prefix: usize,
) -> Result<(String, Reproduction), LabelledError> {
    let d = read_for_model(model, path)?;
    if prefix < 2 || prefix > d.rows.len() {
        return Err(LabelledError::Layout {
            path: path.display().to_string(),
            reason: format!(
                "--prefix {prefix}: the file has {} samples; give 2 to {}",
                d.rows.len(),
                d.rows.len()
            ),
        });
    }
    Ok(model.continue_prefix(&d.rows[..prefix])?)
}

/// One recognised file.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RecognisedFile {
    /// The file.
    pub file: String,
    /// The label of the subdirectory it was read from, when the input was labelled.
    pub expected: Option<String>,
    /// The answer.
    pub recognition: Recognition,
}

/// Recognise demonstration files: a file, a directory of CSV files, or a directory of label
/// subdirectories (then each file's expected label is its subdirectory's name).
pub fn recognize_paths(
    model: &GestureModel,
    path: &Path,
) -> Result<Vec<RecognisedFile>, LabelledError> {
    let mut files: Vec<(PathBuf, Option<String>)> = Vec::new();
    let subs = subdirectories(path)?;
    if path.is_dir() && !subs.is_empty() && !has_csv(path) {
        for dir in subs {
            let label = dir
                .file_name()
                .map(|n| n.to_string_lossy().to_string())
                .unwrap_or_default();
            for f in csv_files(&dir)? {
                files.push((f, Some(label.clone())));
            }
        }
    } else if path.is_dir() {
        files.extend(csv_files(path)?.into_iter().map(|f| (f, None)));
    } else {
        files.push((path.to_path_buf(), None));
    }
    files
        .into_iter()
        .map(|(f, expected)| {
            let d = read_for_model(model, &f)?;
            let recognition = model
                .recognize(&d.rows)
                .map_err(|e| LabelledError::Layout {
                    path: f.display().to_string(),
                    reason: steps::error_line(&e),
                })?;
            Ok(RecognisedFile {
                file: f.display().to_string(),
                expected,
                recognition,
            })
        })
        .collect()
}

/// The `*.csv` files of a directory, sorted; an error naming it when there is none.
fn csv_files(dir: &Path) -> Result<Vec<PathBuf>, LabelledError> {
    let io = |source| DemoError::Io {
        path: dir.display().to_string(),
        source,
    };
    let mut files = Vec::new();
    for e in std::fs::read_dir(dir).map_err(io)? {
        let p = e.map_err(io)?.path();
        let csv = p
            .extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| x.eq_ignore_ascii_case("csv"));
        if csv && p.is_file() {
            files.push(p);
        }
    }
    if files.is_empty() {
        return Err(DemoError::EmptyDirectory {
            path: dir.display().to_string(),
        }
        .into());
    }
    files.sort();
    Ok(files)
}
