//! What the `simulate` and `cosco` binaries share: stdout that tolerates a closed pipe,
//! progress bars, the one-line error, and the parsers of their numeric flags; the work is the
//! library's, whose typed errors carry the file, field and value (`anyhow` only here, in the
//! binaries).
#![allow(dead_code)]

/// `print!` that ignores a closed stdout (e.g. `| head`), instead of panicking.
#[allow(unused_macros)]
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
pub mod sweep;

pub mod cosco_args;
pub mod export;
pub mod reproduce;

use indicatif::{ProgressBar, ProgressStyle};

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

/// A progress bar of `what`, and the `(done, total)` callback that moves it (the total as the
/// work reports it).
pub fn counter(what: &str) -> (ProgressBar, impl Fn(usize, usize)) {
    let pb = progress(0, what);
    let bar = pb.clone();
    (pb, move |done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    })
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

/// A binary's exit: success, or `Error: ` and the error with its causes on one line
/// ([`cosco_hsom::app::error_line`]) on stderr, and failure.
pub fn exit(result: anyhow::Result<()>) -> std::process::ExitCode {
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("Error: {}", cosco_hsom::app::error_line(e.as_ref()));
            std::process::ExitCode::FAILURE
        }
    }
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

/// The largest `--noise`, rad: a real encoder's noise is far below it (Nao's encoders
/// resolve about 0.001 rad), and noise of 0.1 rad, about 6 degrees, already hides the
/// smaller gestures' motion.
#[cfg(feature = "sim")]
pub const MAX_ENCODER_NOISE: f64 = 0.1;

/// `--noise`: a standard deviation in rad, from 0 to [`MAX_ENCODER_NOISE`] (clap names the
/// option and the value).
#[cfg(feature = "sim")]
pub fn parse_noise(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=MAX_ENCODER_NOISE).contains(&v) => Ok(v),
        _ => Err(format!(
            "expected a standard deviation in rad: a number >= 0 and <= {MAX_ENCODER_NOISE} \
             (a real encoder's noise is far below {MAX_ENCODER_NOISE} rad); got {s:?}"
        )),
    }
}

/// Every core (1 when it cannot be told).
pub fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}
