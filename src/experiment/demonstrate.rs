//! Kinesthetic teaching in simulation: a synthetic demonstrator guides the simulated arm and
//! the joint encoders are recorded at 40 Hz, as on the real robot.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use std::path::{Path, PathBuf};

use crate::demos::{write_csv, Demonstration};
use crate::gesture::{Gesture, HumanTrajectory, Variation};
use crate::sim::{Controller, ControllerConfig, NaoArm, Recording, TargetTrajectory};

use super::ExperimentError;

/// How demonstrations are made.
#[derive(Debug, Clone, PartialEq)]
pub struct DemoSettings {
    /// How much the demonstrations differ from each other.
    pub variation: Variation,
    /// Standard deviation of the encoder noise, rad (0: exact encoders).
    pub encoder_noise: f64,
    /// Recording rate, Hz (40 as in the paper).
    pub record_rate_hz: f64,
    /// Rate at which the demonstrator's hand trajectory is sampled into servo targets, Hz.
    pub guide_rate_hz: f64,
}

impl Default for DemoSettings {
    fn default() -> Self {
        DemoSettings {
            variation: Variation::default(),
            encoder_noise: 0.0,
            record_rate_hz: 40.0,
            guide_rate_hz: 100.0,
        }
    }
}

/// Record `count` demonstrations of `gesture` on the simulated arm, the encoders' readings held
/// within the joint ranges ([`within_ranges`]). Everything random comes from `seed`:
/// demonstration `i` uses its own sub-stream, so demonstration 0 is the same whatever `count`
/// is.
pub fn record_demonstrations<const N: usize>(
    arm: &NaoArm<N>,
    gesture: &Gesture,
    count: usize,
    seed: u64,
    settings: &DemoSettings,
    mut on_done: impl FnMut(usize),
) -> Result<Vec<Recording>, ExperimentError> {
    if count == 0 {
        return Err(ExperimentError::Invalid(
            "demonstration count is 0: need at least 1".into(),
        ));
    }
    if gesture.robot != arm.robot() {
        return Err(ExperimentError::Invalid(format!(
            "gesture '{}' moves the {} and the model is the {}",
            gesture.name,
            gesture.robot.name(),
            arm.robot().name()
        )));
    }
    let ranges = arm.robot().ranges();
    let mut out = Vec::with_capacity(count);
    for i in 0..count {
        let human = demonstrator(gesture, i, seed, settings)?;
        let controller = Controller::new(ControllerConfig {
            record_rate_hz: settings.record_rate_hz,
            encoder_noise_std: settings.encoder_noise,
            seed: seed.wrapping_add(1000 + i as u64),
            ..ControllerConfig::default()
        })?;
        let samples = human.sampled(1.0 / settings.guide_rate_hz);
        let times: Vec<f64> = samples.iter().map(|(t, _)| *t).collect();
        let targets: Vec<Vec<f64>> = samples.iter().map(|(_, q)| q.to_vec()).collect();
        let trajectory = TargetTrajectory::<N>::new_for(arm.robot(), &times, &targets)?
            .with_hold(1.0 / settings.record_rate_hz)?;
        let mut sim = arm.sim()?;
        sim.set_posture(&targets[0])?;
        let mut rec = controller.follow(&mut sim, &trajectory)?;
        within_ranges(&mut rec.qpos, &ranges);
        out.push(rec);
        on_done(i);
    }
    Ok(out)
}

/// Hold every reading of `qpos` within its joint's range, as the robot's encoders report it:
/// the simulated joints' limits are soft, and a joint driven to its limit (a hand opened
/// fully, an elbow rolled in) reads up to a few milliradians past it, which `cosco export`
/// would refuse.
fn within_ranges(qpos: &mut [Vec<f64>], ranges: &[(f64, f64)]) {
    for row in qpos {
        for (v, (lo, hi)) in row.iter_mut().zip(ranges) {
            *v = v.clamp(*lo, *hi);
        }
    }
}

/// The person guiding demonstration `i` (from 0) of `gesture` with `seed`.
fn demonstrator(
    gesture: &Gesture,
    i: usize,
    seed: u64,
    settings: &DemoSettings,
) -> Result<HumanTrajectory, ExperimentError> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(i as u64 + 1);
    HumanTrajectory::sample(gesture, &settings.variation, &mut rng)
        .map_err(ExperimentError::Invalid)
}

/// How long the longest of the `count` demonstrations [`record_demonstrations`] records
/// lasts, s, known without simulating them (their demonstrators' lengths).
pub fn demonstration_seconds(
    gesture: &Gesture,
    count: usize,
    seed: u64,
    settings: &DemoSettings,
) -> Result<f64, ExperimentError> {
    (0..count).try_fold(0.0, |longest: f64, i| {
        Ok(longest.max(demonstrator(gesture, i, seed, settings)?.duration()))
    })
}

/// [`record_demonstrations`] as demonstrations named `"<gesture> demonstration N (seed S)"`
/// (N from 1), each with the recording's `time` column.
pub fn synthetic_demonstrations<const N: usize>(
    arm: &NaoArm<N>,
    gesture: &Gesture,
    count: usize,
    seed: u64,
    settings: &DemoSettings,
    on_done: impl FnMut(usize),
) -> Result<Vec<Demonstration>, ExperimentError> {
    let recs = record_demonstrations(arm, gesture, count, seed, settings, on_done)?;
    Ok(as_demonstrations(gesture, seed, &recs))
}

/// Recordings of [`record_demonstrations`] as demonstrations named `"<gesture> demonstration
/// N (seed S)"` (N from 1), each with the recording's `time` column.
pub fn as_demonstrations(gesture: &Gesture, seed: u64, recs: &[Recording]) -> Vec<Demonstration> {
    recs.iter()
        .enumerate()
        .map(|(i, r)| {
            r.to_demonstration(format!(
                "{} demonstration {} (seed {seed})",
                gesture.name,
                i + 1
            ))
        })
        .collect()
}

/// Write demonstrations as `demo_01.csv`, ... in `dir` (created if missing).
pub fn write_demos(dir: &Path, demos: &[Demonstration]) -> Result<Vec<PathBuf>, ExperimentError> {
    std::fs::create_dir_all(dir).map_err(ExperimentError::io("creating", dir))?;
    let mut files = Vec::new();
    for (i, d) in demos.iter().enumerate() {
        let p = dir.join(format!("demo_{:02}.csv", i + 1));
        write_csv(&p, d)?;
        files.push(p);
    }
    Ok(files)
}

/// Parse seeds: a comma-separated list of numbers and inclusive ranges `A-B` (`1-5`,
/// `1,3,7-9`). An empty entry, a bad number or a range with `A > B` is an error naming it.
pub fn parse_seeds(text: &str) -> Result<Vec<u64>, ExperimentError> {
    let bad = |entry: &str, why: &str| {
        ExperimentError::Invalid(format!(
            "seeds '{text}': entry '{entry}' {why}; give numbers and ranges A-B separated by \
             commas, e.g. 1-5 or 1,3,7-9"
        ))
    };
    let number = |entry: &str, v: &str| {
        v.trim()
            .parse::<u64>()
            .map_err(|_| bad(entry, "is not a whole number >= 0"))
    };
    let mut out = Vec::new();
    for entry in text.split(',') {
        let e = entry.trim();
        if e.is_empty() {
            return Err(bad(entry, "is empty"));
        }
        match e.split_once('-') {
            Some((a, b)) => {
                let (a, b) = (number(e, a)?, number(e, b)?);
                if a > b {
                    return Err(bad(e, "is a range whose start exceeds its end"));
                }
                out.extend(a..=b);
            }
            None => out.push(number(e, e)?),
        }
    }
    Ok(out)
}

/// Parse comma-separated gesture names; an unknown name is an error listing the known ones.
pub fn parse_gestures(text: &str) -> Result<Vec<Gesture>, ExperimentError> {
    text.split(',')
        .map(|name| {
            let name = name.trim();
            Gesture::by_name(crate::robot::Robot::LeftArm, name).ok_or_else(|| {
                ExperimentError::Invalid(format!(
                    "unknown gesture '{name}' in '{text}': allowed {}",
                    Gesture::names(crate::robot::Robot::LeftArm).join(", ")
                ))
            })
        })
        .collect()
}

#[cfg(test)]
mod tests;
