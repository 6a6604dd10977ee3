//! Fidelity metrics: how closely a reproduction follows the demonstrations, and how smooth
//! it is. Pure functions over joint trajectories sampled at a fixed rate (40 Hz) with
//! optional wrist positions; the simulator supplies the data. Definitions, formulas, units
//! and thresholds: `docs/METRICS.md`.

mod errors;
mod fidelity;
mod smoothness;

pub use errors::MetricsError;
pub use fidelity::{
    fidelity, fidelity_named, DemoScores, FidelityReport, MetricsParams, Stat, Trajectory,
};
pub use smoothness::{
    column_swings, key_pose, large_swings, normalized_jerk, smoothness, velocity_reversals,
    Smoothness,
};
