//! Gestures taught one at a time (`cosco heldout --recognition --one-at-a-time`): every model
//! of the recognition study taught its gestures one after another, each update with that
//! gesture's demonstrations only ([`GestureModel::update`]); on every held-out fold, the
//! held-out demonstration's gesture reproduced from its first posture by the model taught at
//! once, the model right after its gesture was taught and the model after the last gesture.

use serde::Serialize;

use crate::config::HsomConfig;
use crate::demos::Demonstration;
use crate::dtw::{dtw_distance, Band};
use crate::hsom::GestureModel;

use super::super::{diagonal, LooError};

/// The gate on reproduction after the last gesture: at most this times the model taught at
/// once, and at most this times the model right after the gesture was taught (no
/// forgetting).
pub const FORGETTING_GATE: f64 = 1.05;

/// One held-out demonstration's gesture reproduced by the three models of its fold: relative
/// DTW (per-step DTW over the gesture's bounding-box diagonal) against it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reproduced {
    /// Its gesture.
    pub label: String,
    /// The demonstration (its file).
    pub demonstration: String,
    /// By the model taught every gesture at once.
    pub at_once: f64,
    /// By the model right after its gesture was taught.
    pub after_taught: f64,
    /// By the model after the last gesture.
    pub after_last: f64,
    /// Whether the model taught at once recognised it as its own gesture.
    pub at_once_accepted: bool,
}

fn refused(what: &str) -> impl Fn(crate::hsom::GestureError) -> LooError + '_ {
    move |e| LooError::Gesture {
        what: what.to_string(),
        source: Box::new(e),
    }
}

/// A model taught `sets` one gesture after another: trained on the first, then updated with
/// each next one's demonstrations alone; `each(g, model)` sees the model right after gesture
/// `g` was taught.
pub(super) fn in_turn(
    config: &HsomConfig,
    sets: &[(String, Vec<Demonstration>)],
    what: &str,
    mut each: impl FnMut(usize, &GestureModel) -> Result<(), LooError>,
) -> Result<GestureModel, LooError> {
    let Some((first, rest)) = sets.split_first() else {
        return Err(LooError::NoTaught);
    };
    let mut model = config
        .fit_model(std::slice::from_ref(first), crate::hsom::Fit::default())
        .map_err(refused(what))?;
    each(0, &model)?;
    for (g, (label, demos)) in rest.iter().enumerate() {
        model = model
            .update(Some(label), demos, None)
            .map_err(refused(what))?;
        each(g + 1, &model)?;
    }
    Ok(model)
}

/// Relative DTW of `model`'s reproduction of `label` from `demo`'s first posture against
/// `demo`, in a gesture of diagonal `diag`.
fn relative_dtw(
    model: &GestureModel,
    label: &str,
    demo: &Demonstration,
    diag: f64,
    what: &str,
) -> Result<f64, LooError> {
    let rep = model
        .branch(Some(label))
        .and_then(|b| Ok(b.reproduce(&demo.rows[0])?))
        .map_err(refused(what))?;
    let d = dtw_distance(&rep.postures, &demo.rows, Band::None).map_err(|e| {
        LooError::NoReproduction(format!("{what}: DTW against {}: {e}", demo.source))
    })?;
    Ok(d.per_step() / diag.max(f64::MIN_POSITIVE))
}

/// The fold of `taught[g]`'s demonstration `i` taught one gesture at a time: the model taught
/// in turn without it (returned, for its answer), and its gesture reproduced by the three
/// models ([`Reproduced`]).
pub(super) fn fold(
    config: &HsomConfig,
    taught: &[(String, Vec<Demonstration>)],
    g: usize,
    i: usize,
) -> Result<(GestureModel, Reproduced), LooError> {
    let (label, demos) = &taught[g];
    let held = &demos[i];
    let mut sets = taught.to_vec();
    sets[g].1.remove(i);
    let what = format!(
        "the model taught one gesture at a time without {}",
        held.source
    );
    let diag = diagonal(demos);
    let mut after_taught = f64::NAN;
    let last = in_turn(config, &sets, &what, |k, m| {
        if k == g {
            after_taught = relative_dtw(m, label, held, diag, &what)?;
        }
        Ok(())
    })?;
    let once_what = format!("the model taught at once without {}", held.source);
    let once = config
        .fit_model(&sets, crate::hsom::Fit::default())
        .map_err(refused(&once_what))?;
    let at_once_accepted = once
        .recognize(&held.rows)
        .map_err(refused(&once_what))?
        .label
        .as_deref()
        == Some(label.as_str());
    let reproduced = Reproduced {
        label: label.clone(),
        demonstration: held.source.clone(),
        at_once: relative_dtw(&once, label, held, diag, &once_what)?,
        after_taught,
        after_last: relative_dtw(&last, label, held, diag, &what)?,
        at_once_accepted,
    };
    Ok((last, reproduced))
}

/// Per taught label: the median over its folds of each model's relative DTW, and whether
/// the model after the last gesture is within [`FORGETTING_GATE`] of both others.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Forgetting {
    /// The gesture.
    pub label: String,
    /// Its folds.
    pub folds: usize,
    /// Median relative DTW taught at once.
    pub at_once: f64,
    /// Right after it was taught.
    pub after_taught: f64,
    /// After the last gesture.
    pub after_last: f64,
    /// `after_last / at_once`.
    pub against_at_once: f64,
    /// `after_last / after_taught`.
    pub against_taught: f64,
    /// Both ratios at most [`FORGETTING_GATE`].
    pub passes: bool,
}

/// [`Forgetting`] of every label of `taught`, from the folds' `reproduced`.
pub fn forgetting(taught: &[String], reproduced: &[Reproduced]) -> Vec<Forgetting> {
    taught
        .iter()
        .filter_map(|l| {
            let of: Vec<&Reproduced> = reproduced.iter().filter(|r| r.label == *l).collect();
            let med = |f: fn(&Reproduced) -> f64| crate::stats::median(of.iter().map(|r| f(r)));
            let (at_once, after_taught, after_last) = (
                med(|r| r.at_once)?,
                med(|r| r.after_taught)?,
                med(|r| r.after_last)?,
            );
            let (a, t) = (after_last / at_once, after_last / after_taught);
            Some(Forgetting {
                label: l.clone(),
                folds: of.len(),
                at_once,
                after_taught,
                after_last,
                against_at_once: a,
                against_taught: t,
                passes: a <= FORGETTING_GATE && t <= FORGETTING_GATE,
            })
        })
        .collect()
}
