//! `Config` and `Hsom`: a configuration and a hierarchy of one gesture.

use std::error::Error;
use std::path::PathBuf;

use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use cosco_hsom::aim::Aim;
use cosco_hsom::app;
use cosco_hsom::config::{HsomConfig, HsomParams};

use crate::{app_err, array2, demonstrations_of, posture_of, py_err, rows_of};

/// A validated CoSCo-HSOM configuration (the XML schema of docs/CONFIG.md).
#[pyclass(module = "cosco_hsom", name = "Config", frozen)]
#[derive(Clone)]
pub(crate) struct Config {
    pub(crate) inner: HsomConfig,
}

#[pymethods]
impl Config {
    /// Read and validate an XML configuration file.
    #[staticmethod]
    fn from_xml(path: PathBuf) -> PyResult<Self> {
        Ok(Config {
            inner: app::config(Some(&path)).map_err(app_err)?,
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
            inner: app::config(None).map_err(app_err)?,
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

/// A trained CoSCo-HSOM hierarchy: a model of one gesture (a `GestureModel` without labels).
#[pyclass(module = "cosco_hsom", name = "Hsom", frozen)]
pub(crate) struct Hsom {
    /// One unlabelled branch.
    inner: cosco_hsom::hsom::GestureModel,
    /// The model in messages: its file, or `in memory`.
    name: String,
}

impl Hsom {
    /// The model's hierarchy.
    fn branch(&self) -> &cosco_hsom::hsom::Hsom {
        &self.inner.branches()[0]
    }

    /// `f` on the hierarchy with the GIL released; the postures it gives, as a 2-D array.
    fn postures<'py, E: Error + Send + 'static>(
        &self,
        py: Python<'py>,
        f: impl FnOnce(&cosco_hsom::hsom::Hsom) -> Result<cosco_hsom::hsom::Reproduction, E> + Send,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rep = py
            .allow_threads(|| f(self.branch()))
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
            .allow_threads(move || app::train(&cfg, &demos, None))
            .map_err(app_err)?;
        Ok(Hsom {
            inner: model,
            name: "in memory".into(),
        })
    }

    /// Load a model saved by `Hsom.save` or `cosco train` (.bin or .txt). A model of several
    /// gestures is refused, naming `GestureModel.load`.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        let inner = app::load_gesture_model(&path).map_err(app_err)?;
        if !inner.labels().is_empty() {
            return Err(PyValueError::new_err(format!(
                "{}: a model of several gestures ({}): load it with GestureModel.load",
                path.display(),
                inner.labels().join(", ")
            )));
        }
        Ok(Hsom {
            inner,
            name: path.display().to_string(),
        })
    }

    /// Save the model (.bin binary, .txt plain text; written atomically).
    fn save(&self, path: PathBuf) -> PyResult<()> {
        app::save_gesture_model(&self.inner, &path).map_err(app_err)
    }

    /// The model taught `demos` more (2-D arrays of the model's columns), from the model and
    /// them alone: a new model; this one is unchanged. `label` must be None (a model of one
    /// gesture). The GIL is released while it learns.
    #[pyo3(signature = (demos, label = None))]
    fn update(
        &self,
        py: Python<'_>,
        demos: &Bound<'_, PyAny>,
        label: Option<String>,
    ) -> PyResult<Self> {
        let demos = demonstrations_of(demos, Some(self.inner.columns().to_vec()))?;
        let updated = py
            .allow_threads(|| app::update(&self.inner, label.as_deref(), &demos, None))
            .map_err(app_err)?;
        Ok(Hsom {
            inner: updated,
            name: "in memory".into(),
        })
    }

    /// What the model learned from: `{"demonstrations": n, "kept": k, "updates": u}` (the
    /// demonstrations over its first training and every update, how many of them it keeps,
    /// its updates).
    #[getter]
    fn learned<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        learned_dict(py, self.branch())
    }

    /// Reproduce the gesture from an initial posture: a 2-D array, one row per step (the first
    /// row is the initial posture). `goal` (a posture) makes it end exactly there; `via`, a
    /// list of `(phase, posture)` (phase 0 the start, 1 the end), makes it pass each posture
    /// at its phase (read between two rows). With `band=True`, a tuple: the postures and the
    /// lower and upper ends of their central 95 % band (2-D arrays of the same shape).
    /// `duration` (seconds) retimes it to last that long at 40 Hz, its path kept (as `cosco
    /// reproduce --duration`; a duration the servos cannot follow is refused, naming the
    /// shortest). `point_at` and `look_at`, `(x, y, z)` in metres in the torso frame, aim the
    /// held part (as `cosco reproduce --point-at/--look-at`; a model of a Nao's joints).
    #[pyo3(signature = (initial, *, goal = None, via = None, band = false, duration = None, point_at = None, look_at = None))]
    #[allow(clippy::too_many_arguments)]
    fn reproduce<'py>(
        &self,
        py: Python<'py>,
        initial: &Bound<'py, PyAny>,
        goal: Option<&Bound<'py, PyAny>>,
        via: Option<Vec<(f64, Bound<'py, PyAny>)>>,
        band: bool,
        duration: Option<f64>,
        point_at: Option<[f64; 3]>,
        look_at: Option<[f64; 3]>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let how = How {
            conditioning: Some((goal, via)),
            band,
            duration,
            aim: Aim { point_at, look_at },
        };
        reproduce(py, &self.inner, &self.name, None, initial, how)
    }

    /// The hierarchy in the loop from an initial posture, through `goal` and `via` as
    /// `reproduce` takes them: a `Stepper`, whose `step(observed)` gives the next posture to
    /// command from the posture the encoders read at this tick (docs/ALGORITHM.md, section 11).
    /// `point_at` and `look_at` aim its held part as `reproduce` does; the stepper's
    /// `point_at` and `look_at` move the target while it runs.
    #[pyo3(signature = (initial, goal = None, via = None, *, point_at = None, look_at = None))]
    fn stepper(
        &self,
        py: Python<'_>,
        initial: &Bound<'_, PyAny>,
        goal: Option<&Bound<'_, PyAny>>,
        via: Option<Vec<(f64, Bound<'_, PyAny>)>>,
        point_at: Option<[f64; 3]>,
        look_at: Option<[f64; 3]>,
    ) -> PyResult<crate::stepper::Stepper> {
        let aim = Aim { point_at, look_at };
        crate::stepper::Stepper::new(py, &self.inner, None, &self.name, initial, (goal, via), aim)
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
        self.postures(py, |m| app::resume(m, &self.name, &initial, &rows))
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
            inner: self.branch().config().clone(),
        }
    }

    /// The model's levels, sizes and quality measures (what `cosco inspect` prints).
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.branch().summary();
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
        self.branch().summary().to_string()
    }

    fn __repr__(&self) -> String {
        format!(
            "Hsom(model={:?}, columns={:?}, height={})",
            self.name,
            self.inner.columns(),
            self.branch().height()
        )
    }
}

/// `{"demonstrations": n, "kept": k, "updates": u}` of `model` ([`cosco_hsom::hsom::Hsom::learned`]).
pub(crate) fn learned_dict<'py>(
    py: Python<'py>,
    model: &cosco_hsom::hsom::Hsom,
) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
    let (n, kept, updates) = model.learned();
    let d = pyo3::types::PyDict::new(py);
    d.set_item("demonstrations", n)?;
    d.set_item("kept", kept)?;
    d.set_item("updates", updates)?;
    Ok(d)
}

/// The goal and via-points of `Hsom.reproduce` (a posture; a list of `(phase, posture)`).
pub(crate) type Conditioning<'a, 'py> = (
    Option<&'a Bound<'py, PyAny>>,
    Option<Vec<(f64, Bound<'py, PyAny>)>>,
);

/// How `reproduce` is asked to reproduce: through a goal and via-points, with the band, in a
/// given duration (seconds), aimed.
#[derive(Default)]
pub(crate) struct How<'a, 'py> {
    pub(crate) conditioning: Option<Conditioning<'a, 'py>>,
    pub(crate) band: bool,
    pub(crate) duration: Option<f64>,
    pub(crate) aim: Aim,
}

/// Gesture `label` of `model` (named `name` in messages; `None` for a model of one gesture)
/// reproduced from `initial`, as `Hsom.reproduce` and `GestureModel.reproduce` give it: the
/// label checked before the posture, as `cosco reproduce --gesture` does; through the goal and
/// via-points when `how` has them; retimed to its duration when it has one; with its `band`,
/// the postures and the lower and upper ends of their central 95 % band.
pub(crate) fn reproduce<'py>(
    py: Python<'py>,
    model: &cosco_hsom::hsom::GestureModel,
    name: &str,
    label: Option<&str>,
    initial: &Bound<'py, PyAny>,
    how: How<'_, 'py>,
) -> PyResult<Bound<'py, PyAny>> {
    let branch = model.branch(label).map_err(|e| py_err(&e))?;
    let initial = posture_of(initial, "initial")?;
    let conditions = (how.conditioning)
        .map(|(goal, via)| crate::stepper::conditions_of(goal, via))
        .transpose()?;
    let (band, duration, aim) = (how.band, how.duration, how.aim);
    let width = model.columns().len();
    let (rep, lohi) = py
        .allow_threads(|| {
            let conditions = match aim.is_empty() {
                true => conditions,
                false => {
                    let given = conditions.unwrap_or_default();
                    Some(app::aimed(model, name, label, &initial, &given, &aim)?.0)
                }
            };
            let rep = app::reproduce(model, name, label, &initial, conditions.as_ref())?;
            let rep = match duration {
                Some(d) => app::with_duration(&rep, model.columns(), d)?,
                None => rep,
            };
            let phases = conditions.as_ref().map(|c| c.phases()).unwrap_or_default();
            let lohi = match band {
                true => Some(branch.band(&rep.postures, &phases).ok_or_else(|| {
                    app::Error::value(
                        "band=True",
                        "the model keeps fewer than 2 training demonstrations to measure a band from",
                    )
                })?),
                false => None,
            };
            Ok::<_, app::Error>((rep, lohi))
        })
        .map_err(|e| py_err(&e))?;
    let postures = array2(py, &rep.postures, width);
    Ok(match lohi {
        Some(b) => (postures, array2(py, &b.lo, width), array2(py, &b.hi, width))
            .into_pyobject(py)?
            .into_any(),
        None => postures.into_any(),
    })
}
