//! The map itself: weights, best-matching-unit search, neighbourhood update, quality.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::hyperparams::{Neighbourhood, SomParams, Topology};
use super::kernel::{self, Lane, LANES};

/// A node's ID: its `(x, y)` grid position (`x` the column, `y` the row).
pub type NodeId = (u16, u16);

/// Errors of the stand-alone map trainer.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum SomError {
    /// A setting is out of range.
    #[error("invalid SOM parameter {name} = {value}")]
    InvalidParam {
        /// Parameter name.
        name: &'static str,
        /// Offending value.
        value: String,
    },
    /// No data, or zero-length samples.
    #[error("no training data (or zero-dimensional samples)")]
    EmptyData,
    /// A sample of another length than the first.
    #[error("sample {row} has {found} values, expected {expected}")]
    DimensionMismatch {
        /// Expected length.
        expected: usize,
        /// Found length.
        found: usize,
        /// Sample index.
        row: usize,
    },
    /// A NaN or infinite value.
    #[error("sample {row}, column {column} is not a finite number")]
    NonFinite {
        /// Sample index.
        row: usize,
        /// Column index.
        column: usize,
    },
    /// Weights of the wrong length.
    #[error(
        "weights have {found} values, a {rows}x{cols} map of dimension {dim} needs {expected}"
    )]
    WeightsLength {
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// Dimension.
        dim: usize,
        /// Expected length.
        expected: usize,
        /// Found length.
        found: usize,
    },
}

/// How far from the best-matching unit [`SelfOrganizingMap::update_reach`] moves nodes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reach {
    /// Only nodes whose neighbourhood value h is at least `h_min` (0 < `h_min` < 1). For the
    /// gaussian that is a disc of radius `r sqrt(2 ln(1 / h_min))` around the BMU, and the
    /// update visits only the rows and columns that can reach it: with [`DEFAULT_H_MIN`] =
    /// 1e-4, 4.29 r. A node left out would have moved by less than `alpha h_min |x - w|`.
    Cut {
        /// Smallest neighbourhood value applied.
        h_min: f64,
    },
    /// Every node, with h however small (the textbook update; one exponential per node).
    Exact,
}

/// The cut of [`SelfOrganizingMap::update`]: nodes with h < 1e-4 are left untouched, the
/// rule of this map since its first version (for the gaussian, beyond 4.29 learning radii).
pub const DEFAULT_H_MIN: f64 = 1e-4;

/// Per-update scratch space (not part of a map's value).
#[derive(Debug, Clone, Default)]
struct Scratch {
    /// Gaussian values by half grid step (x) and by row step (y).
    gx: Vec<f64>,
    gy: Vec<f64>,
    /// Gaussian column factors of one update, per column and shift.
    colf: Vec<f64>,
    /// The blocks to move.
    plan: kernel::Plan,
}

impl PartialEq for Scratch {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

/// The weights of one node, copied out of the blocked layout; derefs to `&[f64]`.
#[derive(Debug, Clone)]
pub struct NodeWeights {
    inline: [f64; NodeWeights::INLINE],
    heap: Vec<f64>,
    len: usize,
}

impl NodeWeights {
    const INLINE: usize = 32;
}

impl std::ops::Deref for NodeWeights {
    type Target = [f64];
    #[inline]
    fn deref(&self) -> &[f64] {
        if self.len <= Self::INLINE {
            &self.inline[..self.len]
        } else {
            &self.heap
        }
    }
}

/// A 2-D Kohonen map of `rows` x `cols` nodes, each with a weight vector of length `dim`.
/// Node index `i = y * cols + x` has ID `(x, y)`.
///
/// The weights are stored in blocks of `LANES` = 8 nodes, dimension by dimension (value
/// `d` of node `i` at `((i / 8) * dim + d) * 8 + i % 8`): a scan over the nodes reads one
/// contiguous array and computes 8 nodes at a time in vector registers.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(into = "MapRecord", try_from = "MapRecord")]
pub struct SelfOrganizingMap {
    rows: usize,
    cols: usize,
    dim: usize,
    topology: Topology,
    /// `ceil(rows cols / LANES) * dim` lanes; padding lanes hold 0.
    w: Vec<Lane>,
    /// Grid position of every node (for neighbourhood distances).
    pos: Vec<(f64, f64)>,
    scratch: Scratch,
}

/// A map as model files describe it: its grid, topology and weights, node by node.
#[derive(serde::Serialize, serde::Deserialize)]
struct MapRecord {
    rows: u32,
    cols: u32,
    dim: u32,
    topology: Topology,
    weights: Vec<f64>,
}

impl From<SelfOrganizingMap> for MapRecord {
    fn from(m: SelfOrganizingMap) -> Self {
        MapRecord {
            rows: m.rows as u32,
            cols: m.cols as u32,
            dim: m.dim as u32,
            topology: m.topology,
            weights: m.all_weights(),
        }
    }
}

impl TryFrom<MapRecord> for SelfOrganizingMap {
    type Error = String;
    /// A map read from a file: at least one node of at least one value, and exactly
    /// `rows x cols x dim` weight values (checked before anything is sized by the grid).
    fn try_from(r: MapRecord) -> Result<Self, String> {
        let (rows, cols, dim) = (r.rows as usize, r.cols as usize, r.dim as usize);
        let expected = rows.checked_mul(cols).and_then(|n| n.checked_mul(dim));
        if rows == 0 || cols == 0 || dim == 0 || expected != Some(r.weights.len()) {
            return Err(format!(
                "a map of {rows}x{cols} nodes of dimension {dim} with {} weight values",
                r.weights.len()
            ));
        }
        Self::from_weights(rows, cols, dim, r.topology, r.weights).map_err(|e| e.to_string())
    }
}

/// The `(dimension, value)` pairs of `x` among its first `dim` where `mask` is true.
#[inline]
pub(crate) fn known<'a>(
    x: &'a [f64],
    mask: &'a [bool],
    dim: usize,
) -> impl Iterator<Item = (usize, f64)> + 'a {
    let pairs = x.iter().zip(mask).take(dim).enumerate();
    pairs.filter_map(|(d, (&v, &m))| m.then_some((d, v)))
}

pub(crate) fn positions(rows: usize, cols: usize, topology: Topology) -> Vec<(f64, f64)> {
    let mut pos = Vec::with_capacity(rows * cols);
    for y in 0..rows {
        for x in 0..cols {
            pos.push(match topology {
                Topology::Orthogonal => (x as f64, y as f64),
                Topology::Hexagonal => (
                    x as f64 + 0.5 * (y % 2) as f64,
                    y as f64 * (3f64).sqrt() / 2.0,
                ),
            });
        }
    }
    pos
}

impl SelfOrganizingMap {
    fn blank(rows: usize, cols: usize, dim: usize, topology: Topology) -> Self {
        let blocks = (rows * cols).div_ceil(LANES);
        SelfOrganizingMap {
            rows,
            cols,
            dim,
            topology,
            w: vec![[0.0; LANES]; blocks * dim],
            pos: positions(rows, cols, topology),
            scratch: Scratch::default(),
        }
    }

    /// A map whose weights are drawn uniformly from `rng`, dimension `d` inside `[lo[d], hi[d]]`.
    /// `lo` and `hi` must have length `dim`, `rows` and `cols` must be >= 1 (checked by callers).
    pub fn new_random<R: Rng>(
        rows: usize,
        cols: usize,
        dim: usize,
        topology: Topology,
        lo: &[f64],
        hi: &[f64],
        rng: &mut R,
    ) -> Self {
        let mut m = Self::blank(rows, cols, dim, topology);
        for i in 0..rows * cols {
            for d in 0..dim {
                let u: f64 = rng.gen();
                m.w[(i / LANES) * dim + d][i % LANES] = lo[d] + (hi[d] - lo[d]) * u;
            }
        }
        m
    }

    /// A map with the given weights (node-major, `rows * cols * dim` values).
    pub fn from_weights(
        rows: usize,
        cols: usize,
        dim: usize,
        topology: Topology,
        weights: Vec<f64>,
    ) -> Result<Self, SomError> {
        let expected = rows * cols * dim;
        if weights.len() != expected {
            return Err(SomError::WeightsLength {
                rows,
                cols,
                dim,
                expected,
                found: weights.len(),
            });
        }
        let mut m = Self::blank(rows, cols, dim, topology);
        if dim > 0 {
            for (i, w) in weights.chunks_exact(dim).enumerate() {
                m.set_weights(i, w);
            }
        }
        Ok(m)
    }

    /// Set node `i`'s weights (`dim` values; shorter or longer slices are cut or padded by
    /// what is there already).
    pub fn set_weights(&mut self, i: usize, w: &[f64]) {
        let base = (i / LANES) * self.dim;
        for (d, &v) in w.iter().take(self.dim).enumerate() {
            self.w[base + d][i % LANES] = v;
        }
    }

    /// Number of grid rows.
    pub fn rows(&self) -> usize {
        self.rows
    }
    /// Number of grid columns.
    pub fn cols(&self) -> usize {
        self.cols
    }
    /// Length of each weight vector.
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Grid topology.
    pub fn topology(&self) -> Topology {
        self.topology
    }
    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.rows * self.cols
    }
    /// True for a map without nodes (never, once checked).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// All weights, node-major (`rows * cols * dim` values, node 0 first): a copy.
    pub fn all_weights(&self) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.len() * self.dim);
        for i in 0..self.len() {
            v.extend_from_slice(&self.weights(i));
        }
        v
    }
    /// Weight vector of node index `i` (a copy out of the blocked layout).
    #[inline]
    pub fn weights(&self, i: usize) -> NodeWeights {
        let base = (i / LANES) * self.dim;
        let lanes = &self.w[base..base + self.dim];
        let mut out = NodeWeights {
            inline: [0.0; NodeWeights::INLINE],
            heap: Vec::new(),
            len: self.dim,
        };
        if self.dim <= NodeWeights::INLINE {
            for (o, lane) in out.inline.iter_mut().zip(lanes) {
                *o = lane[i % LANES];
            }
        } else {
            out.heap = lanes.iter().map(|lane| lane[i % LANES]).collect();
        }
        out
    }
    /// Squared distance from node `i`'s weights, dimensions `range`, to `x` (summed over
    /// `range` in order, as far as `x` goes).
    #[inline]
    pub fn distance2(&self, i: usize, x: &[f64], range: std::ops::Range<usize>) -> f64 {
        let base = (i / LANES) * self.dim;
        let mut d = 0.0;
        for (lane, &v) in self.w[base + range.start..base + range.end].iter().zip(x) {
            let t = lane[i % LANES] - v;
            d += t * t;
        }
        d
    }
    /// ID `(x, y)` of node index `i`.
    #[inline]
    pub fn id(&self, i: usize) -> NodeId {
        ((i % self.cols) as u16, (i / self.cols) as u16)
    }
    /// Node index of ID `(x, y)` (which must be on the grid).
    #[inline]
    pub fn index(&self, id: NodeId) -> usize {
        id.1 as usize * self.cols + id.0 as usize
    }
    /// Squared distance between two nodes on the grid (topology-aware).
    #[inline]
    pub fn grid_distance2(&self, a: usize, b: usize) -> f64 {
        let (ax, ay) = self.pos[a];
        let (bx, by) = self.pos[b];
        (ax - bx) * (ax - bx) + (ay - by) * (ay - by)
    }
    /// True when nodes `a` and `b` are adjacent (8-neighbourhood on the orthogonal grid,
    /// 6-neighbourhood on the hexagonal one).
    pub fn are_neighbours(&self, a: usize, b: usize) -> bool {
        let d2 = self.grid_distance2(a, b);
        match self.topology {
            Topology::Orthogonal => d2 <= 2.0 + 1e-9,
            Topology::Hexagonal => d2 <= 1.0 + 1e-9,
        }
    }

    /// Best-matching unit of `x` (length `dim`): its index and squared distance. Ties go to
    /// the lowest index.
    #[inline]
    pub fn bmu(&self, x: &[f64]) -> (usize, f64) {
        if self.dim == 0 {
            return (0, 0.0);
        }
        let dim = self.dim;
        kernel::argmin(&self.w, dim, self.len(), || {
            x.iter().copied().take(dim).enumerate()
        })
    }

    /// Best-matching unit of `x` using only the dimensions where `mask` is true (the unknown
    /// dimensions are ignored): its index and squared distance over the known dimensions.
    pub fn bmu_masked(&self, x: &[f64], mask: &[bool]) -> (usize, f64) {
        if self.dim == 0 {
            return (0, 0.0);
        }
        let dim = self.dim;
        kernel::argmin(&self.w, dim, self.len(), || known(x, mask, dim))
    }

    /// Best-matching unit of `x` over the dimension range `range` only (e.g. the state half).
    pub fn bmu_range(&self, x: &[f64], range: std::ops::Range<usize>) -> (usize, f64) {
        if self.dim == 0 {
            return (0, 0.0);
        }
        let range = range.start..range.end.min(self.dim);
        kernel::argmin(&self.w, self.dim, self.len(), || {
            range.clone().zip(x.iter().copied())
        })
    }

    /// Indices of the best and second-best matching units of `x`.
    pub fn best_two(&self, x: &[f64]) -> (usize, usize) {
        if self.dim == 0 {
            return (0, 1.min(self.len().saturating_sub(1)));
        }
        kernel::best_two(&self.w, self.dim, self.len(), x)
    }

    /// Kohonen update towards `x` around node `bmu`: every node moves by
    /// `alpha * h(grid distance, radius) * (x - w)`, on the dimensions where `mask` is true
    /// (all of them when `mask` is `None`). Nodes with h < [`DEFAULT_H_MIN`] = 1e-4 are left
    /// untouched, and only the rows and columns where h can reach 1e-4 are visited (for the
    /// gaussian, 4.29 radii around the BMU).
    pub fn update(
        &mut self,
        x: &[f64],
        mask: Option<&[bool]>,
        bmu: usize,
        alpha: f64,
        radius: f64,
        neighbourhood: Neighbourhood,
    ) {
        let reach = Reach::Cut {
            h_min: DEFAULT_H_MIN,
        };
        self.update_reach(x, mask, bmu, alpha, radius, neighbourhood, reach);
    }

    /// [`SelfOrganizingMap::update`] with a chosen reach: [`Reach::Exact`] moves every node
    /// (the textbook rule), [`Reach::Cut`] only those with h >= `h_min`. The gaussian's h
    /// is the product of a row and a column factor (tabulated once per update), equal to
    /// `exp(-d^2 / (2 r^2))` up to the last bits.
    #[allow(clippy::too_many_arguments)]
    pub fn update_reach(
        &mut self,
        x: &[f64],
        mask: Option<&[bool]>,
        bmu: usize,
        alpha: f64,
        radius: f64,
        neighbourhood: Neighbourhood,
        reach: Reach,
    ) {
        let dim = self.dim;
        if dim == 0 {
            return;
        }
        match mask {
            None => {
                let dims = || x.iter().copied().take(dim).enumerate();
                self.update_with(dims, bmu, alpha, radius, neighbourhood, reach)
            }
            Some(m) => {
                let dims = || known(x, m, dim);
                self.update_with(dims, bmu, alpha, radius, neighbourhood, reach)
            }
        }
    }

    fn update_with<I, F>(
        &mut self,
        dims: F,
        bmu: usize,
        alpha: f64,
        radius: f64,
        neighbourhood: Neighbourhood,
        reach: Reach,
    ) where
        I: Iterator<Item = (usize, f64)>,
        F: Fn() -> I,
    {
        let (rows, cols, n) = (self.rows, self.cols, self.len());
        let mut plan = std::mem::take(&mut self.scratch.plan);
        plan.clear();
        match (reach, neighbourhood) {
            (Reach::Exact, _) | (Reach::Cut { .. }, Neighbourhood::Bubble) => {
                let h_min = match reach {
                    Reach::Exact => 0.0,
                    Reach::Cut { h_min } => h_min,
                };
                for b in 0..n.div_ceil(LANES) {
                    let mut k = [0.0; LANES];
                    for (l, kl) in k.iter_mut().enumerate() {
                        let i = b * LANES + l;
                        if i < n {
                            let h = neighbourhood.weight(self.grid_distance2(bmu, i), radius);
                            if h >= h_min {
                                *kl = alpha * h;
                            }
                        }
                    }
                    if k.iter().any(|&v| v != 0.0) {
                        plan.push((b, k));
                    }
                }
            }
            (Reach::Cut { h_min }, Neighbourhood::Gaussian) => {
                let hex = self.topology == Topology::Hexagonal;
                let (bx, by) = (bmu % cols, bmu / cols);
                let Scratch { gx, gy, colf, .. } = &mut self.scratch;
                // row factors by row steps, column factors by half steps (hexagonal rows are
                // shifted by half a node); each table is non-zero on its first entries only
                let row_step = if hex { (3f64).sqrt() / 2.0 } else { 1.0 };
                let ny = kernel::gaussian_table(row_step, radius, rows, h_min, gy);
                let nx = kernel::gaussian_table(0.5, radius, 2 * cols + 2, h_min, gx);
                let (y0, y1) = (by.saturating_sub(ny), (by + ny).min(rows - 1));
                let reach = nx / 2 + 1;
                let (c0, c1) = (bx.saturating_sub(reach), (bx + reach).min(cols - 1));
                // the column factor of every column, per shift of half steps (0, and +-1 on
                // hexagonal rows of the other parity): 0 outside the reach
                let shifts: &[isize] = if hex { &[0, 1, -1] } else { &[0] };
                colf.clear();
                colf.resize(shifts.len() * cols, 0.0);
                for (si, &shift) in shifts.iter().enumerate() {
                    for c in c0..=c1 {
                        let half = 2 * c as isize - 2 * bx as isize + shift;
                        colf[si * cols + c] = gx[half.unsigned_abs()];
                    }
                }
                for y in y0..=y1 {
                    let hy = gy[y.abs_diff(by)];
                    if hy < h_min {
                        continue;
                    }
                    // half steps from the BMU to column c: 2 (c - bx), +-1 on hexagonal rows
                    // of the other parity
                    let si = match (hex && y % 2 != by % 2, by % 2) {
                        (false, _) => 0,
                        (true, 0) => 1,
                        (true, _) => 2,
                    };
                    let cf = &colf[si * cols..(si + 1) * cols];
                    let row0 = y * cols;
                    let (i0, i1) = (row0 + c0, row0 + c1);
                    for b in i0 / LANES..=i1 / LANES {
                        let mut k = [0.0; LANES];
                        let first = b * LANES;
                        if first >= row0 && first + LANES <= row0 + cols {
                            // the whole block lies in this row
                            let f = &cf[first - row0..first - row0 + LANES];
                            for (kl, &fc) in k.iter_mut().zip(f) {
                                let h = hy * fc;
                                *kl = if h >= h_min { alpha * h } else { 0.0 };
                            }
                        } else {
                            for (l, kl) in k.iter_mut().enumerate() {
                                let c = (first + l).wrapping_sub(row0);
                                if c < cols {
                                    let h = hy * cf[c];
                                    *kl = if h >= h_min { alpha * h } else { 0.0 };
                                }
                            }
                        }
                        if k.iter().any(|&v| v != 0.0) {
                            plan.push((b, k));
                        }
                    }
                }
            }
        }
        kernel::apply_plan(&mut self.w, self.dim, &plan, dims);
        self.scratch.plan = plan;
    }

    /// Mean Euclidean distance from each sample to its best-matching unit (0 for no data).
    pub fn quantization_error(&self, data: &[Vec<f64>]) -> f64 {
        if data.is_empty() {
            return 0.0;
        }
        data.iter().map(|x| self.bmu(x).1.sqrt()).sum::<f64>() / data.len() as f64
    }

    /// Fraction of samples whose best and second-best matching units are not adjacent on the
    /// grid (0 for no data or a single-node map).
    pub fn topographic_error(&self, data: &[Vec<f64>]) -> f64 {
        if data.is_empty() || self.len() < 2 {
            return 0.0;
        }
        let bad = data
            .iter()
            .filter(|x| {
                let (a, b) = self.best_two(x);
                !self.are_neighbours(a, b)
            })
            .count();
        bad as f64 / data.len() as f64
    }
}

impl SomParams {
    /// Check the settings and train a map on `data` (all rows the same length), presenting
    /// the samples in order and cycling; the initial weights are drawn uniformly, from the
    /// seed, inside the data's bounding box.
    pub fn fit(&self, data: &[Vec<f64>]) -> Result<SelfOrganizingMap, SomError> {
        if self.rows == 0 || self.cols == 0 {
            return Err(SomError::InvalidParam {
                name: "rows/cols",
                value: format!("{}x{}", self.rows, self.cols),
            });
        }
        for (name, s, max) in [
            ("learning_factor", &self.learning_factor, 1.0),
            ("learning_radius", &self.learning_radius, f64::INFINITY),
        ] {
            for v in [s.initial, s.last] {
                if !(v > 0.0 && v <= max) {
                    return Err(SomError::InvalidParam {
                        name,
                        value: v.to_string(),
                    });
                }
            }
        }
        let dim = data.first().map(|r| r.len()).ok_or(SomError::EmptyData)?;
        if dim == 0 {
            return Err(SomError::EmptyData);
        }
        let mut lo = vec![f64::INFINITY; dim];
        let mut hi = vec![f64::NEG_INFINITY; dim];
        for (i, r) in data.iter().enumerate() {
            if r.len() != dim {
                return Err(SomError::DimensionMismatch {
                    expected: dim,
                    found: r.len(),
                    row: i,
                });
            }
            for (d, &v) in r.iter().enumerate() {
                if !v.is_finite() {
                    return Err(SomError::NonFinite { row: i, column: d });
                }
                lo[d] = lo[d].min(v);
                hi[d] = hi[d].max(v);
            }
        }
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        let mut som = SelfOrganizingMap::new_random(
            self.rows,
            self.cols,
            dim,
            self.topology,
            &lo,
            &hi,
            &mut rng,
        );
        let denom = (self.steps.max(2) - 1) as f64;
        for t in 0..self.steps {
            let x = &data[t % data.len()];
            let p = t as f64 / denom;
            let (b, _) = som.bmu(x);
            som.update(
                x,
                None,
                b,
                self.learning_factor.at(p),
                self.learning_radius.at(p),
                self.neighbourhood,
            );
        }
        Ok(som)
    }
}

#[cfg(test)]
mod tests;
