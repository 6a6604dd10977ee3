//! `GestureModel` and `Recognition`: several gestures in one hierarchy, and its answers.

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use cosco_hsom::app;
use cosco_hsom::hsom::StreamCalibration;

use crate::model::Config;
use crate::{app_err, array2, label_dict, labelled_sets, posture_of, py_err, rows_of};

/// Several gestures in one model (a branch per label, each the gesture learned alone, in the
/// units of all of them): reproduction on cue, recognition with `unknown`, continuation of a prefix.
#[pyclass(module = "cosco_hsom", name = "GestureModel", frozen)]
pub(crate) struct GestureModel {
    inner: Arc<cosco_hsom::hsom::GestureModel>,
    /// The model in messages: its file, or `in memory`.
    name: String,
    /// What its recognisers in the loop are calibrated with, measured once.
    stream: OnceLock<StreamCalibration>,
}

impl GestureModel {
    fn new(inner: cosco_hsom::hsom::GestureModel, name: impl Into<String>) -> Self {
        GestureModel {
            inner: Arc::new(inner),
            name: name.into(),
            stream: OnceLock::new(),
        }
    }
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
            .allow_threads(move || app::train(&cfg, &sets, None))
            .map_err(app_err)?;
        Ok(GestureModel::new(model, "in memory"))
    }

    /// Load a model saved by `GestureModel.save` or `cosco train` (with labels;
    /// a single-gesture file loads too, without labels).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        Ok(GestureModel::new(
            app::load_gesture_model(&path).map_err(app_err)?,
            path.display().to_string(),
        ))
    }

    /// The model taught `demos` (2-D arrays of the model's columns) as gesture `label`, from
    /// the model and them alone: a new model; this one is unchanged. A label the model does
    /// not hold adds the gesture; `label` None only for a model of one unlabelled gesture.
    /// The GIL is released while it learns.
    #[pyo3(signature = (demos, label = None))]
    fn update(
        &self,
        py: Python<'_>,
        demos: &Bound<'_, PyAny>,
        label: Option<String>,
    ) -> PyResult<Self> {
        let demos = crate::demonstrations_of(demos, Some(self.inner.columns().to_vec()))?;
        let updated = py
            .allow_threads(|| app::update(&self.inner, label.as_deref(), &demos, None))
            .map_err(app_err)?;
        Ok(GestureModel::new(updated, "in memory"))
    }

    /// What each gesture was learned from: `{label: {"demonstrations": n, "kept": k,
    /// "updates": u}}` (`{"": ...}` for a model of one unlabelled gesture).
    #[getter]
    fn learned<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let unlabelled = [String::new()];
        let labels = match self.inner.labels().is_empty() {
            true => &unlabelled[..],
            false => self.inner.labels(),
        };
        for (l, b) in labels.iter().zip(self.inner.branches()) {
            d.set_item(l, crate::model::learned_dict(py, b)?)?;
        }
        Ok(d)
    }

    /// Save the model (.bin binary, .txt plain text; written atomically): the bytes
    /// `cosco train` writes for the same demonstrations and configuration.
    fn save(&self, path: PathBuf) -> PyResult<()> {
        app::save_gesture_model(&self.inner, &path).map_err(app_err)
    }

    /// Reproduce gesture `label` from an initial posture: a 2-D array, one row per step (the
    /// first row is the initial posture). `label` is None only for a single-gesture model.
    /// `duration` (seconds) retimes it to last that long, its path kept; `point_at` and
    /// `look_at`, `(x, y, z)` in metres in the torso frame, aim its held part (as
    /// `Hsom.reproduce`).
    #[pyo3(signature = (label, initial, *, duration = None, point_at = None, look_at = None))]
    fn reproduce<'py>(
        &self,
        py: Python<'py>,
        label: Option<&str>,
        initial: &Bound<'py, PyAny>,
        duration: Option<f64>,
        point_at: Option<[f64; 3]>,
        look_at: Option<[f64; 3]>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let how = crate::model::How {
            duration,
            aim: cosco_hsom::aim::Aim { point_at, look_at },
            ..Default::default()
        };
        crate::model::reproduce(py, &self.inner, &self.name, label, initial, how)
    }

    /// Gesture `label` in the loop from an initial posture, through `goal` and `via` as
    /// `Hsom.reproduce` takes them: a `Stepper`, whose `step(observed)` gives the next posture
    /// to command from the posture the encoders read at this tick. `label` is None only for a
    /// single-gesture model. `point_at` and `look_at` aim its held part (as `Hsom.stepper`).
    #[pyo3(signature = (label, initial, goal = None, via = None, *, point_at = None, look_at = None))]
    #[allow(clippy::too_many_arguments)]
    fn stepper(
        &self,
        py: Python<'_>,
        label: Option<&str>,
        initial: &Bound<'_, PyAny>,
        goal: Option<&Bound<'_, PyAny>>,
        via: Option<Vec<(f64, Bound<'_, PyAny>)>>,
        point_at: Option<[f64; 3]>,
        look_at: Option<[f64; 3]>,
    ) -> PyResult<crate::stepper::Stepper> {
        let aim = cosco_hsom::aim::Aim { point_at, look_at };
        crate::stepper::Stepper::new(
            py,
            &self.inner,
            label,
            &self.name,
            initial,
            (goal, via),
            aim,
        )
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
            .map_err(|e| py_err(&e))?;
        label_dict(py, self.inner.labels().iter().zip(scores))
    }

    /// Recognise a whole sequence (2-D, samples x variables): the label or unknown (None),
    /// every label's score and threshold, and the sample from which the decision held.
    fn recognize(&self, py: Python<'_>, sequence: &Bound<'_, PyAny>) -> PyResult<Recognition> {
        let rows = rows_of(sequence, "sequence")?;
        let r = py
            .allow_threads(|| self.inner.recognize(&rows))
            .map_err(|e| py_err(&e))?;
        Ok(Recognition { inner: r })
    }

    /// A recogniser in the loop: `push(sample)` one sample at a time returns the label it
    /// committed to (None before, and for a commitment to unknown), `decided` says whether it
    /// has committed, `finish()` is `recognize` on every sample pushed. A commitment never
    /// changes.
    fn recognizer(&self, py: Python<'_>) -> PyResult<Recognizer> {
        let calibration = match self.stream.get() {
            Some(c) => c.clone(),
            None => {
                let c = py
                    .allow_threads(|| self.inner.stream_calibration())
                    .map_err(|e| py_err(&e))?;
                self.stream.get_or_init(|| c).clone()
            }
        };
        let inner = cosco_hsom::hsom::Recognizer::new(Arc::clone(&self.inner), calibration)
            .map_err(|e| py_err(&e))?;
        Ok(Recognizer { inner })
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
            .map_err(|e| py_err(&e))?;
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

    /// The configuration the model was trained with (every label's branch is trained with
    /// it, as the gesture alone).
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

/// Recognition in the loop (`GestureModel.recognizer()`): samples pushed one at a time.
#[pyclass(module = "cosco_hsom", name = "Recognizer")]
pub(crate) struct Recognizer {
    inner: cosco_hsom::hsom::Recognizer<Arc<cosco_hsom::hsom::GestureModel>>,
}

#[pymethods]
impl Recognizer {
    /// Push the next sample (1-D, one value per variable, in the data's units): the label
    /// committed to, or None (before any commitment, and after one to unknown: see
    /// `decided`). A sample of the wrong width or with a value that is not finite is refused
    /// (ValueError) and leaves the recogniser as it was.
    fn push(&mut self, sample: &Bound<'_, PyAny>) -> PyResult<Option<String>> {
        let x = posture_of(sample, "sample")?;
        let c = self.inner.push(&x).map_err(|e| py_err(&e))?;
        Ok(c.and_then(|c| c.label))
    }

    /// True from the sample the recogniser committed on (a committed None is unknown).
    #[getter]
    fn decided(&self) -> bool {
        self.inner.decided()
    }

    /// The samples pushed when it committed (None before).
    #[getter]
    fn committed_at(&self) -> Option<usize> {
        self.inner.commit().map(|c| c.samples)
    }

    /// The samples pushed so far.
    #[getter]
    fn samples(&self) -> usize {
        self.inner.samples()
    }

    /// The whole sequence's answer: what `GestureModel.recognize` gives on every sample
    /// pushed (at least 2).
    fn finish(&self, py: Python<'_>) -> PyResult<Recognition> {
        let r = py
            .allow_threads(|| self.inner.finish())
            .map_err(|e| py_err(&e))?;
        Ok(Recognition { inner: r })
    }

    fn __repr__(&self) -> String {
        match self.inner.commit() {
            None => format!(
                "Recognizer(samples={}, decided=False)",
                self.inner.samples()
            ),
            Some(c) => format!(
                "Recognizer(samples={}, decided=True, label={}, committed_at={})",
                self.inner.samples(),
                c.label.as_ref().map_or("None".into(), |l| format!("{l:?}")),
                c.samples
            ),
        }
    }
}

/// What `GestureModel.recognize` answers for one sequence.
#[pyclass(module = "cosco_hsom", name = "Recognition", frozen)]
pub(crate) struct Recognition {
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

    /// Per label, the variables its score weighs most (heaviest first) with their weights
    /// (a label's weights average 1: what its gesture moves weighs more than what it holds).
    #[getter]
    fn weighed<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for ((l, _), w) in self.inner.scores.iter().zip(&self.inner.weighed) {
            d.set_item(l, w.clone())?;
        }
        Ok(d)
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
        d.set_item("scores", json_pairs(py, &r.scores)?)?;
        d.set_item("thresholds", r.thresholds.clone())?;
        let weighed = PyList::empty(py);
        for w in &r.weighed {
            weighed.append(json_pairs(py, w)?)?;
        }
        d.set_item("weighed", weighed)?;
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

/// `(name, value)` pairs as JSON writes them: a list of two-element lists.
fn json_pairs<'py>(py: Python<'py>, pairs: &[(String, f64)]) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for (l, v) in pairs {
        out.append(PyList::new(
            py,
            [
                l.into_pyobject(py)?.into_any(),
                v.into_pyobject(py)?.into_any(),
            ],
        )?)?;
    }
    Ok(out)
}
