//! The XML form of the configuration: one serde description ([`Doc`]) that quick-xml reads and
//! writes. Its fields' camelCase names are the element names, the enums' serde names the words
//! (read without regard to case), and an omitted setting takes the value of
//! [`HsomParams::recommended`] (`algorithm = events`, the default) or [`HsomParams::table1`]
//! (`algorithm = paper`); the ranges are [`HsomParams::check`]'s.

use std::path::Path;

use quick_xml::events::Event;
use serde::de::{self, DeserializeOwned, IntoDeserializer};
use serde::{Deserialize, Serialize};

use crate::robot::Robot;
use crate::som::{Decay, Neighbourhood, Schedule, Topology};

use super::errors::ConfigError;
use super::hyperparams::{
    default_offset, Algorithm, AlgorithmParams, EventsParams, HsomConfig, HsomParams, IdDecoding,
    LevelParams, MemoryMode, Normalisation, PaperParams, ReproductionParams, StopRule, MAX_HEIGHT,
};

/// The document: every element optional, written when present.
#[derive(Default, Serialize, Deserialize)]
#[serde(rename = "hsom", rename_all = "camelCase", deny_unknown_fields)]
struct Doc {
    #[serde(
        rename = "@version",
        default,
        deserialize_with = "leaf",
        skip_serializing_if = "none"
    )]
    version: Option<String>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    seed: Option<u64>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    algorithm: Option<Algorithm>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    height: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    memory: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    state_length: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    action_length: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    training_steps: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    normalisation: Option<Normalisation>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    update_period: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    memory_mode: Option<MemoryMode>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    change_ratio: Option<f64>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    action_horizon: Option<usize>,
    #[serde(skip_serializing_if = "none")]
    levels: Option<Levels>,
    #[serde(skip_serializing_if = "none")]
    reproduction: Option<Reproduction>,
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Levels {
    #[serde(default)]
    level: Vec<Level>,
}

#[derive(Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
struct Level {
    #[serde(
        rename = "@index",
        default,
        deserialize_with = "leaf",
        skip_serializing_if = "none"
    )]
    index: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    rows: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    cols: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    topology: Option<Topology>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    neighbourhood: Option<Neighbourhood>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    learning_factor: Option<f64>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    learning_factor_final: Option<f64>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    learning_factor_decay: Option<Decay>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    learning_radius: Option<f64>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    learning_radius_final: Option<f64>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    learning_radius_decay: Option<Decay>,
}

#[derive(Default, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
struct Reproduction {
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    max_length: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    length_factor: Option<f64>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    max_level: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    offset: Option<usize>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    id_decoding: Option<IdDecoding>,
    #[serde(default, deserialize_with = "leaf", skip_serializing_if = "none")]
    stop: Option<StopRule>,
}

fn none<T>(v: &Option<T>) -> bool {
    v.is_none()
}

/// Separates the reason from the value in the message of a [`leaf`]'s error.
const SEP: char = '\u{1f}';

/// An element's text, trimmed, read as a number or (without regard to case) one of an enum's
/// words; an error says what was expected and carries the text.
fn leaf<'de, D: de::Deserializer<'de>, T: DeserializeOwned>(d: D) -> Result<Option<T>, D::Error> {
    let text = String::deserialize(d)?;
    T::deserialize(Word(text.trim()))
        .map(Some)
        .map_err(|e| de::Error::custom(format!("{e}{SEP}{text}")))
}

/// The deserializer of one word: numbers parsed, enum variants matched without regard to case.
struct Word<'a>(&'a str);

impl<'de> de::Deserializer<'de> for Word<'_> {
    type Error = de::value::Error;
    fn deserialize_any<V: de::Visitor<'de>>(self, v: V) -> Result<V::Value, Self::Error> {
        v.visit_str(self.0)
    }
    fn deserialize_u64<V: de::Visitor<'de>>(self, v: V) -> Result<V::Value, Self::Error> {
        let n = self
            .0
            .parse()
            .map_err(|_| de::Error::custom("expected a non-negative integer"));
        v.visit_u64(n?)
    }
    fn deserialize_f64<V: de::Visitor<'de>>(self, v: V) -> Result<V::Value, Self::Error> {
        let x = self
            .0
            .parse()
            .map_err(|_| de::Error::custom("expected a number"));
        v.visit_f64(x?)
    }
    fn deserialize_enum<V: de::Visitor<'de>>(
        self,
        _: &'static str,
        words: &'static [&'static str],
        v: V,
    ) -> Result<V::Value, Self::Error> {
        match words.iter().find(|w| w.eq_ignore_ascii_case(self.0)) {
            Some(w) => v.visit_enum(w.into_deserializer()),
            None => Err(de::Error::custom(format!(
                "expected one of {}",
                words.join(", ")
            ))),
        }
    }
    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u128 f32 char str string bytes byte_buf option unit
        unit_struct newtype_struct seq tuple tuple_struct map struct identifier ignored_any
    }
}

/// Settings retired from the schema and what stands in their place: an element at one of these
/// paths is an error naming it.
const RETIRED: &[(&str, &str)] = &[
    ("plan", "plans always follow a training demonstration (what `traced` was)"),
    ("alignment", "the consensus always reads one demonstration along another without the warp's stairs (what `smooth` was)"),
    ("knots", "a followed event of four samples or more always passes through two knots, one per half (what `halves` was)"),
    ("consensus", "the consensus always weighs the demonstrations by their starts where the starts predict the placements, all alike otherwise (what `start` was)"),
    ("partialTraining", "an upper level of the paper algorithm trains once the list below is full (what `skip` was)"),
    ("listUpdate", "the paper algorithm's bottom list takes every step's BMU (what `everyStep` was); the events algorithm's lists hold events"),
    ("reproduction/mode", "the paper's procedure taken literally (what `literal` was)"),
    ("reproduction/unseenFallback", "a decoded node the training data never used is always replaced by the nearest used one (what `true` was)"),
    ("reproduction/minLengthFraction", "the learned stop waits for 0.6 of the shortest demonstration"),
    ("reproduction/stationarySteps", "the learned stop's stationarity window is 60 steps"),
    ("reproduction/stationaryTolerance", "the learned stop's stationarity radius is one bottom quantization error"),
    ("reproduction/endTolerance", "the learned stop ends on a node where a demonstration ended (what 0 was)"),
    ("reproduction/confusionThreshold", "every level with enough history predicts (what 0 was)"),
    ("reproduction/continuity", "the next posture is the executed node's action half, the paper's output (what 0 was)"),
    ("reproduction/closedLoop", "the predicted node is what the bottom list records (what `false` was)"),
    ("reproduction/minAccuracy", "every level with enough history predicts (what 0 was)"),
    ("reproduction/reflex", "the reflex executes the BMU of the current posture, the paper's (what `bmu` was)"),
    ("reproduction/timing", "one posture per executed node, the paper's (what `step` was)"),
    ("reproduction/loopVisits", LOOPS),
    ("reproduction/loopWindow", LOOPS),
    ("reproduction/revisitSuccessors", LOOPS),
];
const LOOPS: &str =
    "the paper algorithm executes what the hierarchy predicts, with no loop breaking";

/// The recommended configuration for the simulated Nao (the events extension): the left arm's
/// built-in configuration ([`Robot::config`]), the default of `simulate` and `cosco`.
pub const NAO_GESTURES_XML: &str = Robot::LeftArm.config().1;

/// Name of the built-in default configuration in reports and messages.
pub const DEFAULT_CONFIG_NAME: &str = Robot::LeftArm.config().0;

/// Load a configuration file ([`load_config`]), or without one the built-in recommended
/// configuration ([`NAO_GESTURES_XML`]).
pub fn load_config_or_default(path: Option<&Path>) -> Result<HsomConfig, ConfigError> {
    load_config_or_robots(path, Robot::LeftArm)
}

/// Load a configuration file ([`load_config`]), or without one `robot`'s built-in recommended
/// configuration ([`Robot::config`]).
pub fn load_config_or_robots(path: Option<&Path>, robot: Robot) -> Result<HsomConfig, ConfigError> {
    match path {
        Some(p) => load_config(p),
        None => {
            let (name, xml) = robot.config();
            parse_config(xml, name)
        }
    }
}

/// Read, parse and validate a configuration file.
pub fn load_config(path: &Path) -> Result<HsomConfig, ConfigError> {
    let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_config(&text, &path.display().to_string())
}

/// Parse and validate a configuration held in `text`; `file` names it in error messages.
/// Omitted settings take the values of [`HsomParams::recommended`] (`algorithm = events`, the
/// default) or [`HsomParams::table1`] (`algorithm = paper`); a retired setting, or one the
/// chosen algorithm does not read, is an error naming it.
pub fn parse_config(text: &str, file: &str) -> Result<HsomConfig, ConfigError> {
    read(text, file, shipped)
}

/// [`parse_config`] with `defaults(algorithm)` giving the values of the omitted settings (called
/// only when one is omitted).
fn read(
    text: &str,
    file: &str,
    defaults: impl Fn(Algorithm) -> HsomParams,
) -> Result<HsomConfig, ConfigError> {
    let indices = scan(text, file)?;
    let mut reader = quick_xml::de::Deserializer::from_str(text);
    let doc: Doc = serde_path_to_error::deserialize(&mut reader).map_err(|e| {
        let mut field = String::new();
        for segment in e.path() {
            match segment {
                serde_path_to_error::Segment::Map { key } if field.is_empty() => field += key,
                serde_path_to_error::Segment::Map { key } => field += &format!("/{key}"),
                serde_path_to_error::Segment::Seq { index } => {
                    let i = indices.get(*index).copied().flatten().unwrap_or(*index);
                    field += &format!("[{i}]");
                }
                _ => {}
            }
        }
        let message = e.into_inner().to_string();
        match message.split_once(SEP) {
            Some((reason, value)) => invalid(file, field, value, reason),
            None if field.is_empty() => ConfigError::Schema {
                file: file.into(),
                message,
            },
            None => ConfigError::Schema {
                file: file.into(),
                message: format!("<{field}>: {message}"),
            },
        }
    })?;
    doc.into_params(file, defaults)?.check(file)
}

impl HsomParams {
    /// The paper's Table I (height 6, memory 4, updatePeriod 2, 5000 steps, state and action
    /// length 6, all orthogonal) with the documented defaults for everything Table I omits:
    /// `configs/table1.xml`, and the defaults of `algorithm = paper`.
    pub fn table1() -> Self {
        shipped(Algorithm::Paper)
    }

    /// The recommended configuration for the simulated Nao (`configs/nao-gestures.xml`): the
    /// events extension, and the defaults of a configuration file.
    pub fn recommended() -> Self {
        shipped(Algorithm::Events)
    }
}

/// The configuration file shipped for `algorithm`, built in: it gives the values a file of
/// that algorithm omits. Each shipped file sets every setting but the reproduction's, so it
/// is read without defaults of its own.
fn shipped(algorithm: Algorithm) -> HsomParams {
    let (file, text) = match algorithm {
        Algorithm::Paper => (
            "configs/table1.xml",
            include_str!("../../configs/table1.xml"),
        ),
        Algorithm::Events => ("configs/nao-gestures.xml", NAO_GESTURES_XML),
    };
    let none =
        |_: Algorithm| -> HsomParams { unreachable!("{file} omits only reproduction settings") };
    match read(text, file, none) {
        Ok(config) => config.into_params(),
        Err(e) => unreachable!("the shipped {file} is valid (tests/config_table1.rs): {e}"),
    }
}

fn invalid(file: &str, field: String, value: impl ToString, reason: impl ToString) -> ConfigError {
    ConfigError::Invalid {
        file: file.into(),
        field,
        value: value.to_string(),
        reason: reason.to_string(),
    }
}

impl Doc {
    /// The settings written, with `defaults(chosen algorithm)`'s for the others (the
    /// reproduction's: [`ReproductionParams::default`], that of both shipped files).
    fn into_params(
        self,
        file: &str,
        defaults: impl Fn(Algorithm) -> HsomParams,
    ) -> Result<HsomParams, ConfigError> {
        if let Some(v) = self.version.as_ref().filter(|v| v.trim() != "1") {
            return Err(invalid(file, "hsom/@version".into(), v, "expected 1"));
        }
        let chosen = self.algorithm.unwrap_or(Algorithm::Events);
        let r = self.reproduction.unwrap_or_default();
        let paper_only = [
            ("updatePeriod", self.update_period.is_some()),
            ("memoryMode", self.memory_mode.is_some()),
            ("reproduction/offset", r.offset.is_some()),
            ("reproduction/idDecoding", r.id_decoding.is_some()),
            ("reproduction/stop", r.stop.is_some()),
        ];
        let events_only = [
            ("changeRatio", self.change_ratio.is_some()),
            ("actionHorizon", self.action_horizon.is_some()),
        ];
        let (reads, given) = match chosen {
            Algorithm::Paper => (Algorithm::Events, &events_only[..]),
            Algorithm::Events => (Algorithm::Paper, &paper_only[..]),
        };
        if let Some((field, _)) = given.iter().find(|g| g.1) {
            return Err(ConfigError::NotRead {
                file: file.into(),
                field: field.to_string(),
                reads: reads.name(),
                chosen: chosen.name(),
            });
        }
        // the defaults, read only when a setting is omitted (never for a shipped file)
        let base = std::cell::OnceCell::new();
        let base = || base.get_or_init(|| defaults(chosen));
        let height = self.height.unwrap_or_else(|| base().height);
        let memory = self.memory.unwrap_or_else(|| base().memory);
        let d = ReproductionParams::default();
        Ok(HsomParams {
            seed: self.seed.unwrap_or_else(|| base().seed),
            height,
            memory,
            state_length: self.state_length.unwrap_or_else(|| base().state_length),
            action_length: self.action_length.unwrap_or_else(|| base().action_length),
            training_steps: self.training_steps.unwrap_or_else(|| base().training_steps),
            normalisation: self.normalisation.unwrap_or_else(|| base().normalisation),
            levels: match self.levels {
                None => base().levels.clone(),
                Some(levels) => in_index_order(levels.level, height, file)?,
            },
            reproduction: ReproductionParams {
                max_length: r.max_length.unwrap_or(d.max_length),
                max_level: r.max_level,
                length_factor: r.length_factor.unwrap_or(d.length_factor),
            },
            algorithm: match chosen {
                Algorithm::Paper => {
                    let paper = "the defaults of algorithm paper are a paper configuration";
                    let q = || {
                        base()
                            .paper()
                            .cloned()
                            .unwrap_or_else(|| unreachable!("{paper}"))
                    };
                    AlgorithmParams::Paper(PaperParams {
                        update_period: self.update_period.unwrap_or_else(|| q().update_period),
                        memory_mode: self.memory_mode.unwrap_or_else(|| q().memory_mode),
                        offset: r.offset.unwrap_or(default_offset(memory)),
                        id_decoding: r.id_decoding.unwrap_or_else(|| q().id_decoding),
                        stop: r.stop.unwrap_or_else(|| q().stop),
                    })
                }
                Algorithm::Events => AlgorithmParams::Events(EventsParams {
                    change_ratio: self.change_ratio.unwrap_or_else(|| base().change_ratio()),
                    action_horizon: self
                        .action_horizon
                        .unwrap_or_else(|| base().action_horizon()),
                }),
            },
        })
    }

    /// Every setting of `p`'s algorithm, written out.
    fn of(p: &HsomParams) -> Doc {
        let (paper, events, r) = (p.paper(), p.events(), &p.reproduction);
        let level = |(i, l): (usize, &LevelParams)| Level {
            index: Some(i),
            rows: Some(l.rows),
            cols: Some(l.cols),
            topology: Some(l.topology),
            neighbourhood: Some(l.neighbourhood),
            learning_factor: Some(l.learning_factor.initial),
            learning_factor_final: Some(l.learning_factor.last),
            learning_factor_decay: Some(l.learning_factor.decay),
            learning_radius: Some(l.learning_radius.initial),
            learning_radius_final: Some(l.learning_radius.last),
            learning_radius_decay: Some(l.learning_radius.decay),
        };
        Doc {
            version: Some("1".into()),
            seed: Some(p.seed),
            algorithm: Some(p.kind()),
            height: Some(p.height),
            memory: Some(p.memory),
            state_length: Some(p.state_length),
            action_length: Some(p.action_length),
            training_steps: Some(p.training_steps),
            normalisation: Some(p.normalisation),
            update_period: paper.map(|q| q.update_period),
            memory_mode: paper.map(|q| q.memory_mode),
            change_ratio: events.map(|q| q.change_ratio),
            action_horizon: events.map(|q| q.action_horizon),
            levels: Some(Levels {
                level: p.levels.iter().enumerate().rev().map(level).collect(),
            }),
            reproduction: Some(Reproduction {
                max_length: Some(r.max_length),
                length_factor: Some(r.length_factor),
                max_level: r.max_level,
                offset: paper.map(|q| q.offset),
                id_decoding: paper.map(|q| q.id_decoding),
                stop: paper.map(|q| q.stop),
            }),
        }
    }
}

/// The `<level>` elements in index order (an element without `index` takes its position):
/// each index from 0 to height - 1 once.
fn in_index_order(
    levels: Vec<Level>,
    height: usize,
    file: &str,
) -> Result<Vec<LevelParams>, ConfigError> {
    let listed = levels.len();
    let mut slots: Vec<Option<LevelParams>> = vec![None; listed.max(height.min(MAX_HEIGHT))];
    let top = slots.len().saturating_sub(1);
    for (pos, l) in levels.into_iter().enumerate() {
        let index = l.index.unwrap_or(pos);
        let at = |name: &str| format!("levels/level[{index}]/{name}");
        let Some(slot) = slots.get_mut(index) else {
            let allowed = format!(
                "expected a level index from 0 to {top} (height {height}, {listed} <level> listed)"
            );
            let field = format!("levels/level[{pos}]/@index");
            return Err(invalid(file, field, index, allowed));
        };
        if slot.is_some() {
            return Err(invalid(file, at("@index"), index, "index given twice"));
        }
        let need = |name: &str| ConfigError::Missing {
            file: file.into(),
            field: at(name),
        };
        let rows = l.rows.ok_or_else(|| need("rows"))?;
        let cols = l.cols.ok_or_else(|| need("cols"))?;
        let topology = l.topology.ok_or_else(|| need("topology"))?;
        let alpha = l.learning_factor.ok_or_else(|| need("learningFactor"))?;
        let d = LevelParams::new(rows, cols, topology, alpha);
        let radius = l
            .learning_radius
            .map_or(d.learning_radius, LevelParams::radius);
        *slot = Some(LevelParams {
            neighbourhood: l.neighbourhood.unwrap_or(d.neighbourhood),
            learning_factor: Schedule {
                last: l.learning_factor_final.unwrap_or(d.learning_factor.last),
                decay: l.learning_factor_decay.unwrap_or(d.learning_factor.decay),
                ..d.learning_factor
            },
            learning_radius: Schedule {
                last: l.learning_radius_final.unwrap_or(radius.last),
                decay: l.learning_radius_decay.unwrap_or(radius.decay),
                ..radius
            },
            ..d
        });
    }
    match slots.iter().position(Option::is_none) {
        Some(index) => Err(ConfigError::MissingLevel {
            file: file.into(),
            index,
            height,
            listed,
        }),
        None => Ok(slots.into_iter().flatten().collect()),
    }
}

/// What serde cannot say: the line and column of a syntax error, a root other than `<hsom>`
/// (another XML document, an MJCF model say, is not a configuration even when some of its
/// element names match), an element holding both text and elements, a retired setting. Returns
/// the `index` attribute of each `<level>`, in order, to name a level by its index.
fn scan(text: &str, file: &str) -> Result<Vec<Option<usize>>, ConfigError> {
    let mut reader = quick_xml::Reader::from_str(text);
    reader.config_mut().check_end_names = true;
    let at = |byte: u64, message: String| {
        let mut b = (byte as usize).min(text.len());
        while !text.is_char_boundary(b) {
            b -= 1;
        }
        let before = &text[..b];
        ConfigError::Malformed {
            file: file.into(),
            line: before.matches('\n').count() + 1,
            column: before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1,
            message,
        }
    };
    // the open elements: name, holds text, holds elements (no element of the schema holds both)
    let mut open: Vec<(String, bool, bool)> = Vec::new();
    let (mut roots, mut indices) = (0, Vec::new());
    loop {
        let event = match reader.read_event() {
            Ok(event) => event,
            Err(e) => return Err(at(reader.error_position(), e.to_string())),
        };
        let (is_text, name) = match &event {
            Event::Eof => break,
            Event::End(_) => {
                open.pop();
                continue;
            }
            Event::Text(t) if !t.iter().all(u8::is_ascii_whitespace) => (true, String::new()),
            Event::Start(e) | Event::Empty(e) => {
                let name = String::from_utf8_lossy(e.name().as_ref()).into_owned();
                if open.is_empty() {
                    roots += 1;
                    if name != "hsom" {
                        let message = format!(
                            "the root element is <{name}>, a CoSCo-HSOM configuration's is <hsom>"
                        );
                        return Err(at(reader.buffer_position(), message));
                    }
                }
                let mut path: Vec<&str> = open.iter().skip(1).map(|o| o.0.as_str()).collect();
                path.push(&name);
                let path = path.join("/");
                if let Some((field, now)) = RETIRED.iter().find(|r| r.0 == path) {
                    return Err(ConfigError::Retired {
                        file: file.into(),
                        field: field.to_string(),
                        now: now.to_string(),
                    });
                }
                if path == "levels/level" {
                    let index = e.try_get_attribute("index").ok().flatten();
                    indices.push(
                        index.and_then(|a| std::str::from_utf8(&a.value).ok()?.trim().parse().ok()),
                    );
                }
                (false, name)
            }
            _ => continue,
        };
        if let Some((parent, text, elements)) = open.last_mut() {
            *text |= is_text;
            *elements |= !is_text;
            if *text && *elements {
                let message = format!(
                    "<{parent}> holds both text and elements; a value element holds only its \
                     value, a group only elements"
                );
                return Err(at(reader.buffer_position(), message));
            }
        }
        if matches!(event, Event::Start(_)) {
            open.push((name, false, false));
        }
    }
    if !open.is_empty() || roots != 1 {
        let message = match (roots, open.is_empty()) {
            (0, _) => "no root element",
            (_, false) => "unclosed element at end of file",
            _ => "more than one root element",
        };
        return Err(at(text.len() as u64, message.into()));
    }
    Ok(indices)
}

/// Largest embedded configuration a model file may hold (bytes).
const MAX_EMBEDDED: usize = 1 << 20;

/// A model file describes its configuration as the XML document [`HsomConfig::to_xml`]
/// writes: the one description of the settings, read back with every check of
/// [`parse_config`].
impl serde::Serialize for HsomConfig {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_xml())
    }
}

impl<'de> serde::Deserialize<'de> for HsomConfig {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let xml = Text::deserialize(d)?.0;
        if xml.len() > MAX_EMBEDDED {
            return Err(D::Error::custom(format!(
                "configuration length {} is implausible",
                xml.len()
            )));
        }
        parse_config(&xml, "embedded configuration").map_err(D::Error::custom)
    }
}

/// Text read from a file, copied from its bytes where the deserializer borrows them (the
/// binary model form): a length a file claims sizes nothing before the bytes are there.
pub(crate) struct Text(pub(crate) String);

impl<'de> serde::Deserialize<'de> for Text {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = Text;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a string")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Text, E> {
                Ok(Text(v.to_string()))
            }
        }
        d.deserialize_str(V)
    }
}

impl HsomConfig {
    /// The configuration as an XML document that [`parse_config`] reads back to an equal
    /// configuration (every setting its algorithm reads written out).
    pub fn to_xml(&self) -> String {
        let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
        let mut writer = quick_xml::se::Serializer::new(&mut s);
        writer.indent(' ', 2);
        // numbers, words and element names only: writing to a String cannot fail
        if let Err(e) = Doc::of(self.params()).serialize(writer) {
            unreachable!("a configuration is always written: {e}");
        }
        s.push('\n');
        s
    }
}
