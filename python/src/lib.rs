//! `cosco_hsom._native`: the Python binding of the CoSCo-HSOM crate, built without the
//! simulator. Every step goes through `cosco_hsom::steps`, as `cosco` does, so the checks and
//! messages are the CLI's. Errors become Python exceptions: `ValueError` for every refusal,
//! which is also a `FileNotFoundError` / `PermissionError` / `OSError` when a file could not be
//! read or written (`cosco_hsom._errors`); never a panic across the boundary.

use std::error::Error;
use std::io::ErrorKind;
use std::path::PathBuf;

use numpy::ndarray::Array2;
use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyType};

use cosco_hsom::config::{HsomConfig, HsomParams};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::dtw::{dtw_distance, Band};
use cosco_hsom::gmr::{self, ComponentChoice, GmrParams};
use cosco_hsom::labelled::{self, LabelledError};
use cosco_hsom::steps;

/// The exception for an error: its one-line message (the CLI's); when an I/O error is at its
/// root, one of `cosco_hsom._errors` (each both the matching `OSError` subclass and a
/// `ValueError`), else `ValueError`.
fn py_err(e: &(dyn Error + 'static)) -> PyErr {
    let msg = steps::error_line(e);
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

fn step_err(e: steps::StepError) -> PyErr {
    py_err(&e)
}

fn gmr_err(e: gmr::GmrError) -> PyErr {
    py_err(&e)
}

fn labelled_err(e: LabelledError) -> PyErr {
    py_err(&e)
}

fn gesture_err(e: cosco_hsom::hsom::GestureError) -> PyErr {
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
    steps::demonstrations_from_rows(series, columns).map_err(step_err)
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
        let mut demos = steps::demonstrations_from_rows(series, names).map_err(step_err)?;
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

/// A validated CoSCo-HSOM configuration (the XML schema of docs/CONFIG.md).
#[pyclass(module = "cosco_hsom", name = "Config", frozen)]
#[derive(Clone)]
struct Config {
    inner: HsomConfig,
}

#[pymethods]
impl Config {
    /// Read and validate an XML configuration file.
    #[staticmethod]
    fn from_xml(path: PathBuf) -> PyResult<Self> {
        Ok(Config {
            inner: steps::config(Some(&path)).map_err(step_err)?,
        })
    }

    /// Parse and validate an XML configuration given as text (`name` is used in messages).
    #[staticmethod]
    #[pyo3(signature = (text, name = "<string>"))]
    fn from_xml_string(text: &str, name: &str) -> PyResult<Self> {
        Ok(Config {
            inner: cosco_hsom::config::parse_config(text, name).map_err(|e| py_err(&e))?,
        })
    }

    /// The paper's Table I (height 6, memory 4, updatePeriod 2, 5000 steps, 6 variables).
    #[staticmethod]
    fn table1() -> PyResult<Self> {
        Ok(Config {
            inner: HsomParams::table1()
                .check("Table I")
                .map_err(|e| py_err(&e))?,
        })
    }

    /// The recommended configuration for the simulated Nao arm (configs/nao-gestures.xml).
    #[staticmethod]
    fn nao_gestures() -> PyResult<Self> {
        Ok(Config {
            inner: steps::config(None).map_err(step_err)?,
        })
    }

    /// A copy with some settings changed, validated again.
    #[pyo3(signature = (*, seed = None, state_length = None, training_steps = None))]
    fn replace(
        &self,
        seed: Option<u64>,
        state_length: Option<usize>,
        training_steps: Option<usize>,
    ) -> PyResult<Self> {
        let mut p = self.inner.params().clone();
        if let Some(s) = seed {
            p.seed = s;
        }
        if let Some(n) = state_length {
            p.state_length = n;
            p.action_length = n;
        }
        if let Some(t) = training_steps {
            p.training_steps = t;
        }
        Ok(Config {
            inner: p.check(self.inner.source()).map_err(|e| py_err(&e))?,
        })
    }

    /// The configuration as XML (every setting its algorithm reads written out).
    fn to_xml(&self) -> String {
        self.inner.to_xml()
    }

    /// Seed of every random draw.
    #[getter]
    fn seed(&self) -> u64 {
        self.inner.params().seed
    }

    /// Number of variables of a demonstration (stateLength).
    #[getter]
    fn state_length(&self) -> usize {
        self.inner.params().state_length
    }

    /// Number of training steps.
    #[getter]
    fn training_steps(&self) -> usize {
        self.inner.params().training_steps
    }

    /// Number of levels.
    #[getter]
    fn height(&self) -> usize {
        self.inner.params().height
    }

    /// Where the configuration came from (a file name).
    #[getter]
    fn source(&self) -> String {
        self.inner.source().to_string()
    }

    fn __repr__(&self) -> String {
        let p = self.inner.params();
        format!(
            "Config(source={:?}, seed={}, state_length={}, height={}, training_steps={})",
            self.inner.source(),
            p.seed,
            p.state_length,
            p.height,
            p.training_steps
        )
    }
}

/// A trained CoSCo-HSOM hierarchy.
#[pyclass(module = "cosco_hsom", name = "Hsom", frozen)]
struct Hsom {
    inner: cosco_hsom::hsom::Hsom,
    /// The model in messages: its file, or `in memory`.
    name: String,
}

impl Hsom {
    /// `f` on the model with the GIL released; the postures it gives, as a 2-D array.
    fn postures<'py, E: Error + Send + 'static>(
        &self,
        py: Python<'py>,
        f: impl FnOnce(&cosco_hsom::hsom::Hsom) -> Result<cosco_hsom::hsom::Reproduction, E> + Send,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rep = py
            .allow_threads(|| f(&self.inner))
            .map_err(|e| py_err(&e))?;
        Ok(array2(py, &rep.postures, self.inner.columns().len()))
    }
}

#[pymethods]
impl Hsom {
    /// Train on demonstrations (a list of 2-D arrays, samples x variables), with optional
    /// column names (default x0, x1, ...). The GIL is released while training.
    #[staticmethod]
    #[pyo3(signature = (config, demos, columns = None))]
    fn fit(
        py: Python<'_>,
        config: &Config,
        demos: &Bound<'_, PyAny>,
        columns: Option<Vec<String>>,
    ) -> PyResult<Self> {
        let demos = demonstrations_of(demos, columns)?;
        let cfg = config.inner.clone();
        let model = py
            .allow_threads(move || steps::train(&cfg, &demos, None))
            .map_err(step_err)?;
        Ok(Hsom {
            inner: model,
            name: "in memory".into(),
        })
    }

    /// Load a model saved by `Hsom.save` or `cosco train` (.bin or .txt). A model of several
    /// gestures is refused, naming `GestureModel.load`.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let inner =
            steps::load_model(&path).map_err(|e| match labelled::load_gesture_model(&path) {
                Ok(m) if !m.labels().is_empty() => PyValueError::new_err(format!(
                    "{}: a model of several gestures ({}): load it with GestureModel.load",
                    path.display(),
                    m.labels().join(", ")
                )),
                _ => step_err(e),
            })?;
        Ok(Hsom {
            inner,
            name: path.display().to_string(),
        })
    }

    /// Save the model (.bin binary, .txt plain text; written atomically).
    fn save(&self, path: PathBuf) -> PyResult<()> {
        steps::save_model(&self.inner, &path).map_err(step_err)
    }

    /// Reproduce the gesture from an initial posture: a 2-D array, one row per step (the first
    /// row is the initial posture).
    fn reproduce<'py>(
        &self,
        py: Python<'py>,
        initial: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let initial = posture_of(initial, "initial")?;
        self.postures(py, |m| steps::reproduce(m, &self.name, &initial))
    }

    /// The nearest-sequence baseline (docs/ALGORITHM.md, section 3.6): of
    /// `demos` (a list of 2-D arrays as for `fit`, normally the training demonstrations), the
    /// one whose first posture is nearest `initial`, its bottom events executed through this
    /// model's bottom code from `initial`, with no level above. A 2-D array as `reproduce`
    /// gives (the first row is the initial posture).
    fn follow_nearest<'py>(
        &self,
        py: Python<'py>,
        demos: &Bound<'py, PyAny>,
        initial: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let initial = posture_of(initial, "initial")?;
        let demos = demonstrations_of(demos, None)?;
        self.postures(py, |m| m.follow_nearest(&demos, &initial))
    }

    /// Continue a gesture from its first samples (2-D, at least actionHorizon + 1 rows):
    /// the prefix's events are pushed up the hierarchy's lists and the levels plan the rest
    /// (`algorithm = events`). The postures of the continuation, from the prefix's last.
    fn continue_events<'py>(
        &self,
        py: Python<'py>,
        prefix: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows = rows_of(prefix, "prefix")?;
        self.postures(py, |m| m.continue_events(&rows))
    }

    /// Resume this model's own reproduction from `initial` after part of it was executed:
    /// `reading` (2-D, at least actionHorizon + 1 rows, from `initial`) is what the encoders
    /// read meanwhile, possibly disturbed. The reading is aligned with the plan, the plan's
    /// events are executed for the durations read (pushed up the lists; the levels re-plan
    /// where one surprises them), the event in progress goes on (`algorithm = events`). The
    /// postures of the continuation, from the reading's last.
    fn resume<'py>(
        &self,
        py: Python<'py>,
        initial: &Bound<'py, PyAny>,
        reading: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let initial = posture_of(initial, "initial")?;
        let rows = rows_of(reading, "reading")?;
        self.postures(py, |m| steps::resume(m, &self.name, &initial, &rows))
    }

    /// The nearest-sequence continuation of a prefix: of `demos`, the one along which the
    /// prefix runs closest, continued after the prefix's end through this model's bottom code.
    /// The postures of the continuation, from the prefix's last.
    fn follow_nearest_from<'py>(
        &self,
        py: Python<'py>,
        demos: &Bound<'py, PyAny>,
        prefix: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows = rows_of(prefix, "prefix")?;
        let demos = demonstrations_of(demos, None)?;
        self.postures(py, |m| m.follow_nearest_from(&demos, &rows))
    }

    /// The names of the variables the model learned.
    #[getter]
    fn columns(&self) -> Vec<String> {
        self.inner.columns().to_vec()
    }

    /// The configuration the model was trained with.
    #[getter]
    fn config(&self) -> Config {
        Config {
            inner: self.inner.config().clone(),
        }
    }

    /// The model's levels, sizes and quality measures (what `cosco inspect` prints).
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.inner.summary();
        let d = PyDict::new(py);
        d.set_item("memory_mode", format!("{:?}", s.memory_mode))?;
        d.set_item("memory", s.memory)?;
        d.set_item("update_period", s.update_period)?;
        d.set_item("state_length", s.state_length)?;
        d.set_item("weights", s.weights)?;
        d.set_item("demo_lengths", s.demo_lengths.to_vec())?;
        d.set_item("demo_events", s.demo_events.to_vec())?;
        let levels = PyList::empty(py);
        for l in &s.levels {
            let ld = PyDict::new(py);
            ld.set_item("level", l.level)?;
            ld.set_item("rows", l.rows)?;
            ld.set_item("cols", l.cols)?;
            ld.set_item("topology", format!("{:?}", l.topology))?;
            ld.set_item("input_dim", l.input_dim)?;
            ld.set_item("period", l.period)?;
            ld.set_item("trained", l.trained)?;
            ld.set_item("nodes_used", l.nodes_used)?;
            ld.set_item("quantization_error", l.quantization_error)?;
            ld.set_item("topographic_error", l.topographic_error)?;
            ld.set_item("prediction_accuracy", l.prediction_accuracy)?;
            ld.set_item("lookup_accuracy", l.lookup_accuracy)?;
            ld.set_item("heldout_prediction_accuracy", l.heldout_prediction_accuracy)?;
            ld.set_item("heldout_lookup_accuracy", l.heldout_lookup_accuracy)?;
            ld.set_item("used_in_reproduction", l.used_in_reproduction)?;
            levels.append(ld)?;
        }
        d.set_item("levels", levels)?;
        Ok(d)
    }

    fn __str__(&self) -> String {
        self.inner.summary().to_string()
    }

    fn __repr__(&self) -> String {
        format!(
            "Hsom(model={:?}, columns={:?}, height={})",
            self.name,
            self.inner.columns(),
            self.inner.height()
        )
    }
}

/// Several gestures in one hierarchy (a shared bottom level, a branch of upper levels per
/// label): reproduction on cue, recognition with `unknown`, continuation of a prefix.
#[pyclass(module = "cosco_hsom", name = "GestureModel", frozen)]
struct GestureModel {
    inner: cosco_hsom::hsom::GestureModel,
    /// The model in messages: its file, or `in memory`.
    name: String,
}

#[pymethods]
impl GestureModel {
    /// Train one hierarchy on labelled demonstrations: `gestures` maps each label (a plain
    /// word) to its demonstrations (2-D arrays, samples x variables), in the mapping's order;
    /// optional column names (default x0, x1, ...). The configuration must use the events
    /// algorithm. The GIL is released while training.
    #[staticmethod]
    #[pyo3(signature = (config, gestures, columns = None))]
    fn fit(
        py: Python<'_>,
        config: &Config,
        gestures: &Bound<'_, PyAny>,
        columns: Option<Vec<String>>,
    ) -> PyResult<Self> {
        let sets = labelled_sets(gestures, columns)?;
        let cfg = config.inner.clone();
        let model = py
            .allow_threads(move || labelled::train_gestures(&cfg, &sets, None))
            .map_err(labelled_err)?;
        Ok(GestureModel {
            inner: model,
            name: "in memory".into(),
        })
    }

    /// Load a model saved by `GestureModel.save` or `cosco train` (with labels;
    /// a single-gesture file loads too, without labels).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        Ok(GestureModel {
            inner: labelled::load_gesture_model(&path).map_err(labelled_err)?,
            name: path.display().to_string(),
        })
    }

    /// Save the model (.bin binary, .txt plain text; written atomically): the bytes
    /// `cosco train` writes for the same demonstrations and configuration.
    fn save(&self, path: PathBuf) -> PyResult<()> {
        labelled::save_gesture_model(&self.inner, &path).map_err(labelled_err)
    }

    /// Reproduce gesture `label` from an initial posture: a 2-D array, one row per step (the
    /// first row is the initial posture). `label` is None only for a single-gesture model.
    #[pyo3(signature = (label, initial))]
    fn reproduce<'py>(
        &self,
        py: Python<'py>,
        label: Option<&str>,
        initial: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        // the label is checked before the posture, as `cosco reproduce --gesture` does
        self.inner.branch(label).map_err(gesture_err)?;
        let initial = posture_of(initial, "initial")?;
        let rep = py
            .allow_threads(|| labelled::reproduce_gesture(&self.inner, &self.name, label, &initial))
            .map_err(labelled_err)?;
        Ok(array2(py, &rep.postures, self.inner.columns().len()))
    }

    /// Per label (in the model's order), the score of a whole sequence (2-D, samples x
    /// variables, in the data's units): lower is closer; the recognised label is the lowest
    /// when it is at most that label's threshold (`Recognition.thresholds`).
    fn scores<'py>(
        &self,
        py: Python<'py>,
        sequence: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let rows = rows_of(sequence, "sequence")?;
        let scores = py
            .allow_threads(|| self.inner.scores(&rows))
            .map_err(gesture_err)?;
        label_dict(py, self.inner.labels().iter().zip(scores))
    }

    /// Recognise a whole sequence (2-D, samples x variables): the label or unknown (None),
    /// every label's score and threshold, and the sample from which the decision held.
    fn recognize(&self, py: Python<'_>, sequence: &Bound<'_, PyAny>) -> PyResult<Recognition> {
        let rows = rows_of(sequence, "sequence")?;
        let r = py
            .allow_threads(|| self.inner.recognize(&rows))
            .map_err(gesture_err)?;
        Ok(Recognition { inner: r })
    }

    /// Continue a gesture from its first samples (2-D, at least 2 rows): the hierarchy
    /// decides which gesture it is and continues it. Returns the label and the postures (the
    /// prefix first).
    fn continue_prefix<'py>(
        &self,
        py: Python<'py>,
        prefix: &Bound<'py, PyAny>,
    ) -> PyResult<(String, Bound<'py, PyArray2<f64>>)> {
        let rows = rows_of(prefix, "prefix")?;
        let (label, rep) = py
            .allow_threads(|| self.inner.continue_prefix(&rows))
            .map_err(gesture_err)?;
        Ok((label, array2(py, &rep.postures, self.inner.columns().len())))
    }

    /// The gesture labels, in the model's order (empty for a single-gesture model).
    #[getter]
    fn labels(&self) -> Vec<String> {
        self.inner.labels().to_vec()
    }

    /// The names of the variables the model learned.
    #[getter]
    fn columns(&self) -> Vec<String> {
        self.inner.columns().to_vec()
    }

    /// The configuration the model was trained with; with several labels, trainingSteps is
    /// the configured value times the number of labels (the shared bottom level sees every
    /// gesture as often as a gesture learned alone).
    #[getter]
    fn config(&self) -> Config {
        Config {
            inner: self.inner.branches()[0].config().clone(),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "GestureModel(model={:?}, labels={:?}, columns={:?})",
            self.name,
            self.inner.labels(),
            self.inner.columns()
        )
    }
}

/// What `GestureModel.recognize` answers for one sequence.
#[pyclass(module = "cosco_hsom", name = "Recognition", frozen)]
struct Recognition {
    inner: cosco_hsom::hsom::Recognition,
}

#[pymethods]
impl Recognition {
    /// The recognised label, or None when no taught gesture matches well enough (unknown).
    #[getter]
    fn label(&self) -> Option<String> {
        self.inner.label.clone()
    }

    /// True when no taught gesture matches well enough.
    #[getter]
    fn unknown(&self) -> bool {
        self.inner.label.is_none()
    }

    /// The label with the lowest score, whether or not it is below its threshold.
    #[getter]
    fn best(&self) -> String {
        self.inner.best.clone()
    }

    /// Per label (in the model's order), its score: lower is closer.
    #[getter]
    fn scores<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        label_dict(py, self.inner.scores.iter().map(|(l, s)| (l, *s)))
    }

    /// Per label, the score above which it is not recognised (calibrated on its training
    /// data).
    #[getter]
    fn thresholds<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let labels = self.inner.scores.iter().map(|(l, _)| l);
        label_dict(py, labels.zip(self.inner.thresholds.iter().copied()))
    }

    /// The earliest sample from which the best label stayed the same (early recognition).
    #[getter]
    fn decided_at(&self) -> usize {
        self.inner.decided_at
    }

    /// Samples in the sequence.
    #[getter]
    fn samples(&self) -> usize {
        self.inner.samples
    }

    /// `decided_at / samples`: the fraction of the gesture seen before the decision was final.
    #[getter]
    fn decided_fraction(&self) -> f64 {
        self.inner.decided_fraction()
    }

    /// The answer as `cosco recognize --json` writes each file's `recognition`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.inner;
        let d = PyDict::new(py);
        d.set_item("label", r.label.clone())?;
        d.set_item("best", r.best.clone())?;
        let scores = PyList::empty(py);
        for (l, s) in &r.scores {
            scores.append(PyList::new(
                py,
                [
                    l.into_pyobject(py)?.into_any(),
                    s.into_pyobject(py)?.into_any(),
                ],
            )?)?;
        }
        d.set_item("scores", scores)?;
        d.set_item("thresholds", r.thresholds.clone())?;
        d.set_item("decided_at", r.decided_at)?;
        d.set_item("samples", r.samples)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        let r = &self.inner;
        format!(
            "Recognition(label={}, best={:?}, decided_at={} of {}, scores={{{}}})",
            r.label.as_ref().map_or("None".into(), |l| format!("{l:?}")),
            r.best,
            r.decided_at,
            r.samples,
            r.scores
                .iter()
                .map(|(l, s)| format!("{l:?}: {s:.4}"))
                .collect::<Vec<_>>()
                .join(", ")
        )
    }
}

/// The paper's baseline: a Gaussian mixture over (time, variables), regressed on time.
#[pyclass(module = "cosco_hsom.gmr", name = "GmrModel", frozen)]
struct GmrModel {
    inner: gmr::GmrModel,
    sample_period: f64,
}

#[pymethods]
impl GmrModel {
    /// Fit the baseline (idle trimming, DTW alignment, resampling, EM; components fixed or
    /// chosen by BIC over 1..=8 when `components` is None).
    #[staticmethod]
    #[pyo3(signature = (demos, columns = None, components = None, seed = 0, sample_period = 0.025))]
    fn fit(
        py: Python<'_>,
        demos: &Bound<'_, PyAny>,
        columns: Option<Vec<String>>,
        components: Option<usize>,
        seed: u64,
        sample_period: f64,
    ) -> PyResult<Self> {
        let demos = demonstrations_of(demos, columns)?;
        let mut params = GmrParams::new().seed(seed).sample_period(sample_period);
        if let Some(k) = components {
            params = params.components(ComponentChoice::Fixed(k));
        }
        let params = params.check().map_err(gmr_err)?;
        let model = py
            .allow_threads(move || {
                cosco_hsom::demos::validate_set(&demos, None)?;
                Ok::<_, steps::StepError>(params.fit(&demos))
            })
            .map_err(step_err)?
            .map_err(gmr_err)?;
        Ok(GmrModel {
            inner: model,
            sample_period,
        })
    }

    /// Load a model saved by `save` (or `cosco compare`).
    #[staticmethod]
    #[pyo3(signature = (path, sample_period = 0.025))]
    fn load(path: PathBuf, sample_period: f64) -> PyResult<Self> {
        Ok(GmrModel {
            inner: gmr::load_model(&path).map_err(gmr_err)?,
            sample_period,
        })
    }

    /// Save the model (JSON, written atomically).
    fn save(&self, path: PathBuf) -> PyResult<()> {
        gmr::save_model(&path, &self.inner).map_err(gmr_err)
    }

    /// The regressed gesture: the conditional mean at every sample period over the learned
    /// duration, one row per step.
    #[pyo3(signature = (period = None))]
    fn reproduce<'py>(
        &self,
        py: Python<'py>,
        period: Option<f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let preds = self
            .inner
            .reproduce(period.unwrap_or(self.sample_period))
            .map_err(gmr_err)?;
        let rows: Vec<Vec<f64>> = preds.into_iter().map(|p| p.mean).collect();
        Ok(array2(py, &rows, self.inner.columns().len()))
    }

    /// Learned duration of the gesture, seconds.
    #[getter]
    fn duration(&self) -> f64 {
        self.inner.duration()
    }

    /// Number of mixture components.
    #[getter]
    fn n_components(&self) -> usize {
        self.inner.gmm().n_components()
    }

    /// The names of the variables.
    #[getter]
    fn columns(&self) -> Vec<String> {
        self.inner.columns().to_vec()
    }
}

/// Dynamic time warping between two sequences (2-D: samples x variables, same width), with
/// Euclidean local cost and no band: the summed cost of the cheapest warping path, or the
/// mean cost per path step with `per_step=True`.
/// Leave-one-out on demonstrations (`cosco heldout`): for each demonstration of a gesture,
/// learn from the others, reproduce from its first sample, score against it alone; the
/// hierarchy beside the nearest sequence, height 1, GMM/GMR, ProMP and a replay on the same
/// folds.
/// `gestures`: a list of 2-D arrays (one gesture) or a mapping label -> list. Returns the
/// JSON document of `cosco heldout --json` as a dict. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (config, gestures, *, columns = None, sample_period = 0.025, height_1 = true, gmr = true, promp = true, in_sample = true, threads = 1))]
#[allow(clippy::too_many_arguments)]
fn heldout<'py>(
    py: Python<'py>,
    config: &Config,
    gestures: &Bound<'py, PyAny>,
    columns: Option<Vec<String>>,
    sample_period: f64,
    height_1: bool,
    gmr: bool,
    promp: bool,
    in_sample: bool,
    threads: usize,
) -> PyResult<Bound<'py, PyAny>> {
    use cosco_hsom::eval;
    if !(sample_period.is_finite() && sample_period > 0.0) {
        return Err(PyValueError::new_err(format!(
            "sample_period = {sample_period}: a finite number of seconds > 0"
        )));
    }
    let mut sets = if gestures.hasattr("items")? {
        labelled_sets(gestures, columns)?
    } else {
        vec![("gesture".to_string(), demonstrations_of(gestures, columns)?)]
    };
    for d in sets.iter_mut().flat_map(|(_, d)| d.iter_mut()) {
        d.time = Some(
            (0..d.rows.len())
                .map(|k| k as f64 * sample_period)
                .collect(),
        );
    }
    let settings = eval::LooSettings {
        height_1,
        gmr,
        promp,
        replay: true,
        in_sample,
        threads,
    };
    let cfg = config.inner.clone();
    let text = py
        .allow_threads(|| {
            eval::leave_one_out(&cfg, sets, &settings, &eval::Kinematic, None).map(|s| eval::json(&cfg, &s))
        })
        .map_err(|e| py_err(&e))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// Read demonstration CSV files (a directory of *.csv files, or files), checked as one set
/// as `cosco train` reads them: `(demos, columns)`, the demonstrations as 2-D arrays
/// (samples x variables, the `time` column left out). With `resample` (Hz), every file, each
/// with a `time` column, is first resampled to that rate (shape-preserving cubic), as
/// `cosco ... --resample HZ` does; pass `sample_period=1/resample` to `heldout`.
#[pyfunction]
#[pyo3(signature = (paths, *, resample = None))]
#[allow(clippy::type_complexity)]
fn read_demos(
    py: Python<'_>,
    paths: Vec<PathBuf>,
    resample: Option<f64>,
) -> PyResult<(Vec<Bound<'_, PyArray2<f64>>>, Vec<String>)> {
    let demos = steps::read_demos_at(&paths, None, resample).map_err(step_err)?;
    let columns = demos[0].columns.clone();
    Ok((
        demos
            .iter()
            .map(|d| array2(py, &d.rows, d.width()))
            .collect(),
        columns,
    ))
}

#[pyfunction]
#[pyo3(signature = (a, b, per_step = false))]
fn dtw(a: &Bound<'_, PyAny>, b: &Bound<'_, PyAny>, per_step: bool) -> PyResult<f64> {
    let a = rows_of(a, "a")?;
    let b = rows_of(b, "b")?;
    let cost = dtw_distance(&a, &b, Band::None).map_err(|e| py_err(&e))?;
    Ok(if per_step {
        cost.per_step()
    } else {
        cost.distance
    })
}

/// The native part of the `cosco_hsom` package.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Config>()?;
    m.add_class::<Hsom>()?;
    m.add_class::<GestureModel>()?;
    m.add_class::<Recognition>()?;
    m.add_class::<GmrModel>()?;
    m.add_function(wrap_pyfunction!(dtw, m)?)?;
    m.add_function(wrap_pyfunction!(heldout, m)?)?;
    m.add_function(wrap_pyfunction!(read_demos, m)?)?;
    Ok(())
}
