//! Fidelity metrics: how closely a reproduction follows the demonstrations, how smooth it
//! is, and where it starts and ends against them. Pure functions over joint trajectories sampled at a fixed rate (40 Hz) with
//! optional wrist positions; the simulator supplies the data. Definitions, formulas, units
//! and thresholds: `docs/METRICS.md`.

mod errors;
mod fidelity;
pub mod registry;
mod smoothness;
mod start_end;
pub mod two_arms;

pub use errors::MetricsError;
pub use fidelity::{
    fidelity, fidelity_named, fidelity_of_rows, trimmed_normalized_jerk, DemoScores,
    FidelityReport, MetricsParams, Stat, Trajectory,
};
pub(crate) use smoothness::DemoSmoothness;
pub use smoothness::{
    apex_dwell, column_swings, key_pose, large_swings, normalized_jerk, smoothness,
    velocity_reversals, Smoothness, APEX_RADIUS,
};
pub use start_end::{
    diagonal, end_spread, end_tolerance, start_speed, StartEnd, StartEndReference,
    END_DIAGONAL_FRACTION, END_SPREAD_FACTOR, START_SPEED_RTOL,
};

#[cfg(test)]
mod tests;
