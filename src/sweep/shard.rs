//! Shards: `--shard I/N` runs the runs whose grid index is I modulo N, so N job-array tasks
//! cover the grid exactly once between them. Without `--shard`, SLURM's job-array variables
//! choose the shard.

use super::SweepError;

/// One shard of N.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// 0-based index, below `count`.
    pub index: usize,
    /// Number of shards, at least 1.
    pub count: usize,
}

impl Shard {
    /// The whole grid.
    pub const ALL: Shard = Shard { index: 0, count: 1 };

    /// A shard, checked: `count >= 1`, `index < count`; `source` names where the numbers came
    /// from in the error.
    pub fn new(index: usize, count: usize, source: &str) -> Result<Shard, SweepError> {
        if count == 0 {
            return Err(SweepError::Invalid(format!(
                "{source}: {index}/{count}: the number of shards must be at least 1"
            )));
        }
        if index >= count {
            return Err(SweepError::Invalid(format!(
                "{source}: {index}/{count}: shard index {index} is out of range; the shards of \
                 {count} are numbered 0 to {}",
                count - 1
            )));
        }
        Ok(Shard { index, count })
    }

    /// Parse `I/N` (as given to `--shard`).
    pub fn parse(text: &str) -> Result<Shard, SweepError> {
        let bad = || {
            SweepError::Invalid(format!(
                "--shard '{text}': give I/N with whole numbers 0 <= I < N, e.g. 0/4"
            ))
        };
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let i: usize = i.trim().parse().map_err(|_| bad())?;
        let n: usize = n.trim().parse().map_err(|_| bad())?;
        Shard::new(i, n, "--shard")
    }

    /// The shard of a SLURM job-array task, read through `var` (`std::env::var` in the
    /// binary): `SLURM_ARRAY_TASK_ID` less `SLURM_ARRAY_TASK_MIN` (0 when unset) of
    /// `SLURM_ARRAY_TASK_COUNT`. `None` unless both ID and COUNT are set.
    pub fn from_slurm(var: impl Fn(&str) -> Option<String>) -> Result<Option<Shard>, SweepError> {
        let (Some(id), Some(count)) = (var("SLURM_ARRAY_TASK_ID"), var("SLURM_ARRAY_TASK_COUNT"))
        else {
            return Ok(None);
        };
        let number = |name: &str, v: &str| {
            v.trim().parse::<usize>().map_err(|_| {
                SweepError::Invalid(format!("{name}='{v}': expected a whole number >= 0"))
            })
        };
        let id = number("SLURM_ARRAY_TASK_ID", &id)?;
        let count = number("SLURM_ARRAY_TASK_COUNT", &count)?;
        let min = match var("SLURM_ARRAY_TASK_MIN") {
            Some(m) => number("SLURM_ARRAY_TASK_MIN", &m)?,
            None => 0,
        };
        let index = id.checked_sub(min).ok_or_else(|| {
            SweepError::Invalid(format!(
                "SLURM_ARRAY_TASK_ID={id} is below SLURM_ARRAY_TASK_MIN={min}"
            ))
        })?;
        Shard::new(
            index,
            count,
            "SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN / SLURM_ARRAY_TASK_COUNT (submit with \
             --array=0-(N-1) and no step)",
        )
        .map(Some)
    }

    /// Whether the run with grid index `index` belongs to this shard.
    pub fn contains(&self, index: usize) -> bool {
        index % self.count == self.index
    }

    /// `I/N`.
    pub fn label(&self) -> String {
        format!("{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests;
