//! Typed settings ([`HsomParams`], unchecked) and their validated form ([`HsomConfig`]).

use crate::som::{Decay, Neighbourhood, Schedule, Topology};

use super::errors::ConfigError;

/// Short-term memory of each level (paper II).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MemoryMode {
    /// CoSCo-HSOM: a fixed-size FIFO activity list of recent BMU IDs per level, updated in
    /// constant time (the default).
    Lists,
    /// The sparse-code baseline the paper improves on (footnote 1): one activity level per
    /// node, set to 1 on the BMU and decreased linearly by 1/memory on every node each step;
    /// the level above learns the whole activity map.
    Levels,
}

/// How a predicted real-valued ID is turned into a node of the level below (paper III-C.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IdDecoding {
    /// Round each coordinate, clamped to the grid (the paper's first choice; the default).
    Round,
    /// Floor each coordinate, clamped to the grid ("might need the floor of the ID").
    Floor,
    /// The node (among those used by the training data) nearest to the predicted position.
    Nearest,
}

/// How a level above the bottom trains while the list below is not yet full (at the start of
/// every demonstration, since lists are cleared between demonstrations).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PartialTraining {
    /// Do not train nor push until the list below is full (the default).
    Skip,
    /// Train on the known slots only (unknown slots are ignored in matching and update).
    Masked,
}

/// When the bottom level's activity list is updated (and so when the schedule of the upper
/// levels advances), in training and in reproduction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ListUpdate {
    /// Push the bottom BMU at every step (the paper taken literally): with densely sampled
    /// data the list fills with repeats of the same node.
    EveryStep,
    /// Push the bottom BMU only when it differs from the newest entry, so the lists hold
    /// sequences of distinct key postures; how long each node lasts is learned per node
    /// (its dwell) and restored in reproduction with `timing = dwell`.
    OnChange,
}

/// What the bottom level does when no level above can predict (paper III-C.2's reflex).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reflex {
    /// The BMU of the current posture (state half) is executed (the paper's reflex).
    Bmu,
    /// The node that most often followed the node just executed in the training
    /// demonstrations (its learned successor; the BMU when it has none, the nearest node
    /// that has one when the BMU is the node just executed): the reflex follows the learned
    /// sequence of key postures and leaves a still initial posture.
    Successor,
}

/// How many postures an executed bottom node produces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Timing {
    /// One posture per executed node (the paper).
    Step,
    /// The learned dwell of the node (mean number of consecutive steps it was the BMU in the
    /// training demonstrations, idle start and end excluded): the posture moves linearly
    /// from the current one to the node's output over that many steps.
    Dwell,
    /// The learned speed of the node (mean distance between consecutive samples while it
    /// was the BMU): the posture moves linearly to the node's output at that speed, so the
    /// pace is kept even when nodes are skipped; nodes without a speed use their dwell.
    Speed,
}

/// Which sequence model the levels above the bottom are (docs/ALGORITHM.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    /// The paper's procedure: activity lists of node IDs, levels trained every
    /// updatePeriod^level steps on overlapping windows, IDs decoded by rounding (the default).
    Paper,
    /// The extension of docs/ALGORITHM.md: activity lists of events (a node and how long it was
    /// held), levels whose nodes tile `memory` consecutive events of the level below, lists
    /// encoded and predictions decoded by content, a learned begin and end, reproduction that
    /// climbs while its matches lie within what the level saw in training and re-plans on
    /// surprise, executed at the learned tempo.
    Events,
}

/// Internal scaling of the bottom level's input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Normalisation {
    /// Subtract each variable's minimum and divide all by one common scale, the largest
    /// range (keeps the data's geometry; the default).
    Global,
    /// Scale each variable to [0, 1] on its own (amplifies near-constant variables).
    PerDimension,
    /// Raw values.
    None,
}

/// How the events extension's consensus (where each bottom node's events are placed)
/// weighs the other demonstrations at each sample (docs/ALGORITHM.md, passage 6).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Consensus {
    /// Every demonstration alike: the mean of the samples aligned to this one.
    All,
    /// The demonstrations that agree here: each other demonstration's aligned sample
    /// weighted by how far it is, relative to the nearest one (for demonstrations of several
    /// modes: different routes from different starts).
    Local,
    /// Every demonstration alike where it is learned, and at reproduction each training
    /// demonstration's placement weighted by how near its first posture is to the
    /// reproduction's (a Gaussian of that distance, its width chosen by leave-one-out on the
    /// training demonstrations, and used only where the starts predict the placements better
    /// than shuffled starts do: otherwise, and with three demonstrations or fewer, `All`).
    /// The default.
    Start,
}

impl std::str::FromStr for Consensus {
    type Err = String;
    /// `all`, `local` or `start`, in any case; otherwise a message naming the word and both values.
    fn from_str(word: &str) -> Result<Self, String> {
        match word.to_ascii_lowercase().as_str() {
            "all" => Ok(Consensus::All),
            "local" => Ok(Consensus::Local),
            "start" => Ok(Consensus::Start),
            _ => Err(format!("consensus {word:?}: one of all, local, start")),
        }
    }
}

/// How the events extension reads one demonstration along another for the consensus
/// (docs/ALGORITHM.md, passage 6, "A consensus without stairs"): DTW aligns them sample to
/// sample, and where one is slower, a run of its samples is aligned to one sample of the
/// other.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Alignment {
    /// Each sample takes the mean of the samples aligned to it: a run aligned to one sample
    /// all take that sample (the warp's stairs). The default.
    Stepped,
    /// The warp's stairs replaced by the line through their middles, the other
    /// demonstration read between its samples (linearly): a run aligned to one sample
    /// moves on through it at an even pace.
    Smooth,
}

impl Alignment {
    /// The configuration's word for it: `stepped` or `smooth`.
    pub fn name(self) -> &'static str {
        match self {
            Alignment::Stepped => "stepped",
            Alignment::Smooth => "smooth",
        }
    }
}

impl std::str::FromStr for Alignment {
    type Err = String;
    /// `stepped` or `smooth`, in any case; otherwise a message naming the word and both
    /// values.
    fn from_str(word: &str) -> Result<Self, String> {
        match word.to_ascii_lowercase().as_str() {
            "stepped" => Ok(Alignment::Stepped),
            "smooth" => Ok(Alignment::Smooth),
            _ => Err(format!("alignment {word:?}: one of stepped, smooth")),
        }
    }
}

/// Where a traced plan's events put their knots, the postures the executed curve passes
/// through (docs/ALGORITHM.md, passage 6, "Two knots per event"; `plan = traced` only: a
/// decoded event has no place of its own in the consensus).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Knots {
    /// One knot per event, at its middle, where the event lies in the consensus. The
    /// default.
    Event,
    /// Two knots per event of four samples or more (two per half), at a quarter and three
    /// quarters of its duration, each where that half of the event lies in the consensus: a
    /// swing shorter than two events keeps its turn.
    Halves,
}

impl Knots {
    /// The configuration's word for it: `event` or `halves`.
    pub fn name(self) -> &'static str {
        match self {
            Knots::Event => "event",
            Knots::Halves => "halves",
        }
    }
}

impl std::str::FromStr for Knots {
    type Err = String;
    /// `event` or `halves`, in any case; otherwise a message naming the word and both
    /// values.
    fn from_str(word: &str) -> Result<Self, String> {
        match word.to_ascii_lowercase().as_str() {
            "event" => Ok(Knots::Event),
            "halves" => Ok(Knots::Halves),
            _ => Err(format!("knots {word:?}: one of event, halves")),
        }
    }
}

/// How the events extension turns the levels' prediction into a plan of bottom events
/// (docs/ALGORITHM.md, passage 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plan {
    /// The demonstrated stretch the predicting node stands for: of the training chunks the
    /// node was the BMU of, the one whose demonstration was nearest where the reproduction is,
    /// replayed event by event, and continued along the same demonstration until a level is
    /// surprised.
    Traced,
    /// Every predicted slot decoded by content, level by level (among the followers of the
    /// entry before, the node's exemplar first). The default.
    Decoded,
}

impl std::str::FromStr for Plan {
    type Err = String;
    /// `traced` or `decoded`, in any case; otherwise a message naming the word and both values.
    fn from_str(word: &str) -> Result<Self, String> {
        match word.to_ascii_lowercase().as_str() {
            "traced" => Ok(Plan::Traced),
            "decoded" => Ok(Plan::Decoded),
            _ => Err(format!("plan {word:?}: one of traced, decoded")),
        }
    }
}

/// The reproduction procedure (paper III-C.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReproductionMode {
    /// The paper's procedure taken literally: the highest level whose lower list holds
    /// `offset` entries predicts every unknown slot, each expanded in full, depth-first,
    /// oldest first.
    Literal,
    /// Predict one entry of the level below at a time, at the time step it is due by the
    /// training schedule, and expand it only into the bottom steps it adds (its newest
    /// updatePeriod^(l-1) steps), so that overlapping windows are not replayed twice
    /// (the default; see docs/ALGORITHM.md).
    Strided,
}

/// When a reproduction ends.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopRule {
    /// Stop on a node where training demonstrations ended, on a stationary posture, or past
    /// `lengthFactor` times the longest demonstration; all after `minLengthFraction` of the
    /// shortest demonstration (the default); `maxLength` always applies.
    Learned,
    /// Run exactly `maxLength` postures.
    MaxLength,
}

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
            learning_radius: Schedule {
                initial: r0,
                last: 0.5f64.min(r0),
                decay: Decay::Exponential,
            },
        }
    }
}

/// Settings of the reproduction phase.
#[derive(Debug, Clone, PartialEq)]
pub struct ReproductionParams {
    /// Entries a list must hold before the level above is used to predict (1..=memory).
    pub offset: usize,
    /// Procedure.
    pub mode: ReproductionMode,
    /// Decoding of predicted IDs.
    pub id_decoding: IdDecoding,
    /// Replace a decoded node never used by the training data by the nearest used one.
    pub unseen_fallback: bool,
    /// Maximum number of postures produced (the initial one included).
    pub max_length: usize,
    /// When to stop.
    pub stop: StopRule,
    /// No learned stop before this fraction of the shortest demonstration's length.
    pub min_length_fraction: f64,
    /// Learned stop when the posture comes within this many bottom quantization errors of
    /// the action half of a node on which a training demonstration ended (0: only when that
    /// node is executed or nearest).
    pub end_tolerance: f64,
    /// Learned stop at this factor times the longest demonstration's length.
    pub length_factor: f64,
    /// Learned stop once the posture has stayed for this many steps within
    /// `stationary_tolerance` of its mean over those steps.
    pub stationary_steps: usize,
    /// Radius of the stationarity test, in multiples of the bottom level's quantization
    /// error (0: the posture must not change at all).
    pub stationary_tolerance: f64,
    /// A level is "confused" (not used to predict) when the root-mean-square distance, per
    /// known coordinate, between its best node and the known entries exceeds this many grid
    /// cells; 0 disables the test.
    pub confusion_threshold: f64,
    /// Highest level used to predict (levels above are still trained); `None` = all.
    pub max_level: Option<usize>,
    /// How much of the current posture's offset from the executed node's state half is
    /// carried into the next posture: next = action + continuity (current - state). 0 snaps
    /// to the node's action half (the paper's literal output); 1 applies the node's
    /// displacement (action - state) to the current posture.
    pub continuity: f64,
    /// Record in the bottom activity list the node that best matches the executed transition
    /// [current, next] (as in training), instead of the node that was predicted.
    pub closed_loop: bool,
    /// A level whose measured prediction accuracy (the fraction of next entries of the level
    /// below it predicted exactly when the training data were replayed) is below this is
    /// "confused" and not used; 0 disables the test.
    pub min_accuracy: f64,
    /// The bottom reflex.
    pub reflex: Reflex,
    /// Postures per executed bottom node.
    pub timing: Timing,
    /// Loop breaking: a bottom node about to be executed that is already among the last
    /// `loop_window` executed bottom nodes `loop_visits` times marks a loop; the learned
    /// successor (of the newest recent node whose successor is not among them) is executed
    /// instead. 0 disables it (the paper executes what the hierarchy predicts).
    pub loop_visits: usize,
    /// Number of most recently executed bottom nodes looked at by `loop_visits`.
    pub loop_window: usize,
    /// Successors that remember revisits: on the first execution of a bottom node that the
    /// demonstrations revisited, the successor reflex takes the transition that came first in
    /// the demonstrations (among the equally frequent ones), and the loop breaker, when no
    /// recent node's successor leaves the cycle, takes the transition that came last. false:
    /// one successor per node.
    pub revisit_successors: bool,
}

impl Default for ReproductionParams {
    fn default() -> Self {
        ReproductionParams {
            offset: 3,
            mode: ReproductionMode::Literal,
            id_decoding: IdDecoding::Round,
            unseen_fallback: true,
            max_length: 2000,
            stop: StopRule::Learned,
            min_length_fraction: 0.6,
            length_factor: 1.5,
            end_tolerance: 0.0,
            stationary_steps: 60,
            stationary_tolerance: 1.0,
            confusion_threshold: 0.0,
            max_level: None,
            continuity: 0.85,
            closed_loop: true,
            min_accuracy: 0.0,
            reflex: Reflex::Bmu,
            timing: Timing::Step,
            loop_visits: 0,
            loop_window: 24,
            revisit_successors: false,
        }
    }
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
    /// Level l is trained every updatePeriod^l steps.
    pub update_period: usize,
    /// Length of the state S_t (the number of variables of a demonstration).
    pub state_length: usize,
    /// Length of the action S_t+1 (must equal `state_length`).
    pub action_length: usize,
    /// Number of training steps (state-action pairs fed, cycling through the demonstrations).
    pub training_steps: usize,
    /// Short-term memory encoding.
    pub memory_mode: MemoryMode,
    /// Input scaling of the bottom level.
    pub normalisation: Normalisation,
    /// How the consensus weighs the demonstrations (`algorithm = events`).
    pub consensus: Consensus,
    /// How the consensus reads one demonstration along another (`algorithm = events`).
    pub alignment: Alignment,
    /// How the levels' prediction becomes a plan (`algorithm = events`).
    pub plan: Plan,
    /// Where a traced plan's events put their knots (`plan = traced`).
    pub knots: Knots,
    /// Training of upper levels on partially filled lists.
    pub partial_training: PartialTraining,
    /// When the bottom activity list is updated.
    pub list_update: ListUpdate,
    /// With `OnChange`: a new bottom BMU replaces the newest entry only when its distance to
    /// the input is below this fraction of the newest entry's distance (1: on any change).
    pub change_ratio: f64,
    /// The bottom level learns [S_t, S_t+h] with this h (1: the paper's next state); the
    /// sample h steps ahead makes the direction of motion visible in the node even when
    /// consecutive samples are nearly equal. Reproduction uses S_t + (S_t+h - S_t) / h.
    pub action_horizon: usize,
    /// The sequence model of the upper levels.
    pub algorithm: Algorithm,
    /// Level settings, index 0 = bottom.
    pub levels: Vec<LevelParams>,
    /// Reproduction settings.
    pub reproduction: ReproductionParams,
}

impl HsomParams {
    /// The paper's Table I (height 6, memory 4, updatePeriod 2, 5000 steps, state and action
    /// length 6, all orthogonal) with the documented defaults for everything Table I omits.
    pub fn table1() -> Self {
        let sizes = [(16, 0.1), (10, 0.2), (8, 0.3), (6, 0.5), (2, 0.6), (1, 0.8)];
        HsomParams {
            seed: 1,
            height: 6,
            memory: 4,
            update_period: 2,
            state_length: 6,
            action_length: 6,
            training_steps: 5000,
            memory_mode: MemoryMode::Lists,
            normalisation: Normalisation::Global,
            consensus: Consensus::Start,
            alignment: Alignment::Stepped,
            knots: Knots::Event,
            plan: Plan::Decoded,
            partial_training: PartialTraining::Skip,
            list_update: ListUpdate::EveryStep,
            change_ratio: 1.0,
            action_horizon: 1,
            algorithm: Algorithm::Paper,
            levels: sizes
                .iter()
                .map(|&(n, a)| LevelParams::new(n, n, Topology::Orthogonal, a))
                .collect(),
            reproduction: ReproductionParams::default(),
        }
    }

    /// Validate every value; `source` (a file name) is used in the error messages.
    pub fn check(self, source: &str) -> Result<HsomConfig, ConfigError> {
        let bad = |field: &str, value: String, reason: &str| ConfigError::Invalid {
            file: source.to_string(),
            field: field.to_string(),
            value,
            reason: reason.to_string(),
        };
        let range = |field: &str, v: usize, lo: usize, hi: usize| {
            if v < lo || v > hi {
                Err(bad(
                    field,
                    v.to_string(),
                    &format!("expected an integer in {lo}..={hi}"),
                ))
            } else {
                Ok(())
            }
        };
        range("height", self.height, 1, 16)?;
        range("memory", self.memory, 1, 256)?;
        range("updatePeriod", self.update_period, 1, 1024)?;
        range("stateLength", self.state_length, 1, 4096)?;
        range("actionLength", self.action_length, 1, 4096)?;
        if self.action_length != self.state_length {
            return Err(bad(
                "actionLength",
                self.action_length.to_string(),
                &format!(
                    "the action is the next state, so actionLength must equal stateLength ({})",
                    self.state_length
                ),
            ));
        }
        range("trainingSteps", self.training_steps, 1, 1_000_000_000)?;
        let period_top = (self.update_period as f64).powi(self.height as i32 - 1);
        if period_top > 1e12 {
            return Err(bad(
                "updatePeriod",
                self.update_period.to_string(),
                &format!("updatePeriod^(height-1) = {period_top:e} is too large"),
            ));
        }
        if self.levels.len() != self.height {
            return Err(bad(
                "height",
                self.height.to_string(),
                &format!(
                    "height must equal the number of <level> elements ({})",
                    self.levels.len()
                ),
            ));
        }
        for (i, l) in self.levels.iter().enumerate() {
            let f = |name: &str| format!("levels/level[{i}]/{name}");
            range(&f("rows"), l.rows, 1, 1024)?;
            range(&f("cols"), l.cols, 1, 1024)?;
            for (name, s, max) in [
                ("learningFactor", &l.learning_factor, 1.0),
                ("learningRadius", &l.learning_radius, 1e6),
            ] {
                for (suffix, v) in [("", s.initial), ("Final", s.last)] {
                    if !(v.is_finite() && v > 0.0 && v <= max) {
                        let reason = if max == 1.0 {
                            "expected a number in (0, 1]".to_string()
                        } else {
                            "expected a positive number".to_string()
                        };
                        return Err(bad(&f(&format!("{name}{suffix}")), v.to_string(), &reason));
                    }
                }
            }
        }
        if self.algorithm == Algorithm::Events && self.memory_mode == MemoryMode::Levels {
            return Err(bad(
                "memoryMode",
                "levels".into(),
                "algorithm events keeps activity lists of events; use memoryMode lists (or algorithm paper)",
            ));
        }
        let mut weights: u64 = 0;
        for (i, l) in self.levels.iter().enumerate() {
            let dim = if i == 0 {
                (2 * self.state_length) as u64
            } else if self.algorithm == Algorithm::Events {
                // context (posture, begin, phase) + memory slots (two postures, duration, end)
                (self.state_length + 2 + self.memory * (2 * self.state_length + 2)) as u64
            } else {
                match self.memory_mode {
                    MemoryMode::Lists => 2 * self.memory as u64,
                    MemoryMode::Levels => {
                        (self.levels[i - 1].rows * self.levels[i - 1].cols) as u64
                    }
                }
            };
            weights += (l.rows * l.cols) as u64 * dim;
        }
        if weights > 100_000_000 {
            return Err(bad(
                "levels",
                format!("{weights} weights"),
                "the hierarchy would hold more than 100 million weights; use smaller maps",
            ));
        }
        if !(self.change_ratio.is_finite() && self.change_ratio > 0.0 && self.change_ratio <= 1.0) {
            return Err(bad(
                "changeRatio",
                self.change_ratio.to_string(),
                "expected a number in (0, 1]",
            ));
        }
        range("actionHorizon", self.action_horizon, 1, 100_000)?;
        let r = &self.reproduction;
        range("reproduction/offset", r.offset, 1, self.memory).map_err(|_| {
            bad(
                "reproduction/offset",
                r.offset.to_string(),
                &format!("expected 1..=memory ({})", self.memory),
            )
        })?;
        range("reproduction/maxLength", r.max_length, 1, 10_000_000)?;
        range(
            "reproduction/stationarySteps",
            r.stationary_steps,
            1,
            10_000_000,
        )?;
        let real = |field: &str, v: f64, lo: f64, hi: f64| {
            if !(v.is_finite() && v >= lo && v <= hi) {
                Err(bad(
                    field,
                    v.to_string(),
                    &format!("expected a number in [{lo}, {hi}]"),
                ))
            } else {
                Ok(())
            }
        };
        real(
            "reproduction/minLengthFraction",
            r.min_length_fraction,
            0.0,
            100.0,
        )?;
        real("reproduction/lengthFactor", r.length_factor, 0.01, 1000.0)?;
        real(
            "reproduction/confusionThreshold",
            r.confusion_threshold,
            0.0,
            1e6,
        )?;
        real("reproduction/continuity", r.continuity, 0.0, 1.0)?;
        real("reproduction/minAccuracy", r.min_accuracy, 0.0, 1.0)?;
        real("reproduction/endTolerance", r.end_tolerance, 0.0, 1e6)?;
        real(
            "reproduction/stationaryTolerance",
            r.stationary_tolerance,
            0.0,
            1e6,
        )?;
        if let Some(m) = r.max_level {
            range("reproduction/maxLevel", m, 0, self.height - 1)?;
        }
        range("reproduction/loopVisits", r.loop_visits, 0, 1_000_000)?;
        range("reproduction/loopWindow", r.loop_window, 1, 1_000_000)?;
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
    /// The same configuration with other (already valid) reproduction settings; fails when
    /// they are out of range.
    pub fn with_reproduction(self, r: ReproductionParams) -> Result<HsomConfig, ConfigError> {
        let source = self.source.clone();
        let mut p = self.params;
        p.reproduction = r;
        p.check(&source)
    }
    /// updatePeriod^level, the training period of `level`.
    pub fn period(&self, level: usize) -> u64 {
        (self.params.update_period as u64).pow(level as u32)
    }
    /// The same configuration with its lowest `height` levels (`levels` truncated, a
    /// `maxLevel` at or above the new top level dropped: the top is the limit anyway). A
    /// height above the configuration's own, or 0, is an error naming both: levels cannot be
    /// made up.
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
        if p.reproduction.max_level.is_some_and(|m| m + 1 >= height) {
            p.reproduction.max_level = None;
        }
        p.check(&format!("{} (at height {height})", self.source))
    }
    /// The same configuration with another [`Consensus`].
    pub fn with_consensus(&self, consensus: Consensus) -> Result<HsomConfig, ConfigError> {
        let mut p = self.params.clone();
        p.consensus = consensus;
        p.check(&self.source)
    }
    /// The same configuration with another [`Alignment`].
    pub fn with_alignment(&self, alignment: Alignment) -> Result<HsomConfig, ConfigError> {
        let mut p = self.params.clone();
        p.alignment = alignment;
        p.check(&self.source)
    }
    /// The same configuration with another [`Knots`].
    pub fn with_knots(&self, knots: Knots) -> Result<HsomConfig, ConfigError> {
        let mut p = self.params.clone();
        p.knots = knots;
        p.check(&self.source)
    }
    /// The same configuration with another [`Plan`].
    pub fn with_plan(&self, plan: Plan) -> Result<HsomConfig, ConfigError> {
        let mut p = self.params.clone();
        p.plan = plan;
        p.check(&self.source)
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
