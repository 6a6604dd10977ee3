//! `cosco`: the steps of the main job one at a time, for scripting. Without the feature `sim`
//! only `train`, `reproduce`, `recognize`, `inspect`, `evaluate` and `heldout` (which need no
//! simulator; `heldout --png` needs the feature `plot`).

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};

mod cli;

/// `print!` that ignores a closed stdout (e.g. `| head`), instead of panicking.
macro_rules! out {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stdout(), $($t)*);
    }};
}

/// `println!` that ignores a closed stdout.
macro_rules! outln {
    ($($t:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stdout(), $($t)*);
    }};
}

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
    #[cfg(feature = "sim")]
    /// Record synthetic, human-like demonstrations of a gesture on the simulated arm (40 Hz
    /// encoders); `demos import`: from a ROS 2 bag.
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Demos {
        #[cfg(feature = "ros2")]
        #[command(subcommand)]
        action: Option<cli::export::DemosAction>,
        /// Gesture name (reading-watch, wave, reach-point, salute), or `all`: every gesture,
        /// each in its own labelled subdirectory of --out (OUT/<gesture>/demo_01.csv, ...).
        #[arg(long, default_value = "reading-watch")]
        gesture: String,
        /// Number of demonstrations.
        #[arg(long, default_value_t = 3, allow_negative_numbers = true, value_parser = cli::parse_count)]
        count: usize,
        /// Seed of every random choice.
        #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = cli::parse_seed)]
        seed: u64,
        /// Output directory (created if missing); files demo_01.csv, demo_02.csv, ...
        #[arg(long, required = true)]
        out: Option<PathBuf>,
        /// Standard deviation of the encoder noise, rad.
        #[arg(long, default_value_t = cli::DEFAULT_ENCODER_NOISE, allow_negative_numbers = true, value_parser = cli::parse_noise)]
        noise: f64,
        /// MJCF model of the arm.
        #[arg(long)]
        model: Option<PathBuf>,
    },
    #[cfg(all(feature = "ros2", not(feature = "sim")))]
    /// `demos import`: demonstrations from a ROS 2 bag.
    Demos {
        #[command(subcommand)]
        action: cli::export::DemosAction,
    },
    /// Export a reproduction for a real robot: NAOqi JSON, ROS 2 MCAP or CSV, time-scaled
    /// and checked against the robot's joint ranges and velocity limits.
    Export(cli::export::ExportArgs),
    /// Train a CoSCo-HSOM hierarchy on demonstration CSV files and save it (.bin or .txt).
    Train {
        /// XML configuration (default: the built-in configs/nao-gestures.xml, the recommended events extension).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Demonstrations: a directory of *.csv files, or files (one gesture); or directories
        /// whose subdirectories are gesture labels (DIR/<label>/*.csv: several gestures in one
        /// hierarchy).
        #[arg(long, num_args = 1.., required = true)]
        demos: Vec<PathBuf>,
        /// Where to save the model: `.bin` (binary) or `.txt` (plain text).
        #[arg(long)]
        out: PathBuf,
        /// Take stateLength and actionLength from the demonstrations' columns.
        #[arg(long)]
        state_length_from_data: bool,
        /// Resample demonstrations with `time` columns to this rate, Hz (shape-preserving).
        #[arg(long)]
        resample: Option<f64>,
    },
    /// Reproduce a gesture from an initial posture with a saved model; writes `step` then the
    /// demonstrations' columns.
    Reproduce {
        /// A model saved by `cosco train` (.bin or .txt).
        #[arg(long)]
        model: PathBuf,
        /// The initial posture, comma-separated, one value per state variable.
        #[arg(
            long,
            conflicts_with_all = ["initial_from", "prefix_from"],
            required_unless_present_any = ["initial_from", "prefix_from"]
        )]
        initial: Option<String>,
        /// Take the initial posture from the first row of this demonstration CSV.
        #[arg(long, conflicts_with = "prefix_from")]
        initial_from: Option<PathBuf>,
        /// The gesture to reproduce (required with a model of several gestures).
        #[arg(long, conflicts_with = "prefix_from")]
        gesture: Option<String>,
        /// Continue the gesture begun in this demonstration CSV's first --prefix samples; the
        /// hierarchy decides which gesture it is.
        #[arg(long, requires = "prefix")]
        prefix_from: Option<PathBuf>,
        /// Samples of --prefix-from to continue from.
        #[arg(long, requires = "prefix_from")]
        prefix: Option<usize>,
        /// Resume the reproduction from the initial posture after part of it was executed:
        /// this CSV (the model's columns) is what the encoders read meanwhile, possibly
        /// disturbed; writes the rest, from the reading's last posture (`algorithm = events`).
        #[arg(long, conflicts_with = "prefix_from")]
        resume_from: Option<PathBuf>,
        /// Output CSV.
        #[arg(long)]
        out: PathBuf,
    },
    /// Recognise demonstrations with a model of several gestures: per file the label (or
    /// `unknown`), a score per label and the earliest sample from which the decision held.
    Recognize {
        /// A model trained on labelled directories (`cosco train --demos DIR`, DIR/<label>/*.csv).
        #[arg(long)]
        model: PathBuf,
        /// A demonstration CSV, a directory of them, or a directory of label subdirectories.
        #[arg(long)]
        demos: PathBuf,
        /// Also write every answer as JSON here.
        #[arg(long)]
        json: Option<PathBuf>,
    },
    /// Held out on your own demonstrations, without the simulator: for each demonstration,
    /// learn from the others, reproduce from its first sample, score against it; the
    /// hierarchy beside the nearest sequence, height 1, GMM/GMR and a replay, on the same folds
    /// (Markdown on stdout).
    Heldout {
        /// Demonstrations: a directory of *.csv files or files (one gesture), or directories of
        /// gesture subdirectories (DIR/<gesture>/*.csv, each gesture on its own); at least 3
        /// per gesture.
        #[arg(long, num_args = 1.., required = true)]
        demos: Vec<PathBuf>,
        /// XML configuration (default: the built-in configs/nao-gestures.xml).
        #[arg(long)]
        config: Option<PathBuf>,
        /// Take stateLength and actionLength from the demonstrations' columns.
        #[arg(long)]
        state_length_from_data: bool,
        /// Resample demonstrations with `time` columns to this rate, Hz (shape-preserving).
        #[arg(long)]
        resample: Option<f64>,
        /// How the consensus weighs the demonstrations, instead of the configuration's:
        /// `start` (by how near each one started, where the starts predict the route),
        /// `all` (alike) or `local` (those that agree at each sample).
        #[arg(long)]
        consensus: Option<cosco_hsom::config::Consensus>,
        /// How the levels' prediction becomes a plan, instead of the configuration's:
        /// `traced` (the demonstrated stretch the predicting node stands for, followed along
        /// its demonstration) or `decoded` (slot by slot, by content).
        #[arg(long)]
        plan: Option<cosco_hsom::config::Plan>,
        /// How the consensus reads one demonstration along another, instead of the
        /// configuration's: `stepped` (each sample the mean of those aligned to it) or `smooth`
        /// (the DTW warp's stairs replaced by lines).
        #[arg(long)]
        alignment: Option<cosco_hsom::config::Alignment>,
        /// Where a traced plan's events put their knots, instead of the configuration's:
        /// `event` (one, at its middle) or `halves` (one at each half's place).
        #[arg(long)]
        knots: Option<cosco_hsom::config::Knots>,
        /// Leave out the configuration at height 1.
        #[arg(long)]
        no_height_1: bool,
        /// Leave out GMM/GMR.
        #[arg(long)]
        no_gmr: bool,
        /// Leave out the in-sample result (learned from all).
        #[arg(long)]
        no_in_sample: bool,
        /// Worker threads (default: every core).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=1024))]
        threads: Option<u64>,
        /// Also write every fold's scores as JSON here.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Also draw one fold per gesture (the first sample's plane) as a PNG here.
        #[cfg(feature = "plot")]
        #[arg(long)]
        png: Option<PathBuf>,
    },
    /// Print a saved model's levels, sizes and quality measures.
    Inspect {
        /// A model saved by `cosco train` (.bin or .txt).
        model: PathBuf,
    },
    /// Fidelity metrics of a reproduction CSV against demonstrations (docs/METRICS.md).
    Evaluate {
        /// Reproduction CSV (`time` or `step` column, then the demonstrations' columns).
        #[arg(long)]
        reproduction: PathBuf,
        /// Demonstrations: a directory of *.csv files, or files.
        #[arg(long, num_args = 1.., required = true)]
        demos: Vec<PathBuf>,
        /// Also write the full report as JSON here.
        #[arg(long)]
        json: Option<PathBuf>,
        /// MJCF model of the arm, for wrist paths (default: the crate's model).
        #[cfg(feature = "sim")]
        #[arg(long)]
        model: Option<PathBuf>,
    },
    #[cfg(feature = "sim")]
    /// Compare CoSCo-HSOM with the paper's GMM/GMR baseline on the same demonstrations, both
    /// executed on the simulated arm from the same initial posture (report, csvs, plots).
    Compare {
        /// Directory of demonstration CSVs (columns: time, then the arm's six joints).
        #[arg(long)]
        demos: PathBuf,
        /// CoSCo-HSOM configuration (XML); default: the built-in configs/nao-gestures.xml.
        #[arg(long)]
        config: Option<PathBuf>,
        /// Output directory (created if missing).
        #[arg(long, default_value = "out-compare")]
        out: PathBuf,
        /// GMM components: a number K >= 1, or `bic` (lowest BIC over 1..=16).
        #[arg(long, default_value = "bic", value_parser = cli::compare::parse_components)]
        components: cosco_hsom::gmr::ComponentChoice,
        /// How CoSCo-HSOM's postures become servo targets: `linear` (the paper) or
        /// `min-jerk[:TOL]` (as for `simulate`).
        #[arg(long, default_value = "linear")]
        transition: String,
        /// MJCF model of the arm.
        #[arg(long)]
        model: Option<PathBuf>,
        /// Resample demonstrations with `time` columns to this rate, Hz (shape-preserving).
        #[arg(long)]
        resample: Option<f64>,
    },
    #[cfg(feature = "sim")]
    /// Run a sweep: every combination of the axes of a TOML spec (docs/SWEEPS.md), one JSON
    /// file per run in DIR/runs, finished runs skipped; `merge` makes the tables and plots.
    #[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
    Sweep {
        #[command(subcommand)]
        action: Option<SweepAction>,
        /// The spec file (TOML).
        #[arg(long, required = true)]
        spec: Option<PathBuf>,
        /// Output directory: DIR/runs/<run-id>.json, then the merged tables and plots.
        #[arg(long, required = true)]
        out: Option<PathBuf>,
        /// Run only the runs whose grid index is I modulo N (default: SLURM_ARRAY_TASK_ID /
        /// SLURM_ARRAY_TASK_COUNT when set, else all).
        #[arg(long, value_name = "I/N")]
        shard: Option<String>,
        /// Worker threads (default: every core).
        #[arg(long)]
        threads: Option<usize>,
        /// Run again the runs whose file records a failure.
        #[arg(long)]
        retry_failed: bool,
    },
}

#[cfg(feature = "sim")]
#[derive(Subcommand)]
enum SweepAction {
    /// Merge the run files of DIR (all shards) into tables.md, tables.csv, wins.csv,
    /// timing.md and plots/*.png there.
    Merge {
        /// The sweep's output directory.
        dir: PathBuf,
    },
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        #[cfg(feature = "ros2")]
        #[cfg(feature = "sim")]
        Command::Demos {
            action: Some(a), ..
        } => cli::export::demos_action(&a)?
            .iter()
            .for_each(|l| outln!("{l}")),
        #[cfg(all(feature = "ros2", not(feature = "sim")))]
        Command::Demos { action } => cli::export::demos_action(&action)?
            .iter()
            .for_each(|l| outln!("{l}")),
        Command::Export(a) => cli::export::export(&a)?.iter().for_each(|l| outln!("{l}")),
        #[cfg(feature = "sim")]
        Command::Demos {
            gesture,
            count,
            seed,
            out,
            noise,
            model,
            ..
        } => {
            let out = out.ok_or_else(|| anyhow::anyhow!("give --out DIR"))?;
            let files = cli::demos(&gesture, count, seed, &out, noise, model.as_deref())?;
            for f in files {
                outln!("{}", f.display());
            }
        }
        Command::Train {
            config,
            demos,
            out,
            state_length_from_data,
            resample,
        } => {
            if let Some(l) = cli::export::resample_line(&demos, resample)? {
                outln!("{l}");
            }
            let model = cli::train_files(
                config.as_deref(),
                &demos,
                &out,
                state_length_from_data,
                resample,
            )?;
            if model.labels().is_empty() {
                out!("{}", model.branches()[0].summary());
            } else {
                outln!(
                    "{} gestures in one hierarchy: {}",
                    model.labels().len(),
                    model.labels().join(", ")
                );
            }
            outln!("saved {}", out.display());
        }
        Command::Reproduce {
            model,
            initial,
            initial_from,
            gesture,
            prefix_from,
            prefix,
            resume_from,
            out,
        } => {
            let (n, label) = match (prefix_from, prefix) {
                (Some(p), Some(k)) => cli::continue_file(&model, &p, k, &out)?,
                _ => cli::reproduce_gesture_file(
                    &model,
                    gesture.as_deref(),
                    initial.as_deref(),
                    initial_from.as_deref(),
                    resume_from.as_deref(),
                    &out,
                )?,
            };
            match label {
                Some(l) => outln!("{n} postures of {l} written to {}", out.display()),
                None => outln!("{n} postures written to {}", out.display()),
            }
        }
        Command::Recognize { model, demos, json } => {
            for line in cli::recognize_lines(&model, &demos, json.as_deref())? {
                outln!("{line}");
            }
        }
        Command::Heldout {
            demos,
            config,
            state_length_from_data,
            resample,
            consensus,
            plan,
            alignment,
            knots,
            no_height_1,
            no_gmr,
            no_in_sample,
            threads,
            json,
            #[cfg(feature = "plot")]
            png,
        } => {
            #[cfg(not(feature = "plot"))]
            let png: Option<PathBuf> = None;
            let job = cli::HeldoutJob {
                demos,
                config,
                state_length_from_data,
                resample,
                consensus,
                plan,
                alignment,
                knots,
                settings: cosco_hsom::offline::LooSettings {
                    height_1: !no_height_1,
                    gmr: !no_gmr,
                    replay: true,
                    in_sample: !no_in_sample,
                    threads: threads.map_or_else(cli::cores, |t| t as usize),
                },
                json,
                png,
            };
            if let Some(l) = cli::export::resample_line(&job.demos, resample)? {
                outln!("{l}\n");
            }
            out!("{}", cli::heldout(&job)?);
        }
        Command::Inspect { model } => {
            let m = cli::load_gesture_model(&model)?;
            outln!("{}", model.display());
            if m.labels().is_empty() {
                out!("{}", m.branches()[0].summary());
            }
            for (l, b) in m.labels().iter().zip(m.branches()) {
                outln!("gesture {l}:");
                out!("{}", b.summary());
            }
        }
        Command::Evaluate {
            reproduction,
            demos,
            json,
            #[cfg(feature = "sim")]
            model,
        } => {
            #[cfg(not(feature = "sim"))]
            let model: Option<PathBuf> = None;
            let (report, unit) = cli::evaluate_files(&reproduction, &demos, model.as_deref())?;
            out!("{}", cli::fidelity_lines(&report, unit));
            if let Some(p) = json {
                let bytes = serde_json::to_vec_pretty(&report)?;
                cosco_hsom::fsutil::write_atomic(&p, &bytes)
                    .with_context(|| format!("writing {}", p.display()))?;
            }
        }
        #[cfg(feature = "sim")]
        Command::Compare {
            demos,
            config,
            out,
            components,
            transition,
            model,
            resample,
        } => {
            if let Some(l) = cli::export::resample_line(std::slice::from_ref(&demos), resample)? {
                outln!("{l}");
            }
            let job = cli::compare::CompareJob {
                resample,
                demos,
                config,
                out,
                components,
                model,
                transition: cosco_hsom::experiment::Transition::parse(&transition)?,
            };
            let report = cli::compare::compare(&job)?;
            for line in cli::compare::summary_lines(&report) {
                outln!("{line}");
            }
            outln!("report: {}", job.out.join("report.md").display());
        }
        #[cfg(feature = "sim")]
        Command::Sweep {
            action,
            spec,
            out,
            shard,
            threads,
            retry_failed,
        } => {
            let lines = match (action, spec, out) {
                (Some(SweepAction::Merge { dir }), _, _) => cli::sweep::merge_lines(&dir)?,
                (None, Some(spec), Some(out)) => {
                    cli::sweep::sweep(&spec, &out, shard.as_deref(), threads, retry_failed)?
                }
                _ => anyhow::bail!("give --spec FILE and --out DIR, or `merge DIR`"),
            };
            for line in lines {
                outln!("{line}");
            }
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("Error: {}", cli::error_line(&e));
            ExitCode::FAILURE
        }
    }
}
