//! Reading and writing the XML form of the configuration (quick-xml + serde).

use std::path::Path;

use quick_xml::events::Event;
use serde::de::IgnoredAny;
use serde::Deserialize;

use crate::som::{Decay, Neighbourhood, Schedule, Topology};

use super::errors::ConfigError;
use super::hyperparams::{
    Algorithm, AlgorithmParams, EventsParams, HsomConfig, HsomParams, IdDecoding, LevelParams,
    MemoryMode, Normalisation, PaperParams, StopRule,
};

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    #[serde(rename = "@version")]
    version: Option<String>,
    seed: Option<String>,
    height: Option<String>,
    memory: Option<String>,
    #[serde(rename = "updatePeriod")]
    update_period: Option<String>,
    #[serde(rename = "stateLength")]
    state_length: Option<String>,
    #[serde(rename = "actionLength")]
    action_length: Option<String>,
    #[serde(rename = "trainingSteps")]
    training_steps: Option<String>,
    #[serde(rename = "memoryMode")]
    memory_mode: Option<String>,
    normalisation: Option<String>,
    #[serde(rename = "changeRatio")]
    change_ratio: Option<String>,
    #[serde(rename = "actionHorizon")]
    action_horizon: Option<String>,
    algorithm: Option<String>,
    levels: Option<RawLevels>,
    reproduction: Option<RawReproduction>,
    // retired settings, read only to name them in the error
    consensus: Option<IgnoredAny>,
    alignment: Option<IgnoredAny>,
    plan: Option<IgnoredAny>,
    knots: Option<IgnoredAny>,
    #[serde(rename = "partialTraining")]
    partial_training: Option<IgnoredAny>,
    #[serde(rename = "listUpdate")]
    list_update: Option<IgnoredAny>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLevels {
    #[serde(default)]
    level: Vec<RawLevel>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLevel {
    #[serde(rename = "@index")]
    index: Option<String>,
    rows: Option<String>,
    cols: Option<String>,
    topology: Option<String>,
    neighbourhood: Option<String>,
    #[serde(rename = "learningFactor")]
    learning_factor: Option<String>,
    #[serde(rename = "learningFactorFinal")]
    learning_factor_final: Option<String>,
    #[serde(rename = "learningFactorDecay")]
    learning_factor_decay: Option<String>,
    #[serde(rename = "learningRadius")]
    learning_radius: Option<String>,
    #[serde(rename = "learningRadiusFinal")]
    learning_radius_final: Option<String>,
    #[serde(rename = "learningRadiusDecay")]
    learning_radius_decay: Option<String>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawReproduction {
    offset: Option<String>,
    #[serde(rename = "idDecoding")]
    id_decoding: Option<String>,
    #[serde(rename = "maxLength")]
    max_length: Option<String>,
    stop: Option<String>,
    #[serde(rename = "lengthFactor")]
    length_factor: Option<String>,
    #[serde(rename = "maxLevel")]
    max_level: Option<String>,
    // retired settings, read only to name them in the error
    mode: Option<IgnoredAny>,
    #[serde(rename = "unseenFallback")]
    unseen_fallback: Option<IgnoredAny>,
    #[serde(rename = "minLengthFraction")]
    min_length_fraction: Option<IgnoredAny>,
    #[serde(rename = "stationarySteps")]
    stationary_steps: Option<IgnoredAny>,
    #[serde(rename = "stationaryTolerance")]
    stationary_tolerance: Option<IgnoredAny>,
    #[serde(rename = "confusionThreshold")]
    confusion_threshold: Option<IgnoredAny>,
    continuity: Option<IgnoredAny>,
    #[serde(rename = "endTolerance")]
    end_tolerance: Option<IgnoredAny>,
    #[serde(rename = "closedLoop")]
    closed_loop: Option<IgnoredAny>,
    reflex: Option<IgnoredAny>,
    timing: Option<IgnoredAny>,
    #[serde(rename = "minAccuracy")]
    min_accuracy: Option<IgnoredAny>,
    #[serde(rename = "loopVisits")]
    loop_visits: Option<IgnoredAny>,
    #[serde(rename = "loopWindow")]
    loop_window: Option<IgnoredAny>,
    #[serde(rename = "revisitSuccessors")]
    revisit_successors: Option<IgnoredAny>,
}

/// Each retired setting, whether `raw` names it, and what it is now.
fn retired(raw: &RawConfig) -> Vec<(&'static str, bool, &'static str)> {
    let mut out = vec![
        ("plan", raw.plan.is_some(), "plans always follow a training demonstration (what `traced` was)"),
        ("alignment", raw.alignment.is_some(), "the consensus always reads one demonstration along another without the warp's stairs (what `smooth` was)"),
        ("knots", raw.knots.is_some(), "a followed event of four samples or more always passes through two knots, one per half (what `halves` was)"),
        ("consensus", raw.consensus.is_some(), "the consensus always weighs the demonstrations by their starts where the starts predict the placements, all alike otherwise (what `start` was)"),
        ("partialTraining", raw.partial_training.is_some(), "an upper level of the paper algorithm trains once the list below is full (what `skip` was)"),
        ("listUpdate", raw.list_update.is_some(), "the paper algorithm's bottom list takes every step's BMU (what `everyStep` was); the events algorithm's lists hold events"),
    ];
    let Some(r) = &raw.reproduction else {
        return out;
    };
    let loops = "the paper algorithm executes what the hierarchy predicts, with no loop breaking";
    out.extend([
        ("reproduction/mode", r.mode.is_some(), "the paper's procedure taken literally (what `literal` was)"),
        ("reproduction/unseenFallback", r.unseen_fallback.is_some(), "a decoded node the training data never used is always replaced by the nearest used one (what `true` was)"),
        ("reproduction/minLengthFraction", r.min_length_fraction.is_some(), "the learned stop waits for 0.6 of the shortest demonstration"),
        ("reproduction/stationarySteps", r.stationary_steps.is_some(), "the learned stop's stationarity window is 60 steps"),
        ("reproduction/stationaryTolerance", r.stationary_tolerance.is_some(), "the learned stop's stationarity radius is one bottom quantization error"),
        ("reproduction/endTolerance", r.end_tolerance.is_some(), "the learned stop ends on a node where a demonstration ended (what 0 was)"),
        ("reproduction/confusionThreshold", r.confusion_threshold.is_some(), "every level with enough history predicts (what 0 was)"),
        ("reproduction/continuity", r.continuity.is_some(), "the next posture is the executed node's action half, the paper's output (what 0 was)"),
        ("reproduction/closedLoop", r.closed_loop.is_some(), "the predicted node is what the bottom list records (what `false` was)"),
        ("reproduction/minAccuracy", r.min_accuracy.is_some(), "every level with enough history predicts (what 0 was)"),
        ("reproduction/reflex", r.reflex.is_some(), "the reflex executes the BMU of the current posture, the paper's (what `bmu` was)"),
        ("reproduction/timing", r.timing.is_some(), "one posture per executed node, the paper's (what `step` was)"),
        ("reproduction/loopVisits", r.loop_visits.is_some(), loops),
        ("reproduction/loopWindow", r.loop_window.is_some(), loops),
        ("reproduction/revisitSuccessors", r.revisit_successors.is_some(), loops),
    ]);
    out
}

/// Each setting only one algorithm reads, whether `raw` names it, and that algorithm.
fn one_algorithm(raw: &RawConfig) -> Vec<(&'static str, bool, Algorithm)> {
    let r = raw.reproduction.as_ref();
    vec![
        (
            "updatePeriod",
            raw.update_period.is_some(),
            Algorithm::Paper,
        ),
        ("memoryMode", raw.memory_mode.is_some(), Algorithm::Paper),
        (
            "reproduction/offset",
            r.is_some_and(|r| r.offset.is_some()),
            Algorithm::Paper,
        ),
        (
            "reproduction/idDecoding",
            r.is_some_and(|r| r.id_decoding.is_some()),
            Algorithm::Paper,
        ),
        (
            "reproduction/stop",
            r.is_some_and(|r| r.stop.is_some()),
            Algorithm::Paper,
        ),
        ("changeRatio", raw.change_ratio.is_some(), Algorithm::Events),
        (
            "actionHorizon",
            raw.action_horizon.is_some(),
            Algorithm::Events,
        ),
    ]
}

/// Read, parse and validate a configuration file.
pub fn load_config(path: &Path) -> Result<HsomConfig, ConfigError> {
    let text = std::fs::read_to_string(path).map_err(|source| ConfigError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    parse_config(&text, &path.display().to_string())
}

fn line_col(text: &str, byte: usize) -> (usize, usize) {
    let byte = byte.min(text.len());
    let mut b = byte;
    while !text.is_char_boundary(b) {
        b -= 1;
    }
    let before = &text[..b];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Check well-formedness first, to report the line and column of a syntax error.
fn check_well_formed(text: &str, file: &str) -> Result<(), ConfigError> {
    let mut reader = quick_xml::Reader::from_str(text);
    reader.config_mut().check_end_names = true;
    let mut depth: i64 = 0;
    let mut roots = 0;
    // per open element: its name, whether it holds text, whether it holds elements (no
    // element of the schema holds both: such mixed content is an error naming the element)
    let mut open: Vec<(Vec<u8>, bool, bool)> = Vec::new();
    let mixed =
        |open: &[(Vec<u8>, bool, bool)], reader: &quick_xml::Reader<&[u8]>| match open.last() {
            Some((name, true, true)) => Err(malformed_here(
                text,
                file,
                reader,
                format!(
                    "<{}> holds both text and elements; a value element holds only its value, \
                     a group only elements",
                    String::from_utf8_lossy(name)
                ),
            )),
            _ => Ok(()),
        };
    loop {
        match reader.read_event() {
            Ok(Event::Eof) => break,
            Ok(Event::Start(e)) => {
                if depth == 0 {
                    roots += 1;
                    check_root(text, file, e.name().as_ref(), &reader)?;
                }
                if let Some(top) = open.last_mut() {
                    top.2 = true;
                }
                mixed(&open, &reader)?;
                open.push((e.name().as_ref().to_vec(), false, false));
                depth += 1;
            }
            Ok(Event::Empty(e)) => {
                if depth == 0 {
                    roots += 1;
                    check_root(text, file, e.name().as_ref(), &reader)?;
                }
                if let Some(top) = open.last_mut() {
                    top.2 = true;
                }
                mixed(&open, &reader)?;
            }
            Ok(Event::Text(t)) => {
                if !t.iter().all(|b| b.is_ascii_whitespace()) {
                    if let Some(top) = open.last_mut() {
                        top.1 = true;
                    }
                    mixed(&open, &reader)?;
                }
            }
            Ok(Event::End(_)) => {
                open.pop();
                depth -= 1
            }
            Ok(_) => {}
            Err(e) => {
                let (line, column) = line_col(text, reader.error_position() as usize);
                return Err(ConfigError::Malformed {
                    file: file.to_string(),
                    line,
                    column,
                    message: e.to_string(),
                });
            }
        }
    }
    if depth != 0 || roots != 1 {
        let (line, column) = line_col(text, text.len());
        return Err(ConfigError::Malformed {
            file: file.to_string(),
            line,
            column,
            message: if roots == 0 {
                "no root element".into()
            } else if depth != 0 {
                "unclosed element at end of file".into()
            } else {
                "more than one root element".into()
            },
        });
    }
    Ok(())
}

/// The root element must be `<hsom>` (another XML document, an MJCF model say, is not a
/// configuration even when some of its element names match).
fn check_root(
    text: &str,
    file: &str,
    name: &[u8],
    reader: &quick_xml::Reader<&[u8]>,
) -> Result<(), ConfigError> {
    if name == b"hsom" {
        return Ok(());
    }
    Err(malformed_here(
        text,
        file,
        reader,
        format!(
            "the root element is <{}>, a CoSCo-HSOM configuration's is <hsom>",
            String::from_utf8_lossy(name)
        ),
    ))
}

/// A [`ConfigError::Malformed`] at the reader's position.
fn malformed_here(
    text: &str,
    file: &str,
    reader: &quick_xml::Reader<&[u8]>,
    message: String,
) -> ConfigError {
    let (line, column) = line_col(text, reader.buffer_position() as usize);
    ConfigError::Malformed {
        file: file.to_string(),
        line,
        column,
        message,
    }
}

struct Fields<'a> {
    file: &'a str,
}

impl Fields<'_> {
    fn missing(&self, field: &str) -> ConfigError {
        ConfigError::Missing {
            file: self.file.to_string(),
            field: field.to_string(),
        }
    }
    fn invalid(&self, field: &str, value: &str, reason: &str) -> ConfigError {
        ConfigError::Invalid {
            file: self.file.to_string(),
            field: field.to_string(),
            value: value.to_string(),
            reason: reason.to_string(),
        }
    }
    fn req<T: std::str::FromStr>(&self, field: &str, v: &Option<String>) -> Result<T, ConfigError> {
        match v {
            None => Err(self.missing(field)),
            Some(s) => self.parse(field, s),
        }
    }
    fn opt<T: std::str::FromStr>(
        &self,
        field: &str,
        v: &Option<String>,
        default: T,
    ) -> Result<T, ConfigError> {
        match v {
            None => Ok(default),
            Some(s) => self.parse(field, s),
        }
    }
    fn parse<T: std::str::FromStr>(&self, field: &str, s: &str) -> Result<T, ConfigError> {
        s.trim().parse::<T>().map_err(|_| {
            let what = std::any::type_name::<T>();
            let reason = if what.contains("f64") {
                "expected a number".to_string()
            } else if what.contains("bool") {
                "expected true or false".to_string()
            } else {
                "expected a non-negative integer".to_string()
            };
            self.invalid(field, s, &reason)
        })
    }
    fn name<T>(
        &self,
        field: &str,
        v: &Option<String>,
        default: T,
        f: impl Fn(&str) -> Option<T>,
        allowed: &str,
    ) -> Result<T, ConfigError> {
        match v {
            None => Ok(default),
            Some(s) => {
                f(s).ok_or_else(|| self.invalid(field, s, &format!("expected one of {allowed}")))
            }
        }
    }
}

fn word<'a, T: Copy>(table: &'a [(&'a str, T)]) -> impl Fn(&str) -> Option<T> + 'a {
    move |s: &str| {
        let s = s.trim().to_ascii_lowercase();
        table
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(&s))
            .map(|(_, v)| *v)
    }
}

/// Parse and validate a configuration held in `text`; `file` names it in error messages.
/// Omitted settings take the values of [`HsomParams::recommended`] (`algorithm = events`, the
/// default) or [`HsomParams::table1`] (`algorithm = paper`); a retired setting, or one the
/// chosen algorithm does not read, is an error naming it.
pub fn parse_config(text: &str, file: &str) -> Result<HsomConfig, ConfigError> {
    check_well_formed(text, file)?;
    let raw: RawConfig = quick_xml::de::from_str(text).map_err(|e| ConfigError::Schema {
        file: file.to_string(),
        message: e.to_string(),
    })?;
    let f = Fields { file };
    if let Some(v) = &raw.version {
        if v.trim() != "1" {
            return Err(f.invalid("hsom/@version", v, "expected 1"));
        }
    }
    if let Some((field, _, now)) = retired(&raw).into_iter().find(|r| r.1) {
        return Err(ConfigError::Retired {
            file: file.to_string(),
            field: field.to_string(),
            now: now.to_string(),
        });
    }
    let algorithm = f.name(
        "algorithm",
        &raw.algorithm,
        Algorithm::Events,
        word(&[("paper", Algorithm::Paper), ("events", Algorithm::Events)]),
        "paper, events",
    )?;
    if let Some((field, _, reads)) = one_algorithm(&raw)
        .into_iter()
        .find(|r| r.1 && r.2 != algorithm)
    {
        return Err(ConfigError::NotRead {
            file: file.to_string(),
            field: field.to_string(),
            reads: reads.name().to_string(),
            chosen: algorithm.name().to_string(),
        });
    }
    let base = match algorithm {
        Algorithm::Paper => HsomParams::table1(),
        Algorithm::Events => HsomParams::recommended(),
    };
    let height: usize = f.opt("height", &raw.height, base.height)?;
    let memory: usize = f.opt("memory", &raw.memory, base.memory)?;
    let levels = match &raw.levels {
        None => base.levels.clone(),
        Some(raw_levels) => parse_levels(&f, raw_levels, height)?,
    };
    let d = base.reproduction.clone();
    let empty = RawReproduction::default();
    let r = raw.reproduction.as_ref().unwrap_or(&empty);
    let reproduction = super::hyperparams::ReproductionParams {
        max_length: f.opt("reproduction/maxLength", &r.max_length, d.max_length)?,
        max_level: match &r.max_level {
            None => d.max_level,
            Some(s) => Some(f.parse("reproduction/maxLevel", s)?),
        },
        length_factor: f.opt(
            "reproduction/lengthFactor",
            &r.length_factor,
            d.length_factor,
        )?,
    };
    let algorithm = match &base.algorithm {
        AlgorithmParams::Paper(q) => AlgorithmParams::Paper(PaperParams {
            update_period: f.opt("updatePeriod", &raw.update_period, q.update_period)?,
            memory_mode: f.name(
                "memoryMode",
                &raw.memory_mode,
                q.memory_mode,
                word(&[("lists", MemoryMode::Lists), ("levels", MemoryMode::Levels)]),
                "lists, levels",
            )?,
            offset: f.opt(
                "reproduction/offset",
                &r.offset,
                memory.saturating_sub(1).max(1),
            )?,
            id_decoding: f.name(
                "reproduction/idDecoding",
                &r.id_decoding,
                q.id_decoding,
                word(&[
                    ("round", IdDecoding::Round),
                    ("floor", IdDecoding::Floor),
                    ("nearest", IdDecoding::Nearest),
                ]),
                "round, floor, nearest",
            )?,
            stop: f.name(
                "reproduction/stop",
                &r.stop,
                q.stop,
                word(&[
                    ("learned", StopRule::Learned),
                    ("maxlength", StopRule::MaxLength),
                ]),
                "learned, maxLength",
            )?,
        }),
        AlgorithmParams::Events(q) => AlgorithmParams::Events(EventsParams {
            change_ratio: f.opt("changeRatio", &raw.change_ratio, q.change_ratio)?,
            action_horizon: f.opt("actionHorizon", &raw.action_horizon, q.action_horizon)?,
        }),
    };
    let params = HsomParams {
        seed: f.opt("seed", &raw.seed, base.seed)?,
        height,
        memory,
        state_length: f.opt("stateLength", &raw.state_length, base.state_length)?,
        action_length: f.opt("actionLength", &raw.action_length, base.action_length)?,
        training_steps: f.opt("trainingSteps", &raw.training_steps, base.training_steps)?,
        normalisation: f.name(
            "normalisation",
            &raw.normalisation,
            base.normalisation,
            word(&[
                ("global", Normalisation::Global),
                ("perdimension", Normalisation::PerDimension),
                ("none", Normalisation::None),
            ]),
            "global, perDimension, none",
        )?,
        levels,
        reproduction,
        algorithm,
    };
    params.check(file)
}

/// The `<level>` elements of `raw_levels`, in index order, for a hierarchy of `height`.
fn parse_levels(
    f: &Fields,
    raw_levels: &RawLevels,
    height: usize,
) -> Result<Vec<LevelParams>, ConfigError> {
    let file = f.file;
    let n = raw_levels.level.len();
    // every index 0..height-1 once: which one is missing, or which one is out of range
    let given: Vec<Option<usize>> = raw_levels
        .level
        .iter()
        .enumerate()
        .map(|(pos, rl)| {
            rl.index
                .as_ref()
                .map_or(Some(pos), |s| s.trim().parse().ok())
        })
        .collect();
    if let Some(missing) = (0..height.min(1 << 16)).find(|i| !given.contains(&Some(*i))) {
        let mut distinct = given.clone();
        distinct.sort();
        distinct.dedup();
        // a duplicate or unparsable index is reported below, more precisely
        if given.iter().all(|g| g.is_some()) && distinct.len() == n && n <= height {
            return Err(ConfigError::MissingLevel {
                file: file.to_string(),
                index: missing,
                height,
                listed: n,
            });
        }
    }
    let mut levels: Vec<Option<LevelParams>> = vec![None; n];
    for (pos, rl) in raw_levels.level.iter().enumerate() {
        let idx: usize = match &rl.index {
            Some(s) => f.parse(&format!("levels/level[{pos}]/@index"), s)?,
            None => pos,
        };
        let p = |name: &str| format!("levels/level[{idx}]/{name}");
        if idx >= n {
            return Err(f.invalid(
                &format!("levels/level[{pos}]/@index"),
                &idx.to_string(),
                &format!("level indices must be 0..{} ({} levels listed)", n, n),
            ));
        }
        if levels[idx].is_some() {
            return Err(f.invalid(&p("@index"), &idx.to_string(), "index given twice"));
        }
        let rows: usize = f.req(&p("rows"), &rl.rows)?;
        let cols: usize = f.req(&p("cols"), &rl.cols)?;
        let topology = match &rl.topology {
            None => return Err(f.missing(&p("topology"))),
            Some(s) => Topology::from_name(s)
                .ok_or_else(|| f.invalid(&p("topology"), s, "expected orthogonal or hexagonal"))?,
        };
        let alpha: f64 = f.req(&p("learningFactor"), &rl.learning_factor)?;
        let mut lp = LevelParams::new(rows, cols, topology, alpha);
        lp.neighbourhood = f.name(
            &p("neighbourhood"),
            &rl.neighbourhood,
            lp.neighbourhood,
            Neighbourhood::from_name,
            "gaussian, bubble",
        )?;
        let decays = "exponential, linear, constant";
        lp.learning_factor = Schedule {
            initial: alpha,
            last: f.opt(
                &p("learningFactorFinal"),
                &rl.learning_factor_final,
                lp.learning_factor.last,
            )?,
            decay: f.name(
                &p("learningFactorDecay"),
                &rl.learning_factor_decay,
                Decay::Exponential,
                Decay::from_name,
                decays,
            )?,
        };
        let r0: f64 = f.opt(
            &p("learningRadius"),
            &rl.learning_radius,
            lp.learning_radius.initial,
        )?;
        lp.learning_radius = Schedule {
            initial: r0,
            last: f.opt(
                &p("learningRadiusFinal"),
                &rl.learning_radius_final,
                0.5f64.min(r0),
            )?,
            decay: f.name(
                &p("learningRadiusDecay"),
                &rl.learning_radius_decay,
                Decay::Exponential,
                Decay::from_name,
                decays,
            )?,
        };
        levels[idx] = Some(lp);
    }
    Ok(levels.into_iter().flatten().collect())
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
        use std::fmt::Write;
        let p = self.params();
        let mut s = String::new();
        let _ = writeln!(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
        let _ = writeln!(s, "<hsom version=\"1\">");
        let _ = writeln!(s, "  <seed>{}</seed>", p.seed);
        let _ = writeln!(s, "  <algorithm>{}</algorithm>", p.kind().name());
        let _ = writeln!(s, "  <height>{}</height>", p.height);
        let _ = writeln!(s, "  <memory>{}</memory>", p.memory);
        let _ = writeln!(s, "  <stateLength>{}</stateLength>", p.state_length);
        let _ = writeln!(s, "  <actionLength>{}</actionLength>", p.action_length);
        let _ = writeln!(s, "  <trainingSteps>{}</trainingSteps>", p.training_steps);
        let nm = match p.normalisation {
            Normalisation::Global => "global",
            Normalisation::PerDimension => "perDimension",
            Normalisation::None => "none",
        };
        let _ = writeln!(s, "  <normalisation>{nm}</normalisation>");
        match &p.algorithm {
            AlgorithmParams::Paper(q) => {
                let _ = writeln!(s, "  <updatePeriod>{}</updatePeriod>", q.update_period);
                let mm = match q.memory_mode {
                    MemoryMode::Lists => "lists",
                    MemoryMode::Levels => "levels",
                };
                let _ = writeln!(s, "  <memoryMode>{mm}</memoryMode>");
            }
            AlgorithmParams::Events(q) => {
                let _ = writeln!(s, "  <changeRatio>{}</changeRatio>", q.change_ratio);
                let _ = writeln!(s, "  <actionHorizon>{}</actionHorizon>", q.action_horizon);
            }
        }
        let _ = writeln!(s, "  <levels>");
        for (i, l) in p.levels.iter().enumerate().rev() {
            let _ = writeln!(s, "    <level index=\"{i}\">");
            let _ = writeln!(s, "      <rows>{}</rows>", l.rows);
            let _ = writeln!(s, "      <cols>{}</cols>", l.cols);
            let _ = writeln!(s, "      <topology>{}</topology>", l.topology.name());
            let _ = writeln!(
                s,
                "      <neighbourhood>{}</neighbourhood>",
                l.neighbourhood.name()
            );
            for (name, sch) in [
                ("learningFactor", &l.learning_factor),
                ("learningRadius", &l.learning_radius),
            ] {
                let _ = writeln!(s, "      <{name}>{}</{name}>", sch.initial);
                let _ = writeln!(s, "      <{name}Final>{}</{name}Final>", sch.last);
                let _ = writeln!(s, "      <{name}Decay>{}</{name}Decay>", sch.decay.name());
            }
            let _ = writeln!(s, "    </level>");
        }
        let _ = writeln!(s, "  </levels>");
        let r = &p.reproduction;
        let _ = writeln!(s, "  <reproduction>");
        let _ = writeln!(s, "    <maxLength>{}</maxLength>", r.max_length);
        let _ = writeln!(s, "    <lengthFactor>{}</lengthFactor>", r.length_factor);
        if let Some(m) = r.max_level {
            let _ = writeln!(s, "    <maxLevel>{m}</maxLevel>");
        }
        if let Some(q) = p.paper() {
            let _ = writeln!(s, "    <offset>{}</offset>", q.offset);
            let dec = match q.id_decoding {
                IdDecoding::Round => "round",
                IdDecoding::Floor => "floor",
                IdDecoding::Nearest => "nearest",
            };
            let _ = writeln!(s, "    <idDecoding>{dec}</idDecoding>");
            let stop = match q.stop {
                StopRule::Learned => "learned",
                StopRule::MaxLength => "maxLength",
            };
            let _ = writeln!(s, "    <stop>{stop}</stop>");
        }
        let _ = writeln!(s, "  </reproduction>");
        let _ = writeln!(s, "</hsom>");
        s
    }
}
