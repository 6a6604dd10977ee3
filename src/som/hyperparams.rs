//! Settings of one Kohonen map: topology, neighbourhood function and decay schedules.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::algorithm::{SelfOrganizingMap, SomError};

/// Arrangement of the nodes on the 2-D grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Topology {
    /// Rectangular grid; node (x, y) sits at (x, y); its neighbours are the 8 surrounding nodes.
    Orthogonal,
    /// Hexagonal grid (odd rows shifted right by half a node); node (x, y) sits at
    /// (x + 0.5 (y mod 2), y sqrt(3)/2); each inner node has 6 neighbours at distance 1.
    Hexagonal,
}

impl Topology {
    /// The name used in configuration files.
    pub fn name(self) -> &'static str {
        match self {
            Topology::Orthogonal => "orthogonal",
            Topology::Hexagonal => "hexagonal",
        }
    }
    /// Parse a configuration name (`orthogonal`/`rectangular`, `hexagonal`).
    pub fn from_name(s: &str) -> Option<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "orthogonal" | "rectangular" => Some(Topology::Orthogonal),
            "hexagonal" => Some(Topology::Hexagonal),
            _ => None,
        }
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
    /// The name used in configuration files.
    pub fn name(self) -> &'static str {
        match self {
            Neighbourhood::Gaussian => "gaussian",
            Neighbourhood::Bubble => "bubble",
        }
    }
    /// Parse a configuration name.
    pub fn from_name(s: &str) -> Option<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "gaussian" => Some(Neighbourhood::Gaussian),
            "bubble" => Some(Neighbourhood::Bubble),
            _ => None,
        }
    }
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
    Constant,
}

impl Decay {
    /// The name used in configuration files.
    pub fn name(self) -> &'static str {
        match self {
            Decay::Exponential => "exponential",
            Decay::Linear => "linear",
            Decay::Constant => "constant",
        }
    }
    /// Parse a configuration name.
    pub fn from_name(s: &str) -> Option<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "exponential" => Some(Decay::Exponential),
            "linear" => Some(Decay::Linear),
            "constant" | "none" => Some(Decay::Constant),
            _ => None,
        }
    }
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

    /// Check the settings and train a map on `data` (all rows the same length), presenting
    /// the samples in order and cycling; the initial weights are drawn uniformly, from the
    /// seed, inside the data's bounding box.
    pub fn fit(&self, data: &[Vec<f64>]) -> Result<SelfOrganizingMap, SomError> {
        if self.rows == 0 || self.cols == 0 {
            return Err(SomError::InvalidParam {
                name: "rows/cols",
                value: format!("{}x{}", self.rows, self.cols),
            });
        }
        for (name, s, max) in [
            ("learning_factor", &self.learning_factor, 1.0),
            ("learning_radius", &self.learning_radius, f64::INFINITY),
        ] {
            for v in [s.initial, s.last] {
                if !(v > 0.0 && v <= max) {
                    return Err(SomError::InvalidParam {
                        name,
                        value: v.to_string(),
                    });
                }
            }
        }
        let dim = data.first().map(|r| r.len()).ok_or(SomError::EmptyData)?;
        if dim == 0 {
            return Err(SomError::EmptyData);
        }
        let mut lo = vec![f64::INFINITY; dim];
        let mut hi = vec![f64::NEG_INFINITY; dim];
        for (i, r) in data.iter().enumerate() {
            if r.len() != dim {
                return Err(SomError::DimensionMismatch {
                    expected: dim,
                    found: r.len(),
                    row: i,
                });
            }
            for (d, &v) in r.iter().enumerate() {
                if !v.is_finite() {
                    return Err(SomError::NonFinite { row: i, column: d });
                }
                lo[d] = lo[d].min(v);
                hi[d] = hi[d].max(v);
            }
        }
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        let mut som = SelfOrganizingMap::new_random(
            self.rows,
            self.cols,
            dim,
            self.topology,
            &lo,
            &hi,
            &mut rng,
        );
        let denom = (self.steps.max(2) - 1) as f64;
        for t in 0..self.steps {
            let x = &data[t % data.len()];
            let p = t as f64 / denom;
            let (b, _) = som.bmu(x);
            som.update(
                x,
                None,
                b,
                self.learning_factor.at(p),
                self.learning_radius.at(p),
                self.neighbourhood,
            );
        }
        Ok(som)
    }
}
