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
use std::path::PathBuf;
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
    /// Gestures, comma-separated.
    #[arg(long, default_value = "reading-watch,wave,reach-point,salute")]
    gestures: String,
    /// Seeds of the demonstrations: numbers and ranges, e.g. `1-5`.
    #[arg(long, default_value = "1-5")]
    seeds: String,
    /// Demonstrations per gesture to learn from.
    #[arg(long, default_value_t = 3)]
    train: usize,
    /// Held-out demonstrations per gesture.
    #[arg(long, default_value_t = 2)]
    test: usize,
    /// Encoder noise of the recordings, rad.
    #[arg(long, default_value_t = 0.001)]
    noise: f64,
    /// CoSCo-HSOM configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    config: PathBuf,
    /// Skip reproducing and executing (recognition only).
    #[arg(long)]
    no_fidelity: bool,
    /// Skip the unknown study.
    #[arg(long)]
    no_unknown: bool,
    /// Skip the negative controls.
    #[arg(long)]
    no_controls: bool,
    /// Write every number to this JSON file.
    #[arg(long)]
    json: Option<PathBuf>,
}

fn run(a: Args) -> Result<()> {
    let t = Instant::now();
    let gestures = parse_gestures(&a.gestures)?;
    let seeds = parse_seeds(&a.seeds)?;
    let (config, arm) = common::config_and_arm(&a.config)?;
    let settings = MultiSettings {
        train: a.train,
        test: a.test,
        noise: a.noise,
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
        a.noise,
        t.elapsed().as_secs_f64()
    );
    if let Some(p) = &a.json {
        let bytes = serde_json::to_vec_pretty(&results)?;
        cosco_hsom::fsutil::write_atomic(p, &bytes)
            .with_context(|| format!("writing {}", p.display()))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
