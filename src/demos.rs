//! Demonstration files: one CSV file per demonstration, a header row, an optional first
//! column `time` (seconds), then one column per state variable.
//!
//! Reading checks everything a learner relies on and names the file, line and column of the
//! first problem: empty files, a header without samples, ragged rows, cells that are not
//! numbers or not finite, empty or duplicate column names, and time stamps that do not
//! increase. [`validate_set`] then checks that a set of demonstrations agrees on its
//! columns (and, optionally, on a configured state length); labelled sets, one per gesture,
//! take plain words as labels ([`is_plain_label`]) and record the same variables
//! ([`check_gesture_columns`]). Reading sets from paths: [`crate::demo_sets`].
//!
//! ```
//! use cosco_hsom::demos::{read_csv, write_csv, Demonstration};
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("demo1.csv");
//! let demo = Demonstration {
//!     source: "example".into(),
//!     columns: vec!["q0".into(), "q1".into()],
//!     time: Some(vec![0.0, 0.025]),
//!     rows: vec![vec![0.1, 0.2], vec![0.15, 0.25]],
//! };
//! write_csv(&path, &demo).unwrap();
//! let back = read_csv(&path).unwrap();
//! assert_eq!(back.rows, demo.rows);
//! assert_eq!(back.time, demo.time);
//! ```

use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// One demonstration: a multivariate time series sampled at a fixed rate.
#[derive(Debug, Clone, PartialEq)]
pub struct Demonstration {
    /// Where it came from (a file path or a generator name), used in messages.
    pub source: String,
    /// State-variable names, one per column (the `time` column excluded).
    pub columns: Vec<String>,
    /// Sample times in seconds, when the file had a `time` column.
    pub time: Option<Vec<f64>>,
    /// One row per sample, each `columns.len()` long, every value finite.
    pub rows: Vec<Vec<f64>>,
}

impl Demonstration {
    /// Plain time series (rows of values) as demonstrations: `series #0`, `series #1`, ... in
    /// messages, columns `x0`, `x1`, ..., no times.
    pub fn from_series(series: &[Vec<Vec<f64>>]) -> Vec<Demonstration> {
        let width = series.first().and_then(|s| s.first()).map_or(0, Vec::len);
        let columns: Vec<String> = (0..width).map(|i| format!("x{i}")).collect();
        (series.iter().enumerate())
            .map(|(i, rows)| Demonstration {
                source: format!("series #{i}"),
                columns: columns.clone(),
                time: None,
                rows: rows.clone(),
            })
            .collect()
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// True when the demonstration has no samples.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Number of state variables (columns other than `time`).
    pub fn width(&self) -> usize {
        self.columns.len()
    }
}

/// Name of the optional first column holding sample times in seconds (matched without
/// regard to case or surrounding spaces).
pub const TIME_COLUMN: &str = "time";

/// What can go wrong reading, writing or checking demonstrations. Every variant names the
/// file (`path`, the demonstration's `source` for in-memory data) and, where it applies,
/// the 1-based line of the file (the header is line 1) or the 0-based sample index.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DemoError {
    /// The file could not be opened or read.
    #[error("{path}: cannot read the demonstration file: {source}")]
    Io {
        /// File path.
        path: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// The file could not be written.
    #[error("{path}: cannot write the demonstration file: {source}")]
    Write {
        /// File path.
        path: String,
        /// Underlying error.
        source: std::io::Error,
    },
    /// The CSV parser rejected the file (for instance invalid UTF-8).
    #[error("{path}: line {line}: malformed CSV: {message}")]
    Csv {
        /// File path.
        path: String,
        /// 1-based line.
        line: u64,
        /// Parser message.
        message: String,
    },
    /// The file has no header row at all.
    #[error("{path}: the file is empty; expected a header row (optional `time`, then one name per state variable) and one row per sample")]
    Empty {
        /// File path.
        path: String,
    },
    /// The header is present but no sample follows it.
    #[error(
        "{path}: the file has a header but no samples; add one row per sample below the header"
    )]
    NoSamples {
        /// File path.
        path: String,
    },
    /// The header names no state variable (it is empty or only `time`).
    #[error("{path}: the header names no state variable; add one column per joint after the optional `time` column")]
    NoStateColumns {
        /// File path.
        path: String,
    },
    /// A column name is empty.
    #[error("{path}: column {column_index} (1-based) of the header has an empty name; name every column")]
    EmptyColumnName {
        /// File path.
        path: String,
        /// 1-based column position in the file.
        column_index: usize,
    },
    /// Two columns share a name.
    #[error("{path}: column name `{column}` appears twice (columns {first} and {second}, 1-based); rename one")]
    DuplicateColumn {
        /// File path.
        path: String,
        /// The repeated name.
        column: String,
        /// 1-based position of the first occurrence.
        first: usize,
        /// 1-based position of the second occurrence.
        second: usize,
    },
    /// A row has a different number of cells than the header.
    #[error("{path}: line {line} has {found} cells but the header has {expected}; every row needs one value per column")]
    Ragged {
        /// File path.
        path: String,
        /// 1-based line.
        line: u64,
        /// Cells in the header.
        expected: usize,
        /// Cells in this row.
        found: usize,
    },
    /// A cell is not a number.
    #[error("{path}: line {line}, column `{column}`: `{value}` is not a number")]
    NotNumeric {
        /// File path.
        path: String,
        /// 1-based line.
        line: u64,
        /// Column name.
        column: String,
        /// The cell's text.
        value: String,
    },
    /// A cell (or an in-memory value) is NaN or infinite.
    #[error("{path}: {location}, column `{column}`: value `{value}` is not finite (NaN or infinity); demonstrations must hold finite numbers")]
    NotFinite {
        /// File path or source.
        path: String,
        /// `line N` for a file, `sample N` (0-based) for in-memory data.
        location: String,
        /// Column name.
        column: String,
        /// The offending value as text.
        value: String,
    },
    /// Time stamps do not strictly increase.
    #[error("{path}: {location}: time {value} s is not after the previous sample's {previous} s; time must strictly increase")]
    NonIncreasingTime {
        /// File path or source.
        path: String,
        /// `line N` for a file, `sample N` (0-based) for in-memory data.
        location: String,
        /// This sample's time.
        value: f64,
        /// The previous sample's time.
        previous: f64,
    },
    /// An in-memory demonstration whose time vector length differs from its row count.
    #[error("{path}: {times} time stamps for {rows} samples; give one time per sample")]
    TimeLength {
        /// Source.
        path: String,
        /// Number of time stamps.
        times: usize,
        /// Number of samples.
        rows: usize,
    },
    /// An in-memory sample whose width differs from the number of columns.
    #[error("{path}: sample {sample} has {found} values but there are {expected} columns")]
    RowWidth {
        /// Source.
        path: String,
        /// 0-based sample index.
        sample: usize,
        /// Number of columns.
        expected: usize,
        /// Values in the sample.
        found: usize,
    },
    /// Two demonstrations of one set have different columns.
    #[error("{path}: columns {found:?} differ from the columns {expected:?} of {reference}; all demonstrations of a set must have the same columns in the same order")]
    ColumnsDiffer {
        /// The differing demonstration.
        path: String,
        /// The first demonstration of the set, against which the others are checked.
        reference: String,
        /// The reference's columns.
        expected: Vec<String>,
        /// This demonstration's columns.
        found: Vec<String>,
    },
    /// Two demonstrations of one set are sampled at different rates (their `time` columns'
    /// median sample periods differ by more than 1 %), or only some have a `time` column.
    #[error("{path}: sampled every {found} s, but {reference} every {expected} s; all demonstrations of a set must share one sampling rate (resample them to one with --resample HZ, Python: resample=HZ, or drop every `time` column to declare them equal)")]
    RateMismatch {
        /// The differing demonstration.
        path: String,
        /// The first demonstration of the set.
        reference: String,
        /// The reference's median sample period, s ("none" without a time column).
        expected: String,
        /// This demonstration's, s.
        found: String,
    },
    /// The number of state columns differs from the configured state length.
    #[error("{path}: {found} state columns but the configured state length is {expected}")]
    WidthMismatch {
        /// File path or source.
        path: String,
        /// Expected state length.
        expected: usize,
        /// Columns found.
        found: usize,
    },
    /// `--resample` given for a demonstration without a `time` column.
    #[error("{path}: no `time` column to resample from; --resample (Python: resample=) needs the sample times of every demonstration")]
    ResampleWithoutTime {
        /// File path or source.
        path: String,
    },
    /// A resampling rate that is not one.
    #[error("--resample {value}: expected a rate in (0, 10000] Hz")]
    ResampleRate {
        /// The rate given.
        value: f64,
    },
    /// A set of demonstrations is empty.
    #[error("no demonstrations given; pass at least one CSV file or a directory of them")]
    NoDemonstrations,
    /// A directory holds no `*.csv` files.
    #[error("{path}: the directory holds no *.csv files")]
    EmptyDirectory {
        /// Directory path.
        path: String,
    },
    /// Directories or lists that hold no demonstration.
    #[error("no demonstration files found in {paths}")]
    NoFiles {
        /// The paths given, comma-separated.
        paths: String,
    },
    /// Plain demonstrations given beside directories of gesture subdirectories.
    #[error("{path}: plain demonstrations given together with labelled directories: give only directories of gesture subdirectories (demos/<label>/*.csv)")]
    MixedSets {
        /// The plain file or directory.
        path: String,
    },
    /// A gesture subdirectory whose name is not a plain word ([`is_plain_label`]).
    #[error("{path}: the gesture label {label:?} is not a plain word: name the directory with letters, digits, '_' and '-' only")]
    LabelDirectory {
        /// The subdirectory.
        path: String,
        /// Its name.
        label: String,
    },
    /// Gestures whose demonstrations record different variables.
    #[error("gesture {label:?} has columns {found:?}, but gesture {first_label:?} has {expected:?}: every gesture must record the same variables")]
    GestureColumns {
        /// The label that differs.
        label: String,
        /// Its columns.
        found: Vec<String>,
        /// The first label.
        first_label: String,
        /// The first label's columns.
        expected: Vec<String>,
    },
}

pub(crate) fn parse_cell(
    path: &str,
    line: u64,
    column: &str,
    text: &str,
) -> Result<f64, DemoError> {
    let v: f64 = text.parse().map_err(|_| DemoError::NotNumeric {
        path: path.to_string(),
        line,
        column: column.to_string(),
        value: text.to_string(),
    })?;
    if !v.is_finite() {
        return Err(DemoError::NotFinite {
            path: path.to_string(),
            location: format!("line {line}"),
            column: column.to_string(),
            value: text.to_string(),
        });
    }
    Ok(v)
}

pub(crate) fn check_names(path: &str, names: &[String]) -> Result<(), DemoError> {
    let mut seen: HashMap<&str, usize> = HashMap::new();
    for (i, name) in names.iter().enumerate() {
        let pos = i + 1;
        if name.trim().is_empty() {
            return Err(DemoError::EmptyColumnName {
                path: path.to_string(),
                column_index: pos,
            });
        }
        if let Some(&first) = seen.get(name.as_str()) {
            return Err(DemoError::DuplicateColumn {
                path: path.to_string(),
                column: name.clone(),
                first,
                second: pos,
            });
        }
        seen.insert(name.as_str(), pos);
    }
    Ok(())
}

/// Read one demonstration CSV file: a header row, an optional first column named `time`
/// (seconds, strictly increasing), then one column per state variable. Cells are trimmed of
/// surrounding spaces; every value must be a finite number.
pub fn read_csv(path: &Path) -> Result<Demonstration, DemoError> {
    let p = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| DemoError::Io {
        path: p.clone(),
        source,
    })?;
    parse_csv(&p, &bytes)
}

/// Parse demonstration CSV text held in memory; `source` names it in messages.
/// Same rules as [`read_csv`].
pub fn parse_csv(source: &str, bytes: &[u8]) -> Result<Demonstration, DemoError> {
    let p = source.to_string();
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(bytes);
    let mut records = reader.records();
    let csv_err = |e: csv::Error| DemoError::Csv {
        path: p.clone(),
        line: e.position().map(|pos| pos.line()).unwrap_or(0),
        message: e.to_string(),
    };
    let header = match records.next() {
        None => return Err(DemoError::Empty { path: p.clone() }),
        Some(r) => r.map_err(csv_err)?,
    };
    let names: Vec<String> = header.iter().map(|s| s.to_string()).collect();
    if names.len() == 1 && names[0].is_empty() {
        return Err(DemoError::Empty { path: p.clone() });
    }
    let has_time = names
        .first()
        .is_some_and(|n| n.trim().eq_ignore_ascii_case(TIME_COLUMN));
    let offset = usize::from(has_time);
    let columns: Vec<String> = names[offset..].to_vec();
    check_names(&p, &names)?;
    if columns.is_empty() {
        return Err(DemoError::NoStateColumns { path: p.clone() });
    }
    let mut time = Vec::new();
    let mut rows = Vec::new();
    for rec in records {
        let rec = rec.map_err(csv_err)?;
        let line = rec.position().map(|pos| pos.line()).unwrap_or(0);
        // A blank line inside the file: the csv crate skips fully empty lines already;
        // a line of only separators is a ragged row and reported as such.
        if rec.len() != names.len() {
            return Err(DemoError::Ragged {
                path: p.clone(),
                line,
                expected: names.len(),
                found: rec.len(),
            });
        }
        if has_time {
            let t = parse_cell(&p, line, &names[0], &rec[0])?;
            if let Some(&prev) = time.last() {
                if t <= prev {
                    return Err(DemoError::NonIncreasingTime {
                        path: p.clone(),
                        location: format!("line {line}"),
                        value: t,
                        previous: prev,
                    });
                }
            }
            time.push(t);
        }
        let mut row = Vec::with_capacity(columns.len());
        for (c, name) in columns.iter().enumerate() {
            row.push(parse_cell(&p, line, name, &rec[c + offset])?);
        }
        rows.push(row);
    }
    if rows.is_empty() {
        return Err(DemoError::NoSamples { path: p });
    }
    Ok(Demonstration {
        source: p,
        columns,
        time: has_time.then_some(time),
        rows,
    })
}

/// Read demonstrations from a list of paths: a directory contributes its `*.csv` files
/// (extension matched without regard to case) sorted by file name; a file is read as is.
/// Each file is checked by [`read_csv`]; the set is not cross-checked here: call
/// [`validate_set`] for that.
pub fn read_dir_or_files(paths: &[PathBuf]) -> Result<Vec<Demonstration>, DemoError> {
    if paths.is_empty() {
        return Err(DemoError::NoDemonstrations);
    }
    let mut out = Vec::new();
    for path in paths {
        if path.is_dir() {
            let io = |source| DemoError::Io {
                path: path.display().to_string(),
                source,
            };
            let mut files = Vec::new();
            for e in std::fs::read_dir(path).map_err(io)? {
                let e = e.map_err(io)?;
                let f = e.path();
                let is_csv = f
                    .extension()
                    .and_then(|x| x.to_str())
                    .is_some_and(|x| x.eq_ignore_ascii_case("csv"));
                if is_csv && f.is_file() {
                    files.push(f);
                }
            }
            if files.is_empty() {
                return Err(DemoError::EmptyDirectory {
                    path: path.display().to_string(),
                });
            }
            files.sort_by(|a, b| a.file_name().cmp(&b.file_name()));
            for f in files {
                out.push(read_csv(&f)?);
            }
        } else {
            out.push(read_csv(path)?);
        }
    }
    Ok(out)
}

/// Render a demonstration as CSV text (header, then one row per sample; values printed
/// with Rust's shortest round-trip formatting, so reading back gives identical numbers).
/// The demonstration is checked first by [`validate_set`] on its own.
pub fn to_csv_bytes(demo: &Demonstration) -> Result<Vec<u8>, DemoError> {
    validate_set(std::slice::from_ref(demo), None)?;
    let mut w = csv::Writer::from_writer(Vec::new());
    let io = |e: &dyn ToString| DemoError::Write {
        path: demo.source.clone(),
        source: std::io::Error::other(e.to_string()),
    };
    let mut header: Vec<&str> = Vec::with_capacity(demo.columns.len() + 1);
    if demo.time.is_some() {
        header.push(TIME_COLUMN);
    }
    header.extend(demo.columns.iter().map(|s| s.as_str()));
    w.write_record(&header).map_err(|e| io(&e))?;
    for (i, row) in demo.rows.iter().enumerate() {
        let mut rec: Vec<String> = Vec::with_capacity(row.len() + 1);
        if let Some(t) = &demo.time {
            rec.push(format!("{}", t[i]));
        }
        rec.extend(row.iter().map(|v| format!("{v}")));
        w.write_record(&rec).map_err(|e| io(&e))?;
    }
    w.into_inner().map_err(|e| io(&e))
}

/// Write a demonstration to `path` atomically (temporary file + rename, see
/// [`crate::fsutil::write_atomic`]). The demonstration is checked first; an invalid one is
/// refused and nothing is written.
pub fn write_csv(path: &Path, demo: &Demonstration) -> Result<(), DemoError> {
    let bytes = to_csv_bytes(demo)?;
    crate::fsutil::write_atomic(path, &bytes).map_err(|source| DemoError::Write {
        path: path.display().to_string(),
        source,
    })
}

/// Check one in-memory demonstration: named, unique columns; at least one sample; every
/// row as wide as the columns; finite values; one strictly increasing time per sample.
pub fn validate(demo: &Demonstration) -> Result<(), DemoError> {
    let p = &demo.source;
    if demo.columns.is_empty() {
        return Err(DemoError::NoStateColumns { path: p.clone() });
    }
    check_names(p, &demo.columns)?;
    if demo.rows.is_empty() {
        return Err(DemoError::NoSamples { path: p.clone() });
    }
    for (i, row) in demo.rows.iter().enumerate() {
        if row.len() != demo.columns.len() {
            return Err(DemoError::RowWidth {
                path: p.clone(),
                sample: i,
                expected: demo.columns.len(),
                found: row.len(),
            });
        }
        if let Some((c, v)) = row.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(DemoError::NotFinite {
                path: p.clone(),
                location: format!("sample {i}"),
                column: demo.columns[c].clone(),
                value: format!("{v}"),
            });
        }
    }
    if let Some(time) = &demo.time {
        if time.len() != demo.rows.len() {
            return Err(DemoError::TimeLength {
                path: p.clone(),
                times: time.len(),
                rows: demo.rows.len(),
            });
        }
        for (i, &t) in time.iter().enumerate() {
            if !t.is_finite() {
                return Err(DemoError::NotFinite {
                    path: p.clone(),
                    location: format!("sample {i}"),
                    column: TIME_COLUMN.to_string(),
                    value: format!("{t}"),
                });
            }
            if i > 0 && t <= time[i - 1] {
                return Err(DemoError::NonIncreasingTime {
                    path: p.clone(),
                    location: format!("sample {i}"),
                    value: t,
                    previous: time[i - 1],
                });
            }
        }
    }
    Ok(())
}

/// Check a set of demonstrations: at least one; each valid on its own ([`validate`]); all
/// with the same columns in the same order as the first; and, when `expected_width` is
/// given (the configured state length), that many state columns.
pub fn validate_set(
    demos: &[Demonstration],
    expected_width: Option<usize>,
) -> Result<(), DemoError> {
    let first = demos.first().ok_or(DemoError::NoDemonstrations)?;
    for d in demos {
        validate(d)?;
        if let Some(w) = expected_width {
            if d.columns.len() != w {
                return Err(DemoError::WidthMismatch {
                    path: d.source.clone(),
                    expected: w,
                    found: d.columns.len(),
                });
            }
        }
        if d.columns != first.columns {
            return Err(DemoError::ColumnsDiffer {
                path: d.source.clone(),
                reference: first.source.clone(),
                expected: first.columns.clone(),
                found: d.columns.clone(),
            });
        }
        let (a, b) = (median_interval(first), median_interval(d));
        let same = match (a, b) {
            (None, None) => true,
            (Some(x), Some(y)) => same_rate(x, y),
            _ => false,
        };
        if !same {
            let show =
                |p: Option<f64>| p.map_or("none (no time column)".to_string(), |v| format!("{v}"));
            return Err(DemoError::RateMismatch {
                path: d.source.clone(),
                reference: first.source.clone(),
                expected: show(a),
                found: show(b),
            });
        }
    }
    Ok(())
}

/// True for a plain word, as a gesture label must be: `[A-Za-z0-9_-]+`.
pub fn is_plain_label(label: &str) -> bool {
    !label.is_empty()
        && label
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Gesture `i` of labelled `sets` records the variables of the first: each of its
/// demonstrations has the columns of the first gesture's first demonstration.
pub fn check_gesture_columns(
    sets: &[(String, Vec<Demonstration>)],
    i: usize,
) -> Result<(), DemoError> {
    let (Some((first_label, Some(first))), Some((label, demos))) =
        (sets.first().map(|(l, d)| (l, d.first())), sets.get(i))
    else {
        return Ok(());
    };
    match demos.iter().find(|d| d.columns != first.columns) {
        Some(d) => Err(DemoError::GestureColumns {
            label: label.clone(),
            found: d.columns.clone(),
            first_label: first_label.clone(),
            expected: first.columns.clone(),
        }),
        None => Ok(()),
    }
}

/// Seconds between samples of a demonstration: from its `time` column (its span over the
/// intervals), else 1/40 s. The one period that scoring, GMM/GMR and execution use.
pub fn sample_period(d: &Demonstration) -> f64 {
    match &d.time {
        Some(t) if t.len() >= 2 => (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64,
        _ => 0.025,
    }
}

/// Whether two sample periods are one rate: within 1 % of each other (what [`validate_set`]
/// holds a set to, and an update holds new demonstrations to against a model's).
pub fn same_rate(x: f64, y: f64) -> bool {
    (x - y).abs() <= 0.01 * x.max(y)
}

/// The median interval of a demonstration's `time` column, s (None without one or with a
/// single sample): what [`validate_set`] compares, so that one late sample does not make two
/// recordings differ in rate.
pub fn median_interval(d: &Demonstration) -> Option<f64> {
    let t = d.time.as_ref()?;
    let mut dt: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    crate::stats::upper_median(&mut dt)
}

#[cfg(test)]
mod tests;
