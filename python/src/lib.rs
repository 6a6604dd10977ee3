//! `cosco_hsom._native`: the Python binding of the CoSCo-HSOM crate, built without the
//! simulator. Every operation goes through `cosco_hsom::app`, as `cosco` does, so the checks
//! and messages are the CLI's. Errors become Python exceptions: `ValueError` for every refusal,
//! which is also a `FileNotFoundError` / `PermissionError` / `OSError` when a file could not be
//! read or written (`cosco_hsom._errors`); never a panic across the boundary.

mod eval;
mod gestures;
mod model;
mod stepper;

use std::error::Error;
use std::io::ErrorKind;

use numpy::ndarray::Array2;
use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyType};

use cosco_hsom::app;
use cosco_hsom::demos::Demonstration;

/// The exception for an error: its one-line message (the CLI's); when an I/O error is at its
/// root, one of `cosco_hsom._errors` (each both the matching `OSError` subclass and a
/// `ValueError`), else `ValueError`.
fn py_err(e: &(dyn Error + 'static)) -> PyErr {
    let msg = app::error_line(e);
    let mut cause = Some(e);
    while let Some(c) = cause {
        if let Some(io) = c.downcast_ref::<std::io::Error>() {
            let name = match io.kind() {
                ErrorKind::NotFound => "MissingFileError",
                ErrorKind::PermissionDenied => "FileAccessError",
                _ => "FileError",
            };
            return Python::with_gil(|py| {
                match py
                    .import("cosco_hsom._errors")
                    .and_then(|m| m.getattr(name))
                    .and_then(|t| t.downcast_into::<PyType>().map_err(PyErr::from))
                {
                    Ok(t) => PyErr::from_type(t, msg),
                    // The package is incomplete (no _errors.py): the plain OSError.
                    Err(_) => PyOSError::new_err(msg),
                }
            });
        }
        cause = c.source();
    }
    PyValueError::new_err(msg)
}

fn app_err(e: app::Error) -> PyErr {
    py_err(&e)
}

/// Rows of one 2-D input: a numpy array (any numeric dtype, any layout) or a list of rows.
/// Ragged rows are kept ragged: the library's check names the sample and the widths.
fn rows_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Vec<f64>>> {
    if let Ok(a) = obj.downcast::<PyUntypedArray>() {
        if a.ndim() != 2 {
            return Err(PyValueError::new_err(format!(
                "{what}: a 2-D array (samples x variables) is needed; got a {}-D array of shape {}",
                a.ndim(),
                py_shape(a.shape())
            )));
        }
        let cast;
        let a = match obj.extract::<PyReadonlyArray2<'_, f64>>() {
            Ok(a) => a,
            Err(_) => {
                cast = obj.call_method1("astype", ("float64",)).map_err(|e| {
                    PyValueError::new_err(format!("{what}: the values must be numbers ({e})"))
                })?;
                cast.extract::<PyReadonlyArray2<'_, f64>>()?
            }
        };
        return Ok(a.as_array().outer_iter().map(|r| r.to_vec()).collect());
    }
    if let Ok(rows) = obj.extract::<Vec<Vec<f64>>>() {
        return Ok(rows);
    }
    let got = match obj.extract::<Vec<f64>>() {
        Ok(v) => format!(
            "a 1-D sequence of {} numbers (for one variable, give shape ({}, 1))",
            v.len(),
            v.len()
        ),
        Err(_) => format!("an object of type {}", obj.get_type().name()?),
    };
    Err(PyValueError::new_err(format!(
        "{what}: a 2-D array or a list of rows of numbers (samples x variables) is needed; got {got}"
    )))
}

/// The demonstrations: a list (or other sequence) of 2-D inputs, `{what}[i]` in messages
/// (`demos[i]`, or `gestures['wave'][i]` for a label's).
fn series_of(demos: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Vec<Vec<f64>>>> {
    if demos.downcast::<PyUntypedArray>().is_ok() {
        return Err(PyValueError::new_err(format!(
            "{what}: a list of 2-D arrays is needed, one per demonstration; got one array (wrap it in a list)"
        )));
    }
    let items: Vec<Bound<'_, PyAny>> = demos.extract().map_err(|_| {
        PyValueError::new_err(format!(
            "{what}: a list of 2-D arrays is needed, one per demonstration"
        ))
    })?;
    items
        .iter()
        .enumerate()
        .map(|(i, d)| rows_of(d, &format!("{what}[{i}]")))
        .collect()
}

/// The argument `demos` (a list of 2-D inputs) as demonstrations, with optional column
/// names (default x0, x1, ...).
fn demonstrations_of(
    demos: &Bound<'_, PyAny>,
    columns: Option<Vec<String>>,
) -> PyResult<Vec<Demonstration>> {
    let series = series_of(demos, "demos")?;
    app::demonstrations_from_rows(series, columns).map_err(app_err)
}

/// Labelled demonstration sets from a mapping label -> list of 2-D inputs, in the mapping's
/// order, each demonstration named `gestures['label'][i]` in messages. `columns` name the
/// variables of every label whose width they fit (the first label's always, so a wrong
/// count is the message of `Hsom.fit`); a label of another width keeps generated names and is
/// refused by the configuration's width check, as `cosco train` refuses its files.
fn labelled_sets(
    gestures: &Bound<'_, PyAny>,
    columns: Option<Vec<String>>,
) -> PyResult<Vec<(String, Vec<Demonstration>)>> {
    const NEEDED: &str = "gestures: a mapping label -> list of demonstrations is needed (e.g. {'wave': [array, ...], 'salute': [...]})";
    if gestures.downcast::<PyUntypedArray>().is_ok() || gestures.extract::<String>().is_ok() {
        return Err(PyValueError::new_err(NEEDED));
    }
    let items = gestures
        .call_method0("items")
        .map_err(|_| PyValueError::new_err(NEEDED))?;
    let mut sets = Vec::new();
    for item in items.try_iter()? {
        let (key, value): (Bound<'_, PyAny>, Bound<'_, PyAny>) = item?.extract()?;
        let label: String = key.extract().map_err(|_| {
            PyValueError::new_err(format!(
                "gestures: the labels must be strings (plain words); got {} of type {}",
                key.repr().map_or_else(|_| "?".into(), |r| r.to_string()),
                key.get_type()
                    .name()
                    .map_or_else(|_| "?".into(), |n| n.to_string())
            ))
        })?;
        let what = format!("gestures[{}]", key.repr()?);
        let series = series_of(&value, &what)?;
        let width = series.first().and_then(|s| s.first()).map(Vec::len);
        let names = match &columns {
            Some(c) if sets.is_empty() || width == Some(c.len()) => Some(c.clone()),
            _ => None,
        };
        let mut demos = app::demonstrations_from_rows(series, names).map_err(app_err)?;
        for (i, d) in demos.iter_mut().enumerate() {
            d.source = format!("{what}[{i}]");
        }
        sets.push((label, demos));
    }
    Ok(sets)
}

/// A posture: one number per variable.
fn posture_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    if let Ok(a) = obj.downcast::<PyUntypedArray>() {
        if a.ndim() != 1 {
            return Err(PyValueError::new_err(format!(
                "{what}: a 1-D array (one value per variable) is needed; got a {}-D array of shape {}",
                a.ndim(),
                py_shape(a.shape())
            )));
        }
    }
    obj.extract::<Vec<f64>>().map_err(|_| {
        PyValueError::new_err(format!(
            "{what}: a sequence of numbers (one value per variable) is needed"
        ))
    })
}

/// A shape as Python writes it: `(5,)`, `(3, 4, 2)`.
fn py_shape(shape: &[usize]) -> String {
    match shape {
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

fn array2<'py>(py: Python<'py>, rows: &[Vec<f64>], width: usize) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    let a = Array2::from_shape_vec((rows.len(), width), flat)
        .expect("rows of the library's output all have `width` values");
    PyArray2::from_owned_array(py, a)
}

/// `{label: value}` in the model's order (per-label scores and thresholds).
fn label_dict<'py, 'a>(
    py: Python<'py>,
    pairs: impl IntoIterator<Item = (&'a String, f64)>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (l, v) in pairs {
        d.set_item(l, v)?;
    }
    Ok(d)
}

/// The native part of the `cosco_hsom` package.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<model::Config>()?;
    m.add_class::<model::Hsom>()?;
    m.add_class::<gestures::GestureModel>()?;
    m.add_class::<gestures::Recognition>()?;
    m.add_class::<gestures::Recognizer>()?;
    m.add_class::<stepper::Stepper>()?;
    m.add_class::<eval::GmrModel>()?;
    m.add_class::<eval::Dmp>()?;
    m.add_function(wrap_pyfunction!(eval::dtw, m)?)?;
    m.add_function(wrap_pyfunction!(eval::heldout, m)?)?;
    m.add_function(wrap_pyfunction!(eval::read_demos, m)?)?;
    Ok(())
}
