//! Recognition in the loop, held out on the Nao's gestures (docs/ALGORITHM.md, section 4,
//! item 7): per seed, every gesture's demonstrations recorded in the simulator, the model of
//! all of them taught the first `--train` of each and the rest streamed one sample at a
//! time into its recogniser; then each gesture left out in turn (the model taught the
//! others) and its demonstrations streamed as untaught. Beside the recogniser, the negative
//! control that commits at the first sample. Markdown on stdout, every stream with
//! `--json FILE`.
//!
//! ```sh
//! cargo run --release --example stream_heldout -- --seeds 41-45
//! ```

mod common;

use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::Parser;

use cosco_hsom::demos::Demonstration;
use cosco_hsom::eval::recognition::stream::{
    stream, Policy, StreamSummary, Streamed, MARKDOWN_HEADER,
};
use cosco_hsom::experiment::demonstrate::{
    parse_gestures, parse_seeds, synthetic_demonstrations, DemoSettings,
};
use cosco_hsom::hsom::GestureModel;

/// Recognition in the loop, held out.
#[derive(Parser, Debug)]
#[command(name = "stream_heldout")]
struct Args {
    #[command(flatten)]
    sets: common::HeldOutSets,
}

/// Stream every demonstration of `tests` (`(expected, demonstration)`) into `model`.
fn streams(
    model: &GestureModel,
    tests: &[(Option<String>, &Demonstration)],
    policy: Policy,
) -> Result<Vec<Streamed>> {
    let c = model.stream_calibration()?;
    tests
        .iter()
        .map(|(e, d)| Ok(stream(model, &c, &d.rows, e.as_deref(), policy)?))
        .collect()
}

fn run(a: Args) -> Result<()> {
    let a = a.sets;
    let gestures = parse_gestures(&a.gestures)?;
    let seeds = parse_seeds(&a.seeds)?;
    let (config, arm) = common::config_and_arm(&a.config)?;
    let settings = DemoSettings {
        encoder_noise: a.noise,
        ..DemoSettings::default()
    };
    let (mut rule, mut first) = (Vec::new(), Vec::new());
    for &seed in &seeds {
        let mut sets = Vec::new();
        for g in &gestures {
            let mut d =
                synthetic_demonstrations(&arm, g, a.train + a.test, seed, &settings, |_| {})?;
            let test = d.split_off(a.train);
            sets.push((g.name.to_string(), d, test));
        }
        let taught: Vec<(String, Vec<Demonstration>)> = sets
            .iter()
            .map(|(l, t, _)| (l.clone(), t.clone()))
            .collect();
        let model = config.fit_model(&taught, cosco_hsom::hsom::Fit::default())?;
        let tests: Vec<(Option<String>, &Demonstration)> = sets
            .iter()
            .flat_map(|(l, _, t)| t.iter().map(move |d| (Some(l.clone()), d)))
            .collect();
        rule.extend(streams(&model, &tests, Policy::Rule)?);
        first.extend(streams(&model, &tests, Policy::FirstSample)?);
        for (u, (_, _, left_out)) in sets.iter().enumerate() {
            let others: Vec<(String, Vec<Demonstration>)> = taught
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != u)
                .map(|(_, s)| s.clone())
                .collect();
            let model = config.fit_model(&others, cosco_hsom::hsom::Fit::default())?;
            let tests: Vec<(Option<String>, &Demonstration)> =
                left_out.iter().map(|d| (None, d)).collect();
            rule.extend(streams(&model, &tests, Policy::Rule)?);
            first.extend(streams(&model, &tests, Policy::FirstSample)?);
        }
        eprintln!(
            "seed {seed}: {}",
            StreamSummary::of(&rule).markdown_row("so far")
        );
    }
    let (r, f) = (StreamSummary::of(&rule), StreamSummary::of(&first));
    println!("{MARKDOWN_HEADER}");
    println!("{}", r.markdown_row("the recogniser"));
    println!("{}", f.markdown_row("control: commits at the first sample"));
    println!();
    println!(
        "seeds {}; gates failed by the recogniser: {:?}; by the control: {:?}",
        a.seeds,
        r.failures(),
        f.failures()
    );
    if let Some(p) = &a.json {
        let bytes = serde_json::to_vec_pretty(&(&rule, &first))?;
        cosco_hsom::fsutil::write_atomic(p, &bytes)
            .with_context(|| format!("writing {}", p.display()))?;
    }
    Ok(())
}

fn main() -> ExitCode {
    let a = common::parse_with_defaults::<Args>(&[("seeds", "41-45"), ("test", "4")]);
    common::exit(run(a))
}
