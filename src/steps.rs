//! The steps of `cosco train`, `reproduce`, `inspect` and `evaluate` that need no simulator,
//! shared by the `cosco` binary and the Python package (`python/`): the same checks in the
//! same order, hence the same messages from either.
//!
//! ```
//! use cosco_hsom::config::HsomParams;
//! use cosco_hsom::steps::{demonstrations_from_rows, train};
//! let mut p = HsomParams::table1();
//! p.state_length = 2;
//! p.action_length = 2;
//! p.training_steps = 200;
//! let cfg = p.check("example").unwrap();
//! let rows: Vec<Vec<f64>> = (0..30).map(|i| vec![i as f64 / 30.0, 0.5]).collect();
//! let demos = demonstrations_from_rows(vec![rows.clone(), rows], None).unwrap();
//! let model = train(&cfg, &demos, None).unwrap();
//! assert_eq!(model.columns(), ["x0", "x1"]);
//! ```

use std::path::{Path, PathBuf};

use crate::config::{load_config, parse_config, ConfigError, HsomConfig};
use crate::demos::{self, DemoError, Demonstration};
use crate::hsom::{Hsom, HsomError, PersistError, Reproduction};
use crate::metrics::{fidelity_named, FidelityReport, MetricsError, MetricsParams, Trajectory};

/// The recommended configuration for the simulated Nao (the events extension), built in so
/// that the binaries run from any directory; the default of `simulate` and `cosco`.
pub const NAO_GESTURES_XML: &str = include_str!("../configs/nao-gestures.xml");

/// Name of the built-in default configuration in reports and messages.
pub const DEFAULT_CONFIG_NAME: &str = "configs/nao-gestures.xml (built in)";

/// Why a step was refused. The wrapped errors name their file, field and value; the others
/// say what is allowed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum StepError {
    /// The configuration was refused.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// A demonstration was refused.
    #[error(transparent)]
    Demo(#[from] DemoError),
    /// Training or reproduction was refused.
    #[error(transparent)]
    Hsom(#[from] HsomError),
    /// A model file could not be saved or loaded.
    #[error(transparent)]
    Persist(#[from] PersistError),
    /// The fidelity metrics were refused.
    #[error(transparent)]
    Metrics(#[from] MetricsError),
    /// A model path that ends neither in `.bin` nor in `.txt`.
    #[error("{path}: a model file must end in .bin (binary) or .txt (plain text)")]
    ModelExtension {
        /// The path.
        path: String,
    },
    /// An initial posture of the arm far outside a joint's range.
    #[error("the initial posture's {joint} = {value} is outside its range [{lo}, {hi}] by more than {tolerance} rad: not a posture the arm can start from")]
    InitialOutOfRange {
        /// The joint.
        joint: String,
        /// The value given.
        value: f64,
        /// The joint's range.
        lo: f64,
        /// The joint's range.
        hi: f64,
        /// How far beyond the range a value is still accepted (encoder noise, soft limits).
        tolerance: f64,
    },
    /// The directory a model is to be written to does not exist or cannot be written.
    #[error("{path}: cannot write the model there: {reason}")]
    OutputDir {
        /// The model file's path.
        path: String,
        /// Why (the directory is missing, not a directory, or not writable).
        reason: String,
    },
    /// Directories or lists that hold no demonstration.
    #[error("no demonstration files found in {paths}")]
    NoDemonstrations {
        /// The paths given, comma-separated.
        paths: String,
    },
    /// Column names given for in-memory demonstrations that do not match their width.
    #[error("columns: {found} names ({names}) for demonstrations of {expected} variables")]
    ColumnCount {
        /// Names given.
        found: usize,
        /// The names, comma-separated.
        names: String,
        /// Variables of the first demonstration.
        expected: usize,
    },
    /// An initial posture of another length than the model's state.
    #[error("the initial posture has {found} values; the model {model} learned {expected} variables ({columns})")]
    InitialWidth {
        /// Values given.
        found: usize,
        /// The model (a file, or `in memory`).
        model: String,
        /// Variables the model learned.
        expected: usize,
        /// Their names, comma-separated.
        columns: String,
    },
    /// A file whose columns differ from the ones expected.
    #[error("{path}: columns {found:?} differ from the {what}'s {expected:?}")]
    ColumnsDiffer {
        /// The file.
        path: String,
        /// Whose columns were expected (`model`, `demonstrations`).
        what: &'static str,
        /// The expected columns.
        expected: Vec<String>,
        /// The file's columns.
        found: Vec<String>,
    },
    /// A reproduction file with a `step` column and nothing else.
    #[error("{path}: only a `step` column, no state variables")]
    NoStateVariables {
        /// The file.
        path: String,
    },
}

/// The extension of a model file: `.bin` or `.txt`, else an error saying so.
pub fn check_model_extension(path: &Path) -> Result<(), StepError> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("bin") | Some("txt") => Ok(()),
        _ => Err(StepError::ModelExtension {
            path: path.display().to_string(),
        }),
    }
}

/// Check, before any work, that a model can be written to `path`: a `.bin` or `.txt` name in
/// an existing directory where a file can be created (a temporary file is made and removed).
pub fn check_model_output(path: &Path) -> Result<(), StepError> {
    check_model_extension(path)?;
    check_output(path)
}

/// Check, before any work, that a file can be written to `path`: its directory exists and a
/// file can be created there (a temporary file is made and removed).
pub fn check_output(path: &Path) -> Result<(), StepError> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let err = |reason: String| StepError::OutputDir {
        path: path.display().to_string(),
        reason,
    };
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

/// Load a CoSCo-HSOM configuration file, or the built-in recommended configuration.
pub fn config(path: Option<&Path>) -> Result<HsomConfig, StepError> {
    Ok(match path {
        Some(p) => load_config(p)?,
        None => parse_config(NAO_GESTURES_XML, DEFAULT_CONFIG_NAME)?,
    })
}

/// Read demonstration files (a directory of *.csv or explicit files), checked as a set
/// (against `state_length` when given).
pub fn read_demos(
    paths: &[PathBuf],
    state_length: Option<usize>,
) -> Result<Vec<Demonstration>, StepError> {
    read_demos_at(paths, state_length, None)
}

/// [`read_demos`], each demonstration first resampled to `resample_hz` when given
/// ([`crate::resample::resample_all`]).
pub fn read_demos_at(
    paths: &[PathBuf],
    state_length: Option<usize>,
    resample_hz: Option<f64>,
) -> Result<Vec<Demonstration>, StepError> {
    let demos = crate::resample::resample_all(demos::read_dir_or_files(paths)?, resample_hz)?;
    if demos.is_empty() {
        return Err(StepError::NoDemonstrations {
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

/// In-memory demonstrations (`demos[0]`, `demos[1]`, ... in messages) from rows of samples,
/// with `columns` as their variable names (default `x0`, `x1`, ...). Only the names are
/// checked here; [`train`] checks the set.
pub fn demonstrations_from_rows(
    series: Vec<Vec<Vec<f64>>>,
    columns: Option<Vec<String>>,
) -> Result<Vec<Demonstration>, StepError> {
    let width = series.first().and_then(|s| s.first()).map_or(0, Vec::len);
    let columns = match columns {
        Some(c) if c.len() != width && !series.is_empty() => {
            return Err(StepError::ColumnCount {
                found: c.len(),
                names: c.join(", "),
                expected: width,
            })
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

/// Check the demonstrations as a set against the configuration (at least one; see
/// [`demos::validate_set`]), then train, calling
/// `progress(done, total)` now and then when given.
pub fn train(
    cfg: &HsomConfig,
    demos: &[Demonstration],
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<Hsom, StepError> {
    demos::validate_set(demos, Some(cfg.params().state_length))?;
    Ok(cfg.fit_with_progress(demos, progress)?)
}

/// Save a model (`.bin` or `.txt`, atomically).
pub fn save_model(model: &Hsom, path: &Path) -> Result<(), StepError> {
    check_model_extension(path)?;
    Ok(model.save(path)?)
}

/// Load a saved model (`.bin` or `.txt`).
pub fn load_model(path: &Path) -> Result<Hsom, StepError> {
    check_model_extension(path)?;
    Ok(Hsom::load(path)?)
}

/// Reproduce from `initial`, first checking that it has one value per learned variable
/// (`model_name` names the model in the message: its file, or `in memory`).
pub fn reproduce(
    model: &Hsom,
    model_name: &str,
    initial: &[f64],
) -> Result<Reproduction, StepError> {
    check_initial(model, model_name, initial)?;
    Ok(model.reproduce(initial)?)
}

/// Resume the reproduction from `initial` after part of it was executed (`reading`: what the
/// encoders read meanwhile; [`Hsom::resume`]), with the checks of [`reproduce`].
pub fn resume(
    model: &Hsom,
    model_name: &str,
    initial: &[f64],
    reading: &[Vec<f64>],
) -> Result<Reproduction, StepError> {
    check_initial(model, model_name, initial)?;
    Ok(model.resume(initial, reading)?)
}

/// `initial` has one value per learned variable and, for the arm's joints, lies within
/// their ranges.
fn check_initial(model: &Hsom, model_name: &str, initial: &[f64]) -> Result<(), StepError> {
    let columns = model.columns();
    if initial.len() != columns.len() {
        return Err(StepError::InitialWidth {
            found: initial.len(),
            model: model_name.to_string(),
            expected: columns.len(),
            columns: columns.join(", "),
        });
    }
    #[cfg(feature = "sim")]
    if crate::experiment::are_arm_joints(columns) {
        use crate::experiment::RANGE_TOLERANCE_RAD;
        for (v, spec) in initial.iter().zip(crate::sim::JOINT_SPECS.iter()) {
            let (lo, hi) = spec.range;
            if v.is_finite() && !(lo - RANGE_TOLERANCE_RAD..=hi + RANGE_TOLERANCE_RAD).contains(v) {
                return Err(StepError::InitialOutOfRange {
                    joint: spec.name.to_string(),
                    value: *v,
                    lo,
                    hi,
                    tolerance: RANGE_TOLERANCE_RAD,
                });
            }
        }
    }
    Ok(())
}

/// The first row of a demonstration file, as an initial posture for `model`.
pub fn initial_from_file(model: &Hsom, path: &Path) -> Result<Vec<f64>, StepError> {
    Ok(rows_from_file(model, path)?.swap_remove(0))
}

/// The rows of a CSV of postures (a demonstration, an encoder reading, or a reproduction
/// as `cosco reproduce` writes it: a first `time` or `step` column is not a variable) whose
/// columns must be the model's.
pub fn rows_from_file(model: &Hsom, path: &Path) -> Result<Vec<Vec<f64>>, StepError> {
    let d = read_reproduction(path)?;
    check_columns(path, &d, model.columns())?;
    Ok(d.rows)
}

/// A demonstration CSV whose columns must be `columns` (a model's).
pub fn read_for_columns(path: &Path, columns: &[String]) -> Result<Demonstration, StepError> {
    let d = demos::read_csv(path)?;
    check_columns(path, &d, columns)?;
    Ok(d)
}

fn check_columns(path: &Path, d: &Demonstration, columns: &[String]) -> Result<(), StepError> {
    if d.columns != columns {
        return Err(StepError::ColumnsDiffer {
            path: path.display().to_string(),
            what: "model",
            expected: columns.to_vec(),
            found: d.columns.clone(),
        });
    }
    Ok(())
}

/// A reproduction as `cosco reproduce` writes it: CSV with `step`, then the model's columns.
pub fn reproduction_csv(model: &Hsom, rep: &Reproduction) -> Result<Vec<u8>, csv::Error> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["step".to_string()];
    header.extend(model.columns().iter().cloned());
    w.write_record(&header)?;
    for (step, row) in rep.steps.iter().zip(&rep.postures) {
        let mut rec = vec![step.to_string()];
        rec.extend(row.iter().map(|v| v.to_string()));
        w.write_record(&rec)?;
    }
    w.into_inner().map_err(|e| e.into_error().into())
}

/// Read a reproduction CSV (`time` or `step` first column, then the demonstrations' columns).
pub fn read_reproduction(path: &Path) -> Result<Demonstration, StepError> {
    let mut d = demos::read_csv(path)?;
    if d.columns.first().map(String::as_str) == Some("step") {
        d.columns.remove(0);
        for r in &mut d.rows {
            r.remove(0);
        }
        if d.columns.is_empty() {
            return Err(StepError::NoStateVariables {
                path: path.display().to_string(),
            });
        }
    }
    Ok(d)
}

/// A reproduction file and its demonstrations, read and checked for `cosco evaluate`.
pub fn evaluation_inputs(
    reproduction: &Path,
    demo_paths: &[PathBuf],
) -> Result<(Demonstration, Vec<Demonstration>), StepError> {
    let demos = read_demos(demo_paths, None)?;
    let rep = read_reproduction(reproduction)?;
    if rep.columns != demos[0].columns {
        return Err(StepError::ColumnsDiffer {
            path: reproduction.display().to_string(),
            what: "demonstrations",
            expected: demos[0].columns.clone(),
            found: rep.columns,
        });
    }
    Ok((rep, demos))
}

/// The fidelity of `rows` against the demonstrations in the data's own variables, without
/// wrist paths (those need the simulated arm's kinematics: `experiment::evaluate`).
pub fn evaluate_rows(
    demos: &[Demonstration],
    rows: &[Vec<f64>],
    params: &MetricsParams,
) -> Result<FidelityReport, StepError> {
    let trajs: Vec<Trajectory> = demos.iter().map(Trajectory::from).collect();
    let names: Vec<String> = demos.iter().map(|d| d.source.clone()).collect();
    Ok(fidelity_named(
        &trajs,
        &names,
        &Trajectory::from_joints(rows.to_vec()),
        params,
    )?)
}

/// An error and its causes on one line, leaving out causes whose text the message above
/// already contains (many errors quote their cause): what `cosco` prints after `Error: `, and
/// the message of the Python package's exceptions.
pub fn error_line(e: &(dyn std::error::Error + 'static)) -> String {
    let mut line = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !line.contains(&text) {
            line.push_str(": ");
            line.push_str(&text);
        }
        cause = c.source();
    }
    line
}
