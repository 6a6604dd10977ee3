//! `cosco compare` and the baseline section of the main job: the paper's GMM/GMR baseline and
//! CoSCo-HSOM trained on the same demonstrations, both executed on the simulated arm from
//! the same initial posture, scored with the same metrics, side by side in one table.

use std::path::{Path, PathBuf};

use crate::config::load_config_or_default;
use crate::demo_sets::read_demos;
use crate::demos::{sample_period, validate_set, write_csv, Demonstration};
use crate::eval::{Fitted, FoldInput, Method, MethodRun};
use crate::gmr::{load_model, save_model, BicScore, ComponentChoice, GmrModel, MIN_DEMONSTRATIONS};
use crate::gmr::{GmrPlan, TrainingSet};
use crate::plot::BLACK;
use crate::sim::{demo_wrist_paths, NaoArm, Recording, Transition, JOINT_NAMES};

use super::baseline::{fig3_png, fig5_png, GMR_COLOR, GMR_NAME, GMR_NEEDS};
use super::figures::right_wrist_png;
use super::figures::{demo_curves, demo_paths, joint_panels_png, reproduction, wrist_png};
use super::heldout::on_arm;
use super::output::{config_name, file_size, hsom_on_arm, load_arm, write_hsom_run, Stopwatch};
use super::report::{DemoInfo, MethodResult, Report};
use super::{ExperimentError, Progress};
use crate::robot::{are_arm_joints, Robot};

/// The result of a job's step.
type Result<T> = std::result::Result<T, ExperimentError>;

pub use super::baseline::DEFAULT_COMPONENTS;

/// Parse `--components`: a count `K` (≥ 1) or `bic` (BIC over 1..=16).
pub fn parse_components(s: &str) -> std::result::Result<ComponentChoice, String> {
    let t = s.trim();
    if t.eq_ignore_ascii_case("bic") {
        return Ok(DEFAULT_COMPONENTS);
    }
    match t.parse::<usize>() {
        Ok(k) if k >= 1 => Ok(ComponentChoice::Fixed(k)),
        _ => Err(format!(
            "--components '{s}': expected a number of components >= 1 or 'bic'"
        )),
    }
}

/// Fail with the expected columns when the demonstrations are not the arm's joints.
pub fn require_arm_joints(demos: &[Demonstration]) -> Result<()> {
    if let Some(d) = demos.first() {
        if !are_arm_joints(&d.columns) {
            return Err(ExperimentError::Invalid(format!(
                "{}: the demonstrations' columns are {:?}; comparing needs the simulator to \
                 execute both methods, so the columns must be exactly time (optional) then {:?}",
                d.source, d.columns, JOINT_NAMES
            )));
        }
    }
    Ok(())
}

/// Fit, execute and score the GMM/GMR baseline on `demos` (the arm's joints), then write into
/// `out`: `gmr_model.txt` (reloaded and checked identical), `gmr_reproduction.csv`,
/// `fig3_gmr_training_data.png`, `fig5_gmr_lshoulderpitch.png`, and, with CoSCo-HSOM's
/// executed trajectory `hsom`, `joints_compare.png` and `wrist_compare.png`. Returns the
/// baseline's column of the comparison table; the files written are appended to `files`.
/// `demo_wrists` are the demonstrations' wrist paths (`demo_wrist_paths`), computed once by
/// the caller.
pub fn baseline_section<const N: usize>(
    arm: &NaoArm<N>,
    demos: &[Demonstration],
    demo_wrists: &[Vec<[f64; 3]>],
    hsom: &Recording,
    out: &Path,
    components: ComponentChoice,
    files: &mut Vec<String>,
) -> Result<MethodResult> {
    let dt = sample_period(&demos[0]);
    let input = FoldInput {
        gmr_components: components,
        ..FoldInput::new(demos, demos)
    };
    let run = on_arm(arm, Transition::Linear, Method::GmmGmr, &input)
        .map_err(|e| ExperimentError::Invalid(format!("{GMR_NAME}: {e}")))?;
    let Some(Fitted::GmmGmr {
        model,
        training,
        bic,
        plan,
    }) = &run.fitted
    else {
        return Err(ExperimentError::Invalid(format!("{GMR_NAME}: no model")));
    };
    let executed = &run.executed.trace;

    let model_path = out.join("gmr_model.txt");
    save_model(&model_path, model)?;
    let back = load_model(&model_path)?;
    if back != **model {
        return Err(ExperimentError::Invalid(format!(
            "{}: the reloaded GMR model differs from the saved one",
            model_path.display()
        )));
    }
    files.push("gmr_model.txt".into());
    write_csv(
        &out.join("gmr_reproduction.csv"),
        &executed.to_demonstration("GMM/GMR reproduction"),
    )?;
    files.push("gmr_reproduction.csv".into());

    let robot = arm.robot();
    let panels = robot.plot_panels();
    fig3_png(&out.join("fig3_gmr_training_data.png"), training, &panels)?;
    files.push("fig3_gmr_training_data.png".into());
    // Fig. 5 is drawn for LShoulderPitch (the left arm's first joint) on every robot
    let names = robot.joint_names();
    let fig5_joint = names
        .iter()
        .position(|n| *n == "LShoulderPitch")
        .unwrap_or(0);
    fig5_png(
        &out.join("fig5_gmr_lshoulderpitch.png"),
        model,
        training,
        fig5_joint,
        names[fig5_joint],
        dt,
    )?;
    files.push("fig5_gmr_lshoulderpitch.png".into());

    let (hsom_curve, hsom_path) = reproduction("CoSCo-HSOM reproduction", BLACK, hsom);
    let (gmr_curve, gmr_path) = reproduction("GMM/GMR reproduction", GMR_COLOR, executed);
    let mut curves = demo_curves(demos);
    curves.extend([hsom_curve, gmr_curve]);
    joint_panels_png(
        &out.join("joints_compare.png"),
        "Demonstrations (colour), CoSCo-HSOM (black), GMM/GMR (magenta: learned without the idle start)",
        &panels,
        &curves,
        None,
    )?;
    files.push("joints_compare.png".into());

    let mut paths = demo_paths(demo_wrists);
    paths.extend([hsom_path, gmr_path]);
    wrist_png(
        &out.join("wrist_compare.png"),
        "Wrist path (l_wrist), torso frame: both methods",
        &paths,
    )?;
    files.push("wrist_compare.png".into());
    if robot == Robot::UpperBody {
        let traces = [("CoSCo-HSOM reproduction", BLACK, hsom)];
        let traces = traces
            .into_iter()
            .chain([("GMM/GMR reproduction", GMR_COLOR, executed)]);
        right_wrist_png(
            arm,
            demos,
            traces,
            &out.join("wrist_right_compare.png"),
            "Wrist path (r_wrist), torso frame: both methods",
        )?;
        files.push("wrist_right_compare.png".into());
    }

    let fit = (&**model, &**training, bic.as_slice(), plan);
    Ok(gmr_result(&run, fit, file_size(&model_path)))
}

/// The baseline's column of the comparison table: `run` with what it `fit` (model, training
/// data, BIC of each count tried, plan); `model_bytes` is the size of the saved model file.
fn gmr_result(
    run: &MethodRun<Recording>,
    (model, training, bic, plan): (&GmrModel, &TrainingSet, &[BicScore], &GmrPlan),
    model_bytes: u64,
) -> MethodResult {
    let g = model.gmm();
    let chosen: Vec<String> = bic
        .iter()
        .map(|b| match b.bic {
            Some(v) => format!("K={}: {v:.0}", b.components),
            None => format!("K={}: failed", b.components),
        })
        .collect();
    let mut notes = vec![
        format!(
            "{} Gaussian components over [t, q] (dimension {}); {} numbers in the model",
            g.n_components(),
            g.dim(),
            g.n_components() * (1 + g.dim() + g.dim() * g.dim())
        ),
        format!(
            "training data: {} demonstrations x {} points, aligned to demonstration {} \
             (the medoid); learned duration {:.2} s",
            training.demos.len(),
            training.times.len(),
            training
                .reference
                .map_or("none".into(), |r| (r + 1).to_string()),
            training.duration
        ),
        format!(
            "minimum-jerk lead-in from the initial posture to GMR's first point: {} ticks \
             ({:.3} s), then {} GMR postures",
            plan.lead_in,
            plan.lead_in as f64 / run.executed.trace.rate_hz,
            plan.predictions.len()
        ),
    ];
    if chosen.len() > 1 {
        let top = bic.last().map(|b| b.components);
        let edge = if top == Some(g.n_components()) {
            " -- the largest count tried: a wider range may fit better"
        } else {
            ""
        };
        notes.push(format!(
            "components chosen by BIC (lowest wins): {}{edge}",
            chosen.join(", ")
        ));
    }
    MethodResult::of(GMR_NAME, GMR_NEEDS, run, model_bytes, notes)
}

/// What `cosco compare` needs.
#[derive(Debug, Clone)]
pub struct CompareJob {
    /// Directory (or file) of demonstration CSVs.
    pub demos: PathBuf,
    /// CoSCo-HSOM configuration (None: built-in Table I).
    pub config: Option<PathBuf>,
    /// Output directory.
    pub out: PathBuf,
    /// GMM component choice.
    pub components: ComponentChoice,
    /// Arm model file.
    pub model: Option<PathBuf>,
    /// How CoSCo-HSOM's postures become servo targets (the main job's `--transition`).
    pub transition: Transition,
    /// Resample the demonstrations to this rate, Hz.
    pub resample: Option<f64>,
}

/// `cosco compare`: both methods on the same demonstrations, executed on the simulated arm;
/// report, csvs, models and plots written into `job.out`.
pub fn compare(job: &CompareJob, on_progress: Progress<'_>) -> Result<Report> {
    let mut clock = Stopwatch::default();
    let out = &job.out;
    let cfg = load_config_or_default(job.config.as_deref())?;
    let demos = read_demos(std::slice::from_ref(&job.demos), None, job.resample)?;
    require_arm_joints(&demos)?;
    if demos.len() < MIN_DEMONSTRATIONS {
        return Err(ExperimentError::Invalid(format!(
            "{}: {} demonstration file(s); the GMM/GMR baseline needs at least \
             {MIN_DEMONSTRATIONS} demonstrations to align and to estimate their spread",
            job.demos.display(),
            demos.len()
        )));
    }
    validate_set(&demos, Some(cfg.params().state_length)).map_err(|source| {
        ExperimentError::StateLength {
            state_length: cfg.params().state_length,
            source,
        }
    })?;
    std::fs::create_dir_all(out).map_err(ExperimentError::io("creating", out))?;
    let arm = load_arm(job.model.as_deref())?;
    let demo_info: Vec<DemoInfo> = demos
        .iter()
        .map(|d| DemoInfo::new(d.source.clone(), d))
        .collect();
    clock.lap("read demonstrations");

    let mut files = Vec::new();
    let run = hsom_on_arm(
        &arm,
        &cfg,
        &demos,
        job.transition,
        None,
        Default::default(),
        on_progress,
    )?;
    let notes = vec![format!("transition: {:?}", job.transition)];
    let hsom_result = write_hsom_run(out, &run, notes, &mut files)?;
    clock.lap("CoSCo-HSOM (train + reproduce + execute + metrics)");
    let demo_wrists = demo_wrist_paths(&arm, &demos)?;
    let gmr_result = baseline_section(
        &arm,
        &demos,
        &demo_wrists,
        &run.executed.trace,
        out,
        job.components,
        &mut files,
    )?;
    clock.lap("GMM/GMR (fit + reproduce + execute + metrics + plots)");

    files.extend(["report.md".into(), "report.json".into()]);
    let report = Report {
        title: "CoSCo-HSOM and the GMM/GMR baseline on the simulated Nao left arm".into(),
        gesture: None,
        seed: cfg.params().seed,
        config: config_name(job.config.as_deref()),
        demos: demo_info,
        methods: vec![hsom_result, gmr_result],
        variants: Vec::new(),
        heldout: None,
        heldout_note: None,
        levels: Vec::new(),
        stages: clock.stages,
        files,
        not_run: Vec::new(),
        in_loop: None,
    };
    report
        .write(out)
        .map_err(ExperimentError::io("writing the report into", out))?;
    Ok(report)
}

/// The wrist-path DTW means of a summary line: `4.5`, `n/a`, or on two arms (the upper
/// body) `4.5 (left), 4.7 (right)`.
fn wrist_dtw(f: &crate::metrics::FidelityReport) -> String {
    let mm = |s: Option<crate::metrics::Stat>| s.map_or("n/a".into(), |s| format!("{:.1}", s.mean));
    match f.right_wrist_dtw_mm {
        None => mm(f.wrist_dtw_mm),
        Some(r) => format!("{} (left), {} (right)", mm(f.wrist_dtw_mm), mm(Some(r))),
    }
}

/// One terminal line per method.
pub fn summary_lines(r: &Report) -> Vec<String> {
    r.methods
        .iter()
        .map(|m| {
            format!(
                "{}: joint DTW {:.4} rad/step, wrist DTW {} mm, apex error {:.3} rad, final error {:.3} rad, duration ratio {:.2}, reversals {}",
                m.name,
                m.fidelity.joint_dtw_rad_per_step.mean,
                wrist_dtw(&m.fidelity),
                m.fidelity.apex_error_rad.mean,
                m.fidelity.final_error_rad.mean,
                m.fidelity.duration_ratio.mean,
                m.fidelity.reproduction_smoothness.total_reversals,
            ) + &m.heldout.as_ref().map_or(String::new(), |h| {
                format!(
                    "; held-out ({} folds): joint DTW {:.4}, wrist DTW {} mm, duration ratio {:.2}",
                    h.folds,
                    h.joint_dtw_rad_per_step,
                    h.wrist_dtw_mm.map_or("n/a".into(), |w| format!("{w:.1}")),
                    h.duration_ratio
                )
            })
        })
        .collect()
}
