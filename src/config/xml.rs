//! Reading and writing the XML form of the configuration (quick-xml + serde).

use std::path::Path;

use quick_xml::events::Event;
use serde::Deserialize;

use crate::som::{Decay, Neighbourhood, Schedule, Topology};

use super::errors::ConfigError;
use super::hyperparams::{
    Algorithm, Alignment, Consensus, HsomConfig, HsomParams, IdDecoding, Knots, LevelParams,
    ListUpdate, MemoryMode, Normalisation, PartialTraining, Plan, Reflex, ReproductionMode,
    ReproductionParams, StopRule, Timing,
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
    consensus: Option<String>,
    alignment: Option<String>,
    plan: Option<String>,
    knots: Option<String>,
    #[serde(rename = "partialTraining")]
    partial_training: Option<String>,
    #[serde(rename = "listUpdate")]
    list_update: Option<String>,
    #[serde(rename = "changeRatio")]
    change_ratio: Option<String>,
    #[serde(rename = "actionHorizon")]
    action_horizon: Option<String>,
    algorithm: Option<String>,
    levels: Option<RawLevels>,
    reproduction: Option<RawReproduction>,
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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawReproduction {
    offset: Option<String>,
    mode: Option<String>,
    #[serde(rename = "idDecoding")]
    id_decoding: Option<String>,
    #[serde(rename = "unseenFallback")]
    unseen_fallback: Option<String>,
    #[serde(rename = "maxLength")]
    max_length: Option<String>,
    stop: Option<String>,
    #[serde(rename = "minLengthFraction")]
    min_length_fraction: Option<String>,
    #[serde(rename = "lengthFactor")]
    length_factor: Option<String>,
    #[serde(rename = "stationarySteps")]
    stationary_steps: Option<String>,
    #[serde(rename = "confusionThreshold")]
    confusion_threshold: Option<String>,
    #[serde(rename = "maxLevel")]
    max_level: Option<String>,
    continuity: Option<String>,
    #[serde(rename = "endTolerance")]
    end_tolerance: Option<String>,
    #[serde(rename = "stationaryTolerance")]
    stationary_tolerance: Option<String>,
    #[serde(rename = "closedLoop")]
    closed_loop: Option<String>,
    reflex: Option<String>,
    timing: Option<String>,
    #[serde(rename = "minAccuracy")]
    min_accuracy: Option<String>,
    #[serde(rename = "loopVisits")]
    loop_visits: Option<String>,
    #[serde(rename = "loopWindow")]
    loop_window: Option<String>,
    #[serde(rename = "revisitSuccessors")]
    revisit_successors: Option<String>,
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
    let height: usize = f.req("height", &raw.height)?;
    let memory: usize = f.req("memory", &raw.memory)?;
    let raw_levels = raw.levels.as_ref().ok_or_else(|| f.missing("levels"))?;
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
    let levels: Vec<LevelParams> = levels.into_iter().flatten().collect();
    let d = ReproductionParams::default();
    let reproduction = match &raw.reproduction {
        None => ReproductionParams {
            offset: memory.saturating_sub(1).max(1),
            ..d
        },
        Some(r) => ReproductionParams {
            offset: f.opt(
                "reproduction/offset",
                &r.offset,
                memory.saturating_sub(1).max(1),
            )?,
            mode: f.name(
                "reproduction/mode",
                &r.mode,
                d.mode,
                word(&[
                    ("literal", ReproductionMode::Literal),
                    ("strided", ReproductionMode::Strided),
                ]),
                "literal, strided",
            )?,
            id_decoding: f.name(
                "reproduction/idDecoding",
                &r.id_decoding,
                d.id_decoding,
                word(&[
                    ("round", IdDecoding::Round),
                    ("floor", IdDecoding::Floor),
                    ("nearest", IdDecoding::Nearest),
                ]),
                "round, floor, nearest",
            )?,
            unseen_fallback: f.opt(
                "reproduction/unseenFallback",
                &r.unseen_fallback,
                d.unseen_fallback,
            )?,
            max_length: f.opt("reproduction/maxLength", &r.max_length, d.max_length)?,
            stop: f.name(
                "reproduction/stop",
                &r.stop,
                d.stop,
                word(&[
                    ("learned", StopRule::Learned),
                    ("maxlength", StopRule::MaxLength),
                ]),
                "learned, maxLength",
            )?,
            min_length_fraction: f.opt(
                "reproduction/minLengthFraction",
                &r.min_length_fraction,
                d.min_length_fraction,
            )?,
            length_factor: f.opt(
                "reproduction/lengthFactor",
                &r.length_factor,
                d.length_factor,
            )?,
            stationary_steps: f.opt(
                "reproduction/stationarySteps",
                &r.stationary_steps,
                d.stationary_steps,
            )?,
            confusion_threshold: f.opt(
                "reproduction/confusionThreshold",
                &r.confusion_threshold,
                d.confusion_threshold,
            )?,
            max_level: match &r.max_level {
                None => None,
                Some(s) => Some(f.parse("reproduction/maxLevel", s)?),
            },
            continuity: f.opt("reproduction/continuity", &r.continuity, d.continuity)?,
            end_tolerance: f.opt(
                "reproduction/endTolerance",
                &r.end_tolerance,
                d.end_tolerance,
            )?,
            stationary_tolerance: f.opt(
                "reproduction/stationaryTolerance",
                &r.stationary_tolerance,
                d.stationary_tolerance,
            )?,
            closed_loop: f.opt("reproduction/closedLoop", &r.closed_loop, d.closed_loop)?,
            min_accuracy: f.opt("reproduction/minAccuracy", &r.min_accuracy, d.min_accuracy)?,
            loop_visits: f.opt("reproduction/loopVisits", &r.loop_visits, d.loop_visits)?,
            loop_window: f.opt("reproduction/loopWindow", &r.loop_window, d.loop_window)?,
            revisit_successors: f.opt(
                "reproduction/revisitSuccessors",
                &r.revisit_successors,
                d.revisit_successors,
            )?,
            reflex: f.name(
                "reproduction/reflex",
                &r.reflex,
                d.reflex,
                word(&[("bmu", Reflex::Bmu), ("successor", Reflex::Successor)]),
                "bmu, successor",
            )?,
            timing: f.name(
                "reproduction/timing",
                &r.timing,
                d.timing,
                word(&[
                    ("step", Timing::Step),
                    ("dwell", Timing::Dwell),
                    ("speed", Timing::Speed),
                ]),
                "step, dwell, speed",
            )?,
        },
    };
    let params = HsomParams {
        seed: f.opt("seed", &raw.seed, 1u64)?,
        height,
        memory,
        update_period: f.req("updatePeriod", &raw.update_period)?,
        state_length: f.req("stateLength", &raw.state_length)?,
        action_length: f.req("actionLength", &raw.action_length)?,
        training_steps: f.req("trainingSteps", &raw.training_steps)?,
        memory_mode: f.name(
            "memoryMode",
            &raw.memory_mode,
            MemoryMode::Lists,
            word(&[("lists", MemoryMode::Lists), ("levels", MemoryMode::Levels)]),
            "lists, levels",
        )?,
        normalisation: f.name(
            "normalisation",
            &raw.normalisation,
            Normalisation::Global,
            word(&[
                ("global", Normalisation::Global),
                ("perdimension", Normalisation::PerDimension),
                ("none", Normalisation::None),
            ]),
            "global, perDimension, none",
        )?,
        consensus: f.name(
            "consensus",
            &raw.consensus,
            Consensus::Start,
            word(&[
                ("all", Consensus::All),
                ("local", Consensus::Local),
                ("start", Consensus::Start),
            ]),
            "all, local, start",
        )?,
        alignment: f.name(
            "alignment",
            &raw.alignment,
            Alignment::Stepped,
            word(&[
                ("stepped", Alignment::Stepped),
                ("smooth", Alignment::Smooth),
            ]),
            "stepped, smooth",
        )?,
        knots: f.name(
            "knots",
            &raw.knots,
            Knots::Event,
            word(&[("event", Knots::Event), ("halves", Knots::Halves)]),
            "event, halves",
        )?,
        plan: f.name(
            "plan",
            &raw.plan,
            Plan::Decoded,
            word(&[("traced", Plan::Traced), ("decoded", Plan::Decoded)]),
            "traced, decoded",
        )?,
        partial_training: f.name(
            "partialTraining",
            &raw.partial_training,
            PartialTraining::Skip,
            word(&[
                ("skip", PartialTraining::Skip),
                ("masked", PartialTraining::Masked),
            ]),
            "skip, masked",
        )?,
        list_update: f.name(
            "listUpdate",
            &raw.list_update,
            ListUpdate::EveryStep,
            word(&[
                ("everystep", ListUpdate::EveryStep),
                ("onchange", ListUpdate::OnChange),
            ]),
            "everyStep, onChange",
        )?,
        change_ratio: f.opt("changeRatio", &raw.change_ratio, 1.0)?,
        action_horizon: f.opt("actionHorizon", &raw.action_horizon, 1usize)?,
        algorithm: f.name(
            "algorithm",
            &raw.algorithm,
            Algorithm::Paper,
            word(&[("paper", Algorithm::Paper), ("events", Algorithm::Events)]),
            "paper, events",
        )?,
        levels,
        reproduction,
    };
    params.check(file)
}

impl HsomConfig {
    /// The configuration as an XML document that [`parse_config`] reads back to an equal
    /// configuration (every optional value written out).
    pub fn to_xml(&self) -> String {
        use std::fmt::Write;
        let p = self.params();
        let mut s = String::new();
        let _ = writeln!(s, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
        let _ = writeln!(s, "<hsom version=\"1\">");
        let _ = writeln!(s, "  <seed>{}</seed>", p.seed);
        let _ = writeln!(s, "  <height>{}</height>", p.height);
        let _ = writeln!(s, "  <memory>{}</memory>", p.memory);
        let _ = writeln!(s, "  <updatePeriod>{}</updatePeriod>", p.update_period);
        let _ = writeln!(s, "  <stateLength>{}</stateLength>", p.state_length);
        let _ = writeln!(s, "  <actionLength>{}</actionLength>", p.action_length);
        let _ = writeln!(s, "  <trainingSteps>{}</trainingSteps>", p.training_steps);
        let mm = match p.memory_mode {
            MemoryMode::Lists => "lists",
            MemoryMode::Levels => "levels",
        };
        let _ = writeln!(s, "  <memoryMode>{mm}</memoryMode>");
        let nm = match p.normalisation {
            Normalisation::Global => "global",
            Normalisation::PerDimension => "perDimension",
            Normalisation::None => "none",
        };
        let _ = writeln!(s, "  <normalisation>{nm}</normalisation>");
        let cs = match p.consensus {
            Consensus::All => "all",
            Consensus::Local => "local",
            Consensus::Start => "start",
        };
        let _ = writeln!(s, "  <consensus>{cs}</consensus>");
        let _ = writeln!(s, "  <alignment>{}</alignment>", p.alignment.name());
        let pl = match p.plan {
            Plan::Traced => "traced",
            Plan::Decoded => "decoded",
        };
        let _ = writeln!(s, "  <plan>{pl}</plan>");
        let _ = writeln!(s, "  <knots>{}</knots>", p.knots.name());
        let pt = match p.partial_training {
            PartialTraining::Skip => "skip",
            PartialTraining::Masked => "masked",
        };
        let _ = writeln!(s, "  <partialTraining>{pt}</partialTraining>");
        let lu = match p.list_update {
            ListUpdate::EveryStep => "everyStep",
            ListUpdate::OnChange => "onChange",
        };
        let _ = writeln!(s, "  <listUpdate>{lu}</listUpdate>");
        let _ = writeln!(s, "  <changeRatio>{}</changeRatio>", p.change_ratio);
        let _ = writeln!(s, "  <actionHorizon>{}</actionHorizon>", p.action_horizon);
        let alg = match p.algorithm {
            Algorithm::Paper => "paper",
            Algorithm::Events => "events",
        };
        let _ = writeln!(s, "  <algorithm>{alg}</algorithm>");
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
            let _ = writeln!(
                s,
                "      <learningFactor>{}</learningFactor>",
                l.learning_factor.initial
            );
            let _ = writeln!(
                s,
                "      <learningFactorFinal>{}</learningFactorFinal>",
                l.learning_factor.last
            );
            let _ = writeln!(
                s,
                "      <learningFactorDecay>{}</learningFactorDecay>",
                l.learning_factor.decay.name()
            );
            let _ = writeln!(
                s,
                "      <learningRadius>{}</learningRadius>",
                l.learning_radius.initial
            );
            let _ = writeln!(
                s,
                "      <learningRadiusFinal>{}</learningRadiusFinal>",
                l.learning_radius.last
            );
            let _ = writeln!(
                s,
                "      <learningRadiusDecay>{}</learningRadiusDecay>",
                l.learning_radius.decay.name()
            );
            let _ = writeln!(s, "    </level>");
        }
        let _ = writeln!(s, "  </levels>");
        let r = &p.reproduction;
        let _ = writeln!(s, "  <reproduction>");
        let _ = writeln!(s, "    <offset>{}</offset>", r.offset);
        let mode = match r.mode {
            ReproductionMode::Literal => "literal",
            ReproductionMode::Strided => "strided",
        };
        let _ = writeln!(s, "    <mode>{mode}</mode>");
        let dec = match r.id_decoding {
            IdDecoding::Round => "round",
            IdDecoding::Floor => "floor",
            IdDecoding::Nearest => "nearest",
        };
        let _ = writeln!(s, "    <idDecoding>{dec}</idDecoding>");
        let _ = writeln!(
            s,
            "    <unseenFallback>{}</unseenFallback>",
            r.unseen_fallback
        );
        let _ = writeln!(s, "    <maxLength>{}</maxLength>", r.max_length);
        let stop = match r.stop {
            StopRule::Learned => "learned",
            StopRule::MaxLength => "maxLength",
        };
        let _ = writeln!(s, "    <stop>{stop}</stop>");
        let _ = writeln!(
            s,
            "    <minLengthFraction>{}</minLengthFraction>",
            r.min_length_fraction
        );
        let _ = writeln!(s, "    <lengthFactor>{}</lengthFactor>", r.length_factor);
        let _ = writeln!(
            s,
            "    <stationarySteps>{}</stationarySteps>",
            r.stationary_steps
        );
        let _ = writeln!(
            s,
            "    <confusionThreshold>{}</confusionThreshold>",
            r.confusion_threshold
        );
        let _ = writeln!(s, "    <continuity>{}</continuity>", r.continuity);
        let _ = writeln!(s, "    <endTolerance>{}</endTolerance>", r.end_tolerance);
        let _ = writeln!(
            s,
            "    <stationaryTolerance>{}</stationaryTolerance>",
            r.stationary_tolerance
        );
        let _ = writeln!(s, "    <closedLoop>{}</closedLoop>", r.closed_loop);
        let rf = match r.reflex {
            Reflex::Bmu => "bmu",
            Reflex::Successor => "successor",
        };
        let _ = writeln!(s, "    <minAccuracy>{}</minAccuracy>", r.min_accuracy);
        let _ = writeln!(s, "    <reflex>{rf}</reflex>");
        let _ = writeln!(s, "    <loopVisits>{}</loopVisits>", r.loop_visits);
        let _ = writeln!(s, "    <loopWindow>{}</loopWindow>", r.loop_window);
        let _ = writeln!(
            s,
            "    <revisitSuccessors>{}</revisitSuccessors>",
            r.revisit_successors
        );
        let tm = match r.timing {
            Timing::Step => "step",
            Timing::Dwell => "dwell",
            Timing::Speed => "speed",
        };
        let _ = writeln!(s, "    <timing>{tm}</timing>");
        if let Some(m) = r.max_level {
            let _ = writeln!(s, "    <maxLevel>{m}</maxLevel>");
        }
        let _ = writeln!(s, "  </reproduction>");
        let _ = writeln!(s, "</hsom>");
        s
    }
}
