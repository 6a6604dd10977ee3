//! Continuing a prefix, held out: for every leave-one-out fold the hierarchy is shown the
//! first part of the held-out demonstration and continues it (`Hsom::continue_events`: the
//! prefix pushed up the lists, the levels plan the rest), beside the nearest-sequence
//! baseline from the same model (`Hsom::follow_nearest_from`: the training demonstration
//! along which the prefix runs closest, continued after the prefix's end). The prefix and
//! each continuation are executed on the simulated arm and scored against the held-out
//! demonstration; the prefix is the same for both, so the difference is the continuation's.
//! With `--disturbance hold:N` or `rewind:N` the arm is held still, or pushed back along its
//! path, for N samples at the prefix's end before the continuation takes over.
//! Markdown on stdout: means over the folds per (gesture, seed), medians per gesture.
//!
//! ```sh
//! cargo run --release --example continuation -- --seeds 1-5 --fraction 0.5
//! cargo run --release --example continuation -- --seeds 6-10 --disturbance rewind:40
//! ```

mod common;
#[path = "common/continuation.rs"]
mod continuation;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

use continuation::{continuation_folds, Disturbance};
use cosco_hsom::eval::FoldScores;
use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::{synthetic_demonstrations, Transition};
use cosco_hsom::stats::median;
use cosco_hsom::table::Table;

/// Continuing a held-out demonstration's prefix: the hierarchy and the nearest sequence.
#[derive(Parser, Debug)]
#[command(name = "continuation")]
struct Args {
    #[command(flatten)]
    sets: common::Sets,
    /// The share of the held-out demonstration's samples shown, strictly between 0 and 1.
    #[arg(long, default_value_t = 0.5)]
    fraction: f64,
    /// What happens at the prefix's end: `none`, `hold:N` or `rewind:N` (samples).
    #[arg(long, default_value = "none")]
    disturbance: String,
    /// CoSCo-HSOM configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    config: PathBuf,
}

/// Mean joint DTW over the folds and the folds whose swings are the held-out demonstration's.
fn summary(folds: &[FoldScores]) -> (f64, usize) {
    let dtw = folds
        .iter()
        .map(|f| f.fidelity.joint_dtw_rad_per_step.mean)
        .sum::<f64>()
        / folds.len().max(1) as f64;
    let exact = folds
        .iter()
        .filter(|f| f.swings.as_ref().is_some_and(|w| w.reproduction == w.demo))
        .count();
    (dtw, exact)
}

fn run(a: Args) -> Result<()> {
    a.sets.check_leave_one_out()?;
    let disturbance = Disturbance::parse(&a.disturbance)?;
    let (config, arm) = common::config_and_arm(&a.config)?;
    let settings = a.sets.demo_settings();
    println!(
        "Continuing the first {:.0} % of each held-out demonstration, disturbance {} ({}, seeds {}, {} demonstrations, noise {} rad): joint DTW of prefix + continuation against the held-out demonstration, means over the folds; LElbowRoll swings exact (folds).\n",
        a.fraction * 100.0,
        a.disturbance,
        a.config.display(),
        a.sets.seeds,
        a.sets.count,
        a.sets.noise
    );
    let header = [
        "gesture",
        "seed",
        "hierarchy joint DTW",
        "nearest sequence",
        "hierarchy swings exact",
        "nearest sequence swings exact",
    ];
    print!("{}", Table::new(header));
    let mut all = Vec::new();
    for g in parse_gestures(&a.sets.gestures)? {
        let mut rows = Vec::new();
        for seed in parse_seeds(&a.sets.seeds)? {
            let demos = synthetic_demonstrations(&arm, &g, a.sets.count, seed, &settings, |_| {})?;
            let (h, s) = continuation_folds(
                &arm,
                &config,
                &demos,
                a.fraction,
                disturbance,
                Transition::Linear,
            )
            .with_context(|| format!("{} seed {seed}", g.name))?;
            let ((hd, he), (sd, se)) = (summary(&h), summary(&s));
            print!(
                "{}",
                Table::line([
                    g.name.to_string(),
                    seed.to_string(),
                    format!("{hd:.4}"),
                    format!("{sd:.4}"),
                    format!("{he} of {}", h.len()),
                    format!("{se} of {}", s.len()),
                ])
            );
            rows.push((hd, sd, he, se, h.len()));
        }
        let med = |f: fn(&(f64, f64, usize, usize, usize)) -> f64| {
            median(rows.iter().map(f)).unwrap_or(f64::NAN)
        };
        let (he, se, n) = rows
            .iter()
            .fold((0, 0, 0), |(a, b, c), r| (a + r.2, b + r.3, c + r.4));
        print!(
            "{}",
            Table::line([
                format!("**{}**", g.name),
                "median".into(),
                format!("{:.4}", med(|r| r.0)),
                format!("{:.4}", med(|r| r.1)),
                format!("{he} of {n}"),
                format!("{se} of {n}"),
            ])
        );
        all.extend(rows);
    }
    let hsom_closer = all.iter().filter(|r| r.0 < r.1).count();
    print!(
        "{}",
        Table::line([
            "**all**".into(),
            "median".into(),
            format!("{:.4}", median(all.iter().map(|r| r.0)).unwrap_or(f64::NAN)),
            format!("{:.4}", median(all.iter().map(|r| r.1)).unwrap_or(f64::NAN)),
            format!("hierarchy closer in {hsom_closer} of {} runs", all.len()),
            String::new(),
        ])
    );
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
