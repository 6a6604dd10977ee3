//! The simplest baseline of the held-out study: no model at all, a training demonstration
//! replayed. For every leave-one-out fold of 4 demonstrations, each of the 3 training
//! demonstrations' recorded joint trajectory is scored against the held-out one (the same
//! metrics as `examples/heldout.rs`); prints the mean over the 3 and the 4 folds, per
//! (gesture, seed), and the medians.
//!
//! ```sh
//! cargo run --release --example replay_baseline -- --seeds 11-15
//! ```

mod common;

use std::process::ExitCode;

use anyhow::Result;
use clap::Parser;

use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::{record_demonstrations, DemoSettings};
use cosco_hsom::metrics::MetricsParams;
use cosco_hsom::sim::evaluate;
use cosco_hsom::sim::NaoArm;
use cosco_hsom::stats::median;
use cosco_hsom::table::Table;

/// Held-out score of replaying a training demonstration.
#[derive(Parser, Debug)]
struct Args {
    /// Gestures, comma-separated.
    #[arg(long, default_value = "reading-watch,wave,reach-point,salute")]
    gestures: String,
    /// Seeds of the demonstrations: numbers and ranges, e.g. `11-15`.
    #[arg(long, default_value = "11-15")]
    seeds: String,
    /// Demonstrations per (gesture, seed), at least 2.
    #[arg(long, default_value_t = 4)]
    count: usize,
    /// Encoder noise of the synthetic demonstrations, rad.
    #[arg(long, default_value_t = 0.001)]
    noise: f64,
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}

fn run(a: Args) -> Result<()> {
    anyhow::ensure!(a.count >= 2, "--count must be at least 2, got {}", a.count);
    let arm = NaoArm::load_default()?;
    let settings = DemoSettings {
        encoder_noise: a.noise,
        ..DemoSettings::default()
    };
    let params = MetricsParams::default();
    let (gestures, seeds) = (parse_gestures(&a.gestures)?, parse_seeds(&a.seeds)?);
    let header = [
        "gesture",
        "seed",
        "joint DTW (rad/step)",
        "wrist DTW (mm/step)",
    ];
    print!("{}", Table::new(header));
    let (mut all_j, mut all_w) = (Vec::new(), Vec::new());
    for g in gestures {
        for &seed in &seeds {
            let demos: Vec<_> = record_demonstrations(&arm, &g, a.count, seed, &settings, |_| {})?
                .iter()
                .enumerate()
                .map(|(i, r)| r.to_demonstration(format!("{} #{i}", g.name)))
                .collect();
            let (mut j, mut w, mut n) = (0.0, 0.0, 0.0);
            for (i, held_out) in demos.iter().enumerate() {
                for (k, replayed) in demos.iter().enumerate().filter(|&(k, _)| k != i) {
                    let f = evaluate(
                        Some(&arm),
                        std::slice::from_ref(held_out),
                        &replayed.rows,
                        &params,
                    )
                    .map_err(|e| anyhow::anyhow!("fold {i}, demonstration {k}: {e}"))?;
                    j += f.joint_dtw_rad_per_step.mean;
                    w += f.wrist_dtw_mm.map_or(f64::NAN, |s| s.mean);
                    n += 1.0;
                }
            }
            print!(
                "{}",
                Table::line([
                    g.name.to_string(),
                    seed.to_string(),
                    format!("{:.4}", j / n),
                    format!("{:.2}", w / n),
                ])
            );
            all_j.push(j / n);
            all_w.push(w / n);
        }
    }
    print!(
        "{}",
        Table::line([
            "**all**".into(),
            "median".into(),
            format!("{:.4}", median(all_j).unwrap_or(f64::NAN)),
            format!("{:.2}", median(all_w).unwrap_or(f64::NAN)),
        ])
    );
    Ok(())
}
