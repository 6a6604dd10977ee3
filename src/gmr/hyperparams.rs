//! Parameters of the GMM/GMR baseline, checked once by [`GmrParams::check`].

use serde::Serialize;

use super::errors::GmrError;
use crate::dtw::Band;

/// Idle trimming settings (the formula: the `preprocess` module's documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct IdleTrim {
    /// Absolute floor of the threshold, rad/s; also the "never moves" limit.
    pub min_speed: f64,
    /// Threshold as a fraction of the peak smoothed speed, in `[0, 1)`.
    pub relative: f64,
    /// Half-width of the speed smoothing window, in samples.
    pub half_window: usize,
}

impl Default for IdleTrim {
    fn default() -> Self {
        IdleTrim {
            min_speed: 0.02,
            relative: 0.05,
            half_window: 2,
        }
    }
}

impl IdleTrim {
    /// Check the settings: `(name, value, reason)` of the first bad one.
    pub fn check(&self) -> Result<(), (&'static str, String, &'static str)> {
        let bad = |name, value: &dyn ToString, reason| Err((name, value.to_string(), reason));
        let (speed, relative) = (self.min_speed, self.relative);
        if !(speed.is_finite() && speed > 0.0) {
            return bad("trim.min_speed", &speed, "a finite speed in rad/s > 0");
        }
        if !(relative.is_finite() && (0.0..1.0).contains(&relative)) {
            return bad("trim.relative", &relative, "a fraction within [0, 1)");
        }
        if self.half_window > 1000 {
            return bad(
                "trim.half_window",
                &self.half_window,
                "at most 1000 samples",
            );
        }
        Ok(())
    }
}

/// How many mixture components to use.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ComponentChoice {
    /// Exactly this many.
    Fixed(usize),
    /// Fit every count in `min..=max` and keep the one with the lowest BIC
    /// (`−2 ln L + p ln N`, `p = (K−1) + K·d + K·d(d+1)/2`); ties go to the smaller count.
    Bic {
        /// Smallest count tried (≥ 1).
        min: usize,
        /// Largest count tried (≥ `min`).
        max: usize,
    },
}

/// Unchecked parameters of the baseline; consuming setters, then [`GmrParams::check`].
///
/// Defaults: components by BIC over 1..=8, `reg_covar` 1e-6 (added to every covariance
/// diagonal; keeps joints that never move, such as the unused wrist, from making a
/// covariance singular), EM tolerance 1e-6 on the change of the mean log-likelihood
/// lower bound, at most 500 EM iterations, seed 0, 100 resampled points per
/// demonstration, 0.025 s sample period (40 Hz) for files without a `time` column,
/// [`IdleTrim::default`], DTW alignment on with no band, at least 2 demonstrations.
#[derive(Debug, Clone, PartialEq)]
pub struct GmrParams {
    pub(crate) components: ComponentChoice,
    pub(crate) reg_covar: f64,
    pub(crate) tolerance: f64,
    pub(crate) max_iterations: u64,
    pub(crate) seed: u64,
    pub(crate) n_points: usize,
    pub(crate) sample_period: f64,
    pub(crate) trim: IdleTrim,
    pub(crate) align: bool,
    pub(crate) band: Band,
}

/// Validated parameters: the only type that can fit a model.
#[derive(Debug, Clone, PartialEq)]
pub struct GmrValidParams(pub(super) GmrParams);

/// The pipeline needs this many demonstrations: GMR's envelope is the spread across
/// demonstrations, and DTW alignment needs something to align. One demonstration is
/// refused with [`GmrError::TooFewDemonstrations`]; to fit a mixture to any point set, use
/// [`GmrValidParams::fit_gmm`].
pub const MIN_DEMONSTRATIONS: usize = 2;

impl Default for GmrParams {
    fn default() -> Self {
        GmrParams {
            components: ComponentChoice::Bic { min: 1, max: 8 },
            reg_covar: 1e-6,
            tolerance: 1e-6,
            max_iterations: 500,
            seed: 0,
            n_points: 100,
            sample_period: 0.025,
            trim: IdleTrim::default(),
            align: true,
            band: Band::None,
        }
    }
}

impl GmrParams {
    /// The defaults (see the type's documentation).
    pub fn new() -> Self {
        Self::default()
    }
    /// Number of components, fixed or chosen by BIC.
    pub fn components(mut self, c: ComponentChoice) -> Self {
        self.components = c;
        self
    }
    /// Regularisation added to every covariance diagonal (> 0).
    pub fn reg_covar(mut self, v: f64) -> Self {
        self.reg_covar = v;
        self
    }
    /// EM convergence tolerance on the change of the lower bound (> 0).
    pub fn tolerance(mut self, v: f64) -> Self {
        self.tolerance = v;
        self
    }
    /// EM iteration budget (≥ 1).
    pub fn max_iterations(mut self, v: u64) -> Self {
        self.max_iterations = v;
        self
    }
    /// Seed of the k-means initialisation (ChaCha8): same seed, same model.
    pub fn seed(mut self, v: u64) -> Self {
        self.seed = v;
        self
    }
    /// Points per demonstration after resampling (≥ 2).
    pub fn n_points(mut self, v: usize) -> Self {
        self.n_points = v;
        self
    }
    /// Sample period in seconds for demonstrations without a `time` column (> 0).
    pub fn sample_period(mut self, v: f64) -> Self {
        self.sample_period = v;
        self
    }
    /// Idle trimming of start and end.
    pub fn trim(mut self, v: IdleTrim) -> Self {
        self.trim = v;
        self
    }
    /// Align the trimmed demonstrations to a reference with DTW before resampling.
    pub fn align(mut self, v: bool) -> Self {
        self.align = v;
        self
    }
    /// Sakoe-Chiba band of the alignment.
    pub fn band(mut self, v: Band) -> Self {
        self.band = v;
        self
    }

    /// Check every parameter once; only the checked type can fit.
    pub fn check(self) -> Result<GmrValidParams, GmrError> {
        let bad = |name, value: &dyn ToString, reason| {
            let value = value.to_string();
            Err(GmrError::InvalidParam {
                name,
                value,
                reason,
            })
        };
        let positive = |v: f64| v.is_finite() && v > 0.0;
        match self.components {
            ComponentChoice::Fixed(0) => return bad("components", &0, "at least one component"),
            ComponentChoice::Bic { min, max } if min == 0 || max < min => {
                let range = format!("BIC {min}..={max}");
                return bad("components", &range, "a range with 1 <= min <= max");
            }
            _ => {}
        }
        if !positive(self.reg_covar) {
            return bad("reg_covar", &self.reg_covar, "a finite value > 0");
        }
        if !positive(self.tolerance) {
            return bad("tolerance", &self.tolerance, "a finite value > 0");
        }
        if self.max_iterations == 0 {
            return bad("max_iterations", &0, "at least 1");
        }
        if self.n_points < 2 {
            return bad("n_points", &self.n_points, "at least 2");
        }
        let period = self.sample_period;
        if !positive(period) {
            return bad("sample_period", &period, "a finite time in seconds > 0");
        }
        if let Err((name, value, reason)) = self.trim.check() {
            return bad(name, &value, reason);
        }
        if let Band::Fraction(f) = self.band {
            if !(0.0..=1.0).contains(&f) {
                return bad("band", &f, "a fraction within [0, 1]");
            }
        }
        Ok(GmrValidParams(self))
    }
}

impl GmrValidParams {
    /// The checked parameters.
    pub fn params(&self) -> &GmrParams {
        &self.0
    }
}
