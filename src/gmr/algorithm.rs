//! The Gaussian mixture over `[t, q]` (EM by linfa-clustering) and Gaussian mixture
//! regression of `q` on `t`.
//!
//! **Why linfa-clustering.** Its `GaussianMixtureModel` gives full covariances, an explicit
//! `reg_covariance`, k-means initialisation and a caller-supplied RNG (seeded ChaCha8 here),
//! which is everything GMR needs. Measured on this project's 2-core machine: adding
//! linfa 0.8 + linfa-clustering 0.8 + ndarray 0.16 adds 38 crates and 26 s to a dev build of
//! the library (a cold build of linfa-clustering alone with the project's profile: 86 s);
//! acceptable, so EM is not hand-written. What linfa does not give is kept here: the
//! log-likelihood for BIC, the conditioning for GMR, and validation of the fitted
//! parameters (a Cholesky factor per component) before a model is accepted.
//! Two behaviours of linfa to know: EM that does not reach the tolerance within the
//! iteration budget is an error (no best-effort model), reported as
//! [`GmrError::NotConverged`]; and an empty k-means cluster is an error, reported as
//! [`GmrError::Em`].
//!
//! **GMR.** With component `k` split as `μ = [μ_t, μ_q]`,
//! `Σ = [[σ_tt, σ_tq], [σ_qt, Σ_qq]]`, the responsibility of `k` at time `t` is
//! `h_k(t) ∝ π_k 𝒩(t; μ_t, σ_tt)` (normalised over `k`, computed in the log domain), the
//! component's conditional mean `m_k(t) = μ_q + σ_qt (t − μ_t) / σ_tt` and conditional
//! covariance `C_k = Σ_qq − σ_qt σ_tq / σ_tt`. GMR returns
//! `m(t) = Σ_k h_k m_k(t)` and `C(t) = Σ_k h_k (C_k + m_k m_kᵀ) − m mᵀ`.

use linfa::prelude::*;
use linfa_clustering::{GaussianMixtureModel, GmmError};
use nalgebra::{DMatrix, DVector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use super::errors::GmrError;
use super::hyperparams::{ComponentChoice, GmrValidParams};
use super::preprocess::{preprocess, TrainingSet};
use crate::demos::Demonstration;

const LN_2PI: f64 = 1.837_877_066_409_345_5;

/// A Gaussian mixture with full covariances, every covariance checked positive definite.
#[derive(Debug, Clone, PartialEq)]
pub struct Gmm {
    weights: Vec<f64>,
    means: Vec<DVector<f64>>,
    covariances: Vec<DMatrix<f64>>,
    chol: Vec<DMatrix<f64>>,
    log_dets: Vec<f64>,
}

impl Gmm {
    /// Build a mixture from its parameters, checking them: at least one component; one
    /// mean and one `d×d` covariance per weight; finite values; weights > 0 summing to 1
    /// (within 1e-6); symmetric (within 1e-9 relative) positive definite covariances.
    pub fn new(
        weights: Vec<f64>,
        means: Vec<DVector<f64>>,
        covariances: Vec<DMatrix<f64>>,
    ) -> Result<Gmm, GmrError> {
        let invalid = |message: String| GmrError::InvalidModel { message };
        let k = weights.len();
        if k == 0 {
            return Err(invalid("a mixture needs at least one component".into()));
        }
        if means.len() != k || covariances.len() != k {
            return Err(invalid(format!(
                "{k} weights but {} means and {} covariances",
                means.len(),
                covariances.len()
            )));
        }
        let d = means[0].len();
        if d == 0 {
            return Err(invalid("mixture dimension is zero".into()));
        }
        let sum: f64 = weights.iter().sum();
        if weights.iter().any(|w| !(w.is_finite() && *w > 0.0)) || (sum - 1.0).abs() > 1e-6 {
            return Err(invalid(format!(
                "weights must be finite, > 0 and sum to 1, got {weights:?}"
            )));
        }
        let mut chol = Vec::with_capacity(k);
        let mut log_dets = Vec::with_capacity(k);
        for c in 0..k {
            let (m, s) = (&means[c], &covariances[c]);
            if m.len() != d || s.nrows() != d || s.ncols() != d {
                return Err(invalid(format!(
                    "component {c}: mean of {} and covariance of {}x{}, expected {d} and {d}x{d}",
                    m.len(),
                    s.nrows(),
                    s.ncols()
                )));
            }
            if m.iter().chain(s.iter()).any(|v| !v.is_finite()) {
                return Err(invalid(format!("component {c}: non-finite parameter")));
            }
            let scale = s.amax().max(f64::MIN_POSITIVE);
            if (s - s.transpose()).amax() > 1e-9 * scale {
                return Err(invalid(format!(
                    "component {c}: covariance is not symmetric"
                )));
            }
            let l = s
                .clone()
                .cholesky()
                .ok_or(GmrError::DegenerateCovariance {
                    component: c,
                    reg_covar: 0.0,
                })?
                .unpack();
            let log_det = 2.0 * l.diagonal().iter().map(|x| x.ln()).sum::<f64>();
            if !log_det.is_finite() {
                return Err(GmrError::DegenerateCovariance {
                    component: c,
                    reg_covar: 0.0,
                });
            }
            chol.push(l);
            log_dets.push(log_det);
        }
        Ok(Gmm {
            weights,
            means,
            covariances,
            chol,
            log_dets,
        })
    }

    /// Number of components `K`.
    pub fn n_components(&self) -> usize {
        self.weights.len()
    }
    /// Dimension `d` of the data (1 + number of state variables for the baseline).
    pub fn dim(&self) -> usize {
        self.means[0].len()
    }
    /// Mixing weights `π_k`.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
    /// Means `μ_k`.
    pub fn means(&self) -> &[DVector<f64>] {
        &self.means
    }
    /// Covariances `Σ_k` (regularisation included).
    pub fn covariances(&self) -> &[DMatrix<f64>] {
        &self.covariances
    }
    /// Number of free parameters: `(K−1) + K·d + K·d(d+1)/2`.
    pub fn n_parameters(&self) -> usize {
        let (k, d) = (self.n_components(), self.dim());
        (k - 1) + k * d + k * d * (d + 1) / 2
    }

    /// `ln p(x)` of one point (its width must be `dim()`).
    fn log_density(&self, x: &[f64]) -> f64 {
        let d = self.dim();
        let terms: Vec<f64> = (0..self.n_components())
            .map(|c| {
                let diff = DVector::from_iterator(
                    d,
                    x.iter().zip(self.means[c].iter()).map(|(a, b)| a - b),
                );
                let z = self.chol[c]
                    .solve_lower_triangular(&diff)
                    .map_or(f64::INFINITY, |z| z.norm_squared());
                self.weights[c].ln() - 0.5 * (d as f64 * LN_2PI + self.log_dets[c] + z)
            })
            .collect();
        log_sum_exp(&terms)
    }

    /// Total log-likelihood `Σ_i ln p(x_i)` of points of width `dim()`.
    pub fn log_likelihood(&self, points: &[Vec<f64>]) -> Result<f64, GmrError> {
        check_points(points, self.dim())?;
        Ok(points.iter().map(|x| self.log_density(x)).sum())
    }

    /// Bayesian information criterion `−2 ln L + p ln N` on `points`.
    pub fn bic(&self, points: &[Vec<f64>]) -> Result<f64, GmrError> {
        let ll = self.log_likelihood(points)?;
        Ok(-2.0 * ll + self.n_parameters() as f64 * (points.len() as f64).ln())
    }
}

fn log_sum_exp(v: &[f64]) -> f64 {
    let m = v.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    if !m.is_finite() {
        return m;
    }
    m + v.iter().map(|x| (x - m).exp()).sum::<f64>().ln()
}

fn check_points(points: &[Vec<f64>], width: usize) -> Result<(), GmrError> {
    for (index, p) in points.iter().enumerate() {
        if p.len() != width {
            return Err(GmrError::BadPoint {
                index,
                message: format!("{} values, expected {width}", p.len()),
            });
        }
        if p.iter().any(|v| !v.is_finite()) {
            return Err(GmrError::BadPoint {
                index,
                message: "non-finite value".into(),
            });
        }
    }
    Ok(())
}

/// The BIC of one component count tried.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct BicScore {
    /// Component count.
    pub components: usize,
    /// Total log-likelihood of the data, when the fit succeeded.
    pub log_likelihood: Option<f64>,
    /// BIC, when the fit succeeded.
    pub bic: Option<f64>,
    /// Why the fit failed, when it did.
    pub error: Option<String>,
}

impl GmrValidParams {
    /// Fit one mixture with exactly `k` components to `points` (all of one width ≥ 1,
    /// finite, at least `k` of them).
    pub fn fit_gmm_k(&self, points: &[Vec<f64>], k: usize) -> Result<Gmm, GmrError> {
        let p = self.params();
        let width = points.first().map_or(0, |x| x.len());
        if width == 0 {
            return Err(GmrError::TooFewPoints {
                points: points.len(),
                components: k,
            });
        }
        check_points(points, width)?;
        if points.len() < k || k == 0 {
            return Err(GmrError::TooFewPoints {
                points: points.len(),
                components: k,
            });
        }
        let flat: Vec<f64> = points.iter().flatten().cloned().collect();
        let records =
            ndarray::Array2::from_shape_vec((points.len(), width), flat).map_err(|e| {
                GmrError::Em {
                    components: k,
                    message: e.to_string(),
                }
            })?;
        let dataset = DatasetBase::from(records);
        let rng = ChaCha8Rng::seed_from_u64(p.seed);
        let fitted = GaussianMixtureModel::params_with_rng(k, rng)
            .reg_covariance(p.reg_covar)
            .tolerance(p.tolerance)
            .max_n_iterations(p.max_iterations)
            .n_runs(1)
            .fit(&dataset)
            .map_err(|e| match e {
                GmmError::NotConverged(_) => GmrError::NotConverged {
                    components: k,
                    max_iterations: p.max_iterations,
                },
                other => GmrError::Em {
                    components: k,
                    message: other.to_string(),
                },
            })?;
        let weights = fitted.weights().to_vec();
        let means = fitted
            .means()
            .outer_iter()
            .map(|m| DVector::from_iterator(width, m.iter().cloned()))
            .collect();
        let covariances = fitted
            .covariances()
            .outer_iter()
            .map(|c| {
                let m = DMatrix::from_fn(width, width, |i, j| c[[i, j]]);
                // symmetrise exactly: linfa's products leave 1-ulp asymmetries
                (&m + m.transpose()) * 0.5
            })
            .collect();
        Gmm::new(weights, means, covariances).map_err(|e| match e {
            GmrError::DegenerateCovariance { component, .. } => GmrError::DegenerateCovariance {
                component,
                reg_covar: p.reg_covar,
            },
            other => other,
        })
    }

    /// Fit the mixture to `points` with the configured component choice: a fixed count, or
    /// the lowest BIC over a range (counts above the number of points are not tried; counts
    /// whose fit fails are recorded and skipped; an error only when every count fails, the
    /// last error then). Returns the model and the score of every count tried.
    pub fn fit_gmm(&self, points: &[Vec<f64>]) -> Result<(Gmm, Vec<BicScore>), GmrError> {
        let (lo, hi) = match self.params().components {
            ComponentChoice::Fixed(k) => (k, k),
            ComponentChoice::Bic { min, max } => (min, max),
        };
        if points.len() < lo {
            return Err(GmrError::TooFewPoints {
                points: points.len(),
                components: lo,
            });
        }
        let mut best: Option<(f64, Gmm)> = None;
        let mut scores = Vec::new();
        let mut last_err = None;
        for k in lo..=hi.min(points.len()) {
            match self.fit_gmm_k(points, k) {
                Ok(g) => {
                    let ll = g.log_likelihood(points)?;
                    let bic = -2.0 * ll + g.n_parameters() as f64 * (points.len() as f64).ln();
                    scores.push(BicScore {
                        components: k,
                        log_likelihood: Some(ll),
                        bic: Some(bic),
                        error: None,
                    });
                    if best.as_ref().map_or(true, |(b, _)| bic < *b) {
                        best = Some((bic, g));
                    }
                }
                Err(e) if lo != hi => {
                    scores.push(BicScore {
                        components: k,
                        log_likelihood: None,
                        bic: None,
                        error: Some(e.to_string()),
                    });
                    last_err = Some(e);
                }
                Err(e) => return Err(e),
            }
        }
        match best {
            Some((_, g)) => Ok((g, scores)),
            None => Err(last_err.unwrap_or(GmrError::TooFewPoints {
                points: points.len(),
                components: lo,
            })),
        }
    }

    /// The whole baseline: pre-process the demonstrations (see
    /// [`super::preprocess`]), fit the mixture over `[t, q]`, return the GMR model.
    pub fn fit(&self, demos: &[Demonstration]) -> Result<GmrModel, GmrError> {
        Ok(self.fit_with_details(demos)?.0)
    }

    /// As [`GmrValidParams::fit`], also returning the training set (for plots) and the
    /// BIC of every component count tried.
    pub fn fit_with_details(
        &self,
        demos: &[Demonstration],
    ) -> Result<(GmrModel, TrainingSet, Vec<BicScore>), GmrError> {
        let training = preprocess(demos, self)?;
        let points = training.points();
        let (gmm, scores) = self.fit_gmm(&points)?;
        let model = GmrModel::new(training.columns.clone(), training.duration, gmm)?;
        Ok((model, training, scores))
    }
}

/// GMR's answer at one time.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Prediction {
    /// Query time, seconds.
    pub time: f64,
    /// Conditional mean `E[q | t]`, one value per state variable.
    pub mean: Vec<f64>,
    /// Conditional covariance `Cov[q | t]`, row-major `D×D`.
    pub covariance: Vec<Vec<f64>>,
}

#[derive(Debug, Clone, PartialEq)]
struct Conditional {
    log_weight: f64,
    mu_t: f64,
    var_t: f64,
    mu_q: DVector<f64>,
    slope: DVector<f64>,
    cov: DMatrix<f64>,
}

/// A trained baseline: the mixture over `[t, q]`, the names of `q`'s columns and the
/// duration of the motion; regresses `q` on `t`.
#[derive(Debug, Clone, PartialEq)]
pub struct GmrModel {
    columns: Vec<String>,
    duration: f64,
    gmm: Gmm,
    conditionals: Vec<Conditional>,
}

impl GmrModel {
    /// Build a model from a mixture over `[t, q_1 … q_D]` (dimension `D + 1`, `D` =
    /// `columns.len()` ≥ 1) and a duration in seconds (finite, ≥ 0).
    pub fn new(columns: Vec<String>, duration: f64, gmm: Gmm) -> Result<GmrModel, GmrError> {
        let d = columns.len();
        if d == 0 || gmm.dim() != d + 1 {
            return Err(GmrError::InvalidModel {
                message: format!(
                    "a mixture of dimension {} cannot regress {d} state variables on time",
                    gmm.dim()
                ),
            });
        }
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(GmrError::InvalidModel {
                message: format!("duration must be finite and >= 0, got {duration}"),
            });
        }
        let conditionals = (0..gmm.n_components())
            .map(|c| {
                let (m, s) = (&gmm.means[c], &gmm.covariances[c]);
                let var_t = s[(0, 0)];
                let s_qt = s.view((1, 0), (d, 1)).column(0).into_owned();
                let s_qq = s.view((1, 1), (d, d)).into_owned();
                Conditional {
                    log_weight: gmm.weights[c].ln(),
                    mu_t: m[0],
                    var_t,
                    mu_q: m.rows(1, d).into_owned(),
                    slope: &s_qt / var_t,
                    cov: s_qq - &s_qt * s_qt.transpose() / var_t,
                }
            })
            .collect();
        Ok(GmrModel {
            columns,
            duration,
            gmm,
            conditionals,
        })
    }

    /// Names of the state variables.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }
    /// Duration of the motion in seconds.
    pub fn duration(&self) -> f64 {
        self.duration
    }
    /// The mixture over `[t, q]`.
    pub fn gmm(&self) -> &Gmm {
        &self.gmm
    }

    /// Conditional mean and covariance of `q` at time `t` (finite; times outside
    /// `[0, duration]` extrapolate with the nearest components).
    pub fn predict(&self, t: f64) -> Result<Prediction, GmrError> {
        if !t.is_finite() {
            return Err(GmrError::Query {
                message: format!("query time must be finite, got {t}"),
            });
        }
        let d = self.columns.len();
        let logs: Vec<f64> = self
            .conditionals
            .iter()
            .map(|c| {
                let z = t - c.mu_t;
                c.log_weight - 0.5 * ((LN_2PI + c.var_t.ln()) + z * z / c.var_t)
            })
            .collect();
        let norm = log_sum_exp(&logs);
        let mut mean = DVector::zeros(d);
        let mut second = DMatrix::zeros(d, d);
        for (c, l) in self.conditionals.iter().zip(&logs) {
            let h = (l - norm).exp();
            let m_k = &c.mu_q + &c.slope * (t - c.mu_t);
            second += (&c.cov + &m_k * m_k.transpose()) * h;
            mean += m_k * h;
        }
        let cov = second - &mean * mean.transpose();
        Ok(Prediction {
            time: t,
            mean: mean.iter().cloned().collect(),
            covariance: (0..d)
                .map(|i| cov.row(i).iter().cloned().collect())
                .collect(),
        })
    }

    /// The reproduction: predictions at `k · period`, `k = 0 … round(duration / period)`
    /// (`period` finite and > 0; at most 10⁷ samples).
    pub fn reproduce(&self, period: f64) -> Result<Vec<Prediction>, GmrError> {
        if !(period.is_finite() && period > 0.0) {
            return Err(GmrError::Query {
                message: format!("sample period must be finite and > 0, got {period}"),
            });
        }
        let steps = (self.duration / period).round();
        if steps > 1e7 {
            return Err(GmrError::Query {
                message: format!("{steps} samples requested; use a longer period"),
            });
        }
        let n = steps as usize + 1;
        (0..n).map(|k| self.predict(k as f64 * period)).collect()
    }
}
