//! The DTW mean of the demonstrations, a baseline: DTW barycenter averaging (DBA; Petitjean,
//! Ketterlin and Gançarski, 2011). Scored by DTW against a new demonstration, the sequence
//! that minimises the expected score is the one at least summed DTW distance from the
//! demonstrations; DBA approaches it from the medoid (the demonstration nearest all the others)
//! by rounds of: align every demonstration with the mean by DTW, set each of the mean's
//! samples to the mean of all the samples aligned with it. The mean keeps the medoid's length.
//!
//! The alignments are made on the postures scaled per variable by the demonstrations' range
//! (a variable that moves in metres and one in radians count alike); the means are of the
//! postures as recorded, each demonstration read along its warp without stairs (where it is
//! slower than the mean, its samples move on at an even pace instead of repeating, as the
//! hierarchy's consensus reads them). A reproduction starts at the given initial posture: its
//! offset from the mean's start fades along a minimum-jerk profile as long as the
//! demonstrations' own offsets from their mean start lasted, never faster than they move, and
//! is smoothed to the demonstrations' smoothness as the hierarchy's curve is.

use crate::curve::{minimum_jerk_at, MINIMUM_JERK_PEAK};
use crate::demos::Demonstration;
use crate::dtw::{dtw, dtw_distance, Band, DtwError};
use crate::hsom::{as_smooth_as, smooth_warp, DemoSmoothness};

#[cfg(test)]
mod tests;

/// Rounds of alignment and averaging (Petitjean et al. found DBA converged within 10).
pub const ROUNDS: usize = 10;

/// What can go wrong fitting the DTW mean.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DbaError {
    /// No demonstration, or one without samples.
    #[error("the DTW mean needs at least 1 demonstration of at least 1 sample, got {found} demonstration(s), the shortest {shortest} sample(s)")]
    TooFew {
        /// Demonstrations given.
        found: usize,
        /// Samples of the shortest.
        shortest: usize,
    },
    /// A row not as wide as the first demonstration's first row.
    #[error(
        "the DTW mean: {demo}: row {row} has {found} values, the demonstrations have {expected}"
    )]
    Width {
        /// The demonstration.
        demo: String,
        /// The row, from 0.
        row: usize,
        /// Its values.
        found: usize,
        /// The first demonstration's width.
        expected: usize,
    },
    /// Demonstrations that do not align (values not finite).
    #[error("the DTW mean: {0}")]
    Dtw(#[from] DtwError),
}

/// The DTW mean of a set of demonstrations and how a reproduction joins it from a new start.
#[derive(Debug, Clone, PartialEq)]
pub struct Dba {
    /// The mean, one posture per sample, as long as the medoid.
    pub mean: Vec<Vec<f64>>,
    /// How long a start's offset lasts, as a fraction of the mean (0 to 1).
    pub fade: f64,
    /// How smooth and fast the demonstrations are (`None` for too short to tell).
    pub(crate) smoothness: Option<DemoSmoothness>,
}

impl Dba {
    /// The DTW mean of `demos`: initialised at their medoid, [`ROUNDS`] rounds of DBA (fewer
    /// when a round changes nothing).
    pub fn fit(demos: &[Demonstration]) -> Result<Dba, DbaError> {
        Dba::from(demos, None)
    }

    /// [`ROUNDS`] rounds of DBA of `demos` from `start` (any length; their medoid when
    /// `None`), fewer when a round changes nothing.
    pub fn from(demos: &[Demonstration], start: Option<&[Vec<f64>]>) -> Result<Dba, DbaError> {
        let shortest = demos.iter().map(|d| d.rows.len()).min().unwrap_or(0);
        if shortest == 0 || start.is_some_and(|s| s.is_empty()) {
            return Err(DbaError::TooFew {
                found: demos.len(),
                shortest,
            });
        }
        let rows: Vec<&[Vec<f64>]> = demos.iter().map(|d| d.rows.as_slice()).collect();
        let width = rows[0][0].len();
        let starts = start.into_iter().map(|s| ("the start", s));
        for (source, d) in demos
            .iter()
            .map(|d| (d.source.as_str(), &d.rows[..]))
            .chain(starts)
        {
            if let Some((row, r)) = d.iter().enumerate().find(|(_, r)| r.len() != width) {
                return Err(DbaError::Width {
                    demo: source.to_string(),
                    row,
                    found: r.len(),
                    expected: width,
                });
            }
        }
        let scale: Vec<f64> = (0..width)
            .map(|j| {
                let v = rows.iter().flat_map(|d| d.iter().map(|r| r[j]));
                let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                    (lo.min(x), hi.max(x))
                });
                if hi > lo {
                    1.0 / (hi - lo)
                } else {
                    1.0
                }
            })
            .collect();
        let scaled = |d: &[Vec<f64>]| -> Vec<Vec<f64>> {
            d.iter()
                .map(|r| r.iter().zip(&scale).map(|(x, s)| x * s).collect())
                .collect()
        };
        let norm: Vec<Vec<Vec<f64>>> = rows.iter().map(|d| scaled(d)).collect();
        let mut mean = match start {
            Some(s) => s.to_vec(),
            None => {
                let mut medoid = (0, f64::INFINITY);
                for (i, a) in norm.iter().enumerate() {
                    let mut sum = 0.0;
                    for b in &norm {
                        sum += dtw_distance(a, b, Band::None)?.per_step();
                    }
                    if sum < medoid.1 {
                        medoid = (i, sum);
                    }
                }
                rows[medoid.0].to_vec()
            }
        };
        for _ in 0..ROUNDS {
            let at = scaled(&mean);
            let mut sum = vec![vec![0.0; width]; mean.len()];
            for (d, n) in rows.iter().zip(&norm) {
                // per sample of the mean, the mean index of d's samples aligned to it
                let mut warp = vec![(0.0, 0.0); mean.len()];
                for (i, j) in dtw(&at, n, Band::None)?.path {
                    warp[i].0 += j as f64;
                    warp[i].1 += 1.0;
                }
                let warp: Vec<f64> = warp.iter().map(|(j, c)| j / c).collect();
                for (s, r) in sum.iter_mut().zip(smooth_warp(&warp, d)) {
                    s.iter_mut().zip(&r).for_each(|(s, x)| *s += x);
                }
            }
            let next: Vec<Vec<f64>> = sum
                .into_iter()
                .map(|s| s.into_iter().map(|x| x / rows.len() as f64).collect())
                .collect();
            if next == mean {
                break;
            }
            mean = next;
        }
        let owned: Vec<Vec<Vec<f64>>> = rows.iter().map(|d| d.to_vec()).collect();
        let fade = crate::hsom::start_fade(&owned, width).unwrap_or(1.0);
        Ok(Dba {
            mean,
            fade,
            smoothness: DemoSmoothness::of(&owned, width),
        })
    }

    /// The mean from `initial`: its offset from the mean's first posture fades to nothing over
    /// [`Dba::fade`] of the mean, and over at least the samples a minimum-jerk move of that
    /// offset takes at the demonstrations' peak step; then smoothed as the hierarchy's curve
    /// is (docs/ALGORITHM.md, section 3.8, "As smooth as the demonstrations").
    pub fn reproduce(&self, initial: &[f64]) -> Vec<Vec<f64>> {
        let whole = (self.mean.len().max(2) - 1) as f64;
        let offset: Vec<f64> = initial
            .iter()
            .zip(&self.mean[0])
            .map(|(x, m)| x - m)
            .collect();
        let peak = self.smoothness.as_ref().map_or(&[][..], |s| &s.peak_step);
        let horizon = offset
            .iter()
            .zip(peak)
            .filter(|(_, p)| **p > 0.0)
            .map(|(o, p)| MINIMUM_JERK_PEAK * o.abs() / p)
            .fold(self.fade * whole, f64::max)
            .clamp(1.0, whole);
        let columns: Vec<Vec<f64>> = (0..offset.len())
            .map(|j| {
                self.mean
                    .iter()
                    .enumerate()
                    .map(|(i, m)| m[j] + offset[j] * (1.0 - minimum_jerk_at(i as f64 / horizon)))
                    .collect()
            })
            .collect();
        let at_rest = vec![0.0; offset.len()];
        let smoothed = as_smooth_as(&columns, &at_rest, self.smoothness.clone());
        (0..self.mean.len())
            .map(|i| {
                let mut row: Vec<f64> = smoothed.iter().map(|c| c[i]).collect();
                if i == 0 {
                    // exactly the given posture
                    row.copy_from_slice(initial);
                }
                row
            })
            .collect()
    }
}
