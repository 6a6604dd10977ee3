//! What the main job and `cosco compare` both write and time: the report's name of the
//! configuration, the arm they load, the stopwatch of their stages, the hierarchy's model and
//! executed trajectory with its column of the report.

use std::path::Path;
use std::time::Instant;

use crate::aim::Aim;
use crate::config::HsomConfig;
use crate::config::DEFAULT_CONFIG_NAME;
use crate::demos::{write_csv, Demonstration};
use crate::eval::{Fitted, FoldInput, Method, MethodRun};
use crate::hsom::{Hsom, Reproduction};
use crate::robot::Robot;
use crate::sim::{NaoArm, Recording, Transition};

use super::heldout::on_arm;
use super::report::{MethodResult, Stage};
use super::{ExperimentError, Progress};

/// What CoSCo-HSOM needs as input (the report's "needs as input" row).
pub const HSOM_NEEDS: &str = "raw demonstrations; the initial posture";

/// How a report names the configuration: its path, or the built-in default's name.
pub fn config_name(path: Option<&Path>) -> String {
    path.map_or(DEFAULT_CONFIG_NAME.into(), |p| p.display().to_string())
}

/// Load the arm model from `path` or the default model.
pub fn load_arm(path: Option<&Path>) -> Result<NaoArm, ExperimentError> {
    load_robot(Robot::LeftArm, path)
}

/// Load `robot`'s model from `path` (None: its shipped model), `N` its joints.
pub fn load_robot<const N: usize>(
    robot: Robot,
    path: Option<&Path>,
) -> Result<NaoArm<N>, ExperimentError> {
    NaoArm::load_robot(robot, path.unwrap_or(Path::new(robot.model_path()))).map_err(|source| {
        ExperimentError::Arm {
            path: path.map(Path::to_path_buf),
            source,
        }
    })
}

/// Wall time of the main job's stages.
pub struct Stopwatch {
    /// The stages timed so far.
    pub stages: Vec<Stage>,
    /// Start of the current stage.
    pub t: Instant,
}

impl Default for Stopwatch {
    /// A stopwatch with no stage, started now.
    fn default() -> Self {
        Stopwatch {
            stages: Vec::new(),
            t: Instant::now(),
        }
    }
}

impl Stopwatch {
    /// Close the current stage as `stage`.
    pub fn lap(&mut self, stage: &str) {
        self.push(stage, self.t.elapsed().as_secs_f64());
        self.t = Instant::now();
    }

    /// Close the current stage as two: `first`, which took `seconds` of it, then `rest`.
    pub fn split_lap(&mut self, first: &str, seconds: f64, rest: &str) {
        self.push(first, seconds);
        self.push(rest, (self.t.elapsed().as_secs_f64() - seconds).max(0.0));
        self.t = Instant::now();
    }

    fn push(&mut self, stage: &str, seconds: f64) {
        let stage = stage.to_string();
        self.stages.push(Stage { stage, seconds });
    }
}

/// File size in bytes (0 when it cannot be read).
pub fn file_size(p: &Path) -> u64 {
    std::fs::metadata(p).map(|m| m.len()).unwrap_or(0)
}

/// The model and the reproduction of a run of [`Method::Hierarchy`](crate::eval::Method)
/// (an error for a run of another method).
pub fn hsom_model(run: &MethodRun<Recording>) -> Result<(&Hsom, &Reproduction), ExperimentError> {
    match &run.fitted {
        Some(Fitted::Hierarchy {
            model,
            reproduction,
        }) => Ok((model, reproduction)),
        _ => Err(ExperimentError::Invalid(
            "not a run of the hierarchy: no model to save".into(),
        )),
    }
}

/// Train CoSCo-HSOM with `cfg` on `demos` (stage `training` to `on_progress`), reproduce from
/// the first one's initial posture (aimed at `aim`, then retimed to `duration` seconds, when
/// given; [`FoldInput::aim`], [`FoldInput::duration`]), execute on the arm with `transition`
/// and score against all of them (the main job's in-sample run).
pub fn hsom_on_arm<const N: usize>(
    arm: &NaoArm<N>,
    cfg: &HsomConfig,
    demos: &[Demonstration],
    transition: Transition,
    duration: Option<f64>,
    aim: Aim,
    on_progress: Progress<'_>,
) -> Result<MethodRun<Recording>, ExperimentError> {
    let total = cfg.params().training_steps;
    let progress = |done, _| on_progress("training", done, total);
    let input = FoldInput {
        config: Some(cfg),
        progress: Some(&progress),
        duration,
        aim,
        ..FoldInput::new(demos, demos)
    };
    on_arm(arm, transition, Method::Hierarchy, &input)
}

/// Save a CoSCo-HSOM run's model (`model.bin`) and executed trajectory (`reproduction.csv`)
/// into `out`, list them in `files`, and return its column of the report (notes: why it
/// stopped, postures per level, then `notes`).
pub fn write_hsom_run(
    out: &Path,
    run: &MethodRun<Recording>,
    notes: Vec<String>,
    files: &mut Vec<String>,
) -> Result<MethodResult, ExperimentError> {
    let (model, reproduction) = hsom_model(run)?;
    let model_path = out.join("model.bin");
    model.save(&model_path)?;
    let trace = &run.executed.trace;
    write_csv(
        &out.join("reproduction.csv"),
        &trace.to_demonstration("CoSCo-HSOM reproduction"),
    )?;
    files.extend(["model.bin".into(), "reproduction.csv".into()]);
    let mut all = vec![
        format!("stopped: {:?}", reproduction.stop),
        levels_note(&reproduction.predicted_by),
    ];
    all.extend(notes);
    let bytes = file_size(&model_path);
    Ok(MethodResult::of("CoSCo-HSOM", HSOM_NEEDS, run, bytes, all))
}

/// "predicted by level": how many postures each level produced.
fn levels_note(by: &[usize]) -> String {
    let top = by.iter().copied().max().unwrap_or(0);
    let counts: Vec<String> = (0..=top)
        .map(|l| format!("L{l}: {}", by.iter().filter(|&&b| b == l).count()))
        .collect();
    format!("postures predicted per level: {}", counts.join(", "))
}
