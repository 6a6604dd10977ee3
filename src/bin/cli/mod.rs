//! The steps shared by the `simulate` and `cosco` binaries. Errors are `anyhow` here (binaries
//! only); the library's typed errors carry the file, field and value.
#![allow(dead_code)]

pub mod compare;
pub mod sweep;

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};

use cosco_hsom::config::{load_config, parse_config, HsomConfig};
use cosco_hsom::demos::{self, write_csv, Demonstration};
use cosco_hsom::experiment::baseline::GMR_NAME;
use cosco_hsom::experiment::figures::{demo_paths, joint_panels_png, wrist_png, Curve, Path3};
use cosco_hsom::experiment::report::{level_rows, DemoInfo, Report, Stage};
use cosco_hsom::experiment::variants::{reference_variants, run_variant, variants};
use cosco_hsom::experiment::{
    are_arm_joints, demo_wrist_paths, evaluate, film, hsom_folds, learn_and_reproduce,
    leave_one_out, sample_period, synthetic_demonstrations, DemoSettings, HeldOutSummary, Training,
    Transition,
};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::hsom::Hsom;
use cosco_hsom::metrics::{FidelityReport, MetricsParams};
use cosco_hsom::plot::BLACK;
use cosco_hsom::render::RenderOptions;
use cosco_hsom::sim::{NaoArm, JOINT_NAMES};

/// Default encoder noise of synthetic demonstrations, rad (about Nao's encoder resolution).
pub const DEFAULT_ENCODER_NOISE: f64 = 0.001;

/// A progress bar on stderr (hidden when stderr is not a terminal).
pub fn progress(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template(
            "{msg:>14} [{bar:40.cyan/blue}] {pos}/{len} {elapsed_precise}",
        )
        .expect("static template")
        .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    pb
}

/// Load the arm model from `path` or the default model.
pub fn load_arm(path: Option<&Path>) -> Result<NaoArm> {
    match path {
        Some(p) => {
            NaoArm::load(p).with_context(|| format!("loading the arm model {}", p.display()))
        }
        None => NaoArm::load_default().context("loading the default arm model"),
    }
}

/// Look a gesture up by name, with the list of known names on failure.
pub fn gesture(name: &str) -> Result<Gesture> {
    match Gesture::by_name(name) {
        Some(g) => Ok(g),
        None => bail!(
            "unknown gesture '{name}': allowed {}",
            Gesture::names().join(", ")
        ),
    }
}

/// Record synthetic demonstrations in the simulator, with a progress bar.
pub fn record(
    arm: &NaoArm,
    gesture: &Gesture,
    count: usize,
    seed: u64,
    noise: f64,
) -> Result<Vec<Demonstration>> {
    let settings = DemoSettings {
        encoder_noise: noise,
        ..DemoSettings::default()
    };
    let pb = progress(count as u64, "demonstrating");
    let demos = synthetic_demonstrations(arm, gesture, count, seed, &settings, |_| pb.inc(1))?;
    pb.finish_and_clear();
    Ok(demos)
}

/// Write demonstrations as `demo_01.csv`, ... in `dir` (created if missing).
pub fn write_demos(dir: &Path, demos: &[Demonstration]) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut files = Vec::new();
    for (i, d) in demos.iter().enumerate() {
        let p = dir.join(format!("demo_{:02}.csv", i + 1));
        demos::write_csv(&p, d)?;
        files.push(p);
    }
    Ok(files)
}

/// `cosco demos`: record and write demonstrations.
pub fn demos(
    gesture_name: &str,
    count: usize,
    seed: u64,
    out: &Path,
    noise: f64,
    model: Option<&Path>,
) -> Result<Vec<PathBuf>> {
    let g = gesture(gesture_name)?;
    let arm = load_arm(model)?;
    let demos = record(&arm, &g, count, seed, noise)?;
    write_demos(out, &demos)
}

/// The recommended configuration for the simulated Nao (the events extension), built into the
/// binaries so they run from any directory; the default of `simulate` and `cosco`.
pub const NAO_GESTURES_XML: &str = include_str!("../../../configs/nao-gestures.xml");

/// Name of the built-in default configuration in reports and messages.
pub const DEFAULT_CONFIG_NAME: &str = "configs/nao-gestures.xml (built in)";

/// Load a CoSCo-HSOM configuration file, or the built-in recommended configuration.
pub fn hsom_config(path: Option<&Path>) -> Result<HsomConfig> {
    Ok(match path {
        Some(p) => load_config(p)?,
        None => parse_config(NAO_GESTURES_XML, DEFAULT_CONFIG_NAME)?,
    })
}

/// Read demonstration files (a directory of *.csv or explicit files), checked as a set.
pub fn read_demos(paths: &[PathBuf], state_length: Option<usize>) -> Result<Vec<Demonstration>> {
    let demos = demos::read_dir_or_files(paths)?;
    if demos.is_empty() {
        bail!(
            "no demonstration files found in {}",
            paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    demos::validate_set(&demos, state_length)?;
    Ok(demos)
}

/// Train with a progress bar.
pub fn train(cfg: &HsomConfig, demos: &[Demonstration]) -> Result<Hsom> {
    let pb = progress(cfg.params().training_steps as u64, "training");
    let model = cfg.fit_with_progress(demos, Some(&|done, _total| pb.set_position(done as u64)))?;
    pb.finish_and_clear();
    Ok(model)
}

/// Everything the main job needs to know.
#[derive(Debug, Clone)]
pub struct Job {
    /// Gesture of the synthetic demonstrations.
    pub gesture: String,
    /// Configuration file (None: built-in Table I).
    pub config: Option<PathBuf>,
    /// Directory of recorded demonstrations (None: synthetic).
    pub demos: Option<PathBuf>,
    /// Seed of the job.
    pub seed: u64,
    /// Number of synthetic demonstrations.
    pub count: usize,
    /// Encoder noise of synthetic demonstrations, rad.
    pub noise: f64,
    /// Render the clip and contact sheet.
    pub render: bool,
    /// Output directory.
    pub out: PathBuf,
    /// Arm model file.
    pub model: Option<PathBuf>,
    /// How the learned postures become servo targets.
    pub transition: Transition,
    /// Also run the before/after variants.
    pub variants: bool,
    /// Also run the held-out (leave-one-out) evaluation of both methods.
    pub heldout: bool,
}

struct Stopwatch {
    stages: Vec<Stage>,
    t: Instant,
}

impl Stopwatch {
    fn new() -> Self {
        Stopwatch {
            stages: Vec::new(),
            t: Instant::now(),
        }
    }
    fn lap(&mut self, stage: &str) -> f64 {
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
fn file_size(p: &Path) -> u64 {
    std::fs::metadata(p).map(|m| m.len()).unwrap_or(0)
}

/// The four joints of the paper's Fig. 4.
pub const FIG4_JOINTS: [(usize, &str); 4] = [
    (0, "LShoulderPitch"),
    (1, "LShoulderRoll"),
    (2, "LElbowYaw"),
    (3, "LElbowRoll"),
];

/// The main job: demonstrations -> training -> reproduction in the simulator -> report,
/// plots and clip, all written into `job.out`.
pub fn main_job(job: &Job) -> Result<Report> {
    let mut clock = Stopwatch::new();
    let out = &job.out;
    std::fs::create_dir_all(out.join("demos"))
        .with_context(|| format!("creating {}", out.display()))?;
    let cfg = hsom_config(job.config.as_deref())?;
    let arm = load_arm(job.model.as_deref())?;
    let mut files = Vec::new();

    // 1. Demonstrations.
    let (demos, gesture) = match &job.demos {
        Some(dir) => (
            read_demos(std::slice::from_ref(dir), Some(cfg.params().state_length))?,
            None,
        ),
        None => {
            let g = gesture(&job.gesture)?;
            let demos = record(&arm, &g, job.count, job.seed, job.noise)?;
            (demos, Some(g.name.to_string()))
        }
    };
    if !are_arm_joints(&demos[0].columns) {
        bail!(
            "the demonstrations' columns are {:?}; the simulated arm needs exactly {:?} (use `cosco train` / `cosco reproduce` for other data)",
            demos[0].columns,
            JOINT_NAMES
        );
    }
    let demo_files = write_demos(&out.join("demos"), &demos)?;
    let demo_info: Vec<DemoInfo> = demos
        .iter()
        .zip(&demo_files)
        .map(|(d, f)| DemoInfo {
            file: f.strip_prefix(out).unwrap_or(f).display().to_string(),
            samples: d.rows.len(),
            duration_s: (d.rows.len().saturating_sub(1)) as f64 * sample_period(d),
        })
        .collect();
    files.extend(demo_info.iter().map(|d| d.file.clone()));
    clock.lap("demonstrations (simulate + record)");

    // 2-4. Training, reproduction from the initial posture on the simulated arm, metrics.
    let pb = progress(cfg.params().training_steps as u64, "training");
    let run = learn_and_reproduce(
        &arm,
        &cfg,
        &demos,
        Training::Trained,
        job.transition,
        Some(&|done, _| pb.set_position(done as u64)),
    )?;
    pb.finish_and_clear();
    clock.stages.push(Stage {
        stage: "training".into(),
        seconds: run.train_s,
    });
    clock.stages.push(Stage {
        stage: "reproduction (predict + execute) and metrics".into(),
        seconds: (clock.t.elapsed().as_secs_f64() - run.train_s).max(0.0),
    });
    clock.t = Instant::now();
    let hsom_result = write_hsom_run(out, &run, Vec::new(), &mut files)?;
    let executed = &run.executed;
    clock.lap("writing the model and reproduction.csv");

    // 5. Plots.
    let demo_curves: Vec<Curve> = demos
        .iter()
        .enumerate()
        .map(|(i, d)| Curve::demo(i, d.time.as_deref().unwrap_or(&[]), &d.rows))
        .collect();
    let mut curves = demo_curves.clone();
    curves.push(Curve::reproduction(
        "CoSCo-HSOM reproduction",
        &executed.time,
        &executed.qpos,
    ));
    joint_panels_png(
        &out.join("joints.png"),
        "Training demonstrations (colour) and the reproduced gesture (black)",
        &FIG4_JOINTS,
        &curves,
        "rad",
    )?;
    files.push("joints.png".into());
    let demo_wrists = demo_wrist_paths(&arm, &demos)?;
    let mut paths = demo_paths(&demo_wrists);
    paths.push(Path3::reproduction(
        "CoSCo-HSOM reproduction",
        BLACK,
        &executed.wrist,
    ));
    wrist_png(
        &out.join("wrist.png"),
        "Wrist path (l_wrist), torso frame",
        &paths,
    )?;
    files.push("wrist.png".into());
    clock.lap("plots");

    // 5b. The paper's baseline (GMM/GMR) on the same demonstrations, executed and scored the
    // same way (cli/compare.rs). It needs at least two demonstrations: otherwise noted, skipped.
    let mut methods = vec![hsom_result];
    match compare::baseline_section(
        &arm,
        &demos,
        &demo_wrists,
        executed,
        out,
        compare::DEFAULT_COMPONENTS,
        &mut files,
    ) {
        Ok(gmr_result) => methods.push(gmr_result),
        Err(e) => {
            eprintln!("warning: GMM/GMR baseline skipped: {e:#}");
            methods[0]
                .notes
                .push(format!("GMM/GMR baseline not run: {e:#}"));
        }
    }
    clock.lap("GMM/GMR baseline (fit + execute + metrics + plots)");

    // 5c. Held-out: each demonstration in turn left out, both methods (experiment::heldout).
    let (heldout, heldout_note) = if !job.heldout {
        (None, Some("--no-heldout was given".to_string()))
    } else if demos.len() < 2 {
        let note = format!(
            "{} demonstration(s); leave-one-out needs at least 2",
            demos.len()
        );
        methods[0]
            .notes
            .push(format!("held-out evaluation not run: {note}"));
        (None, Some(note))
    } else {
        let h = leave_one_out(&arm, &cfg, &demos, job.transition)?;
        methods[0].heldout = Some(h.hsom.clone());
        if let Some(g) = methods.iter_mut().find(|m| m.name == GMR_NAME) {
            g.heldout = h.gmr.clone();
        }
        clock.lap("held-out (leave-one-out, both methods, every fold)");
        (Some(h), None)
    };

    // 5d. Before / after: the beyond-the-paper options switched off (docs/ALGORITHM.md).
    let mut variant_results = Vec::new();
    if job.variants {
        let mut vs = reference_variants(&cfg, job.transition)?;
        vs.extend(variants(&cfg, job.transition)?);
        let pb = progress(vs.len() as u64, "variants");
        let mut main = methods[0].clone();
        main.name = format!("{} ({})", cfg.source(), job.transition.name());
        if job.heldout && main.heldout.is_none() && demos.len() >= 2 {
            let folds = hsom_folds(&arm, &cfg, &demos, Training::Trained, job.transition)?;
            main.heldout = HeldOutSummary::of(&folds.iter().collect::<Vec<_>>());
        }
        variant_results.push(main);
        for v in &vs {
            variant_results.push(run_variant(&arm, v, &demos, job.heldout)?);
            pb.inc(1);
        }
        pb.finish_and_clear();
        clock.lap(if job.heldout {
            "before/after variants (train + reproduce + execute + metrics each, in-sample and held-out)"
        } else {
            "before/after variants (train + reproduce + execute + metrics each)"
        });
    }

    // 6. Clip.
    if job.render {
        let opts = RenderOptions {
            width: 480,
            height: 360,
            shadows: true,
            multisample: false,
            camera: Some("front".into()),
        };
        let stride = 2;
        let pb = progress(executed.len().div_ceil(stride) as u64, "rendering");
        let clip = film(&arm, executed, &opts, stride, |n, _| {
            pb.set_position(n as u64)
        })?;
        pb.finish_and_clear();
        clip.write_gif(&out.join("clip.gif"))?;
        clip.write_contact_sheet(&out.join("contact_sheet.png"), 8, 4, true)?;
        files.push("clip.gif".into());
        files.push("contact_sheet.png".into());
        clock.lap("rendering (clip + contact sheet)");
    }

    files.push("report.md".into());
    files.push("report.json".into());
    let report = Report {
        title: format!(
            "CoSCo-HSOM on the simulated Nao left arm{}",
            gesture
                .as_deref()
                .map(|g| format!(": {g}"))
                .unwrap_or_default()
        ),
        gesture,
        seed: job.seed,
        config: job
            .config
            .as_ref()
            .map_or(DEFAULT_CONFIG_NAME.into(), |p| p.display().to_string()),
        demos: demo_info,
        methods,
        variants: variant_results,
        heldout,
        heldout_note,
        levels: level_rows(&run.model),
        stages: clock.stages,
        files,
    };
    report
        .write(out)
        .with_context(|| format!("writing the report into {}", out.display()))?;
    Ok(report)
}

/// Save a CoSCo-HSOM run's model (`model.bin`) and executed trajectory (`reproduction.csv`)
/// into `out`, list them in `files`, and return its column of the report (notes: why it
/// stopped, postures per level, then `notes`).
pub fn write_hsom_run(
    out: &Path,
    run: &cosco_hsom::experiment::Outcome,
    notes: Vec<String>,
    files: &mut Vec<String>,
) -> Result<cosco_hsom::experiment::report::MethodResult> {
    let model_path = out.join("model.bin");
    run.model.save(&model_path)?;
    files.push("model.bin".into());
    write_csv(
        &out.join("reproduction.csv"),
        &run.executed.to_demonstration("CoSCo-HSOM reproduction"),
    )?;
    files.push("reproduction.csv".into());
    let mut all = vec![
        format!("stopped: {:?}", run.reproduction.stop),
        levels_note(&run.reproduction.predicted_by),
    ];
    all.extend(notes);
    Ok(run.method_result("CoSCo-HSOM", file_size(&model_path), all))
}

/// "predicted by level": how many postures each level produced.
fn levels_note(by: &[usize]) -> String {
    let top = by.iter().copied().max().unwrap_or(0);
    let counts: Vec<String> = (0..=top)
        .map(|l| format!("L{l}: {}", by.iter().filter(|&&b| b == l).count()))
        .collect();
    format!("postures predicted per level: {}", counts.join(", "))
}

/// Read a reproduction CSV (`time` or `step` first column, then the demonstrations' columns).
pub fn read_reproduction(path: &Path) -> Result<Demonstration> {
    let mut d = demos::read_csv(path)?;
    if d.columns.first().map(String::as_str) == Some("step") {
        d.columns.remove(0);
        for r in &mut d.rows {
            r.remove(0);
        }
        if d.columns.is_empty() {
            bail!(
                "{}: only a `step` column, no state variables",
                path.display()
            );
        }
    }
    Ok(d)
}

/// `cosco evaluate`: the fidelity metrics of a reproduction CSV against demonstrations, and
/// the unit of its distances (`rad` for the arm's joints, the data's own units otherwise).
pub fn evaluate_files(
    reproduction: &Path,
    demo_paths: &[PathBuf],
    model: Option<&Path>,
) -> Result<(FidelityReport, &'static str)> {
    let demos = read_demos(demo_paths, None)?;
    let rep = read_reproduction(reproduction)?;
    if rep.columns != demos[0].columns {
        bail!(
            "{}: columns {:?} differ from the demonstrations' {:?} ({})",
            reproduction.display(),
            rep.columns,
            demos[0].columns,
            demos[0].source
        );
    }
    let arm = if are_arm_joints(&rep.columns) {
        Some(load_arm(model)?)
    } else {
        None
    };
    let params = MetricsParams {
        sample_period: sample_period(&demos[0]),
        ..MetricsParams::default()
    };
    let unit = if arm.is_some() { "rad" } else { "data units" };
    Ok((evaluate(arm.as_ref(), &demos, &rep.rows, &params)?, unit))
}

/// Human-readable lines of a fidelity report.
pub fn fidelity_lines(f: &FidelityReport, unit: &str) -> String {
    let st = |s: &cosco_hsom::metrics::Stat| format!("mean {:.4}, worst {:.4}", s.mean, s.worst);
    let mut out = String::new();
    let line = |label: String, value: String| format!("{label:<34}{value}\n");
    out += &line(
        format!("joint DTW ({unit}/step):"),
        st(&f.joint_dtw_rad_per_step),
    );
    if let Some(w) = &f.wrist_dtw_mm {
        out += &line("wrist-path DTW (mm/step):".into(), st(w));
    }
    out += &line(format!("apex error ({unit}):"), st(&f.apex_error_rad));
    out += &line(
        format!("final-posture error ({unit}):"),
        st(&f.final_error_rad),
    );
    out += &line("duration ratio:".into(), st(&f.duration_ratio));
    out += &format!(
        "smoothness: normalized jerk {}, velocity reversals {} ({:?} per column)\n",
        f.reproduction_smoothness
            .normalized_jerk
            .map_or("n/a".into(), |j| format!("{j:.0}")),
        f.reproduction_smoothness.total_reversals,
        f.reproduction_smoothness.reversals
    );
    out
}

/// The extension of a model file: `.bin` or `.txt`, else an error saying so.
pub fn check_model_extension(path: &Path) -> Result<()> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("bin") | Some("txt") => Ok(()),
        _ => bail!(
            "{}: a model file must end in .bin (binary) or .txt (plain text)",
            path.display()
        ),
    }
}

/// `cosco train`: read, train with a progress bar, save atomically.
pub fn train_files(config: Option<&Path>, demo_paths: &[PathBuf], out: &Path) -> Result<Hsom> {
    check_model_extension(out)?;
    let cfg = hsom_config(config)?;
    let demos = read_demos(demo_paths, Some(cfg.params().state_length))?;
    let model = train(&cfg, &demos)?;
    model.save(out)?;
    Ok(model)
}

/// Load a saved model (.bin or .txt).
pub fn load_model(path: &Path) -> Result<Hsom> {
    check_model_extension(path)?;
    Ok(Hsom::load(path)?)
}

/// The error and its causes on one line, leaving out causes whose text the message above
/// already contains (many library errors quote their cause).
pub fn error_line(e: &anyhow::Error) -> String {
    let mut line = e.to_string();
    for cause in e.chain().skip(1) {
        let c = cause.to_string();
        if !line.contains(&c) {
            line.push_str(": ");
            line.push_str(&c);
        }
    }
    line
}

/// Parse `"v1,v2,..."` into numbers, naming the bad entry.
pub fn parse_posture(text: &str) -> Result<Vec<f64>> {
    text.split(',')
        .enumerate()
        .map(|(i, v)| {
            let v = v.trim();
            match v.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => bail!("--initial: value {} is '{v}': need a finite number", i + 1),
            }
        })
        .collect()
}

/// `cosco reproduce`: the initial posture from the command line or a demonstration's first
/// row, the reproduction written as `step` + the model's column names. Returns the number of
/// postures.
pub fn reproduce_file(
    model: &Path,
    initial: Option<&str>,
    initial_from: Option<&Path>,
    out: &Path,
) -> Result<usize> {
    let m = load_model(model)?;
    let columns = m.columns().to_vec();
    let initial = match (initial, initial_from) {
        (Some(text), None) => parse_posture(text)?,
        (None, Some(p)) => {
            let d = demos::read_csv(p)?;
            if d.columns != columns {
                bail!(
                    "{}: columns {:?} differ from the model's {:?}",
                    p.display(),
                    d.columns,
                    columns
                );
            }
            d.rows[0].clone()
        }
        _ => bail!("give exactly one of --initial and --initial-from"),
    };
    if initial.len() != columns.len() {
        bail!(
            "the initial posture has {} values; the model {} learned {} variables ({})",
            initial.len(),
            model.display(),
            columns.len(),
            columns.join(", ")
        );
    }
    let rep = m.reproduce(&initial)?;
    let mut header = vec!["step".to_string()];
    header.extend(columns);
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(&header)?;
    for (step, row) in rep.steps.iter().zip(&rep.postures) {
        let mut rec = vec![step.to_string()];
        rec.extend(row.iter().map(|v| v.to_string()));
        w.write_record(&rec)?;
    }
    let bytes = w
        .into_inner()
        .map_err(|e| anyhow::anyhow!("CSV buffer: {e}"))?;
    cosco_hsom::fsutil::write_atomic(out, &bytes)
        .with_context(|| format!("writing {}", out.display()))?;
    Ok(rep.postures.len())
}
