//! The steps shared by the `simulate` and `cosco` binaries: progress bars, printing, and the
//! library's steps ([`cosco_hsom::steps`]) with `anyhow` errors (binaries only); the library's
//! typed errors carry the file, field and value. What needs the simulated arm is in [`arm`].
#![allow(dead_code)]

#[cfg(feature = "sim")]
pub mod sweep;

pub mod cosco_args;
pub mod export;

#[cfg(feature = "sim")]
pub use cosco_hsom::experiment::compare;
#[cfg(feature = "sim")]
pub use cosco_hsom::experiment::job::DEFAULT_ENCODER_NOISE;

use std::path::{Path, PathBuf};

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};

use cosco_hsom::config::HsomConfig;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::hsom::Hsom;
use cosco_hsom::steps;

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

/// One progress bar per stage of a job (`(stage, done, total)`): a new bar when the stage
/// changes, the last one cleared by [`StageBars::finish`].
#[derive(Default)]
pub struct StageBars(std::cell::RefCell<Option<(String, ProgressBar)>>);

impl StageBars {
    /// Show `done` of `total` in `stage`'s bar.
    pub fn update(&self, stage: &str, done: usize, total: usize) {
        let mut b = self.0.borrow_mut();
        if b.as_ref().map_or(true, |(s, _)| s != stage) {
            if let Some((_, old)) = b.take() {
                old.finish_and_clear();
            }
            *b = Some((stage.to_string(), progress(total as u64, stage)));
        }
        if let Some((_, pb)) = b.as_ref() {
            pb.set_position(done as u64);
        }
    }

    /// Clear the last bar.
    pub fn finish(&self) {
        if let Some((_, pb)) = self.0.borrow_mut().take() {
            pb.finish_and_clear();
        }
    }
}

/// Load a CoSCo-HSOM configuration file, or the built-in recommended configuration.
pub fn hsom_config(path: Option<&Path>) -> Result<HsomConfig> {
    Ok(steps::config(path)?)
}

/// Read demonstration files (a directory of *.csv or explicit files), checked as a set.
pub fn read_demos(paths: &[PathBuf], state_length: Option<usize>) -> Result<Vec<Demonstration>> {
    Ok(steps::read_demos(paths, state_length)?)
}

/// Train with a progress bar.
pub fn train(cfg: &HsomConfig, demos: &[Demonstration]) -> Result<Hsom> {
    let pb = progress(cfg.params().training_steps as u64, "training");
    let model = steps::train(
        cfg,
        demos,
        Some(&|done, _total| pb.set_position(done as u64)),
    )?;
    pb.finish_and_clear();
    Ok(model)
}

/// Load a saved model (.bin or .txt).
pub fn load_model(path: &Path) -> Result<Hsom> {
    Ok(steps::load_model(path)?)
}

/// The error and its causes on one line ([`steps::error_line`]).
pub fn error_line(e: &anyhow::Error) -> String {
    steps::error_line(e.as_ref())
}

/// `--count`: a whole number of demonstrations, at least 1 (negative numbers reach this
/// parser, so that `--count -1` is answered with what is allowed, not "unexpected argument").
#[cfg(feature = "sim")]
pub fn parse_count(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "expected a whole number of demonstrations, at least 1; got {s:?}"
        )),
    }
}

/// `--seed`: a whole number from 0 to 2^64 - 1.
#[cfg(feature = "sim")]
pub fn parse_seed(s: &str) -> Result<u64, String> {
    s.trim()
        .parse::<u64>()
        .map_err(|_| format!("expected a whole number from 0 to {}; got {s:?}", u64::MAX))
}

/// `--noise`: a standard deviation in rad, finite and at least 0.
#[cfg(feature = "sim")]
pub fn parse_noise(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!(
            "expected a standard deviation in rad: a finite number >= 0; got {s:?}"
        )),
    }
}

/// Every core (1 when it cannot be told).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
