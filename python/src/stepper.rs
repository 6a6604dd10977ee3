//! `Stepper`: the hierarchy in the loop, made by `Hsom.stepper` and `GestureModel.stepper`.

use std::sync::Arc;

use numpy::PyArray1;
use pyo3::prelude::*;

use cosco_hsom::aim::{Aim, Aiming};
use cosco_hsom::app;
use cosco_hsom::condition::{Conditions, ViaPoint};
use cosco_hsom::hsom::{GestureModel, Hsom, HsomStepper};
use cosco_hsom::stepper::Stepper as _;

use crate::model::Conditioning;
use crate::{app_err, posture_of, py_err};

/// The hierarchy in the loop: `step(observed)` gives the next posture to command from the
/// posture the encoders read at this tick; `done` is True once the reproduction has ended; `goal =
/// posture` moves the goal from this tick on (docs/ALGORITHM.md, section 11).
#[pyclass(module = "cosco_hsom", name = "Stepper")]
pub(crate) struct Stepper {
    inner: HsomStepper<Arc<Hsom>>,
    goal: Option<Vec<f64>>,
    /// What the held part is aimed at, when it is.
    aiming: Option<Aiming>,
}

/// The conditions of `goal` and `via` (a list of `(phase, posture)`), as `Hsom.reproduce`
/// reads them.
pub(crate) fn conditions_of(
    goal: Option<&Bound<'_, PyAny>>,
    via: Option<Vec<(f64, Bound<'_, PyAny>)>>,
) -> PyResult<Conditions> {
    let mut conditions = Conditions {
        goal: goal.map(|g| posture_of(g, "goal")).transpose()?,
        via: Vec::new(),
    };
    for (k, (phase, posture)) in via.unwrap_or_default().iter().enumerate() {
        conditions.via.push(ViaPoint {
            phase: *phase,
            posture: posture_of(posture, &format!("via[{k}]"))?,
        });
    }
    Ok(conditions)
}

impl Stepper {
    /// The stepper of gesture `label` of `model` (named `name` in messages; `None` for a model
    /// of one gesture) from `initial` through `goal` and `via`, checked as `reproduce` checks
    /// them (the plan is made with the GIL released).
    pub(crate) fn new(
        py: Python<'_>,
        model: &GestureModel,
        label: Option<&str>,
        name: &str,
        initial: &Bound<'_, PyAny>,
        (goal, via): Conditioning<'_, '_>,
        aim: Aim,
    ) -> PyResult<Self> {
        let model = Arc::new(model.branch(label).map_err(|e| py_err(&e))?.clone());
        let initial = posture_of(initial, "initial")?;
        let conditions = conditions_of(goal, via)?;
        let (inner, aiming) = py
            .allow_threads(|| match aim.is_empty() {
                true => Ok((app::stepper(model, name, &initial, &conditions)?, None)),
                false => app::aimed_stepper(model, name, &initial, &conditions, &aim)
                    .map(|(s, a)| (s, Some(a))),
            })
            .map_err(app_err)?;
        Ok(Stepper {
            inner,
            goal: conditions.goal,
            aiming,
        })
    }

    /// Aim, from this tick on, at the current aim as `change` leaves it (a stepper made with
    /// an aim).
    fn retarget(&mut self, change: impl FnOnce(&mut Aim)) -> PyResult<()> {
        let Some(aiming) = &self.aiming else {
            return Err(pyo3::exceptions::PyValueError::new_err(
                "the stepper was made without point_at or look_at: its held part is chosen when it is made (give point_at or look_at to Hsom.stepper)",
            ));
        };
        let mut aim = aiming.aim();
        change(&mut aim);
        let next = aiming.retargeted(&aim).map_err(|e| py_err(&e))?;
        self.inner.set_via(next.via()).map_err(|e| py_err(&e))?;
        self.aiming = Some(next);
        Ok(())
    }
}

#[pymethods]
impl Stepper {
    /// The next posture to command (a 1-D array), given the posture the encoders read at this tick
    /// (one value per variable; the first call reads the initial posture). While the arm is
    /// where it was last sent the stepper follows its plan; when it is not, it re-plans from
    /// what the encoders have read.
    fn step<'py>(
        &mut self,
        py: Python<'py>,
        observed: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let observed = posture_of(observed, "observed")?;
        let next = self.inner.step(&observed).map_err(|e| py_err(&e))?;
        Ok(PyArray1::from_vec(py, next))
    }

    /// True once the reproduction has ended (its last posture has been commanded).
    #[getter]
    fn done(&self) -> bool {
        self.inner.done()
    }

    /// The goal (a 1-D array), or None for the reproduction's own end. Setting it moves the
    /// goal from this tick on: the rest of the reproduction is bent from the posture last
    /// commanded onto it (no jump), and it is reached exactly.
    #[getter]
    fn goal<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.goal.clone().map(|g| PyArray1::from_vec(py, g))
    }

    #[setter]
    fn set_goal(&mut self, goal: &Bound<'_, PyAny>) -> PyResult<()> {
        let goal = posture_of(goal, "goal")?;
        self.inner.set_goal(&goal).map_err(|e| py_err(&e))?;
        self.goal = Some(goal);
        Ok(())
    }

    /// The point `(x, y, z)` the held part points at, or None. Setting it moves the target
    /// from this tick on: solved from the same held posture and the rest of the reproduction
    /// bent onto it (a stepper made with `point_at`).
    #[getter]
    fn point_at(&self) -> Option<(f64, f64, f64)> {
        let p = self.aiming.as_ref().and_then(|a| a.aim().point_at);
        p.map(|[x, y, z]| (x, y, z))
    }

    #[setter]
    fn set_point_at(&mut self, target: Option<[f64; 3]>) -> PyResult<()> {
        self.retarget(|aim| aim.point_at = target)
    }

    /// The point `(x, y, z)` the top camera looks at during the held part, or None. Setting
    /// it moves the gaze from this tick on (a stepper made with `point_at` or `look_at`).
    #[getter]
    fn look_at(&self) -> Option<(f64, f64, f64)> {
        let p = self.aiming.as_ref().and_then(|a| a.aim().look_at);
        p.map(|[x, y, z]| (x, y, z))
    }

    #[setter]
    fn set_look_at(&mut self, target: Option<[f64; 3]>) -> PyResult<()> {
        self.retarget(|aim| aim.look_at = target)
    }

    /// How far along the reproduction is, 0 to 1.
    #[getter]
    fn phase(&self) -> f64 {
        self.inner.phase()
    }

    /// How many times the stepper re-planned because the arm was not where it was sent.
    #[getter]
    fn replans(&self) -> usize {
        self.inner.replans()
    }

    fn __repr__(&self) -> String {
        format!(
            "Stepper(phase={:.3}, done={}, replans={})",
            self.inner.phase(),
            if self.inner.done() { "True" } else { "False" },
            self.inner.replans()
        )
    }
}
