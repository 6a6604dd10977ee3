//! Several gestures in one model (docs/ALGORITHM.md, section 4): a [`GestureModel`] is one
//! branch per gesture label, each the gesture learned alone (its own bottom level and upper
//! levels, trained on that label's demonstrations), all in the units of every gesture's
//! demonstrations, so that recognition ([`super::recognize`]) compares their scores; the
//! label chooses the branch on reproduction.
//!
//! A single-gesture model (no label) loads as a [`GestureModel`] with one unlabelled branch,
//! and is saved as an [`Hsom`]; a file of several gestures holds the labels, their
//! recognition calibration and every branch, in the one description of [`super::persist`],
//! its header saying the kind. Older files get the "retrain" error.

use crate::config::{Algorithm, HsomConfig};
use crate::demos::{check_gesture_columns, is_plain_label, Demonstration};

use super::algorithm::Fit;
use super::errors::{GestureError, HsomError};
use super::inputs::{demo_series, Series};
use super::kept::Warm;
use super::model::{EventsHsom, GestureModel, Hsom, Scoring};
use super::persist::FORMAT_VERSION;

/// Format version of a multi-gesture model file: the one version of model files (the header
/// says the kind).
pub const GESTURES_FORMAT_VERSION: u32 = FORMAT_VERSION;

/// Most gesture labels a model may hold (a bound on what a file may make us allocate).
pub const MAX_LABELS: usize = 1024;

/// Label `i` of `sets` (given `source_dir`, for messages) a plain word not given before.
pub(super) fn check_label(
    sets: &[(String, Vec<Demonstration>)],
    i: usize,
    source_dir: &str,
) -> Result<(), GestureError> {
    let label = &sets[i].0;
    if !is_plain_label(label) {
        return Err(GestureError::BadLabel {
            label: label.clone(),
            source_dir: source_dir.into(),
        });
    }
    if sets[..i].iter().any(|(l, _)| l == label) {
        return Err(GestureError::DuplicateLabel {
            label: label.clone(),
        });
    }
    Ok(())
}

impl From<Hsom> for GestureModel {
    fn from(model: Hsom) -> Self {
        GestureModel {
            labels: Vec::new(),
            branches: vec![model],
            calibration: Vec::new(),
            scoring: Scoring::default(),
        }
    }
}

/// What a model is fitted on: one gesture's demonstrations (a model without labels), or
/// labelled sets `(label, demonstrations)` of several gestures.
#[derive(Debug, Clone, Copy)]
pub enum Gestures<'a> {
    /// One gesture, no label.
    One(&'a [Demonstration]),
    /// Labelled sets, in the order given.
    Labelled(&'a [(String, Vec<Demonstration>)]),
}

impl<'a> From<&'a [Demonstration]> for Gestures<'a> {
    fn from(demos: &'a [Demonstration]) -> Self {
        Gestures::One(demos)
    }
}

impl<'a> From<&'a Vec<Demonstration>> for Gestures<'a> {
    fn from(demos: &'a Vec<Demonstration>) -> Self {
        Gestures::One(demos)
    }
}

impl<'a, const N: usize> From<&'a [Demonstration; N]> for Gestures<'a> {
    fn from(demos: &'a [Demonstration; N]) -> Self {
        Gestures::One(demos)
    }
}

impl<'a> From<&'a [(String, Vec<Demonstration>)]> for Gestures<'a> {
    fn from(sets: &'a [(String, Vec<Demonstration>)]) -> Self {
        Gestures::Labelled(sets)
    }
}

impl<'a> From<&'a Vec<(String, Vec<Demonstration>)>> for Gestures<'a> {
    fn from(sets: &'a Vec<(String, Vec<Demonstration>)>) -> Self {
        Gestures::Labelled(sets)
    }
}

impl<'a, const N: usize> From<&'a [(String, Vec<Demonstration>); N]> for Gestures<'a> {
    fn from(sets: &'a [(String, Vec<Demonstration>); N]) -> Self {
        Gestures::Labelled(sets)
    }
}

impl HsomConfig {
    /// Fit a model of one gesture or several, as `how` says (trained, or the untrained
    /// negative control; a progress callback). One gesture: its hierarchy, the model's one
    /// unlabelled branch. Labelled sets: one branch per label, the gesture learned alone
    /// in the units of all of them; each label's recognition threshold is calibrated on its
    /// training data (leave-one-out). Labels must be plain words, distinct, each with
    /// demonstrations of the same columns, and the algorithm the events extension.
    pub fn fit_model<'a>(
        &self,
        sets: impl Into<Gestures<'a>>,
        how: Fit<'_>,
    ) -> Result<GestureModel, GestureError> {
        match sets.into() {
            Gestures::One(demos) => Ok(self.fit_one(demos, how)?.into()),
            Gestures::Labelled(sets) => self.fit_labelled(sets, how),
        }
    }

    pub(super) fn fit_labelled(
        &self,
        sets: &[(String, Vec<Demonstration>)],
        how: Fit<'_>,
    ) -> Result<GestureModel, GestureError> {
        if self.params().kind() != Algorithm::Events {
            return Err(GestureError::NeedsEvents);
        }
        if sets.is_empty() {
            return Err(HsomError::NoDemonstrations.into());
        }
        for (i, (label, demos)) in sets.iter().enumerate() {
            check_label(sets, i, "in memory")?;
            if demos.is_empty() {
                return Err(GestureError::EmptyLabel {
                    label: label.clone(),
                });
            }
            check_gesture_columns(sets, i)?;
        }
        let all: Vec<Demonstration> = sets.iter().flat_map(|(_, d)| d.clone()).collect();
        // every gesture in the units of all of them (recognition compares their scores),
        // each learned alone in them: its own bottom level, trainingSteps on its own
        // demonstrations, and its upper levels (docs/ALGORITHM.md, section 4)
        let (offset, scale) = self.units(&demo_series(&all))?;
        let seed = self.params().seed;
        let units = Warm::units(&offset, &scale, seed);
        let mut branches: Vec<EventsHsom> = Vec::with_capacity(sets.len());
        for (g, (_, demos)) in sets.iter().enumerate() {
            let progress = |done: usize, total: usize| {
                if let Some(p) = how.progress {
                    p(g * total + done, total * sets.len());
                }
            };
            let fit = Fit {
                progress: Some(&progress),
                untrained: how.untrained,
            };
            let Hsom::Events(b) = self.fit_one_in(demos, fit, Some(&units))? else {
                return Err(GestureError::NeedsEvents);
            };
            branches.push(*b);
        }
        let norm: Vec<Vec<Vec<Vec<f64>>>> = (sets.iter().zip(&branches))
            .map(|((_, demos), b)| demos.iter().map(|d| b.normalise_rows(&d.rows)).collect())
            .collect();
        let calibration = super::recognize::calibrate(&branches, &norm, !how.untrained, seed)?;
        Ok(GestureModel {
            labels: sets.iter().map(|(l, _)| l.clone()).collect(),
            branches: branches
                .into_iter()
                .map(|b| Hsom::Events(Box::new(b)))
                .collect(),
            calibration,
            scoring: Scoring::default(),
        })
    }
}

impl EventsHsom {
    /// This branch's gesture learned again, bottom level and all, from `norm` alone (its
    /// normalised demonstrations but one: a held-out branch for calibration), in its units.
    pub(crate) fn without(
        &self,
        norm: &[Vec<Vec<f64>>],
        learn: bool,
        seed: u64,
    ) -> Result<EventsHsom, HsomError> {
        let raw: Vec<Vec<Vec<f64>>> = (norm.iter())
            .map(|d| d.iter().map(|r| self.denormalise(r)).collect())
            .collect();
        let series: Vec<Series<'_>> = (raw.iter())
            .map(|rows| Series {
                source: "a demonstration of a held-out branch",
                rows,
            })
            .collect();
        let units = Warm::units(&self.offset, &self.scale, seed);
        let columns = self.columns.clone();
        let Hsom::Events(mut m) =
            self.config
                .fit_from(&series, None, learn, columns, Some(&units))?
        else {
            return Err(HsomError::NoDemonstrations);
        };
        m.kept.period = self.kept.period;
        if learn {
            m.fit_postures(norm);
        }
        Ok(*m)
    }

    /// This model's bottom level (and normalisation) with every statistic recomputed and
    /// the upper levels trained on `norm` (normalised demonstrations of a gesture) by the
    /// events extension's own training; trained (`learn`), it places the nodes' events where
    /// the demonstrations have them ([`EventsHsom::fit_postures`]): a held-out branch of a
    /// gesture of two demonstrations, and the negative control of a gesture's levels on a
    /// bottom learned from other gestures too.
    pub(crate) fn build_branch(
        &self,
        norm: &[Vec<Vec<f64>>],
        learn: bool,
        seed: u64,
    ) -> EventsHsom {
        let mut b = self.clone();
        let h = b.maps.len();
        // what the replay and the levels' training add to or may leave; every other
        // statistic they compute anew
        b.hits.iter_mut().for_each(|v| v.fill(0));
        b.trained[1..].iter_mut().for_each(|t| *t = 0);
        b.lookup = vec![0.0; h];
        b.part.threshold = vec![0.0; h];
        let lens: Vec<f64> = norm.iter().map(|d| d.len() as f64).collect();
        b.demo_len = super::inputs::spread(&lens);
        let period = b.kept.period;
        (b.paths, b.kept) = super::kept::kept(norm, norm.iter().map(Vec::len), seed);
        b.kept.period = period;
        b.replay(norm);
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(seed);
        b.fit_events(norm, learn, &mut rng);
        if learn {
            b.fit_postures(norm);
        }
        b
    }
}

impl GestureModel {
    /// The same model scoring recognition another way (the thresholds stay the default
    /// scoring's: compare labels, not `unknown`, with another scoring).
    pub fn with_scoring(mut self, scoring: Scoring) -> Self {
        self.scoring = scoring;
        self
    }

    /// The gesture labels (empty for a single-gesture model).
    pub fn labels(&self) -> &[String] {
        &self.labels
    }

    /// The branches: one [`Hsom`] per label (one for a single-gesture model), each in the
    /// units of all of them.
    pub fn branches(&self) -> &[Hsom] {
        &self.branches
    }

    /// The variables learned.
    pub fn columns(&self) -> &[String] {
        self.branches[0].columns()
    }

    /// The branch of `label`; `None` is only accepted for a single-gesture model.
    pub fn branch(&self, label: Option<&str>) -> Result<&Hsom, GestureError> {
        match (label, self.labels.is_empty()) {
            (None, true) => Ok(&self.branches[0]),
            (None, false) => Err(GestureError::LabelNeeded {
                labels: self.labels.join(", "),
            }),
            (Some(l), _) => self
                .labels
                .iter()
                .position(|x| x == l)
                .map(|i| &self.branches[i])
                .ok_or_else(|| GestureError::UnknownLabel {
                    label: l.to_string(),
                    labels: if self.labels.is_empty() {
                        "no labels (a single-gesture model: leave the gesture out)".into()
                    } else {
                        self.labels.join(", ")
                    },
                }),
        }
    }

    /// Check what was read: at least one and at most [`MAX_LABELS`] plain, distinct labels,
    /// a branch and a valid calibration each, branches sound ([`Model::check`]) of the events
    /// extension, all of the same configuration, columns, normalisation and bottom level.
    pub(super) fn check(&self) -> Result<(), String> {
        let n = self.labels.len();
        if n == 0 || n > MAX_LABELS || self.branches.len() != n || self.calibration.len() != n {
            return Err(format!(
                "{n} gesture labels, {} branches, {} calibrations: 1 to {MAX_LABELS}, one each",
                self.branches.len(),
                self.calibration.len()
            ));
        }
        let mut first: Option<&EventsHsom> = None;
        for (i, (l, b)) in self.labels.iter().zip(&self.branches).enumerate() {
            if !is_plain_label(l) || self.labels[..i].contains(l) {
                return Err(format!("gesture label {l:?}: plain distinct words only"));
            }
            let Some(b) = b.as_events() else {
                return Err(format!(
                    "gesture {l:?}: several gestures need algorithm = events"
                ));
            };
            b.check().map_err(|what| format!("gesture {l:?}: {what}"))?;
            let first = *first.get_or_insert(b);
            let same = b.config == first.config
                && b.columns == first.columns
                && b.offset == first.offset
                && b.scale == first.scale;
            if !same {
                return Err(format!(
                    "gesture {l:?} does not share the first gesture's configuration, \
                     variables and units"
                ));
            }
        }
        let height = self.branches[0].height();
        match self
            .labels
            .iter()
            .zip(&self.calibration)
            .find(|(_, c)| !c.fits(height))
        {
            Some((l, _)) => Err(format!("gesture {l:?}: bad calibration")),
            None => Ok(()),
        }
    }
}
