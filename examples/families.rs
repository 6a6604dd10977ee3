//! Generality, held out first: the synthetic families of `tests/algorithm/hsom_measure.rs`
//! (figure eight, open stroke, handwriting-like 2-D, six joints), leave-one-out. For each
//! demonstration: train on the others, reproduce from its first posture, score against it
//! (held out) and against the training demonstrations (in-sample, the figure
//! `tests/algorithm/hsom_measure.rs` prints). Side by side: the recommended configuration
//! (configs/nao-gestures.xml, stateLength adapted), the paper's Table I (literal,
//! configs/table1.xml), a replay of the
//! training demonstration whose first posture is nearest (no model), the nearest-sequence
//! baseline (the recommended model's bottom code following that demonstration's bottom
//! events, no level above: `Hsom::follow_nearest`), and the recommended
//! configuration's encoding ceiling (each training demonstration through the bottom level's
//! own code and back, `Hsom::reencode`). Relative DTW: mean Euclidean distance along the DTW
//! path / the diagonal of the family's bounding box.
//!
//! ```sh
//! cargo run --release --example families -- --seeds 1-6
//! ```

mod common;

#[path = "../tests/hsom_common/mod.rs"]
mod hsom_common;

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

use cosco_hsom::config::{HsomConfig, HsomParams};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::eval::{loo_map, Pool};
use cosco_hsom::experiment::demonstrate::parse_seeds;
use cosco_hsom::stats::median;
use cosco_hsom::table::Table;
use hsom_common::{diagonal, dtw, figure_eight, handwriting, joints6, recommended_for, stroke};

/// Leave-one-out on the synthetic families.
#[derive(Parser, Debug)]
#[command(name = "families")]
struct Args {
    /// CoSCo-HSOM seeds (the families' data are fixed).
    #[arg(long, default_value = "1-6")]
    seeds: String,
    /// Training steps of the recommended configuration (default: the file's).
    #[arg(long)]
    training_steps: Option<usize>,
}

/// `work(train, held)` on every leave-one-out fold of `demos` ([`loo_map`], one thread), in
/// order; the first error.
fn folds<T: Send>(
    demos: &[Demonstration],
    work: impl Fn(&[Demonstration], &Demonstration) -> Result<T> + Sync,
) -> Result<Vec<T>> {
    let pool = Pool::new(1).map_err(anyhow::Error::msg)?;
    let folds = loo_map(&[demos], false, &pool, None, |_, split| {
        let (train, held) = split.of(demos);
        work(&train, &held[0])
    });
    folds
        .into_iter()
        .flat_map(|(held_out, _)| held_out)
        .collect()
}

/// Held-out and in-sample relative DTW of one configuration, and held out the same models'
/// nearest-sequence baseline; means over the folds.
fn loo(cfg: &HsomConfig, demos: &[Demonstration], diag: f64) -> Result<(f64, f64, f64)> {
    let scores = folds(demos, |train, held| {
        let model = cfg.fit(train)?;
        let rep = model.reproduce(&held.rows[0])?;
        let follow = model.follow_nearest(train, &held.rows[0])?;
        let ins = train
            .iter()
            .map(|d| dtw(&rep.postures, &d.rows))
            .sum::<f64>()
            / train.len() as f64
            / diag;
        let held_out = dtw(&rep.postures, &held.rows) / diag;
        Ok((held_out, ins, dtw(&follow.postures, &held.rows) / diag))
    })?;
    let (mut held, mut ins, mut seq) = (0.0, 0.0, 0.0);
    for (h, i, s) in scores {
        (held, ins, seq) = (held + h, ins + i, seq + s);
    }
    let n = demos.len() as f64;
    Ok((held / n, ins / n, seq / n))
}

/// Held-out score of replaying the training demonstration whose first posture is nearest.
fn replay(demos: &[Demonstration], diag: f64) -> Result<f64> {
    let scores = folds(demos, |train, held| {
        let start = |x: &Demonstration| cosco_hsom::dtw::euclidean(&x.rows[0], &held.rows[0]);
        let near = (train.iter())
            .min_by(|a, b| start(a).total_cmp(&start(b)))
            .context("at least two demonstrations")?;
        Ok(dtw(&near.rows, &held.rows) / diag)
    })?;
    Ok(scores.into_iter().fold(0.0, |sum, s| sum + s) / demos.len() as f64)
}

/// Mean relative DTW of each demonstration re-encoded by a model trained on all of them.
fn ceiling(cfg: &HsomConfig, demos: &[Demonstration], diag: f64) -> Result<f64> {
    let model = cfg.fit(demos)?;
    let mut sum = 0.0;
    for d in demos {
        sum += dtw(&model.reencode(d)?.postures, &d.rows) / diag;
    }
    Ok(sum / demos.len() as f64)
}

fn adapted(mut p: HsomParams, dims: usize, seed: u64) -> Result<HsomConfig> {
    p.state_length = dims;
    p.action_length = dims;
    p.seed = seed;
    Ok(p.check("adapted")?)
}

fn run(a: Args) -> Result<()> {
    let seeds = parse_seeds(&a.seeds)?;
    println!("Leave-one-out relative DTW (held out | in-sample), CoSCo-HSOM seeds {}; medians over the seeds in the last rows.\n", a.seeds);
    let header = [
        "family",
        "seed",
        "recommended held out",
        "Table I held out",
        "replay held out",
        "nearest-sequence held out",
        "recommended in-sample",
        "encoding ceiling",
    ];
    print!("{}", Table::new(header));
    let families = [
        ("eight", figure_eight(6, 7)),
        ("stroke", stroke(6, 8)),
        ("handwriting", handwriting(8, 9)),
        ("joints6", joints6(6, 9)),
    ];
    for (name, demos) in &families {
        let dims = demos[0].rows[0].len();
        let diag = diagonal(demos);
        let rp = replay(demos, diag)?;
        let mut rows: Vec<[f64; 6]> = Vec::new();
        for &seed in &seeds {
            let mut rec = recommended_for(dims).into_params();
            if let Some(s) = a.training_steps {
                rec.training_steps = s;
            }
            let rec = adapted(rec, dims, seed)?;
            let (rh, ri, rs) = loo(&rec, demos, diag)?;
            let (th, _, _) = loo(&adapted(HsomParams::table1(), dims, seed)?, demos, diag)?;
            let c = ceiling(&rec, demos, diag)?;
            let r = [rh, th, rp, rs, ri, c];
            let cells = r.map(|v| format!("{v:.4}"));
            let head = [name.to_string(), seed.to_string()];
            print!("{}", Table::line(head.into_iter().chain(cells)));
            rows.push(r);
        }
        let m: Vec<String> = (0..6)
            .map(|k| {
                format!(
                    "{:.4}",
                    median(rows.iter().map(|r| r[k])).unwrap_or(f64::NAN)
                )
            })
            .collect();
        let head = [format!("**{name}**"), "median".into()];
        print!("{}", Table::line(head.into_iter().chain(m)));
    }
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
