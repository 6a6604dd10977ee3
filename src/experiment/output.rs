//! What the main job and `cosco compare` both write and time: the report's name of the
//! configuration, the arm they load, the stopwatch of their stages, the hierarchy's model and
//! executed trajectory with its column of the report.

use std::path::Path;
use std::time::Instant;

use crate::app::DEFAULT_CONFIG_NAME;
use crate::demos::write_csv;
use crate::eval::{Fitted, MethodRun};
use crate::hsom::{Hsom, Reproduction};
use crate::sim::{NaoArm, Recording};

use super::report::{MethodResult, Stage};
use super::ExperimentError;

/// What CoSCo-HSOM needs as input (the report's "needs as input" row).
pub const HSOM_NEEDS: &str = "raw demonstrations; the initial posture";

/// How a report names the configuration: its path, or the built-in default's name.
pub fn config_name(path: Option<&Path>) -> String {
    path.map_or(DEFAULT_CONFIG_NAME.into(), |p| p.display().to_string())
}

/// Load the arm model from `path` or the default model.
pub fn load_arm(path: Option<&Path>) -> Result<NaoArm, ExperimentError> {
    match path {
        Some(p) => NaoArm::load(p),
        None => NaoArm::load_default(),
    }
    .map_err(|source| ExperimentError::Arm {
        path: path.map(Path::to_path_buf),
        source,
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
    fn default() -> Self {
        Self::new()
    }
}

impl Stopwatch {
    /// A stopwatch with no stage, started now.
    pub fn new() -> Self {
        Stopwatch {
            stages: Vec::new(),
            t: Instant::now(),
        }
    }
    /// Close the current stage as `stage`; its seconds.
    pub fn lap(&mut self, stage: &str) -> f64 {
        let s = self.t.elapsed().as_secs_f64();
        self.stages.push(Stage {
            stage: stage.to_string(),
            seconds: s,
        });
        self.t = Instant::now();
        s
    }
}

/// File size in bytes (0 when it cannot be read).
pub fn file_size(p: &Path) -> u64 {
    std::fs::metadata(p).map(|m| m.len()).unwrap_or(0)
}

/// The four joints of the paper's Fig. 4.
pub const FIG4_JOINTS: [(usize, &str); 4] = [
    (0, "LShoulderPitch"),
    (1, "LShoulderRoll"),
    (2, "LElbowYaw"),
    (3, "LElbowRoll"),
];

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

/// CoSCo-HSOM's column of a comparison table (no held-out figures: see
/// `heldout::leave_one_out`); `model_bytes` is the size of the saved model.
pub fn hsom_result(
    name: &str,
    run: &MethodRun<Recording>,
    model_bytes: u64,
    notes: Vec<String>,
) -> MethodResult {
    MethodResult {
        name: name.into(),
        needs: HSOM_NEEDS.into(),
        fidelity: run.executed.fidelity.clone(),
        train_s: run.train_s,
        reproduce_s: run.reproduce_s,
        model_bytes,
        postures: run.postures.len(),
        clamped_values: run.executed.clamped_values,
        notes,
        heldout: None,
    }
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
    files.push("model.bin".into());
    write_csv(
        &out.join("reproduction.csv"),
        &run.executed
            .trace
            .to_demonstration("CoSCo-HSOM reproduction"),
    )?;
    files.push("reproduction.csv".into());
    let mut all = vec![
        format!("stopped: {:?}", reproduction.stop),
        levels_note(&reproduction.predicted_by),
    ];
    all.extend(notes);
    Ok(hsom_result("CoSCo-HSOM", run, file_size(&model_path), all))
}

/// "predicted by level": how many postures each level produced.
fn levels_note(by: &[usize]) -> String {
    let top = by.iter().copied().max().unwrap_or(0);
    let counts: Vec<String> = (0..=top)
        .map(|l| format!("L{l}: {}", by.iter().filter(|&&b| b == l).count()))
        .collect();
    format!("postures predicted per level: {}", counts.join(", "))
}
