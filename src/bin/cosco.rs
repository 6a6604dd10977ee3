//! `cosco`: the steps of the main job one at a time, for scripting: each subcommand parsed
//! and handed to the library in one call ([`cosco_hsom::app`], or the held-out studies of
//! [`cosco_hsom::eval`] and the simulator's jobs). Without the feature `sim` only `train`,
//! `reproduce`, `recognize`, `inspect`, `evaluate` and `heldout` (which need no simulator;
//! `heldout --png` needs the feature `plot`).

use std::process::ExitCode;

use anyhow::Result;
use clap::Parser;
use cosco_hsom::app;

#[macro_use]
mod cli;

use cli::cosco_args::{Cli, Command, RecognitionArgs, StudyArgs};

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
        Command::Export(a) => cli::export::export(a)?.iter().for_each(|l| outln!("{l}")),
        #[cfg(feature = "sim")]
        Command::Demos {
            robot,
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
            let request = cosco_hsom::experiment::job::DemosRequest {
                robot,
                gesture: &gesture,
                count,
                seed,
                noise,
                model: model.as_deref(),
            };
            let files = cosco_hsom::experiment::job::demos(&request, &out, &on_progress)?;
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
            from,
        } => {
            resample_line(&demos, resample)?;
            let bars = cli::StageBars::default();
            let on_step = |done, total| bars.update("training", done, total);
            let model = match &from {
                Some(from) => app::update_files(
                    from,
                    config.as_deref(),
                    &demos,
                    &out,
                    resample,
                    Some(&on_step),
                )?,
                None => app::train_files(
                    config.as_deref(),
                    &demos,
                    &out,
                    state_length_from_data,
                    resample,
                    Some(&on_step),
                )?,
            };
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
        Command::Reproduce(r) => outln!("{}", app::reproduce_file(&r.into())?),
        Command::Recognize {
            model,
            stream: true,
            ..
        } => {
            app::recognize_stream(&model, std::io::stdin().lock(), &mut |line| {
                use std::io::Write as _;
                let mut out = std::io::stdout().lock();
                let _ = writeln!(out, "{line}");
                let _ = out.flush();
            })?;
        }
        Command::Recognize {
            model,
            demos: Some(demos),
            json,
            ..
        } => {
            for line in app::recognize_files(&model, &demos, json.as_deref())? {
                outln!("{line}");
            }
        }
        Command::Recognize { demos: None, .. } => {
            anyhow::bail!("give --demos PATH, or --stream to read CSV rows from standard input")
        }
        Command::Recognition { study, common } => recognition(study, common)?,
        Command::Heldout {
            study: Some(study),
            common,
            recognition: true,
            ..
        } => recognition(study, common)?,
        Command::Heldout {
            demos,
            common:
                StudyArgs {
                    data,
                    threads,
                    json,
                },
            no_height_1,
            no_gmr,
            no_promp,
            no_dmp,
            no_dba,
            condition,
            far,
            sittings,
            no_in_sample,
            disturb,
            goal_moves,
            #[cfg(feature = "plot")]
            png,
            ..
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
                    dmp: !no_dmp,
                    dba: !no_dba,
                    replay: true,
                    in_sample: !no_in_sample,
                    conditioning: condition.map(Into::into).unwrap_or_default(),
                    far: None,
                    sittings,
                    threads: threads.map_or_else(cli::cores, |t| t as usize),
                    keep_learned: false,
                },
                json,
                png,
                far,
                disturb: disturb.into_iter().chain(goal_moves).collect(),
            };
            let (pb, on_fold) = cli::counter("folds");
            // on the upper body's joints, the hierarchy's reproductions executed for contacts
            #[cfg(feature = "sim")]
            let threads = job.settings.threads;
            #[cfg(feature = "sim")]
            let contacts = move |study: &[_]| {
                cosco_hsom::experiment::upper_body::contacts_section(study, threads)
            };
            #[cfg(feature = "sim")]
            let extra: Option<cosco_hsom::eval::Extra> = Some(&contacts);
            #[cfg(not(feature = "sim"))]
            let extra = None;
            let tables = cosco_hsom::eval::heldout_with(&job, Some(&on_fold), extra)?;
            pb.finish_and_clear();
            out!("{tables}");
        }
        Command::Inspect { model } => out!("{}", app::inspect(&model)?),
        Command::Evaluate {
            reproduction,
            demos,
            json,
            #[cfg(feature = "sim")]
            model,
        } => {
            // wrist paths with the simulated arm, loaded when the columns are its joints
            #[cfg(feature = "sim")]
            let arm = |d: &[_], rows: &[_], params: &_| -> Result<_, app::evaluate::BoxError> {
                let arm = cosco_hsom::experiment::load_arm(model.as_deref())?;
                Ok(cosco_hsom::sim::evaluate(Some(&arm), d, rows, params)?)
            };
            #[cfg(feature = "sim")]
            let arm: Option<app::evaluate::ArmScorer> = Some(&arm);
            #[cfg(not(feature = "sim"))]
            let arm = None;
            out!(
                "{}",
                app::evaluate_files(&reproduction, &demos, json.as_deref(), arm)?.lines()
            );
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
            let job = cosco_hsom::experiment::compare::CompareJob {
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
            let report = cosco_hsom::experiment::compare::compare(&job, &on_progress)?;
            bars.finish();
            for line in cosco_hsom::experiment::compare::summary_lines(&report) {
                outln!("{line}");
            }
            outln!("report: {}", job.out.join("report.md").display());
        }
        #[cfg(feature = "sim")]
        Command::Sweep(a) => cli::sweep::run(a)?.iter().for_each(|l| outln!("{l}")),
    }
    Ok(())
}

/// `cosco heldout --recognition` (and its hidden alias `cosco recognition`, for scripts).
fn recognition(study: RecognitionArgs, common: StudyArgs) -> Result<()> {
    use cosco_hsom::eval::recognition::{recognition, RecognitionJob, RecognitionSettings};
    let job = RecognitionJob {
        taught: study.taught,
        untaught: study.untaught,
        config: common.data.config,
        state_length_from_data: common.data.state_length_from_data,
        resample: common.data.resample,
        settings: RecognitionSettings {
            control: !study.no_control,
            one_at_a_time: study.one_at_a_time,
            threads: common.threads.map_or_else(cli::cores, |t| t as usize),
            stream: study.stream,
        },
        json: common.json,
    };
    let (pb, on_model) = cli::counter("models");
    let tables = recognition(&job, Some(&on_model))?;
    pb.finish_and_clear();
    out!("{tables}");
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
    cli::exit(run(Cli::parse()))
}
