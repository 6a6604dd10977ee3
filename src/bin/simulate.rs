//! `simulate`: the main job. Demonstrations -> CoSCo-HSOM training -> reproduction from the
//! initial posture on the simulated Nao arm (or upper body) -> metrics, report, plots and a
//! clip.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::Parser;
use cosco_hsom::aim::Aim;
use cosco_hsom::experiment::arm_loop::LoopMode;
use cosco_hsom::experiment::job;
use cosco_hsom::robot::Robot;
use cosco_hsom::stepper::{Clock, Disturbance};

#[macro_use]
mod cli;

/// Teach the simulated Nao a gesture from demonstrations, reproduce it from the initial
/// posture alone, and measure how faithful the reproduction is.
#[derive(Parser, Debug)]
#[command(name = "simulate", version)]
struct Args {
    /// The robot: `left-arm` (the paper's experiment) or `upper-body` (the head and both arms,
    /// 14 joints, with collision shapes: in-sample only, contacts in the report).
    #[arg(long, default_value = "left-arm")]
    robot: Robot,
    /// Gesture of the synthetic demonstrations. Left arm: reading-watch (default), wave,
    /// reach-point, salute, point-left, or `all`: one hierarchy learns every gesture (`--count`
    /// demonstrations each, one held out in turn), reproduces each on cue, and recognises the
    /// held-out ones. Upper body: wave-right (default), clap, welcome, shrug, nod, shake-head,
    /// reading-watch, salute, point-left, point-right.
    #[arg(long)]
    gesture: Option<String>,
    /// CoSCo-HSOM configuration (XML); default: the shipped configs/nao-gestures.xml (the recommended events extension; configs/table1.xml is the paper taken literally), on the upper body configs/nao-upper-body.xml.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Learn from recorded demonstration CSV files in this directory instead of synthetic ones.
    #[arg(long)]
    demos: Option<PathBuf>,
    /// With --demos: resample demonstrations with `time` columns to this rate, Hz
    /// (shape-preserving).
    #[arg(long, requires = "demos")]
    resample: Option<f64>,
    /// Seed of every random choice of the job (demonstrations; the model's seed is in the config).
    #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = cli::parse_seed)]
    seed: u64,
    /// Number of synthetic demonstrations (in-sample: learn from all, score against all;
    /// held-out: each left out in turn).
    #[arg(long, default_value_t = 4, allow_negative_numbers = true, value_parser = cli::parse_count)]
    count: usize,
    /// Standard deviation of the synthetic encoder noise, rad: 0 to 0.1 (a real encoder's
    /// noise is far below 0.1 rad, about 6 degrees; more would hide the gesture).
    #[arg(long, default_value_t = job::DEFAULT_ENCODER_NOISE, allow_negative_numbers = true, value_parser = cli::parse_noise)]
    noise: f64,
    /// Skip the off-screen rendering of the clip and contact sheet.
    #[arg(long)]
    no_render: bool,
    /// Output directory.
    #[arg(long, default_value = "out")]
    out: PathBuf,
    /// How learned postures become servo targets: `linear` (the paper: posture to posture at
    /// 40 Hz) or `min-jerk[:TOL]` (key poses within TOL rad joined by minimum-jerk transitions).
    #[arg(long, default_value = "linear")]
    transition: String,
    /// Skip the before/after variants (the beyond-the-paper options switched off one at a time).
    #[arg(long)]
    no_variants: bool,
    /// Skip the held-out (leave-one-out) evaluation of both methods.
    #[arg(long)]
    no_heldout: bool,
    /// MJCF model of the robot (default: models/nao_left_arm.xml of this crate, on the upper
    /// body models/nao_upper_body.xml).
    #[arg(long)]
    model: Option<PathBuf>,
    /// How the gesture is reproduced: `open` (planned from the initial posture, then tracked)
    /// or `closed` (also in the loop: each method's stepper drives the arm at 40 Hz from what
    /// its encoders read, undisturbed and then disturbed; report section "In the loop",
    /// in_loop.csv, in_loop.png, and the clip films the hierarchy's run).
    #[arg(long = "loop", default_value = "open", value_name = "open|closed")]
    loop_mode: LoopMode,
    /// In the loop, a hand holds the arm where it is from T s for SECONDS (`T:SECONDS`, e.g.
    /// `3.0:1.0`); repeatable. Needs `--loop closed`.
    #[arg(long, value_name = "T:SECONDS", value_parser = |s: &str| Disturbance::parse("hold", s, Clock::Seconds))]
    hold: Vec<Disturbance>,
    /// In the loop, a force (N, the torso's frame: x forward, y left, z up) on the link BODY
    /// from T s for SECONDS (`T:BODY:FX,FY,FZ:SECONDS`, e.g. `3.0:LForeArm:0,0,-20:0.3`);
    /// repeatable. Needs `--loop closed`.
    #[arg(long, value_name = "T:BODY:FX,FY,FZ:SECONDS", value_parser = |s: &str| Disturbance::parse("push", s, Clock::Seconds), allow_hyphen_values = true)]
    push: Vec<Disturbance>,
    /// In the loop, the goal moves to the posture V1,... (one value per joint) at T s
    /// (`T:V1,...`); repeatable. Needs `--loop closed`.
    #[arg(long, value_name = "T:V1,...", value_parser = |s: &str| Disturbance::parse("goal", s, Clock::Seconds), allow_hyphen_values = true)]
    goal_at: Vec<Disturbance>,
    /// With `--gesture all`: stream each gesture's last held-out demonstration, a sample at a
    /// time, into the recogniser of the fold that did not learn it; the clip films those
    /// demonstrations with the committed label, and the report says when it committed.
    #[arg(long)]
    recognize: bool,
    /// Reproduce the gesture in this many seconds, its path kept (the tempo changes, not the
    /// path), as `cosco reproduce --duration`: a duration the servos cannot follow is refused
    /// naming the shortest. The hierarchy's reproduction of the main job (not with `--gesture
    /// all` or `--loop closed`).
    #[arg(long, value_name = "SECONDS")]
    duration: Option<f64>,
    /// Point at X,Y,Z (metres, in the torso frame: x forward, y to the robot's left, z up), as
    /// `cosco reproduce --point-at`: during the held part of the hierarchy's reproduction of
    /// the main job, the ray from the pointing arm's shoulder through its gripper passes
    /// through it (before `--duration` retimes it); the report says how near the executed
    /// motion pointed. A target the arm cannot point at from the gesture's apex is refused
    /// before any work, naming the closest direction it can. Not with `--gesture all` or
    /// `--loop closed`.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = cosco_hsom::aim::parse_point)]
    point_at: Option<[f64; 3]>,
    /// Look at X,Y,Z (the upper body; metres, torso frame), as `cosco reproduce --look-at`:
    /// during the held part the top camera's optical axis passes through it; the report says
    /// how near the executed motion looked. Checked and refused as `--point-at`.
    #[arg(long, value_name = "X,Y,Z", allow_hyphen_values = true, value_parser = cosco_hsom::aim::parse_point)]
    look_at: Option<[f64; 3]>,
    /// Turn warnings into errors (posture values clamped into the joint ranges before
    /// execution): the outputs are written, the exit status is 1.
    #[arg(long)]
    strict: bool,
}

fn run(a: Args) -> Result<()> {
    let strict = a.strict;
    let mut disturbances = a.hold;
    disturbances.extend(a.push);
    disturbances.extend(a.goal_at);
    if a.loop_mode == LoopMode::Open && !disturbances.is_empty() {
        anyhow::bail!("--hold, --push and --goal-at disturb the loop: they need --loop closed");
    }
    if a.recognize && a.gesture.as_deref() != Some("all") {
        anyhow::bail!(
            "--recognize streams the held-out gestures of --gesture all: give --gesture all"
        );
    }
    if let Some(d) = a.duration {
        if a.gesture.as_deref() == Some("all") || a.loop_mode == LoopMode::Closed {
            anyhow::bail!(
                "--duration {d} retimes the main job's reproduction: not with --gesture all or --loop closed"
            );
        }
        cosco_hsom::export::limits::check_duration(d)?;
    }
    let aim = Aim {
        point_at: a.point_at,
        look_at: a.look_at,
    };
    if !aim.is_empty() && (a.gesture.as_deref() == Some("all") || a.loop_mode == LoopMode::Closed) {
        anyhow::bail!(
            "{} aims the main job's reproduction: not with --gesture all or --loop closed",
            job::aim_flags(&aim)
        );
    }
    if a.loop_mode == LoopMode::Closed && a.gesture.as_deref() == Some("all") {
        anyhow::bail!("--loop closed runs one gesture in the loop; --gesture all is not one");
    }
    let job = job::Job {
        robot: a.robot,
        gesture: a
            .gesture
            .unwrap_or_else(|| a.robot.default_gesture().to_string()),
        config: a.config,
        demos: a.demos,
        resample: a.resample,
        seed: a.seed,
        count: a.count,
        noise: a.noise,
        render: !a.no_render,
        out: a.out,
        model: a.model,
        transition: cosco_hsom::experiment::Transition::parse(&a.transition)?,
        variants: !a.no_variants,
        heldout: !a.no_heldout,
        in_loop: a.loop_mode,
        disturbances,
        recognize: a.recognize,
        duration: a.duration,
        aim,
    };
    // the targets on the gesture's apex, before anything is recorded (recorded demonstrations:
    // on the first one's held part, before anything is written)
    if !aim.is_empty() && job.demos.is_none() {
        job::check_aim(
            job.robot,
            &job::gesture(job.robot, &job.gesture, false)?,
            &aim,
        )?;
    }
    if let Some(d) = &job.demos {
        let line = cosco_hsom::resample::report_line(std::slice::from_ref(d), job.resample)?;
        if let Some(l) = line {
            outln!("{l}");
        }
    }
    let bars = cli::StageBars::default();
    let on_progress = |stage: &str, done, total| bars.update(stage, done, total);
    if job.gesture == "all" {
        let lines = cosco_hsom::experiment::all_gestures::all_gestures_job(&job, &on_progress)?;
        bars.finish();
        for line in lines {
            outln!("{line}");
        }
        outln!("report: {}", job.out.join("report.md").display());
        return Ok(());
    }
    let summary = job::main_job(&job, &on_progress)?;
    bars.finish();
    for w in &summary.warnings {
        eprintln!("warning: {w}");
    }
    let report = summary.report;
    // values moved into the joint ranges before execution: said on stderr, an error with --strict
    let clamped: Vec<String> = report
        .methods
        .iter()
        .filter(|m| m.clamped_values > 0)
        .map(|m| format!("{} {}", m.name, m.clamped_values))
        .collect();
    if !clamped.is_empty() {
        let msg = format!(
            "posture values outside the joint ranges were clamped to the nearest limit before \
             execution ({}; counted in report.md)",
            clamped.join(", ")
        );
        if strict {
            anyhow::bail!("{msg}; --strict makes this an error");
        }
        eprintln!("warning: {msg}; --strict makes this an error");
    }
    // one line per method (CoSCo-HSOM, then the baseline when it ran)
    for line in cosco_hsom::experiment::compare::summary_lines(&report) {
        outln!("{line}");
    }
    outln!("report: {}", job.out.join("report.md").display());
    Ok(())
}

fn main() -> ExitCode {
    cli::exit(run(Args::parse()))
}
