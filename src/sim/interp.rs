//! Time-scaling profiles of a point-to-point transition.

use serde::{Deserialize, Serialize};

use crate::curve::{minimum_jerk_at, minimum_jerk_velocity, MINIMUM_JERK_PEAK};

/// How a transition between two postures is timed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Interpolation {
    /// Constant velocity: position linear in time (velocity jumps at the ends).
    Linear,
    /// Minimum-jerk quintic s = 10 u^3 - 15 u^4 + 6 u^5 ([`minimum_jerk_at`]): zero velocity and
    /// acceleration at both ends, a smooth bell-shaped velocity profile (Flash & Hogan), like
    /// human reaching.
    #[default]
    MinimumJerk,
}

impl Interpolation {
    /// Progress `s` in [0, 1] and its derivative `ds/du` at normalised time `u` (clamped to [0, 1]).
    pub fn profile(self, u: f64) -> (f64, f64) {
        let u = u.clamp(0.0, 1.0);
        match self {
            Interpolation::Linear => (u, 1.0),
            Interpolation::MinimumJerk => (minimum_jerk_at(u), minimum_jerk_velocity(u)),
        }
    }

    /// Peak of `ds/du` over [0, 1]: the ratio of peak to mean velocity (1 for linear, 15/8 for
    /// minimum jerk). A transition of amplitude `d` in time `T` peaks at `d * peak / T`.
    pub fn peak_velocity_factor(self) -> f64 {
        match self {
            Interpolation::Linear => 1.0,
            Interpolation::MinimumJerk => MINIMUM_JERK_PEAK,
        }
    }
}

#[cfg(test)]
mod tests;
