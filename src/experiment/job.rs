//! The main job of `simulate` (demonstrations, training, reproduction on the simulated arm,
//! metrics, the GMM/GMR baseline, held-out folds, before/after variants, plots, clip and
//! report, all written into one directory), `simulate --gesture all`, and `cosco demos`, as
//! library functions the binaries, the tests and Python can call. Progress is reported
//! through a callback `(stage, done, total)`; nothing here prints.

use std::path::{Path, PathBuf};

use crate::aim::{gaze_errors, pointing_errors, Aim, AimError, Aimed, Point};
use crate::config::{load_config_or_robots, HsomConfig};
use crate::demo_sets::read_demos;
use crate::demos::Demonstration;
use crate::eval::Training;
use crate::gesture::Gesture;
use crate::plot::BLACK;
use crate::sim::in_loop::resistible_force;
use crate::sim::{check_reachable_of, demo_wrist_paths, NaoArm, Recording, Touch, Transition};
use crate::stepper::Kind;

use super::arm_loop::{self, LoopMode};
use super::baseline::GMR_NAME;
use super::compare;
use super::demonstrate::{
    as_demonstrations, demonstration_seconds, record_demonstrations, write_demos,
};
use super::figures::{
    demo_curves, demo_paths, joint_panels_png, reproduction, right_wrist_png, wrist_png, BandTrace,
};
use super::heldout::hierarchy_held_out;
use super::output::{hsom_model, hsom_on_arm, load_robot, write_hsom_run, Stopwatch};
use super::report::{DemoInfo, Report};
use super::variants::{reference_variants, run_variant, variants};
use super::{film, leave_one_out, DemoSettings, ExperimentError, Progress};
use crate::robot::Robot;

/// The result of a job's step.
type Result<T> = std::result::Result<T, ExperimentError>;

/// Default encoder noise of synthetic demonstrations, rad (about Nao's encoder resolution).
pub const DEFAULT_ENCODER_NOISE: f64 = 0.001;

/// Look a gesture of `robot` up by name. The error lists the robot's gestures (and `all`
/// when the command takes it: `all`) and names the robot whose gesture it is, if another's.
pub fn gesture(robot: Robot, name: &str, all: bool) -> Result<Gesture> {
    Gesture::by_name(robot, name).ok_or_else(|| {
        let all = if all {
            ", or all (every gesture but the pointing ones)"
        } else {
            ""
        };
        let other = (Robot::ALL.into_iter())
            .find(|&r| Gesture::by_name(r, name).is_some())
            .map_or(String::new(), |r| {
                format!(
                    "; '{name}' is the {}'s: give --robot {}",
                    r.name(),
                    r.name()
                )
            });
        ExperimentError::Invalid(format!(
            "unknown gesture '{name}' of the {}: allowed {}{all}{other}",
            robot.name(),
            Gesture::names(robot).join(", ")
        ))
    })
}

/// `aim`'s flags as given: `--point-at X,Y,Z`, `--look-at X,Y,Z`.
pub fn aim_flags(aim: &Aim) -> String {
    let flag =
        |name: &str, t: Option<Point>| t.map(|t| format!("{name} {},{},{}", t[0], t[1], t[2]));
    (flag("--point-at", aim.point_at).into_iter())
        .chain(flag("--look-at", aim.look_at))
        .collect::<Vec<_>>()
        .join(" and ")
}

/// A refused target, naming its flag and value when the refusal does not.
fn aim_refused(e: AimError, aim: &Aim) -> ExperimentError {
    let flag = match &e {
        AimError::Unreachable { what, .. } if what == "the head" => Aim {
            point_at: None,
            ..*aim
        },
        AimError::Unreachable { .. } => Aim {
            look_at: None,
            ..*aim
        },
        _ => return ExperimentError::Invalid(e.to_string()),
    };
    ExperimentError::Invalid(format!("{}: {e}", aim_flags(&flag)))
}

/// The targets of `aim` checked on `gesture`'s apex, before any work (the held part of its
/// reproductions is near it): the pointing arm ([`crate::aim::pointing_arm`] of its initial
/// posture and apex) pointed at `--point-at`, then the head turned to `--look-at`
/// ([`crate::aim::point`], [`crate::aim::look`]), each within the joint ranges. A target the
/// arm or the head cannot reach is refused naming the closest direction it can; `--look-at`
/// on the left arm, which has no head, is refused.
pub fn check_aim(robot: Robot, gesture: &Gesture, aim: &Aim) -> Result<()> {
    let apex = gesture.apex();
    let mut posture = apex.clone();
    if let Some(target) = aim.point_at {
        let arm = crate::aim::pointing_arm(robot, &[gesture.initial.clone(), apex]);
        posture =
            crate::aim::point(robot, arm, &posture, target).map_err(|e| aim_refused(e, aim))?;
    }
    if let Some(target) = aim.look_at {
        crate::aim::look(robot, &posture, target).map_err(|e| aim_refused(e, aim))?;
    }
    Ok(())
}

/// The report's notes on what the hierarchy's reproduction was aimed at (`aimed`, solved for
/// `aim`): the angle between the target and the pointing ray (the top camera's optical axis)
/// on the encoders' rows of `executed` over the held part, the largest and the median.
fn aim_notes(robot: Robot, aim: &Aim, aimed: Option<&Aimed>, executed: &Recording) -> Vec<String> {
    let rows = &executed.qpos;
    let Some(aimed) = aimed.filter(|_| !rows.is_empty()) else {
        return Vec::new();
    };
    let last = rows.len() - 1;
    let held = &rows[aimed.span.0.min(last)..=aimed.span.1.min(last)];
    let seconds = held.len() as f64 / executed.rate_hz;
    let within = |errors: Vec<f64>| {
        let largest = errors.iter().copied().fold(0.0, f64::max);
        let median = crate::stats::median(errors).unwrap_or(f64::NAN);
        format!("within {largest:.2} deg of it over the held part ({seconds:.2} s) after execution (median {median:.2} deg)")
    };
    let at = |t: Point| format!("aimed at ({}, {}, {}) m", t[0], t[1], t[2]);
    let mut notes = Vec::new();
    if let (Some(t), Some(arm)) = (aim.point_at, aimed.arm) {
        notes.push(format!(
            "{} (--point-at): the {} arm's pointing ray {}",
            at(t),
            arm.name(),
            within(pointing_errors(robot, arm, held, t))
        ));
    }
    if let Some(t) = aim.look_at {
        notes.push(format!(
            "{} (--look-at): the top camera's optical axis {}",
            at(t),
            within(gaze_errors(held, t))
        ));
    }
    notes
}

/// Record synthetic demonstrations in the simulator (stage `demonstrating`).
pub fn record<const N: usize>(
    arm: &NaoArm<N>,
    gesture: &Gesture,
    count: usize,
    seed: u64,
    noise: f64,
    on_progress: Progress<'_>,
) -> Result<Vec<Demonstration>> {
    let recs = record_traced(arm, gesture, count, seed, noise, on_progress)?;
    Ok(as_demonstrations(gesture, seed, &recs))
}

/// [`record`], the simulator's recordings (contacts included) rather than demonstrations.
fn record_traced<const N: usize>(
    arm: &NaoArm<N>,
    gesture: &Gesture,
    count: usize,
    seed: u64,
    noise: f64,
    on_progress: Progress<'_>,
) -> Result<Vec<Recording>> {
    let settings = DemoSettings {
        encoder_noise: noise,
        ..DemoSettings::default()
    };
    let done = std::cell::Cell::new(0);
    on_progress("demonstrating", 0, count);
    record_demonstrations(arm, gesture, count, seed, &settings, |_| {
        done.set(done.get() + 1);
        on_progress("demonstrating", done.get(), count);
    })
}

/// The loop's disturbances of `job` (`--hold`, `--push`, `--goal-at`) checked against `arm`
/// before any work: a goal of one value per joint within the joint ranges (as `cosco
/// reproduce --goal` holds it), a pushed link of the model, each starting within the motion
/// (the longest demonstration, known without simulating: `--demos`' files, or the
/// demonstrators' lengths). A push the servos cannot hold the link against at the initial
/// posture ([`resistible_force`]) is a warning with the figure.
fn check_loop<const N: usize>(
    job: &Job,
    arm: &NaoArm<N>,
    state_length: usize,
) -> Result<Vec<String>> {
    let robot = arm.robot();
    let (motion, initial) = match &job.demos {
        Some(dir) => {
            let demos = read_demos(std::slice::from_ref(dir), Some(state_length), job.resample)?;
            let seconds = |d: &Demonstration| {
                d.rows.len().saturating_sub(1) as f64 * crate::demos::sample_period(d)
            };
            let motion = demos.iter().map(seconds).fold(0.0, f64::max);
            (motion, demos[0].rows.first().cloned().unwrap_or_default())
        }
        None => {
            let g = gesture(robot, &job.gesture, robot == Robot::LeftArm)?;
            let settings = DemoSettings::default();
            let motion = demonstration_seconds(&g, job.count, job.seed, &settings)?;
            (motion, g.initial.to_vec())
        }
    };
    let columns: Vec<String> = robot.joint_names().iter().map(|n| n.to_string()).collect();
    let links: Vec<String> = (1..arm.model().nbody())
        .filter_map(|i| arm.model().body_name(i))
        .collect();
    let mut warnings = Vec::new();
    for d in &job.disturbances {
        (d.check(&columns, Some(&robot.ranges()), Some(&links), motion))
            .map_err(ExperimentError::Invalid)?;
        let Kind::Push { body, force } = &d.kind else {
            continue;
        };
        let norm = force.iter().map(|f| f * f).sum::<f64>().sqrt();
        if let Some((holds, joint)) = resistible_force(arm, &initial, body, *force)? {
            if norm > holds {
                warnings.push(format!(
                    "{}: {norm:.0} N is beyond the {holds:.1} N the servos hold {body} against \
                     along it at the initial posture ({joint} gives way first, its torque limit \
                     over the lever of the force about its axis): the arm will be thrown",
                    d.describe()
                ));
            }
        }
    }
    Ok(warnings)
}

/// The configuration of the main job on `robot` from `path`, or without one the robot's
/// built-in configuration ([`Robot::config`]), and its name in the report.
fn job_config(robot: Robot, path: Option<&Path>) -> Result<(HsomConfig, String)> {
    let name = path.map_or(robot.config().0.into(), |p| p.display().to_string());
    Ok((load_config_or_robots(path, robot)?, name))
}

/// What `cosco demos` records: which robot's gesture, how many, from which seed, with how
/// much encoder noise, on which model file (None: the robot's shipped model).
#[derive(Debug, Clone)]
pub struct DemosRequest<'a> {
    /// The robot.
    pub robot: Robot,
    /// A gesture of the robot, or `all`.
    pub gesture: &'a str,
    /// Demonstrations per gesture.
    pub count: usize,
    /// Seed of every random choice.
    pub seed: u64,
    /// Encoder noise, rad.
    pub noise: f64,
    /// Model file.
    pub model: Option<&'a Path>,
}

/// `cosco demos`: record and write demonstrations into `out` (with `all`, every gesture into
/// its labelled subdirectory `out/<gesture>/demo_NN.csv`).
pub fn demos(r: &DemosRequest<'_>, out: &Path, on_progress: Progress<'_>) -> Result<Vec<PathBuf>> {
    match r.robot {
        Robot::LeftArm => demos_on::<6>(r, out, on_progress),
        Robot::UpperBody => demos_on::<14>(r, out, on_progress),
    }
}

fn demos_on<const N: usize>(
    r: &DemosRequest<'_>,
    out: &Path,
    on_progress: Progress<'_>,
) -> Result<Vec<PathBuf>> {
    let arm = load_robot::<N>(r.robot, r.model)?;
    let record = |g: &Gesture| record(&arm, g, r.count, r.seed, r.noise, on_progress);
    if r.gesture == "all" {
        let mut files = Vec::new();
        for g in Gesture::all(r.robot) {
            files.extend(write_demos(&out.join(g.name), &record(&g)?)?);
        }
        return Ok(files);
    }
    write_demos(out, &record(&gesture(r.robot, r.gesture, true)?)?)
}

/// Everything the main job needs to know.
#[derive(Debug, Clone)]
pub struct Job {
    /// The robot: the left arm (the paper's experiment) or the upper body.
    pub robot: Robot,
    /// Gesture of the synthetic demonstrations (one of the robot's).
    pub gesture: String,
    /// Configuration file (None: the robot's built-in configuration).
    pub config: Option<PathBuf>,
    /// Directory of recorded demonstrations (None: synthetic).
    pub demos: Option<PathBuf>,
    /// Resample the recorded demonstrations to this rate, Hz.
    pub resample: Option<f64>,
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
    /// Also reproduce in the loop (`--loop closed`): every method's stepper on the arm from
    /// its encoders ([`super::arm_loop`]); the clip then films the hierarchy's run.
    pub in_loop: LoopMode,
    /// What disturbs the arm in the loop (`--hold`, `--push`, `--goal-at`).
    pub disturbances: Vec<crate::stepper::Disturbance>,
    /// With `--gesture all`: stream each gesture's last held-out demonstration into the
    /// recogniser and film it captioned with the committed label.
    pub recognize: bool,
    /// The hierarchy's reproduction retimed to this many seconds, its path kept (`--duration`;
    /// [`crate::export::limits::at_duration`]).
    pub duration: Option<f64>,
    /// What the hierarchy's reproduction points and looks at during its held part
    /// (`--point-at`, `--look-at`; [`crate::eval::FoldInput::aim`]), before any retiming.
    pub aim: Aim,
}

/// What the main job produced: the report (also written as `report.md` and `report.json`) and
/// the warnings to show (the job went on past them).
#[derive(Debug, Clone)]
pub struct JobSummary {
    /// The report.
    pub report: Report,
    /// Steps skipped, with the reason.
    pub warnings: Vec<String>,
}

/// The main job: demonstrations -> training -> reproduction in the simulator -> report,
/// plots and clip, all written into `job.out`, on the job's robot. On the upper body the
/// before/after variants and the held-out section are not run (the report says so), both
/// wrists' paths are drawn and scored, and the report lists the contacts between its parts.
pub fn main_job(job: &Job, on_progress: Progress<'_>) -> Result<JobSummary> {
    match job.robot {
        Robot::LeftArm => main_job_on::<6>(job, on_progress),
        Robot::UpperBody => main_job_on::<14>(job, on_progress),
    }
}

/// What the main job leaves out on `robot`, one line each (nothing on the left arm).
fn not_run(robot: Robot) -> Vec<String> {
    match robot {
        Robot::LeftArm => Vec::new(),
        Robot::UpperBody => vec![
            "held-out (leave-one-out) evaluation, with the nearest sequence, ProMP and the DMP: \
             the upper body's job is in-sample only"
                .into(),
            "the before/after variants: their reference is the paper's Table I \
             (configs/table1.xml), whose stateLength is the left arm's 6"
                .into(),
        ],
    }
}

fn main_job_on<const N: usize>(job: &Job, on_progress: Progress<'_>) -> Result<JobSummary> {
    let robot = job.robot;
    let in_sample_only = robot != Robot::LeftArm;
    let mut warnings = Vec::new();
    let mut clock = Stopwatch::default();
    let out = &job.out;
    let (cfg, cfg_name) = job_config(robot, job.config.as_deref())?;
    let arm = load_robot::<N>(robot, job.model.as_deref())?;
    if job.in_loop == LoopMode::Closed {
        warnings.extend(check_loop(job, &arm, cfg.params().state_length)?);
    }
    let mut files = Vec::new();

    // 1. Demonstrations (with their contacts, on a model with collision shapes).
    let (demos, gesture, contacts): (_, _, Option<Vec<Vec<Touch>>>) = match &job.demos {
        Some(dir) => (
            read_demos(
                std::slice::from_ref(dir),
                Some(cfg.params().state_length),
                job.resample,
            )?,
            None,
            None,
        ),
        None => {
            // `simulate --gesture all` runs on the left arm alone
            let g = gesture(robot, &job.gesture, robot == Robot::LeftArm)?;
            let recs = record_traced(&arm, &g, job.count, job.seed, job.noise, on_progress)?;
            let contacts = robot
                .has_collision_shapes()
                .then(|| recs.iter().map(|r| r.contacts.clone()).collect());
            let demos = as_demonstrations(&g, job.seed, &recs);
            (demos, Some(g.name.to_string()), contacts)
        }
    };
    if Robot::of_columns(&demos[0].columns) != Some(robot) {
        return Err(ExperimentError::Invalid(format!(
            "the demonstrations' columns are {:?}; the simulated arm needs exactly {:?} (use `cosco train` / `cosco reproduce` for other data)",
            demos[0].columns,
            robot.joint_names()
        )));
    }
    // recorded demonstrations far outside the joint ranges are no gesture the arm can make
    for d in &demos {
        check_reachable_of(robot, &d.rows, &d.source)?;
    }
    // recorded demonstrations: the aim checked on the first one's held part before anything
    // is written (`simulate` checks a synthetic gesture's apex before recording, `check_aim`)
    if job.demos.is_some() && !job.aim.is_empty() {
        crate::aim::solve(robot, &demos[0].rows, &job.aim).map_err(|e| aim_refused(e, &job.aim))?;
    }
    let demo_files = write_demos(&out.join("demos"), &demos)?;
    let demo_info: Vec<DemoInfo> = demos
        .iter()
        .zip(&demo_files)
        .enumerate()
        .map(|(i, (d, f))| DemoInfo {
            contacts: contacts.as_ref().map(|c| c[i].clone()),
            ..DemoInfo::new(f.strip_prefix(out).unwrap_or(f).display().to_string(), d)
        })
        .collect();
    files.extend(demo_info.iter().map(|d| d.file.clone()));
    clock.lap("demonstrations (simulate + record)");

    // 2-4. Training, reproduction from the initial posture on the simulated arm, metrics.
    let run = hsom_on_arm(
        &arm,
        &cfg,
        &demos,
        job.transition,
        job.duration,
        job.aim,
        on_progress,
    )?;
    clock.split_lap(
        "training",
        run.train_s,
        "reproduction (predict + execute) and metrics",
    );
    let executed = &run.executed.trace;
    let mut notes = aim_notes(robot, &job.aim, run.aimed.as_ref(), executed);
    notes.extend((job.duration).map(|d| format!("retimed to {d} s (--duration), its path kept")));
    let hsom_result = write_hsom_run(out, &run, notes, &mut files)?;
    clock.lap("writing the model and reproduction.csv");

    // 5. Plots.
    let (curve, path) = reproduction("CoSCo-HSOM reproduction", BLACK, executed);
    let mut curves = demo_curves(&demos);
    curves.push(curve);
    let band = run.band.as_ref().map(|b| {
        let period = demos.first().map_or(0.025, crate::demos::sample_period);
        BandTrace::reproduction("its 95 % band", BLACK, (period, b))
    });
    joint_panels_png(
        &out.join("joints.png"),
        "Training demonstrations (colour) and the reproduced gesture (black) with its 95 % band",
        &robot.plot_panels(),
        &curves,
        band.as_ref(),
    )?;
    files.push("joints.png".into());
    let demo_wrists = demo_wrist_paths(&arm, &demos)?;
    let mut paths = demo_paths(&demo_wrists);
    paths.push(path);
    wrist_png(
        &out.join("wrist.png"),
        "Wrist path (l_wrist), torso frame",
        &paths,
    )?;
    files.push("wrist.png".into());
    if robot == Robot::UpperBody {
        right_wrist_png(
            &arm,
            &demos,
            [("CoSCo-HSOM reproduction", BLACK, executed)],
            &out.join("wrist_right.png"),
            "Wrist path (r_wrist), torso frame",
        )?;
        files.push("wrist_right.png".into());
    }
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
            warnings.push(format!("GMM/GMR baseline skipped: {e:#}"));
            methods[0]
                .notes
                .push(format!("GMM/GMR baseline not run: {e:#}"));
        }
    }
    clock.lap("GMM/GMR baseline (fit + execute + metrics + plots)");

    // 5c. Held-out: each demonstration in turn left out, both methods (experiment::heldout).
    let (heldout, heldout_note) = if in_sample_only {
        let note = format!("the {} job is in-sample only", robot.name());
        (None, Some(note))
    } else if !job.heldout {
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
    if job.variants && !in_sample_only {
        let mut vs = reference_variants(&cfg, job.transition)?;
        vs.extend(variants(&cfg, job.transition)?);
        on_progress("variants", 0, vs.len());
        let mut main = methods[0].clone();
        main.name = format!("{} ({})", cfg.source(), job.transition.name());
        if job.heldout && main.heldout.is_none() && demos.len() >= 2 {
            main.heldout = Some(hierarchy_held_out(
                &arm,
                &cfg,
                &demos,
                Training::Trained,
                job.transition,
            )?);
        }
        variant_results.push(main);
        for (k, v) in vs.iter().enumerate() {
            variant_results.push(run_variant(&arm, v, &demos, job.heldout)?);
            on_progress("variants", k + 1, vs.len());
        }
        clock.lap(if job.heldout {
            "before/after variants (train + reproduce + execute + metrics each, in-sample and held-out)"
        } else {
            "before/after variants (train + reproduce + execute + metrics each)"
        });
    }

    // 5e. In the loop: every method's stepper on the arm, undisturbed and disturbed.
    let in_loop = match job.in_loop {
        LoopMode::Open => None,
        LoopMode::Closed => {
            let model = hsom_model(&run)?.0;
            let (section, h) =
                arm_loop::closed_loop(&arm, model, &demos, &job.disturbances, out, &mut files)?;
            arm_loop::loop_png(&out.join("in_loop.png"), robot, &demos, &h)?;
            files.push("in_loop.png".into());
            clock.lap("in the loop (every method's stepper on the arm, undisturbed and disturbed)");
            Some((section, h))
        }
    };

    // 6. Clip: the reproduction (in the loop: the hierarchy's disturbed run, marked).
    if job.render {
        let opts = super::film::clip_options();
        let stride = 2;
        let filmed = in_loop.as_ref().map_or(executed, |(_, h)| &h.run);
        let frames = filmed.len().div_ceil(stride);
        let progress = |n, _| on_progress("rendering", n, frames);
        let clip = match &in_loop {
            None => film(&arm, executed, &opts, stride, progress)?,
            Some((_, h)) => {
                let size = (opts.width as u32, opts.height as u32);
                let camera = opts
                    .camera
                    .as_deref()
                    .and_then(|c| arm.model().camera_id(c));
                let mark =
                    |i: usize, data: &crate::mujoco::Data<'_>, frame: &mut image::RgbImage| {
                        arm_loop::mark_frame(h, i, data, camera, size, frame)
                    };
                super::film::film_marked(&arm, filmed, &opts, stride, mark, progress)?
            }
        };
        clip.write_gif(&out.join("clip.gif"))?;
        // in the loop, every disturbance on the sheet, and the frames' own captions give the
        // time (a sheet label would cover them)
        let (picked, labels) = match &in_loop {
            None => (clip.key_frames(8), true),
            Some((_, h)) => (
                clip.key_frames_within(8, &arm_loop::marked_windows(h)),
                false,
            ),
        };
        clip.write_contact_sheet(&out.join("contact_sheet.png"), &picked, 4, labels)?;
        files.extend(["clip.gif".into(), "contact_sheet.png".into()]);
        clock.lap("rendering (clip + contact sheet)");
    }

    files.extend(["report.md".into(), "report.json".into()]);
    let report = Report {
        title: format!(
            "CoSCo-HSOM on the simulated Nao {}{}",
            robot.phrase(),
            gesture
                .as_deref()
                .map(|g| format!(": {g}"))
                .unwrap_or_default()
        ),
        gesture,
        seed: job.seed,
        config: cfg_name,
        demos: demo_info,
        methods,
        variants: variant_results,
        heldout,
        heldout_note,
        levels: hsom_model(&run)?.0.summary().levels,
        stages: clock.stages,
        files,
        not_run: not_run(robot),
        in_loop: in_loop.map(|(section, _)| section),
    };
    report
        .write(out)
        .map_err(ExperimentError::io("writing the report into", out))?;
    Ok(JobSummary { report, warnings })
}
