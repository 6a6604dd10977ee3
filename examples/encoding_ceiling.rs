//! The ceiling of the bottom level's code: each demonstration re-encoded through the
//! bottom level's own events and back to postures ([`Hsom::reencode`]), with no upper level
//! involved. What is lost here the hierarchy cannot reproduce. For each (gesture, seed):
//! a model trained on all demonstrations, then per demonstration the joint DTW between
//! the re-encoded and the original trajectory, the large swings of `LElbowRoll` and the
//! ratio of its range (re-encoded / original). With `--shared`, each gesture's ceiling
//! through the bottom level it shares with the other gestures given (one hierarchy, a branch
//! per gesture) beside the same gesture learned alone.
//!
//! ```sh
//! cargo run --release --example encoding_ceiling -- --gestures wave --seeds 11-15
//! cargo run --release --example encoding_ceiling -- --shared --seeds 11-15 --count 3
//! ```
//!
//! [`Hsom::reencode`]: cosco_hsom::hsom::Hsom::reencode

mod common;

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

use cosco_hsom::config::{load_config, HsomConfig};
use cosco_hsom::demos::Demonstration;
use cosco_hsom::dtw::{dtw_distance, Band};
use cosco_hsom::eval::SWING_MIN_AMPLITUDE_RAD;
use cosco_hsom::experiment::demonstrate::{parse_gestures, parse_seeds};
use cosco_hsom::experiment::demonstrate::{synthetic_demonstrations, DemoSettings};
use cosco_hsom::hsom::Hsom;
use cosco_hsom::metrics::column_swings;
use cosco_hsom::sim::NaoArm;
use cosco_hsom::sim::SWING_JOINT;
use cosco_hsom::stats::median;
use cosco_hsom::table::Table;

/// Re-encode demonstrations through the bottom level and score what survives.
#[derive(Parser, Debug)]
#[command(name = "encoding_ceiling")]
struct Args {
    #[command(flatten)]
    sets: common::Sets,
    /// CoSCo-HSOM configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    config: PathBuf,
    /// Also the ceiling through a bottom shared by all the gestures given (one
    /// hierarchy, one branch per gesture), beside the gesture learned alone.
    #[arg(long)]
    shared: bool,
}

/// (gesture, joint DTW, swings, demonstration swings, range ratio) of one set.
type Row = (String, f64, f64, f64, f64);

fn range(rows: &[Vec<f64>], c: usize) -> f64 {
    let (lo, hi) = rows
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
            (lo.min(r[c]), hi.max(r[c]))
        });
    hi - lo
}

/// Mean joint DTW of the demonstrations re-encoded by `model`, its events per demonstration
/// and the bottom nodes its demonstrations use.
fn ceiling(model: &Hsom, demos: &[Demonstration]) -> Result<(f64, f64, usize)> {
    let mut dtw = 0.0;
    for d in demos {
        let r = model.reencode(d)?;
        dtw += dtw_distance(&r.postures, &d.rows, Band::None)?.per_step();
    }
    let s = model.summary();
    Ok((
        dtw / demos.len() as f64,
        s.demo_events[1],
        s.levels[0].nodes_used,
    ))
}

/// Each gesture's ceiling through the bottom it shares with the others, beside alone.
fn shared(a: &Args, arm: &NaoArm, config: &HsomConfig, settings: &DemoSettings) -> Result<()> {
    let gestures = parse_gestures(&a.sets.gestures)?;
    println!("Each demonstration through the bottom level's events and back: the gesture learned alone, and through the bottom shared by {} gestures ({}, trained on all {} demonstrations of each): means over the demonstrations.\n", gestures.len(), a.config.display(), a.sets.count);
    let header = [
        "gesture",
        "seed",
        "joint DTW alone",
        "joint DTW shared",
        "shared / alone",
        "events per demo alone",
        "shared",
        "bottom nodes used alone",
        "shared",
    ];
    print!("{}", Table::new(header));
    let mut all: Vec<(String, f64)> = Vec::new();
    for &seed in &parse_seeds(&a.sets.seeds)? {
        let sets: Vec<(String, Vec<Demonstration>)> = gestures
            .iter()
            .map(|g| {
                Ok((
                    g.name.to_string(),
                    synthetic_demonstrations(arm, g, a.sets.count, seed, settings, |_| {})?,
                ))
            })
            .collect::<Result<_>>()?;
        let model = config.fit_model(&sets, cosco_hsom::hsom::Fit::default())?;
        for (label, demos) in &sets {
            let (da, ea, ua) = ceiling(&config.fit(demos)?, demos)?;
            let (ds, es, us) = ceiling(model.branch(Some(label))?, demos)?;
            print!(
                "{}",
                Table::line([
                    label.clone(),
                    seed.to_string(),
                    format!("{da:.4}"),
                    format!("{ds:.4}"),
                    format!("{:.2}", ds / da),
                    format!("{ea:.1}"),
                    format!("{es:.1}"),
                    ua.to_string(),
                    us.to_string(),
                ])
            );
            all.push((label.to_string(), ds / da));
        }
    }
    for g in &gestures {
        let m = median(all.iter().filter(|r| r.0 == g.name).map(|r| r.1)).unwrap_or(f64::NAN);
        let blank = String::new;
        let (name, ratio) = (format!("**{}**", g.name), format!("{m:.2}"));
        let cells = [name, "median".into(), blank(), blank(), ratio];
        print!("{}", Table::line(cells.into_iter().chain(vec![blank(); 4])));
    }
    Ok(())
}

fn run(a: Args) -> Result<()> {
    let arm = NaoArm::load_default()?;
    let config = load_config(&a.config).with_context(|| a.config.display().to_string())?;
    let settings = a.sets.demo_settings();
    if a.shared {
        return shared(&a, &arm, &config, &settings);
    }
    println!("Each demonstration through the bottom level's events and back ({}, trained on all {} demonstrations of the set): means over the demonstrations.\n", a.config.display(), a.sets.count);
    let header = [
        "gesture",
        "seed",
        "joint DTW (rad/step)",
        "LElbowRoll swings (re-encoded / demo)",
        "LElbowRoll range ratio",
        "events per demo",
    ];
    print!("{}", Table::new(header));
    let mut all: Vec<Row> = Vec::new();
    for g in parse_gestures(&a.sets.gestures)? {
        for &seed in &parse_seeds(&a.sets.seeds)? {
            let demos = synthetic_demonstrations(&arm, &g, a.sets.count, seed, &settings, |_| {})?;
            let model = config.fit(&demos)?;
            let (mut dtw, mut sw, mut dsw, mut rr) = (0.0, 0.0, 0.0, 0.0);
            for d in &demos {
                let r = model.reencode(d)?;
                dtw += dtw_distance(&r.postures, &d.rows, Band::None)?.per_step();
                sw += column_swings(&r.postures, SWING_JOINT, SWING_MIN_AMPLITUDE_RAD)? as f64;
                dsw += column_swings(&d.rows, SWING_JOINT, SWING_MIN_AMPLITUDE_RAD)? as f64;
                rr += range(&r.postures, SWING_JOINT) / range(&d.rows, SWING_JOINT).max(1e-12);
            }
            let n = demos.len() as f64;
            let events = model.summary().demo_events[1];
            print!(
                "{}",
                Table::line([
                    g.name.to_string(),
                    seed.to_string(),
                    format!("{:.4}", dtw / n),
                    format!("{:.1} / {:.1}", sw / n, dsw / n),
                    format!("{:.2}", rr / n),
                    format!("{events:.1}"),
                ])
            );
            all.push((g.name.to_string(), dtw / n, sw / n, dsw / n, rr / n));
        }
    }
    let names: Vec<String> = {
        let mut v: Vec<String> = all.iter().map(|r| r.0.clone()).collect();
        v.dedup();
        v
    };
    for name in names {
        let rows: Vec<_> = all.iter().filter(|r| r.0 == name).collect();
        let m = |f: &dyn Fn(&Row) -> f64| median(rows.iter().map(|r| f(r))).unwrap_or(f64::NAN);
        print!(
            "{}",
            Table::line([
                format!("**{name}**"),
                "median".into(),
                format!("{:.4}", m(&|r| r.1)),
                format!("{:.1} / {:.1}", m(&|r| r.2), m(&|r| r.3)),
                format!("{:.2}", m(&|r| r.4)),
                String::new(),
            ])
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    common::exit(run(Args::parse()))
}
