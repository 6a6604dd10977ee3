//! Probabilistic Movement Primitives (ProMP; Paraschos, Daniel, Peters and Neumann, 2013),
//! a baseline conditioned on the initial posture.
//!
//! Each demonstration (rows of `stateLength` values at one sample period) is given its own
//! phase z = t / (T - 1) in [0, 1], so demonstrations of different durations line up by
//! phase; the model keeps their mean duration in samples for reproduction. Every dimension is
//! a weighted sum of the same `basis` normalised Gaussian radial basis functions of the phase
//! ([`basis_row`]). Per demonstration the weights of each dimension are fitted by ridge
//! regression and stacked into one vector (dimension-major); the weight distribution is the
//! Gaussian of those vectors over the demonstrations (mean and full sample covariance) plus a
//! diagonal term ([`PrompSettings::regulariser`] times the sample covariance's mean diagonal,
//! at least [`MIN_PRIOR_VARIANCE`]). With the 3-7 demonstrations that are the normal case the
//! sample covariance has rank 2-6 in a space of `basis` x `stateLength` weights: the diagonal
//! term keeps it positive definite, and it keeps conditioning from reading spurious
//! correlations into a few demonstrations (where the starts differ only by noise, the sample
//! covariance alone would bend the whole trajectory to meet a new start; the diagonal term
//! moves mostly the weights of the first basis functions). [`Promp::reproduce`] conditions that distribution on the postures at z = 0 equal
//! to the given initial posture (Gaussian conditioning with observation noise
//! [`PrompSettings::observation_noise`]) and returns the conditioned mean trajectory.

use nalgebra::{DMatrix, DVector};

use crate::demos::Demonstration;

mod stepper;
#[cfg(test)]
mod tests;

pub use stepper::{PrompReplan, PrompStepper};

/// What can go wrong configuring, fitting or reproducing a ProMP.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PrompError {
    /// A setting out of its range (checked by [`PrompSettings::check`]).
    #[error("invalid ProMP setting `{name}` = {value}: allowed {allowed}")]
    InvalidSetting {
        /// The setting.
        name: &'static str,
        /// The rejected value, as text.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// Fewer than two demonstrations: one has no spread to learn.
    #[error(
        "ProMP needs at least 2 demonstrations to estimate their weight distribution, got {found}"
    )]
    TooFewDemonstrations {
        /// Demonstrations given.
        found: usize,
    },
    /// A demonstration of fewer than two samples has no phase to fit.
    #[error("{demo}: {len} sample(s); ProMP needs at least 2 per demonstration")]
    TooShort {
        /// The demonstration.
        demo: String,
        /// Its samples.
        len: usize,
    },
    /// A demonstration whose rows are not all as wide as the first demonstration's.
    #[error("{demo}: row {row} has {found} values, the demonstrations have {expected}")]
    Width {
        /// The demonstration.
        demo: String,
        /// The row, from 0.
        row: usize,
        /// Its values.
        found: usize,
        /// The width of the first demonstration's first row (at least 1).
        expected: usize,
    },
    /// A value that is NaN or infinite.
    #[error("{demo}: row {row}, column {column} is {value}; ProMP needs finite values")]
    NonFinite {
        /// The demonstration.
        demo: String,
        /// The row, from 0.
        row: usize,
        /// The column, from 0.
        column: usize,
        /// The value.
        value: f64,
    },
    /// An initial posture that is not one finite value per dimension.
    #[error("initial posture {found:?}: needs {expected} finite values")]
    BadInitial {
        /// The posture given.
        found: Vec<f64>,
        /// Values needed.
        expected: usize,
    },
    /// More weights than the covariance may hold: variables x basis functions above
    /// [`MAX_WEIGHTS`] (its covariance alone would take more than 128 MiB).
    #[error(
        "ProMP: {width} variables x {basis} basis functions = {weights} weights, more than the \
         {max} a weight covariance may hold; use fewer basis functions or variables"
    )]
    TooManyWeights {
        /// Variables per sample.
        width: usize,
        /// Basis functions per variable.
        basis: usize,
        /// Their product.
        weights: usize,
        /// [`MAX_WEIGHTS`].
        max: usize,
    },
    /// A matrix that should be positive definite is not (values too large for the
    /// regularisers).
    #[error("ProMP: the {what} is not positive definite; raise `ridge` or `regulariser`")]
    NotPositiveDefinite {
        /// Which matrix.
        what: &'static str,
    },
}

/// The most weights (variables x basis functions) a model may have: the full covariance of
/// 4,096 weights takes 128 MiB, and a wide file must get an error, not exhaust the memory.
pub const MAX_WEIGHTS: usize = 4096;

/// The least variance added to the diagonal of the weights' covariance, in the data's units
/// squared: demonstrations that agree exactly still give a positive definite covariance, and
/// a start none of them had can still be reached.
pub const MIN_PRIOR_VARIANCE: f64 = 1e-6;

/// The settings of a ProMP; [`PrompSettings::check`] validates them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrompSettings {
    /// Basis functions per dimension, 2..=100.
    pub basis: usize,
    /// Ridge regulariser of each demonstration's weight fit, per sample (the penalty is
    /// `ridge` x the demonstration's sample count, so it does not depend on its length);
    /// finite, > 0.
    pub ridge: f64,
    /// Added to the diagonal of the weights' covariance, as a fraction of the sample
    /// covariance's mean diagonal; finite, > 0.
    pub regulariser: f64,
    /// Variance of the observation of the initial posture when conditioning, in the data's
    /// units squared; finite, > 0. Small against [`MIN_PRIOR_VARIANCE`]: the reproduction
    /// starts at the given posture.
    pub observation_noise: f64,
}

impl Default for PrompSettings {
    fn default() -> Self {
        PrompSettings {
            basis: 20,
            ridge: 1e-6,
            regulariser: 0.1,
            observation_noise: 1e-9,
        }
    }
}

impl PrompSettings {
    /// The settings, or an error naming the first field out of range and what is allowed.
    pub fn check(self) -> Result<Self, PrompError> {
        let bad = |name, value: String, allowed| PrompError::InvalidSetting {
            name,
            value,
            allowed,
        };
        if !(2..=100).contains(&self.basis) {
            return Err(bad("basis", self.basis.to_string(), "2..=100"));
        }
        for (name, value) in [
            ("ridge", self.ridge),
            ("regulariser", self.regulariser),
            ("observation_noise", self.observation_noise),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(bad(name, value.to_string(), "a finite number > 0"));
            }
        }
        Ok(self)
    }

    /// Fit the weight distribution of `demos` (checked first: at least 2, each of at least
    /// 2 samples, all as wide, every value finite).
    pub fn fit(self, demos: &[Demonstration]) -> Result<Promp, PrompError> {
        let s = self.check()?;
        let width = check_demos(demos)?;
        let n = s.basis;
        let weights = width.saturating_mul(n);
        if weights > MAX_WEIGHTS {
            return Err(PrompError::TooManyWeights {
                width,
                basis: n,
                weights,
                max: MAX_WEIGHTS,
            });
        }
        let weights: Vec<DVector<f64>> = demos
            .iter()
            .map(|d| demo_weights(&d.rows, width, n, s.ridge))
            .collect::<Result<_, _>>()?;
        let m = weights.len() as f64;
        let dim = width * n;
        let mean = weights.iter().fold(DVector::zeros(dim), |acc, w| acc + w) / m;
        let mut cov = weights.iter().fold(DMatrix::zeros(dim, dim), |acc, w| {
            let c = w - &mean;
            acc + &c * c.transpose()
        }) / (m - 1.0);
        let prior = (s.regulariser * cov.trace() / dim as f64).max(MIN_PRIOR_VARIANCE);
        for i in 0..dim {
            cov[(i, i)] += prior;
        }
        let samples = (demos.iter().map(|d| d.rows.len() as f64).sum::<f64>() / m).round() as usize;
        Ok(Promp {
            settings: s,
            width,
            samples,
            mean,
            cov,
        })
    }
}

/// The demonstrations' width, or the first problem found.
fn check_demos(demos: &[Demonstration]) -> Result<usize, PrompError> {
    if demos.len() < 2 {
        return Err(PrompError::TooFewDemonstrations { found: demos.len() });
    }
    let expected = demos[0].rows.first().map_or(0, Vec::len).max(1);
    for d in demos {
        if d.rows.len() < 2 {
            return Err(PrompError::TooShort {
                demo: d.source.clone(),
                len: d.rows.len(),
            });
        }
        for (row, r) in d.rows.iter().enumerate() {
            if r.len() != expected {
                return Err(PrompError::Width {
                    demo: d.source.clone(),
                    row,
                    found: r.len(),
                    expected,
                });
            }
            if let Some((column, &value)) = r.iter().enumerate().find(|(_, v)| !v.is_finite()) {
                return Err(PrompError::NonFinite {
                    demo: d.source.clone(),
                    row,
                    column,
                    value,
                });
            }
        }
    }
    Ok(expected)
}

/// The `n` normalised Gaussian basis functions at phase `z`: centres evenly spaced over
/// [-m, 1 + m] with the margin m = 1 / (2 (n - 1)) (so the ends of the phase are covered as
/// well as its middle), width (standard deviation) the centres' spacing; each value divided
/// by their sum, so they add up to 1 at every phase.
pub fn basis_row(z: f64, n: usize) -> Vec<f64> {
    let margin = 0.5 / (n - 1) as f64;
    let spacing = (1.0 + 2.0 * margin) / (n - 1) as f64;
    let raw: Vec<f64> = (0..n)
        .map(|i| {
            let c = -margin + i as f64 * spacing;
            (-0.5 * ((z - c) / spacing).powi(2)).exp()
        })
        .collect();
    let sum: f64 = raw.iter().sum();
    raw.into_iter().map(|v| v / sum).collect()
}

/// The basis matrix of `samples` samples (one row per sample, phase t / (samples - 1)).
fn basis_matrix(samples: usize, n: usize) -> DMatrix<f64> {
    let last = (samples - 1).max(1) as f64;
    let rows: Vec<f64> = (0..samples)
        .flat_map(|t| basis_row(t as f64 / last, n))
        .collect();
    DMatrix::from_row_slice(samples, n, &rows)
}

/// One demonstration's weights: per dimension (Φ'Φ + ridge T I) w = Φ'y, stacked.
fn demo_weights(
    rows: &[Vec<f64>],
    width: usize,
    n: usize,
    ridge: f64,
) -> Result<DVector<f64>, PrompError> {
    let phi = basis_matrix(rows.len(), n);
    let mut gram = phi.transpose() * &phi;
    for i in 0..n {
        gram[(i, i)] += ridge * rows.len() as f64;
    }
    let chol = gram.cholesky().ok_or(PrompError::NotPositiveDefinite {
        what: "basis Gram matrix",
    })?;
    let mut w = DVector::zeros(width * n);
    for d in 0..width {
        let y = DVector::from_iterator(rows.len(), rows.iter().map(|r| r[d]));
        w.rows_mut(d * n, n)
            .copy_from(&chol.solve(&(phi.transpose() * y)));
    }
    Ok(w)
}

/// A fitted ProMP: the weight distribution of the demonstrations.
#[derive(Debug, Clone)]
pub struct Promp {
    settings: PrompSettings,
    width: usize,
    samples: usize,
    mean: DVector<f64>,
    cov: DMatrix<f64>,
}

impl Promp {
    /// Values per posture.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Samples of a reproduction: the demonstrations' mean duration, rounded.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// The settings it was fitted with.
    pub fn settings(&self) -> PrompSettings {
        self.settings
    }

    /// The mean trajectory of weights `w` at every sample of the mean duration.
    fn trajectory(&self, w: &DVector<f64>) -> Vec<Vec<f64>> {
        let n = self.settings.basis;
        let phi = basis_matrix(self.samples, n);
        (0..self.samples)
            .map(|t| {
                (0..self.width)
                    .map(|d| phi.row(t).dot(&w.rows(d * n, n).transpose()))
                    .collect()
            })
            .collect()
    }

    /// The unconditioned mean trajectory (where the demonstrations go on average).
    pub fn mean_trajectory(&self) -> Vec<Vec<f64>> {
        self.trajectory(&self.mean)
    }

    /// The mean of the weight distribution conditioned on the posture at phase 0 being
    /// `initial`, as postures at every sample of the mean duration; it starts at (within the
    /// observation noise of) `initial`.
    pub fn reproduce(&self, initial: &[f64]) -> Result<Vec<Vec<f64>>, PrompError> {
        Ok(self.conditioned(initial, &[])?.0)
    }

    /// The distribution conditioned on `initial` at phase 0 and on each `(phase, posture)` of
    /// `points` (Gaussian conditioning on all of them at once, each observed with
    /// [`PrompSettings::observation_noise`]): its mean at every sample of the mean duration,
    /// and the central 95 % band of its trajectories (the mean ± 1.96 standard deviations of
    /// each variable at each sample).
    pub fn conditioned(
        &self,
        initial: &[f64],
        points: &[(f64, Vec<f64>)],
    ) -> Result<(Vec<Vec<f64>>, crate::condition::ConfidenceBand), PrompError> {
        let all: Vec<(f64, &[f64])> = std::iter::once((0.0, initial))
            .chain(points.iter().map(|(p, v)| (*p, v.as_slice())))
            .collect();
        let (mean, sigma_ht, chol) = self.condition(&all)?;
        let (n, w) = (self.settings.basis, self.width);
        let cov = &self.cov - &sigma_ht * chol.solve(&sigma_ht.transpose());
        let rows = self.trajectory(&mean);
        let phi = basis_matrix(self.samples, n);
        let half: Vec<Vec<f64>> = (0..self.samples)
            .map(|t| {
                (0..w)
                    .map(|d| {
                        let p = phi.row(t).transpose();
                        let block = cov.view((d * n, d * n), (n, n));
                        1.96 * (p.dot(&(block * &p))).max(0.0).sqrt()
                    })
                    .collect()
            })
            .collect();
        let band = crate::condition::ConfidenceBand::around(&rows, &half);
        Ok((rows, band))
    }

    /// The weight distribution conditioned on each `(phase, posture)` of `all` at once
    /// (Gaussian conditioning, each observed with [`PrompSettings::observation_noise`]): the
    /// conditioned mean, `Σ Hᵀ` and the Cholesky factor of `H Σ Hᵀ + noise` (from which the
    /// conditioned covariance is `Σ - Σ Hᵀ (H Σ Hᵀ + noise)⁻¹ H Σ`).
    #[allow(clippy::type_complexity)]
    fn condition(
        &self,
        all: &[(f64, &[f64])],
    ) -> Result<
        (
            DVector<f64>,
            DMatrix<f64>,
            nalgebra::Cholesky<f64, nalgebra::Dyn>,
        ),
        PrompError,
    > {
        for (_, p) in all {
            if p.len() != self.width || p.iter().any(|v| !v.is_finite()) {
                return Err(PrompError::BadInitial {
                    found: p.to_vec(),
                    expected: self.width,
                });
            }
        }
        let (n, w) = (self.settings.basis, self.width);
        // H (points x width, width x basis): block-diagonal, the basis at each point's phase
        let mut h = DMatrix::zeros(all.len() * w, w * n);
        let mut observed = DVector::zeros(all.len() * w);
        for (k, (phase, posture)) in all.iter().enumerate() {
            let phi = basis_row(phase.clamp(0.0, 1.0), n);
            for d in 0..w {
                observed[k * w + d] = posture[d];
                for (i, v) in phi.iter().enumerate() {
                    h[(k * w + d, d * n + i)] = *v;
                }
            }
        }
        let sigma_ht = &self.cov * h.transpose();
        let mut s = &h * &sigma_ht;
        for i in 0..s.nrows() {
            s[(i, i)] += self.settings.observation_noise;
        }
        let chol = s.cholesky().ok_or(PrompError::NotPositiveDefinite {
            what: "covariance of the conditioned postures",
        })?;
        let mean = &self.mean + &sigma_ht * chol.solve(&(observed - &h * &self.mean));
        Ok((mean, sigma_ht, chol))
    }

    /// The mean of the distribution conditioned on each `(phase, posture)` of `points` at
    /// once, at the samples `from` to the last of the mean duration (phase `t / (samples -
    /// 1)`).
    pub(crate) fn conditioned_from(
        &self,
        points: &[(f64, &[f64])],
        from: usize,
    ) -> Result<Vec<Vec<f64>>, PrompError> {
        let (mean, _, _) = self.condition(points)?;
        let n = self.settings.basis;
        let last = (self.samples - 1).max(1) as f64;
        Ok((from.min(self.samples - 1)..self.samples)
            .map(|t| {
                let phi = basis_row(t as f64 / last, n);
                (0..self.width)
                    .map(|d| (0..n).map(|i| phi[i] * mean[d * n + i]).sum())
                    .collect()
            })
            .collect())
    }
}
