//! The trained model, described once: the types a model file is generated from
//! ([`super::persist`]), each holding only what its algorithm reads, and the checks of each
//! against its configuration. [`Model`] holds what both algorithms share (the maps,
//! normalisation, training counts, hits, quality figures, columns, demonstration lengths and
//! the bottom's dwell times) and the part of its algorithm: [`PaperModel`] (the paper's,
//! Table I) or [`EventsModel`] (the events extension). [`Hsom`] is one of the two.
//! [`GestureModel`] is several gestures, one branch each. Training lives in
//! [`super::algorithm`] and [`super::events`], reproduction in [`super::paper`] and
//! [`super::events`], recognition in [`super::recognize`].

use serde::{Deserialize, Serialize};

use crate::config::{Algorithm, HsomConfig, HsomParams};
pub(crate) use crate::metrics::DemoSmoothness;
use crate::som::SelfOrganizingMap;

use super::errors::HsomError;
use super::followers::FOLLOWERS;
use super::inputs::input_dim;
use super::kept::{Kept, BAND_ROWS, KEPT_DEMONSTRATIONS};
use super::reproduction::Reproduction;

/// A trained CoSCo-HSOM: a model of the paper's algorithm or of the events extension, each
/// holding only its own algorithm's part. Its size is bounded by the configuration and never
/// grows with the length of the training data: the events extension keeps at most a few
/// training chunks per node (its traces) and, with the consensus weighed by the starts where
/// the starts are used, one placement of the bottom nodes per training demonstration. Its
/// operations are in `dispatch.rs`.
#[derive(Debug, Clone, PartialEq)]
pub enum Hsom {
    /// Trained by the paper's procedure (`algorithm = paper`).
    Paper(Box<Model<PaperModel>>),
    /// Trained by the events extension (`algorithm = events`).
    Events(Box<Model<EventsModel>>),
}

/// A model of the paper's algorithm.
pub(crate) type PaperHsom = Model<PaperModel>;
/// A model of the events extension.
pub(crate) type EventsHsom = Model<EventsModel>;

/// One Kohonen map per level plus the few per-node statistics both algorithms' reproduction
/// reads, and `part`, what only its algorithm reads ([`PaperModel`] or [`EventsModel`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(bound(serialize = "A: Part", deserialize = "A: Deserialize<'de>"))]
pub struct Model<A> {
    pub(crate) config: HsomConfig,
    /// Per-variable offset and scale: the bottom level sees (x - offset) / scale.
    pub(crate) offset: Vec<f64>,
    pub(crate) scale: Vec<f64>,
    /// Number of times each level was trained.
    pub(crate) trained: Vec<u64>,
    /// Per level, per node: how often the node is the BMU when the training data are replayed.
    pub(crate) hits: Vec<Vec<u32>>,
    /// Per level quantization and topographic error on the training data.
    pub(crate) qe: Vec<f64>,
    pub(crate) te: Vec<f64>,
    /// Shortest, mean and longest demonstration (samples).
    pub(crate) demo_len: [f64; 3],
    /// Shortest, mean and longest demonstration in runs of the same bottom BMU (the length
    /// of its sequence of distinct bottom nodes).
    pub(crate) demo_runs: [f64; 3],
    /// Per bottom node: mean length (steps) of its runs as the BMU inside the demonstrations
    /// (first and last run of each demonstration, the idle start and end, excluded); 0 when
    /// it never had such a run.
    pub(crate) dwell: Vec<f64>,
    /// Names of the demonstrations' columns (`x0`, `x1`, ... for plain series).
    #[serde(with = "super::record::strings")]
    pub(crate) columns: Vec<String>,
    /// Per level: how often its partial match predicted the next entry of the level below
    /// exactly during the replay of the training data (0 for level 0).
    pub(crate) accuracy: Vec<f64>,
    /// Per level: how often a lookup table of "next entry given the last entry" of the level
    /// below, counted on the same replay, predicted that entry (0 for level 0): the simple
    /// baseline every level must beat.
    pub(crate) lookup: Vec<f64>,
    /// What only its algorithm reads; a model file names its algorithm (`Paper` or `Events`).
    #[serde(rename = "algo", serialize_with = "tagged")]
    pub(crate) part: A,
    /// The kept demonstrations as the bottom level sees them (normalised), each resampled
    /// to [`BAND_ROWS`] rows: at most [`KEPT_DEMONSTRATIONS`], a uniform sample of every
    /// demonstration learned from ([`Kept`]). How far they lie from a reproduction is its
    /// confidence band ([`crate::condition::spread_band`]); an update learns from them again
    /// beside the new demonstrations (docs/ALGORITHM.md, section 10).
    pub(crate) paths: Vec<Vec<Vec<f64>>>,
    /// What the model learned from: how many demonstrations, in how many updates, and each
    /// kept path's length (`memory` in a model file).
    #[serde(rename = "memory")]
    pub(crate) kept: Kept,
    /// The maps, bottom first (last in a model file).
    pub(crate) maps: Vec<SelfOrganizingMap>,
}

/// The part of a model only its algorithm reads, as a model file names it: read as one of
/// the two (`Algo`), written from either borrowed (`Algo<&PaperModel, &EventsModel>`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Algo<P = PaperModel, E = Box<EventsModel>> {
    /// The paper's procedure (`algorithm = paper`).
    Paper(P),
    /// The events extension (`algorithm = events`).
    Events(E),
}

/// What an algorithm's own part tells the code both algorithms share.
pub trait Part: Sized + Clone {
    /// The algorithm whose part it is.
    const ALGORITHM: Algorithm;
    /// The events extension's part, where the shared code reads it if there is one (the
    /// executed curve, the consensus): `None` for the paper's.
    fn events(&self) -> Option<&EventsModel>;
    /// A training demonstration ends on bottom node `node` (the replay of the training data).
    fn count_end(&mut self, _node: usize) {}
    /// The part as a model file names it.
    fn tagged(&self) -> Algo<&PaperModel, &EventsModel>;
    /// Its shapes and values against `s` (a model read from a file).
    fn check(&self, s: &Shape) -> Result<(), String>;
    /// `model`'s reproduction from the normalised posture `y0` with the settings `p`.
    fn reproduce(m: &Model<Self>, y0: Vec<f64>, p: &HsomParams) -> Result<Reproduction, HsomError>;
    /// The model as an [`Hsom`].
    fn wrap(m: Model<Self>) -> Hsom;
}

fn tagged<A: Part, S: serde::Serializer>(part: &A, s: S) -> Result<S::Ok, S::Error> {
    part.tagged().serialize(s)
}

impl Part for PaperModel {
    const ALGORITHM: Algorithm = Algorithm::Paper;
    fn events(&self) -> Option<&EventsModel> {
        None
    }
    fn count_end(&mut self, node: usize) {
        self.end_hits[node] = self.end_hits[node].saturating_add(1);
    }
    fn tagged(&self) -> Algo<&PaperModel, &EventsModel> {
        Algo::Paper(self)
    }
    fn check(&self, s: &Shape) -> Result<(), String> {
        sized("end nodes", self.end_hits.len(), s.nodes[0])
    }
    fn reproduce(m: &PaperHsom, y0: Vec<f64>, p: &HsomParams) -> Result<Reproduction, HsomError> {
        m.reproduce_paper(y0, p)
    }
    fn wrap(m: PaperHsom) -> Hsom {
        Hsom::Paper(Box::new(m))
    }
}

impl<A> Model<A> {
    /// The same shared part with `part` for its algorithm's, and the part it held.
    pub(crate) fn with_part<B>(self, part: B) -> (Model<B>, A) {
        let m = Model {
            config: self.config,
            offset: self.offset,
            scale: self.scale,
            trained: self.trained,
            hits: self.hits,
            qe: self.qe,
            te: self.te,
            demo_len: self.demo_len,
            demo_runs: self.demo_runs,
            dwell: self.dwell,
            columns: self.columns,
            accuracy: self.accuracy,
            lookup: self.lookup,
            part,
            paths: self.paths,
            kept: self.kept,
            maps: self.maps,
        };
        (m, self.part)
    }
}

#[cfg(test)]
impl Hsom {
    /// The events extension's model (a test's: a model of the paper's algorithm panics).
    pub(crate) fn into_events(self) -> EventsHsom {
        match self {
            Hsom::Events(m) => *m,
            Hsom::Paper(_) => panic!("a model of the paper's algorithm"),
        }
    }
}

/// A model file holds either model as it is, its part named by its algorithm.
impl Serialize for Hsom {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Hsom::Paper(m) => m.serialize(s),
            Hsom::Events(m) => m.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Hsom {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let (m, part) = Model::<Algo>::deserialize(d)?.with_part(());
        Ok(match part {
            Algo::Paper(p) => Hsom::Paper(Box::new(m.with_part(p).0)),
            Algo::Events(e) => Hsom::Events(Box::new(m.with_part(*e).0)),
        })
    }
}

/// What the paper's reproduction reads beyond the shared part.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PaperModel {
    /// Per bottom node: how many demonstrations end on it.
    pub(crate) end_hits: Vec<u32>,
}

/// What the events extension reads beyond the shared part: its levels' match thresholds
/// and held-out figures, the follower tables and exemplars it decodes with, where it places
/// bottom events, and the traced training chunks its plans replay.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EventsModel {
    /// Per level: the largest partial-match distance (RMS per known
    /// coordinate) seen when the training data were replayed; a level whose match in
    /// reproduction is farther is "confused".
    pub(crate) threshold: Vec<f64>,
    /// Per level: `accuracy` and `lookup` measured held out, on each
    /// training demonstration's entries by the levels trained on the others (the bottom
    /// kept; [`Hsom::level_trusted`]). Equal to the in-sample figures when there is a
    /// single demonstration.
    pub(crate) heldout_accuracy: Vec<f64>,
    pub(crate) heldout_lookup: Vec<f64>,
    /// Per level: up to `FOLLOWERS` entries that most often followed
    /// each node (and, in the last row, the begin) in training; `u32::MAX` pads. Decoding
    /// by content chooses among them.
    pub(crate) followers: Vec<Vec<u32>>,
    /// Per entry of the bottom's follower table: the mean position
    /// (bottom events before it / the mean number of events per demonstration) at which
    /// that follower came after its row's entry in training; level 1 decodes among
    /// followers by content and position.
    pub(crate) follower_at: Vec<f64>,
    /// Per level >= 1, per node: the position of its exemplar chunk in its demonstration
    /// (the phase of the chunk's context: bottom events before it / the mean number per
    /// demonstration). Expanding a plan, each slot's position follows from its top node's
    /// exemplar and the tiling, and level 1 decodes by content and that position.
    pub(crate) exemplar_phase: Vec<Vec<f64>>,
    /// Per level >= 1, per node, the lower entries of its exemplar (`memory` each).
    pub(crate) exemplars: Vec<Vec<u32>>,
    /// Per bottom node, where a reproduction places its events (state part, normalised,
    /// `stateLength` values per node): the consensus of the demonstrations it was trained on
    /// (a branch of a model of several gestures: its own gesture's; [`EventsHsom::fit_postures`]);
    /// `None`: the nodes' weights.
    pub(crate) knots: Option<Vec<f64>>,
    /// With `consensus = start`: each training demonstration's own placement of the bottom
    /// nodes and its first posture, weighed at reproduction by the start
    /// ([`StartKnots`]).
    pub(crate) start_knots: Option<StartKnots>,
    /// Where the training demonstrations began: the mean of their first postures (state
    /// part, normalised). A reproduction's plan begins there (or where the demonstrations
    /// weighed by its start began, [`StartKnots`]) and is joined from the given posture
    /// (docs/ALGORITHM.md, section 3.8). `None`: untrained.
    pub(crate) start_posture: Option<Vec<f64>>,
    /// How smooth the training demonstrations are: a reproduction's curve is smoothed until
    /// it is as smooth (docs/ALGORITHM.md, section 3.8). `None`: untrained, or too short to
    /// tell.
    pub(crate) demo_smoothness: Option<DemoSmoothness>,
    /// How long a start's offset from the demonstrations' lasts, as a fraction of the
    /// gesture: the fade that best describes how the training demonstrations' own offsets
    /// from their mean start carried on (`events::start::start_fade`;
    /// docs/ALGORITHM.md, section 3.8). `None`: untrained.
    pub(crate) start_fade: Option<f64>,
    /// Where the training demonstrations ended: the mean of their last postures (state part,
    /// normalised). A reproduction that ends by its end event ends there (docs/ALGORITHM.md,
    /// section 3.8). `None`: untrained.
    pub(crate) end_posture: Option<Vec<f64>>,
    /// The training demonstrations' entries at every level and which training chunk each
    /// node's exemplar is: a plan replays the demonstrated chunk its
    /// node stands for ([`Traces`]).
    pub(crate) traces: Option<Traces>,
}

impl EventsModel {
    /// The events part of an untrained model configured by `p`: nothing placed, nothing
    /// traced, every follower and exemplar the padding.
    pub(crate) fn untrained(p: &crate::config::HsomParams) -> Self {
        let nodes = |l: &crate::config::LevelParams| l.rows * l.cols;
        EventsModel {
            threshold: vec![0.0; p.height],
            heldout_accuracy: vec![0.0; p.height],
            heldout_lookup: vec![0.0; p.height],
            followers: p
                .levels
                .iter()
                .map(|l| vec![u32::MAX; (nodes(l) + 1) * FOLLOWERS])
                .collect(),
            follower_at: vec![0.0; (nodes(&p.levels[0]) + 1) * FOLLOWERS],
            exemplar_phase: p.levels.iter().map(|l| vec![0.0; nodes(l)]).collect(),
            exemplars: p
                .levels
                .iter()
                .map(|l| vec![u32::MAX; nodes(l) * p.memory])
                .collect(),
            // nothing learned from the demonstrations
            knots: None,
            start_knots: None,
            start_posture: None,
            demo_smoothness: None,
            start_fade: None,
            end_posture: None,
            traces: None,
        }
    }
}

impl Part for EventsModel {
    const ALGORITHM: Algorithm = Algorithm::Events;
    fn events(&self) -> Option<&EventsModel> {
        Some(self)
    }
    fn tagged(&self) -> Algo<&PaperModel, &EventsModel> {
        Algo::Events(self)
    }
    fn reproduce(m: &EventsHsom, y0: Vec<f64>, p: &HsomParams) -> Result<Reproduction, HsomError> {
        Ok(m.plan_events(&y0, &y0, &[], &p.reproduction))
    }
    fn wrap(m: EventsHsom) -> Hsom {
        Hsom::Events(Box::new(m))
    }
    fn check(&self, s: &Shape) -> Result<(), String> {
        let (h, n0, state) = (s.nodes.len(), s.nodes[0], s.state);
        sized("match thresholds", self.threshold.len(), h)?;
        sized("held-out accuracy", self.heldout_accuracy.len(), h)?;
        sized("held-out lookup accuracy", self.heldout_lookup.len(), h)?;
        let fol = (n0 + 1) * FOLLOWERS;
        sized("follower positions", self.follower_at.len(), fol)?;
        per_level("followers", &self.followers, |l| {
            (s.nodes[l] + 1) * FOLLOWERS
        })?;
        per_level("exemplars", &self.exemplars, |l| s.nodes[l] * s.memory)?;
        per_level("exemplar positions", &self.exemplar_phase, |l| s.nodes[l])?;
        let acc = self.heldout_accuracy.iter().chain(&self.heldout_lookup);
        each("held-out accuracies", acc, unit, ACCURACY)?;
        let nonneg = |v: f64| v.is_finite() && v >= 0.0;
        each(
            "match thresholds",
            &self.threshold,
            nonneg,
            "negative or non-finite",
        )?;
        let at = self
            .follower_at
            .iter()
            .chain(self.exemplar_phase.iter().flatten());
        each("follower and exemplar positions", at, position, POSITION)?;
        for (l, f) in self.followers.iter().enumerate() {
            indices(&format!("followers of level {l}"), f, s.nodes[l])?;
        }
        for (l, e) in self.exemplars.iter().enumerate() {
            // level l's exemplars are entries of level l - 1 (none at the bottom)
            let below = if l == 0 { 0 } else { s.nodes[l - 1] };
            indices(&format!("exemplars of level {l}"), e, below)?;
        }
        let want = n0 * state;
        if let Some(knots) = &self.knots {
            if knots.len() != want {
                return Err(format!(
                    "{} posture values, the bottom level needs {want} (nodes x stateLength) or none",
                    knots.len()
                ));
            }
            each("postures", knots, normalised, NORMALISED)?;
        }
        for (what, p) in [("start", &self.start_posture), ("end", &self.end_posture)] {
            if let Some(p) = p {
                if p.len() != state {
                    return Err(format!(
                        "{} {what}-posture values: none or stateLength = {state} values",
                        p.len()
                    ));
                }
                each(&format!("the {what} posture"), p, normalised, NORMALISED)?;
            }
        }
        if self.demo_smoothness.as_ref().is_some_and(|d| {
            d.peak_step.len() != state
                || ![d.jerk, d.start_step]
                    .iter()
                    .chain(&d.peak_step)
                    .all(|&v| nonneg(v))
        }) {
            return Err(format!(
                "the demonstrations' jerk, first step and stateLength = {state} largest steps: \
                 none or finite values >= 0"
            ));
        }
        if self.start_fade.is_some_and(|f| !(0.0..=1.0).contains(&f)) {
            return Err("the start's fade: none or a fraction in [0, 1]".into());
        }
        if let Some(k) = &self.start_knots {
            let sound = k.width > 0.0
                && k.starts.len() >= 3
                && k.starts.len() == k.knots.len()
                && k.starts.iter().all(|v| v.len() == state)
                && k.knots.iter().all(|v| v.len() == want)
                && self.knots.is_some();
            if !sound {
                return Err(format!(
                    "start-weighted postures of {} demonstrations (width {}): at least 3 \
                     needed, each with stateLength start values and {want} posture values, a \
                     positive finite width, and the postures stored",
                    k.starts.len(),
                    k.width
                ));
            }
            let values = k.starts.iter().chain(&k.knots).flatten();
            each(
                "start-weighted postures",
                values.chain([&k.width]),
                normalised,
                NORMALISED,
            )?;
        }
        match &self.traces {
            Some(t) => t
                .check(s.memory, s.trace_places, &s.nodes)
                .map_err(|why| format!("traces: {why}")),
            None => Err(
                "traces missing for a model of algorithm events: stored exactly with \
                         algorithm = events"
                    .into(),
            ),
        }
    }
}

/// The consensus weighed by the starts (docs/ALGORITHM.md, section 3.7): where each training
/// demonstration places every bottom node's events (the node's samples, of every
/// demonstration, replaced by that demonstration's samples aligned to them, smoothed as
/// [`EventsHsom::fit_postures`] smooths the consensus), and where each started. A reproduction
/// weighs the demonstrations by a Gaussian of the distance between their start and its own,
/// of the width that best predicted each training demonstration's placement from the others'
/// (leave-one-out); all alike (`width` infinite) is a candidate, and is the plain
/// [`consensus`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct StartKnots {
    /// Per training demonstration, its first posture (state part, normalised).
    pub(crate) starts: Vec<Vec<f64>>,
    /// Per training demonstration, its placement of every bottom node (`stateLength` values
    /// per node).
    pub(crate) knots: Vec<Vec<f64>>,
    /// The Gaussian's width (normalised units); infinite: all alike.
    pub(crate) width: f64,
}

/// What the levels were trained on, kept so a plan can replay it (`plan = traced`): per
/// level l >= 1, per node, up to [`TRACED_CHUNKS`] of the training chunks it was the BMU of,
/// nearest its weights first (the exemplar first), each as [`trace_width`] words (`u32::MAX`
/// pads what is not there), by node. At most nodes x [`TRACED_CHUNKS`] chunks a level, a bound
/// set by the configuration alone; level 0, and a level over [`TRACE_BUDGET`], keeps none.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct Traces {
    pub(crate) levels: Vec<Vec<TracedChunk>>,
}

/// One traced training chunk of a node ([`Traces`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct TracedChunk {
    /// The node it was the BMU of.
    pub(crate) node: u32,
    /// [`trace_width`] words: its head, bottom events, their places and the lower levels'
    /// BMUs.
    pub(crate) words: Vec<u32>,
}

/// A model of one or several gestures: one branch per label, each an [`Hsom`] of its
/// gesture alone, all in the same units.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GestureModel {
    /// Empty for a single-gesture model (one unlabelled branch).
    #[serde(with = "super::record::strings")]
    pub(crate) labels: Vec<String>,
    /// Per label, what recognition compares with (empty without labels).
    pub(crate) calibration: Vec<Calibration>,
    pub(crate) branches: Vec<Hsom>,
    /// How recognition scores (not stored: the default on load).
    #[serde(skip)]
    pub(crate) scoring: Scoring,
}

/// What recognition compares a label's matches with: per level, the branch's mean chunk
/// distance on its training data (index 0, the bottom, unused), and the score above which a
/// sequence is not this gesture.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub(crate) struct Calibration {
    pub(crate) reference: Vec<f64>,
    pub(crate) threshold: f64,
}

impl Calibration {
    /// Whether it fits a model of `height` levels (loaded, untrusted): one reference per
    /// level, every value finite and not negative.
    pub(crate) fn fits(&self, height: usize) -> bool {
        self.reference.len() == height
            && self
                .reference
                .iter()
                .chain([&self.threshold])
                .all(|x| x.is_finite() && *x >= 0.0)
    }
}

/// How a label's matches become its score (lower is better).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum Scoring {
    /// Level 1's mean chunk distance alone.
    Level1,
    /// The bottom alone: the mean distance of the events' postures to the nearest posture
    /// the gesture used (its branch's statistics).
    Postures,
    /// The gesture reproduced from the sequence's first posture, and the sequence's DTW
    /// distance per step from it (a prefix: open-ended). The default (docs/ALGORITHM.md,
    /// section 4).
    #[default]
    Reproduction,
    /// The mean over levels of distance / the label's held-out reference (the same mean on
    /// its own demonstrations held out, leave-one-out).
    Relative,
}

/// The largest magnitude of a normalised training value: squared distances over thousands
/// of inputs stay far from overflowing.
pub(crate) const MAX_NORMALISED: f64 = 1e100;

/// The longest demonstration a model file may record, samples (a day at 1 kHz): the
/// reproduction's length cap derives from it.
const MAX_DEMO_SAMPLES: f64 = 1e8;

/// What a model's configuration makes of its parts' shapes: what [`Model::check`] and each
/// part's `check` hold a model read from a file to.
pub struct Shape {
    /// Nodes per level, bottom first.
    pub(crate) nodes: Vec<usize>,
    /// stateLength.
    pub(crate) state: usize,
    /// memory.
    pub(crate) memory: usize,
    /// Values placing each traced event ([`super::events::trace_places`]).
    pub(crate) trace_places: usize,
}

const ACCURACY: &str = "an accuracy outside [0, 1]";
const POSITION: &str = "a position negative or non-finite (at most 1e8)";
const NORMALISED: &str =
    "a normalised value beyond 1e100 or non-finite (training refuses data beyond 1e100 once normalised)";

fn unit(v: f64) -> bool {
    (0.0..=1.0).contains(&v)
}

fn position(v: f64) -> bool {
    (0.0..=MAX_DEMO_SAMPLES).contains(&v)
}

fn normalised(v: f64) -> bool {
    v.abs() <= MAX_NORMALISED
}

/// `found` values of `what`, `want` expected.
fn sized(what: &str, found: usize, want: usize) -> Result<(), String> {
    if found == want {
        return Ok(());
    }
    Err(format!("{found} values of {what}, {want} expected"))
}

/// One row of `what` per level, level `l`'s of `want(l)` values.
fn per_level<T>(what: &str, rows: &[Vec<T>], want: impl Fn(usize) -> usize) -> Result<(), String> {
    (0..rows.len()).try_for_each(|l| sized(&format!("{what} of level {l}"), rows[l].len(), want(l)))
}

/// Every value of `what` allowed by `ok`; the first that is not, and `why` it is refused.
fn each<'a>(
    what: &str,
    values: impl IntoIterator<Item = &'a f64>,
    ok: impl Fn(f64) -> bool,
    why: &str,
) -> Result<(), String> {
    match values.into_iter().find(|&&v| !ok(v)) {
        None => Ok(()),
        Some(v) if v.abs() >= 1e6 || v.abs() < 1e-4 && *v != 0.0 => {
            Err(format!("{what} holds {v:e}: {why}"))
        }
        Some(v) => Err(format!("{what} holds {v}: {why}")),
    }
}

/// Every entry of `what` a node of a map of `nodes` nodes, the end or the padding.
fn indices(what: &str, entries: &[u32], nodes: usize) -> Result<(), String> {
    match entries
        .iter()
        .find(|&&v| (v as usize) >= nodes && v != u32::MAX && v != super::events::END)
    {
        None => Ok(()),
        Some(v) => Err(format!(
            "{what} holds {v}: a follower or exemplar outside its map of {nodes} nodes"
        )),
    }
}

impl<A: Part> Model<A> {
    /// Every shape and value of a model read from a file against its embedded configuration
    /// and the bounds training holds them to: the shared part here, its algorithm's part by
    /// that part's own [`Part::check`]. What is wrong, naming the field and what is allowed.
    pub(crate) fn check(&self) -> Result<(), String> {
        let p = self.config.params();
        let holds = A::ALGORITHM;
        if holds != p.kind() {
            return Err(format!(
                "the model holds the {} algorithm's part, the configuration algorithm {}",
                holds.name(),
                p.kind().name()
            ));
        }
        let height = p.levels.len();
        sized("levels", self.maps.len(), height)?;
        for (l, (m, lp)) in self.maps.iter().zip(&p.levels).enumerate() {
            let dim = input_dim(&self.config, l);
            if (m.rows(), m.cols(), m.dim()) != (lp.rows, lp.cols, dim)
                || m.topology() != lp.topology
            {
                return Err(format!(
                    "level {l} is {}x{} of dimension {} ({}), the configuration says {}x{} of dimension {dim} ({})",
                    m.rows(),
                    m.cols(),
                    m.dim(),
                    m.topology().name(),
                    lp.rows,
                    lp.cols,
                    lp.topology.name()
                ));
            }
            each(
                &format!("the weights of level {l}"),
                &m.all_weights(),
                normalised,
                NORMALISED,
            )?;
        }
        let nodes: Vec<usize> = self.maps.iter().map(|m| m.len()).collect();
        let state = p.state_length;
        sized("training counts", self.trained.len(), height)?;
        sized("quantization errors", self.qe.len(), height)?;
        sized("topographic errors", self.te.len(), height)?;
        sized("accuracy", self.accuracy.len(), height)?;
        sized("lookup accuracy", self.lookup.len(), height)?;
        sized("hit counts", self.hits.len(), height)?;
        per_level("hit counts", &self.hits, |l| nodes[l])?;
        sized("offset", self.offset.len(), state)?;
        sized("scale", self.scale.len(), state)?;
        sized("column names", self.columns.len(), state)?;
        sized("dwell", self.dwell.len(), nodes[0])?;
        let kept = self.paths.len();
        if kept > KEPT_DEMONSTRATIONS
            || self.kept.lengths.len() != kept
            || self.kept.learned < kept as u64
        {
            return Err(format!(
                "{kept} kept demonstrations with {} lengths, of {} learned from: at most \
                 {KEPT_DEMONSTRATIONS}, one length each, no more than were learned from",
                self.kept.lengths.len(),
                self.kept.learned
            ));
        }
        self.kept.check_counts()?;
        if let Some(p) = self.kept.period.filter(|p| !(p.is_finite() && *p > 0.0)) {
            return Err(format!("a sample period of {p} s: positive and finite"));
        }
        if let Some(n) =
            (self.kept.lengths.iter()).find(|&&n| n < 2 || f64::from(n) > MAX_DEMO_SAMPLES)
        {
            return Err(format!(
                "a kept demonstration of {n} samples: 2 to {MAX_DEMO_SAMPLES:e}"
            ));
        }
        for (k, path) in self.paths.iter().enumerate() {
            if path.len() != BAND_ROWS || path.iter().any(|r| r.len() != state) {
                return Err(format!(
                    "training path {k} has {} rows of widths {:?}: {BAND_ROWS} rows of {state} \
                     values",
                    path.len(),
                    path.iter()
                        .map(Vec::len)
                        .collect::<std::collections::BTreeSet<_>>()
                ));
            }
        }
        each(
            "the training paths",
            self.paths.iter().flatten().flatten(),
            normalised,
            NORMALISED,
        )?;
        // values that size the reproduction: no demonstration is longer than the longest, no
        // event longer than a demonstration
        let len = self.demo_len;
        if !(len.iter().all(|&v| position(v)) && len[0] <= len[1] + 1e-9 && len[1] <= len[2] + 1e-9)
        {
            return Err(format!(
                "demonstration lengths {len:?} (shortest, mean, longest) must be ordered and at \
                 most {MAX_DEMO_SAMPLES:e} samples"
            ));
        }
        let longest = len[2];
        each(
            "the bottom's dwell times and events per demonstration",
            self.dwell.iter().chain(&self.demo_runs),
            |v| (0.0..=longest).contains(&v),
            &format!(
                "negative, non-finite or longer than the longest demonstration ({longest} samples)"
            ),
        )?;
        each(
            "accuracies",
            self.accuracy.iter().chain(&self.lookup),
            unit,
            ACCURACY,
        )?;
        let finite = |v: f64| v.is_finite();
        each(
            "quantization and topographic errors",
            self.qe.iter().chain(&self.te),
            finite,
            "non-finite",
        )?;
        self.check_normalisation()?;
        let shape = Shape {
            nodes,
            state,
            memory: p.memory,
            trace_places: super::events::trace_places(p),
        };
        self.part.check(&shape)
    }

    /// The offset and scale training makes: with normalisation none, 0 and 1; otherwise each
    /// variable's least value and a positive finite range that changes it when added to it
    /// (1 for a constant variable), with normalisation global one range for all.
    fn check_normalisation(&self) -> Result<(), String> {
        use crate::config::Normalisation;
        let norm = self.config.params().normalisation;
        let first = self.scale.first().copied().unwrap_or(1.0);
        for (d, (&o, &s)) in self.offset.iter().zip(&self.scale).enumerate() {
            let basic = o.is_finite() && s.is_finite() && s > 0.0;
            let (ok, allowed) = match norm {
                Normalisation::None => (o == 0.0 && s == 1.0, "with normalisation none, offset 0 and scale 1"),
                Normalisation::PerDimension => (
                    basic && (s == 1.0 || o + s != o),
                    "with normalisation perDimension, a finite offset (the variable's least value) \
                     and a positive finite scale (its range, 1 for a constant variable) large enough \
                     to change the offset when added to it",
                ),
                Normalisation::Global => (
                    basic && s == first && (s == 1.0 || self.offset.iter().any(|&o| o + s != o)),
                    "with normalisation global, finite offsets (each variable's least value) and one \
                     positive finite scale for every variable (the largest range, 1 when every \
                     variable is constant) large enough to change an offset when added to it",
                ),
            };
            if !ok {
                return Err(format!(
                    "offset {o:e} and scale {s:e} of variable {d} ({}): training makes {allowed}",
                    self.columns.get(d).map_or("?", |c| c.as_str())
                ));
            }
        }
        Ok(())
    }
}
