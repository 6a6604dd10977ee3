//! `cosco sweep` and `cosco sweep merge`: the spec, shard and progress bar around the
//! library's `sweep` room.

use std::io::IsTerminal as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use cosco_hsom::sweep::{merge, run_sweep, MergeSummary, Progress, Shard, SweepOptions, SweepSpec};

/// `cosco sweep`: a sweep, or `merge`.
#[derive(Args)]
pub struct SweepArgs {
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
}

/// What `cosco sweep` does besides running a sweep.
#[derive(Subcommand)]
pub enum SweepAction {
    /// Merge the run files of DIR (all shards) into tables.md, tables.csv, wins.csv,
    /// timing.md and plots/*.png there.
    Merge {
        /// The sweep's output directory.
        dir: PathBuf,
    },
}

/// `cosco sweep`: run the sweep, or merge one; the lines to print.
pub fn run(a: SweepArgs) -> Result<Vec<String>> {
    match (a.action, a.spec, a.out) {
        (Some(SweepAction::Merge { dir }), _, _) => merge_lines(&dir),
        (None, Some(spec), Some(out)) => {
            sweep(&spec, &out, a.shard.as_deref(), a.threads, a.retry_failed)
        }
        _ => anyhow::bail!("give --spec FILE and --out DIR, or `merge DIR`"),
    }
}

/// The shard: `--shard I/N`, else SLURM's job-array variables, else the whole grid.
pub fn shard(flag: Option<&str>) -> Result<Shard> {
    Ok(match flag {
        Some(text) => Shard::parse(text)?,
        None => Shard::from_slurm(|k| std::env::var(k).ok())?.unwrap_or(Shard::ALL),
    })
}

/// `cosco sweep --spec FILE --out DIR`: run the shard's runs not yet recorded, then merge when
/// the sweep is not sharded. Returns lines to print.
pub fn sweep(
    spec: &Path,
    out: &Path,
    shard_flag: Option<&str>,
    threads: Option<usize>,
    retry_failed: bool,
) -> Result<Vec<String>> {
    let spec = SweepSpec::load(spec)?;
    let options = SweepOptions {
        shard: shard(shard_flag)?,
        threads,
        retry_failed,
    };
    let pb = ProgressBar::hidden();
    let terminal = std::io::stderr().is_terminal();
    let summary = run_sweep(&spec, out, &options, &|p| match p {
        Progress::Start {
            to_run,
            skipped,
            threads,
        } => {
            eprintln!(
                "sweep {}: shard {}, {to_run} runs to do, {skipped} already recorded, {threads} threads",
                spec.settings.name,
                options.shard.label()
            );
            if terminal {
                pb.set_length(to_run as u64);
                pb.set_style(
                    ProgressStyle::with_template(
                        "{msg:>10} [{bar:40.cyan/blue}] {pos}/{len} runs, {elapsed_precise} elapsed, ETA {eta_precise}",
                    )
                    .expect("static template")
                    .progress_chars("=> "),
                );
                pb.set_message("sweep");
                pb.set_draw_target(indicatif::ProgressDrawTarget::stderr());
            }
        }
        Progress::Done(r) => {
            let status = if r.failed() { "FAILED" } else { "ok" };
            if terminal {
                if r.failed() {
                    pb.println(format!("{} failed (recorded in its file)", r.run_id));
                }
                pb.inc(1);
            } else {
                // logs of cluster jobs: one line per run
                eprintln!("{} {status} in {:.1} s", r.run_id, r.wall_s);
            }
        }
    })?;
    pb.finish_and_clear();
    let mut lines = vec![format!(
        "shard {}: {} runs of {} in the grid; ran {} ({} failed), skipped {} already recorded; \
         wall {:.1} s, sum of the runs' wall times {:.1} s ({} threads)",
        options.shard.label(),
        summary.in_shard,
        summary.grid,
        summary.ran,
        summary.failed,
        summary.skipped,
        summary.wall_s,
        summary.runs_s,
        summary.threads
    )];
    if options.shard.count == 1 {
        lines.extend(merge_lines(out)?);
    } else {
        lines.push(format!(
            "when every shard is done: cosco sweep merge {}",
            out.display()
        ));
    }
    Ok(lines)
}

/// `cosco sweep merge DIR`: lines to print.
pub fn merge_lines(dir: &Path) -> Result<Vec<String>> {
    let MergeSummary {
        grid,
        recorded,
        failed,
        missing,
        files,
    } = merge(dir).with_context(|| format!("merging the sweep in {}", dir.display()))?;
    let mut lines = vec![format!(
        "merged {recorded} of {grid} runs ({} failed, {} missing)",
        failed.len(),
        missing.len()
    )];
    for f in &failed {
        lines.push(format!("failed: {f}"));
    }
    for f in files {
        lines.push(format!("wrote {}", f.display()));
    }
    Ok(lines)
}
