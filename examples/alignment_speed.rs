//! What the consensus's stairs do to a traced plan's tempo, to look at: one leave-one-out
//! fold of one gesture learned with the consensus read along the DTW warp with its stairs
//! (`alignment = stepped`) and without them (`smooth`), the executed speed of the held-out
//! demonstration's fastest joint beside the demonstration's (docs/ALGORITHM.md, passage 6,
//! "A consensus without stairs"). Writes `<out>/alignment-speed-<gesture>-seed-<S>-fold-<F>.png`
//! and prints each alignment's jerk ratio and joint DTW.
//!
//! ```sh
//! cargo run --release --example alignment_speed -- --gesture salute --seed 20 --fold 1 \
//!     --config tests/configs/traced-finer-events.xml --out docs/figures
//! ```

mod common;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

use cosco_hsom::experiment::demonstrate::{synthetic_demonstrations, DemoSettings};
use cosco_hsom::experiment::heldout::{alignment_fold, velocity_png};
use cosco_hsom::experiment::Transition;
use cosco_hsom::sim::JOINT_NAMES;

/// One fold, learned with each alignment of the consensus, drawn.
#[derive(Parser, Debug)]
#[command(name = "alignment_speed")]
struct Args {
    /// The gesture.
    #[arg(long, default_value = "salute")]
    gesture: String,
    /// Seed of the demonstrations.
    #[arg(long, default_value_t = 20)]
    seed: u64,
    /// The held-out demonstration, 1-based.
    #[arg(long, default_value_t = 1)]
    fold: usize,
    /// Demonstrations.
    #[arg(long, default_value_t = 4)]
    count: usize,
    /// Encoder noise of the synthetic demonstrations, rad.
    #[arg(long, default_value_t = 0.001)]
    noise: f64,
    /// CoSCo-HSOM configuration (XML); its `alignment` is replaced by each in turn.
    #[arg(long, default_value = "tests/configs/traced-finer-events.xml")]
    config: PathBuf,
    /// Directory of the figure.
    #[arg(long, default_value = "alignment-speed")]
    out: PathBuf,
}

fn run(a: Args) -> Result<()> {
    let (config, arm) = common::config_and_arm(&a.config)?;
    let gesture = common::one_gesture(&a.gesture)?;
    if a.fold == 0 || a.fold > a.count {
        anyhow::bail!("--fold {}: allowed 1 to --count ({})", a.fold, a.count);
    }
    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    let settings = DemoSettings {
        encoder_noise: a.noise,
        ..DemoSettings::default()
    };
    let demos = synthetic_demonstrations(&arm, &gesture, a.count, a.seed, &settings, |_| {})?;
    let fold = alignment_fold(&arm, &config, &demos, a.fold - 1, Transition::Linear)?;
    println!("| alignment | jerk ratio (rep / demo) | joint DTW (rad/step) |");
    println!("|---|---|---|");
    for r in &fold.runs {
        println!(
            "| {} | {:.2} | {:.4} |",
            r.alignment, r.jerk_ratio, r.joint_dtw
        );
    }
    let path = a.out.join(format!(
        "alignment-speed-{}-seed-{}-fold-{}.png",
        gesture.name, a.seed, a.fold
    ));
    let title = format!(
        "{}, seed {}, demonstration {} held out: {} speed, {}",
        gesture.name,
        a.seed,
        a.fold,
        JOINT_NAMES.get(fold.joint).copied().unwrap_or("joint"),
        a.config.file_name().map_or_else(
            || a.config.display().to_string(),
            |n| n.to_string_lossy().into_owned()
        )
    );
    velocity_png(&path, &title, &fold)?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
