//! What the levels read: the demonstrations as borrowed series and their checks, each
//! level's input length, and the events encoding's layout.

use crate::config::{HsomConfig, MemoryMode};
use crate::demos::Demonstration;
use crate::som::SelfOrganizingMap;

use super::errors::HsomError;

/// Sizes of the event encoding.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Layout {
    /// stateLength.
    pub(crate) s: usize,
    /// memory: entries per chunk.
    pub(crate) k: usize,
}

impl Layout {
    pub(crate) fn of(config: &HsomConfig) -> Self {
        let p = config.params();
        Layout {
            s: p.state_length,
            k: p.memory,
        }
    }
    /// Values of one slot.
    pub(crate) fn slot(&self) -> usize {
        2 * self.s + 2
    }
    /// Values of the context.
    pub(crate) fn ctx(&self) -> usize {
        self.s + 2
    }
    /// Input length of a level above the bottom.
    pub(crate) fn dim(&self) -> usize {
        self.ctx() + self.k * self.slot()
    }
    pub(super) fn slot_range(&self, j: usize) -> std::ops::Range<usize> {
        let o = self.ctx() + j * self.slot();
        o..o + self.slot()
    }
}

/// A demonstration as borrowed rows with a name for messages.
#[derive(Clone, Copy)]
pub(crate) struct Series<'a> {
    pub(crate) source: &'a str,
    pub(crate) rows: &'a [Vec<f64>],
}

/// Refuse `series` unless there is one and each has samples of `state` finite values, at
/// least one state-action pair at action horizon `horizon` and never fewer than 2.
pub(crate) fn check_series(
    series: &[Series<'_>],
    state: usize,
    horizon: usize,
) -> Result<(), HsomError> {
    if series.is_empty() {
        return Err(HsomError::NoDemonstrations);
    }
    let needed = (horizon + 1).max(2);
    for s in series {
        if s.rows.len() < needed {
            return Err(HsomError::TooShort {
                demo: s.source.to_string(),
                rows: s.rows.len(),
                needed,
            });
        }
        for (i, r) in s.rows.iter().enumerate() {
            if r.len() != state {
                return Err(HsomError::DimensionMismatch {
                    demo: s.source.to_string(),
                    row: i,
                    expected: state,
                    found: r.len(),
                });
            }
            if let Some(c) = r.iter().position(|v| !v.is_finite()) {
                return Err(HsomError::NonFinite {
                    demo: s.source.to_string(),
                    row: i,
                    column: c,
                });
            }
        }
    }
    Ok(())
}

/// The shortest, mean and longest of `v`.
pub(crate) fn spread(v: &[f64]) -> [f64; 3] {
    [
        v.iter().cloned().fold(f64::INFINITY, f64::min),
        v.iter().sum::<f64>() / v.len().max(1) as f64,
        v.iter().cloned().fold(0.0, f64::max),
    ]
}

/// Per node, the mean of its `sum` over its `n` values (0 where it has none).
pub(crate) fn node_means(sum: &[f64], n: &[u32]) -> Vec<f64> {
    sum.iter()
        .zip(n)
        .map(|(&s, &n)| if n > 0 { s / n as f64 } else { 0.0 })
        .collect()
}

/// One input buffer and one mask (all known) per level, each of the level's input length.
pub(crate) fn level_buffers(config: &HsomConfig) -> (Vec<Vec<f64>>, Vec<Vec<bool>>) {
    let h = config.params().height;
    let dims = (0..h).map(|l| input_dim(config, l));
    (
        dims.clone().map(|d| vec![0.0; d]).collect(),
        dims.map(|d| vec![true; d]).collect(),
    )
}

/// The BMU of `x` in `map` and its squared distance, on the known coordinates of `mask`;
/// and whether every coordinate is known.
pub(crate) fn bmu_known(map: &SelfOrganizingMap, x: &[f64], mask: &[bool]) -> (usize, f64, bool) {
    let full = mask.iter().all(|&m| m);
    let (b, d2) = if full {
        map.bmu(x)
    } else {
        map.bmu_masked(x, mask)
    };
    (b, d2, full)
}

/// The demonstrations as borrowed series for training.
pub(crate) fn demo_series(demos: &[Demonstration]) -> Vec<Series<'_>> {
    demos
        .iter()
        .map(|d| Series {
            source: &d.source,
            rows: &d.rows,
        })
        .collect()
}

pub(crate) fn input_dim(config: &HsomConfig, level: usize) -> usize {
    let p = config.params();
    if level == 0 {
        p.state_length + p.action_length
    } else if p.kind() == crate::config::Algorithm::Events {
        Layout::of(config).dim()
    } else {
        match p.memory_mode() {
            MemoryMode::Lists => 2 * p.memory,
            MemoryMode::Levels => p.levels[level - 1].rows * p.levels[level - 1].cols,
        }
    }
}
