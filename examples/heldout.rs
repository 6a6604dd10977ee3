//! Held-out (leave-one-out) study of CoSCo-HSOM beside GMM/GMR and ProMP over gestures, seeds
//! and configurations; Markdown tables on stdout, every number with `--json FILE`.
//!
//! ```sh
//! cargo run --release --example heldout -- --gestures reading-watch,wave --seeds 1-5 \
//!     --config configs/nao-gestures.xml --config configs/table1.xml --in-sample --json h.json
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
use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::Transition;
use cosco_hsom::sim::NaoArm;
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
    /// Write every number to this JSON file.
    #[arg(long)]
    json: Option<PathBuf>,
}

fn run(a: Args) -> Result<()> {
    let t = Instant::now();
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
