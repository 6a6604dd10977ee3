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

/// `cosco recognize`'s line for one answer: the file, the label (or `unknown`) and what was
/// expected, the early decision, every score with its threshold, and per label the variables
/// its score weighs most with their weights.
pub fn answer_line(file: &str, expected: Option<&str>, r: &Recognition) -> String {
    let scores: Vec<String> = r
        .scores
        .iter()
        .zip(&r.thresholds)
        .map(|((l, s), t)| format!("{l} {s:.4} (threshold {t:.4})"))
        .collect();
    let weighed: Vec<String> = (r.scores.iter().zip(&r.weighed))
        .map(|((l, _), w)| {
            let w: Vec<String> = w.iter().map(|(v, w)| format!("{v} {w:.2}")).collect();
            format!("{l}: {}", w.join(", "))
        })
        .collect();
    format!(
        "{}: {}{} | decided at sample {} of {} | scores: {} | weighed most: {}",
        file,
        r.label.as_deref().unwrap_or("unknown"),
        expected.map_or(String::new(), |e| format!(" (expected {e})")),
        r.decided_at,
        r.samples,
        scores.join(", "),
        weighed.join("; ")
    )
}

/// `cosco recognize`: one line per file (label, scores, early decision), an accuracy line
/// when the files came from label subdirectories; every answer as JSON in `json` when given.
pub fn recognize_files(model: &Path, demos: &Path, json: Option<&Path>) -> Result<Vec<String>> {
    let m = files::load_gesture_model(model)?;
    let answers = recognize_paths(&m, demos)?;
    let mut lines = Vec::new();
    for a in &answers {
        lines.push(answer_line(&a.file, a.expected.as_deref(), &a.recognition));
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

/// What `cosco recognize --stream` calls its input in messages.
pub const STREAM_SOURCE: &str = "standard input";

/// `cosco recognize --model M --stream`: CSV rows read from `input` as they come (a header
/// of the model's columns, optionally a first `time` column in seconds, strictly increasing,
/// and a `step` column before the variables as `cosco reproduce` writes), each pushed into a
/// recogniser in the loop ([`crate::hsom::Recognizer`]); `out` gets a line when it commits
/// (`sample N[ time T s]: label` or `unknown`) and, at the end, the whole sequence's answer
/// as `cosco recognize` prints it. A bad header, cell, row width or time is refused naming
/// its line and column.
pub fn recognize_stream(
    model: &Path,
    input: impl std::io::Read,
    out: &mut dyn FnMut(&str),
) -> Result<Recognition> {
    use crate::demos::{check_names, parse_cell, DemoError, TIME_COLUMN};
    let m = files::load_gesture_model(model)?;
    let mut recognizer = m.recognizer()?;
    let src = STREAM_SOURCE;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(input);
    let csv_err = |e: csv::Error| DemoError::Csv {
        path: src.into(),
        line: e.position().map_or(0, |p| p.line()),
        message: e.to_string(),
    };
    let mut records = reader.records();
    let header = match records.next() {
        None => return Err(DemoError::Empty { path: src.into() }.into()),
        Some(r) => r.map_err(csv_err)?,
    };
    let names: Vec<String> = header.iter().map(str::to_string).collect();
    check_names(src, &names)?;
    let has_time = names[0].eq_ignore_ascii_case(TIME_COLUMN);
    let mut offset = usize::from(has_time);
    if names.get(offset).map(String::as_str) == Some("step") {
        offset += 1;
    }
    if names[offset..] != *m.columns() {
        return Err(Error::value(
            format!("{src}, line 1 (the header):"),
            format!(
                "columns {:?} differ from the model's {:?} (an optional first `time` column, \
                 then the model's columns)",
                &names[offset..],
                m.columns()
            ),
        ));
    }
    let mut last_time: Option<f64> = None;
    let mut row = Vec::with_capacity(names.len() - offset);
    for rec in records {
        let rec = rec.map_err(csv_err)?;
        let line = rec.position().map_or(0, |p| p.line());
        if rec.len() != names.len() {
            return Err(DemoError::Ragged {
                path: src.into(),
                line,
                expected: names.len(),
                found: rec.len(),
            }
            .into());
        }
        let time = if has_time {
            let t = parse_cell(src, line, &names[0], &rec[0])?;
            if let Some(prev) = last_time.filter(|&p| t <= p) {
                return Err(DemoError::NonIncreasingTime {
                    path: src.into(),
                    location: format!("line {line}"),
                    value: t,
                    previous: prev,
                }
                .into());
            }
            last_time = Some(t);
            Some(t)
        } else {
            None
        };
        row.clear();
        for (name, cell) in names[offset..].iter().zip(rec.iter().skip(offset)) {
            row.push(parse_cell(src, line, name, cell)?);
        }
        let before = recognizer.decided();
        let commit = recognizer
            .push(&row)
            .map_err(|e| Error::value(format!("{src}, line {line}:"), error_line(&e)))?;
        if let (false, Some(c)) = (before, commit) {
            out(&format!(
                "sample {}{}: {}",
                c.samples,
                time.map_or(String::new(), |t| format!(" time {t} s")),
                c.label.as_deref().unwrap_or("unknown")
            ));
        }
    }
    let r = recognizer
        .finish()
        .map_err(|e| Error::value(format!("{src}:"), error_line(&e)))?;
    out(&answer_line(src, None, &r));
    Ok(r)
}
