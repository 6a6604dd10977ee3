//! What the operations read and write: the configuration, demonstrations (one gesture:
//! [`crate::demo_sets`]), model files and reproduction files, each checked as it is read.

use std::path::{Path, PathBuf};

use super::{Error, Result};
use crate::config::{load_config_or_default, HsomConfig};
use crate::demos::{self, Demonstration};
use crate::hsom::GestureModel;

/// Load a CoSCo-HSOM configuration file, or the built-in recommended configuration.
pub fn config(path: Option<&Path>) -> Result<HsomConfig> {
    Ok(load_config_or_default(path)?)
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
    Ok(crate::fsutil::check_output(path)?)
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
/// to `resample_hz` when given, checked as a set (against `state_length` when given):
/// [`crate::demo_sets::read_demos`].
pub fn read_demos(
    paths: &[PathBuf],
    state_length: Option<usize>,
    resample_hz: Option<f64>,
) -> Result<Vec<Demonstration>> {
    Ok(crate::demo_sets::read_demos(
        paths,
        state_length,
        resample_hz,
    )?)
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
