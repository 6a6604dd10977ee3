//! A gesture in a given duration (`cosco reproduce --duration`), held out: for every
//! leave-one-out fold of each (gesture, seed), the hierarchy learns from the other
//! demonstrations, reproduces from the held-out one's first posture, and the reproduction is
//! retimed to a factor of the held-out demonstration's duration. Per factor: how many were
//! refused as too fast for the servos, the worst duration error, the worst distance of the
//! time-normalised path from the reproduction at its own tempo, and the fastest joint of the
//! trajectory then exported, over its maximum velocity.
//!
//! ```sh
//! cargo run --release --example retime -- --seeds 11-15
//! ```

mod common;

use std::process::ExitCode;

use anyhow::Result;
use clap::Parser;

use cosco_hsom::app::with_duration;
use cosco_hsom::curve::at_phase;
use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::record_demonstrations;
use cosco_hsom::export::limits::RobotLimits;
use cosco_hsom::export::{Trajectory, DEFAULT_STEP_RATE_HZ};
use cosco_hsom::robot::Robot;
use cosco_hsom::table::Table;

/// Held-out reproductions retimed.
#[derive(Parser, Debug)]
struct Args {
    #[command(flatten)]
    sets: common::Sets,
    /// The durations asked, as factors of the held-out demonstration's, comma-separated.
    #[arg(long, default_value = "0.5,0.75,1.5,2")]
    factors: String,
    /// CoSCo-HSOM configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    config: std::path::PathBuf,
}

fn main() -> ExitCode {
    common::exit(run(common::parse_with_defaults(&[("seeds", "11-15")])))
}

/// What one factor gave over every fold.
#[derive(Default)]
struct Row {
    folds: usize,
    refused: usize,
    duration_error: f64,
    path_gap: f64,
    fastest: f64,
}

/// The mean over 201 phases of the mean joint distance between two paths, time normalised.
fn path_gap(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    let d: f64 = (0..=200)
        .map(|k| {
            let (x, y) = (at_phase(a, k as f64 / 200.0), at_phase(b, k as f64 / 200.0));
            x.iter().zip(&y).map(|(x, y)| (x - y).abs()).sum::<f64>() / x.len() as f64
        })
        .sum();
    d / 201.0
}

fn run(a: Args) -> Result<()> {
    a.sets.check_leave_one_out()?;
    let (cfg, arm) = common::config_and_arm(&a.config)?;
    let factors: Vec<f64> = (a.factors.split(','))
        .map(|f| f.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| anyhow::anyhow!("--factors '{}': {e}", a.factors))?;
    let limits = RobotLimits::of(Robot::LeftArm);
    let names: Vec<String> = Robot::LeftArm
        .joint_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    let mut rows: Vec<Row> = factors.iter().map(|_| Row::default()).collect();
    let settings = a.sets.demo_settings();
    for g in parse_gestures(&a.sets.gestures)? {
        for seed in parse_seeds(&a.sets.seeds)? {
            let demos: Vec<_> =
                record_demonstrations(&arm, &g, a.sets.count, seed, &settings, |_| {})?
                    .iter()
                    .map(|r| r.to_demonstration(g.name))
                    .collect();
            for (i, held_out) in demos.iter().enumerate() {
                let train: Vec<_> = (demos.iter().enumerate())
                    .filter(|&(k, _)| k != i)
                    .map(|(_, d)| d.clone())
                    .collect();
                let model = cfg.fit(&train)?;
                let own = model.reproduce(&held_out.rows[0])?;
                let demonstrated = (held_out.rows.len() - 1) as f64 / DEFAULT_STEP_RATE_HZ;
                for (row, &f) in rows.iter_mut().zip(&factors) {
                    row.folds += 1;
                    let asked = f * demonstrated;
                    let Ok(rep) = with_duration(&own, &names, asked) else {
                        row.refused += 1;
                        continue;
                    };
                    let n = rep.postures.len();
                    let got = (n - 1) as f64 / DEFAULT_STEP_RATE_HZ;
                    row.duration_error = row.duration_error.max((got / asked - 1.0).abs());
                    row.path_gap = row.path_gap.max(path_gap(&rep.postures, &own.postures));
                    let times = (0..n).map(|k| k as f64 / DEFAULT_STEP_RATE_HZ).collect();
                    let t = Trajectory::new(names.clone(), times, rep.postures)?;
                    let fastest = limits.fastest(&t)?.map_or(0.0, |v| v.ratio);
                    row.fastest = row.fastest.max(fastest);
                }
            }
        }
    }
    let header = [
        "duration asked (x the held-out demonstration's)",
        "folds",
        "refused (too fast for the servos)",
        "worst duration error",
        "worst path distance (rad, time-normalised)",
        "fastest joint (x its maximum velocity)",
    ];
    let mut table = Table::new(header);
    for (row, f) in rows.iter().zip(&factors) {
        table.row([
            format!("{f}"),
            format!("{}", row.folds),
            format!("{}", row.refused),
            format!("{:.2} %", 100.0 * row.duration_error),
            format!("{:.5}", row.path_gap),
            format!("{:.3}", row.fastest),
        ]);
    }
    print!("{table}");
    Ok(())
}
