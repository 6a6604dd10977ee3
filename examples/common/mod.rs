//! What several examples share: the sets of synthetic demonstrations they record (the same
//! flags and defaults in each) and how they exit.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use cosco_hsom::config::{load_config, HsomConfig};
use cosco_hsom::experiment::DemoSettings;
use cosco_hsom::sim::NaoArm;

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

impl Sets {
    /// Leave-one-out needs at least 2 demonstrations per set (one held out, one to learn from).
    #[allow(dead_code)] // not every example holds demonstrations out
    pub fn check_leave_one_out(&self) -> anyhow::Result<()> {
        anyhow::ensure!(
            self.count >= 2,
            "--count must be at least 2, got {}",
            self.count
        );
        Ok(())
    }
}

/// The studies that teach every gesture some demonstrations and hold out others: which to
/// record, the configuration and where every result goes.
#[derive(clap::Args, Debug)]
#[allow(dead_code)] // only the held-out studies of several gestures take it
pub struct HeldOutSets {
    /// Gestures, comma-separated.
    #[arg(long, default_value = "reading-watch,wave,reach-point,salute")]
    pub gestures: String,
    /// Seeds of the demonstrations: numbers and ranges, e.g. `1-5`.
    #[arg(long, default_value = "1-5")]
    pub seeds: String,
    /// Demonstrations per gesture to learn from.
    #[arg(long, default_value_t = 3)]
    pub train: usize,
    /// Held-out demonstrations per gesture.
    #[arg(long, default_value_t = 2)]
    pub test: usize,
    /// Encoder noise of the recordings, rad.
    #[arg(long, default_value_t = 0.001)]
    pub noise: f64,
    /// CoSCo-HSOM configuration (XML).
    #[arg(long, default_value = "configs/nao-gestures.xml")]
    pub config: PathBuf,
    /// Write every result to this JSON file.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// `A` read from the command line, with `defaults` (`(flag, value)`) in place of the ones its
/// flags declare (an example whose study wants other defaults for shared flags).
#[allow(dead_code)] // used by the examples that change a shared default
pub fn parse_with_defaults<A: clap::Parser>(defaults: &[(&'static str, &'static str)]) -> A {
    let mut command = A::command();
    for &(flag, value) in defaults {
        command = command.mut_arg(flag, |a| a.default_value(value));
    }
    let mut matches = command.get_matches_mut();
    A::from_arg_matches_mut(&mut matches).unwrap_or_else(|e| e.format(&mut command).exit())
}

/// A CoSCo-HSOM configuration file, loaded, and the default arm model.
#[allow(dead_code)] // examples that do not train take the module for `exit`
pub fn config_and_arm(config: &Path) -> anyhow::Result<(HsomConfig, NaoArm)> {
    let c = load_config(config).with_context(|| format!("loading {}", config.display()))?;
    let arm = NaoArm::load_default().context("loading the default arm model")?;
    Ok((c, arm))
}

/// The one gesture `--gesture` names (a list of more, or none, is refused).
#[allow(dead_code)] // used by the examples that draw one gesture
pub fn one_gesture(names: &str) -> anyhow::Result<cosco_hsom::gesture::Gesture> {
    let mut gestures = cosco_hsom::experiment::demonstrate::parse_gestures(names)?;
    if gestures.len() != 1 {
        anyhow::bail!(
            "--gesture '{names}': name exactly one gesture ({} given)",
            gestures.len()
        );
    }
    Ok(gestures.remove(0))
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
