//! The steps shared by the `simulate` and `cosco` binaries. Errors are `anyhow` here (binaries
//! only); the library's typed errors carry the file, field and value.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use indicatif::{ProgressBar, ProgressStyle};

use cosco_hsom::demos::{self, Demonstration};
use cosco_hsom::experiment::{record_demonstrations, DemoSettings};
use cosco_hsom::gesture::Gesture;
use cosco_hsom::sim::{NaoArm, Recording};

/// Default encoder noise of synthetic demonstrations, rad (about Nao's encoder resolution).
pub const DEFAULT_ENCODER_NOISE: f64 = 0.001;

/// A progress bar on stderr (hidden when stderr is not a terminal).
pub fn progress(len: u64, what: &str) -> ProgressBar {
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template(
            "{msg:>14} [{bar:40.cyan/blue}] {pos}/{len} {elapsed_precise}",
        )
        .expect("static template")
        .progress_chars("=> "),
    );
    pb.set_message(what.to_string());
    pb
}

/// Load the arm model from `path` or the default model.
pub fn load_arm(path: Option<&Path>) -> Result<NaoArm> {
    match path {
        Some(p) => {
            NaoArm::load(p).with_context(|| format!("loading the arm model {}", p.display()))
        }
        None => NaoArm::load_default().context("loading the default arm model"),
    }
}

/// Look a gesture up by name, with the list of known names on failure.
pub fn gesture(name: &str) -> Result<Gesture> {
    match Gesture::by_name(name) {
        Some(g) => Ok(g),
        None => bail!(
            "unknown gesture '{name}': allowed {}",
            Gesture::names().join(", ")
        ),
    }
}

/// Record synthetic demonstrations in the simulator.
pub fn record(
    arm: &NaoArm,
    gesture: &Gesture,
    count: usize,
    seed: u64,
    noise: f64,
) -> Result<Vec<Recording>> {
    let settings = DemoSettings {
        encoder_noise: noise,
        ..DemoSettings::default()
    };
    let pb = progress(count as u64, "demonstrating");
    let recs = record_demonstrations(arm, gesture, count, seed, &settings, |_| pb.inc(1))?;
    pb.finish_and_clear();
    Ok(recs)
}

/// Write demonstrations as `demo_01.csv`, ... in `dir` (created if missing).
pub fn write_demos(dir: &Path, demos: &[Demonstration]) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let mut files = Vec::new();
    for (i, d) in demos.iter().enumerate() {
        let p = dir.join(format!("demo_{:02}.csv", i + 1));
        demos::write_csv(&p, d)?;
        files.push(p);
    }
    Ok(files)
}

/// `cosco demos`: record and write demonstrations.
pub fn demos(
    gesture_name: &str,
    count: usize,
    seed: u64,
    out: &Path,
    noise: f64,
    model: Option<&Path>,
) -> Result<Vec<PathBuf>> {
    let g = gesture(gesture_name)?;
    let arm = load_arm(model)?;
    let recs = record(&arm, &g, count, seed, noise)?;
    let demos: Vec<Demonstration> = recs
        .iter()
        .enumerate()
        .map(|(i, r)| {
            r.to_demonstration(format!("{} demonstration {} (seed {seed})", g.name, i + 1))
        })
        .collect();
    write_demos(out, &demos)
}
