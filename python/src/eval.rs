//! The baseline (`GmrModel`), the held-out study (`heldout`), demonstration files
//! (`read_demos`) and `dtw`.

use std::path::PathBuf;

use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use cosco_hsom::app;
use cosco_hsom::dtw::{dtw_distance, Band};
use cosco_hsom::gmr::{self, ComponentChoice, GmrParams};

use crate::model::Config;
use crate::{app_err, array2, demonstrations_of, labelled_sets, py_err, rows_of};

fn gmr_err(e: gmr::GmrError) -> PyErr {
    py_err(&e)
}

/// The paper's baseline: a Gaussian mixture over (time, variables), regressed on time.
#[pyclass(module = "cosco_hsom.gmr", name = "GmrModel", frozen)]
pub(crate) struct GmrModel {
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
                Ok::<_, cosco_hsom::demos::DemoError>(params.fit(&demos))
            })
            .map_err(|e| py_err(&e))?
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

/// Leave-one-out on demonstrations (`cosco heldout`): for each demonstration of a gesture,
/// learn from the others, reproduce from its first sample, score against it alone; the
/// hierarchy beside the nearest sequence, height 1, GMM/GMR, ProMP, the DMP and a replay on the same
/// folds.
/// `gestures`: a list of 2-D arrays (one gesture) or a mapping label -> list. Returns the
/// JSON document of `cosco heldout --json` as a dict (with `condition="end"` or `"end+mid"`,
/// the conditioned folds under `conditioned`; with `sittings=True`, the folds taught in two
/// sittings under `sittings`). The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (config, gestures, *, columns = None, sample_period = 0.025, height_1 = true, gmr = true, promp = true, dmp = true, dba = true, in_sample = true, condition = None, far = Vec::new(), sittings = false, threads = 1))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn heldout<'py>(
    py: Python<'py>,
    config: &Config,
    gestures: &Bound<'py, PyAny>,
    columns: Option<Vec<String>>,
    sample_period: f64,
    height_1: bool,
    gmr: bool,
    promp: bool,
    dmp: bool,
    dba: bool,
    in_sample: bool,
    condition: Option<String>,
    far: Vec<f64>,
    sittings: bool,
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
        dmp,
        dba,
        replay: true,
        in_sample,
        conditioning: match condition.as_deref() {
            None => eval::Conditioning::Unconditioned,
            Some("end") => eval::Conditioning::End,
            Some("end+mid") => eval::Conditioning::EndMid,
            Some(other) => {
                return Err(PyValueError::new_err(format!(
                    "condition = {other:?}: allowed None, \"end\" or \"end+mid\""
                )))
            }
        },
        far: None,
        sittings,
        threads,
        keep_learned: false,
    };
    let cfg = config.inner.clone();
    let text = py
        .allow_threads(|| {
            eval::study(&cfg, sets, &settings, &far, &eval::Kinematic, None).map(|s| s.json(&cfg))
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
pub(crate) fn read_demos(
    py: Python<'_>,
    paths: Vec<PathBuf>,
    resample: Option<f64>,
) -> PyResult<(Vec<Bound<'_, PyArray2<f64>>>, Vec<String>)> {
    let demos = app::read_demos(&paths, None, resample).map_err(app_err)?;
    let columns = demos[0].columns.clone();
    Ok((
        demos
            .iter()
            .map(|d| array2(py, &d.rows, d.width()))
            .collect(),
        columns,
    ))
}

/// Dynamic time warping between two sequences (2-D: samples x variables, same width), with
/// Euclidean local cost and no band: the summed cost of the cheapest warping path, or the
/// mean cost per path step with `per_step=True`.
#[pyfunction]
#[pyo3(signature = (a, b, per_step = false))]
pub(crate) fn dtw(a: &Bound<'_, PyAny>, b: &Bound<'_, PyAny>, per_step: bool) -> PyResult<f64> {
    let a = rows_of(a, "a")?;
    let b = rows_of(b, "b")?;
    let cost = dtw_distance(&a, &b, Band::None).map_err(|e| py_err(&e))?;
    Ok(if per_step {
        cost.per_step()
    } else {
        cost.distance
    })
}

/// The dynamic movement primitive baseline (discrete, Ijspeert et al. 2013), learned from
/// several demonstrations.
#[pyclass(module = "cosco_hsom", name = "Dmp", frozen)]
pub(crate) struct Dmp {
    inner: cosco_hsom::dmp::Dmp,
}

#[pymethods]
impl Dmp {
    /// Learn from demonstrations (a list of 2-D arrays, samples x variables, one sample
    /// period apart) with `basis` basis functions per variable.
    #[staticmethod]
    #[pyo3(signature = (demos, *, basis = 50))]
    fn fit(py: Python<'_>, demos: &Bound<'_, PyAny>, basis: usize) -> PyResult<Self> {
        let demos = demonstrations_of(demos, None)?;
        let settings = cosco_hsom::dmp::DmpSettings {
            basis,
            ..Default::default()
        };
        let inner = py
            .allow_threads(|| settings.check()?.fit(&demos))
            .map_err(|e| py_err(&e))?;
        Ok(Dmp { inner })
    }

    /// The movement from rest at `start` to `goal` (the demonstrations' mean end when None)
    /// over their mean number of samples: one row per sample.
    #[pyo3(signature = (start, goal = None))]
    fn reproduce<'py>(
        &self,
        py: Python<'py>,
        start: &Bound<'py, PyAny>,
        goal: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let start = crate::posture_of(start, "start")?;
        let goal = goal.map(|g| crate::posture_of(g, "goal")).transpose()?;
        let rows = self
            .inner
            .reproduce(&start, goal.as_deref())
            .map_err(|e| py_err(&e))?;
        Ok(array2(py, &rows, self.inner.width()))
    }

    /// Samples of a reproduction.
    #[getter]
    fn samples(&self) -> usize {
        self.inner.samples()
    }
}
