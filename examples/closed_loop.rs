//! A hand grabs the arm during execution, held out (`experiment::closed_loop::closed_loop_folds`):
//! for every leave-one-out fold each method plans from the held-out demonstration's first
//! posture, its plan is executed on the simulated arm, and at `--at` of the held-out
//! demonstration's duration a hand holds the arm still for `--grab` ticks (40 Hz) while the
//! servo targets go on. Then either the plan goes on by its clock (no re-plan), or the method
//! is given what the encoders read of its own execution and the grab and continues from there
//! (the closed loop): the hierarchy with `Hsom::resume` (the reading aligned with its own
//! plan, the plan's events executed so far pushed up the lists, the levels plan the rest) and,
//! beside it, with `Hsom::continue_events` (the reading encoded again by the bottom, as a new
//! demonstration's prefix is), the nearest sequence with `Hsom::follow_nearest_from`
//! (re-aligned by open-end DTW); as the re-plan's control, each also re-plans at the same
//! moment from the reading of its undisturbed execution ("read back, no grab": does a re-plan
//! alone keep the gesture?). GMM/GMR is time-driven: by its clock only. Every motion, the
//! grab included, is scored against the held-out demonstration alone. Markdown on stdout:
//! means over the folds per (gesture, seed), medians per gesture and over all runs.
//!
//! ```sh
//! cargo run --release --example closed_loop -- --seeds 1-5 --at 0.5 --grab 40
//! cargo run --release --example closed_loop -- --seeds 12 --gestures wave --png docs/figures
//! ```

#[path = "common/closed_loop.rs"]
mod closed_loop;
mod common;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

use closed_loop::{closed_loop_folds, closed_loop_png, ClosedLoop, ClosedLoopFold, ClosedLoopGrab};
use cosco_hsom::eval::FoldScores;
use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::{synthetic_demonstrations, Transition};
use cosco_hsom::stats::median;
use cosco_hsom::table::Table;

/// A grab during execution: the hierarchy's and the nearest sequence's closed loops, and
/// every method by its clock.
#[derive(Parser, Debug)]
#[command(name = "closed_loop")]
struct Args {
    #[command(flatten)]
    sets: common::Sets,
    /// When the hand takes hold: this share of the held-out demonstration's duration,
    /// strictly between 0 and 1.
    #[arg(long, default_value_t = 0.5)]
    at: f64,
    /// How long it holds the arm still, ticks of 40 Hz (at least 1).
    #[arg(long, default_value_t = 40)]
    grab: usize,
    /// Gaussian noise on what a method reads of the encoders when it continues, rad (the
    /// scored recording stays exact); drawn from the demonstrations' seed.
    #[arg(long, default_value_t = 0.0)]
    reading_noise: f64,
    /// CoSCo-HSOM configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    config: PathBuf,
    /// Also draw each (gesture, seed): `<DIR>/closed-loop-<gesture>-seed-<S>.png`, one panel
    /// per fold (LElbowRoll against time, the grab shaded).
    #[arg(long, value_name = "DIR")]
    png: Option<PathBuf>,
}

/// The columns, in order.
const COLUMNS: [&str; 11] = [
    "hierarchy undisturbed",
    "hierarchy by its clock",
    "hierarchy read back, no grab",
    "hierarchy resumed",
    "hierarchy re-encoded read back, no grab",
    "hierarchy re-encoded after the grab",
    "nearest sequence undisturbed",
    "nearest sequence read back, no grab",
    "nearest sequence re-aligned",
    "GMM/GMR undisturbed",
    "GMM/GMR by its clock",
];

/// Means over the folds: joint DTW, duration ratio, folds with the held-out swings.
#[derive(Clone, Copy)]
struct Mean {
    dtw: f64,
    duration: f64,
    exact: usize,
    folds: usize,
}

fn mean<'a>(folds: impl Iterator<Item = &'a FoldScores>) -> Mean {
    let folds: Vec<&FoldScores> = folds.collect();
    let n = folds.len().max(1) as f64;
    Mean {
        dtw: folds
            .iter()
            .map(|f| f.fidelity.joint_dtw_rad_per_step.mean)
            .sum::<f64>()
            / n,
        duration: folds
            .iter()
            .map(|f| f.fidelity.duration_ratio.mean)
            .sum::<f64>()
            / n,
        exact: folds
            .iter()
            .filter(|f| f.swings.as_ref().is_some_and(|w| w.reproduction == w.demo))
            .count(),
        folds: folds.len(),
    }
}

/// The columns of one (gesture, seed).
fn row(folds: &ClosedLoop) -> [Mean; 11] {
    let gmr: Vec<&ClosedLoopFold> = folds.gmr.iter().filter_map(|r| r.as_ref().ok()).collect();
    let replanned = |f: &[ClosedLoopFold]| mean(f.iter().filter_map(|f| f.replanned.as_ref()));
    let read_back = |f: &[ClosedLoopFold]| mean(f.iter().filter_map(|f| f.read_back.as_ref()));
    [
        mean(folds.hsom.iter().map(|f| &f.undisturbed)),
        mean(folds.hsom.iter().map(|f| &f.by_clock)),
        read_back(&folds.hsom),
        replanned(&folds.hsom),
        read_back(&folds.hsom_reencoded),
        replanned(&folds.hsom_reencoded),
        mean(folds.sequence.iter().map(|f| &f.undisturbed)),
        read_back(&folds.sequence),
        replanned(&folds.sequence),
        mean(gmr.iter().map(|f| &f.undisturbed)),
        mean(gmr.iter().map(|f| &f.by_clock)),
    ]
}

fn print_row(gesture: &str, seed: &str, r: &[Mean; 11]) {
    let cells: Vec<String> = r
        .iter()
        .map(|m| format!("{:.4} ({:.2}x, {}/{})", m.dtw, m.duration, m.exact, m.folds))
        .collect();
    print!(
        "{}",
        Table::line([gesture, seed].map(String::from).into_iter().chain(cells))
    );
}

fn print_median(gesture: &str, rows: &[[Mean; 11]]) {
    let cells: Vec<String> = (0..COLUMNS.len())
        .map(|c| {
            let med =
                |f: fn(&Mean) -> f64| median(rows.iter().map(|r| f(&r[c]))).unwrap_or(f64::NAN);
            let exact: usize = rows.iter().map(|r| r[c].exact).sum();
            let folds: usize = rows.iter().map(|r| r[c].folds).sum();
            format!(
                "{:.4} ({:.2}x, {exact}/{folds})",
                med(|m| m.dtw),
                med(|m| m.duration)
            )
        })
        .collect();
    let head = [format!("**{gesture}**"), "median".into()];
    print!("{}", Table::line(head.into_iter().chain(cells)));
}

fn run(a: Args) -> Result<()> {
    a.sets.check_leave_one_out()?;
    let grab = |seed: u64| ClosedLoopGrab {
        at: a.at,
        ticks: a.grab,
        reading_noise: a.reading_noise,
        seed,
    };
    grab(0).check()?;
    let (config, arm) = common::config_and_arm(&a.config)?;
    let settings = a.sets.demo_settings();
    println!(
        "A hand holds the arm still for {} ticks at {:.0} % of the held-out demonstration's duration; continuations read the encoders with noise {} rad ({}, seeds {}, {} demonstrations, noise {} rad). Each cell: joint DTW against the held-out demonstration (duration ratio, folds whose LElbowRoll swings are the demonstration's), means over the folds.\n",
        a.grab,
        a.at * 100.0,
        a.reading_noise,
        a.config.display(),
        a.sets.seeds,
        a.sets.count,
        a.sets.noise
    );
    print!(
        "{}",
        Table::new(["gesture", "seed"].into_iter().chain(COLUMNS))
    );
    let mut all = Vec::new();
    for g in parse_gestures(&a.sets.gestures)? {
        let mut rows = Vec::new();
        for seed in parse_seeds(&a.sets.seeds)? {
            let demos = synthetic_demonstrations(&arm, &g, a.sets.count, seed, &settings, |_| {})?;
            let folds = closed_loop_folds(&arm, &config, &demos, grab(seed), Transition::Linear)
                .with_context(|| format!("{} seed {seed}", g.name))?;
            for e in folds.gmr.iter().filter_map(|r| r.as_ref().err()) {
                eprintln!("{} seed {seed}: {e}", g.name);
            }
            if let Some(dir) = &a.png {
                std::fs::create_dir_all(dir)
                    .with_context(|| format!("creating {}", dir.display()))?;
                let path = dir.join(format!("closed-loop-{}-seed-{seed}.png", g.name));
                let title = format!(
                    "{} seed {seed}: a hand holds the arm for {} ticks at {:.0} % of the held-out demonstration",
                    g.name,
                    a.grab,
                    a.at * 100.0
                );
                closed_loop_png(&path, &title, &demos, &folds)
                    .with_context(|| format!("drawing {}", path.display()))?;
                eprintln!("wrote {}", path.display());
            }
            let r = row(&folds);
            print_row(g.name, &seed.to_string(), &r);
            rows.push(r);
        }
        print_median(g.name, &rows);
        all.extend(rows);
    }
    print_median("all", &all);
    let count = |f: fn(&[Mean; 11]) -> bool| all.iter().filter(|r| f(r)).count();
    println!(
        "\nOf {} runs: the hierarchy resumed is closer than the nearest sequence re-aligned in {}, than its own plan by the clock in {}, than re-encoded after the grab in {}; GMM/GMR by its clock is closer than the hierarchy resumed in {}.",
        all.len(),
        count(|r| r[3].dtw < r[8].dtw),
        count(|r| r[3].dtw < r[1].dtw),
        count(|r| r[3].dtw < r[5].dtw),
        count(|r| r[10].dtw < r[3].dtw),
    );
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
