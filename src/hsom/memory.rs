//! Short-term memory: a level's activity list (CoSCo-HSOM) and, as the baseline, the per-node
//! activity levels of the sparse-code HSOM; the memory of every level ([`Stm`]), shared by the
//! paper's training and reproduction and by the replay of the training data.

use crate::config::{HsomConfig, MemoryMode};
use crate::som::{NodeId, SelfOrganizingMap};

/// A fixed-size FIFO of the IDs of a level's recent best-matching units, newest first.
/// `push` is O(1): a ring buffer overwrites the oldest entry when full.
#[derive(Debug, Clone, PartialEq)]
pub struct ActivityList {
    buf: Vec<NodeId>,
    head: usize,
    len: usize,
}

impl ActivityList {
    /// An empty list of `memory` entries (`memory` >= 1).
    pub fn new(memory: usize) -> Self {
        ActivityList {
            buf: vec![(0, 0); memory.max(1)],
            head: 0,
            len: 0,
        }
    }
    /// Number of entries held.
    pub fn len(&self) -> usize {
        self.len
    }
    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    /// True when it holds `memory` entries.
    pub fn is_full(&self) -> bool {
        self.len == self.buf.len()
    }
    /// Push the newest ID; the oldest is dropped when the list is full.
    #[inline]
    pub fn push(&mut self, id: NodeId) {
        self.head = if self.head == 0 {
            self.buf.len() - 1
        } else {
            self.head - 1
        };
        self.buf[self.head] = id;
        if self.len < self.buf.len() {
            self.len += 1;
        }
    }
    /// Entry `k`, 0 = newest; `None` past the entries held.
    #[inline]
    pub fn get(&self, k: usize) -> Option<NodeId> {
        if k < self.len {
            Some(self.buf[(self.head + k) % self.buf.len()])
        } else {
            None
        }
    }
    /// Entries newest first.
    pub fn to_vec(&self) -> Vec<NodeId> {
        (0..self.len).filter_map(|k| self.get(k)).collect()
    }
    /// Forget every entry (at the end of a demonstration).
    pub fn clear(&mut self) {
        self.len = 0;
        self.head = 0;
    }
    /// Write the newest `count` entries (count <= len) as coordinates `(x, y)` into slots
    /// `shift..shift + count` of `out` (slot k at `out[2k], out[2k+1]`) and mark them known in
    /// `mask`; every other slot is marked unknown. Slots past `memory` are dropped.
    pub fn encode(&self, count: usize, shift: usize, out: &mut [f64], mask: &mut [bool]) {
        mask.iter_mut().for_each(|m| *m = false);
        let slots = out.len() / 2;
        for j in 0..count.min(self.len) {
            let s = shift + j;
            if s >= slots {
                break;
            }
            let (x, y) = self.buf[(self.head + j) % self.buf.len()];
            out[2 * s] = x as f64;
            out[2 * s + 1] = y as f64;
            mask[2 * s] = true;
            mask[2 * s + 1] = true;
        }
    }
}

/// The sparse-code baseline: one activity level per node of a level. On every push each
/// level decreases linearly by 1/memory (never below 0) and the best-matching unit is set to
/// 1, so with memory 4 the last four BMUs hold 1.0, 0.75, 0.5, 0.25 (footnote 1).
/// `push` is O(number of nodes).
#[derive(Debug, Clone, PartialEq)]
pub struct ActivityLevels {
    act: Vec<f64>,
    step: f64,
}

impl ActivityLevels {
    /// All levels zero, for a map of `nodes` nodes and a memory of `memory` steps.
    pub fn new(nodes: usize, memory: usize) -> Self {
        ActivityLevels {
            act: vec![0.0; nodes],
            step: 1.0 / memory.max(1) as f64,
        }
    }
    /// Decay every node and raise the BMU (node index) to 1.
    #[inline]
    pub fn push(&mut self, node: usize) {
        let s = self.step;
        for a in self.act.iter_mut() {
            *a = (*a - s).max(0.0);
        }
        if let Some(a) = self.act.get_mut(node) {
            *a = 1.0;
        }
    }
    /// The activity levels (the input of the level above).
    pub fn levels(&self) -> &[f64] {
        &self.act
    }
    /// Number of active (non-zero) nodes.
    pub fn active(&self) -> usize {
        self.act.iter().filter(|&&a| a > 0.0).count()
    }
    /// All levels back to zero.
    pub fn clear(&mut self) {
        self.act.iter_mut().for_each(|a| *a = 0.0);
    }
    /// The decay per step (1/memory).
    pub fn decrement(&self) -> f64 {
        self.step
    }
}

/// The short-term memory of every level, in either mode.
#[derive(Debug, Clone)]
pub(crate) enum Activity {
    Lists(Vec<ActivityList>),
    Levels(Vec<ActivityLevels>),
}

#[derive(Debug, Clone)]
pub(crate) struct Stm {
    pub(crate) mem: Activity,
    /// Pushes since the last clear, per level.
    pub(crate) pushes: Vec<usize>,
    pub(crate) memory: usize,
}

impl Stm {
    pub(crate) fn new(config: &HsomConfig) -> Self {
        let p = config.params();
        let mem = match p.memory_mode() {
            MemoryMode::Lists => {
                Activity::Lists((0..p.height).map(|_| ActivityList::new(p.memory)).collect())
            }
            MemoryMode::Levels => Activity::Levels(
                p.levels
                    .iter()
                    .map(|l| ActivityLevels::new(l.rows * l.cols, p.memory))
                    .collect(),
            ),
        };
        Stm {
            mem,
            pushes: vec![0; p.height],
            memory: p.memory,
        }
    }
    pub(crate) fn clear(&mut self) {
        match &mut self.mem {
            Activity::Lists(v) => v.iter_mut().for_each(|l| l.clear()),
            Activity::Levels(v) => v.iter_mut().for_each(|l| l.clear()),
        }
        self.pushes.iter_mut().for_each(|c| *c = 0);
    }
    /// Push a bottom BMU.
    #[inline]
    pub(crate) fn push_bottom(&mut self, node: usize, map: &SelfOrganizingMap) {
        self.push(0, node, map);
    }
    #[inline]
    pub(crate) fn push(&mut self, level: usize, node: usize, map: &SelfOrganizingMap) {
        match &mut self.mem {
            Activity::Lists(v) => v[level].push(map.id(node)),
            Activity::Levels(v) => v[level].push(node),
        }
        self.pushes[level] += 1;
    }
    /// Input of level `level + 1` from the memory of `level`, for training: false when the
    /// level above must not train now (the list below is not yet full).
    #[inline]
    pub(crate) fn input(&self, level: usize, out: &mut [f64], mask: &mut [bool]) -> bool {
        let n = self.pushes[level];
        if n == 0 || n < self.memory {
            return false;
        }
        match &self.mem {
            Activity::Lists(v) => v[level].encode(self.memory, 0, out, mask),
            Activity::Levels(v) => {
                out.copy_from_slice(v[level].levels());
                mask.iter_mut().for_each(|m| *m = true);
            }
        }
        true
    }
}

#[cfg(test)]
mod tests;
