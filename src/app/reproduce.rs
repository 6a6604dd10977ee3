//! Reproduction: from an initial posture, resumed after an encoder reading, or continuing
//! the gesture a prefix begins; and the reproduction CSV `cosco reproduce` writes.

use std::borrow::Borrow;
use std::path::{Path, PathBuf};

use super::files::{self, read_for_columns};
use super::{Error, Result};
use crate::condition::{Conditions, PostureArg, ViaPoint};
use crate::hsom::{GestureModel, Hsom, HsomError, HsomStepper, Reproduction};

/// The initial posture of `--initial V1,V2,...` or `--initial-from CSV` (its first row, whose
/// columns must be the model's): exactly one of them.
fn initial_posture(
    model: &Hsom,
    initial: Option<&PostureArg>,
    initial_from: Option<&Path>,
) -> Result<Vec<f64>> {
    match (initial, initial_from) {
        (Some(posture), None) => Ok(posture.0.clone()),
        (None, Some(p)) => Ok(read_for_columns(p, model.columns())?.rows.swap_remove(0)),
        _ => Err(Error::value(
            "--initial:",
            "give exactly one of --initial and --initial-from",
        )),
    }
}

/// An initial posture of the arm's joints within their ranges, give or take
/// [`RANGE_TOLERANCE_RAD`](crate::robot::RANGE_TOLERANCE_RAD). Held in the
/// simulator's builds, whose models are of the simulated arm; of another length, the
/// hierarchy's own check names the lengths.
fn check_arm_range(columns: &[String], initial: &[f64]) -> Result<()> {
    use crate::robot::{Robot, RANGE_TOLERANCE_RAD as TOL};
    let robot = Robot::of_columns(columns).filter(|_| cfg!(feature = "sim"));
    let Some(robot) = robot.filter(|_| initial.len() == columns.len()) else {
        return Ok(());
    };
    for (v, j) in initial.iter().zip(robot.joints()) {
        let (lower, upper) = j.range;
        if v.is_finite() && !(lower - TOL..=upper + TOL).contains(v) {
            return Err(Error::value(
                format!("the initial posture's {} = {v}", j.name),
                format!("is outside its range [{lower}, {upper}] by more than {TOL} rad: not a posture the arm can start from"),
            ));
        }
    }
    Ok(())
}

/// The hierarchy's refusal of an initial posture of another length, naming the model
/// (`model_name`: its file, or `in memory`) and its variables.
fn naming_model(e: HsomError, model: &Hsom, model_name: &str) -> Error {
    match e {
        HsomError::DimensionMismatch { demo, found, .. } if demo == "initial posture" => {
            Error::value(
                "the initial posture",
                format!(
                    "has {found} values; the model {model_name} learned {} variables ({})",
                    model.columns().len(),
                    model.columns().join(", ")
                ),
            )
        }
        e => e.into(),
    }
}

/// A model (`model_name`) whose variables `columns` are `robot`'s joints, in NAOqi order.
fn check_robot(robot: crate::robot::Robot, columns: &[String], model_name: &str) -> Result<()> {
    if crate::robot::Robot::of_columns(columns) == Some(robot) {
        return Ok(());
    }
    Err(Error::value(
        format!("--robot {}:", robot.name()),
        format!(
            "the model {model_name} learned {} variables ({}), not the {}'s {} joints ({})",
            columns.len(),
            columns.join(", "),
            robot.name(),
            robot.joint_names().len(),
            robot.joint_names().join(", ")
        ),
    ))
}

/// The ranges of the arm's joints when `columns` are theirs (in the simulator's builds).
fn arm_ranges(columns: &[String]) -> Option<Vec<(f64, f64)>> {
    crate::robot::arm_ranges(columns).filter(|_| cfg!(feature = "sim"))
}

/// Reproduce gesture `label` of `model` (`None` only for a model of one gesture; `model_name`
/// names it in messages: its file, or `in memory`) from `initial`; with `conditions`, through
/// them (a goal, via-points; [`Hsom::reproduce_conditioned`]), each checked against the arm's
/// joint ranges when the model's variables are the arm's.
pub fn reproduce(
    model: &GestureModel,
    model_name: &str,
    label: Option<&str>,
    initial: &[f64],
    conditions: Option<&Conditions>,
) -> Result<Reproduction> {
    let model = model.branch(label)?;
    check_arm_range(model.columns(), initial)?;
    let rep = match conditions {
        None => model.reproduce(initial),
        Some(conditions) => {
            let ranges = arm_ranges(model.columns());
            conditions.check(model.columns(), ranges.as_deref(), initial)?;
            model.reproduce_conditioned(initial, conditions, ranges.as_deref())
        }
    };
    rep.map_err(|e| naming_model(e, model, model_name))
}

/// The robot whose kinematics aim a model of `columns` (`model_name` in messages): its
/// variables must be the joints of the left arm or the upper body.
fn robot_to_aim(columns: &[String], model_name: &str) -> Result<crate::robot::Robot> {
    crate::robot::Robot::of_columns(columns).ok_or_else(|| {
        Error::value(
            "--point-at and --look-at",
            format!(
                "aim through a Nao's kinematics: the model {model_name} learned {} ({}), not the joints of the left arm or the upper body",
                columns.len(),
                columns.join(", ")
            ),
        )
    })
}

/// [`stepper`] aimed at `aim`: the hierarchy's reproduction through `conditions`, its held
/// part aimed ([`crate::aim::Aiming`]), the stepper started through the aim's via-points;
/// with the aiming, to move the target while it runs ([`crate::aim::Aiming::retargeted`],
/// then [`HsomStepper::set_via`](crate::stepper::Follower::set_via)).
pub fn aimed_stepper<M: Borrow<Hsom>>(
    model: M,
    model_name: &str,
    initial: &[f64],
    conditions: &Conditions,
    aim: &crate::aim::Aim,
) -> Result<(HsomStepper<M>, crate::aim::Aiming)> {
    let m = model.borrow();
    let robot = robot_to_aim(m.columns(), model_name)?;
    check_arm_range(m.columns(), initial)?;
    let ranges = arm_ranges(m.columns());
    conditions.check(m.columns(), ranges.as_deref(), initial)?;
    let rows = (m.reproduce_conditioned(initial, conditions, ranges.as_deref()))
        .map_err(|e| naming_model(e, m, model_name))?
        .postures;
    let (aimed, aiming) = crate::aim::Aiming::new(robot, &rows, conditions, aim)?;
    Ok((stepper(model, model_name, initial, &aimed)?, aiming))
}

/// `conditions` and the via-points that aim the reproduction of gesture `label` of `model`
/// (`model_name` in messages) from `initial` at `aim` ([`crate::aim`]): the reproduction
/// through `conditions` alone, its held part's posture aimed, and that posture passed along
/// the held part ([`crate::aim::via_points`]); with what was solved. The model's variables
/// must be a robot's joints.
pub fn aimed(
    model: &GestureModel,
    model_name: &str,
    label: Option<&str>,
    initial: &[f64],
    conditions: &Conditions,
    aim: &crate::aim::Aim,
) -> Result<(Conditions, crate::aim::Aimed)> {
    let robot = robot_to_aim(model.columns(), model_name)?;
    let rows = reproduce(model, model_name, label, initial, Some(conditions))?.postures;
    Ok(crate::aim::aim_conditions(robot, &rows, conditions, aim)?)
}

/// `rep` (a reproduction of variables `columns`, a step every 1/40 s) retimed to last
/// `duration_s` seconds, its path kept ([`crate::export::limits::at_duration`]); each new
/// step's level that of the nearest original step.
pub fn with_duration(
    rep: &Reproduction,
    columns: &[String],
    duration_s: f64,
) -> Result<Reproduction> {
    let rate = crate::export::DEFAULT_STEP_RATE_HZ;
    let postures = crate::export::limits::at_duration(columns, &rep.postures, rate, duration_s)?;
    let (n, len) = (postures.len(), rep.postures.len());
    let nearest = |k: usize| ((k * (len - 1)) as f64 / (n - 1) as f64).round() as usize;
    Ok(Reproduction {
        steps: (0..n).collect(),
        postures,
        predicted_by: (0..n)
            .map(|k| rep.predicted_by[nearest(k).min(len - 1)])
            .collect(),
        stop: rep.stop,
    })
}

/// The hierarchy in the loop ([`HsomStepper`]) from `initial` through `conditions` (a goal,
/// via-points), checked as [`reproduce`] checks them: the initial posture's
/// width (naming `model_name`), and the arm's joint ranges when the model's variables are
/// the arm's (they also bound a goal set later). `M` is the model or anything that borrows
/// it.
pub fn stepper<M: Borrow<Hsom>>(
    model: M,
    model_name: &str,
    initial: &[f64],
    conditions: &Conditions,
) -> Result<HsomStepper<M>> {
    let m = model.borrow();
    check_arm_range(m.columns(), initial)?;
    if initial.len() != m.columns().len() {
        let e = HsomError::DimensionMismatch {
            demo: "initial posture".into(),
            row: 0,
            expected: m.columns().len(),
            found: initial.len(),
        };
        return Err(naming_model(e, m, model_name));
    }
    let ranges = arm_ranges(m.columns());
    conditions.check(m.columns(), ranges.as_deref(), initial)?;
    Ok(HsomStepper::new(
        model,
        initial,
        conditions,
        ranges.as_deref(),
    )?)
}

/// The conditions of `--goal V1,V2,...` and `--via PHASE:V1,V2,...` (each of them).
pub fn conditions(goal: Option<&PostureArg>, via: &[ViaPoint]) -> Conditions {
    Conditions {
        goal: goal.map(|g| g.0.clone()),
        via: via.to_vec(),
    }
}

/// Resume the reproduction from `initial` after part of it was executed (`reading`: what the
/// encoders read meanwhile; [`Hsom::resume`]).
pub fn resume(
    model: &Hsom,
    model_name: &str,
    initial: &[f64],
    reading: &[Vec<f64>],
) -> Result<Reproduction> {
    check_arm_range(model.columns(), initial)?;
    model
        .resume(initial, reading)
        .map_err(|e| naming_model(e, model, model_name))
}

/// A gesture of a saved model reproduced from an initial posture, as `cosco reproduce` and
/// `cosco export --model` ask it: the model, the gesture (required with several), the initial
/// posture (exactly one of `initial` and `initial_from`), the goal and via-points, and where
/// the band goes.
#[derive(Debug, Clone, Default)]
pub struct ReproduceRequest {
    /// A model saved by `cosco train` (.bin or .txt).
    pub model: PathBuf,
    /// The gesture to reproduce (required with a model of several gestures).
    pub gesture: Option<String>,
    /// The initial posture, one value per state variable.
    pub initial: Option<PostureArg>,
    /// Or the first row of this CSV (the model's columns).
    pub initial_from: Option<PathBuf>,
    /// The last posture, comma-separated: the reproduction ends exactly there.
    pub goal: Option<PostureArg>,
    /// Postures to pass at a phase of the reproduction.
    pub via: Vec<ViaPoint>,
    /// Where to write the central 95 % confidence band about the reproduction, when asked.
    pub band: Option<PathBuf>,
    /// The robot the model must be of (`--robot`): its variables that robot's joints, whose
    /// ranges the postures are checked against. `None`: any variables (the ranges of the
    /// robot whose joints they are, if any).
    pub robot: Option<crate::robot::Robot>,
    /// The reproduction retimed to last this many seconds, its shape kept ([`with_duration`]).
    pub duration: Option<f64>,
    /// What the held part points and looks at ([`aimed`]).
    pub aim: crate::aim::Aim,
}

/// What `cosco reproduce` is asked: a [`ReproduceRequest`], or the continuation of a prefix,
/// or the rest after an encoder reading; and the output.
#[derive(Debug, Clone, Default)]
pub struct ReproduceFile {
    /// The model, the gesture, the initial posture, the goal, via-points and band.
    pub request: ReproduceRequest,
    /// Continue the gesture begun in this demonstration CSV's first `prefix` samples (the
    /// hierarchy decides which gesture it is), instead of reproducing from an initial posture.
    pub prefix_from: Option<PathBuf>,
    /// Samples of `prefix_from` to continue from.
    pub prefix: Option<usize>,
    /// Resume the reproduction from the initial posture after part of it was executed: this
    /// CSV (the model's columns) is what the encoders read meanwhile.
    pub resume_from: Option<PathBuf>,
    /// Output CSV.
    pub out: PathBuf,
}

/// A gesture of a saved model reproduced ([`ReproduceRequest::run`]).
pub(super) struct Reproduced {
    /// The model's variables.
    pub columns: Vec<String>,
    /// The reproduction.
    pub rep: Reproduction,
    /// The gesture's kept demonstrations, in the data's units, and their sample period, s
    /// (`None`: recorded without times).
    pub kept: (Vec<Vec<Vec<f64>>>, Option<f64>),
    /// The band as `--band` writes it, when asked: its file, and its bytes or why there are
    /// none.
    pub band: Option<(PathBuf, Result<Vec<u8>>)>,
}

impl ReproduceRequest {
    /// Load the model, choose the gesture (checked before the initial posture is read), read
    /// the initial posture and reproduce through `conditions`, or with `resume_from` the rest
    /// after that reading ([`resume`]); the band when asked. Nothing is written.
    pub(super) fn run(
        &self,
        conditions: &Conditions,
        resume_from: Option<&Path>,
    ) -> Result<Reproduced> {
        let m = files::load_gesture_model(&self.model)?;
        let name = self.model.display().to_string();
        if let Some(robot) = self.robot {
            check_robot(robot, m.columns(), &name)?;
        }
        let branch = m.branch(self.gesture.as_deref())?;
        let initial = initial_posture(branch, self.initial.as_ref(), self.initial_from.as_deref())?;
        if let (Some(_), Some(d)) = (resume_from, self.duration) {
            return Err(Error::value(
                format!("--duration {d}"),
                "applies to a reproduction from an initial posture, not with --resume-from",
            ));
        }
        if let (Some(_), false) = (resume_from, self.aim.is_empty()) {
            return Err(Error::value(
                "--point-at and --look-at",
                "apply to a reproduction from an initial posture, not with --resume-from",
            ));
        }
        let aimed;
        let conditions = match self.aim.is_empty() {
            true => conditions,
            false => {
                let label = self.gesture.as_deref();
                aimed = self::aimed(&m, &name, label, &initial, conditions, &self.aim)?.0;
                &aimed
            }
        };
        let rep = match resume_from {
            Some(path) => {
                let reading = read_for_columns(path, branch.columns())?.rows;
                resume(branch, &name, &initial, &reading).map_err(|e| Error::Resume {
                    path: path.to_path_buf(),
                    source: Box::new(e),
                })?
            }
            None => reproduce(
                &m,
                &name,
                self.gesture.as_deref(),
                &initial,
                Some(conditions),
            )?,
        };
        let rep = match self.duration {
            Some(d) => with_duration(&rep, m.columns(), d)?,
            None => rep,
        };
        let band = (self.band.as_ref())
            .map(|path| (path.clone(), band_csv(branch, &rep, conditions, path)));
        Ok(Reproduced {
            columns: m.columns().to_vec(),
            rep,
            kept: branch.kept_demonstrations(),
            band,
        })
    }
}

/// The band of `rep` (a reproduction of `model` conditioned on `conditions`) as `--band`
/// writes it to `path`; an error naming the file when the model keeps fewer than 2 training
/// demonstrations.
fn band_csv(
    model: &Hsom,
    rep: &Reproduction,
    conditions: &Conditions,
    path: &Path,
) -> Result<Vec<u8>> {
    let band = model
        .band(&rep.postures, &conditions.phases())
        .ok_or_else(|| {
            Error::file(
                path,
                "no band: the model keeps fewer than 2 training demonstrations to measure it from",
            )
        })?;
    band.csv(model.columns(), &rep.steps)
        .map_err(|e| Error::Write {
            path: path.to_path_buf(),
            source: e.into(),
        })
}

/// `cosco reproduce`: gesture `gesture` (required with several) from the initial posture;
/// with `resume_from`, the rest of it after that reading ([`Hsom::resume`]); with
/// `prefix_from` and `prefix`, the continuation of the gesture the hierarchy recognises in
/// the file's first samples. Writes `step` then the model's columns (the band first, when
/// asked); returns the line to print.
pub fn reproduce_file(r: &ReproduceFile) -> Result<String> {
    let q = &r.request;
    let conditions = conditions(q.goal.as_ref(), &q.via);
    if let (Some(_), Some(d)) = (&r.prefix_from, q.duration) {
        return Err(Error::value(
            format!("--duration {d}"),
            "applies to a reproduction from an initial posture, not with --prefix-from",
        ));
    }
    if !conditions.is_empty() && (r.prefix_from.is_some() || r.resume_from.is_some()) {
        return Err(Error::value(
            "--goal and --via",
            "apply to a reproduction from an initial posture, not with --prefix-from or --resume-from",
        ));
    }
    if !q.aim.is_empty() && (r.prefix_from.is_some() || r.resume_from.is_some()) {
        return Err(Error::value(
            "--point-at and --look-at",
            "apply to a reproduction from an initial posture, not with --prefix-from or --resume-from",
        ));
    }
    if let Some(b) = &q.band {
        crate::fsutil::check_output(b)?;
    }
    let (columns, rep, label, band) = match (&r.prefix_from, r.prefix) {
        (Some(path), Some(prefix)) => {
            let m = files::load_gesture_model(&q.model)?;
            let (label, rep) = continue_file(&m, path, prefix)?;
            (m.columns().to_vec(), rep, Some(label), Ok(()))
        }
        _ => {
            let Reproduced {
                columns, rep, band, ..
            } = q.run(&conditions, r.resume_from.as_deref())?;
            let band = match band {
                Some((path, bytes)) => bytes.and_then(|b| files::write(&path, &b)),
                None => Ok(()),
            };
            (columns, rep, q.gesture.clone(), band)
        }
    };
    let bytes = reproduction_csv(&columns, &rep).map_err(|e| Error::Write {
        path: r.out.clone(),
        source: e.into(),
    })?;
    band?;
    files::write(&r.out, &bytes)?;
    let n = rep.postures.len();
    let mut line = match label {
        Some(l) => format!("{n} postures of {l} written to {}", r.out.display()),
        None => format!("{n} postures written to {}", r.out.display()),
    };
    if let Some(robot) = crate::robot::Robot::of_columns(&columns).filter(|_| !q.aim.is_empty()) {
        let rate = crate::export::DEFAULT_STEP_RATE_HZ;
        for said in crate::aim::summary(robot, &rep.postures, &q.aim, rate) {
            line += &format!("; {said}");
        }
    }
    Ok(line)
}

/// The first `prefix` samples of a demonstration file, continued by the gesture the
/// hierarchy recognises in them; the label and the postures (the prefix first).
pub fn continue_file(
    model: &GestureModel,
    path: &Path,
    prefix: usize,
) -> Result<(String, Reproduction)> {
    let d = read_for_columns(path, model.columns())?;
    if prefix < 2 || prefix > d.rows.len() {
        let n = d.rows.len();
        return Err(Error::file(
            path,
            format!("--prefix {prefix}: the file has {n} samples; give 2 to {n}"),
        ));
    }
    Ok(model.continue_prefix(&d.rows[..prefix])?)
}

/// A reproduction as `cosco reproduce` writes it: CSV with `step`, then the model's columns.
pub fn reproduction_csv(columns: &[String], rep: &Reproduction) -> csv::Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(std::iter::once("step").chain(columns.iter().map(String::as_str)))?;
    for (step, row) in rep.steps.iter().zip(&rep.postures) {
        w.write_record(std::iter::once(step.to_string()).chain(row.iter().map(f64::to_string)))?;
    }
    w.into_inner().map_err(|e| e.into_error().into())
}
