//! What `cosco inspect` and the reports show of a model: its levels, their sizes and quality,
//! and which of them reproduction plans from.

use crate::config::MemoryMode;
use crate::som::Topology;

use super::model::{EventsModel, Model, Part};

/// Quality of one level, as reported by [`Hsom::summary`].
#[derive(Debug, Clone, PartialEq)]
pub struct LevelSummary {
    /// Level index (0 = bottom).
    pub level: usize,
    /// Grid rows.
    pub rows: usize,
    /// Grid columns.
    pub cols: usize,
    /// Topology.
    pub topology: Topology,
    /// Input (weight vector) length.
    pub input_dim: usize,
    /// Training period (updatePeriod^level).
    pub period: u64,
    /// Times the level was trained.
    pub trained: u64,
    /// Nodes that are the BMU of some training input.
    pub nodes_used: usize,
    /// Mean distance from each training input to its BMU (level 0: in the data's units
    /// unless normalisation is perDimension; upper levels: in grid cells of the level below).
    pub quantization_error: f64,
    /// Fraction of training inputs whose two best nodes are not adjacent.
    pub topographic_error: f64,
    /// Fraction of the next entries of the level below predicted exactly from the partial
    /// list on the training data (0 for the bottom level).
    pub prediction_accuracy: f64,
    /// The same fraction for a lookup table of "next entry given the last entry" of the level
    /// below, counted on the same training data (the baseline the level must beat).
    pub lookup_accuracy: f64,
    /// `prediction_accuracy` held out (`algorithm = events`): on each training
    /// demonstration's entries, by the levels above the bottom trained on the other
    /// demonstrations (the in-sample figure with one demonstration; 0 with the paper's
    /// algorithm).
    pub heldout_prediction_accuracy: f64,
    /// `lookup_accuracy` held out the same way: the lookup table counted on the other
    /// demonstrations, scored on the held-out one.
    pub heldout_lookup_accuracy: f64,
    /// Whether reproduction may plan from this level ([`Hsom::level_trusted`]).
    pub used_in_reproduction: bool,
}

/// How `cosco inspect` and the reports say whether reproduction plans from `level`: `-` for
/// the bottom, `yes` or `no` above it.
pub fn plans_word(level: usize, used_in_reproduction: bool) -> &'static str {
    match (level, used_in_reproduction) {
        (0, _) => "-",
        (_, true) => "yes",
        (_, false) => "no",
    }
}

/// What `cosco inspect` shows: the levels, their sizes and quality.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelSummary {
    /// Short-term memory mode.
    pub memory_mode: MemoryMode,
    /// memory (list length).
    pub memory: usize,
    /// updatePeriod.
    pub update_period: usize,
    /// stateLength.
    pub state_length: usize,
    /// Number of weights over all levels.
    pub weights: usize,
    /// Shortest, mean and longest training demonstration (samples).
    pub demo_lengths: [f64; 3],
    /// Shortest, mean and longest training demonstration in bottom events (runs of the
    /// bottom BMU).
    pub demo_events: [f64; 3],
    /// One entry per level, bottom first.
    pub levels: Vec<LevelSummary>,
}

impl std::fmt::Display for ModelSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "CoSCo-HSOM: {} levels, memory {} ({:?}), updatePeriod {}, stateLength {}, {} weights",
            self.levels.len(),
            self.memory,
            self.memory_mode,
            self.update_period,
            self.state_length,
            self.weights
        )?;
        writeln!(
            f,
            "training demonstrations: {:.0} to {:.0} samples (mean {:.1})",
            self.demo_lengths[0], self.demo_lengths[2], self.demo_lengths[1]
        )?;
        writeln!(
            f,
            "bottom events per demonstration: {:.0} to {:.0} (mean {:.1})",
            self.demo_events[0], self.demo_events[2], self.demo_events[1]
        )?;
        writeln!(
            f,
            "level  size     topology    input  period  trained  used    QE        TE       acc    lookup  acc-ho lookup-ho plans"
        )?;
        for l in self.levels.iter().rev() {
            writeln!(
                f,
                "{:<6} {:<8} {:<11} {:<6} {:<7} {:<8} {:<7} {:<9.4} {:<8.4} {:<6.3} {:<7.3} {:<6.3} {:<9.3} {}",
                l.level,
                format!("{}x{}", l.rows, l.cols),
                l.topology.name(),
                l.input_dim,
                l.period,
                l.trained,
                l.nodes_used,
                l.quantization_error,
                l.topographic_error,
                l.prediction_accuracy,
                l.lookup_accuracy,
                l.heldout_prediction_accuracy,
                l.heldout_lookup_accuracy,
                plans_word(l.level, l.used_in_reproduction)
            )?;
        }
        Ok(())
    }
}

impl<A: Part> Model<A> {
    /// Levels, sizes, node usage, quantization and topographic error per level (computed on
    /// the training data when the model was trained).
    pub(crate) fn summary(&self) -> ModelSummary {
        let p = self.config.params();
        // the events extension's held-out figures (0 with the paper's algorithm)
        let held_out = |f: fn(&EventsModel) -> &Vec<f64>, l: usize| {
            self.part
                .events()
                .and_then(|e| f(e).get(l).copied())
                .unwrap_or(0.0)
        };
        ModelSummary {
            memory_mode: p.memory_mode(),
            memory: p.memory,
            update_period: p.update_period(),
            state_length: p.state_length,
            weights: self.maps.iter().map(|m| m.all_weights().len()).sum(),
            demo_lengths: self.demo_len,
            demo_events: self.demo_runs,
            levels: self
                .maps
                .iter()
                .enumerate()
                .map(|(l, m)| LevelSummary {
                    level: l,
                    rows: m.rows(),
                    cols: m.cols(),
                    topology: m.topology(),
                    input_dim: m.dim(),
                    period: self.config.period(l),
                    trained: self.trained[l],
                    nodes_used: self.hits[l].iter().filter(|&&h| h > 0).count(),
                    quantization_error: self.qe[l],
                    topographic_error: self.te[l],
                    prediction_accuracy: self.accuracy.get(l).copied().unwrap_or(0.0),
                    lookup_accuracy: self.lookup.get(l).copied().unwrap_or(0.0),
                    heldout_prediction_accuracy: held_out(|e| &e.heldout_accuracy, l),
                    heldout_lookup_accuracy: held_out(|e| &e.heldout_lookup, l),
                    used_in_reproduction: self.level_trusted(l),
                })
                .collect(),
        }
    }

    /// Whether reproduction may plan from level `l` (`algorithm = events`): level 1 always
    /// (the lowest level with a sequence); a level above only if it and every level between
    /// it and level 1, on their own training data, predicted the next entry of the level
    /// below more often than the lookup table of "next entry given the last one" counted on
    /// the same data (docs/ALGORITHM.md, section 3.5). Always true with the paper's algorithm
    /// and for the bottom.
    pub(crate) fn level_trusted(&self, l: usize) -> bool {
        if A::ALGORITHM != crate::config::Algorithm::Events {
            return true;
        }
        (2..=l).all(|k| {
            self.accuracy.get(k).copied().unwrap_or(0.0)
                > self.lookup.get(k).copied().unwrap_or(0.0)
        })
    }
}
