//! `cosco heldout`: leave-one-out on demonstration files (read as `cosco train` reads them),
//! with the outputs it writes.

use std::path::PathBuf;

use crate::config::load_config_or_robots;
use crate::fsutil::check_output;
use crate::stepper::KinematicLoop;

use super::{
    failures, read_gestures_at, study, Extra, Kinematic, LooError, LooSettings, Method, Section,
};

/// What `cosco heldout` does.
pub struct HeldoutJob {
    /// Demonstration paths, as for `cosco train`.
    pub demos: Vec<PathBuf>,
    /// Configuration file (default: the built-in recommended one).
    pub config: Option<PathBuf>,
    /// Take `stateLength` from the data.
    pub state_length_from_data: bool,
    /// Resample the demonstrations to this rate, Hz.
    pub resample: Option<f64>,
    /// Which methods, which results, how many threads.
    pub settings: LooSettings,
    /// Far goals to run the folds with besides (`K` each, [`super::far_target`]).
    pub far: Vec<f64>,
    /// Disturbances to run every fold in the loop with besides ([`super::in_loop`]).
    pub disturb: Vec<crate::stepper::Disturbance>,
    /// Where to write every fold's scores as JSON.
    pub json: Option<PathBuf>,
    /// Where to draw one fold per gesture.
    pub png: Option<PathBuf>,
}

/// `cosco heldout`: leave-one-out on the demonstrations' files with the kinematic executor
/// (`progress(done, total)` after each fold); the Markdown tables, after writing the JSON and
/// the figure when asked.
pub fn heldout(
    job: &HeldoutJob,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<String, LooError> {
    heldout_with(job, progress, None)
}

/// [`heldout`], with the section `extra` computes from the folds appended to the Markdown and
/// put into the JSON.
pub fn heldout_with(
    job: &HeldoutJob,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
    extra: Option<Extra>,
) -> Result<String, LooError> {
    for p in job.json.iter().chain(&job.png) {
        check_output(p)?;
    }
    // without --config, demonstrations of a robot's joints take that robot's configuration
    let robot = match &job.config {
        Some(_) => crate::robot::Robot::LeftArm,
        None => crate::demo_sets::robot_of(&job.demos, job.resample)?,
    };
    let cfg = load_config_or_robots(job.config.as_deref(), robot)?;
    let (cfg, gestures) =
        read_gestures_at(&job.demos, &cfg, job.state_length_from_data, job.resample)?;
    // the loop study runs what the folds learned
    let settings = LooSettings {
        keep_learned: !job.disturb.is_empty(),
        ..job.settings
    };
    let all = study(&cfg, gestures, &settings, &job.far, &Kinematic, progress)?;
    // nothing to compare when the hierarchy itself never ran: the reason, as an error
    let plain = &all.unconditioned;
    if !super::results::held_out_runs(plain, Method::Hierarchy).any(|r| r.score.is_some()) {
        let why = failures(plain)
            .into_iter()
            .find(|(m, _, _)| *m == Method::Hierarchy)
            .map_or_else(|| "no fold ran".to_string(), |(_, why, _)| why);
        return Err(LooError::NoReproduction(why));
    }
    let mut sections: Vec<Section> = match extra {
        Some(f) => f(plain).map_err(LooError::Extra)?.into_iter().collect(),
        None => Vec::new(),
    };
    if !job.disturb.is_empty() {
        let pool = super::Pool::new(job.settings.threads).map_err(LooError::Pool)?;
        let methods = job.settings.methods(true);
        let (mut markdown, mut json) = (String::new(), Vec::new());
        let all = super::in_loop(&cfg, plain, &methods, &job.disturb, &KinematicLoop, &pool);
        for (d, runs) in job.disturb.iter().zip(all) {
            markdown.push_str(&super::loop_markdown(d, &runs));
            json.push(serde_json::json!({ "disturbance": d, "gestures": runs }));
        }
        sections.push(Section {
            key: "in_loop",
            markdown,
            json: serde_json::Value::Array(json),
        });
    }
    if let Some(p) = &job.json {
        let text = super::report::json_text(&all.document(&cfg, &sections));
        super::loo::write(p, text.as_bytes())?;
    }
    #[cfg(feature = "plot")]
    if let Some(p) = &job.png {
        super::png(p, plain, 0)?;
    }
    let mut out = all.markdown();
    for s in sections {
        out.push_str(&s.markdown);
    }
    Ok(out)
}
