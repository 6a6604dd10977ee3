//! What the levels read: the demonstrations as borrowed series and their checks, each
//! level's input length, and the events encoding's layout.

use crate::config::{HsomConfig, MemoryMode};
use crate::demos::Demonstration;

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
pub(crate) struct Series<'a> {
    pub(crate) source: &'a str,
    pub(crate) rows: &'a [Vec<f64>],
}

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
