//! What several examples share: the sets of synthetic demonstrations they record (the same
//! flags and defaults in each) and how they exit.

use std::process::ExitCode;

use cosco_hsom::experiment::DemoSettings;

/// Which sets of synthetic demonstrations to record: every gesture x seed, `count` each.
#[derive(clap::Args, Debug)]
pub struct Sets {
    /// Gestures, comma-separated.
    #[arg(long, default_value = "reading-watch,wave,reach-point,salute")]
    pub gestures: String,
    /// Seeds of the demonstrations: numbers and ranges, e.g. `1-5` or `1,3,7-9`.
    #[arg(long, default_value = "1-5")]
    pub seeds: String,
    /// Demonstrations per (gesture, seed).
    #[arg(long, default_value_t = 4)]
    pub count: usize,
    /// Encoder noise of the synthetic demonstrations, rad.
    #[arg(long, default_value_t = 0.001)]
    pub noise: f64,
}

impl Sets {
    /// The recording settings: the default ones with this encoder noise.
    #[allow(dead_code)] // examples that do not record take the module for `exit`
    pub fn demo_settings(&self) -> DemoSettings {
        DemoSettings {
            encoder_noise: self.noise,
            ..DemoSettings::default()
        }
    }
}

/// An example's exit status: success, or the error with its causes on stderr and failure.
pub fn exit(result: anyhow::Result<()>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
