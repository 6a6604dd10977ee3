//! The discrete dynamic movement primitive (DMP; Ijspeert, Nakanishi, Hoffmann, Pastor and
//! Schaal 2013), a baseline learned from several demonstrations and conditioned on its start
//! and its goal.
//!
//! Time is counted in samples: a demonstration of `n` samples lasts `T = n - 1`. Each variable
//! follows the transformation system `T² ÿ = α (β (g - y) - T ẏ) + f(x)`, a spring pulled to
//! the goal `g` and shaped by the forcing term `f(x) = x Σ ψᵢ(x) wᵢ / Σ ψᵢ(x)` of the
//! canonical phase `x = 0.01^(t / T)` (1 at the start, 0.01 at the end). The `basis`
//! Gaussians ψᵢ are centred at the phases of evenly spaced times, each as wide as makes it
//! `overlap` high at its neighbour's centre. As in `movement_primitives` (the Python package
//! the tests check against, docs/METRICS.md) the forcing term is not scaled by `g - y₀`: a
//! gesture that ends where it starts (most of the Nao's) keeps its shape instead of
//! vanishing.
//!
//! Learning pools every demonstration: per demonstration `k` (its own `T_k`, its own goal, its
//! last velocity and acceleration taken as 0) the target `T_k² ÿ - α (β (g_k - y) - T_k ẏ)`
//! from central differences, and one least-squares fit of the weights over all of them
//! (ridge `ridge` x the samples). A reproduction starts at rest at the given posture, is pulled
//! to the given goal (by default the demonstrations' mean end) and lasts their mean duration,
//! integrated with one Runge-Kutta step per sample. The DMP takes no via-point: its only
//! conditions are its start and its goal.

use nalgebra::DMatrix;

use crate::demos::Demonstration;

mod stepper;
#[cfg(test)]
mod tests;

pub use stepper::{DmpLoop, DmpStepper};

/// What can go wrong configuring, fitting or reproducing a DMP.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DmpError {
    /// A setting out of its range ([`DmpSettings::check`]).
    #[error("invalid DMP setting `{name}` = {value}: allowed {allowed}")]
    InvalidSetting {
        /// The setting.
        name: &'static str,
        /// The rejected value, as text.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// No demonstration, or one of fewer than 3 samples (no acceleration to learn).
    #[error("{demo}: {len} sample(s); the DMP needs at least 3 per demonstration")]
    TooShort {
        /// The demonstration (`no demonstration` when there is none).
        demo: String,
        /// Its samples.
        len: usize,
    },
    /// A row not as wide as the first demonstration's first row, or a value not finite.
    #[error("{demo}: row {row} is not {expected} finite values")]
    BadRow {
        /// The demonstration.
        demo: String,
        /// The row, from 0.
        row: usize,
        /// Values per row.
        expected: usize,
    },
    /// A start or goal that is not one finite value per variable.
    #[error("DMP {what} {found:?}: needs {expected} finite values")]
    BadPosture {
        /// `start` or `goal`.
        what: &'static str,
        /// The posture given.
        found: Vec<f64>,
        /// Values needed.
        expected: usize,
    },
}

/// The settings of a DMP; [`DmpSettings::check`] validates them. The defaults are
/// `movement_primitives`' (α 25, β 6.25, overlap 0.8, no ridge) with more basis functions
/// than its 10: a gesture of several swings needs about five per swing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DmpSettings {
    /// Basis functions per variable, 2..=200.
    pub basis: usize,
    /// The spring's gain α (β is α / 4: critically damped); finite, > 0.
    pub alpha: f64,
    /// A basis function's height at its neighbour's centre, in (0, 1).
    pub overlap: f64,
    /// Ridge of the weights' fit per sample of the demonstrations; finite, >= 0.
    pub ridge: f64,
}

impl Default for DmpSettings {
    fn default() -> Self {
        DmpSettings {
            basis: 50,
            alpha: 25.0,
            overlap: 0.8,
            ridge: 0.0,
        }
    }
}

/// The phase at the end of the movement.
const FINAL_PHASE: f64 = 0.01;

impl DmpSettings {
    /// The settings, or an error naming the first field out of range and what is allowed.
    pub fn check(self) -> Result<Self, DmpError> {
        let bad = |name, value: String, allowed| DmpError::InvalidSetting {
            name,
            value,
            allowed,
        };
        if !(2..=200).contains(&self.basis) {
            return Err(bad("basis", self.basis.to_string(), "2..=200"));
        }
        if !(self.alpha.is_finite() && self.alpha > 0.0) {
            return Err(bad("alpha", self.alpha.to_string(), "a finite number > 0"));
        }
        if !(self.overlap > 0.0 && self.overlap < 1.0) {
            return Err(bad("overlap", self.overlap.to_string(), "between 0 and 1"));
        }
        if !(self.ridge.is_finite() && self.ridge >= 0.0) {
            return Err(bad("ridge", self.ridge.to_string(), "a finite number >= 0"));
        }
        Ok(self)
    }

    /// Learn the forcing term of `demos` (checked first: at least one, each of at least 3
    /// samples, all as wide, every value finite).
    pub fn fit(self, demos: &[Demonstration]) -> Result<Dmp, DmpError> {
        let s = self.check()?;
        let width = check_demos(demos)?;
        let (centers, widths) = basis(s.basis, s.overlap);
        let rows: usize = demos.iter().map(Demonstration::len).sum();
        let mut x = DMatrix::zeros(rows, s.basis);
        let mut f = DMatrix::zeros(rows, width);
        let mut r = 0;
        for d in demos {
            let t_end = (d.len() - 1) as f64;
            let goal = &d.rows[d.len() - 1];
            let (vel, acc) = derivatives(&d.rows);
            for (t, y) in d.rows.iter().enumerate() {
                let features = forcing_features(phase(t as f64 / t_end), &centers, &widths);
                x.row_mut(r).copy_from_slice(&features);
                for j in 0..width {
                    f[(r, j)] = t_end * t_end * acc[t][j]
                        - s.alpha * (s.alpha / 4.0 * (goal[j] - y[j]) - t_end * vel[t][j]);
                }
                r += 1;
            }
        }
        let mut gram = x.transpose() * &x;
        for i in 0..s.basis {
            gram[(i, i)] += s.ridge * rows as f64;
        }
        let weights = gram
            .pseudo_inverse(1e-12)
            .expect("a non-negative tolerance is accepted")
            * x.transpose()
            * f;
        let mean_row = |pick: fn(&Demonstration) -> &Vec<f64>| -> Vec<f64> {
            (0..width)
                .map(|j| demos.iter().map(|d| pick(d)[j]).sum::<f64>() / demos.len() as f64)
                .collect()
        };
        let extent = (0..width)
            .map(|j| {
                let values = demos.iter().flat_map(|d| d.rows.iter().map(move |r| r[j]));
                let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                });
                (hi - lo).powi(2)
            })
            .sum::<f64>()
            .sqrt();
        Ok(Dmp {
            settings: s,
            centers,
            widths,
            weights,
            samples: (rows as f64 / demos.len() as f64).round() as usize,
            goal: mean_row(|d| &d.rows[d.rows.len() - 1]),
            extent,
        })
    }
}

/// The demonstrations' width, or the first problem found.
fn check_demos(demos: &[Demonstration]) -> Result<usize, DmpError> {
    let first = demos.first().ok_or(DmpError::TooShort {
        demo: "no demonstration".into(),
        len: 0,
    })?;
    let width = first.rows.first().map_or(0, Vec::len);
    for d in demos {
        if d.len() < 3 {
            return Err(DmpError::TooShort {
                demo: d.source.clone(),
                len: d.len(),
            });
        }
        if let Some(row) = d
            .rows
            .iter()
            .position(|r| r.len() != width || width == 0 || r.iter().any(|v| !v.is_finite()))
        {
            return Err(DmpError::BadRow {
                demo: d.source.clone(),
                row,
                expected: width.max(1),
            });
        }
    }
    Ok(width)
}

/// The canonical phase at the fraction `z` (0..1) of the movement.
fn phase(z: f64) -> f64 {
    FINAL_PHASE.powf(z)
}

/// The basis functions' centres (the phases of `n` evenly spaced times) and widths.
fn basis(n: usize, overlap: f64) -> (Vec<f64>, Vec<f64>) {
    let centers: Vec<f64> = (0..n).map(|i| phase(i as f64 / (n - 1) as f64)).collect();
    let mut widths: Vec<f64> = centers
        .windows(2)
        .map(|c| -overlap.ln() / (c[1] - c[0]).powi(2))
        .collect();
    widths.push(widths[n - 2]);
    (centers, widths)
}

/// The forcing term's features at phase `x`: x ψᵢ(x) / Σ ψ(x).
fn forcing_features(x: f64, centers: &[f64], widths: &[f64]) -> Vec<f64> {
    let psi: Vec<f64> = centers
        .iter()
        .zip(widths)
        .map(|(c, h)| (-h * (x - c).powi(2)).exp())
        .collect();
    let sum: f64 = psi.iter().sum::<f64>().max(f64::MIN_POSITIVE);
    psi.into_iter().map(|p| x * p / sum).collect()
}

/// Velocity and acceleration per sample by central differences (one-sided at the ends), the
/// last sample's taken as 0: the movement ends at rest.
fn derivatives(rows: &[Vec<f64>]) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let gradient = |v: &[Vec<f64>]| -> Vec<Vec<f64>> {
        let n = v.len();
        (0..n)
            .map(|t| {
                let (a, b, h) = match t {
                    0 => (0, 1, 1.0),
                    _ if t == n - 1 => (n - 2, n - 1, 1.0),
                    _ => (t - 1, t + 1, 2.0),
                };
                v[b].iter().zip(&v[a]).map(|(q, p)| (q - p) / h).collect()
            })
            .collect()
    };
    let zero = |mut v: Vec<Vec<f64>>| {
        v.last_mut().expect("at least 3 samples").fill(0.0);
        v
    };
    let vel = zero(gradient(rows));
    let acc = zero(gradient(&vel));
    (vel, acc)
}

/// A learned DMP.
#[derive(Debug, Clone)]
pub struct Dmp {
    settings: DmpSettings,
    centers: Vec<f64>,
    widths: Vec<f64>,
    /// basis x variables.
    weights: DMatrix<f64>,
    samples: usize,
    goal: Vec<f64>,
    /// The diagonal of the demonstrations' bounding box: the scale of a tracking error.
    extent: f64,
}

impl Dmp {
    /// Values per posture.
    pub fn width(&self) -> usize {
        self.goal.len()
    }

    /// Samples of a reproduction: the demonstrations' mean, rounded.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// The demonstrations' mean last posture: the goal when none is given.
    pub fn mean_goal(&self) -> &[f64] {
        &self.goal
    }

    /// The settings it was learned with.
    pub fn settings(&self) -> DmpSettings {
        self.settings
    }

    /// The forcing term at the fraction `z` of the movement, one value per variable.
    fn forcing(&self, z: f64) -> Vec<f64> {
        let phi = forcing_features(phase(z.min(1.0)), &self.centers, &self.widths);
        (0..self.width())
            .map(|j| (0..phi.len()).map(|i| phi[i] * self.weights[(i, j)]).sum())
            .collect()
    }

    /// The postures of a movement from rest at `start` to `goal` (the demonstrations' mean
    /// end when `None`) over [`Dmp::samples`] samples.
    pub fn reproduce(
        &self,
        start: &[f64],
        goal: Option<&[f64]>,
    ) -> Result<Vec<Vec<f64>>, DmpError> {
        let w = self.width();
        self.check_posture("start", start)?;
        let goal = goal.unwrap_or(&self.goal);
        self.check_posture("goal", goal)?;
        let mut y = start.to_vec();
        let mut v = vec![0.0; w];
        let mut out = Vec::with_capacity(self.samples);
        out.push(y.clone());
        for t in 1..self.samples {
            let t0 = (t - 1) as f64;
            self.integrate(&mut y, &mut v, goal, [t0, t0 + 0.5, t0 + 1.0]);
            out.push(y.clone());
        }
        Ok(out)
    }

    /// `p` as the DMP's `what` (start or goal): one finite value per variable.
    fn check_posture(&self, what: &'static str, p: &[f64]) -> Result<(), DmpError> {
        if p.len() == self.width() && p.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(DmpError::BadPosture {
                what,
                found: p.to_vec(),
                expected: self.width(),
            })
        }
    }

    /// The duration `T` of a reproduction, samples.
    fn t_end(&self) -> f64 {
        (self.samples.max(2) - 1) as f64
    }

    /// One Runge-Kutta step of one sample of the transformation system from position `y`
    /// and velocity `v` (per sample) towards `goal`, its forcing term at the times `at`
    /// (samples: the step's start, middle and end).
    fn integrate(&self, y: &mut [f64], v: &mut [f64], goal: &[f64], at: [f64; 3]) {
        let w = self.width();
        let t_end = self.t_end();
        let (a, b) = (self.settings.alpha, self.settings.alpha / 4.0);
        // acceleration per sample² of position y, velocity v at the fraction z
        let acc = |y: &[f64], v: &[f64], f: &[f64]| -> Vec<f64> {
            (0..w)
                .map(|j| (a * (b * (goal[j] - y[j]) - t_end * v[j]) + f[j]) / (t_end * t_end))
                .collect()
        };
        let axpy = |x: &[f64], k: f64, d: &[f64]| -> Vec<f64> {
            x.iter().zip(d).map(|(x, d)| x + k * d).collect()
        };
        let (f0, fh, f1) = (
            self.forcing(at[0] / t_end),
            self.forcing(at[1] / t_end),
            self.forcing(at[2] / t_end),
        );
        let k0 = acc(y, v, &f0);
        let c1 = axpy(v, 0.5, &k0);
        let k1 = acc(&axpy(y, 0.5, v), &c1, &fh);
        let c2 = axpy(v, 0.5, &k1);
        let k2 = acc(&axpy(y, 0.5, &c1), &c2, &fh);
        let c3 = axpy(v, 1.0, &k2);
        let k3 = acc(&axpy(y, 1.0, &c2), &c3, &f1);
        for j in 0..w {
            y[j] += v[j] + (k0[j] + k1[j] + k2[j]) / 6.0;
            v[j] += (k0[j] + 2.0 * k1[j] + 2.0 * k2[j] + k3[j]) / 6.0;
        }
    }
}
