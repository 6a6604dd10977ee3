//! Typed settings ([`HsomParams`], unchecked) and their validated form ([`HsomConfig`]).
//!
//! The settings both algorithms read are fields of [`HsomParams`]; those only one algorithm
//! reads live in its part of [`AlgorithmParams`], so a setting the chosen algorithm ignores
//! cannot be written down. The values the paper fixes and this implementation does not offer
//! to change (the retired settings of docs/CONFIG.md) are constants of the algorithm that
//! uses them.

use serde::{Deserialize, Serialize};

use crate::som::{Decay, Neighbourhood, Schedule, Topology};

use super::errors::ConfigError;

/// Short-term memory of each level (paper II; `algorithm = paper`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MemoryMode {
    /// CoSCo-HSOM: a fixed-size FIFO activity list of recent BMU IDs per level, updated in
    /// constant time.
    Lists,
    /// The sparse-code baseline the paper improves on (footnote 1): one activity level per
    /// node, set to 1 on the BMU and decreased linearly by 1/memory on every node each step;
    /// the level above learns the whole activity map.
    Levels,
}

/// How a predicted real-valued ID is turned into a node of the level below (paper III-C.2,
/// which names all three; `algorithm = paper`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum IdDecoding {
    /// Round each coordinate, clamped to the grid (the paper's first choice).
    Round,
    /// Floor each coordinate, clamped to the grid ("might need the floor of the ID").
    Floor,
    /// The node (among those used by the training data) nearest to the predicted position
    /// ("find the closest node").
    Nearest,
}

/// Which sequence model the levels above the bottom are (docs/ALGORITHM.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Algorithm {
    /// The paper's procedure: activity lists of node IDs (or activity levels), levels trained
    /// every updatePeriod^level steps on overlapping windows, predicted IDs decoded to nodes.
    Paper,
    /// The extension of docs/ALGORITHM.md: activity lists of events (a node and how long it was
    /// held), levels whose nodes tile `memory` consecutive events of the level below, lists
    /// encoded and predictions decoded by content, a learned begin and end, reproduction that
    /// climbs while its matches lie within what the level saw in training and follows a
    /// training demonstration until a level is surprised, executed at the learned tempo.
    Events,
}

impl Algorithm {
    /// The configuration's word for it: `paper` or `events`.
    pub fn name(self) -> String {
        crate::som::word(&self)
    }
}

/// Internal scaling of the bottom level's input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum Normalisation {
    /// Subtract each variable's minimum and divide all by one common scale, the largest
    /// range (keeps the data's geometry).
    Global,
    /// Scale each variable to [0, 1] on its own (amplifies near-constant variables).
    PerDimension,
    /// Raw values.
    None,
}

/// When a paper reproduction ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub enum StopRule {
    /// Stop on a node where training demonstrations ended, on a stationary posture, or past
    /// `lengthFactor` times the longest demonstration; all after
    /// [`PAPER_MIN_LENGTH_FRACTION`] of the shortest demonstration; `maxLength` always applies.
    Learned,
    /// Run exactly `maxLength` postures (the paper gives no end rule).
    MaxLength,
}

/// The `offset` of a configuration that omits it: `memory - 1`, at least 1.
pub(super) fn default_offset(memory: usize) -> usize {
    memory.saturating_sub(1).max(1)
}

/// The most levels a hierarchy may have.
pub(crate) const MAX_HEIGHT: usize = 16;

/// The paper algorithm's learned stop: no stop before this fraction of the shortest
/// demonstration's length.
pub const PAPER_MIN_LENGTH_FRACTION: f64 = 0.6;
/// The paper algorithm's learned stop: a posture that stayed this many steps within
/// [`PAPER_STATIONARY_TOLERANCE`] of its mean over those steps ends the reproduction.
pub const PAPER_STATIONARY_STEPS: usize = 60;
/// Radius of the stationarity test, in multiples of the bottom level's quantization error.
pub const PAPER_STATIONARY_TOLERANCE: f64 = 1.0;

/// Settings of one level of the hierarchy.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelParams {
    /// Grid rows.
    pub rows: usize,
    /// Grid columns.
    pub cols: usize,
    /// Grid topology.
    pub topology: Topology,
    /// Neighbourhood function.
    pub neighbourhood: Neighbourhood,
    /// Learning factor schedule over this level's own training steps.
    pub learning_factor: Schedule,
    /// Learning radius schedule (grid units) over this level's own training steps.
    pub learning_radius: Schedule,
}

impl LevelParams {
    /// A level with the documented defaults: learning factor `alpha` decaying exponentially
    /// to alpha/100, radius max(rows, cols)/2 decaying exponentially to 0.5 (or the initial
    /// radius when smaller), gaussian neighbourhood.
    pub fn new(rows: usize, cols: usize, topology: Topology, alpha: f64) -> Self {
        let r0 = (rows.max(cols) as f64 / 2.0).max(0.5);
        LevelParams {
            rows,
            cols,
            topology,
            neighbourhood: Neighbourhood::Gaussian,
            learning_factor: Schedule {
                initial: alpha,
                last: alpha / 100.0,
                decay: Decay::Exponential,
            },
            learning_radius: LevelParams::radius(r0),
        }
    }

    /// The default radius schedule from `r0`: decaying exponentially to 0.5 (or `r0` when
    /// smaller).
    pub(super) fn radius(r0: f64) -> Schedule {
        Schedule {
            initial: r0,
            last: 0.5f64.min(r0),
            decay: Decay::Exponential,
        }
    }
}

/// Reproduction settings both algorithms read.
#[derive(Debug, Clone, PartialEq)]
pub struct ReproductionParams {
    /// Maximum number of postures produced (the initial one included).
    pub max_length: usize,
    /// Highest level used to predict (levels above are still trained); `None` = all.
    pub max_level: Option<usize>,
    /// A reproduction ends at this factor times the longest demonstration's length (the
    /// paper's learned stop; the events algorithm's cap on its plan).
    pub length_factor: f64,
}

impl Default for ReproductionParams {
    fn default() -> Self {
        ReproductionParams {
            max_length: 2000,
            max_level: None,
            length_factor: 1.5,
        }
    }
}

/// The settings only the paper algorithm reads (`configs/table1.xml`).
#[derive(Debug, Clone, PartialEq)]
pub struct PaperParams {
    /// Level l is trained every updatePeriod^l steps.
    pub update_period: usize,
    /// Short-term memory encoding.
    pub memory_mode: MemoryMode,
    /// Entries a list must hold before the level above is used to predict (1..=memory).
    pub offset: usize,
    /// Decoding of predicted IDs.
    pub id_decoding: IdDecoding,
    /// When a reproduction ends.
    pub stop: StopRule,
}

/// The settings only the events algorithm reads (`configs/nao-gestures.xml`).
#[derive(Debug, Clone, PartialEq)]
pub struct EventsParams {
    /// Event hysteresis: a new bottom BMU begins an event only when its distance to the
    /// input is below this fraction of the current event's node's distance (1: on any
    /// change). The paper's value is 1.
    pub change_ratio: f64,
    /// The bottom level learns [S_t, S_t+h] with this h (the paper's is 1, the next state);
    /// the sample h steps ahead makes the direction of motion visible in the node even when
    /// consecutive samples are nearly equal.
    pub action_horizon: usize,
}

/// The settings of the chosen algorithm.
#[derive(Debug, Clone, PartialEq)]
pub enum AlgorithmParams {
    /// The paper's procedure.
    Paper(PaperParams),
    /// The events extension.
    Events(EventsParams),
}

/// All settings, as written (unchecked). Turn into a [`HsomConfig`] with [`HsomParams::check`].
#[derive(Debug, Clone, PartialEq)]
pub struct HsomParams {
    /// Seed of every random draw (same seed, bit-identical model).
    pub seed: u64,
    /// Number of levels; must equal `levels.len()`.
    pub height: usize,
    /// Size of each activity list (entries).
    pub memory: usize,
    /// Length of the state S_t (the number of variables of a demonstration).
    pub state_length: usize,
    /// Length of the action S_t+1 (must equal `state_length`).
    pub action_length: usize,
    /// Number of training steps (state-action pairs fed, cycling through the demonstrations).
    pub training_steps: usize,
    /// Input scaling of the bottom level.
    pub normalisation: Normalisation,
    /// Level settings, index 0 = bottom.
    pub levels: Vec<LevelParams>,
    /// Reproduction settings both algorithms read.
    pub reproduction: ReproductionParams,
    /// The sequence model of the upper levels and its own settings.
    pub algorithm: AlgorithmParams,
}

impl HsomParams {
    /// Which algorithm these settings are for.
    pub fn kind(&self) -> Algorithm {
        match self.algorithm {
            AlgorithmParams::Paper(_) => Algorithm::Paper,
            AlgorithmParams::Events(_) => Algorithm::Events,
        }
    }
    /// The paper algorithm's own settings (`None` under `algorithm = events`).
    pub fn paper(&self) -> Option<&PaperParams> {
        match &self.algorithm {
            AlgorithmParams::Paper(q) => Some(q),
            AlgorithmParams::Events(_) => None,
        }
    }
    /// The events algorithm's own settings (`None` under `algorithm = paper`).
    pub fn events(&self) -> Option<&EventsParams> {
        match &self.algorithm {
            AlgorithmParams::Events(q) => Some(q),
            AlgorithmParams::Paper(_) => None,
        }
    }
    /// The paper algorithm's own settings, to change (`None` under `algorithm = events`).
    pub fn paper_mut(&mut self) -> Option<&mut PaperParams> {
        match &mut self.algorithm {
            AlgorithmParams::Paper(q) => Some(q),
            AlgorithmParams::Events(_) => None,
        }
    }
    /// The events algorithm's own settings, to change (`None` under `algorithm = paper`).
    pub fn events_mut(&mut self) -> Option<&mut EventsParams> {
        match &mut self.algorithm {
            AlgorithmParams::Events(q) => Some(q),
            AlgorithmParams::Paper(_) => None,
        }
    }
    /// Level l trains every `update_period()`^l steps: the paper's `updatePeriod`; the events
    /// algorithm's levels tile `memory` entries of the level below.
    pub fn update_period(&self) -> usize {
        self.paper().map_or(self.memory, |q| q.update_period)
    }
    /// The short-term memory: the paper's `memoryMode`; activity lists for the events.
    pub fn memory_mode(&self) -> MemoryMode {
        self.paper().map_or(MemoryMode::Lists, |q| q.memory_mode)
    }
    /// The event hysteresis: the events algorithm's `changeRatio`; 1 (the paper's) otherwise.
    pub fn change_ratio(&self) -> f64 {
        self.events().map_or(1.0, |q| q.change_ratio)
    }
    /// The bottom's action horizon: the events algorithm's `actionHorizon`; 1 (the paper's
    /// next state) otherwise.
    pub fn action_horizon(&self) -> usize {
        self.events().map_or(1, |q| q.action_horizon)
    }
    /// The paper algorithm's `offset`; `memory - 1` (at least 1) for the events, which
    /// predict from any number of entries.
    pub fn offset(&self) -> usize {
        self.paper()
            .map_or(default_offset(self.memory), |q| q.offset)
    }

    /// Validate every value; `source` (a file name) is used in the error messages.
    pub fn check(self, source: &str) -> Result<HsomConfig, ConfigError> {
        let need = |ok: bool, field: &str, value: &dyn ToString, reason: &str| match ok {
            true => Ok(()),
            false => Err(ConfigError::Invalid {
                file: source.into(),
                field: field.into(),
                value: value.to_string(),
                reason: reason.into(),
            }),
        };
        let int = |field: &str, v: usize, lo: usize, hi: usize| {
            let reason = format!("expected an integer in {lo}..={hi}");
            need((lo..=hi).contains(&v), field, &v, &reason)
        };
        let fraction = "expected a number in (0, 1]";
        int("height", self.height, 1, MAX_HEIGHT)?;
        int("memory", self.memory, 1, 256)?;
        int("stateLength", self.state_length, 1, 4096)?;
        int("actionLength", self.action_length, 1, 4096)?;
        let (state, action) = (self.state_length, self.action_length);
        let reason = format!(
            "the action is the next state, so actionLength must equal stateLength ({state})"
        );
        need(action == state, "actionLength", &action, &reason)?;
        int("trainingSteps", self.training_steps, 1, 1_000_000_000)?;
        if let Some(q) = self.paper() {
            int("updatePeriod", q.update_period, 1, 1024)?;
            let top = (q.update_period as f64).powi(self.height as i32 - 1);
            let reason = format!("updatePeriod^(height-1) = {top:e} is too large");
            need(top <= 1e12, "updatePeriod", &q.update_period, &reason)?;
            let reason = format!("expected 1..=memory ({})", self.memory);
            let offset_ok = (1..=self.memory).contains(&q.offset);
            need(offset_ok, "reproduction/offset", &q.offset, &reason)?;
        }
        let listed = self.levels.len();
        let reason = format!("height must equal the number of <level> elements ({listed})");
        need(listed == self.height, "height", &self.height, &reason)?;
        for (i, l) in self.levels.iter().enumerate() {
            let f = |name: &str| format!("levels/level[{i}]/{name}");
            int(&f("rows"), l.rows, 1, 1024)?;
            int(&f("cols"), l.cols, 1, 1024)?;
            let (factor, radius) = (l.learning_factor, l.learning_radius);
            let positive = "expected a positive number";
            for (name, s, max, reason) in [
                ("learningFactor", factor, 1.0, fraction),
                ("learningRadius", radius, 1e6, positive),
            ] {
                for (suffix, v) in [("", s.initial), ("Final", s.last)] {
                    let field = f(&format!("{name}{suffix}"));
                    need(v > 0.0 && v <= max, &field, &v, reason)?;
                }
            }
        }
        let mut weights: u64 = 0;
        for (i, l) in self.levels.iter().enumerate() {
            let dim = if i == 0 {
                (2 * self.state_length) as u64
            } else if self.kind() == Algorithm::Events {
                // context (posture, begin, phase) + memory slots (two postures, duration, end)
                (self.state_length + 2 + self.memory * (2 * self.state_length + 2)) as u64
            } else {
                match self.memory_mode() {
                    MemoryMode::Lists => 2 * self.memory as u64,
                    MemoryMode::Levels => {
                        (self.levels[i - 1].rows * self.levels[i - 1].cols) as u64
                    }
                }
            };
            weights += (l.rows * l.cols) as u64 * dim;
        }
        let reason = "the hierarchy would hold more than 100 million weights; use smaller maps";
        let count = format!("{weights} weights");
        need(weights <= 100_000_000, "levels", &count, reason)?;
        if let Some(q) = self.events() {
            let c = q.change_ratio;
            need(c > 0.0 && c <= 1.0, "changeRatio", &c, fraction)?;
            int("actionHorizon", q.action_horizon, 1, 100_000)?;
        }
        let r = &self.reproduction;
        int("reproduction/maxLength", r.max_length, 1, 10_000_000)?;
        let (factor, reason) = (r.length_factor, "expected a number in [0.01, 1000]");
        let factor_ok = (0.01..=1000.0).contains(&factor);
        need(factor_ok, "reproduction/lengthFactor", &factor, reason)?;
        if let Some(m) = r.max_level {
            int("reproduction/maxLevel", m, 0, self.height - 1)?;
        }
        Ok(HsomConfig {
            params: self,
            source: source.to_string(),
        })
    }
}

/// A validated configuration: the only way to train a hierarchy
/// ([`HsomConfig::fit`](crate::hsom) lives in the `hsom` room).
#[derive(Debug, Clone)]
pub struct HsomConfig {
    params: HsomParams,
    source: String,
}

/// Two configurations are equal when their settings are (wherever they were read from).
impl PartialEq for HsomConfig {
    fn eq(&self, other: &Self) -> bool {
        self.params == other.params
    }
}

impl HsomConfig {
    /// The checked settings.
    pub fn params(&self) -> &HsomParams {
        &self.params
    }
    /// Where the configuration came from (file name), for messages.
    pub fn source(&self) -> &str {
        &self.source
    }
    /// Back to unchecked settings (to change a value and check again).
    pub fn into_params(self) -> HsomParams {
        self.params
    }
    /// update_period^level, the training period of `level`.
    pub fn period(&self, level: usize) -> u64 {
        (self.params.update_period() as u64).pow(level as u32)
    }
    /// The same configuration with its lowest `height` levels (`levels` truncated). A height
    /// above the configuration's own, or 0, is an error naming both: levels cannot be made
    /// up; so is a `maxLevel` the new height does not have.
    pub fn at_height(&self, height: usize) -> Result<HsomConfig, ConfigError> {
        let mut p = self.params.clone();
        if height == 0 || height > p.levels.len() {
            return Err(ConfigError::Invalid {
                file: self.source.clone(),
                field: "height".into(),
                value: height.to_string(),
                reason: format!(
                    "a height override from 1 to the configuration's own {} levels",
                    p.levels.len()
                ),
            });
        }
        p.levels.truncate(height);
        p.height = height;
        p.check(&format!("{} (at height {height})", self.source))
    }
    /// The same configuration for data of `width` variables: `stateLength` and
    /// `actionLength` set to `width` (the rest unchanged and checked again), as the
    /// configuration is adapted to data other than the arm's six joints.
    pub fn for_width(&self, width: usize) -> Result<HsomConfig, ConfigError> {
        let mut p = self.params.clone();
        p.state_length = width;
        p.action_length = width;
        p.check(&format!(
            "{} (stateLength {width} from the data)",
            self.source
        ))
    }
}
