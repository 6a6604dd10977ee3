//! What a swing count means, to look at: for each seed, the leave-one-out folds of one
//! gesture (learn from the other demonstrations, reproduce from the held-out one's initial
//! posture, execute on the simulated arm), one panel per fold with the held-out
//! demonstration's `LElbowRoll` and the executed reproduction's, the large swings counted in
//! each (the `LElbowRoll swings` column of `examples/heldout`). Writes
//! `<out>/swing-folds-<gesture>-seed-<S>.png` and prints the counts.
//!
//! ```sh
//! cargo run --release --example swing_folds -- --seeds 11-15 --out docs/figures
//! ```

mod common;
#[path = "common/swing_folds.rs"]
mod swing;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

use cosco_hsom::experiment::demonstrate::parse_seeds;
use cosco_hsom::experiment::demonstrate::{synthetic_demonstrations, DemoSettings};
use cosco_hsom::experiment::Transition;
use cosco_hsom::table::Table;
use swing::{swing_folds, swing_folds_png};

/// Leave-one-out folds of one gesture, drawn.
#[derive(Parser, Debug)]
#[command(name = "swing_folds")]
struct Args {
    /// The gesture.
    #[arg(long, default_value = "wave")]
    gesture: String,
    /// Seeds of the demonstrations: numbers and ranges, e.g. `1-5`.
    #[arg(long, default_value = "11-15")]
    seeds: String,
    /// Demonstrations per seed.
    #[arg(long, default_value_t = 4)]
    count: usize,
    /// Encoder noise of the synthetic demonstrations, rad.
    #[arg(long, default_value_t = 0.001)]
    noise: f64,
    /// CoSCo-HSOM configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    config: PathBuf,
    /// Directory of the figures.
    #[arg(long, default_value = "swing-folds")]
    out: PathBuf,
}

fn run(a: Args) -> Result<()> {
    let (config, arm) = common::config_and_arm(&a.config)?;
    let gesture = common::one_gesture(&a.gesture)?;
    let seeds = parse_seeds(&a.seeds)?;
    std::fs::create_dir_all(&a.out).with_context(|| format!("creating {}", a.out.display()))?;
    let settings = DemoSettings {
        encoder_noise: a.noise,
        ..DemoSettings::default()
    };
    let header = [
        "seed",
        "fold",
        "swings (rep / demo)",
        "joint DTW (rad/step)",
        "duration ratio",
    ];
    print!("{}", Table::new(header));
    for seed in seeds {
        let demos = synthetic_demonstrations(&arm, &gesture, a.count, seed, &settings, |_| {})?;
        let folds = swing_folds(&arm, &config, &demos, Transition::Linear)?;
        for f in &folds {
            print!(
                "{}",
                Table::line([
                    seed.to_string(),
                    (f.held_out + 1).to_string(),
                    format!("{} / {}", f.swings.reproduction, f.swings.demo),
                    format!("{:.4}", f.joint_dtw),
                    format!("{:.2}", f.duration_ratio),
                ])
            );
        }
        let path = a
            .out
            .join(format!("swing-folds-{}-seed-{seed}.png", gesture.name));
        let title = format!(
            "{}, seed {seed}: leave-one-out, {} ({})",
            gesture.name,
            config_name(&a.config),
            folds.first().map_or("", |f| f.swings.joint.as_str())
        );
        swing_folds_png(&path, &title, &folds)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

fn config_name(p: &std::path::Path) -> String {
    p.file_name().map_or_else(
        || p.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
