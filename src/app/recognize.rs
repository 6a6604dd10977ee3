//! Recognition of demonstration files by a model of several gestures (`cosco recognize`).

use std::path::{Path, PathBuf};

use super::files::{self, read_for_columns};
use super::{error_line, Error, Result};
use crate::demo_sets::{csv_files, dir_label, has_csv, subdirectories};
use crate::hsom::{GestureModel, Recognition};

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
pub fn recognize_paths(model: &GestureModel, path: &Path) -> Result<Vec<RecognisedFile>> {
    let mut files: Vec<(PathBuf, Option<String>)> = Vec::new();
    let subs = subdirectories(path)?;
    if path.is_dir() && !subs.is_empty() && !has_csv(path) {
        for dir in subs {
            let label = dir_label(&dir);
            files.extend(
                csv_files(&dir)?
                    .into_iter()
                    .map(|f| (f, Some(label.clone()))),
            );
        }
    } else if path.is_dir() {
        files.extend(csv_files(path)?.into_iter().map(|f| (f, None)));
    } else {
        files.push((path.to_path_buf(), None));
    }
    files
        .into_iter()
        .map(|(f, expected)| {
            let d = read_for_columns(&f, model.columns())?;
            let recognition = model
                .recognize(&d.rows)
                .map_err(|e| Error::file(&f, error_line(&e)))?;
            Ok(RecognisedFile {
                file: f.display().to_string(),
                expected,
                recognition,
            })
        })
        .collect()
}

/// `cosco recognize`: one line per file (label, scores, early decision), an accuracy line
/// when the files came from label subdirectories; every answer as JSON in `json` when given.
pub fn recognize_files(model: &Path, demos: &Path, json: Option<&Path>) -> Result<Vec<String>> {
    let m = files::load_gesture_model(model)?;
    let answers = recognize_paths(&m, demos)?;
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
    let labelled: Vec<_> = answers.iter().filter(|a| a.expected.is_some()).collect();
    if !labelled.is_empty() {
        let right = labelled
            .iter()
            .filter(|a| a.expected == a.recognition.label)
            .count();
        lines.push(format!(
            "{right} of {} recognised as their directory's label",
            labelled.len()
        ));
    }
    if let Some(p) = json {
        files::write_json(p, &answers)?;
    }
    Ok(lines)
}
