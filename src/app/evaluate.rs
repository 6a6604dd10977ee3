//! A reproduction's fidelity against demonstrations (`cosco evaluate`), and a saved model's
//! levels and sizes (`cosco inspect`).

use std::path::{Path, PathBuf};

use super::files::{self, read_demos, read_reproduction};
use super::{Error, Result};
use crate::demos::{sample_period, Demonstration};
use crate::metrics::{
    diagonal, fidelity_of_rows, FidelityReport, MetricsParams, StartEnd, StartEndReference,
};

/// Any error, as an [`ArmScorer`] gives it.
pub type BoxError = Box<dyn std::error::Error + Send + Sync>;

/// Scores a reproduction of the arm's joints with the arm's kinematics (wrist paths): what a
/// caller built with the simulator passes to [`evaluate_files`] (`experiment::evaluate`).
pub type ArmScorer<'a> = &'a dyn Fn(
    &[Demonstration],
    &[Vec<f64>],
    &MetricsParams,
) -> std::result::Result<FidelityReport, BoxError>;

/// What `cosco evaluate` found (its `--json` document): the fidelity report's fields, and
/// the reproduction's start and end against the demonstrations given.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Evaluation {
    /// The fidelity metrics against the demonstrations.
    #[serde(flatten)]
    pub fidelity: FidelityReport,
    /// Its start speed against theirs and its mean final error against their end spread,
    /// in the diagonal of their bounding box (docs/METRICS.md, "Start and end").
    pub start_end: StartEnd,
    /// The unit of the distances: `rad` for the arm's joints, the data's own units otherwise.
    #[serde(skip)]
    pub unit: &'static str,
    /// Every contact between two parts of the robot while the reproduction is executed on
    /// the simulated upper body (when its columns are the upper body's joints; the left arm's
    /// model is collision-free, so none there).
    #[cfg(feature = "sim")]
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contacts: Option<Vec<crate::sim::Touch>>,
}

/// The contacts of `rep` executed on the simulated upper body, when its columns are the
/// upper body's joints (`rate_hz`: its rows' rate when it has no `time`).
#[cfg(feature = "sim")]
fn contacts(rep: &Demonstration, rate_hz: f64) -> Result<Option<Vec<crate::sim::Touch>>> {
    use crate::robot::Robot;
    if Robot::of_columns(&rep.columns) != Some(Robot::UpperBody) {
        return Ok(None);
    }
    let t = crate::export::Trajectory::from_demonstration(rep, rate_hz)?;
    let done = crate::export::executed::execute(Robot::UpperBody, &t, rate_hz)?;
    Ok(Some(done.contacts))
}

/// `cosco evaluate`: the fidelity metrics of a reproduction CSV against demonstrations, and
/// its start and end against theirs; written as JSON to `json` when given. When the columns
/// are the arm's joints and `arm` is given, it scores them (with wrist paths, in rad);
/// otherwise they are scored in the data's units. Every error names the reproduction file
/// or the file it concerns.
pub fn evaluate_files(
    reproduction: &Path,
    demo_paths: &[PathBuf],
    json: Option<&Path>,
    arm: Option<ArmScorer<'_>>,
) -> Result<Evaluation> {
    let demos = read_demos(demo_paths, None, None)?;
    let rep = read_reproduction(reproduction)?;
    if rep.columns != demos[0].columns {
        return Err(Error::file(
            reproduction,
            format!(
                "columns {:?} differ from the demonstrations' {:?}",
                rep.columns, demos[0].columns
            ),
        ));
    }
    let params = MetricsParams {
        sample_period: sample_period(&demos[0]),
        ..MetricsParams::default()
    };
    let failed = |source| Error::Evaluate {
        path: reproduction.to_path_buf(),
        source,
    };
    let (fidelity, unit) = match arm {
        Some(score) if crate::robot::are_arm_joints(&rep.columns) => {
            (score(&demos, &rep.rows, &params).map_err(failed)?, "rad")
        }
        _ => (
            fidelity_of_rows(&demos, &rep.rows, &params).map_err(|e| failed(e.into()))?,
            "data units",
        ),
    };
    let reference = StartEndReference::of(&demos, diagonal(&demos));
    let start_end = reference.judge(
        &rep.rows,
        params.sample_period,
        fidelity.final_error_rad.mean,
    );
    let e = Evaluation {
        fidelity,
        start_end,
        unit,
        #[cfg(feature = "sim")]
        contacts: contacts(&rep, 1.0 / params.sample_period)?,
    };
    if let Some(p) = json {
        files::write_json(p, &e)?;
    }
    Ok(e)
}

impl Evaluation {
    /// The human-readable report `cosco evaluate` prints: the fidelity metrics, then the
    /// start and end against the demonstrations'.
    pub fn lines(&self) -> String {
        let (f, s, unit) = (&self.fidelity, &self.start_end, self.unit);
        let st = |s: &crate::metrics::Stat| format!("mean {:.4}, worst {:.4}", s.mean, s.worst);
        let line = |label: String, value: String| format!("{label:<34}{value}\n");
        let mut out = line(
            format!("joint DTW ({unit}/step):"),
            st(&f.joint_dtw_rad_per_step),
        );
        if let Some(w) = &f.wrist_dtw_mm {
            out += &line("wrist-path DTW (mm/step):".into(), st(w));
        } else if cfg!(not(feature = "sim")) {
            out += &line(
                "wrist-path DTW (mm/step):".into(),
                "n/a (built without the `sim` feature: no arm kinematics)".into(),
            );
        }
        out += &line(format!("apex error ({unit}):"), st(&f.apex_error_rad));
        out += &line(
            format!("final-posture error ({unit}):"),
            st(&f.final_error_rad),
        );
        out += &line("duration ratio:".into(), st(&f.duration_ratio));
        out += &format!(
            "smoothness: normalized jerk {}, velocity reversals {} ({:?} per column)\n",
            f.reproduction_smoothness
                .normalized_jerk
                .map_or("n/a".into(), |j| format!("{j:.0}")),
            f.reproduction_smoothness.total_reversals,
            f.reproduction_smoothness.reversals
        );
        let num = |v: Option<f64>| v.map_or("n/a".to_string(), |v| format!("{v:.4}"));
        let verdict = |ok: bool, yes: &str, no: &str| if ok { yes } else { no }.to_string();
        out += &line(
            format!("start speed ({unit}/s):"),
            format!(
                "{}; demonstrations' largest {}: {}",
                num(s.start_speed),
                num(s.demo_start_speed_max),
                verdict(
                    s.start_in_range,
                    "in range",
                    "FASTER than every demonstration's start"
                )
            ),
        );
        out += &line(
            format!("final error ({unit}):"),
            format!(
                "{:.4}; demonstrations' end spread {:.4}, tolerance {:.4}: {}",
                s.final_error,
                s.end_spread,
                s.end_tolerance,
                verdict(s.end_within_spread, "within", "OUTSIDE the spread")
            ),
        );
        #[cfg(feature = "sim")]
        if let Some(c) = &self.contacts {
            let seen: Vec<String> = c.iter().map(|t| t.describe()).collect();
            out += &line(
                "contacts (simulated upper body):".into(),
                match seen.is_empty() {
                    true => "none".into(),
                    false => format!("{}: {}", seen.len(), seen.join("; ")),
                },
            );
        }
        out
    }
}

/// `cosco inspect`: a saved model's levels, sizes and quality measures; for one gesture also
/// its binary file by part (`Hsom::file_parts`: one line a part, its bytes, then the total
/// and the configuration's ceiling for the traced chunks; docs/BENCHMARKS.md, "The model
/// file").
pub fn inspect(path: &Path) -> Result<String> {
    let m = files::load_gesture_model(path)?;
    let mut s = format!("{}\n", path.display());
    let taught = |b: &crate::hsom::Hsom| {
        let (learned, kept, updates) = b.learned();
        format!(
            "learned from {learned} demonstrations in {} (the training or update that \
             taught it, then every update that brought it more); {kept} kept for updates and \
             the band (at most {})\n",
            match updates {
                0 => "1 sitting".to_string(),
                u => format!("{} sittings", u + 1),
            },
            crate::hsom::KEPT_DEMONSTRATIONS
        )
    };
    if m.labels().is_empty() {
        let model = &m.branches()[0];
        s += &taught(model);
        s += &model.summary().to_string();
        let parts = model.file_parts();
        s += "binary model file by part (bytes):\n";
        for p in &parts {
            s += &format!("  {:>9}  {}\n", p.bytes, p.part);
        }
        let total: usize = parts.iter().map(|p| p.bytes).sum();
        s += &format!("  {total:>9}  total\n");
        s += &format!(
            "  {:>9}  ceiling of the traced chunks this configuration allows\n",
            model.traced_ceiling()
        );
    }
    for (l, b) in m.labels().iter().zip(m.branches()) {
        s += &format!("gesture {l}: {}{}", taught(b), b.summary());
    }
    Ok(s)
}
