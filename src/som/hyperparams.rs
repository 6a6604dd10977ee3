//! Settings of one Kohonen map: topology, neighbourhood function and decay schedules.

use serde::{Deserialize, Serialize};

/// The word a file writes for `v`, a unit variant: its serde name (each enum's words are
/// written once, in its `#[serde]` attributes).
pub(crate) fn word<T: Serialize>(v: &T) -> String {
    match serde_json::to_value(v) {
        Ok(serde_json::Value::String(s)) => s,
        _ => String::new(),
    }
}

/// Arrangement of the nodes on the 2-D grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Topology {
    /// Rectangular grid; node (x, y) sits at (x, y); its neighbours are the 8 surrounding nodes.
    #[serde(alias = "rectangular")]
    Orthogonal,
    /// Hexagonal grid (odd rows shifted right by half a node); node (x, y) sits at
    /// (x + 0.5 (y mod 2), y sqrt(3)/2); each inner node has 6 neighbours at distance 1.
    Hexagonal,
}

impl Topology {
    /// The name used in configuration files (`rectangular` is read as `orthogonal`).
    pub fn name(self) -> String {
        word(&self)
    }
}

/// The neighbourhood function h(d, r) of grid distance d and learning radius r.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Neighbourhood {
    /// h = exp(-d^2 / (2 r^2)) (the default).
    Gaussian,
    /// h = 1 if d <= r, else 0.
    Bubble,
}

impl Neighbourhood {
    /// Value of the neighbourhood function at squared grid distance `d2` for radius `r`.
    #[inline]
    pub fn weight(self, d2: f64, r: f64) -> f64 {
        match self {
            Neighbourhood::Gaussian => (-d2 / (2.0 * r * r)).exp(),
            Neighbourhood::Bubble => {
                if d2 <= r * r + 1e-12 {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}

/// How a value decays from its initial to its final value over training.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Decay {
    /// v(p) = v0 (v1 / v0)^p: geometric decay (the default).
    Exponential,
    /// v(p) = v0 + (v1 - v0) p.
    Linear,
    /// v(p) = v0: no decay (the final value is ignored).
    #[serde(alias = "none")]
    Constant,
}

/// A decaying value: `initial` at the start of training, `last` at its end.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Schedule {
    /// Value at the first training step.
    pub initial: f64,
    /// Value at the last training step (both must be > 0 for exponential decay).
    pub last: f64,
    /// Shape of the decay.
    pub decay: Decay,
}

impl Schedule {
    /// Value at training progress `p` in [0, 1] (clamped).
    #[inline]
    pub fn at(&self, p: f64) -> f64 {
        let p = p.clamp(0.0, 1.0);
        match self.decay {
            Decay::Exponential => self.initial * (self.last / self.initial).powf(p),
            Decay::Linear => self.initial + (self.last - self.initial) * p,
            Decay::Constant => self.initial,
        }
    }
}

/// Settings to train a stand-alone map on a data set (sequential presentation, cycling).
#[derive(Debug, Clone, PartialEq)]
pub struct SomParams {
    /// Number of grid rows (>= 1).
    pub rows: usize,
    /// Number of grid columns (>= 1).
    pub cols: usize,
    /// Grid topology.
    pub topology: Topology,
    /// Neighbourhood function.
    pub neighbourhood: Neighbourhood,
    /// Learning factor schedule (values in (0, 1]).
    pub learning_factor: Schedule,
    /// Learning radius schedule in grid units (values > 0).
    pub learning_radius: Schedule,
    /// Number of training steps (samples presented).
    pub steps: usize,
    /// Seed of the random initial weights.
    pub seed: u64,
}

impl SomParams {
    /// Defaults for a `rows` x `cols` map: orthogonal, gaussian, learning factor 0.5 -> 0.01,
    /// radius max(rows, cols)/2 -> 0.5, both exponential, 1000 steps, seed 0.
    pub fn new(rows: usize, cols: usize) -> Self {
        SomParams {
            rows,
            cols,
            topology: Topology::Orthogonal,
            neighbourhood: Neighbourhood::Gaussian,
            learning_factor: Schedule {
                initial: 0.5,
                last: 0.01,
                decay: Decay::Exponential,
            },
            learning_radius: Schedule {
                initial: (rows.max(cols) as f64 / 2.0).max(0.5),
                last: 0.5,
                decay: Decay::Exponential,
            },
            steps: 1000,
            seed: 0,
        }
    }
}
