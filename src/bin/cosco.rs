//! `cosco`: the steps of the main job one at a time, for scripting.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Result;
use clap::{Parser, Subcommand};

mod cli;

#[derive(Parser)]
#[command(
    name = "cosco",
    version,
    about = "CoSCo-HSOM: learn a gesture from raw demonstrations, reproduce it from the initial posture"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Record synthetic, human-like demonstrations of a gesture on the simulated arm (40 Hz encoders).
    Demos {
        /// Gesture name (reading-watch, wave, reach-point, salute).
        #[arg(long, default_value = "reading-watch")]
        gesture: String,
        /// Number of demonstrations.
        #[arg(long, default_value_t = 3)]
        count: usize,
        /// Seed of every random choice.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Output directory (created if missing); files demo_01.csv, demo_02.csv, ...
        #[arg(long)]
        out: PathBuf,
        /// Standard deviation of the encoder noise, rad.
        #[arg(long, default_value_t = cli::DEFAULT_ENCODER_NOISE)]
        noise: f64,
        /// MJCF model of the arm.
        #[arg(long)]
        model: Option<PathBuf>,
    },
    /// Compare CoSCo-HSOM with the paper's GMM/GMR baseline on the same demonstrations, both
    /// executed on the simulated arm from the same initial posture (report, csvs, plots).
    Compare {
        /// Directory of demonstration CSVs (columns: time, then the arm's six joints).
        #[arg(long)]
        demos: PathBuf,
        /// CoSCo-HSOM configuration (XML); default: the built-in Table I.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Output directory (created if missing).
        #[arg(long, default_value = "out-compare")]
        out: PathBuf,
        /// GMM components: a number K >= 1, or `bic` (lowest BIC over 1..=16).
        #[arg(long, default_value = "bic", value_parser = cli::compare::parse_components)]
        components: cosco_hsom::gmr::ComponentChoice,
        /// MJCF model of the arm.
        #[arg(long)]
        model: Option<PathBuf>,
    },
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Command::Demos {
            gesture,
            count,
            seed,
            out,
            noise,
            model,
        } => {
            let files = cli::demos(&gesture, count, seed, &out, noise, model.as_deref())?;
            for f in files {
                println!("{}", f.display());
            }
        }
        Command::Compare {
            demos,
            config,
            out,
            components,
            model,
        } => {
            let job = cli::compare::CompareJob {
                demos,
                config,
                out,
                components,
                model,
            };
            let report = cli::compare::compare(&job)?;
            for line in cli::compare::summary_lines(&report) {
                println!("{line}");
            }
            println!("report: {}", job.out.join("report.md").display());
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("Error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
