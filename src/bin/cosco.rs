//! `cosco`: the steps of the main job one at a time, for scripting. Without the feature `sim`
//! only `train`, `reproduce`, `recognize`, `recognition`, `inspect`, `evaluate` and `heldout`
//! (which need no simulator; `heldout --png` needs the feature `plot`).

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;
use cosco_hsom::commands;

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

#[cfg(feature = "sim")]
use cli::cosco_args::SweepAction;
use cli::cosco_args::{Cli, Command};

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        #[cfg(all(feature = "ros2", feature = "sim"))]
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
            let bars = cli::StageBars::default();
            let on_progress = |stage: &str, done, total| bars.update(stage, done, total);
            let files = cosco_hsom::experiment::job::demos(
                &gesture,
                count,
                seed,
                &out,
                noise,
                model.as_deref(),
                &on_progress,
            )?;
            bars.finish();
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
            resample_line(&demos, resample)?;
            let bars = cli::StageBars::default();
            let on_step = |done, total| bars.update("training", done, total);
            let model = commands::train_files(
                config.as_deref(),
                &demos,
                &out,
                state_length_from_data,
                resample,
                Some(&on_step),
            )?;
            bars.finish();
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
                (Some(p), Some(k)) => commands::continue_file(&model, &p, k, &out)?,
                _ => commands::reproduce_gesture_file(
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
            for line in commands::recognize_lines(&model, &demos, json.as_deref())? {
                outln!("{line}");
            }
        }
        Command::Recognition {
            taught,
            untaught,
            data,
            no_control,
            threads,
            json,
        } => {
            use cosco_hsom::eval::recognition::{recognition, RecognitionJob, RecognitionSettings};
            let job = RecognitionJob {
                taught,
                untaught,
                config: data.config,
                state_length_from_data: data.state_length_from_data,
                resample: data.resample,
                settings: RecognitionSettings {
                    control: !no_control,
                    threads: threads.map_or_else(cli::cores, |t| t as usize),
                },
                json,
            };
            let pb = cli::progress(0, "models");
            let on_model = |done: usize, total: usize| {
                pb.set_length(total as u64);
                pb.set_position(done as u64);
            };
            let tables = recognition(&job, Some(&on_model))?;
            pb.finish_and_clear();
            out!("{tables}");
        }
        Command::Heldout {
            demos,
            data,
            no_height_1,
            no_gmr,
            no_promp,
            no_in_sample,
            threads,
            json,
            #[cfg(feature = "plot")]
            png,
        } => {
            #[cfg(not(feature = "plot"))]
            let png: Option<std::path::PathBuf> = None;
            if let Some(l) = cosco_hsom::resample::report_line(&demos, data.resample)? {
                outln!("{l}\n");
            }
            let job = cosco_hsom::eval::HeldoutJob {
                demos,
                config: data.config,
                state_length_from_data: data.state_length_from_data,
                resample: data.resample,
                settings: cosco_hsom::eval::LooSettings {
                    height_1: !no_height_1,
                    gmr: !no_gmr,
                    promp: !no_promp,
                    replay: true,
                    in_sample: !no_in_sample,
                    threads: threads.map_or_else(cli::cores, |t| t as usize),
                },
                json,
                png,
            };
            let pb = cli::progress(0, "folds");
            let on_fold = |done: usize, total: usize| {
                pb.set_length(total as u64);
                pb.set_position(done as u64);
            };
            let tables = cosco_hsom::eval::heldout(&job, Some(&on_fold))?;
            pb.finish_and_clear();
            out!("{tables}");
        }
        Command::Inspect { model } => {
            let m = commands::load_gesture_model(&model)?;
            outln!("{}", model.display());
            if m.labels().is_empty() {
                out!("{}", m.branches()[0].summary());
                out!("{}", commands::file_parts_lines(&m.branches()[0]));
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
            let model: Option<std::path::PathBuf> = None;
            let e = commands::evaluate_files(&reproduction, &demos, model.as_deref())?;
            out!("{}", commands::fidelity_lines(&e.fidelity, e.unit));
            out!("{}", commands::start_end_lines(&e.start_end, e.unit));
            if let Some(p) = json {
                let bytes = serde_json::to_vec_pretty(&e)?;
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
            resample_line(std::slice::from_ref(&demos), resample)?;
            let job = cli::compare::CompareJob {
                resample,
                demos,
                config,
                out,
                components,
                model,
                transition: cosco_hsom::experiment::Transition::parse(&transition)?,
            };
            let bars = cli::StageBars::default();
            let on_progress = |stage: &str, done, total| bars.update(stage, done, total);
            let report = cli::compare::compare(&job, &on_progress)?;
            bars.finish();
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

/// Print the `--resample HZ` report line of `paths` (nothing without it).
fn resample_line(paths: &[std::path::PathBuf], hz: Option<f64>) -> Result<()> {
    if let Some(l) = cosco_hsom::resample::report_line(paths, hz)? {
        outln!("{l}");
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
