//! Teaching a trained model more (docs/ALGORITHM.md, section 10): new demonstrations of a
//! gesture it knows, or a new labelled gesture, from the model and the new demonstrations
//! alone.
//!
//! A model keeps at most [`KEPT_DEMONSTRATIONS`](super::KEPT_DEMONSTRATIONS) of the demonstrations of each gesture it
//! learned from, a uniform sample of them all (reservoir sampling, seeded), normalised and
//! resampled to [`BAND_ROWS`](super::BAND_ROWS) rows with each one's length ([`Kept`]). An update:
//! 1. trains the gesture's bottom map on the new demonstrations and the kept ones
//!    (rehearsal), in order, the new ones first, going on from its weights over the end of
//!    its schedule: the share of the steps and the rates that the new demonstrations' share
//!    of all learned from would have had (a model of the paper's algorithm goes on training
//!    every level so);
//! 2. fits the gesture's upper levels and plans again on its kept and new demonstrations
//!    (the bottom moved under them);
//! 3. keeps the sample of demonstrations up to date.
//!
//! In a model of several gestures each gesture is taught so, on its own branch, and the
//! gestures not taught stay as they were; a new gesture has every gesture learned again at
//! once from its kept and new demonstrations, in the units of all of them; recognition is
//! calibrated again on every gesture's kept and new demonstrations.
//!
//! Its cost is bounded by the configuration: whatever the number of demonstrations learned
//! from, it learns from at most [`KEPT_DEMONSTRATIONS`](super::KEPT_DEMONSTRATIONS) earlier ones per gesture.

use crate::demos::{median_interval, same_rate, Demonstration};

use super::algorithm::Fit;
use super::errors::{GestureError, HsomError};
use super::inputs::Series;
use super::kept::{band_path, Kept};
use super::kept::{keep, mixed, Warm};
use super::labels::check_label;
use super::model::{EventsHsom, GestureModel, Hsom, Model, Part};
use super::recognize::calibrate;

impl<A: Part> Model<A> {
    /// The kept demonstrations in the data's units, each at its own length (read between two
    /// rows of its path).
    pub(crate) fn kept_rows(&self) -> Vec<Vec<Vec<f64>>> {
        (self.paths.iter().zip(&self.kept.lengths))
            .map(|(path, &n)| {
                (0..n)
                    .map(|k| {
                        let phase = f64::from(k) / f64::from(n.max(2) - 1);
                        self.denormalise(&crate::curve::at_phase(path, phase))
                    })
                    .collect()
            })
            .collect()
    }

    /// Whether `demos` can teach this model more: its columns, in its order, and its sample
    /// period; what is wrong, naming the demonstration.
    fn accepts(&self, demos: &[Demonstration]) -> Result<(), HsomError> {
        for d in demos {
            if d.columns != self.columns {
                return Err(HsomError::UpdateColumns {
                    demo: d.source.clone(),
                    found: d.columns.clone(),
                    expected: self.columns.clone(),
                });
            }
            // a rate not recorded on either side cannot be compared
            let same = match (self.kept.period, median_interval(d)) {
                (Some(a), Some(b)) => same_rate(a, b),
                _ => true,
            };
            if !same {
                return Err(HsomError::UpdatePeriod {
                    demo: d.source.clone(),
                    found: median_interval(d).unwrap_or(f64::NAN),
                    expected: self.kept.period.unwrap_or(f64::NAN),
                });
            }
        }
        Ok(())
    }

    /// Where an update of this model starts: its maps (`levels` of them), normalisation and
    /// counts, going on from the earlier demonstrations' share `from`.
    fn warm(&self, levels: usize, from: f64) -> Warm<'_> {
        Warm {
            maps: &self.maps[..levels],
            offset: &self.offset,
            scale: &self.scale,
            trained: &self.trained,
            from,
            seed: mixed(self.config.params().seed, u64::from(self.kept.updates) + 1),
        }
    }

    /// This model's kept paths in `to`'s normalisation, and its record ([`Kept`]), with `new`
    /// (normalised as `to` normalises) kept as [`keep`] keeps them and `updates` more updates
    /// counted.
    fn remembered<B: Part>(
        &self,
        to: &Model<B>,
        new: &[Vec<Vec<f64>>],
        updates: u32,
    ) -> (Vec<Vec<Vec<f64>>>, Kept) {
        let mut paths: Vec<Vec<Vec<f64>>> = (self.paths.iter())
            .map(|p| {
                p.iter()
                    .map(|r| to.normalise(&self.denormalise(r)))
                    .collect()
            })
            .collect();
        let mut kept = self.kept.clone();
        keep(
            &mut paths,
            &mut kept,
            new.iter().map(|rows| (band_path(rows), rows.len())),
            self.config.params().seed,
        );
        kept.updates += updates;
        (paths, kept)
    }
}

/// Named series of demonstrations and kept rows: the new ones first (`new_first`), or the
/// kept ones first, as they were learned.
fn series<'a>(
    new: &'a [Demonstration],
    kept: &'a [Vec<Vec<f64>>],
    names: &'a [String],
    new_first: bool,
) -> Vec<Series<'a>> {
    let new = new.iter().map(|d| Series {
        source: &d.source,
        rows: &d.rows,
    });
    let kept = kept
        .iter()
        .zip(names)
        .map(|(rows, source)| Series { source, rows });
    match new_first {
        true => new.chain(kept).collect(),
        false => kept.chain(new).collect(),
    }
}

/// Names for `n` kept demonstrations in messages.
fn kept_names(label: &str, n: usize) -> Vec<String> {
    (0..n)
        .map(|k| format!("kept demonstration #{k} of {label}"))
        .collect()
}

impl Hsom {
    /// The kept demonstrations in the data's units ([`Model::kept_rows`]) and their sample
    /// period, s (`None`: recorded without times).
    pub(crate) fn kept_demonstrations(&self) -> (Vec<Vec<Vec<f64>>>, Option<f64>) {
        let rows = match self {
            Hsom::Paper(m) => m.kept_rows(),
            Hsom::Events(m) => m.kept_rows(),
        };
        (rows, self.kept().period)
    }

    /// This model taught `demos` more, from the model and them alone (docs/ALGORITHM.md,
    /// section 10); with no demonstrations, the model as it is.
    pub fn update(&self, demos: &[Demonstration]) -> Result<Hsom, HsomError> {
        self.update_with_progress(demos, None)
    }

    /// [`Hsom::update`], calling `progress(done, total)` about a hundred times.
    pub fn update_with_progress(
        &self,
        demos: &[Demonstration],
        progress: Option<&dyn Fn(usize, usize)>,
    ) -> Result<Hsom, HsomError> {
        match self {
            Hsom::Paper(m) => m.updated(demos, progress),
            Hsom::Events(m) => m.updated(demos, progress),
        }
    }

    /// The kept paths and record this model's update leaves (see [`Model::remembered`]).
    fn remember(&mut self, paths: Vec<Vec<Vec<f64>>>, kept: Kept) {
        match self {
            Hsom::Paper(m) => (m.paths, m.kept) = (paths, kept),
            Hsom::Events(m) => (m.paths, m.kept) = (paths, kept),
        }
    }

    /// What this model learned from ([`Kept`]).
    fn kept(&self) -> &Kept {
        match self {
            Hsom::Paper(m) => &m.kept,
            Hsom::Events(m) => &m.kept,
        }
    }

    /// Demonstrations learned from, kept, and updates ([`Kept`]).
    pub fn learned(&self) -> (u64, usize, u32) {
        let (paths, kept) = match self {
            Hsom::Paper(m) => (&m.paths, &m.kept),
            Hsom::Events(m) => (&m.paths, &m.kept),
        };
        (kept.learned, paths.len(), kept.updates)
    }

    /// The sample period of the demonstrations learned from, seconds (`None`: no times).
    pub(crate) fn set_period(&mut self, period: Option<f64>) {
        match self {
            Hsom::Paper(m) => m.kept.period = period,
            Hsom::Events(m) => m.kept.period = period,
        }
    }
}

impl<A: Part> Model<A> {
    /// [`Hsom::update`] of a model of one gesture.
    fn updated(
        &self,
        demos: &[Demonstration],
        progress: Option<&dyn Fn(usize, usize)>,
    ) -> Result<Hsom, HsomError> {
        if demos.is_empty() {
            return Ok(A::wrap(self.clone()));
        }
        self.accepts(demos)?;
        self.kept.room(demos.len(), "the model")?;
        let kept = self.kept_rows();
        let names = kept_names("the model", kept.len());
        let all = series(demos, &kept, &names, true);
        let learned = self.kept.learned as f64;
        let from = learned / (learned + demos.len() as f64);
        // the events extension fits its upper levels anew; the paper's levels go on learning
        let levels = match A::ALGORITHM {
            crate::config::Algorithm::Events => 1,
            crate::config::Algorithm::Paper => self.maps.len(),
        };
        let warm = self.warm(levels, from);
        let mut model =
            self.config
                .fit_from(&all, progress, true, self.columns.clone(), Some(&warm))?;
        if let Hsom::Events(m) = &mut model {
            m.learn_postures(all.iter().map(|s| s.rows));
        }
        let new: Vec<Vec<Vec<f64>>> = demos.iter().map(|d| self.normalise_rows(&d.rows)).collect();
        let (paths, record) = match &model {
            Hsom::Paper(m) => self.remembered(m, &new, 1),
            Hsom::Events(m) => self.remembered(m, &new, 1),
        };
        model.remember(paths, record);
        Ok(model)
    }
}

impl GestureModel {
    /// This model taught `demos` of gesture `label` more (a label it does not hold adds the
    /// gesture), from the model and them alone; `label` `None` for a model of one unlabelled
    /// gesture. With no demonstrations, the model as it is.
    pub fn update(
        &self,
        label: Option<&str>,
        demos: &[Demonstration],
        progress: Option<&dyn Fn(usize, usize)>,
    ) -> Result<GestureModel, GestureError> {
        match label {
            None if self.labels.is_empty() => Ok(self.branches[0]
                .update_with_progress(demos, progress)?
                .into()),
            None => Err(GestureError::LabelNeeded {
                labels: self.labels.join(", "),
            }),
            Some(l) => self.update_labelled(&[(l.to_string(), demos.to_vec())], progress),
        }
    }

    /// This model taught every `(label, demonstrations)` of `sets` more, in one update (a
    /// label it does not hold adds the gesture): each gesture taught more goes on learning, as
    /// a gesture alone does, from its new demonstrations and its kept ones; with a new one,
    /// every gesture is learned again at once from its kept and new demonstrations;
    /// recognition is calibrated again on all of them. Labels must be plain, distinct words, demonstrations
    /// of the model's columns and sample period. With no demonstrations, the model as it is.
    pub fn update_labelled(
        &self,
        sets: &[(String, Vec<Demonstration>)],
        progress: Option<&dyn Fn(usize, usize)>,
    ) -> Result<GestureModel, GestureError> {
        if sets.iter().all(|(_, d)| d.is_empty()) {
            return Ok(self.clone());
        }
        if self.labels.is_empty() {
            return Err(GestureError::UnlabelledUpdate);
        }
        let Some(first) = self.branches[0].as_events() else {
            return Err(GestureError::NeedsEvents);
        };
        for (i, (label, demos)) in sets.iter().enumerate() {
            check_label(sets, i, "the update")?;
            first.accepts(demos)?;
            if let Some(g) = self.labels.iter().position(|l| l == label) {
                (self.branches[g].kept()).room(demos.len(), &format!("gesture {label:?}"))?;
            }
        }
        // every label after the update: the model's, then the new ones in the order given
        let mut labels = self.labels.clone();
        for (l, _) in sets {
            if !labels.contains(l) {
                labels.push(l.clone());
            }
        }
        let branch = |l: &str| {
            (self.labels.iter().position(|x| x == l)).and_then(|g| self.branches[g].as_events())
        };
        let none: Vec<Demonstration> = Vec::new();
        let new_of = |l: &str| sets.iter().find(|(x, _)| x == l).map_or(&none, |(_, d)| d);
        let earlier: Vec<Vec<Vec<Vec<f64>>>> = labels
            .iter()
            .map(|l| branch(l).map(|b| b.kept_rows()).unwrap_or_default())
            .collect();
        if labels.len() > self.labels.len() {
            return self.relearned(first, &labels, &earlier, sets, progress);
        }
        let seed = first.config.params().seed;
        let taught = sets.iter().filter(|(_, d)| !d.is_empty()).count();
        let mut at = 0;
        // each gesture taught more goes on as a gesture alone does; the others stay as
        // they are
        let mut branches: Vec<EventsHsom> = Vec::with_capacity(labels.len());
        for (l, b) in labels.iter().zip(&self.branches) {
            let Some(b) = b.as_events() else {
                return Err(GestureError::NeedsEvents);
            };
            let new = new_of(l);
            let k = at;
            at += usize::from(!new.is_empty());
            let step = |done: usize, total: usize| {
                if let Some(p) = progress {
                    p(k * total + done, total * taught);
                }
            };
            let b = match new.is_empty() {
                true => Hsom::Events(Box::new(b.clone())),
                false => b.updated(new, Some(&step))?,
            };
            let Hsom::Events(b) = b else {
                return Err(GestureError::NeedsEvents);
            };
            branches.push(*b);
        }
        // recognition calibrated on every gesture's kept and new demonstrations
        let norm: Vec<Vec<Vec<Vec<f64>>>> = (labels.iter().zip(&earlier))
            .map(|(l, k)| {
                (k.iter().chain(new_of(l).iter().map(|d| &d.rows)))
                    .map(|rows| first.normalise_rows(rows))
                    .collect()
            })
            .collect();
        let calibration = calibrate(&branches, &norm, true, seed)?;
        Ok(GestureModel {
            labels,
            branches: branches
                .into_iter()
                .map(|b| Hsom::Events(Box::new(b)))
                .collect(),
            calibration,
            scoring: self.scoring,
        })
    }
}

impl GestureModel {
    /// [`GestureModel::update_labelled`] adding a gesture (`labels`: every label after it;
    /// `earlier`: each one's kept demonstrations, in the data's units): every gesture learned
    /// again at once from its kept and new demonstrations, as training at once on them does,
    /// in the units of all of them (the model's were its first gestures', which may not span
    /// the new one: a variable they held still has the scale of its noise), with each known
    /// gesture's record of what it learned from carried on.
    fn relearned(
        &self,
        first: &EventsHsom,
        labels: &[String],
        earlier: &[Vec<Vec<Vec<f64>>>],
        sets: &[(String, Vec<Demonstration>)],
        progress: Option<&dyn Fn(usize, usize)>,
    ) -> Result<GestureModel, GestureError> {
        let none: Vec<Demonstration> = Vec::new();
        let new_of = |l: &str| sets.iter().find(|(x, _)| x == l).map_or(&none, |(_, d)| d);
        let all: Vec<(String, Vec<Demonstration>)> = (labels.iter().zip(earlier))
            .map(|(l, kept)| {
                let mut demos: Vec<Demonstration> = (kept.iter())
                    .zip(kept_names(l, kept.len()))
                    .map(|(rows, source)| Demonstration {
                        source,
                        columns: first.columns.clone(),
                        time: None,
                        rows: rows.clone(),
                    })
                    .collect();
                demos.extend(new_of(l).iter().cloned());
                (l.clone(), demos)
            })
            .collect();
        let fit = Fit {
            progress,
            untrained: false,
        };
        let mut model = first.config.fit_labelled(&all, fit)?;
        for (l, b) in labels.iter().zip(&mut model.branches) {
            let Hsom::Events(b) = b else {
                return Err(GestureError::NeedsEvents);
            };
            let fresh: Vec<Vec<Vec<f64>>> = (new_of(l).iter())
                .map(|d| b.normalise_rows(&d.rows))
                .collect();
            let old = self.labels.iter().position(|x| x == l);
            if let Some(old) = old.and_then(|g| self.branches[g].as_events()) {
                (b.paths, b.kept) = old.remembered(&**b, &fresh, u32::from(!fresh.is_empty()));
            }
            b.kept.period = first.kept.period;
        }
        model.scoring = self.scoring;
        Ok(model)
    }
}

#[cfg(test)]
mod tests;
