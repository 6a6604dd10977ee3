//! The baseline of recognition: a 1-nearest-neighbour classifier under dynamic time
//! warping ([`crate::dtw`]), the strong standard for time-series classification. A query
//! takes the label of the training sequence at the smallest DTW distance per path step.

use crate::dtw::{dtw_distance, Band, DtwError};

/// Labelled training sequences.
#[derive(Debug, Clone, PartialEq)]
pub struct NearestNeighbour {
    templates: Vec<(String, Vec<Vec<f64>>)>,
    band: Band,
}

/// The answer for one query.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct NearestAnswer {
    /// The nearest template's label.
    pub label: String,
    /// Its DTW distance per path step.
    pub distance: f64,
    /// The earliest sample from which the answer on the query's prefixes (checked every
    /// [`EARLY_STEP`] of its length, each prefix against the templates' prefixes of the
    /// same fraction of their length) stayed the final one; only with
    /// [`NearestNeighbour::classify_early`].
    pub decided_at: usize,
}

/// Spacing of the prefixes checked by [`NearestNeighbour::classify_early`], as a fraction of
/// the query's length.
pub const EARLY_STEP: f64 = 0.02;

impl NearestNeighbour {
    /// A classifier over `(label, rows)` templates, with a Sakoe-Chiba `band`.
    pub fn new(templates: Vec<(String, Vec<Vec<f64>>)>, band: Band) -> Self {
        NearestNeighbour { templates, band }
    }

    fn nearest(&self, query: &[Vec<f64>], fraction: f64) -> Result<(usize, f64), DtwError> {
        let mut best = (0, f64::INFINITY);
        for (i, (_, t)) in self.templates.iter().enumerate() {
            let m = ((t.len() as f64 * fraction).ceil() as usize).clamp(1, t.len());
            let d = dtw_distance(query, &t[..m], self.band)?.per_step();
            if d < best.1 {
                best = (i, d);
            }
        }
        Ok(best)
    }

    /// The nearest template's label of a whole query.
    pub fn classify(&self, query: &[Vec<f64>]) -> Result<NearestAnswer, DtwError> {
        let (i, d) = self.nearest(query, 1.0)?;
        Ok(NearestAnswer {
            label: self.templates[i].0.clone(),
            distance: d,
            decided_at: query.len(),
        })
    }

    /// As [`NearestNeighbour::classify`], with the earliest sample from which the answer
    /// stayed the same.
    pub fn classify_early(&self, query: &[Vec<f64>]) -> Result<NearestAnswer, DtwError> {
        let mut a = self.classify(query)?;
        let steps = (1.0 / EARLY_STEP).round() as usize;
        for k in (1..steps).rev() {
            let f = k as f64 * EARLY_STEP;
            let n = ((query.len() as f64 * f).ceil() as usize).clamp(1, query.len());
            let (i, _) = self.nearest(&query[..n], f)?;
            if self.templates[i].0 != a.label {
                break;
            }
            a.decided_at = n;
        }
        Ok(a)
    }
}
