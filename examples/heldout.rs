//! Held-out (leave-one-out) study of CoSCo-HSOM beside GMM/GMR and ProMP over gestures, seeds
//! and configurations; Markdown tables on stdout, every number with `--json FILE`.
//!
//! With `--hold` or `--push`, the loop on the simulated arm instead: on every held-out fold
//! each method's stepper drives the arm at 40 Hz from its encoders
//! (`cosco_hsom::sim::in_loop::ArmLoop`), undisturbed and then held or pushed, scored as
//! `cosco heldout --disturb` scores the kinematic loop (`cosco_hsom::eval::in_loop`).
//!
//! ```sh
//! cargo run --release --example heldout -- --gestures reading-watch,wave --seeds 1-5 \
//!     --config configs/nao-gestures.xml --config configs/table1.xml --in-sample --json h.json
//! cargo run --release --example heldout -- --seeds 11-15 --hold 0.4:0.25 \
//!     --push 0.4:LForeArm:0,0,-8:0.1
//! ```

mod common;
#[path = "common/study.rs"]
mod study;

use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Parser;

use cosco_hsom::config::load_config;
use cosco_hsom::eval::{in_loop, loop_markdown, GestureLoo, Pool, LOOP_METHODS};
use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::{synthetic_demonstrations, Transition};
use cosco_hsom::metrics::diagonal;
use cosco_hsom::sim::in_loop::ArmLoop;
use cosco_hsom::sim::{ControllerConfig, NaoArm};
use cosco_hsom::stepper::Disturbance;
use study::{run_study, StudySettings};

/// Leave-one-out evaluation of CoSCo-HSOM and GMM/GMR on synthetic demonstrations.
#[derive(Parser, Debug)]
#[command(name = "heldout")]
struct Args {
    #[command(flatten)]
    sets: common::Sets,
    /// CoSCo-HSOM configuration (XML); repeat for several.
    #[arg(long = "config")]
    configs: Vec<PathBuf>,
    /// `linear` or `min-jerk[:TOL]`.
    #[arg(long, default_value = "linear")]
    transition: String,
    /// Also learn from all demonstrations and score against all (the in-sample result).
    #[arg(long)]
    in_sample: bool,
    /// Also run every configuration at height 1 (its bottom level alone).
    #[arg(long)]
    height_1: bool,
    /// Write every number to this JSON file (with `--hold` or `--push`: every run in the loop).
    #[arg(long)]
    json: Option<PathBuf>,
    /// The loop on the simulated arm, held: a hand holds it from phase P of the held-out
    /// demonstration's duration for D of it (`P:D`, e.g. `0.4:0.25`); repeat for several.
    #[arg(long, value_name = "P:D")]
    hold: Vec<String>,
    /// The loop on the simulated arm, pushed: a force (N, the torso's frame) on the link BODY
    /// from phase P for D of the duration (`P:BODY:FX,FY,FZ:D`, e.g.
    /// `0.4:LForeArm:0,0,-8:0.1`); repeat for several.
    #[arg(long, value_name = "P:BODY:FX,FY,FZ:D")]
    push: Vec<String>,
}

/// The loop on the simulated arm: every (gesture, seed) recorded, each method's stepper on
/// every held-out fold, undisturbed and with each disturbance; a table per disturbance.
fn arm_loop(a: &Args, disturbances: &[Disturbance]) -> Result<String> {
    let gestures = parse_gestures(&a.sets.gestures)?;
    let seeds = parse_seeds(&a.sets.seeds)?;
    let config = a.configs.first().cloned();
    let config = config.unwrap_or_else(|| PathBuf::from("configs/nao-gestures.xml"));
    let cfg = load_config(&config).with_context(|| format!("loading {}", config.display()))?;
    let arm = NaoArm::load_default().context("loading the default arm model")?;
    let mut sets = Vec::new();
    for g in &gestures {
        for &seed in &seeds {
            let demos = synthetic_demonstrations(
                &arm,
                g,
                a.sets.count,
                seed,
                &a.sets.demo_settings(),
                |_| {},
            )?;
            sets.push(GestureLoo {
                gesture: format!("{} seed {seed}", g.name),
                diagonal: diagonal(&demos),
                demonstrations: demos,
                held_out: Vec::new(),
                in_sample: Vec::new(),
            });
        }
    }
    let plant = ArmLoop {
        arm: &arm,
        config: ControllerConfig::default(),
    };
    let pool = Pool::new(2).map_err(anyhow::Error::msg)?;
    let runs = in_loop(&cfg, &sets, &LOOP_METHODS, disturbances, &plant, &pool);
    if let Some(p) = &a.json {
        let doc: Vec<serde_json::Value> = (disturbances.iter().zip(&runs))
            .map(|(d, r)| serde_json::json!({ "disturbance": d, "gestures": r }))
            .collect();
        let text = serde_json::to_string_pretty(&doc)?;
        cosco_hsom::fsutil::write_atomic(p, text.as_bytes())
            .with_context(|| format!("writing {}", p.display()))?;
    }
    Ok(disturbances
        .iter()
        .zip(&runs)
        .map(|(d, r)| {
            loop_markdown(d, r).replacen(
                "## In the loop:",
                "## On the simulated arm in the loop:",
                1,
            )
        })
        .collect())
}

fn run(a: Args) -> Result<()> {
    let t = Instant::now();
    let disturbances: Vec<Disturbance> = (a.hold.iter().map(|h| format!("hold:{h}")))
        .chain(a.push.iter().map(|p| format!("push:{p}")))
        .map(|d| Disturbance::disturb(&d).map_err(anyhow::Error::msg))
        .collect::<Result<_>>()?;
    if !disturbances.is_empty() {
        a.sets.check_leave_one_out()?;
        let text = arm_loop(&a, &disturbances)?;
        let mut out = std::io::stdout().lock();
        let _ = write!(out, "{text}");
        let _ = writeln!(out, "in {:.1} s", t.elapsed().as_secs_f64());
        return Ok(());
    }
    let gestures = parse_gestures(&a.sets.gestures)?;
    let seeds = parse_seeds(&a.sets.seeds)?;
    let paths = if a.configs.is_empty() {
        vec![PathBuf::from("configs/nao-gestures.xml")]
    } else {
        a.configs
    };
    let configs = paths
        .iter()
        .map(|p| load_config(p).with_context(|| format!("loading {}", p.display())))
        .collect::<Result<Vec<_>>>()?;
    let configs = if a.height_1 {
        let mut all = Vec::new();
        for c in configs {
            let h1 = c.at_height(1)?;
            all.push(c);
            all.push(h1);
        }
        all
    } else {
        configs
    };
    let settings = StudySettings {
        count: a.sets.count,
        noise: a.sets.noise,
        transition: Transition::parse(&a.transition)?,
        in_sample: a.in_sample,
        threads: 2,
    };
    let jobs: Vec<_> = gestures
        .iter()
        .flat_map(|g| seeds.iter().map(move |&s| (g.clone(), s)))
        .collect();
    let arm = NaoArm::load_default().context("loading the default arm model")?;
    let study = run_study(&arm, &configs, &jobs, &settings, &|done, total| {
        eprint!("\r{done}/{total} (gesture, seed) sets done");
    })?;
    eprintln!();
    // a closed stdout (`| head`) is not an error
    let mut out = std::io::stdout().lock();
    let _ = write!(out, "{}", study.to_markdown(a.in_sample));
    let _ = writeln!(
        out,
        "{} sets x {} configurations in {:.1} s",
        jobs.len(),
        configs.len(),
        t.elapsed().as_secs_f64()
    );
    if let Some(p) = &a.json {
        study
            .write_json(p)
            .with_context(|| format!("writing {}", p.display()))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
