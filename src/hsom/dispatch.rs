//! What a caller does with an [`Hsom`], whichever its algorithm: each operation handed to the
//! model of that algorithm in one `match`. What only the events extension does (continuing a
//! prefix, resuming) is refused for a model of the paper's algorithm.

use crate::condition::{self, Conditions};
use crate::config::HsomConfig;
use crate::demos::Demonstration;
use crate::som::SelfOrganizingMap;

use super::errors::HsomError;
use super::model::{EventsHsom, Hsom};
use super::persist::FilePart;
use super::reproduction::Reproduction;
use super::summary::ModelSummary;

/// `$e` with `$m` the model of either algorithm.
macro_rules! either {
    ($self:expr, $m:ident => $e:expr) => {
        match $self {
            Hsom::Paper($m) => $e,
            Hsom::Events($m) => $e,
        }
    };
}

impl Hsom {
    /// The events extension's model (`None` for the paper's algorithm).
    pub(crate) fn as_events(&self) -> Option<&EventsHsom> {
        match self {
            Hsom::Events(m) => Some(m),
            Hsom::Paper(_) => None,
        }
    }

    /// The events extension's model, or the error saying `what` needs it.
    fn events_for(&self, what: &str) -> Result<&EventsHsom, HsomError> {
        self.as_events().ok_or_else(|| HsomError::NeedsEvents {
            what: what.into(),
            algorithm: "paper".into(),
        })
    }

    /// The validated configuration the model was trained with.
    pub fn config(&self) -> &HsomConfig {
        either!(self, m => &m.config)
    }
    /// The maps, bottom first.
    pub fn maps(&self) -> &[SelfOrganizingMap] {
        either!(self, m => &m.maps)
    }
    /// Times each level was trained (bottom first).
    pub fn trained_counts(&self) -> &[u64] {
        either!(self, m => &m.trained)
    }
    /// Number of levels.
    pub fn height(&self) -> usize {
        self.maps().len()
    }
    /// Per level (>= 1): the fraction of the entries of the level below that the level
    /// predicted exactly from the partial list when the training data were replayed (0 for
    /// the bottom level or without lists).
    pub fn prediction_accuracy(&self) -> &[f64] {
        either!(self, m => &m.accuracy)
    }
    /// Names of the variables (the demonstrations' columns; `x0`, `x1`, ... when trained on
    /// plain series).
    pub fn columns(&self) -> &[String] {
        either!(self, m => &m.columns)
    }
    /// Levels, sizes, node usage, quantization and topographic error per level (computed on
    /// the training data when the model was trained).
    pub fn summary(&self) -> ModelSummary {
        either!(self, m => m.summary())
    }
    /// Whether reproduction may plan from level `l`: level 1 always (the lowest level with
    /// a sequence); with the events extension, a level above only if it and every level
    /// between it and level 1 beat their lookup tables on their training data
    /// (docs/ALGORITHM.md, section 3.5). Always true with the paper's algorithm and for the
    /// bottom.
    pub fn level_trusted(&self, l: usize) -> bool {
        either!(self, m => m.level_trusted(l))
    }

    /// Reproduce the learned gesture from `initial` (a posture of `stateLength` values, in the
    /// data's units) with the configuration's reproduction settings.
    pub fn reproduce(&self, initial: &[f64]) -> Result<Reproduction, HsomError> {
        either!(self, m => m.reproduce(initial))
    }
    /// Reproduce from `initial` through the via-points of `conditions` and to their goal: the
    /// reproduction re-timed and bent onto them ([`condition::meet`]; docs/ALGORITHM.md,
    /// section 9), each met exactly as [`crate::curve::at_phase`] reads it. With `ranges` (per
    /// variable, its lowest and highest value) the conditions are checked against them and
    /// the bend leaves none. The conditions are checked first.
    pub fn reproduce_conditioned(
        &self,
        initial: &[f64],
        conditions: &Conditions,
        ranges: Option<&[(f64, f64)]>,
    ) -> Result<Reproduction, HsomError> {
        conditions.check(self.columns(), ranges, initial)?;
        let mut rep = self.reproduce(initial)?;
        rep.postures = condition::meet(&rep.postures, &conditions.points(), ranges)?;
        Ok(rep)
    }
    /// The central 95 % band about `rows` (a reproduction of this model), pinned at its start
    /// and at the phases `pinned` where it was conditioned ([`crate::condition::spread_band`]
    /// over the training demonstrations the model keeps); `None` with fewer than 2 of them.
    pub fn band(
        &self,
        rows: &[Vec<f64>],
        pinned: &[f64],
    ) -> Option<crate::condition::ConfidenceBand> {
        either!(self, m => m.band(rows, pinned))
    }
    /// The demonstration through the bottom level's own code and back: the ceiling of what
    /// the hierarchy can reproduce of it (docs/ALGORITHM.md, section 3.6).
    pub fn reencode(&self, demo: &Demonstration) -> Result<Reproduction, HsomError> {
        either!(self, m => m.reencode(demo))
    }
    /// The *nearest-sequence* baseline (docs/ALGORITHM.md, section 3.6): of `demos`, the one
    /// whose first posture is nearest `initial`, its bottom events executed from `initial`
    /// exactly as a reproduction's planned events are.
    pub fn follow_nearest(
        &self,
        demos: &[Demonstration],
        initial: &[f64],
    ) -> Result<Reproduction, HsomError> {
        either!(self, m => m.follow_nearest(demos, initial))
    }
    /// The nearest-sequence baseline for a prefix: of `demos`, the one along which `prefix`
    /// runs closest, its bottom events after where the prefix ends along it.
    pub fn follow_nearest_from(
        &self,
        demos: &[Demonstration],
        prefix: &[Vec<f64>],
    ) -> Result<Reproduction, HsomError> {
        either!(self, m => m.follow_nearest_from(demos, prefix))
    }
    /// Continue a gesture from its first samples (docs/ALGORITHM.md, section 3.10). Needs
    /// `algorithm = events`.
    pub fn continue_events(&self, prefix: &[Vec<f64>]) -> Result<Reproduction, HsomError> {
        self.events_for("continuing a prefix")?
            .continue_events(prefix)
    }
    /// Resume this model's own reproduction from `initial` after part of it was executed,
    /// `reading` being what the encoders read meanwhile (docs/ALGORITHM.md, section 3.10).
    /// Needs `algorithm = events`.
    pub fn resume(&self, initial: &[f64], reading: &[Vec<f64>]) -> Result<Reproduction, HsomError> {
        self.events_for("resuming a reproduction")?
            .resume(initial, reading)
    }

    /// The binary file's bytes by part, in file order grouped by what they hold; they add up
    /// to the file's length (docs/BENCHMARKS.md, "The model file").
    pub fn file_parts(&self) -> Vec<FilePart> {
        either!(self, m => m.file_parts())
    }
    /// The most bytes the traced chunks may take in the binary form: every node of every
    /// traced level with all its chunks, a bound set by the configuration alone (0 for the
    /// paper's algorithm).
    pub fn traced_ceiling(&self) -> usize {
        self.as_events().map_or(0, |m| m.traced_ceiling())
    }
    /// Every shape and value of a model read from a file ([`super::model::Model::check`]).
    pub(crate) fn check(&self) -> Result<(), String> {
        either!(self, m => m.check())
    }
}
