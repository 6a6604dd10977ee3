//! What a model keeps of the demonstrations it learned from (docs/ALGORITHM.md, section 10):
//! at most [`KEPT_DEMONSTRATIONS`] per gesture, a uniform sample of them all drawn by
//! reservoir sampling from the configuration's seed, each normalised and resampled to
//! [`BAND_ROWS`](super::BAND_ROWS) rows with its own length ([`Kept`]); and where an update's training starts
//! ([`Warm`]). The confidence band is measured from them, and an update rehearses them
//! (`update.rs`).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::demos::Demonstration;
use crate::som::SelfOrganizingMap;

use super::errors::HsomError;

use serde::{Deserialize, Serialize};

/// What a model learned from, beside its kept paths ([`Model::paths`](super::model::Model)).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Kept {
    /// Demonstrations learned from, over the first training and every update.
    pub(crate) learned: u64,
    /// Updates that brought this gesture demonstrations after the training or update that
    /// taught it ([`Hsom::update`](super::Hsom::update)).
    pub(crate) updates: u32,
    /// Per kept path, the samples of the demonstration it was made from: an update restores
    /// each kept demonstration to its own length.
    pub(crate) lengths: Vec<u32>,
    /// The demonstrations' sample period, seconds (`None`: recorded without times); an
    /// update takes demonstrations of the same.
    pub(crate) period: Option<f64>,
}

impl Kept {
    /// The counts read from a model file against what training and updates make of them:
    /// 1 to [`MAX_LEARNED`] demonstrations learned from, and fewer updates than that (the
    /// training or update that taught the gesture, and every update counted, each brought at
    /// least one). What is wrong, naming the field and what is allowed.
    pub(crate) fn check_counts(&self) -> Result<(), String> {
        let (learned, updates) = (self.learned, self.updates);
        if !(1..=MAX_LEARNED).contains(&learned) {
            return Err(format!(
                "learned (demonstrations learned from) is {learned}: 1 to {MAX_LEARNED}"
            ));
        }
        if u64::from(updates) >= learned {
            return Err(format!(
                "updates (sittings after the first) is {updates} with learned {learned}: at most \
                 learned - 1 = {}, as every sitting brings at least one demonstration",
                learned - 1
            ));
        }
        Ok(())
    }

    /// The count of demonstrations learned from once `new` more are: an error when it would
    /// pass [`MAX_LEARNED`] (`of` names the model or gesture).
    pub(crate) fn room(&self, new: usize, of: &str) -> Result<u64, HsomError> {
        (u64::try_from(new).ok())
            .and_then(|n| self.learned.checked_add(n))
            .filter(|&n| n <= MAX_LEARNED)
            .ok_or_else(|| HsomError::TooManyLearned {
                of: of.to_string(),
                learned: self.learned,
                new,
                most: MAX_LEARNED,
            })
    }
}

/// Most demonstrations a model keeps per gesture ([`Model::paths`](super::model::Model)): its size is bounded by
/// the configuration, whatever the number of demonstrations learned from; an update learns
/// from at most this many earlier demonstrations beside the new ones, so that its cost does
/// not grow with them (docs/ALGORITHM.md, section 10; docs/BENCHMARKS.md).
pub const KEPT_DEMONSTRATIONS: usize = 6;

/// Most demonstrations a model counts as learned from, over its training and every update
/// (per gesture): a billion, a demonstration a second for over thirty years, far beyond any
/// teaching, and below `u32::MAX`, so that the count of updates (a `u32`, fewer than the
/// demonstrations, since every sitting brings at least one) always has room for one more.
/// Counts of every gesture a model may hold ([`MAX_LABELS`](super::MAX_LABELS)) add up
/// exactly in `u64` and `f64` (an update's share of the schedule). A model file counting
/// more is refused at load, an update that would count more is refused before training.
pub const MAX_LEARNED: u64 = 1_000_000_000;

/// The rows of each training path a model keeps ([`Model::paths`](super::model::Model)): however long the
/// demonstrations, the model's size does not depend on it.
pub const BAND_ROWS: usize = 200;

/// `rows` linearly resampled to [`BAND_ROWS`] rows (evenly in phase, read between two rows).
pub(crate) fn band_path(rows: &[Vec<f64>]) -> Vec<Vec<f64>> {
    (0..BAND_ROWS)
        .map(|k| crate::curve::at_phase(rows, k as f64 / (BAND_ROWS - 1) as f64))
        .collect()
}

/// Where an update's training starts ([`crate::config::HsomConfig::fit_from`]): a trained
/// model's maps (its bottom alone for the events extension, whose upper levels are fitted
/// anew; none: the seeded initial weights, [`Warm::units`]), its normalisation and training
/// counts, the point of the schedule to go on from and the update's seed.
pub(crate) struct Warm<'a> {
    pub(crate) maps: &'a [SelfOrganizingMap],
    pub(crate) offset: &'a [f64],
    pub(crate) scale: &'a [f64],
    pub(crate) trained: &'a [u64],
    /// The share of the schedule already done: the earlier demonstrations' share of all.
    pub(crate) from: f64,
    pub(crate) seed: u64,
}

impl<'a> Warm<'a> {
    /// A start from the seeded initial weights (`seed`) and the whole schedule in the units
    /// `offset` and `scale`: a gesture learned in the units of a model of several.
    pub(crate) fn units(offset: &'a [f64], scale: &'a [f64], seed: u64) -> Warm<'a> {
        Warm {
            maps: &[],
            offset,
            scale,
            trained: &[],
            from: 0.0,
            seed,
        }
    }
}

/// The paths kept of training demonstrations `norm` (normalised, of lengths `lens`), and
/// what the model learned from: [`KEPT_DEMONSTRATIONS`] of them at most, drawn uniformly
/// (from `seed`).
pub(crate) fn kept(
    norm: &[Vec<Vec<f64>>],
    lens: impl Iterator<Item = usize>,
    seed: u64,
) -> (Vec<Vec<Vec<f64>>>, Kept) {
    let mut paths = Vec::new();
    let mut record = Kept {
        learned: 0,
        updates: 0,
        lengths: Vec::new(),
        period: None,
    };
    keep(
        &mut paths,
        &mut record,
        norm.iter().zip(lens).map(|(rows, n)| (band_path(rows), n)),
        seed,
    );
    (paths, record)
}

/// Reservoir sampling (Vitter's algorithm R) of the kept paths: see [`reservoir`].
pub(crate) fn keep(
    paths: &mut Vec<Vec<Vec<f64>>>,
    record: &mut Kept,
    new: impl Iterator<Item = (Vec<Vec<f64>>, usize)>,
    seed: u64,
) {
    let mut slots: Vec<(Vec<Vec<f64>>, u32)> = std::mem::take(paths)
        .into_iter()
        .zip(record.lengths.drain(..))
        .collect();
    let new = new.map(|(path, n)| (path, u32::try_from(n).unwrap_or(u32::MAX)));
    reservoir(&mut slots, &mut record.learned, new, seed);
    (*paths, record.lengths) = slots.into_iter().unzip();
}

/// Reservoir sampling (Vitter's algorithm R): each new item is kept while fewer than
/// [`KEPT_DEMONSTRATIONS`] are, and afterwards replaces a kept one with probability
/// `KEPT_DEMONSTRATIONS / (items seen)`, so that the kept items are a uniform sample of every
/// item seen (`seen` counts them). The draws come from `seed` and the count seen before.
pub(crate) fn reservoir<T>(
    slots: &mut Vec<T>,
    seen: &mut u64,
    new: impl Iterator<Item = T>,
    seed: u64,
) {
    let mut rng = ChaCha8Rng::seed_from_u64(mixed(seed, *seen));
    for item in new {
        if slots.len() < KEPT_DEMONSTRATIONS {
            slots.push(item);
        } else if let Ok(r) = usize::try_from(rng.gen_range(0..=*seen)) {
            if r < KEPT_DEMONSTRATIONS {
                slots[r] = item;
            }
        }
        *seen += 1;
    }
}

/// Which of `n` demonstrations a model trained on them with seed `seed` keeps, in the order
/// kept ([`reservoir`]).
pub(crate) fn kept_indices(n: usize, seed: u64) -> Vec<usize> {
    let mut slots = Vec::new();
    reservoir(&mut slots, &mut 0, 0..n, seed);
    slots
}

/// What a model trained on `demos` with seed `seed` keeps of them, as demonstrations: the
/// same sample ([`KEPT_DEMONSTRATIONS`] at most), each read through its [`BAND_ROWS`](super::BAND_ROWS)-row
/// path back at its own length and sample times. What GMM/GMR, ProMP and the DMP refit on
/// beside new demonstrations when they are updated (docs/ALGORITHM.md, section 10).
pub fn kept_demonstrations(demos: &[Demonstration], seed: u64) -> Vec<Demonstration> {
    kept_indices(demos.len(), seed)
        .into_iter()
        .map(|i| {
            let d = &demos[i];
            let path = band_path(&d.rows);
            let n = d.rows.len();
            let rows = (0..n)
                .map(|k| crate::curve::at_phase(&path, k as f64 / (n.max(2) - 1) as f64))
                .collect();
            Demonstration { rows, ..d.clone() }
        })
        .collect()
}

/// `seed` mixed with `k` (an update's number, a count learned): a seed of its own.
pub(crate) fn mixed(seed: u64, k: u64) -> u64 {
    seed ^ 0x9e37_79b9_7f4a_7c15u64.wrapping_mul(k.wrapping_add(1))
}
