//! The sweep's spec file (TOML, `docs/SWEEPS.md`): axes of values, read and checked once,
//! up front, into a [`SweepSpec`] whose grid ([`SweepSpec::runs`]) is in a fixed order.
//! Every configuration file is read, hashed and checked with every height override (and
//! against the joints of every robot) before any run starts.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::de::value::StrDeserializer;
use serde::de::{DeserializeOwned, IntoDeserializer};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use crate::config::{load_config, HsomConfig};
use crate::eval::Method;
use crate::experiment::demonstrate::parse_seeds;
use crate::experiment::Transition;
use crate::robot::Robot;

use super::robots::{self, check_gesture, load_model, robot_names, shared_default_gesture};
use super::SweepError;

/// The axes in grid order: the first varies slowest, `seed` fastest. The replicates (seeds)
/// of one setting are neighbours, so `index % N` deals every setting, cheap or costly,
/// evenly over N shards. A robot is paired only with the configurations of its width
/// (`stateLength` = its joints), so with several robots the grid is not the whole product.
pub const AXES: [&str; 9] = [
    "method",
    "evaluation",
    "robot",
    "config",
    "height",
    "count",
    "noise",
    "gesture",
    "seed",
];

/// Which method(s) a run executes: a selection of the evaluator's methods
/// ([`eval::Method`]), spelt as in spec files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MethodAxis {
    /// CoSCo-HSOM alone ([`eval::Method::Hierarchy`]).
    CoscoHsom,
    /// The GMM/GMR baseline alone ([`eval::Method::GmmGmr`]).
    Gmr,
    /// Both, on the same demonstrations.
    Both,
    /// The ProMP baseline alone ([`eval::Method::ProMP`]).
    Promp,
    /// The DMP baseline alone ([`eval::Method::Dmp`]).
    Dmp,
    /// The DTW mean alone ([`eval::Method::Dba`]).
    Dba,
}

impl MethodAxis {
    /// The name in spec files and tables.
    pub fn name(self) -> &'static str {
        match self {
            MethodAxis::CoscoHsom => "cosco-hsom",
            MethodAxis::Gmr => "gmr",
            MethodAxis::Both => "both",
            MethodAxis::Promp => "promp",
            MethodAxis::Dmp => "dmp",
            MethodAxis::Dba => "dba",
        }
    }

    /// The evaluator's methods this value runs, in order.
    pub fn singles(self) -> &'static [Method] {
        match self {
            MethodAxis::CoscoHsom => &[Method::Hierarchy],
            MethodAxis::Gmr => &[Method::GmmGmr],
            MethodAxis::Both => &[Method::Hierarchy, Method::GmmGmr],
            MethodAxis::Promp => &[Method::ProMP],
            MethodAxis::Dmp => &[Method::Dmp],
            MethodAxis::Dba => &[Method::Dba],
        }
    }
}

/// A single method's name in run files and tables: the spec file's spelling
/// (`cosco-hsom`, `gmr`, `promp`, `dmp`) for those a sweep runs, the evaluator's otherwise.
pub fn method_name(m: Method) -> &'static str {
    match m {
        Method::Hierarchy => MethodAxis::CoscoHsom.name(),
        Method::GmmGmr => MethodAxis::Gmr.name(),
        Method::ProMP => MethodAxis::Promp.name(),
        Method::Dmp => MethodAxis::Dmp.name(),
        Method::Dba => MethodAxis::Dba.name(),
        other => other.name(),
    }
}

/// [`Method`] in run files, by [`method_name`].
pub(crate) mod method_serde {
    use super::{method_name, Method};

    /// Write the method's name.
    pub fn serialize<S: serde::Serializer>(m: &Method, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(method_name(*m))
    }

    /// Read a method's name back.
    pub fn deserialize<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Method, D::Error> {
        let text = <String as serde::Deserialize>::deserialize(d)?;
        Method::ALL
            .into_iter()
            .find(|&m| method_name(m) == text)
            .ok_or_else(|| serde::de::Error::custom(format!("unknown method '{text}'")))
    }
}

/// How a run is scored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Evaluation {
    /// Learn from all demonstrations, score against all.
    InSample,
    /// Each demonstration held out in turn (`experiment::heldout`), means over the folds.
    LeaveOneOut,
}

impl Evaluation {
    /// The name in spec files and tables.
    pub fn name(self) -> &'static str {
        match self {
            Evaluation::InSample => "in-sample",
            Evaluation::LeaveOneOut => "leave-one-out",
        }
    }
}

/// The height override of a run: the configuration's own height, or its lowest levels.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Height {
    /// The configuration as written (`"config"` in the spec).
    Config(ConfigHeight),
    /// The configuration's lowest `n` levels ([`HsomConfig::at_height`]).
    Levels(usize),
}

/// The word `config` (the configuration's own height).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ConfigHeight {
    /// The configuration's own height.
    Config,
}

impl Height {
    /// `config` or the number of levels.
    pub fn name(self) -> String {
        match self {
            Height::Config(_) => "config".into(),
            Height::Levels(n) => n.to_string(),
        }
    }
}

/// One point of the grid: a value of every axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AxisValues {
    /// The robot: demonstrations, training and execution on its simulation (absent from run
    /// files for the left arm).
    #[serde(
        default = "robots::left_arm",
        skip_serializing_if = "robots::is_left_arm"
    )]
    pub robot: Robot,
    /// Gesture of the synthetic demonstrations.
    pub gesture: String,
    /// Seed of the demonstrations.
    pub seed: u64,
    /// The configuration file as written in the spec.
    pub config: String,
    /// Encoder noise, rad.
    pub noise: f64,
    /// Number of demonstrations.
    pub count: usize,
    /// Height override.
    pub height: Height,
    /// In-sample or leave-one-out.
    pub evaluation: Evaluation,
    /// Method(s).
    pub method: MethodAxis,
}

impl AxisValues {
    /// The value of axis `axis` (one of [`AXES`]) as text, as tables show it.
    pub fn value(&self, axis: &str) -> String {
        match axis {
            "robot" => self.robot.name().into(),
            "gesture" => self.gesture.clone(),
            "seed" => self.seed.to_string(),
            "config" => self.config.clone(),
            "noise" => self.noise.to_string(),
            "count" => self.count.to_string(),
            "height" => self.height.name(),
            "evaluation" => self.evaluation.name().into(),
            "method" => self.method.name().into(),
            _ => String::new(),
        }
    }
}

/// One run of the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct RunPlan {
    /// Position in the grid (0-based).
    pub index: usize,
    /// File name stem: the index, then every axis value (`DIR/runs/<id>.json`).
    pub id: String,
    /// The axes' values.
    pub axes: AxisValues,
}

/// A configuration file of the spec, read and hashed.
#[derive(Debug, Clone)]
pub struct ConfigEntry {
    /// As written in the spec.
    pub written: String,
    /// Resolved against the spec file's directory.
    pub path: PathBuf,
    /// SHA-256 of the file's bytes, hex (`sha256sum FILE` prints the same).
    pub sha256: String,
    /// The checked configuration at each height of the `height` axis (same order).
    pub at_heights: Vec<HsomConfig>,
}

impl ConfigEntry {
    /// Its `stateLength` (the same at every height).
    pub fn state_length(&self) -> usize {
        self.at_heights
            .first()
            .map_or(0, |c| c.params().state_length)
    }

    /// Whether it is a configuration for `robot`: `stateLength` its number of joints.
    pub fn fits(&self, robot: Robot) -> bool {
        self.state_length() == robot.joint_names().len()
    }
}

/// The settings that are not axes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Settings {
    /// A name for tables and plots (default: the spec file's stem).
    pub name: String,
    /// How CoSCo-HSOM's postures become servo targets.
    pub transition: String,
    /// The robot's MJCF model as written (default: the robot's shipped model,
    /// `models/nao_left_arm.xml` or `models/nao_upper_body.xml`).
    pub model: Option<String>,
}

/// The axes' values, checked.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Axes {
    /// Robots (absent from the identity when the left arm alone).
    #[serde(skip_serializing_if = "robots::left_arm_only")]
    pub robot: Vec<Robot>,
    /// Gesture names.
    pub gesture: Vec<String>,
    /// Seeds of the demonstrations.
    pub seed: Vec<u64>,
    /// Configuration files as written.
    pub config: Vec<String>,
    /// Encoder noise, rad.
    pub noise: Vec<f64>,
    /// Numbers of demonstrations.
    pub count: Vec<usize>,
    /// Height overrides.
    pub height: Vec<Height>,
    /// Evaluations.
    pub evaluation: Vec<Evaluation>,
    /// Methods.
    pub method: Vec<MethodAxis>,
}

/// A checked sweep: every value valid, every configuration read, the grid fixed.
#[derive(Debug, Clone)]
pub struct SweepSpec {
    /// The spec file.
    pub source: PathBuf,
    /// Settings that are not axes.
    pub settings: Settings,
    /// The axes.
    pub axes: Axes,
    /// The configuration files, in the order of the `config` axis.
    pub configs: Vec<ConfigEntry>,
    /// The transition, parsed.
    pub transition: Transition,
    /// The robot's model, resolved (None: the robot's shipped model).
    pub model: Option<PathBuf>,
}

/// What identifies a sweep: its settings (but its name), axes and the contents of its
/// configuration files.
/// Two specs with the same identity have the same runs (`DIR/sweep.json` keeps it).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Identity {
    /// Settings that are not axes (as JSON).
    pub settings: serde_json::Value,
    /// The axes' values (as JSON).
    pub axes: serde_json::Value,
    /// SHA-256 of each configuration file, by the name written in the spec.
    pub config_sha256: BTreeMap<String, String>,
}

// ---- the file as written ----

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpec {
    #[serde(default)]
    sweep: RawSettings,
    axes: RawAxes,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSettings {
    name: Option<String>,
    transition: Option<String>,
    model: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawSeeds {
    List(Vec<u64>),
    Text(String),
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum RawHeight {
    Levels(i64),
    Word(String),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxes {
    robot: Option<Vec<String>>,
    gesture: Option<Vec<String>>,
    seed: Option<RawSeeds>,
    config: Option<Vec<String>>,
    noise: Option<Vec<f64>>,
    count: Option<Vec<i64>>,
    height: Option<Vec<RawHeight>>,
    evaluation: Option<Vec<String>>,
    method: Option<Vec<String>>,
}

/// The configuration when the spec has no `config` axis: `simulate`'s default, the shipped
/// `configs/nao-gestures.xml` (absolute, so wherever the spec file is).
pub const DEFAULT_CONFIG: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/configs/nao-gestures.xml");

/// The upper body's configuration when the spec has no `config` axis: `simulate --robot
/// upper-body`'s, the shipped `configs/nao-upper-body.xml`.
pub const UPPER_BODY_CONFIG: &str =
    concat!(env!("CARGO_MANIFEST_DIR"), "/configs/nao-upper-body.xml");

/// The configuration of `robot` when the spec has no `config` axis.
pub fn default_config(robot: Robot) -> &'static str {
    match robot {
        Robot::LeftArm => DEFAULT_CONFIG,
        Robot::UpperBody => UPPER_BODY_CONFIG,
    }
}

/// Hex of SHA-256.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

impl SweepSpec {
    /// Read and check the spec file `path`.
    pub fn load(path: &Path) -> Result<SweepSpec, SweepError> {
        let text = std::fs::read_to_string(path).map_err(SweepError::io("read the spec", path))?;
        SweepSpec::parse(&text, path)
    }

    /// Check the spec text `text` read from `path` (relative file names in it are resolved
    /// against `path`'s directory).
    pub fn parse(text: &str, path: &Path) -> Result<SweepSpec, SweepError> {
        let bad = |message: String| SweepError::Spec {
            file: path.to_path_buf(),
            message,
        };
        let raw: RawSpec = toml::from_str(text).map_err(|e| {
            bad(format!(
                "{}(allowed tables: [sweep] with name, transition, model; [axes] with {})",
                e,
                AXES.join(", ")
            ))
        })?;
        let dir = path.parent().unwrap_or(Path::new(""));
        let axes = check_axes(raw.axes).map_err(bad)?;
        let s = raw.sweep;
        let transition_text = s.transition.unwrap_or_else(|| "linear".into());
        let transition = Transition::parse(&transition_text)
            .map_err(|e| bad(format!("[sweep] transition: {e}")))?;
        let model = s.model.as_ref().map(|m| dir.join(m));
        if let Some(m) = &model {
            let written = s.model.as_deref().unwrap_or_default();
            let [robot] = axes.robot[..] else {
                return Err(bad(format!(
                    "[sweep] model '{written}': a model is one robot's, the `robot` axis has \
                     {}; leave the model out (each robot's shipped model) or sweep one robot",
                    robot_names(&axes.robot)
                )));
            };
            load_model(robot, m).map_err(|e| {
                bad(format!(
                    "[sweep] model '{written}': cannot load {}: {e}",
                    m.display()
                ))
            })?;
        }
        let name = s.name.unwrap_or_else(|| {
            path.file_stem()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_else(|| "sweep".into())
        });
        let configs = axes
            .config
            .iter()
            .map(|written| load_entry(written, dir, &axes.height))
            .collect::<Result<Vec<_>, String>>()
            .map_err(bad)?;
        check_widths(&axes.robot, &configs).map_err(bad)?;
        Ok(SweepSpec {
            source: path.to_path_buf(),
            settings: Settings {
                name,
                transition: transition.name(),
                model: s.model,
            },
            axes,
            configs,
            transition,
            model,
        })
    }

    /// Every run of the grid, in order: nested loops over [`AXES`], the first outermost (a
    /// robot with the configurations of its width only).
    pub fn runs(&self) -> Vec<RunPlan> {
        let a = &self.axes;
        let robot_configs: Vec<(Robot, usize)> = a
            .robot
            .iter()
            .flat_map(|&r| {
                let fit = self
                    .configs
                    .iter()
                    .enumerate()
                    .filter(move |(_, c)| c.fits(r));
                fit.map(move |(ci, _)| (r, ci))
            })
            .collect();
        let total: usize = [
            a.method.len(),
            a.evaluation.len(),
            robot_configs.len(),
            a.height.len(),
            a.count.len(),
            a.noise.len(),
            a.gesture.len(),
            a.seed.len(),
        ]
        .iter()
        .product();
        let width = total.saturating_sub(1).to_string().len().max(4);
        let mut out = Vec::with_capacity(total);
        for &method in &a.method {
            for &evaluation in &a.evaluation {
                for &(robot, ci) in &robot_configs {
                    let config = &self.configs[ci].written;
                    for &height in &a.height {
                        for &count in &a.count {
                            for &noise in &a.noise {
                                for gesture in &a.gesture {
                                    for &seed in &a.seed {
                                        let index = out.len();
                                        let axes = AxisValues {
                                            robot,
                                            gesture: gesture.clone(),
                                            seed,
                                            config: config.clone(),
                                            noise,
                                            count,
                                            height,
                                            evaluation,
                                            method,
                                        };
                                        let id = run_id(index, width, &axes, &self.configs[ci]);
                                        out.push(RunPlan { index, id, axes });
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// The configuration of a run: its config file at its height.
    pub fn config_of(&self, axes: &AxisValues) -> Option<&HsomConfig> {
        let c = self.configs.iter().find(|c| c.written == axes.config)?;
        let h = self.axes.height.iter().position(|h| *h == axes.height)?;
        c.at_heights.get(h)
    }

    /// The SHA-256 of a run's configuration file.
    pub fn config_sha256(&self, axes: &AxisValues) -> Option<&str> {
        self.configs
            .iter()
            .find(|c| c.written == axes.config)
            .map(|c| c.sha256.as_str())
    }

    /// What identifies this sweep.
    pub fn identity(&self) -> Identity {
        Identity {
            // the name only labels tables: renaming the spec file is the same sweep
            settings: serde_json::json!({
                "transition": self.settings.transition,
                "model": self.settings.model,
            }),
            axes: serde_json::to_value(&self.axes).unwrap_or_default(),
            config_sha256: self
                .configs
                .iter()
                .map(|c| (c.written.clone(), c.sha256.clone()))
                .collect(),
        }
    }

    /// SHA-256 of [`SweepSpec::identity`] as JSON: every run file carries it.
    pub fn hash(&self) -> String {
        identity_hash(&self.identity())
    }
}

/// SHA-256 of an identity's JSON.
pub fn identity_hash(id: &Identity) -> String {
    sha256_hex(&serde_json::to_vec(id).unwrap_or_default())
}

/// The axes as written, checked: each axis through [`axis`] (its default when left out), then
/// what the axes must satisfy together.
fn check_axes(a: RawAxes) -> Result<Axes, String> {
    let seed = match a.seed {
        None => None,
        Some(RawSeeds::List(v)) => Some(v),
        Some(RawSeeds::Text(t)) => Some(parse_seeds(&t).map_err(|e| format!("axis `seed`: {e}"))?),
    };
    let robot = axis("robot", a.robot, "left-arm".into(), |r| {
        Robot::from_name(&r)
    })?;
    // without a `config` axis, each robot's own configuration
    let mut default_configs: Vec<String> = Vec::new();
    for r in &robot {
        let c = default_config(*r).to_string();
        if !default_configs.contains(&c) {
            default_configs.push(c);
        }
    }
    let axes = Axes {
        gesture: axis(
            "gesture",
            a.gesture,
            shared_default_gesture(&robot).into(),
            |g| check_gesture(&robot, g),
        )?,
        seed: axis("seed", seed, 1, Ok)?,
        config: axis(
            "config",
            a.config.or(Some(default_configs)),
            String::new(),
            Ok,
        )?,
        noise: axis("noise", a.noise, 0.001, |n| {
            match n.is_finite() && n >= 0.0 {
                true => Ok(n),
                false => Err(format!("{n} rad: allowed a finite encoder noise >= 0")),
            }
        })?,
        count: axis("count", a.count, 4, |c| match usize::try_from(c) {
            Ok(c) if (1..=100).contains(&c) => Ok(c),
            _ => Err(format!("{c} demonstrations: allowed 1 to 100")),
        })?,
        height: axis("height", a.height, RawHeight::Word("config".into()), |h| {
            let given = match h {
                RawHeight::Word(w) if w == "config" => {
                    return Ok(Height::Config(ConfigHeight::Config))
                }
                RawHeight::Levels(n) if n >= 1 => return Ok(Height::Levels(n as usize)),
                RawHeight::Word(w) => format!("'{w}'"),
                RawHeight::Levels(n) => n.to_string(),
            };
            Err(format!(
                "{given}: allowed \"config\" (the configuration's own) or a number of \
                 levels >= 1"
            ))
        })?,
        evaluation: axis("evaluation", a.evaluation, "in-sample".into(), |w| {
            word(w, "in-sample, leave-one-out")
        })?,
        method: axis("method", a.method, "both".into(), |w| {
            word(w, "cosco-hsom, gmr, both, promp, dmp")
        })?,
        robot,
    };
    if axes.method.contains(&MethodAxis::Both) && axes.method.len() > 1 {
        return Err(
            "axis `method`: `both` already runs cosco-hsom and gmr; give either `both` \
             or the single methods"
                .into(),
        );
    }
    if axes.evaluation.contains(&Evaluation::LeaveOneOut) {
        if let Some(c) = axes.count.iter().find(|&&c| c < 2) {
            return Err(format!(
                "axes `count` and `evaluation`: leave-one-out needs at least 2 \
                 demonstrations, `count` has {c}"
            ));
        }
    }
    Ok(axes)
}

/// Every robot has a configuration of its width (`stateLength` its number of joints) and
/// every configuration is some robot's.
fn check_widths(robots: &[Robot], configs: &[ConfigEntry]) -> Result<(), String> {
    let widths = || {
        robots
            .iter()
            .map(|r| format!("{} {}", r.name(), r.joint_names().len()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    if let Some(c) = configs.iter().find(|c| !robots.iter().any(|&r| c.fits(r))) {
        return Err(format!(
            "axes `config` and `robot`: '{}' has stateLength {}, no robot of the `robot` \
             axis has that many joints ({}); give a configuration of one robot's width",
            c.written,
            c.state_length(),
            widths()
        ));
    }
    if let Some(r) = robots.iter().find(|&&r| !configs.iter().any(|c| c.fits(r))) {
        let n = r.joint_names().len();
        return Err(format!(
            "axes `robot` and `config`: no configuration for the {}'s {n} joints (stateLength \
             {n}) on the `config` axis ({}); add one (the shipped {}), or leave the `config` \
             axis out for each robot's own",
            r.name(),
            configs
                .iter()
                .map(|c| format!("'{}' stateLength {}", c.written, c.state_length()))
                .collect::<Vec<_>>()
                .join(", "),
            default_config(*r)
        ));
    }
    Ok(())
}

/// The values of axis `name` (`default` when the spec leaves the axis out), each through
/// `check`: at least one, none twice.
fn axis<R, T: PartialEq + std::fmt::Debug>(
    name: &str,
    given: Option<Vec<R>>,
    default: R,
    check: impl Fn(R) -> Result<T, String>,
) -> Result<Vec<T>, String> {
    let given = given.unwrap_or_else(|| vec![default]);
    if given.is_empty() {
        return Err(format!(
            "axis `{name}` is empty: give at least one value, or leave the axis out for its \
             default"
        ));
    }
    let values = given
        .into_iter()
        .map(|v| check(v).map_err(|e| format!("axis `{name}`: {e}")))
        .collect::<Result<Vec<T>, String>>()?;
    for (i, x) in values.iter().enumerate() {
        if values[..i].contains(x) {
            return Err(format!(
                "axis `{name}`: {x:?} is given twice (every run would be run twice)"
            ));
        }
    }
    Ok(values)
}

/// A word of an axis, as its enum is spelt in spec files; an unknown one is an error listing
/// `allowed`.
fn word<T: DeserializeOwned>(w: String, allowed: &str) -> Result<T, String> {
    let de: StrDeserializer<'_, serde::de::value::Error> = w.as_str().into_deserializer();
    T::deserialize(de).map_err(|_| format!("unknown value '{w}': allowed {allowed}"))
}

fn load_entry(written: &str, dir: &Path, heights: &[Height]) -> Result<ConfigEntry, String> {
    let path = dir.join(written);
    let bytes = std::fs::read(&path).map_err(|e| {
        format!(
            "axis `config`: cannot read '{written}' ({}, relative to the spec file's \
             directory): {e}",
            path.display()
        )
    })?;
    let config = load_config(&path).map_err(|e| format!("axis `config`: '{written}': {e}"))?;
    let at_heights = heights
        .iter()
        .map(|h| match h {
            Height::Config(_) => Ok(config.clone()),
            Height::Levels(n) => config
                .at_height(*n)
                .map_err(|e| format!("axes `config` and `height`: '{written}' at height {n}: {e}")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(ConfigEntry {
        written: written.to_string(),
        path,
        sha256: sha256_hex(&bytes),
        at_heights,
    })
}

/// `0007-wave-s11-nao-gestures-n0.001-c4-hconfig-leave-one-out-both`: the index (unique),
/// then every value, readable in a directory listing; the robot after the index unless it is
/// the left arm (`0003-upper-body-clap-s41-nao-upper-body-...`).
fn run_id(index: usize, width: usize, a: &AxisValues, config: &ConfigEntry) -> String {
    let stem = config
        .path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "config".into());
    let clean = |s: &str| -> String {
        s.chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect()
    };
    let robot = match a.robot {
        Robot::LeftArm => String::new(),
        r => format!("{}-", r.name()),
    };
    format!(
        "{index:0width$}-{robot}{}-s{}-{}-n{}-c{}-h{}-{}-{}",
        clean(&a.gesture),
        a.seed,
        clean(&stem),
        a.noise,
        a.count,
        a.height.name(),
        a.evaluation.name(),
        a.method.name()
    )
}

#[cfg(test)]
mod tests;
