//! The metrics the study tables show, each once: the key a run file or a study document keeps
//! it under, its heading, its decimals and which way is better. The held-out tables of
//! `cosco heldout`, the simulated arm's reports and the sweeps' merged tables take their
//! metric columns from here (docs/METRICS.md defines the metrics).

/// Which way a metric is better.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Better {
    /// Smaller is better (distances, errors).
    Lower,
    /// Closer to 1 is better, in ratio (`|ln x|` smaller).
    TowardOne,
    /// No direction (counts to compare with the demonstrations'); no wins are counted.
    Neither,
}

/// A metric of the tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Metric {
    /// Key in the run files and study documents.
    pub key: &'static str,
    /// Heading.
    pub label: &'static str,
    /// Decimals shown in Markdown.
    pub digits: usize,
    /// Which way is better.
    pub better: Better,
}

const fn metric(key: &'static str, label: &'static str, digits: usize, better: Better) -> Metric {
    Metric {
        key,
        label,
        digits,
        better,
    }
}

impl Metric {
    /// The same metric shown with `digits` decimals (a table of coarser or finer figures).
    pub const fn to(self, digits: usize) -> Metric {
        Metric { digits, ..self }
    }

    /// The same metric under another heading (a table's shorter or longer words for it).
    pub const fn titled(self, label: &'static str) -> Metric {
        Metric { label, ..self }
    }

    /// `v` with the metric's decimals; `missing` for none.
    pub fn cell(&self, v: Option<f64>, missing: &str) -> String {
        v.map_or_else(|| missing.to_string(), |v| format!("{v:.*}", self.digits))
    }
}

/// Joint-space DTW per step of the warping path, radians.
pub const JOINT_DTW: Metric = metric(
    "joint_dtw_rad_per_step",
    "joint DTW (rad/step)",
    4,
    Better::Lower,
);
/// Wrist-path DTW per step, millimetres.
pub const WRIST_DTW: Metric = metric(
    "wrist_dtw_mm_per_step",
    "wrist DTW (mm/step)",
    2,
    Better::Lower,
);
/// Joint error at the apex, radians.
pub const APEX_ERROR: Metric = metric("apex_error_rad", "apex error (rad)", 3, Better::Lower);
/// Joint error of the final posture, radians.
pub const FINAL_ERROR: Metric = metric(
    "final_error_rad",
    "final-posture error (rad)",
    3,
    Better::Lower,
);
/// Reproduction duration over the demonstration's.
pub const DURATION_RATIO: Metric = metric("duration_ratio", "duration ratio", 3, Better::TowardOne);
/// Normalized jerk of the reproduction over the demonstrations'. The demonstrations' jerk
/// includes their encoder noise: a smoother reproduction (ratio below 1) is not worse, so no
/// direction and no wins.
pub const JERK_RATIO: Metric = metric(
    "jerk_ratio",
    "normalized jerk, reproduction / demonstrations",
    2,
    Better::Neither,
);
/// Velocity reversals over all joints.
pub const VELOCITY_REVERSALS: Metric = metric(
    "velocity_reversals",
    "velocity reversals",
    1,
    Better::Neither,
);
/// The demonstrations' velocity reversals.
pub const DEMO_VELOCITY_REVERSALS: Metric = metric(
    "demo_velocity_reversals",
    "velocity reversals of the demonstrations",
    1,
    Better::Neither,
);
/// Large swings of the swing joint.
pub const SWINGS: Metric = metric("swings", "LElbowRoll swings", 1, Better::Neither);
/// The demonstrations' large swings of the swing joint.
pub const DEMO_SWINGS: Metric = metric(
    "demo_swings",
    "LElbowRoll swings of the demonstrations",
    1,
    Better::Neither,
);
/// DTW per step over the gesture's bounding-box diagonal, held out.
pub const RELATIVE_DTW: Metric = metric("relative_dtw", "relative DTW", 4, Better::Lower);
/// [`RELATIVE_DTW`] in-sample (learned from all).
pub const RELATIVE_DTW_IN_SAMPLE: Metric =
    metric("relative_dtw_in_sample", "in-sample", 4, Better::Lower);
/// Final error over the gesture's bounding-box diagonal.
pub const RELATIVE_FINAL_ERROR: Metric = metric(
    "relative_final_error",
    "final error / diagonal",
    4,
    Better::Lower,
);

/// The metrics of the sweeps' tables and plots, in order.
pub const SWEEP: [Metric; 10] = [
    JOINT_DTW,
    WRIST_DTW,
    APEX_ERROR,
    FINAL_ERROR,
    DURATION_RATIO,
    JERK_RATIO,
    VELOCITY_REVERSALS,
    DEMO_VELOCITY_REVERSALS,
    SWINGS,
    DEMO_SWINGS,
];
