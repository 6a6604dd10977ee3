//! Several gestures in one hierarchy, held out: recognition beside 1-NN DTW, early
//! recognition, fidelity shared vs alone, unknown gestures and negative controls; Markdown
//! on stdout, every number with `--json FILE`.
//!
//! ```sh
//! cargo run --release --example multi_heldout -- --seeds 11-15 --json m.json
//! cargo run --release --example multi_heldout -- --seeds 11-15 --noise 0.003 --no-fidelity
//! ```

mod common;
#[path = "common/multi.rs"]
mod multi;

use std::io::Write as _;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, Result};
use clap::Parser;

use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::Transition;
use multi::{run_seed, to_markdown, MultiSettings};

/// Held-out study of one hierarchy on several gestures.
#[derive(Parser, Debug)]
#[command(name = "multi_heldout")]
struct Args {
    #[command(flatten)]
    sets: common::HeldOutSets,
    /// Skip reproducing and executing (recognition only).
    #[arg(long)]
    no_fidelity: bool,
    /// Skip the unknown study.
    #[arg(long)]
    no_unknown: bool,
    /// Skip the negative controls.
    #[arg(long)]
    no_controls: bool,
}

fn run(a: Args) -> Result<()> {
    let t = Instant::now();
    let sets = &a.sets;
    let gestures = parse_gestures(&sets.gestures)?;
    let seeds = parse_seeds(&sets.seeds)?;
    let (config, arm) = common::config_and_arm(&sets.config)?;
    let settings = MultiSettings {
        train: sets.train,
        test: sets.test,
        noise: sets.noise,
        transition: Transition::parse("linear")?,
        fidelity: !a.no_fidelity,
        unknown: !a.no_unknown,
        controls: !a.no_controls,
    };
    let pb = indicatif::ProgressBar::new(seeds.len() as u64);
    let mut results = Vec::new();
    for &s in &seeds {
        results.push(run_seed(&arm, &config, &gestures, s, &settings)?);
        pb.inc(1);
    }
    pb.finish_and_clear();
    let labels: Vec<String> = gestures.iter().map(|g| g.name.to_string()).collect();
    let mut out = std::io::stdout().lock();
    let _ = write!(out, "{}", to_markdown(&results, &labels));
    let _ = writeln!(
        out,
        "{} seeds, noise {} rad, {:.1} s",
        seeds.len(),
        sets.noise,
        t.elapsed().as_secs_f64()
    );
    if let Some(p) = &sets.json {
        let bytes = serde_json::to_vec_pretty(&results)?;
        cosco_hsom::fsutil::write_atomic(p, &bytes)
            .with_context(|| format!("writing {}", p.display()))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
