//! Training: one gesture or several, from values (Python) or from files (`cosco train`).
//!
//! ```
//! use cosco_hsom::app::{demonstrations_from_rows, train};
//! use cosco_hsom::config::{AlgorithmParams, EventsParams, HsomParams};
//! let mut p = HsomParams::table1();
//! p.algorithm = AlgorithmParams::Events(EventsParams { change_ratio: 1.0, action_horizon: 1 });
//! p.state_length = 2;
//! p.action_length = 2;
//! p.training_steps = 300;
//! let cfg = p.check("example").unwrap();
//! let up: Vec<Vec<f64>> = (0..40).map(|i| vec![i as f64 / 40.0, 0.0]).collect();
//! let side: Vec<Vec<f64>> = (0..40).map(|i| vec![0.0, i as f64 / 40.0]).collect();
//! let sets = vec![
//!     ("up".to_string(), demonstrations_from_rows(vec![up.clone(), up.clone()], None).unwrap()),
//!     ("side".to_string(), demonstrations_from_rows(vec![side.clone(), side.clone()], None).unwrap()),
//! ];
//! let model = train(&cfg, &sets, None).unwrap();
//! assert_eq!(model.labels(), ["up", "side"]);
//! assert_eq!(model.recognize(&side).unwrap().best, "side");
//! ```

use std::path::{Path, PathBuf};

use super::files;
use super::Result;
use crate::config::{load_config_or_robots, HsomConfig};
use crate::demo_sets::{read_demo_sets, robot_of, DemoSets};
use crate::demos::{self, Demonstration};
use crate::hsom::{Fit, GestureError, GestureModel, Gestures, HsomError};
use crate::robot::Robot;

/// Check the demonstrations against the configuration (one gesture's as a set, at least
/// one; every label's set, each with demonstrations; see [`demos::validate_set`]), then fit
/// the model of one gesture or several ([`HsomConfig::fit_model`]), calling
/// `progress(done, total)` now and then when given (with several, over every gesture's
/// training).
pub fn train<'a>(
    cfg: &HsomConfig,
    sets: impl Into<Gestures<'a>>,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<GestureModel> {
    let sets = sets.into();
    let state = Some(cfg.params().state_length);
    match sets {
        Gestures::One(demos) => demos::validate_set(demos, state)?,
        Gestures::Labelled(sets) => {
            for (label, demos) in sets {
                // a label without demonstrations is named (validate_set would only say "none")
                if demos.is_empty() {
                    return Err(GestureError::EmptyLabel {
                        label: label.clone(),
                    }
                    .into());
                }
                demos::validate_set(demos, state)?;
            }
        }
    }
    Ok(cfg.fit_model(
        sets,
        Fit {
            progress,
            untrained: false,
        },
    )?)
}

/// Check `demos` as a set against `model`'s configuration, then teach them to it as gesture
/// `label` (`None` for a model of one unlabelled gesture; a label it does not hold adds the
/// gesture), from the model and them alone ([`GestureModel::update`]).
pub fn update(
    model: &GestureModel,
    label: Option<&str>,
    demos: &[Demonstration],
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<GestureModel> {
    if demos.is_empty() {
        return Ok(model.clone());
    }
    let state = model.branches()[0].config().params().state_length;
    demos::validate_set(demos, Some(state))?;
    Ok(model.update(label, demos, progress)?)
}

/// `cosco train --from`: check where the model goes, load the model, read the new
/// demonstrations (a directory of CSV files for a model of one gesture, labelled directories
/// for a model of several; resampled to `resample` Hz when given; of the model's columns),
/// teach them to the model (`progress(done, total)`) and save it atomically: the model it
/// came from is never written, and nothing is written when anything is refused. `config`,
/// when given, must be the model's configuration.
pub fn update_files(
    from: &Path,
    config: Option<&Path>,
    demo_paths: &[PathBuf],
    out: &Path,
    resample: Option<f64>,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<GestureModel> {
    files::check_model_output(out)?;
    let model = files::load_gesture_model(from)?;
    let cfg = model.branches()[0].config();
    if let Some(path) = config {
        let given = files::config(Some(path))?;
        if given.params() != cfg.params() {
            return Err(super::Error::file(
                path,
                format!(
                    "is not the configuration of {} (its configuration: `cosco inspect {}`); \
                     an update goes on with the model's own configuration: leave --config out",
                    from.display(),
                    from.display()
                ),
            ));
        }
    }
    // the sets are checked as they are read, against the model's stateLength
    let state = cfg.params().state_length;
    let updated = match read_demo_sets(demo_paths, Some(state), resample)? {
        DemoSets::Plain(d) => model.update(None, &d, progress),
        DemoSets::Labelled(s) => model.update_labelled(&s, progress),
    }
    // a count the model file holds is named with the file
    .map_err(|e| match e {
        GestureError::Hsom(e @ HsomError::TooManyLearned { .. }) => {
            super::Error::file(from, e.to_string())
        }
        e => e.into(),
    })?;
    files::save_gesture_model(&updated, out)?;
    Ok(updated)
}

/// `cosco train`: check where the model goes, read the demonstrations (one gesture, or
/// labelled directories of several; resampled to `resample` Hz when given), train
/// (`progress(done, total)`) and save atomically. Without `config`, demonstrations whose
/// columns are a robot's joints take that robot's recommended configuration
/// ([`robot_of`], [`Robot::config`]).
pub fn train_files(
    config: Option<&Path>,
    demo_paths: &[PathBuf],
    out: &Path,
    state_length_from_data: bool,
    resample: Option<f64>,
    progress: Option<&dyn Fn(usize, usize)>,
) -> Result<GestureModel> {
    // where the model goes is checked before any reading or training
    files::check_model_output(out)?;
    // without --config, demonstrations of a robot's joints take that robot's configuration
    let robot = match config {
        Some(_) => Robot::LeftArm,
        None => robot_of(demo_paths, resample)?,
    };
    let mut cfg = load_config_or_robots(config, robot)?;
    if state_length_from_data {
        let width = read_demo_sets(demo_paths, None, resample)?.width();
        cfg = cfg.for_width(width)?;
    }
    // the sets are checked as they are read, against the configuration's stateLength
    let sets = read_demo_sets(demo_paths, Some(cfg.params().state_length), resample)?;
    let model = train(&cfg, sets.gestures(), progress)?;
    files::save_gesture_model(&model, out)?;
    Ok(model)
}
