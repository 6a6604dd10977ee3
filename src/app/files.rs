//! What the operations read and write: the configuration, demonstrations (one gesture, or
//! labelled directories `DIR/<label>/*.csv`), model files, reproduction files, and the
//! output paths, each checked as it is read.

use std::path::{Path, PathBuf};

use super::{Error, Result};
use crate::config::{load_config, parse_config, HsomConfig};
use crate::demos::{self, DemoError, Demonstration};
use crate::hsom::{is_plain_label, GestureError, GestureModel, Hsom};

/// The recommended configuration for the simulated Nao (the events extension), built in so
/// that the binaries run from any directory; the default of `simulate` and `cosco`.
pub const NAO_GESTURES_XML: &str = include_str!("../../configs/nao-gestures.xml");

/// Name of the built-in default configuration in reports and messages.
pub const DEFAULT_CONFIG_NAME: &str = "configs/nao-gestures.xml (built in)";

/// Load a CoSCo-HSOM configuration file, or the built-in recommended configuration.
pub fn config(path: Option<&Path>) -> Result<HsomConfig> {
    Ok(match path {
        Some(p) => load_config(p)?,
        None => parse_config(NAO_GESTURES_XML, DEFAULT_CONFIG_NAME)?,
    })
}

/// Write `bytes` atomically to `path`, naming it on failure.
pub(super) fn write(path: &Path, bytes: &[u8]) -> Result<()> {
    crate::fsutil::write_atomic(path, bytes).map_err(|source| Error::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// The extension of a model file: `.bin` or `.txt`, else an error saying so.
fn check_model_extension(path: &Path) -> Result<()> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("bin") | Some("txt") => Ok(()),
        _ => Err(Error::file(
            path,
            "a model file must end in .bin (binary) or .txt (plain text)",
        )),
    }
}

/// Check, before any work, that a model can be written to `path`: a `.bin` or `.txt` name in
/// an existing directory where a file can be created (a temporary file is made and removed).
pub fn check_model_output(path: &Path) -> Result<()> {
    check_model_extension(path)?;
    check_output(path)
}

/// Check, before any work, that a file can be written to `path`: its directory exists and a
/// file can be created there (a temporary file is made and removed).
pub fn check_output(path: &Path) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let err = |reason: String| Error::file(path, format!("cannot write the model there: {reason}"));
    if !dir.exists() {
        return Err(err(format!(
            "the directory {} does not exist",
            dir.display()
        )));
    }
    if !dir.is_dir() {
        return Err(err(format!("{} is not a directory", dir.display())));
    }
    tempfile::NamedTempFile::new_in(dir).map(drop).map_err(|e| {
        err(format!(
            "the directory {} is not writable ({e})",
            dir.display()
        ))
    })
}

/// Save a model of one gesture (`.bin` or `.txt`, atomically).
pub fn save_model(model: &Hsom, path: &Path) -> Result<()> {
    check_model_extension(path)?;
    Ok(model.save(path)?)
}

/// Load a saved model of one gesture (`.bin` or `.txt`).
pub fn load_model(path: &Path) -> Result<Hsom> {
    check_model_extension(path)?;
    Ok(Hsom::load(path)?)
}

/// Save a model (`.bin` or `.txt`, atomically): one gesture without labels, several with.
pub fn save_gesture_model(model: &GestureModel, path: &Path) -> Result<()> {
    check_model_extension(path)?;
    Ok(model.save(path)?)
}

/// Load a model of one or several gestures (`.bin` or `.txt`).
pub fn load_gesture_model(path: &Path) -> Result<GestureModel> {
    check_model_extension(path)?;
    Ok(GestureModel::load(path)?)
}

/// In-memory demonstrations (`demos[0]`, `demos[1]`, ... in messages) from rows of samples,
/// with `columns` as their variable names (default `x0`, `x1`, ...). Only the names are
/// checked here; [`train`](super::train()) checks the set.
pub fn demonstrations_from_rows(
    series: Vec<Vec<Vec<f64>>>,
    columns: Option<Vec<String>>,
) -> Result<Vec<Demonstration>> {
    let width = series.first().and_then(|s| s.first()).map_or(0, Vec::len);
    let columns = match columns {
        Some(c) if c.len() != width && !series.is_empty() => {
            return Err(Error::value(
                "columns:",
                format!(
                    "{} names ({}) for demonstrations of {width} variables",
                    c.len(),
                    c.join(", ")
                ),
            ))
        }
        Some(c) => c,
        None => (0..width).map(|i| format!("x{i}")).collect(),
    };
    Ok(series
        .into_iter()
        .enumerate()
        .map(|(i, rows)| Demonstration {
            source: format!("demos[{i}]"),
            columns: columns.clone(),
            time: None,
            rows,
        })
        .collect())
}

/// Read demonstration files (a directory of *.csv or explicit files), each first resampled
/// to `resample_hz` when given ([`crate::resample::resample_all`]), checked as a set (against
/// `state_length` when given).
pub fn read_demos(
    paths: &[PathBuf],
    state_length: Option<usize>,
    resample_hz: Option<f64>,
) -> Result<Vec<Demonstration>> {
    let demos = crate::resample::resample_all(demos::read_dir_or_files(paths)?, resample_hz)?;
    if demos.is_empty() {
        return Err(Error::NoDemonstrations {
            paths: paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        });
    }
    demos::validate_set(&demos, state_length)?;
    Ok(demos)
}

/// Demonstrations as read from `--demos`: one unlabelled gesture (a directory of CSV files or
/// files), or labelled sets (directories whose subdirectories are the labels).
#[derive(Debug, Clone)]
pub enum DemoSets {
    /// One gesture, no label.
    Plain(Vec<Demonstration>),
    /// `(label, demonstrations)` in the order of the paths, labels sorted within a directory.
    Labelled(Vec<(String, Vec<Demonstration>)>),
}

impl DemoSets {
    /// The number of variables of the first demonstration.
    pub fn width(&self) -> usize {
        match self {
            DemoSets::Plain(d) => d[0].width(),
            DemoSets::Labelled(s) => s[0].1[0].width(),
        }
    }
}

/// Read `--demos`: a directory whose subdirectories hold CSV files is labelled (each
/// subdirectory's name a label, a plain word, with at least one CSV); otherwise the paths are
/// read as one gesture ([`read_demos`]). Each demonstration is first resampled to
/// `resample_hz` when given. Every label's set is checked on its own and against
/// `state_length` when given; labels must record the same columns.
pub fn read_demo_sets(
    paths: &[PathBuf],
    state_length: Option<usize>,
    resample_hz: Option<f64>,
) -> Result<DemoSets> {
    let subs: Vec<Vec<PathBuf>> = paths
        .iter()
        .map(|p| subdirectories(p))
        .collect::<Result<_>>()?;
    let labelled: Vec<bool> = paths
        .iter()
        .zip(&subs)
        .map(|(p, s)| !s.is_empty() && !has_csv(p))
        .collect();
    if !labelled.iter().any(|&l| l) {
        return Ok(DemoSets::Plain(read_demos(
            paths,
            state_length,
            resample_hz,
        )?));
    }
    if let Some(i) = labelled.iter().position(|&l| !l) {
        return Err(Error::file(
            &paths[i],
            "plain demonstrations given together with labelled directories: give only directories of gesture subdirectories (demos/<label>/*.csv)",
        ));
    }
    let mut sets: Vec<(String, Vec<Demonstration>)> = Vec::new();
    for dir in subs.iter().flatten() {
        let label = dir_label(dir);
        if !is_plain_label(&label) {
            return Err(Error::file(
                dir,
                format!("the gesture label {label:?} is not a plain word: name the directory with letters, digits, '_' and '-' only"),
            ));
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

/// A directory's name, as a gesture label.
pub(super) fn dir_label(dir: &Path) -> String {
    dir.file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default()
}

/// The entries of a directory, naming it when it cannot be read.
fn entries(dir: &Path) -> Result<Vec<PathBuf>> {
    let io = |source| DemoError::Io {
        path: dir.display().to_string(),
        source,
    };
    let mut paths = Vec::new();
    for e in std::fs::read_dir(dir).map_err(io)? {
        paths.push(e.map_err(io)?.path());
    }
    paths.sort();
    Ok(paths)
}

/// Subdirectories of a directory, sorted (empty for a file).
pub(super) fn subdirectories(path: &Path) -> Result<Vec<PathBuf>> {
    if !path.is_dir() {
        return Ok(Vec::new());
    }
    Ok(entries(path)?.into_iter().filter(|p| p.is_dir()).collect())
}

/// True when `p` names a `*.csv` file.
fn is_csv(p: &Path) -> bool {
    p.is_file()
        && p.extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| x.eq_ignore_ascii_case("csv"))
}

/// True when the directory holds a `*.csv` file.
pub(super) fn has_csv(path: &Path) -> bool {
    std::fs::read_dir(path).is_ok_and(|rd| rd.flatten().any(|e| is_csv(&e.path())))
}

/// The `*.csv` files of a directory, sorted; an error naming it when there is none.
pub(super) fn csv_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let files: Vec<PathBuf> = entries(dir)?.into_iter().filter(|p| is_csv(p)).collect();
    if files.is_empty() {
        return Err(DemoError::EmptyDirectory {
            path: dir.display().to_string(),
        }
        .into());
    }
    Ok(files)
}

/// A reproduction CSV (a `time` or `step` first column, then the variables): a `step`
/// column is not a variable and is left out.
pub fn read_reproduction(path: &Path) -> Result<Demonstration> {
    let mut d = demos::read_csv(path)?;
    if d.columns.first().map(String::as_str) == Some("step") {
        d.columns.remove(0);
        for r in &mut d.rows {
            r.remove(0);
        }
        if d.columns.is_empty() {
            return Err(Error::file(
                path,
                "only a `step` column, no state variables",
            ));
        }
    }
    Ok(d)
}

/// A CSV of postures (a demonstration, an encoder reading, or a reproduction as `cosco
/// reproduce` writes it) whose columns must be `columns` (a model's).
pub fn read_for_columns(path: &Path, columns: &[String]) -> Result<Demonstration> {
    let d = read_reproduction(path)?;
    if d.columns != columns {
        return Err(Error::file(
            path,
            format!(
                "columns {:?} differ from the model's {columns:?}",
                d.columns
            ),
        ));
    }
    Ok(d)
}

/// Write `value` as pretty JSON atomically to `path`, naming it on failure.
pub(super) fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<()> {
    let bytes = serde_json::to_vec_pretty(value).map_err(|e| Error::Write {
        path: path.to_path_buf(),
        source: e.into(),
    })?;
    write(path, &bytes)
}
